"""Products in the order an engineer writes them: the mass first — m g, m l², m r ω, not g m.

sympy orders the factors of a product alphabetically (g m, l² m).  A report follows the textbook:
a mass (a symbol named m or M, with an index or a suffix: m1, m_A, M2) leads its product.
"""

from __future__ import annotations

import re

import sympy as sp

_MASS = re.compile(r"[mM](\d+|_[A-Za-z0-9]+)?")


def is_mass(factor) -> bool:
    """A mass symbol (``m``, ``m1``, ``m_A``, ``M``), or a power of one."""
    base = factor.base if isinstance(factor, sp.Pow) else factor
    return isinstance(base, sp.Symbol) and _MASS.fullmatch(base.name) is not None


def masses_first(expr) -> tuple[sp.Expr, list] | None:
    """(numeric coefficient, factors with the masses first) of a product with no denominator whose order
    changes; None where sympy's order already puts a mass first or there is none (print it as sympy does)."""
    if not isinstance(expr, sp.Mul) or sp.fraction(expr)[1] != 1:
        return None
    coeff, _ = expr.as_coeff_Mul()
    factors = [f for f in expr.as_ordered_factors() if not f.is_Number]
    masses = [f for f in factors if is_mass(f)]
    if not masses or factors[:len(masses)] == masses:
        return None
    return coeff, masses + [f for f in factors if not is_mass(f)]
