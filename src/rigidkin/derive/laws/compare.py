"""Deciding whether two expressions or equations agree: symbolically where cheap, else numerically.

Symbolically when the difference simplifies to zero (or, for an equation ``= 0``, when the ratio of two
forms is a nonzero constant); else numerically at ``SAMPLES`` random states and parameter sets, to a
relative tolerance ``RTOL``.  Used by the cross-check of the laws, ``check --expect`` and grading.
"""

from __future__ import annotations

import random
import weakref

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base import algebra
from ...base.printing import text

t = dynamicsymbols._t

#: Number of random states and parameter sets of a numerical comparison, and its relative tolerance.
SAMPLES = 24
MIN_SAMPLES = 20
RTOL = 1e-8
#: Above this operation count, symbolic simplification of a difference is not attempted.
SYMBOLIC_LIMIT = 250

def ops_above(expr, limit: int) -> bool:
    """``sympy.count_ops(expr) > limit``, without counting a large expression's operations: every function
    (sin, cos, q(t) …) in the tree is one operation or more of ``count_ops``, and their number is found with
    each shared subexpression visited once; only where it stays within ``limit`` is ``count_ops`` run."""
    memo: dict = {}

    def functions(e) -> int:
        hit = memo.get(e)
        if hit is None:
            hit = memo[e] = int(bool(e.is_Function)) + sum(functions(a) for a in e.args)
        return hit

    expr = sp.sympify(expr)
    if functions(expr) > limit:
        return True
    return sp.count_ops(expr) > limit


def evaluator(plain, syms):
    """A function of the values of ``syms`` giving ``plain`` (an expression or a matrix) in machine complex
    arithmetic: the expression tree walked once per call, each shared subexpression once
    (``algebra.evaluate``; no code is generated, which for the large expressions compared here costs
    more than the few dozen states they are evaluated at)."""
    entries = list(plain) if isinstance(plain, sp.MatrixBase) else [plain]
    shape = plain.shape if isinstance(plain, sp.MatrixBase) else None

    def fn(*args):
        vals = algebra.evaluate(entries, dict(zip(syms, args)))
        if shape is None:
            return vals[0]
        return np.array(vals, dtype=complex).reshape(shape)

    return fn


def _numeric_points(exprs, n: int, seed: int, manifold=None):
    """Lambdified functions of the expressions and ``n`` random argument tuples (on the constraint
    manifold when a ``manifold`` of laws.manifold is given: a point that cannot be drawn there is nan)."""
    plains, backs = [], {}
    for e in exprs:
        p, back = algebra.plain_state(sp.sympify(e))
        plains.append(p)
        backs.update(back)
    syms = sorted(set().union(*[p.free_symbols for p in plains]) - {t}, key=str)
    funcs = [evaluator(p, syms + [t]) for p in plains]
    rng = random.Random(seed)
    pts = []
    for i in range(n):
        vals = algebra.random_point(syms, rng)
        tv = rng.uniform(0.1, 1.0)
        if manifold is not None:
            tv, drawn = manifold.sample(seed, i)       # the same admissible states for every comparison
            if drawn is None:
                pts.append([complex("nan")] * len(syms) + [tv])
                continue
            vals.update({k: v for k, v in drawn.items() if k in vals})
        pts.append([complex(vals[s]) for s in syms] + [tv])
    return funcs, pts


def numerically_equal(a, b, n: int = SAMPLES, seed: int = 3, rtol: float = RTOL, manifold=None) -> bool:
    """a = b at ``n`` random states and parameter sets, to relative tolerance ``rtol``.

    Points where either side is not finite are skipped; at least ``MIN_SAMPLES`` must be usable.
    """
    return _numeric_compare(a, b, n, seed, rtol, manifold)[0]


def _numeric_compare(a, b, n: int = SAMPLES, seed: int = 3, rtol: float = RTOL, manifold=None) -> tuple[bool, int]:
    (fa, fb), pts = _numeric_points([a, b], n, seed, manifold)
    used = 0
    with np.errstate(all="ignore"):
        for p in pts:
            try:
                va, vb = complex(fa(*p)), complex(fb(*p))
            except (ZeroDivisionError, OverflowError, ValueError):
                continue
            if not (np.isfinite(va) and np.isfinite(vb)):
                continue
            used += 1
            if abs(va - vb) > rtol * max(1.0, abs(va), abs(vb)):
                return False, -used          # a definite difference, found at the used-th state
    return used >= MIN_SAMPLES, used


def compare(a, b, manifold=None) -> tuple[bool, str]:
    """(equal, how decided) for two expressions of the state and parameters (numerically at admissible
    states of ``manifold`` when given: laws.manifold)."""
    d = sp.sympify(a) - sp.sympify(b)
    if d == 0:
        return True, "symbolic: identical"
    if not ops_above(d, SYMBOLIC_LIMIT):
        try:
            if algebra.readable(d) == 0 or sp.simplify(d) == 0:
                return True, "symbolic: the difference simplifies to 0"
        except (RecursionError, NotImplementedError, sp.PolynomialError):
            pass
    ok, used = _numeric_compare(a, b, manifold=manifold)
    if used < 0:
        return False, f"numeric: they differ at a random state (state {-used} of those evaluated)"
    if used < MIN_SAMPLES:
        return False, f"numeric: only {used} of {SAMPLES} random states could be evaluated (undecided)"
    return ok, f"numeric: {used} random states and parameter sets, rel. tol. {RTOL:g}"


def same_equation(a, b) -> tuple[bool, str]:
    """Two equations ``= 0`` agree up to a nonzero factor free of the state."""
    a, b = sp.sympify(a), sp.sympify(b)
    if b != 0 and not ops_above(a, SYMBOLIC_LIMIT) and sp.count_ops(a) + sp.count_ops(b) <= SYMBOLIC_LIMIT:
        try:
            r = sp.simplify(sp.cancel(a / b))
            if r != 0 and not algebra.functions_of_time(r) and not r.has(t):
                return True, f"symbolic: equal up to the factor {text(r)}"
        except (RecursionError, NotImplementedError, sp.PolynomialError):
            pass
    return False, "symbolic: not a constant multiple"


class Sampler:
    """Random states and parameter sets, shared by every expression compared; accelerations from M q̈ = f.

    Large systems are compared this way: the accelerations at each random state come from solving the
    mass-matrix form numerically, never from a symbolic inverse.
    """

    def __init__(self, n: int = SAMPLES, seed: int = 5, manifold=None):
        self.n, self.seed, self.rng = n, seed, random.Random(seed)
        self.values: list[dict] = [{} for _ in range(n)]
        self._funcs: dict = {}
        self.manifold = manifold            # laws.manifold.Manifold: admissible states only

    def _value(self, i: int, s):
        d = self.values[i]
        if self.manifold is not None and not d:
            d[t], drawn = self.manifold.sample(self.seed, i)     # shared by every sampler of this seed
            d.update(drawn if drawn is not None else {u: complex("nan") for u in self.manifold.unknowns})
        if s not in d:
            d[s] = self.rng.uniform(0.1, 1.0) if s == t else complex(algebra.random_point([s], self.rng)[s])
        return d[s]

    def evaluate(self, expr, i: int, extra: dict | None = None) -> complex:
        key = sp.sympify(expr)
        if key not in self._funcs:
            plain, _ = algebra.plain_state(key)
            syms = sorted(plain.free_symbols, key=str)
            self._funcs[key] = (syms, evaluator(plain, syms))
        syms, fn = self._funcs[key]
        args = [extra[s] if extra and s in extra else self._value(i, s) for s in syms]
        with np.errstate(all="ignore"):
            return complex(fn(*args))

    def accelerations(self, regime, coords, i: int) -> dict:
        """{plain q̈ symbol: value} at point ``i`` from the regime's M q̈ = f, solved numerically."""
        made = _NUMERIC_MF.get(regime)      # kept while the regime lives: every law is compared with it
        if made is None:
            M, f = regime.raw_mass_matrix, regime.raw_forcing       # as derived: equal, nothing to simplify
            plain, _ = algebra.plain_state(M.row_join(f))
            syms = sorted(plain.free_symbols, key=str)
            made = _NUMERIC_MF[regime] = (syms, evaluator(plain, syms))
        syms, fn = made
        with np.errstate(all="ignore"):
            Mf = np.array(fn(*[self._value(i, s) for s in syms]), dtype=complex)
        a = np.linalg.solve(Mf[:, :-1], Mf[:, -1])
        # the plain symbol of q̈ (of ẇ for a quasi-coordinate, whose rate is a speed w)
        return {_plain_acc(q): complex(v) for q, v in zip(coords, a)}

    def residual(self, expr, regime, coords, i: int, extra: dict | None = None) -> tuple[complex, float]:
        """(value, scale) of ``expr`` with the regime's accelerations (and ``extra`` plain values) at point i."""
        vals = dict(self.accelerations(regime, coords, i))
        vals.update(extra or {})
        terms = sp.Add.make_args(sp.sympify(expr))
        parts = [self.evaluate(a, i, vals) for a in terms]
        return sum(parts), max([1.0] + [abs(p) for p in parts])


_PLAIN_ACC: dict = {}
#: Each regime's M | f ready to evaluate (not on the regime itself: numeric functions are not pickled with
#: a derivation).
_NUMERIC_MF: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _plain_acc(q):
    """The plain symbol that stands for q̈ in ``algebra.plain_state``."""
    if q not in _PLAIN_ACC:
        _PLAIN_ACC[q] = algebra.plain_state(q.diff(t, 2))[0]
    return _PLAIN_ACC[q]


def holds_numerically(expr, regime, coords, sampler: Sampler | None = None, extra=None) -> tuple[bool, str]:
    """``expr`` (with q̈) vanishes when the regime's accelerations are substituted, at random states."""
    sampler = sampler or Sampler()
    used = 0
    for i in range(sampler.n):
        try:
            v, scale = sampler.residual(expr, regime, coords, i, extra)
        except np.linalg.LinAlgError:
            continue
        if not np.isfinite(v):
            continue
        used += 1
        if abs(v) > RTOL * scale:
            return False, f"numeric: fails at a random state (residual {abs(v):.3g})"
    return used >= MIN_SAMPLES, f"numeric: {used} random states and parameter sets, rel. tol. {RTOL:g}"


# the laws -----------------------------------------------------------------------------------------
