"""Is a set of balance equations determinate?  Its numeric rank at a random state decides.

If the rank is short, the error names the unknowns that cannot be found (a redundant support, a
missing constraint); if rows left out contradict the others, it names them (a motion that no
constraint holds back).  Otherwise the indices of a square, nonsingular set of rows are returned.
"""

from __future__ import annotations

import random

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import ConstraintError
from ..base.printing import text
from . import conflict

t = dynamicsymbols._t


def _numeric(M: sp.Matrix, seed: int) -> np.ndarray:
    plain, _ = algebra.plain_state(M)
    rng = random.Random(seed)
    vals = algebra.random_point(plain.free_symbols - {t}, rng)
    vals[t] = sp.Float(0.41)
    return np.array(plain.xreplace(vals).evalf(), dtype=complex)


def _numeric_fast(M: sp.Matrix, seed: int) -> np.ndarray:
    """Like ``_numeric`` in machine arithmetic (``algebra.evaluate``): for large coefficient matrices."""
    entries = list(M)
    vals = algebra.state_point(entries, random.Random(seed), 0.41)
    with np.errstate(all="ignore"):
        return np.array(algebra.evaluate(entries, vals), dtype=complex).reshape(M.shape)


def _determinacy(A: sp.Matrix, b: sp.Matrix, unknowns, labels, dof_note: str = "", equations=None,
                 setup=None) -> list[int]:
    """Check the linear system; return the indices of a square, nonsingular set of rows.  With the balance
    ``equations`` (and the mode's ``setup``) a contradiction names the body, law and contact in conflict."""
    Ab = _numeric_fast(A.row_join(b), 5)
    nA, nb = Ab[:, :-1], Ab[:, -1:]
    scale = max(1.0, float(np.abs(nA).max()))
    rank = np.linalg.matrix_rank(nA, tol=1e-9 * scale)
    n = len(unknowns)
    if rank < n:
        _, _, vh = np.linalg.svd(nA)
        null = vh[rank:].conj().T
        loose = [unknowns[i] for i in range(n) if np.abs(null[i]).max() > 1e-8]
        owner = {row.reaction: row.constraint for row in getattr(setup, "rows", ())}
        of = sorted({owner[u] for u in loose if u in owner})
        raise ConstraintError(
            f"the balance laws give {len(labels)} equations of rank {rank} for {n} unknowns; "
            f"{', '.join(text(u) for u in loose)} cannot be determined from them"
            + (f" (the reactions of {', '.join(of)})." if of else "."), where=", ".join(of) or None,
            hint="The model is under-determined: a reaction is redundant (statically indeterminate "
                 f"supports) or a body lacks a constraint or a coordinate. {dof_note}")
    keep = []
    for i in range(len(labels)):
        trial = keep + [i]
        if np.linalg.matrix_rank(nA[trial], tol=1e-9 * scale) == len(trial):
            keep = trial
        if len(keep) == n:
            break
    # consistency of the rows left out
    x = np.linalg.solve(nA[keep], nb[keep])
    bad = [labels[i] for i in range(len(labels)) if i not in keep
           and abs((nA[i] @ x - nb[i])[0]) > 1e-8 * max(1.0, float(np.abs(nb).max()))]
    named = conflict.explain(setup, equations, nA, nb, unknowns) if bad and equations is not None else None
    if named:
        raise ConstraintError(named[0], hint=f"{named[1]} {dof_note}".strip(), where=named[2] or None)
    if bad:
        raise ConstraintError(
            f"the balance laws give {len(labels)} equations for {n} unknowns "
            f"({', '.join(text(u) for u in unknowns)}), and {'; '.join(bad)} contradict the others.",
            hint="The coordinates hold back motions that no constraint enforces: a constraint (with its "
                 "reaction) is missing, or a load has no reaction to carry it; or the geometry is not what was "
                 "meant: a rope wrapped round a pulley in the wrong sense, a point on the wrong side (see it with "
                 f"'rigidkin draw FILE', which draws the geometry and free-body diagrams without solving). {dof_note}")
    return keep
