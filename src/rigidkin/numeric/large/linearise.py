"""Linearisation of the projected equations of motion about a motion, in many-digit arithmetic.

M δq̈ + C δq̇ + K δq = 0 (or the first-order A of d/dt (δq, δu) = A (δq, δu)) about a state of a
:class:`rigidkin.numeric.large.projected.ProjectedModel`, by central differences of its numeric equations in
``dps``-digit mpmath arithmetic: with a step of 1e-15 the differences' error is below 1e-25, so the
eigenvalues (the bicycle's weave and capsize modes) come out to double precision.  The holonomic dependent
coordinates follow each perturbation (Newton); the other state entries are held.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import mpmath
import numpy as np
import sympy as sp

from ...base.errors import ModelError


@dataclass(frozen=True)
class Linearisation:
    """M δq̈ + C δq̇ + K δq = 0 about a motion, for the independent coordinates (rows) and the chosen
    perturbed coordinates (columns of K); ``M`` and ``C`` are square in the independent rates."""

    coordinates: tuple      # independent coordinates (rows of M, C, K; columns of M, C)
    perturbed: tuple        # the coordinates the columns of K refer to
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray

    def state_matrix(self, rates: Sequence | None = None) -> np.ndarray:
        """A of d/dt (δq_perturbed, δu_rates) = A (...), over the perturbed coordinates and ``rates``
        (the indices of the independent rates kept; default: those of the perturbed coordinates)."""
        idx = [self.coordinates.index(q) for q in self.perturbed]
        rates = idx if rates is None else list(rates)
        Minv = np.linalg.inv(self.M[np.ix_(rates, rates)])
        Kp = self.K[np.ix_(rates, range(len(self.perturbed)))]
        Cp = self.C[np.ix_(rates, rates)]
        n, k = len(self.perturbed), len(rates)
        A = np.zeros((n + k, n + k))
        for i, q in enumerate(self.perturbed):
            A[i, n + rates.index(self.coordinates.index(q))] = 1.0
        A[n:, :n] = -Minv @ Kp
        A[n:, n:] = -Minv @ Cp
        return A


def state_matrix(model, q, ui, coordinates: Sequence, speeds: Sequence, values=None, dps: int = 40,
                 step: float = 1e-15) -> np.ndarray:
    """A of d/dt (δq, δu) = A (δq, δu) about the state (q, u_i), over ``coordinates`` (any of q) and
    ``speeds`` (independent speeds, named as in :attr:`independent`): the whole first-order system
    q̇ = W(q) u, u̇_i = …, differentiated by central differences in ``dps`` digits (mpmath).  The
    holonomic dependent coordinates follow each perturbation; the other state entries are held.
    It holds for any choice of speeds (its eigenvalues do not depend on the choice)."""
    cs = [model.coordinates.index(c) for c in coordinates]
    ss = [model.independent.index(s_) for s_ in speeds]
    with mpmath.workdps(dps):
        h = mpmath.mpf(step)
        p = model._param_vector("mpmath", values)
        q0 = model.configuration([mpmath.mpf(sp.Float(sp.sympify(x), dps + 5)) for x in q], kind="mpmath",
                                values=values)
        u0 = [mpmath.mpf(sp.Float(sp.sympify(x), dps + 5)) for x in ui]

        def f(qq, uu):
            u, ud = model.accelerations(qq, uu, kind="mpmath", values=values)
            qd = model._qdot("mpmath", 0, qq, list(u), p)
            return [qd[i] for i in cs] + [ud[j] for j in ss]

        cols = []
        for i in cs:
            qp, qm = list(q0), list(q0)
            qp[i] += h
            qm[i] -= h
            fp = f(model.configuration(qp, kind="mpmath", values=values), u0)
            fm = f(model.configuration(qm, kind="mpmath", values=values), u0)
            cols.append([(a - b) / (2 * h) for a, b in zip(fp, fm)])
        for j in ss:
            up, um = list(u0), list(u0)
            up[j] += h
            um[j] -= h
            fp, fm = f(q0, up), f(q0, um)
            cols.append([(a - b) / (2 * h) for a, b in zip(fp, fm)])
        return np.array([[float(c[r]) for c in cols] for r in range(len(cols))])


def linearise(model, q, ui, perturb: Sequence, values=None, dps: int = 40, step: float = 1e-15) -> Linearisation:
    """M δq̈ + C δq̇ + K δq = 0 about the state (q, u_i), with the columns of K for ``perturb``.

    Derivatives by central differences in ``dps``-digit arithmetic (mpmath): with the step
    1e-15 their error is below 1e-25, far below double precision.  The holonomic dependent
    coordinates follow each perturbation (Newton); the others keep their values.
    """
    pert = list(perturb)
    bad = [q_ for q_ in pert if q_ not in model.independent]
    if bad:
        names = ", ".join(q_.func.__name__ for q_ in model.independent)
        raise ModelError(f"{', '.join(q_.func.__name__ for q_ in bad)} are not independent coordinates.",
                         where="linearise", hint=f"Independent: {names}.")
    with mpmath.workdps(dps):
        h = mpmath.mpf(step)
        q0 = model.configuration([mpmath.mpf(sp.Float(sp.sympify(x), dps + 5)) for x in q], kind="mpmath",
                                values=values)
        u0 = [mpmath.mpf(sp.Float(sp.sympify(x), dps + 5)) for x in ui]
        M = model.mass_matrix(q0, u0, kind="mpmath", values=values)
        k = len(u0)

        def acc(qq, uu):
            return model.accelerations(qq, uu, kind="mpmath", values=values)[1]

        dK = []
        for qv in pert:
            i = model.coordinates.index(qv)
            qp, qm = list(q0), list(q0)
            qp[i] += h
            qm[i] -= h
            qp = model.configuration(qp, kind="mpmath", values=values)
            qm = model.configuration(qm, kind="mpmath", values=values)
            ap, am = acc(qp, u0), acc(qm, u0)
            dK.append([(ap[r] - am[r]) / (2 * h) for r in range(k)])
        dC = []
        for j in range(k):
            up, um = list(u0), list(u0)
            up[j] += h
            um[j] -= h
            ap, am = acc(q0, up), acc(q0, um)
            dC.append([(ap[r] - am[r]) / (2 * h) for r in range(k)])
        Dk = mpmath.matrix([[dK[c][r] for c in range(len(pert))] for r in range(k)]) if pert else None
        Dc = mpmath.matrix([[dC[c][r] for c in range(k)] for r in range(k)])
        Kmat = -(M * Dk) if pert else mpmath.matrix(k, 0)
        Cmat = -(M * Dc)
        tonp = lambda X: np.array([[float(X[r, c]) for c in range(X.cols)] for r in range(X.rows)])  # noqa: E731
        return Linearisation(model.independent, tuple(pert), tonp(M), tonp(Cmat),
                             tonp(Kmat) if pert else np.zeros((k, 0)))
