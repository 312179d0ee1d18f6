"""Values given to the Python API: numbers or sympy expressions (never text), and friction specifications."""

from __future__ import annotations

import math
from fractions import Fraction

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
    if isinstance(value, float):
        return exact_decimal(value)
    return sp.sympify(value)


def exact_decimal(value: float | str, digits: int = 40) -> sp.Expr:
    """A decimal as the exact rational it denotes: ``"0.1"`` (as written) or the float 0.1 (as it prints) → 1/10.

    Decimals in problem files and bare floats given to the Python API are read so, and exact input gives
    exact output (``0.1*g + 0.9*g`` is g; 0.5 is 1/2, not a float that turns every derived expression into
    floats).  A sympy expression built in Python is taken as it is (``0.5*l`` keeps its float; write
    ``l/2``).  A number whose exact form has more than ``digits`` digits (``1e-60``) stays a float."""
    if isinstance(value, float) and not math.isfinite(value):
        return sp.sympify(value)
    written = repr(value) if isinstance(value, float) else value.replace("_", "")
    frac = Fraction(written)
    if max(len(str(abs(frac.numerator))), len(str(frac.denominator))) > digits:
        return sp.Float(written)
    return sp.Rational(frac.numerator, frac.denominator)


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
