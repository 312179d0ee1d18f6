"""Closing the holonomic constraints of a projected model (:mod:`rigidkin.numeric.large.projected`).

A holonomic constraint among the rows (a gap that must stay zero: the front wheel of a bicycle touching
the ground) fixes one dependent coordinate at any configuration, often with no closed form.  The
coordinates the gaps fix are read from the gaps' Jacobian at a sample configuration (those whose rate is a
dependent speed first), and a configuration is closed on them by Newton's method — in double precision
(numpy) or in any precision (mpmath).
"""

from __future__ import annotations

import random

import mpmath
import numpy as np

from ...base.errors import ConstraintError, RigidkinError


def holonomic_coordinates(model) -> tuple:
    """The dependent coordinates that the gaps fix (one per gap), found from the gaps' Jacobian."""
    if not model._n_gaps:
        return ()
    rng = random.Random(2)
    q = [rng.uniform(0.1, 0.3) for _ in model.coordinates]
    _, J = model.gaps(q)
    J = np.atleast_2d(J)
    chosen: list[int] = []
    # the coordinates whose rate is a dependent speed first, then those whose speeds are replaced
    named = [model.coordinates.index(model._speed_names[i]) for i in model.dependent_index
             if model._speed_names[i] in model.coordinates]
    free = set(model.independent)
    named += [i for i in range(len(model.coordinates)) if i not in named and model.coordinates[i] not in free
              and model.coordinates[i] in model.kinematic.replaced]
    for i in reversed(named):
        trial = chosen + [i]
        if np.linalg.matrix_rank(J[:, trial], tol=1e-9) == len(trial):
            chosen = trial
        if len(chosen) == model._n_gaps:
            break
    if len(chosen) < model._n_gaps:
        raise ConstraintError("the holonomic constraints do not fix any set of dependent coordinates.",
                              where=model.system.name)
    return tuple(sorted(chosen))


def configuration(model, q, kind: str = "numpy", values=None, tol=None, max_iter: int = 50):
    """``q`` of ``model`` with the holonomic dependent coordinates corrected (Newton) so that every gap vanishes."""
    idx = holonomic_coordinates(model)
    if not idx:
        return list(q)
    q = list(q)
    tol = tol if tol is not None else (1e-14 if kind != "mpmath" else mpmath.mpf(10) ** (-mpmath.mp.dps + 5))
    for _ in range(max_iter):
        g, J = model.gaps(q, kind=kind, values=values)
        if kind == "mpmath":
            Jd = mpmath.matrix([[J[r, c] for c in idx] for r in range(len(idx))])
            dq = mpmath.lu_solve(Jd, g)
            step = max(abs(x) for x in dq)
            for k, i in enumerate(idx):
                q[i] -= dq[k]
        else:
            J = np.atleast_2d(J)
            dq = np.linalg.solve(J[:, idx], np.ravel(g))
            step = float(np.abs(dq).max())
            for k, i in enumerate(idx):
                q[i] = q[i] - dq[k]
        if step < tol:
            return q
    raise RigidkinError("Newton's method did not close the holonomic constraints.", where=model.system.name,
                        hint="Start from a configuration closer to one the constraints allow.")
