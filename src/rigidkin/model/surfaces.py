"""Surfaces a body can touch: a line (a plane, in 3D) and a circle (a sphere, in 3D).

A surface is fixed in the ground or in another body.  It gives, at a body's profile centre C, the
unit normal ``n`` that points from the surface into the body, and the gap between the profile and
the surface (zero while they touch, positive when they are apart).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector

from .points import Point


@dataclass(eq=False)
class Line:
    """A straight surface through ``point`` with unit ``normal`` pointing to the body's side.

    In a planar problem it is a line in the plane of motion; in 3D the plane with that normal.
    """

    point: Point
    normal: Vector
    body: object | None = None
    name: str = ""

    kind = "line"

    @property
    def anchor(self) -> Point:
        """The point the surface moves with when it is not fixed in a body (usually fixed)."""
        return self.point

    def normal_at(self, centre_pos: Vector, kin) -> Vector:
        return self.normal

    def gap(self, centre_pos: Vector, radius: sp.Expr, kin) -> sp.Expr:
        return (centre_pos - kin.position(self.point)).dot(self.normal) - radius

    def velocity_at(self, location: Vector, kin) -> Vector:
        """Velocity of the line's material point at ``location`` when it is not fixed in a body: it moves
        with its point and turns as its normal turns (ω = n × ṅ, a rotation in the plane of motion)."""
        v = kin.velocity(self.point)
        ndot = self.normal.dt(kin.F.ref)
        if ndot != Vector(0) and not kin.is_zero_vector(ndot):
            v = v + self.normal.cross(ndot).cross(location - kin.position(self.point))
        return v


Plane = Line


@dataclass(eq=False)
class Circle:
    """A circle (a sphere in 3D) of centre ``centre`` and ``radius``; the body is outside or inside."""

    centre: Point
    radius: sp.Expr
    inside: bool = False
    body: object | None = None
    name: str = ""
    normal_hint: Vector | None = None

    kind = "circle"

    @property
    def anchor(self) -> Point:
        return self.centre

    def _distance(self, centre_pos: Vector, kin) -> tuple[Vector, sp.Expr]:
        d = centre_pos - kin.position(self.centre)
        return d, kin.magnitude(d)

    def velocity_at(self, location: Vector, kin) -> Vector:
        """A circle not fixed in a body moves with its centre (it does not turn)."""
        return kin.velocity(self.centre)

    def normal_at(self, centre_pos: Vector, kin) -> Vector:
        if self.normal_hint is not None:
            return self.normal_hint
        d, dist = self._distance(centre_pos, kin)
        u = kin.simplify_vector(d / dist)
        return -u if self.inside else u

    def gap(self, centre_pos: Vector, radius: sp.Expr, kin) -> sp.Expr:
        _, dist = self._distance(centre_pos, kin)
        if self.inside:
            return self.radius - radius - dist
        return dist - self.radius - radius


Sphere = Circle
