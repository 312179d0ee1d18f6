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
        c = m if fr == frame else frame.dcm(fr) * m
        for i in range(3):
            out[i] += c[i]
    return tuple(out)


def dot(a, b) -> sp.Expr:
    """a · b for two component triples in the same frame (zero terms skipped)."""
    return sp.Add(*[x * y for x, y in zip(a, b) if x != 0 and y != 0])
