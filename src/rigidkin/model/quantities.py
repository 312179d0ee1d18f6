"""Parameters and generalised coordinates: the symbols a problem is written in.

A parameter is a positive real symbol (mass m, length l, gravity g ...) with a description and a
physical dimension; a coordinate is a function of time (``sympy`` dynamicsymbol) with its sense
stated in words (where it is measured from, which way is positive) and its kind (angle, length).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.errors import ModelError
from ..base.units import NAMED, ONE, Dimension, from_si, shown_unit, shown_value, unit_dimension

t = dynamicsymbols._t


@dataclass(frozen=True, eq=False)
class Parameter:
    """A constant of the problem: ``symbol`` is a positive (or real) sympy Symbol."""

    name: str
    symbol: sp.Symbol
    description: str = ""
    unit: str = ""
    dimension: Dimension = ONE
    value: float | None = None

    @property
    def value_in_unit(self) -> float | None:
        """The value in the unit it was declared in (``value`` is in SI): 200 for ``unit="cm", value=200``."""
        return from_si(self.value, self.unit)

    @property
    def shown_unit(self) -> str:
        """The unit the value is shown in: the declared one, else the SI unit of the dimension ("" for a number)."""
        return shown_unit(self.unit, self.dimension)

    @property
    def shown_value(self) -> str:
        """The value as text in its declared unit (``"200 cm"``), or in SI with the SI unit; ``"—"`` for none."""
        return shown_value(self.value, self.unit, self.dimension)

    def __repr__(self) -> str:
        v = "" if self.value is None else f" = {self.shown_value}"
        u = "" if self.value is not None else f" [{self.shown_unit or self.dimension}]"
        return f"Parameter({self.name}{v}{u}: {self.description})"


@dataclass(frozen=True, eq=False)
class Coordinate:
    """A generalised coordinate q(t) with its sense, kind and initial state (q(0), q̇(0))."""

    name: str
    symbol: sp.Function
    sense: str = ""
    kind: str = "angle"          # "angle", "length" or "other"
    dimension: Dimension = ONE
    initial: float | None = None
    rate: float | None = None
    description: str = ""
    extra: dict = field(default_factory=dict, compare=False)
    prescribed: sp.Expr | None = None        # q = f(t) when the coordinate is driven by a law (System.prescribe)
    prescribed_rate: sp.Expr | None = None   # q̇ = g(t) when it or its rate is prescribed

    @property
    def rate_symbol(self) -> sp.Expr:
        """The rate q̇ as a sympy Derivative."""
        return self.symbol.diff(t)

    @property
    def accel_symbol(self) -> sp.Expr:
        """The second derivative q̈."""
        return self.symbol.diff(t, 2)

    def __repr__(self) -> str:
        return f"Coordinate({self.name} [{self.kind}]: {self.sense})"


def declared_dimension(unit, dimension, where: str, examples: str = "kg, m, N/m ...") -> Dimension:
    """The dimension of a declared quantity: its unit's, else the named ``dimension`` ("length", a
    :class:`~rigidkin.base.units.Dimension`), else dimensionless."""
    if unit is not None:
        return unit_dimension(unit, where)
    if isinstance(dimension, Dimension):
        return dimension
    if dimension is not None:
        if dimension not in NAMED:
            raise ModelError(f"unknown dimension '{dimension}'.", where=where,
                             hint=f"Use a unit ({examples}) or one of: {', '.join(sorted(NAMED))}.")
        return NAMED[dimension]
    return ONE
