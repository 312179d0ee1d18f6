"""Compact trigonometric forms for printing: M + m sin²α rather than M + m − m cos²α.

A sum that holds sin²x or cos²x has several equal forms modulo sin²x + cos²x = 1; the one a person
reads fastest is the shortest.  ``compact`` rewrites every sum of an expression, bottom up, in the form
with the fewest operations (then the fewest terms, then the fewest minus signs):

* ``a cos²x + b``  →  ``(a + b) − a sin²x`` or the all-cosine form, whichever is shorter;
* ``I₁ + I₃ cos²θ − I₁ cos²θ``  →  ``I₃ + (I₁ − I₃) sin²θ`` (or ``I₁ sin²θ + I₃ cos²θ``);
* ``(1 − cos 2x)/2``  →  ``sin²x``; ``2 sin x cos x``  →  ``sin 2x`` — the double angle only where every
  sine and cosine of x then reads in 2x (no expression mixes θ and 2θ);
* a denominator with more minus signs than plus signs reads positive (``−N/(1 + 3 sin²θ)``).

Every rewrite is an identity (tested at random and special states) and the result is never longer
than its input.  The work is bounded by size, not by a clock (so the result is the same on any
machine): an expression over ``COMPACT_LIMIT`` operations, a sum with more than ``TERMS_LIMIT``
terms, more than ``ANGLES_LIMIT`` angles, or a power of sin or cos above ``DEGREE_LIMIT`` is left as it is.
"""

from __future__ import annotations

import random
from functools import lru_cache
from math import comb

import sympy as sp

from .sampling import atoms_of, evaluate, state_atoms, state_point

#: Expressions with more operations, or more distinct angles, than these are left as they are.
COMPACT_LIMIT = 400
ANGLES_LIMIT = 3
#: Sums with more terms than this are left as they are.
TERMS_LIMIT = 40
#: Highest power of sin x or cos x (in one term) that is rewritten.
DEGREE_LIMIT = 6
#: Coefficients up to this size are also tried factored (``sp.factor``).
FACTOR_LIMIT = 40

_S, _C = sp.Dummy("S"), sp.Dummy("C")


def compact(expr: sp.Basic) -> sp.Basic:
    """The shortest equal form of ``expr`` in sines and cosines (see the module's docstring)."""
    expr = sp.sympify(expr)
    if not isinstance(expr, sp.Expr) or not expr.has(sp.sin, sp.cos):
        return expr
    if len(_angles(expr)) > ANGLES_LIMIT or sp.count_ops(expr) > COMPACT_LIMIT:
        return expr
    starts = [expr]
    multiple = _multiple_angles(expr)
    if multiple:
        starts.append(expr.xreplace({f: sp.expand_trig(f) for f in multiple}))
    best = expr
    for start in starts:
        allowed = frozenset(_angles(start))
        out = start
        for _ in range(3):
            out = _Pass(allowed).walk(start)
            mixed = _mixed_angles(out) & allowed
            if not mixed:
                break
            allowed = allowed - mixed
        best = _better([out], best)
    if best is expr or length(best) > length(expr):
        return expr
    return best if _same_value(best, expr) else expr


def _same_value(a: sp.Basic, b: sp.Basic, trials: int = 3) -> bool:
    """``a = b`` at a few random states in machine arithmetic: a guard on the rewriting (a reading form
    must never change a value; where it would, the expression is kept as it was)."""
    rng = random.Random(7)
    atoms = state_atoms([a, b])
    for _ in range(trials):
        vals = state_point([a, b], rng, rng.uniform(0.1, 1.0), atoms=atoms)
        va, vb = evaluate([a, b], vals)
        if va != va or vb != vb:            # nan: not decidable here, keep the original
            return False
        if abs(va - vb) > 1e-9 * max(1.0, abs(va), abs(vb)):
            return False
    return True


def length(e: sp.Basic) -> int:
    """Operations (``sp.count_ops``), a leading minus sign of the whole not counted (−a/b reads as a/(−b))."""
    n = sp.count_ops(e)
    return min(n, sp.count_ops(-e)) if e.could_extract_minus_sign() or (e.is_Mul and e.args[0].is_negative) else n


@lru_cache(maxsize=8192)
def _key(e: sp.Basic, free_sign: bool = True) -> tuple:
    """Shorter first: operations, then terms, then minus signs (with ``free_sign``, a leading one of the
    whole not counted: the sign of a whole expression or a denominator can move to the front)."""
    adds = [a for a in sp.preorder_traversal(e) if isinstance(a, sp.Add)]
    terms = sum(len(a.args) for a in adds)
    neg = sum(1 for a in adds for x in a.args if x.could_extract_minus_sign())
    if not free_sign:
        return sp.count_ops(e), terms, neg
    if e.is_Add and _neg_heavy(e):
        neg -= sum(1 for x in e.args if x.could_extract_minus_sign()) * 2 - len(e.args)
    return length(e), terms, neg


def _better(cands: list, current: sp.Basic, free_sign: bool = True) -> sp.Basic:
    """The best candidate if it is strictly shorter than ``current`` (by ``_key``), else ``current``."""
    if not cands:
        return current
    best = min(cands, key=lambda e: (_key(e, free_sign), sp.default_sort_key(e)))
    return best if _key(best, free_sign) < _key(current, free_sign) else current


def _angles(e: sp.Basic) -> list:
    return sorted({f.args[0] for f in atoms_of([e], (sp.sin, sp.cos))}, key=sp.default_sort_key)


def _split_multiple(arg: sp.Basic):
    """(k, x) for an angle k·x with an integer k ≥ 2, else None."""
    c, rest = arg.as_coeff_Mul()
    if c.is_Integer and c >= 2 and rest != 1:
        return int(c), rest
    return None


def _multiple_angles(e: sp.Basic) -> list:
    return sorted((f for f in atoms_of([e], (sp.sin, sp.cos))
                   if _split_multiple(f.args[0]) and _split_multiple(f.args[0])[0] <= 4), key=sp.default_sort_key)


def _mixed_angles(e: sp.Basic) -> set:
    """Angles x that appear both as x and as 2x (the double-angle rewrite made the reading inconsistent)."""
    args = {f.args[0] for f in atoms_of([e], (sp.sin, sp.cos))}
    mixed = set()
    for a in args:
        km = _split_multiple(a)
        if km and km[0] == 2 and km[1] in args:
            mixed.add(km[1])
    return mixed


def _neg_heavy(a: sp.Basic) -> bool:
    if not a.is_Add:
        return False
    neg = sum(1 for x in a.args if x.could_extract_minus_sign())
    return 2 * neg > len(a.args)


class _Pass:
    """One bottom-up pass; ``double``: the angles for which the double-angle forms may be used."""

    def __init__(self, double: frozenset):
        self.double = double
        self.memo: dict = {}

    def walk(self, e: sp.Basic) -> sp.Basic:
        if e.is_Atom or not e.has(sp.sin, sp.cos):
            return e
        hit = self.memo.get(e)
        if hit is not None:
            return hit
        args = [self.walk(a) for a in e.args]
        out = e.func(*args) if any(a is not b for a, b in zip(args, e.args)) else e
        if out.is_Add and len(out.args) <= TERMS_LIMIT:
            out = self.add(out)
        elif out.is_Mul:
            out = self.mul(out)
        self.memo[e] = out
        return out

    # -- products ---------------------------------------------------------------------------------
    def mul(self, m: sp.Mul) -> sp.Basic:
        out = m
        for x in _angles(m):
            if x not in self.double:
                continue
            factors = sp.Mul.make_args(out)
            if sp.sin(x) in factors and sp.cos(x) in factors:
                rest = [f for f in factors if f not in (sp.sin(x), sp.cos(x))]
                out = _better([sp.Mul(*rest) * sp.sin(2 * x) / 2], out)
        if out.is_Mul:           # a denominator with more minus signs than plus signs reads positive
            flips = [f for f in out.args if f.is_Pow and _neg_heavy(f.base) and f.exp.is_Integer and f.exp < 0
                     and f.exp % 2]
            if flips:
                out = (-1) ** len(flips) * sp.Mul(*[sp.Pow(-f.base, f.exp) if f in flips else f for f in out.args])
        if out.is_Mul and out.could_extract_minus_sign():       # −(−a + b − c)  →  (a − b + c)
            args = list(out.args)
            k = next((i for i, f in enumerate(args) if _neg_heavy(f)), None)
            if k is not None:       # the product unchanged: one factor negated, the whole negated
                out = sp.Mul(sp.S.NegativeOne, *[-f if i == k else f for i, f in enumerate(args)])
        return out

    # -- sums -------------------------------------------------------------------------------------
    def add(self, a: sp.Add) -> sp.Basic:
        best = a
        for x in _angles(a):
            best = self.add_in(best, x) if best.is_Add else best
        return best

    def add_in(self, a: sp.Add, x: sp.Basic) -> sp.Basic:
        """The shortest form of the sum ``a`` as a polynomial in sin x and cos x."""
        s, c = sp.sin(x), sp.cos(x)
        poly: dict = {}
        rest, mine = [], []
        for term in a.args:
            mono = _monomial(term, s, c)
            if mono is None:
                rest.append(term)
            else:
                mine.append(term)
                (i, j), coeff = mono
                poly.setdefault((i, j), []).append(coeff)
        if not poly or max(i + j for i, j in poly) > DEGREE_LIMIT:
            return a
        squares = any(i >= 2 or j >= 2 for i, j in poly)
        even = all((i + j) % 2 == 0 for i, j in poly) and any(i + j for i, j in poly)
        double = x in self.double and even and max(i + j for i, j in poly) == 2
        if not squares and not double:
            return a
        base = {k: sp.Add(*v) for k, v in poly.items()}
        forms = [base, _reduce(base, "sin"), _reduce(base, "cos")]
        sin_form = forms[1]
        if set(sin_form) <= {(0, 0), (2, 0)} and len(sin_form) == 2:      # α + β sin²  →  (α + β) sin² + α cos²
            al, be = sin_form[(0, 0)], sin_form[(2, 0)]
            forms.append({(2, 0): al + be, (0, 2): al})
        cands = []
        for f in forms:
            e = sp.Add(*[_coef(k) * s**i * c**j for (i, j), k in sorted(f.items())])
            cands += [e, sp.factor_terms(e)]
        if double:
            cands += self.doubled(base, x)
        if not rest:
            return _better(cands, a)
        own = sp.Add(*mine)           # the other terms stay as they are; only this part is compared
        best = _better(cands, own, free_sign=False)
        return a if best is own else sp.Add(*rest) + best

    def doubled(self, base: dict, x: sp.Basic) -> list:
        """α + β sin²x + γ cos²x + δ sin x cos x  →  α + (β + γ)/2 + (γ − β)/2 cos 2x + δ/2 sin 2x."""
        z = sp.Integer(0)
        al, be, ga, de = (base.get(k, z) for k in ((0, 0), (2, 0), (0, 2), (1, 1)))
        e = _coef(al + (be + ga) / 2) + _coef((ga - be) / 2) * sp.cos(2 * x) \
            + _coef(de / 2) * sp.sin(2 * x)
        return [e, sp.factor_terms(e)]


def _monomial(term: sp.Basic, s: sp.Basic, c: sp.Basic):
    """((i, j), coefficient) for coefficient · sinⁱx · cosʲx, or None where x hides in the coefficient."""
    i = j = 0
    coeff = []
    for f in sp.Mul.make_args(term):
        b, e = f.as_base_exp()
        if b == s and e.is_Integer and e > 0:
            i += int(e)
        elif b == c and e.is_Integer and e > 0:
            j += int(e)
        else:
            coeff.append(f)
    k = sp.Mul(*coeff)
    if k.has(s, c):
        return None
    return (i, j), k


def _reduce(poly: dict, keep: str) -> dict:
    """Eliminate cos² (``keep='sin'``) or sin² (``keep='cos'``) with sin² + cos² = 1."""
    out: dict = {}
    for (i, j), k in poly.items():
        if keep == "sin":
            n, r = divmod(j, 2)
            for p in range(n + 1):          # cos^(2n) = (1 − sin²)^n
                key = (i + 2 * p, r)
                out[key] = out.get(key, 0) + k * comb(n, p) * (-1) ** p
        else:
            n, r = divmod(i, 2)
            for p in range(n + 1):
                key = (r, j + 2 * p)
                out[key] = out.get(key, 0) + k * comb(n, p) * (-1) ** p
    return {k: v for k, v in out.items() if v != 0}


@lru_cache(maxsize=8192)
def _coef(k: sp.Basic) -> sp.Basic:
    """A coefficient collected: the shortest of as given, expanded and factored."""
    k = sp.sympify(k)
    if k.is_number or k.is_Symbol:
        return k
    cands = [k]
    try:
        e = sp.expand(k)
        if e.is_rational_function():
            e = sp.cancel(e)
        cands.append(sp.factor_terms(e))
        if sp.count_ops(e) <= FACTOR_LIMIT:
            cands.append(sp.factor(e))
    except (sp.PolynomialError, NotImplementedError):
        pass
    return min(cands, key=_key)
