"""A regime of a solution: its equations of motion and reactions under one set of sign conditions.

What a derivation needs is computed when the solution is made (the mass matrix M and forcing f as
derived, the regime's conditions); what only a reader needs is computed on first use: the readable
forms of M, f and the equations of motion (bounded simplification), the accelerations and reactions
(``LazyMap``), and the validity conditions that read the reactions (N ≥ 0, |F| ≤ µN).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..base.printing import text
from .keyed import Keyed, keyed


@dataclass(frozen=True)
class Condition:
    """``expr`` ``relation`` 0, e.g. a slip speed > 0 or a normal reaction ≥ 0, with a description."""

    expr: sp.Expr
    relation: str
    label: str
    kind: str = "regime"    # "regime" (defines the regime) or "validity" (the solution holds while)

    def holds(self, value: float, tol: float = 0.0) -> bool:
        return {">": value > tol, ">=": value >= -tol, "<": value < -tol, "<=": value <= tol}[self.relation]

    def __str__(self) -> str:
        return f"{text(self.expr)} {self.relation.replace('>=', '≥').replace('<=', '≤')} 0   ({self.label})"


class LazyMap(Keyed):
    """A read-only mapping computed on first use (accelerations and reactions of large systems), keyed as
    :class:`~rigidkin.derive.keyed.Keyed` (by key, by name, by sympy's own symbol)."""

    def __init__(self, compute, what: str | None = None):
        super().__init__(compute=compute, what=what)


class Deferred:
    """A value of a Regime computed when first read (``Regime`` replaces it by the value)."""

    __slots__ = ("compute",)

    def __init__(self, compute):
        self.compute = compute


def _lazy(name: str):
    private = "_" + name

    def get(self):
        value = self.__dict__[private]
        if isinstance(value, Deferred):
            value = value.compute()
            self.__dict__[private] = value
        return value

    get.__name__ = name
    return property(get)


class Regime:
    """The equations of motion and reactions under one set of sign conditions.

    ``reactions`` are functions of the state; with more than ``READABLE_DOF`` degrees of freedom they
    are written in terms of the accelerations q̈ too (from M q̈ = f: ``Solution.reactions_at`` does it).
    ``mass_matrix``, ``forcing`` and ``eom`` are the forms simplified for reading (made when first read);
    ``raw_mass_matrix`` and ``raw_forcing`` are M and f as derived (what numeric code needs).
    """

    indeterminate = None    # an Indeterminacy (derive/indeterminate.py) where reactions are statically indeterminate
    validity = _lazy("validity")
    eom = _lazy("eom")
    mass_matrix = _lazy("mass_matrix")
    forcing = _lazy("forcing")

    def __init__(self, conditions, validity, signs, eom, accelerations, reactions, mass_matrix, forcing,
                 raw_mass_matrix=None, raw_forcing=None, indeterminate=None):
        d = self.__dict__
        d["conditions"], d["signs"] = tuple(conditions), signs
        d["accelerations"] = keyed(accelerations, "accelerations (coordinate → q̈)")
        d["reactions"] = keyed(reactions, "reactions")
        d["_validity"], d["_eom"], d["_mass_matrix"], d["_forcing"] = validity, eom, mass_matrix, forcing
        d["raw_mass_matrix"] = raw_mass_matrix if raw_mass_matrix is not None else mass_matrix
        d["raw_forcing"] = raw_forcing if raw_forcing is not None else forcing
        d["indeterminate"] = indeterminate

    def __setattr__(self, name, value):
        raise AttributeError(f"a Regime is read-only ({name})")

    def describe(self) -> str:
        return " and ".join(str(c) for c in self.conditions) or "always"

    def __repr__(self) -> str:
        return f"Regime({self.describe()})"
