"""Vectors as their three components in one frame: expressed once, then dotted as sums of products.

``Vector.dot`` turns every pair of frame terms into a direction-cosine product each time it is called;
resolving a vector along three basis vectors, or dotting it with the partial velocities of every
independent rate, repeats that work.  Here each frame term is turned into the target frame once
(``frame.dcm(B) · m``, the same products ``Vector.dot`` forms), and the scalars follow by plain sums.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import Vector

_ZERO = sp.Integer(0)


def in_frame(v: Vector, frame) -> tuple:
    """(x, y, z) of ``v`` along the basis of ``frame`` (a sympy ReferenceFrame)."""
    out = [_ZERO, _ZERO, _ZERO]
    if not isinstance(v, Vector):
        return tuple(out)
    for m, fr in v.args:
        c = list(m)
        if fr != frame:
            d = _dcm(frame, fr)
            c = [d[i][0] * c[0] + d[i][1] * c[1] + d[i][2] * c[2] for i in range(3)]
        for i in range(3):
            out[i] += c[i]
    return tuple(out)


def _dcm(frame, other) -> list:
    """frame.dcm(other) as nested lists (kept on the frame: sympy's Matrix indexing is slow)."""
    cache = frame.__dict__.setdefault("_rigidkin_dcm_rows", {})
    hit = cache.get(other)
    if hit is None:
        hit = cache[other] = frame.dcm(other).tolist()
    return hit


def dot(a, b) -> sp.Expr:
    """a · b for two component triples in the same frame (zero terms skipped)."""
    return sp.Add(*[x * y for x, y in zip(a, b) if x != 0 and y != 0])
