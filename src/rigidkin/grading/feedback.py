"""Naming what is wrong in a step: the term that is missing or extra, a sign, a coefficient, a dimension.

The student's equation and the engine's (``= 0``) are compared term by term after expanding both in
the unknowns and scaling the engine's by the factor that matches the most terms (a student may divide
by l or multiply by 12): a term of the student's that is the engine's with the opposite sign is a sign
error, one with another number in front a wrong coefficient, one the engine does not have is extra, one
the engine has that the student does not is missing.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.dimensions import check_equation, symbol_dimensions
from ..base.printing import text

t = dynamicsymbols._t
MAX_PAIRS = 600


@dataclass(frozen=True)
class TermDiff:
    scale: sp.Expr
    matched: int
    signs: tuple          # student's terms whose sign is wrong
    coefficients: tuple   # (student's term, engine's term) with another numeric coefficient
    extra: tuple          # student's terms the engine does not have
    missing: tuple        # engine's terms (scaled) the student does not have

    accel_matched: int = 0  # matched terms with an acceleration: the scale that keeps them is preferred

    @property
    def score(self) -> float:
        """Matched terms first; on a tie the student's own scale (±1: the terms written as the law gives them,
        so that a missing ½ on Ī is named on the inertia term and a missing 2 on 2T on the load)."""
        unit = 0.2 if self.scale in (1, -1) else 0.0
        return (self.matched * 2 + 0.1 * self.accel_matched + len(self.signs) + len(self.coefficients)
                - len(self.extra) - len(self.missing) + unit)

    def describe(self) -> list[str]:
        out = []
        for u in self.signs:
            out.append(f"sign: the term {text(u)} has the wrong sign")
        for u, r in self.coefficients:
            out.append(f"coefficient: the term {text(u)} should be {text(r)}")
        for r in self.missing:
            out.append(f"missing term: {text(r)}")
        for u in self.extra:
            out.append(f"extra term: {text(u)}")
        return out


def expandable(e) -> bool:
    """Small enough to expand: no power of a sum above the 4th, a bounded size (a claim such as
    (a + b + ... + j)**12 would expand into hundreds of thousands of terms)."""
    e = sp.sympify(e)
    if sp.count_ops(e) > 1500:
        return False
    return not any(isinstance(p.base, sp.Add) and p.exp.is_number and abs(p.exp) > 4 for p in e.atoms(sp.Pow))


def _terms(e) -> list:
    e = sp.expand(sp.sympify(e))
    return [] if e == 0 else list(sp.Add.make_args(e))


def _atoms(e):
    return frozenset(e.atoms(sp.Symbol)) | frozenset(e.atoms(sp.Derivative))


def _same(a, b) -> bool:
    if _atoms(a) != _atoms(b):
        return False
    d = sp.expand(a - b)
    return d == 0 or sp.cancel(d) == 0


def _constant(c) -> bool:
    return c != 0 and not algebra.functions_of_time(c) and not c.has(t) and not c.atoms(sp.Derivative)


def term_diff(student, engine) -> TermDiff | None:
    """The term-by-term comparison of two equations ``= 0`` (None when too large to pair up)."""
    if not (expandable(student) and expandable(engine)):
        return None
    U, R = _terms(student), _terms(engine)
    if not U or not R or len(U) * len(R) > MAX_PAIRS:
        return None
    scales = []
    for u in U:
        for r in R:
            try:
                c = sp.cancel(u / r)
            except (sp.PolynomialError, ZeroDivisionError):
                continue
            if _constant(c):
                for cand in (c, -c):
                    if not any(_same(cand, s) for s in scales):
                        scales.append(cand)
    best = None
    for c in scales[:40] or [sp.Integer(1)]:
        d = _pair(U, [sp.expand(c * r) for r in R], c)
        if best is None or d.score > best.score:
            best = d
    return best


def _pair(U, R, scale) -> TermDiff:
    left_u, left_r = list(U), list(R)
    matched = accel = 0
    for u in list(left_u):
        for r in left_r:
            if _same(u, r):
                left_u.remove(u)
                left_r.remove(r)
                matched += 1
                accel += any(sum(c for _, c in d.variable_count) == 2 for d in u.atoms(sp.Derivative))
                break
    signs, coeffs = [], []
    for u in list(left_u):
        for r in left_r:
            if _same(u, -r):
                signs.append(u)
                left_u.remove(u)
                left_r.remove(r)
                break
    for u in list(left_u):
        for r in left_r:
            if _atoms(u) - _atoms(r) - {t} and _atoms(r) - _atoms(u) - {t}:
                continue
            ratio = sp.cancel(u / r)
            if ratio.is_number and ratio != 0:
                coeffs.append((u, r))
                left_u.remove(u)
                left_r.remove(r)
                break
    return TermDiff(scale, matched, tuple(signs), tuple(coeffs), tuple(left_u), tuple(left_r), accel)


def dimension_problem(ref, lhs, rhs) -> str | None:
    """The first dimensionally inconsistent term of ``lhs = rhs``, in words (None: consistent)."""

    try:
        rep = check_equation(lhs, rhs, symbol_dimensions(ref.system, ref.setup), "claim")
    except Exception:      # an expression the dimension rules do not cover is not a verdict
        return None
    if rep.consistent or not rep.offending:
        return None
    term, dim, why = rep.offending[0]
    if dim is None:
        return f"dimension: the term {text(term)} is not dimensionally consistent ({why})"
    return f"dimension: the term {text(term)} has dimension {dim} while {why}"
