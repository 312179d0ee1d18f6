"""Direction cosines along chains of frames, kept short.

sympy finds the direction cosine matrix (DCM) of a frame relative to a distant one by multiplying the
matrices along the path between them, without simplifying: for n frames each turned about the same
axis (a planar chain of links) the entries of the product have 2ⁿ⁻¹ terms, and the kinematics of a
60-link chain never finishes.  :func:`remember` is called when a frame is oriented; it then stores, in
sympy's own cache, on first use, the DCM of the frame relative to any frame it hangs from:

* in closed form, a rotation about the common axis by the sum of the angles, along a run of frames
  turned about the same axis (cos(θ₁ + θ₂) instead of cos θ₁ cos θ₂ − sin θ₁ sin θ₂);
* otherwise as the product of the frame's own DCM and its parent's (found the same way, and stored).

:func:`shallow` writes a vector given along a frame deep in a chain in the inertial frame.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import ReferenceFrame, Vector

#: Frames deeper than this in a chain have their vectors written in the inertial frame (see ``shallow``).
MAX_CHAIN_DEPTH = 8


def _axis_dcm(u, angle) -> sp.ImmutableMatrix:
    """The DCM ``child.dcm(parent)`` of a rotation by ``angle`` about the unit axis ``u`` (parent components),
    as ``ReferenceFrame.orient_axis`` makes it: entry (i, j) is δᵢⱼ cos + (1 − cos) uᵢuⱼ − εᵢⱼₖ uₖ sin."""
    c, s = sp.cos(angle), sp.sin(angle)
    u = [sp.S(x) for x in u]
    eps = {(0, 1): 2, (1, 2): 0, (2, 0): 1}
    rows = []
    for i in range(3):
        row = []
        for j in range(3):
            uu = u[i] * u[j]
            e = (c if i == j else sp.S.Zero) + ((1 - c) * uu if uu != 0 else sp.S.Zero)
            if (i, j) in eps and u[eps[(i, j)]] != 0:
                e += u[eps[(i, j)]] * s
            elif (j, i) in eps and u[eps[(j, i)]] != 0:
                e -= u[eps[(j, i)]] * s
            row.append(e)
        rows.append(row)
    return sp.ImmutableMatrix(rows)


class _ChainCache(dict):
    """A frame's DCM cache that also answers, on first use, for any frame along its chain of parents
    (sympy asks ``other in frame._dcm_cache`` before multiplying along the path)."""

    def __init__(self, ref: ReferenceFrame, entries: dict):
        super().__init__(entries)
        self.ref = ref

    def __contains__(self, other) -> bool:
        if dict.__contains__(self, other):
            return True
        dcm = _along_chain(self.ref, other)
        if dcm is None:
            return False
        self[other] = dcm
        other._dcm_cache[self.ref] = dcm.T
        return True


def _hangs_from(ref: ReferenceFrame, other: ReferenceFrame) -> list | None:
    """The frames from ``ref`` up to (not including) ``other`` when ``ref`` hangs from ``other``, else None."""
    path, cur = [], ref
    while cur is not other and getattr(cur, "_rigidkin_link", None) is not None:
        path.append(cur)
        cur = cur._rigidkin_link[0]
    return path if cur is other else None


def _along_chain(ref: ReferenceFrame, other: ReferenceFrame):
    """``ref.dcm(other)`` when one of the two hangs from the other, two or more steps apart (None otherwise)."""
    path = _hangs_from(ref, other)
    if path is None:
        back = _hangs_from(other, ref)
        if back is None or len(back) < 2:
            return None
        return _down(other, ref, back).T
    return None if len(path) < 2 else _down(ref, other, path)


def _down(ref: ReferenceFrame, other: ReferenceFrame, path: list):
    parent, axis_col, angle = ref._rigidkin_link
    total = angle
    for frame in path[1:]:                            # a run of rotations about the same axis: one rotation
        u, a = frame._rigidkin_link[1:]
        if axis_col is None or u is None or u != axis_col:
            return ref.dcm(parent) * parent.dcm(other)   # the parent's DCM to ``other`` is found the same way
        total = total + a
    return _axis_dcm(axis_col, total)


def remember(ref: ReferenceFrame, parent: ReferenceFrame, axis_col: sp.Matrix | None, angle) -> None:
    """Note that ``ref`` was just oriented from ``parent`` (about the unit axis ``axis_col``, parent
    components, by ``angle``; None for another kind of rotation): its DCM relative to any frame it
    hangs from is then found along the chain, in closed form where the chain turns about one axis."""
    ref._rigidkin_link = (parent, axis_col, angle)
    for frame in (ref, parent):
        if not isinstance(frame._dcm_cache, _ChainCache):
            frame._dcm_cache = _ChainCache(frame, frame._dcm_cache)


def depth(ref: ReferenceFrame) -> int:
    """How many frames ``ref`` hangs from (0 for the inertial frame)."""
    n = 0
    while getattr(ref, "_rigidkin_link", None) is not None:
        ref, n = ref._rigidkin_link[0], n + 1
    return n


def shallow(vec: Vector, inertial: ReferenceFrame) -> Vector:
    """``vec`` with its components along frames more than ``MAX_CHAIN_DEPTH`` deep written in ``inertial``.

    A point's offset along the last link of a long chain (``l*A59.x``) would otherwise carry the whole
    chain into every velocity and cross product; with the closed-form DCMs above its components in the
    inertial frame are short (cos(θ₁ + ... + θ₆₀)).  Vectors on shallow frames are kept as written.
    """
    if not any(depth(frame) > MAX_CHAIN_DEPTH for _m, frame in vec.args):
        return vec
    out = Vector(0)
    for measure, frame in vec.args:
        part = Vector([(measure, frame)])
        out += part.express(inertial) if depth(frame) > MAX_CHAIN_DEPTH else part
    return out
