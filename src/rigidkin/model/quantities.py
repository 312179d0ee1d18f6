"""Parameters and generalised coordinates: the symbols a problem is written in.

A parameter is a positive real symbol (mass m, length l, gravity g ...) with a description and a
physical dimension; a coordinate is a function of time (``sympy`` dynamicsymbol) with its sense
stated in words (where it is measured from, which way is positive) and its kind (angle, length).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.units import ONE, Dimension

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

    def __repr__(self) -> str:
        v = "" if self.value is None else f" = {self.value:g}"
        return f"Parameter({self.name}{v} [{self.unit or self.dimension}]: {self.description})"


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
