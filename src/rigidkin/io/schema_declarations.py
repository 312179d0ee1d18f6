"""The problem file's declarations: ``[parameters]``, ``[inputs]``, ``[definitions]``, ``[coordinates]``,
``[frames]`` and ``[points]``."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from .schema_base import Expr, Name, Quantity, Strict


class ParameterSpec(Strict):
    unit: str | None = None
    dimension: str | None = None
    description: str = ""
    value: Quantity | None = None
    positive: bool = True


class InputSpec(Strict):
    """An input u(t): its unit, what it is with its positive sense, and optionally its history (an expression
    of t and the parameters) for simulations."""

    unit: str | None = None
    description: str = ""
    history: Expr | None = None


class DefinitionSpec(Strict):
    """A derived quantity: ``a = { value = "sqrt(R**2 - l**2)", unit = "m" }`` (or just the expression)."""

    value: Expr
    unit: str | None = None
    description: str = ""


class CoordinateSpec(Strict):
    sense: str
    kind: Literal["angle", "length", "other"] = "angle"
    unit: str | None = None
    initial: Quantity | None = None
    rate: Quantity | None = None
    description: str = ""
    positive: bool = False
    prescribed: Expr | None = None
    prescribed_rate: Expr | None = None
    drive_effort: Name | None = None


class FrameSpec(Strict):
    parent: Name = "F"
    angle: Expr | None = None
    axis: Expr = "z"
    basis: list[Name] | None = Field(default=None, min_length=3, max_length=3)
    sequence: str | None = None
    angles: list[Expr] | None = Field(default=None, min_length=3, max_length=3)
    # a quaternion: the names of the four Euler parameters (scalar first), declared as coordinates
    quaternion: list[Name] | None = Field(default=None, min_length=4, max_length=4)
    # the frame's angular-velocity components along its basis as speeds (quaternion or sequence)
    speeds: list[Name] | None = Field(default=None, min_length=3, max_length=3)
    initial: list[Quantity] | None = Field(default=None, min_length=4, max_length=4)   # the quaternion's start
    rates: list[Quantity] | None = Field(default=None, min_length=3, max_length=3)     # the speeds' start
    description: str = ""


class PointSpec(Strict):
    from_: Name = Field(default="O", alias="from")
    offset: Expr = 0
    body: Name | None = None
    description: str = ""
