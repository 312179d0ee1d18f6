"""Equations as vectors: is a student's equation a valid combination of the balance equations?

Every balance equation of a mode is linear in the unknowns u = (q̈ of the independent coordinates, the
reactions): ``a(x)·u + b(x) = 0`` with x the state and the parameters.  At a random x it is the row
``(a, b)``.  A claimed equation is valid — whatever its factor, arrangement or the combination of laws
it came from — when its row lies in the span of the balance equations' rows at every random x
(several states and parameter sets, drawn deterministically from the names).  A carried error is the
same test against the balance equations with some replaced by the student's own.
"""

from __future__ import annotations

import random

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra

t = dynamicsymbols._t

SAMPLES = 6
MIN_SAMPLES = 3
RTOL = 1e-7


class NotLinear(ValueError):
    """The equation is not linear in the unknowns (q̈, reactions)."""


def plain_accel(q) -> sp.Symbol:
    """The plain symbol that ``to_plain`` gives q̈: ``_q_d2``, or ``_w_d1`` for a quasi-coordinate whose
    rate is the speed w (its second derivative is ẇ, the unknown its equations are written in)."""
    return to_plain(q.diff(t, 2))


class Sampler:
    """Random states and parameter sets; each symbol's value depends only on its name and the sample."""

    def __init__(self, unknowns, n: int = SAMPLES, seed: int = 19, unit_groups=()):
        self.n, self.seed = n, seed
        self.unknowns = list(unknowns)            # plain symbols
        self._values: list[dict] = [{} for _ in range(n)]
        self._funcs: dict = {}
        # Euler parameters (plain symbols, four per frame): sampled together on |e| = 1, where a hand
        # derivation writes them (the engine's forms hold for any e; a student's for unit e)
        self._unit = {s: tuple(g) for g in unit_groups for s in g}

    def value(self, i: int, s: sp.Symbol) -> float:
        d = self._values[i]
        if s not in d and s in self._unit:
            group = self._unit[s]
            rng = random.Random(f"{self.seed}:{i}:" + ":".join(x.name for x in group))
            e = [rng.gauss(0.0, 1.0) for _ in group]
            norm = sum(x * x for x in e) ** 0.5
            d.update({x: v / norm for x, v in zip(group, e)})
        if s not in d:
            rng = random.Random(f"{self.seed}:{i}:{s.name}")
            if s == t:
                d[s] = rng.uniform(0.1, 1.0)
            elif s.is_positive:
                d[s] = rng.uniform(0.5, 2.0)
            else:
                v = rng.uniform(0.3, 1.5)
                d[s] = v if rng.random() < 0.5 else -v
        return d[s]

    def _lambda(self, exprs):
        key = tuple(exprs)
        if key not in self._funcs:
            syms = sorted(set().union(*[e.free_symbols for e in exprs]), key=str)
            self._funcs[key] = (syms, sp.lambdify(syms, list(exprs), modules=["numpy"]))
        return self._funcs[key]

    def evaluate(self, exprs) -> np.ndarray:
        """(samples, len(exprs)) values of plain-symbol expressions (nan where undefined)."""
        syms, fn = self._lambda([sp.sympify(e) for e in exprs])
        out = np.full((self.n, len(exprs)), np.nan, dtype=complex)
        with np.errstate(all="ignore"):
            for i in range(self.n):
                try:
                    out[i] = np.array(fn(*[self.value(i, s) for s in syms]), dtype=complex)
                except (ZeroDivisionError, OverflowError, ValueError, TypeError):
                    continue
        return out

    def row(self, plain: sp.Expr) -> np.ndarray:
        """(samples, n_unknowns + 1): the coefficients of the unknowns and the remaining term."""
        coeffs = [plain.diff(u) for u in self.unknowns]
        for c in coeffs:
            if c.has(*self.unknowns):
                raise NotLinear(c)
        rest = plain.xreplace({u: 0 for u in self.unknowns})
        return self.evaluate(coeffs + [rest])


def to_plain(expr) -> sp.Expr:
    return algebra.plain_state(sp.sympify(expr))[0]


def _usable(*arrays) -> np.ndarray:
    ok = np.ones(arrays[0].shape[0], dtype=bool)
    for a in arrays:
        ok &= np.all(np.isfinite(a.reshape(a.shape[0], -1)), axis=1)
    return ok


def in_span(basis: list[np.ndarray], row: np.ndarray, rtol: float = RTOL) -> bool | None:
    """True when ``row`` is a combination of the ``basis`` rows at every usable sample (None: undecided)."""
    if not basis:
        return False
    B = np.stack(basis, axis=1)                 # (samples, k, n+1)
    ok = _usable(B, row)
    if ok.sum() < MIN_SAMPLES:
        return None
    for i in np.nonzero(ok)[0]:
        r = row[i]
        nr = np.linalg.norm(r)
        if nr == 0:
            continue
        M = B[i]
        scale = np.linalg.norm(M, axis=1)
        M = M[scale > 0] / scale[scale > 0, None]
        if M.shape[0] == 0:
            return False
        x, *_ = np.linalg.lstsq(M.T, r / nr, rcond=None)
        if np.linalg.norm(M.T @ x - r / nr) > 1e3 * rtol:
            return False
    return True


def is_trivial(row: np.ndarray) -> bool:
    """0 = 0 at every usable sample."""
    ok = _usable(row)
    return bool(ok.any()) and all(np.linalg.norm(row[i]) < 1e-12 for i in np.nonzero(ok)[0])


def vanishes(values: np.ndarray, scale: np.ndarray | None = None, rtol: float = RTOL) -> bool | None:
    """A (samples, k) array of values is zero (relative to ``scale``) at every usable sample."""
    ok = _usable(values) if scale is None else _usable(values, scale)
    if ok.sum() < MIN_SAMPLES:
        return None
    for i in np.nonzero(ok)[0]:
        s = 1.0 if scale is None else max(1.0, float(np.max(np.abs(scale[i]))))
        if np.max(np.abs(values[i])) > 1e3 * rtol * s:
            return False
    return True


def free_dim(rows: list[np.ndarray], n_acc: int) -> tuple[int, int] | None:
    """The reaction-free equations (equations of motion) the rows imply, at the first usable sample:
    (how many, the rank of their acceleration part).  A consistent, determinate set has n_acc of each."""
    if not rows:
        return (0, 0)
    B = np.stack(rows, axis=1)
    ok = _usable(B)
    if not ok.any():
        return None
    M = B[np.nonzero(ok)[0][0]]
    scale = np.linalg.norm(M, axis=1)
    M = M[scale > 0] / scale[scale > 0, None]
    if M.shape[0] == 0:
        return (0, 0)
    R = M[:, n_acc:-1]
    if R.shape[1]:
        _, s_full, vh = np.linalg.svd(R.T, full_matrices=True)
        rank = int((s_full > 1e-9 * max(1.0, s_full.max(initial=0))).sum())
        Y = vh[rank:].T                       # combinations of the rows free of every reaction
    else:
        Y = np.eye(M.shape[0])
    if Y.shape[1] == 0:
        return (0, 0)
    free = Y.T @ M
    tol = 1e-9
    return (int(np.linalg.matrix_rank(free, tol=tol)), int(np.linalg.matrix_rank(free[:, :n_acc], tol=tol)))
