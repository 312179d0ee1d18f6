"""Vector algebra on components: each vector resolved once into a frame, then plain sums of products.

``Vector.dot`` turns every pair of frame terms into a direction-cosine product each time it is called;
resolving a vector along three basis vectors, or dotting it with the partial velocities of every
independent rate, repeats that work.  Here each frame term is turned into the target frame once
(``frame.dcm(B) · m``, the same products ``Vector.dot`` forms), and the scalars follow by plain sums.
``cross`` and ``dt`` give the same expressions as sympy's ``Vector.cross`` and ``Vector.dt`` (the
transport theorem term by term), formed without the Vector and Matrix arithmetic in between.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from .algebra import time_derivatives

_ZERO = sp.Integer(0)
_t = dynamicsymbols._t


def in_frame(v: Vector, frame) -> tuple:
    """(x, y, z) of ``v`` along the basis of ``frame`` (a sympy ReferenceFrame)."""
    out = [_ZERO, _ZERO, _ZERO]
    if not isinstance(v, Vector):
        return tuple(out)
    for m, fr in v.args:
        c = list(m)
        if fr != frame:
            d = _dcm(frame, fr)
            # sympy's zero is one object: skip the products it would make (Zero.__mul__ is not free)
            c = [sp.Add(*[x * y for x, y in zip(d[i], c) if x is not _ZERO and y is not _ZERO])
                 for i in range(3)]
        for i in range(3):
            if c[i] is not _ZERO:
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


def dot_vectors(a: Vector, b: Vector) -> sp.Expr:
    """a · b: ``a`` resolved once into each frame ``b`` is written in."""
    return sp.Add(*[dot(in_frame(a, fr), list(m)) for m, fr in getattr(b, "args", ())])


def cross(a: Vector, b: Vector) -> Vector:
    """a × b, written in the frames of ``b`` (as ``Vector.cross`` writes it)."""
    out = []
    for m, frame in getattr(b, "args", ()):
        s = in_frame(a, frame)
        o = list(m)
        out.append((sp.Matrix([s[1] * o[2] - s[2] * o[1], s[2] * o[0] - s[0] * o[2], s[0] * o[1] - s[1] * o[0]]),
                    frame))
    return Vector(out)


def dt(v: Vector, frame, memo: dict | None = None) -> Vector:
    """The rate of ``v`` in ``frame``: each term's components differentiated, plus ω × term for a term
    written in a frame that turns (the transport theorem, as ``Vector.dt`` applies it).  The components
    are differentiated in one pass (``algebra.time_derivatives``; ``memo`` kept between calls), which
    gives sympy's ``diff`` expressions with each shared subtree differentiated once."""
    out = []
    for m, fr in getattr(v, "args", ()):
        dm = sp.Matrix(time_derivatives(list(m), memo))
        if fr == frame:
            out.append((dm, frame))
        else:
            out += (Vector([(dm, fr)]) + cross(fr.ang_vel_in(frame), Vector([(m, fr)]))).args
    return Vector(out)
