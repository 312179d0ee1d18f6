"""The problem file's ``[bodies]``: one table per shape of the shape library, chosen by ``shape``, its
dimensions those of the shape's constructor."""

from __future__ import annotations

import inspect
from typing import Annotated, Literal, Union

from pydantic import Field, create_model

from ..model.shapes import SHAPES
from .schema_base import Expr, Name, Strict

_WORD_FIELDS = {"axis", "toward", "a_axis", "b_axis", "about"}


def _shape_fields(cls) -> dict[str, tuple]:
    """The dimensions a shape takes (from its constructor), as pydantic field definitions."""
    out = {}
    for p in inspect.signature(cls).parameters.values():
        required = p.default is inspect.Parameter.empty
        if p.name in _WORD_FIELDS:
            out[p.name] = (str, ... if required else p.default)
        elif p.name == "centre":
            out[p.name] = (list[Expr] | None, Field(default=None, min_length=3, max_length=3))
        elif p.name == "mass" and cls.__name__ == "Massless":
            continue
        else:
            out[p.name] = (Expr | None, ... if required else None)
    return out


def _body_model(key: str, cls):
    fields = _shape_fields(cls)
    return create_model(
        f"Body_{key}", __base__=Strict,
        shape=(Literal[key], ...), frame=(Name, ...), at=(Name, ...), description=(str, ""),
        centre_name=(Name | None, None), driven=(bool, False), drive_torque=(Name | None, None),
        drive_force=(Name | None, None), drive_joint=(Name | None, None),
        drive_carrier=(Name | None, None), **fields)


BODY_MODELS = {key: _body_model(key, cls) for key, cls in SHAPES.items()}
BodySpec = Annotated[Union[tuple(BODY_MODELS.values())], Field(discriminator="shape")]  # noqa: UP007
