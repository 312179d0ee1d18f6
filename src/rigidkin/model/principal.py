"""Principal axes and principal moments of inertia of a rigid body.

The inertia dyadic of a body about its mass centre (or about any point fixed in it, by the
parallel-axis theorem) has, in the body's frame, the matrix of moments and products of inertia

    [I] = [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]],   Ixy = −∫ x y dm, ...

It is symmetric, so three orthogonal principal axes exist along which it is diagonal:
[I] e = λ e.  ``principal_axes`` finds them in closed form when at most one product of inertia is
nonzero (a body with a plane of symmetry: the two in-plane axes turn by α, tan 2α = 2 Ixz/(Ixx − Izz)),
and numerically (numpy's symmetric eigensolver) once parameters have values otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp
from sympy.physics.vector import Dyadic, Vector

from ..base import algebra
from ..base.errors import ModelError
from .frames import Frame
from .shapes import parallel_axis


@dataclass(frozen=True)
class PrincipalAxes:
    """Principal moments (``moments``) and unit principal axes (``axes``, right-handed) in ``frame``."""

    moments: tuple
    axes: tuple
    frame: Frame

    @property
    def rotation(self) -> sp.Matrix:
        """The matrix whose columns are the principal axes' components in the frame's basis."""
        return sp.Matrix.hstack(*[a.to_matrix(self.frame.ref) for a in self.axes])

    def dyadic(self) -> Dyadic:
        """Σ λ_i e_i ⊗ e_i: the inertia dyadic rebuilt from the principal values (a check)."""
        return sum((m * a.outer(a) for m, a in zip(self.moments, self.axes)), Dyadic(0))


def inertia_matrix(inertia: Dyadic, frame: Frame) -> sp.Matrix:
    """Moments and products of inertia of a dyadic in the basis of ``frame`` (tensor components)."""
    return inertia.to_matrix(frame.ref)


def body_inertia(body, about=None) -> Dyadic:
    """The inertia dyadic of ``body`` about its mass centre, or about the point ``about`` fixed in it."""
    I = body.inertia
    if about is None or about is body.centre:
        return I
    r = about.position() - body.centre.position()
    if any(not algebra.is_zero(c) for c in r.dt(body.frame.ref).to_matrix(body.frame.ref)):
        raise ModelError(f"point {about.name} moves relative to body {body.name}, so the body's inertia about "
                         "it is not constant.", where=f"body {body.name}",
                         hint="Give a point fixed in the body.")
    return I + parallel_axis(body.mass, r, body.frame)


def principal_axes(body=None, *, inertia: Dyadic | None = None, frame: Frame | None = None, about=None,
                   values: dict | None = None) -> PrincipalAxes:
    """Principal moments and axes of ``body`` (about its mass centre or the point ``about``), or of a dyadic.

    ``values`` maps parameter symbols to numbers for the numeric route (a body with two or more
    products of inertia); by default the system's declared parameter values are not known here, so
    pass them (``system.parameter_values()``).  Moments come in ascending order when they can be
    compared; axes are unit vectors in ``frame`` (the body's frame by default).
    """
    if inertia is None:
        if body is None:
            raise ModelError("give a body or an inertia dyadic.", where="principal axes")
        inertia = body_inertia(body, about)
        frame = frame or body.frame
    if frame is None:
        raise ModelError("an inertia dyadic needs the frame to resolve it in.", where="principal axes")
    M = inertia_matrix(inertia, frame).applyfunc(sp.simplify)
    e = (frame.x, frame.y, frame.z)
    off = [(i, j) for i, j in ((0, 1), (1, 2), (0, 2)) if M[i, j] != 0]
    if not off:
        return _ordered([M[i, i] for i in range(3)], list(e), frame, values)
    if len(off) == 1:
        i, j = off[0]
        k = 3 - i - j
        a, b, c = M[i, i], M[j, j], M[i, j]
        D = sp.sqrt((a - b) ** 2 + 4 * c**2)
        alpha = sp.atan2(2 * c, a - b) / 2      # the axis with the larger moment, turned from e_i towards e_j
        big = sp.cos(alpha) * e[i] + sp.sin(alpha) * e[j]
        small = -sp.sin(alpha) * e[i] + sp.cos(alpha) * e[j]
        moments = [(a + b) / 2 + D / 2, (a + b) / 2 - D / 2, M[k, k]]
        return _ordered(moments, [big, small, e[k]], frame, values)
    num = M.xreplace(values or {})
    if num.free_symbols:
        raise ModelError("this inertia has two or more products of inertia and the parameters "
                         f"{', '.join(sorted(map(str, num.free_symbols)))} have no values, so its principal "
                         "axes have no closed form here.", where="principal axes",
                         hint="Pass values={symbol: number} (e.g. system.parameter_values()).")
    lam, vec = np.linalg.eigh(np.array(num.evalf(), dtype=float))
    axes = [sum((float(vec[r, c]) * e[r] for r in range(3)), Vector(0)) for c in range(3)]
    if np.linalg.det(vec) < 0:
        axes[2] = -axes[2]
    return PrincipalAxes(tuple(sp.Float(v) for v in lam), tuple(axes), frame)


def _ordered(moments, axes, frame, values) -> PrincipalAxes:
    """Sort by moment where the moments can be compared (numbers, or numbers once ``values`` are put in)."""
    try:
        keys = [float(sp.sympify(m).xreplace(values or {})) for m in moments]
    except TypeError:
        keys = None
    if keys is not None:
        order = sorted(range(3), key=lambda n: keys[n])
        moments, axes = [moments[n] for n in order], [axes[n] for n in order]
    # right-handed: e3 = e1 × e2
    triple = axes[0].cross(axes[1]).dot(axes[2])
    if not algebra.is_zero(triple - 1):
        axes[2] = -axes[2]
    return PrincipalAxes(tuple(moments), tuple(axes), frame)
