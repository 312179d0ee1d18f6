"""Steady motions and their linearisation: a spinning top, a rolling coin, a spinning body.

A steady motion keeps some coordinates constant while others — the *ignorable* ones, which appear
in neither the mass matrix nor the forcing (the spin of a top, the heading of a coin) — turn at
constant rates.  It is not a rest equilibrium, so ``analysis.equilibrium`` does not apply; about it
the reaction-free equations M(q) q̈ = f(q, q̇) linearise to

    M δq̈ + C δq̇ + K δq = 0,   M = M(x*), C = −∂f/∂q̇, K = −∂f/∂q at the steady state x*,

(∂M/∂q q̈* drops out because q̈* = 0 on a steady motion).  K has no column for an ignorable
coordinate, so the first-order state is (δq of the others, δq̇ of all); C holds the gyroscopic
terms.  The characteristic polynomial det(λ I − A) is exact (sympy); eigenvalues are numeric with
the parameters' values.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import RigidkinError
from ..model.speeds import require_rate_speeds

t = dynamicsymbols._t


@dataclass(frozen=True)
class SteadyMotion:
    """The linearisation of a solution about a steady motion ``point`` (coordinates and rates → values)."""

    point: Mapping
    coordinates: tuple          # all independent coordinates of the solution
    ignorable: tuple            # coordinates absent from M and f (their rates are states)
    states: tuple               # δq of the non-ignorable coordinates, then δq̇ of all
    M: sp.Matrix
    C: sp.Matrix
    K: sp.Matrix
    A: sp.Matrix                # first-order state matrix: d(states)/dt = A states

    def characteristic_polynomial(self, lam: sp.Symbol | None = None) -> sp.Expr:
        """det(λ I − A), expanded in λ."""
        lam = lam if lam is not None else sp.Symbol("lambda")
        n = self.A.shape[0]
        return sp.expand((lam * sp.eye(n) - self.A).det(method="berkowitz"))

    def numeric_A(self, values: Mapping | None = None) -> np.ndarray:
        """A with the parameters replaced by ``values`` (symbol → number)."""
        Anum = self.A.xreplace({k: sp.Float(v) for k, v in (values or {}).items()})
        if Anum.free_symbols:
            raise RigidkinError("the linearisation still contains "
                                f"{', '.join(sorted(map(str, Anum.free_symbols)))}, which have no values.",
                                where="steady motion", hint="Pass values={symbol: number}.")
        return np.array(Anum.evalf(), dtype=float)

    def eigenvalues(self, values: Mapping | None = None) -> np.ndarray:
        """Eigenvalues of the first-order system, with ``values`` for the parameters."""
        return np.linalg.eigvals(self.numeric_A(values))

    def stability(self, values: Mapping | None = None, tol: float = 1e-9) -> str:
        """"unstable" if an eigenvalue has a positive real part, else "asymptotically stable" or "marginal"."""
        re = self.eigenvalues(values).real
        scale = max(1.0, float(np.abs(re).max()))
        if re.max() > tol * scale:
            return "unstable"
        if re.max() < -tol * scale:
            return "asymptotically stable"
        return "marginal (no growing mode in the linearisation)"


def _present(exprs) -> set:
    """The coordinates the expressions depend on — by the derivative, tested at random states, so a
    coordinate that appears but cancels (an unsimplified spin angle) counts as absent."""
    found = set()
    for e in exprs:
        plain, back = algebra.plain_state(sp.sympify(e))
        for sym in plain.free_symbols:
            q = back.get(sym)
            if q is None or isinstance(q, sp.Derivative) or q in found:
                continue
            if not algebra.is_zero(sp.diff(plain, sym)):
                found.add(q)
    return found


def _generalised(solution):
    require_rate_speeds(solution.system, "a steady motion's linearisation")
    if len(solution.regimes) != 1:
        raise RigidkinError(f"the solution has {len(solution.regimes)} regimes; a steady motion is linearised "
                            "in one.", where="steady motion", hint="Pass solution.regime(i) through a "
                                                                 "single-regime solve (a mode without slip).")
    return solution.mass_matrix, solution.forcing


def residual(solution, at: Mapping) -> dict:
    """q̈ of each independent coordinate at the state ``at``: all zero on a steady motion."""
    M, f = _generalised(solution)
    point = _point(solution, at)
    acc = M.xreplace(point).LUsolve(f.xreplace(point))
    return {q: algebra.readable(a) for q, a in zip(solution.coordinates, acc)}


def _point(solution, at: Mapping) -> dict:
    point = {}
    for k, v in at.items():
        point[k] = sp.sympify(v)
    missing = [q for q in solution.coordinates if q.diff(t) not in point]
    if missing:
        raise RigidkinError("a steady motion needs the rate of every independent coordinate; missing: "
                            + ", ".join(f"d{q.func.__name__}/dt" for q in missing) + ".", where="steady motion")
    return point


def linearise(solution, at: Mapping, check: bool = True) -> SteadyMotion:
    """Linearise the reaction-free equations of ``solution`` about the steady motion ``at``.

    ``at`` gives every independent rate and every coordinate that is not ignorable (coordinates
    and rates → values or expressions).  With ``check`` the accelerations must vanish there.
    """
    M, f = _generalised(solution)
    qs = list(solution.coordinates)
    us = [q.diff(t) for q in qs]
    present = _present(list(M) + list(f))
    extra = [q for q in present if q not in qs]
    if extra:
        raise RigidkinError("the equations contain the dependent coordinates "
                            f"{', '.join(q.func.__name__ for q in extra)}, which no integrated relation gives.",
                            where="steady motion",
                            hint="Linearise a model whose dependent coordinates are integrated, or use "
                                 "rigidkin.numeric.large.projected for large constrained systems.")
    ignorable = tuple(q for q in qs if q not in present)
    kept = [q for q in qs if q not in ignorable]
    point = _point(solution, at)
    unset = [q for q in kept if q not in point]
    if unset:
        raise RigidkinError("the steady motion must give the value of every coordinate that is not ignorable; "
                            f"missing: {', '.join(q.func.__name__ for q in unset)}.", where="steady motion")
    if check:
        res = residual(solution, point)
        bad = {q: r for q, r in res.items() if not algebra.is_zero(r)}
        if bad:
            raise RigidkinError("this is not a steady motion: the accelerations do not vanish there ("
                                + "; ".join(f"{q.func.__name__}'' = {r}" for q, r in bad.items()) + ").",
                                where="steady motion",
                                hint="Choose the rates that satisfy the steady-motion condition.")
    # derivatives: rates first (they are Derivative objects containing q), through plain symbols
    plain_u = {u: sp.Dummy(f"u_{q.func.__name__}") for q, u in zip(qs, us)}
    plain_q = {q: sp.Dummy(q.func.__name__) for q in qs}
    fp = f.xreplace(plain_u).xreplace(plain_q)
    pp = {**{plain_u[u]: v for u, v in point.items() if u in plain_u},
          **{plain_q[q]: 0 for q in ignorable},          # they cancel: any value will do
          **{plain_q[q]: v for q, v in point.items() if q in plain_q}}
    Mv = M.xreplace(plain_u).xreplace(plain_q).xreplace(pp)
    C = (-fp.jacobian([plain_u[u] for u in us])).xreplace(pp)
    K = (-fp.jacobian([plain_q[q] for q in kept])).xreplace(pp)
    Mv, C, K = (X.applyfunc(algebra.readable) for X in (Mv, C, K))
    n, k = len(qs), len(kept)
    Minv = Mv.inv()
    select = sp.zeros(k, n)
    for i, q in enumerate(kept):
        select[i, qs.index(q)] = 1
    A = sp.BlockMatrix([[sp.zeros(k, k), select], [-Minv * K, -Minv * C]]).as_explicit().applyfunc(algebra.readable)
    states = tuple(kept) + tuple(us)
    return SteadyMotion(dict(point), tuple(qs), ignorable, states, Mv, C, K, A)
