"""Values given to the Python API: numbers or sympy expressions (never text), and friction specifications."""

from __future__ import annotations

import sympy as sp

from ..base.errors import ModelError
from . import constraints as C


def _expr(value, where: str = "") -> sp.Expr:
    """A number or sympy expression given to the Python API (a string is refused: no sympify on text)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, sp.Basic)):
        kind = "the string " + repr(value)[:40] if isinstance(value, str) else type(value).__name__
        raise ModelError(f"expected a number or a sympy expression, got {kind}.", where=where or None,
                         hint="In Python, build expressions from the symbols System.parameter and "
                              "System.coordinate return (l/2, m*g); text expressions belong in problem files.")
    return sp.sympify(value)


def _friction(friction, where):
    if friction in (None, "smooth", 0):
        return C.SMOOTH
    if friction in ("rolling", "no-slip", "no_slip"):
        return C.ROLLING
    if isinstance(friction, C.Coulomb):
        return friction
    if isinstance(friction, dict) and set(friction) <= {"static", "kinetic"} and friction:
        # static and kinetic coefficients (µs, µk); one alone means both
        mu_k = friction.get("kinetic", friction.get("static"))
        mu_s = friction.get("static", mu_k)
        if mu_k in (0, None) and mu_s in (0, None):
            return C.SMOOTH
        return C.Coulomb(_expr(mu_k, where), _expr(mu_s, where))
    if isinstance(friction, (int, float, sp.Basic)):
        return C.Coulomb(_expr(friction, where))
    raise ModelError(f"friction must be 'smooth', 'rolling', a coefficient µ or {{'static': µs, 'kinetic': µk}}, "
                     f"not {friction!r}.", where=where)
