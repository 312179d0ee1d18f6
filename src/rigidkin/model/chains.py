"""Direction cosines along chains of frames, kept short.

sympy finds the direction cosine matrix (DCM) of a frame relative to a distant one by multiplying the
matrices along the path between them, without simplifying: for n frames each turned about the same
axis (a planar chain of links) the entries of the product have 2ⁿ⁻¹ terms, and the kinematics of a
60-link chain never finishes.  :func:`remember` is called when a frame is oriented and stores, in
sympy's own cache, the DCM of the new frame relative to every frame it hangs from:

* in closed form, a rotation about the common axis by the sum of the angles, along a run of frames
  turned about the same axis (cos(θ₁ + θ₂) instead of cos θ₁ cos θ₂ − sin θ₁ sin θ₂);
* otherwise as the product of the new frame's own DCM and its parent's stored one (one product per
  pair of frames, not one per step of the path).

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


def remember(ref: ReferenceFrame, parent: ReferenceFrame, axis_col: sp.Matrix | None, angle) -> None:
    """Store the DCM of ``ref`` (just oriented from ``parent``; about ``axis_col`` by ``angle``, or
    None for another kind of rotation) relative to every frame ``parent`` hangs from."""
    ref._rigidkin_link = (parent, axis_col, angle)
    own = ref.dcm(parent)
    total, same_axis = angle, axis_col is not None
    child = parent
    while getattr(child, "_rigidkin_link", None) is not None:
        up, u, a = child._rigidkin_link
        same_axis = same_axis and u is not None and u == axis_col
        if same_axis:
            total = total + a
        dcm = _axis_dcm(axis_col, total) if same_axis else own * parent.dcm(up)
        ref._dcm_cache[up] = dcm
        up._dcm_cache[ref] = dcm.T
        child = up


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
