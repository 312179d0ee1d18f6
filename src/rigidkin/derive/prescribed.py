"""Prescribed motions met by the constraints: a row that a given law of t breaks whatever the coordinates do."""

from __future__ import annotations

import sympy as sp

from ..base import algebra
from ..base.errors import ConstraintError


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
            hint="Make the driven part a body and attach to it: shaft = s.drive(\"shaft\", S) (in a file, in "
                 "[bodies]: shaft = { shape = \"massless\", frame = \"S\", at = \"O\", driven = true }), then "
                 "s.pin(..., body_b=shaft); the drive's reactions are the force and torque needed to keep the "
                 "prescribed motion.")
