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


def _determinacy(A: sp.Matrix, b: sp.Matrix, unknowns, labels, dof_note: str = "") -> list[int]:
    """Check the linear system; return the indices of a square, nonsingular set of rows."""
    Ab = _numeric_fast(A.row_join(b), 5)
    nA, nb = Ab[:, :-1], Ab[:, -1:]
    scale = max(1.0, float(np.abs(nA).max()))
    rank = np.linalg.matrix_rank(nA, tol=1e-9 * scale)
    n = len(unknowns)
    if rank < n:
        _, _, vh = np.linalg.svd(nA)
        null = vh[rank:].conj().T
        loose = [text(unknowns[i]) for i in range(n) if np.abs(null[i]).max() > 1e-8]
        raise ConstraintError(
            f"the balance laws give {len(labels)} equations of rank {rank} for {n} unknowns; "
            f"{', '.join(loose)} cannot be determined from them.",
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
    if bad:
        raise ConstraintError(
            f"the balance laws give {len(labels)} equations for {n} unknowns "
            f"({', '.join(text(u) for u in unknowns)}), and {'; '.join(bad)} contradict the others.",
            hint="The coordinates hold back motions that no constraint enforces: a constraint (with its "
                 "reaction) is missing, or a load has no reaction to carry it. "
                 f"{dof_note}")
    return keep


def refuse_driven_against_ground(relating, exprs, numA) -> None:
    """A row in no rate that still involves t holds a prescribed motion (a frame turned or a point moved by a
    law of t) against the ground: no motion of the coordinates can satisfy it."""
    for i, (row, e) in enumerate(zip(relating, exprs)):
        if abs(numA[i]).max() > 1e-12 or not algebra.plain_state(sp.sympify(e))[0].free_symbols:
            continue
        raise ConstraintError(
            f"the constraint row '{row.label}' reads {e} = 0, which no motion of the coordinates satisfies: it "
            "holds against the ground a motion that is prescribed (a frame turned or a point moved by a given "
            "law of t).",
            where=row.constraint,
            hint="Make the driven part a body and attach to it: shaft = s.drive(\"shaft\", S) (in a file, "
                 "[drives] shaft = { frame = \"S\" }), then s.pin(..., body_b=shaft); the drive's reactions "
                 "are the force and torque needed to keep the prescribed motion.")
