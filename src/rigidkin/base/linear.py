"""Solving the linear balance equations with pivots that vanish only where the physics is singular.

Gaussian elimination divides by its pivots, and whatever it divides by ends up in the denominators of
the accelerations and reactions.  A pivot chosen for its size at one random state (``l·sin θ1``, say)
is zero at the straight hanging state, where the true reactions are finite: a removable singularity
that makes the printed result NaN exactly where a user evaluates it.  Here each pivot is chosen by

1. being non-zero at a random state and at the special states (every coordinate at 0, ±π/2, π, one at
   a time and all together; the same rates and parameters), tracked numerically alongside the symbolic
   elimination;
2. being free of the coordinates and rates (a mass, a length, ±1) rather than a function of the state;
3. its magnitude at the random state.

Rows and columns are both pivoted (full pivoting), so of an over-determined but consistent set of
balance equations the rows with the simplest reaction coefficients (Euler's first law along the
inertial axes for pinned rods) are used.  A mass matrix is solved with symmetric (diagonal) pivots:
it is positive definite, so every pivot is a ratio of its principal minors and never vanishes for a
physical configuration.
"""

from __future__ import annotations

import math
import random

import numpy as np
import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.physics.vector import dynamicsymbols

from . import algebra

t = dynamicsymbols._t

#: The values every coordinate takes at the special states (besides a random value).
SPECIAL_VALUES = (0.0, math.pi / 2, math.pi, -math.pi / 2)
#: At most this many special states are tracked (all coordinates together, then one at a time).
MAX_SPECIAL = 40


def _state_functions(expr) -> set:
    return {f for f in expr.atoms(AppliedUndef) if f.args == (t,)}


def special_states(coords, rng: random.Random) -> list[dict]:
    """Values of plain coordinate symbols: all at 0, ±π/2, π together, then each one alone at those."""
    coords = list(coords)
    states = [dict.fromkeys(coords, v) for v in SPECIAL_VALUES]
    base = {c: rng.uniform(0.3, 1.2) for c in coords}
    for c in coords:
        for v in SPECIAL_VALUES:
            if len(states) >= MAX_SPECIAL:
                return states
            states.append({**base, c: v})
    if len(coords) > 1:
        states.append(dict(base))        # aligned bodies: every angle the same
    return states


class _Probe:
    """Numeric copies of a matrix at one random state and at the special states (the right-hand side,
    which may be large, is not needed to choose pivots)."""

    def __init__(self, A: sp.Matrix, seed: int):
        plain, back = algebra.plain_state(A)
        syms = sorted(plain.free_symbols - {t}, key=str)
        coords = sorted((s for s, f in back.items() if not isinstance(f, sp.Derivative)), key=str)
        rng = random.Random(seed)
        fn = sp.lambdify([t] + syms, plain, "numpy")
        def at(p):
            try:
                return np.array(fn(0.41, *[p[s] for s in syms]), dtype=complex)
            except ZeroDivisionError:         # e.g. Euler parameters all zero: no rotation, not a state
                return np.full(plain.shape, np.nan, dtype=complex)

        with np.errstate(all="ignore"):
            for _ in range(8):     # a point where every entry is defined (a rope's √(d² − r²) needs d > r)
                base = {s: float(v) for s, v in algebra.random_point(syms, rng).items()}
                if np.all(np.isfinite(at(base))):
                    break
            points = [base] + [{**base, **st} for st in special_states(coords, rng)]
            self.mats = np.array([at(p) for p in points])
        self.scale = max(1.0, float(np.nanmax(np.abs(self.mats[0])))) if self.mats[0].size else 1.0

    def zero_at(self, i: int, j: int) -> int:
        """At how many special states the entry (i, j) vanishes (or is not finite)."""
        v = self.mats[1:, i, j]
        bad = ~np.isfinite(v) | (np.abs(v) < 1e-9 * self.scale)
        return int(bad.sum())

    def value(self, i: int, j: int) -> float:
        v = self.mats[0, i, j]
        return abs(v) if np.isfinite(v) else 0.0

    def eliminate(self, rows, cols, rest) -> None:
        """The numeric counterpart of eliminating the pivot block (rows × cols) from the rows ``rest``."""
        with np.errstate(all="ignore"):
            B = self.mats[:, rows][:, :, cols]                       # (points, k, k)
            if len(rows) == 1:
                inv = 1 / B
            else:
                det = B[:, 0, 0] * B[:, 1, 1] - B[:, 0, 1] * B[:, 1, 0]
                inv = np.stack([np.stack([B[:, 1, 1], -B[:, 0, 1]], -1),
                                np.stack([-B[:, 1, 0], B[:, 0, 0]], -1)], -2) / det[:, None, None]
            for i in rest:
                f = np.einsum("pa,pab->pb", self.mats[:, i, cols], inv)
                self.mats[:, i, :] = self.mats[:, i, :] - np.einsum("pb,pbc->pc", f, self.mats[:, rows, :])


def solve_linear(A: sp.Matrix, b: sp.Matrix, simplify=algebra.readable, symmetric: bool = False,
                 seed: int = 7) -> sp.Matrix:
    """x with A x = b, for A with full column rank (rows ≥ columns, a consistent system).

    ``symmetric``: A is a mass matrix (square, positive definite), pivoted on its diagonal.
    Where every single pivot left vanishes at some special state (a bearing couple resolved along axes
    that turn with a spin angle: cos φ, sin φ), a 2 × 2 block whose determinant does not is used instead
    (its inverse is its adjugate over that determinant, reduced with sin² + cos² = 1).
    Raises ZeroDivisionError when no pivot is left (A is singular).
    """
    forced: list = []
    for _ in range(4):
        try:
            return _solve(A, b, simplify, symmetric, seed, forced, retry=len(forced) < 3)
        except _Retry as hard:
            forced.append(hard.column)
    raise ZeroDivisionError("singular")        # not reached: the last try accepts what it finds


class _Retry(Exception):
    """Every pivot left for ``column`` vanishes at a special state: start again with it in a 2 × 2 block."""

    def __init__(self, column: int):
        super().__init__(column)
        self.column = column


def _solve(A, b, simplify, symmetric, seed, forced, retry):
    nrows, n = A.shape
    A, b = A.as_mutable(), b.as_mutable()
    probe = _Probe(A, seed)

    def state_dependent(i, j):
        return bool(_state_functions(A[i, j]))

    free_rows, free_cols = list(range(nrows)), list(range(n))
    blocks = []                 # (rows, columns, inverse of the block) of each pivot
    tol = 1e-10 * probe.scale
    while free_cols:
        if symmetric:
            cands = [(i, i) for i in free_cols if i in free_rows]
        else:
            cands = [(i, j) for j in free_cols for i in free_rows]
        cands = [(i, j) for i, j in cands if A[i, j] != 0 and probe.value(i, j) > tol]
        if not cands and symmetric:
            cands = [(i, j) for j in free_cols for i in free_rows if A[i, j] != 0 and probe.value(i, j) > tol]
        if not cands:
            raise ZeroDivisionError("singular")
        k, j = min(cands, key=lambda ij: (probe.zero_at(*ij), state_dependent(*ij), -probe.value(*ij), ij))
        block = None
        want = [c for c in forced if c in free_cols]
        if want and not symmetric:
            block = _block_pivot(A, probe, free_rows, free_cols, tol, want[0])
        if block is None and probe.zero_at(k, j):
            block = _block_pivot(A, probe, free_rows, free_cols, tol)
            if block is None and retry and not symmetric:
                raise _Retry(j)
        if block is None:
            rows, cols, inv = [k], [j], sp.Matrix([[1 / A[k, j]]])
        else:
            rows, cols, inv = block
        blocks.append((rows, cols, inv))
        for r in rows:
            free_rows.remove(r)
        for c in cols:
            free_cols.remove(c)
        rest = [i for i in free_rows if any(A[i, c] != 0 for c in cols)]
        for i in rest:
            f = (sp.Matrix([[A[i, c] for c in cols]]) * inv).applyfunc(_reduce)
            for c in free_cols:
                if any(A[r, c] != 0 for r in rows):
                    A[i, c] = _reduce(A[i, c] - sum((f[a] * A[r, c] for a, r in enumerate(rows)), sp.Integer(0)))
            for c in cols:
                A[i, c] = sp.Integer(0)
            b[i] = b[i] - sum((f[a] * b[r] for a, r in enumerate(rows)), sp.Integer(0))
        probe.eliminate(rows, cols, rest)
    x = [sp.Integer(0)] * n
    for pos in reversed(range(len(blocks))):
        rows, cols, inv = blocks[pos]
        later = [c for _, cs, _ in blocks[pos + 1:] for c in cs]
        acc = sp.Matrix([b[r] - sum((A[r, c] * x[c] for c in later if A[r, c] != 0), sp.Integer(0)) for r in rows])
        for c, v in zip(cols, inv * acc):
            x[c] = simplify(v)
    return sp.Matrix(x)


def _reduce(e):
    """A coefficient after elimination, cancelled (and reduced with sin² + cos² = 1 where it is small)."""
    e = sp.cancel(e)
    if sp.count_ops(e) <= 60 and e.has(sp.sin, sp.cos):
        e = algebra.trig_reduce(e)
    return e


def _block_pivot(A, probe, free_rows, free_cols, tol, column=None):
    """A 2 × 2 block of the free rows and columns (one of them ``column`` if given) whose determinant
    vanishes at no special state."""
    best = None
    pairs = [(c1, c2) for a, c1 in enumerate(free_cols) for c2 in free_cols[a + 1:]
             if column is None or column in (c1, c2)]
    m = probe.mats
    for c1, c2 in pairs:
        for b_, r1 in enumerate(free_rows):
            for r2 in free_rows[b_ + 1:]:
                with np.errstate(all="ignore"):
                    det = m[:, r1, c1] * m[:, r2, c2] - m[:, r1, c2] * m[:, r2, c1]
                if not np.isfinite(det[0]) or abs(det[0]) <= tol:
                    continue
                zeros = int((~np.isfinite(det[1:]) | (np.abs(det[1:]) < 1e-9 * probe.scale)).sum())
                if zeros:
                    continue
                spread = float(np.nanstd(np.abs(det)) / abs(det[0]))       # ≈ 0: a determinant free of the state
                key = (round(spread, 6), -abs(det[0]))
                if best is None or key < best[0]:
                    best = (key, [r1, r2], [c1, c2])
    if best is None:
        return None
    _, rows, cols = best
    B = sp.Matrix([[A[r, c] for c in cols] for r in rows])
    det = _reduce(sp.expand(B.det()))
    inv = (B.adjugate() / det).applyfunc(_reduce)
    return rows, cols, inv


# linear forms ---------------------------------------------------------------------------------------
def linear_form(exprs, unknowns):
    """(A, b) with exprs = A·unknowns + b, for expressions linear in ``unknowns`` (Derivatives allowed).

    One pass over each expression tree (shared subtrees visited once): a sum splits term by term, a
    product keeps its unknown-free factors as the coefficient of the one factor that holds unknowns.
    O(size) instead of one derivative per unknown; an expression that is not visibly linear in this
    way (an unknown inside a power or a function) is differentiated instead.
    """
    unknowns = list(unknowns)
    index = {u: i for i, u in enumerate(unknowns)}
    memo: dict = {}
    rows, rest = [], []
    for e in exprs:
        e = sp.sympify(e)
        try:
            coeffs, const = _split_linear(e, index, memo)
        except _NotLinear:
            coeffs, const = _split_by_diff(e, unknowns)
        rows.append([coeffs.get(i, sp.Integer(0)) for i in range(len(unknowns))])
        rest.append(const)
    return sp.Matrix(len(rows), len(unknowns), [c for r in rows for c in r]), sp.Matrix(rest)


class _NotLinear(Exception):
    """An unknown sits where a one-pass split cannot take it out (a power, a function's argument)."""


_NONE: dict = {}


def _split_linear(e, index, memo):
    """({unknown index: coefficient}, remainder) of ``e``; the remainder is ``e`` itself when free."""
    hit = memo.get(e)
    if hit is not None:
        return hit
    if e in index:
        out = ({index[e]: sp.Integer(1)}, sp.Integer(0))
    elif e.is_Atom:
        out = (_NONE, e)
    elif e.is_Add:
        parts = [_split_linear(a, index, memo) for a in e.args]
        if all(not c for c, _ in parts):
            out = (_NONE, e)
        else:
            coeffs: dict = {}
            for c, _ in parts:
                for i, v in c.items():
                    coeffs.setdefault(i, []).append(v)
            out = ({i: sp.Add(*v) for i, v in coeffs.items()}, sp.Add(*[r for _, r in parts]))
    elif e.is_Mul:
        parts = [_split_linear(a, index, memo) for a in e.args]
        holding = [k for k, (c, _) in enumerate(parts) if c]
        if not holding:
            out = (_NONE, e)
        elif len(holding) > 1:
            raise _NotLinear
        else:
            k = holding[0]
            other = sp.Mul(*[a for j, a in enumerate(e.args) if j != k])
            c, r = parts[k]
            out = ({i: other * v for i, v in c.items()}, other * r)
    else:
        if any(_split_linear(a, index, memo)[0] for a in e.args if isinstance(a, sp.Basic)):
            raise _NotLinear
        out = (_NONE, e)
    memo[e] = out
    return out


def _split_by_diff(e, unknowns):
    dummies = [sp.Dummy(f"u{i}") for i in range(len(unknowns))]
    e = e.xreplace(dict(zip(unknowns, dummies)))
    present = e.free_symbols
    coeffs = {i: e.diff(d) for i, d in enumerate(dummies) if d in present}
    back = dict(zip(dummies, unknowns))
    return ({i: c.xreplace(back) for i, c in coeffs.items()},
            e.xreplace(dict.fromkeys(dummies, sp.Integer(0))).xreplace(back))
