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
        base = {s: float(v) for s, v in algebra.random_point(syms, rng).items()}
        points = [base] + [{**base, **st} for st in special_states(coords, rng)]
        fn = sp.lambdify([t] + syms, plain, "numpy")
        with np.errstate(all="ignore"):
            self.mats = np.array([np.array(fn(0.41, *[p[s] for s in syms]), dtype=complex) for p in points])
        self.scale = max(1.0, float(np.nanmax(np.abs(self.mats[0])))) if self.mats[0].size else 1.0

    def zero_at(self, i: int, j: int) -> int:
        """At how many special states the entry (i, j) vanishes (or is not finite)."""
        v = self.mats[1:, i, j]
        bad = ~np.isfinite(v) | (np.abs(v) < 1e-9 * self.scale)
        return int(bad.sum())

    def value(self, i: int, j: int) -> float:
        v = self.mats[0, i, j]
        return abs(v) if np.isfinite(v) else 0.0

    def eliminate(self, k: int, j: int, rows) -> None:
        with np.errstate(all="ignore"):
            piv = self.mats[:, k, j][:, None]
            for i in rows:
                f = self.mats[:, i, j][:, None] / piv
                self.mats[:, i, :] = self.mats[:, i, :] - f * self.mats[:, k, :]


def solve_linear(A: sp.Matrix, b: sp.Matrix, simplify=algebra.readable, symmetric: bool = False,
                 seed: int = 7) -> sp.Matrix:
    """x with A x = b, for A with full column rank (rows ≥ columns, a consistent system).

    ``symmetric``: A is a mass matrix (square, positive definite), pivoted on its diagonal.
    Raises ZeroDivisionError when no pivot is left (A is singular).
    """
    nrows, n = A.shape
    A, b = A.as_mutable(), b.as_mutable()
    probe = _Probe(A, seed)

    def state_dependent(i, j):
        return bool(_state_functions(A[i, j]))

    free_rows, free_cols = list(range(nrows)), list(range(n))
    order = []                  # (row, column) of each pivot
    tol = 1e-10 * probe.scale
    for _ in range(n):
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
        order.append((k, j))
        free_rows.remove(k)
        free_cols.remove(j)
        rest = [i for i in free_rows if A[i, j] != 0]
        for i in rest:
            f = A[i, j] / A[k, j]
            for c in free_cols:
                if A[k, c] != 0:
                    A[i, c] = sp.cancel(A[i, c] - f * A[k, c])
            A[i, j] = sp.Integer(0)
            b[i] = b[i] - f * b[k]
        probe.eliminate(k, j, rest)
    x = [sp.Integer(0)] * n
    for pos in reversed(range(n)):
        k, j = order[pos]
        acc = b[k] - sum((A[k, c] * x[c] for _, c in order[pos + 1:] if A[k, c] != 0), sp.Integer(0))
        x[j] = simplify(acc / A[k, j])
    return sp.Matrix(x)
