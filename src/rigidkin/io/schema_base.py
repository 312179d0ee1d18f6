"""The building blocks of the problem-file schema: strict tables, expressions, quantities and names."""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict


def _expression(value: Any) -> Any:
    if isinstance(value, bool) or not isinstance(value, str | int | float):
        raise ValueError("expected an expression (a string such as \"l/2\") or a number")
    return value


def _quantity(value: Any) -> Any:
    if isinstance(value, bool) or not isinstance(value, str | int | float):
        raise ValueError("expected a number or a quantity with a unit (a string such as \"30 deg\")")
    return value


#: An expression: a string in the safe expression language, or a number.
Expr = Annotated[Any, BeforeValidator(_expression)]
#: A number, or a string: a quantity with a unit ("30 deg") or an expression.
Quantity = Annotated[Any, BeforeValidator(_quantity)]
Name = str
State = dict[str, Quantity]


class Strict(BaseModel):
    """Base of every table: unknown fields are refused, types are not coerced."""

    model_config = ConfigDict(extra="forbid", strict=True, populate_by_name=False)
