"""Rotational springs and dampers between two bodies (or a body and the ground), about an axis n.

A rotational spring of stiffness k exerts on ``body_a`` the torque −k (θ_rel − θ0) n and on ``body_b``
the opposite one, θ_rel the angle of ``body_a`` relative to ``body_b`` about n (counter-clockwise about
n); its potential is k (θ_rel − θ0)²/2.  A rotational damper of coefficient c exerts −c ω_rel n on
``body_a`` (and the opposite on ``body_b``), ω_rel = (ω_a − ω_b)·n.

θ_rel is read from the frames: when each body's frame is reached from the ground by rotations about
axes parallel to n (a planar problem, a hinge), θ_rel is the sum of those angles (with the sign of
each axis along n) for ``body_a`` minus that for ``body_b``.  Otherwise give it (``angle=``).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector

from ..base import algebra
from ..base.errors import ModelError
from .checks import NONNEGATIVE
from .loads import Application, Load, TorsionalSpring
from .values import _expr


@dataclass(eq=False)
class RotationalSpring(TorsionalSpring):
    """Torque −k (θ_rel − θ0) n on ``body_a`` and its opposite on ``body_b`` (None: the ground): a torsional
    spring whose angle θ_rel the system reads from the frames (see the module's docstring)."""

    kind = "rotational spring"


@dataclass(eq=False)
class RotationalDamper(Load):
    """Torque −c ω_rel n on ``body_a`` and its opposite on ``body_b``, ω_rel = (ω_a − ω_b)·n."""

    body_a: object = None
    body_b: object | None = None
    coefficient: sp.Expr = None
    axis: Vector = None

    kind = "rotational damper"

    def relative_rate(self, kin) -> sp.Expr:
        w = kin.omega_of(self.body_a) - (kin.omega_of(self.body_b) if self.body_b is not None else Vector(0))
        return kin.simplify_expr(w.dot(self.axis))

    def applications(self, kin):
        torque = -self.coefficient * self.relative_rate(kin) * self.axis
        out = [Application(self.body_a, None, torque, f"rotational damper {self.name} on {self.body_a.name}",
                           self.name)]
        if self.body_b is not None:
            out.append(Application(self.body_b, None, -torque, f"rotational damper {self.name} on {self.body_b.name}",
                                   self.name))
        return out


def frame_angle(frame, axis: Vector):
    """The angle of ``frame`` from the ground about the unit ``axis``: the sum of its chain's single-axis
    angles (each with the sign of its axis along ``axis``), or None when a link turns about another axis."""
    total = sp.Integer(0)
    fr = frame
    while fr.parent is not None:
        if fr.angle is None or fr.axis is None:
            return None
        along = sp.sympify(fr.axis.dot(axis))
        cross = fr.axis.cross(axis)
        if cross != Vector(0) and not all(algebra.is_zero(c) for c in cross.to_matrix(fr.parent.ref)):
            if not algebra.is_zero(fr.angle):
                return None
            fr = fr.parent
            continue
        total += algebra.readable(along) * fr.angle          # ±1: the axis along n or against it
        fr = fr.parent
    return total


class RotationalLoadMethods:
    """Rotational springs and dampers (mixed into System)."""

    def _rotational_axis(self, axis, where) -> Vector:
        n = self.inertial.z if axis is None else self._check_vector(axis, where)
        if n == Vector(0) or not algebra.is_zero(n.dot(n) - 1):
            raise ModelError(f"the axis {n} is not a unit vector.", where=where, hint="Give a basis vector, e.g. B.z.")
        return n

    def rotational_spring(self, name: str, body_a, stiffness, body_b=None, natural_angle=0, axis: Vector | None = None,
                          angle=None, description: str = "") -> RotationalSpring:
        """A rotational spring: torque −k (θ_rel − θ0) about ``axis`` (default Ez) on ``body_a``, the opposite on
        ``body_b`` (None: the ground); θ_rel from the frames (see :mod:`rigidkin.model.rotational_loads`) or
        ``angle``."""
        where = f"rotational spring {name}"
        a = self._check_body(body_a, where)
        b = self._check_body(body_b, where, True)
        n = self._rotational_axis(axis, where)
        if angle is None:
            ta = frame_angle(a.frame, n)
            tb = frame_angle(b.frame, n) if b is not None else sp.Integer(0)
            if ta is None or tb is None:
                raise ModelError("the angle between the bodies about this axis cannot be read from their frames (a "
                                 "frame on the way turns about another axis).", where=where,
                                 hint="Give the relative angle: angle = (an expression of the coordinates).")
            rel = sp.simplify(ta - tb)
        else:
            rel = _expr(angle, where)
        if b is a:
            raise ModelError("a rotational spring joins two different bodies.", where=where)
        return self._add_load(RotationalSpring(
            name, body_a=a, body_b=b, stiffness=self._value(stiffness, where, NONNEGATIVE, "stiffness"), angle=rel,
            natural_angle=_expr(natural_angle, where), axis=n, description=description))

    def rotational_damper(self, name: str, body_a, coefficient, body_b=None, axis: Vector | None = None,
                          description: str = "") -> RotationalDamper:
        """A rotational damper: torque −c ω_rel about ``axis`` (default Ez) on ``body_a``, ω_rel = (ω_a − ω_b)·n,
        and the opposite on ``body_b`` (None: the ground)."""
        where = f"rotational damper {name}"
        a = self._check_body(body_a, where)
        b = self._check_body(body_b, where, True)
        if b is a:
            raise ModelError("a rotational damper joins two different bodies.", where=where)
        return self._add_load(RotationalDamper(
            name, body_a=a, body_b=b, coefficient=self._value(coefficient, where, NONNEGATIVE, "damping coefficient"),
            axis=self._rotational_axis(axis, where), description=description))
