"""The load-building methods of :class:`rigidkin.System` (gravity, forces, springs, dampers, friction, impulses).
"""

from __future__ import annotations

from sympy.physics.vector import Vector, dynamicsymbols

from ..base.errors import ModelError
from . import loads as L
from .checks import NONNEGATIVE
from .inputs import InputMethods
from .points import Point
from .rotational_loads import RotationalLoadMethods
from .values import _expr

t = dynamicsymbols._t


class LoadMethods(InputMethods, RotationalLoadMethods):
    """Loads, each checked as it is added (mixed into System); inputs u(t) from :mod:`rigidkin.model.inputs`;
    rotational springs and dampers from :mod:`rigidkin.model.rotational_loads`."""

    # loads -------------------------------------------------------------------------------------
    def _add_load(self, load):
        self._claim(load.name, "load", "load")
        self.loads[load.name] = load
        return load

    def _body_of(self, point: Point, body, where):
        if body is not None:
            return self._check_body(body, where)
        if point.body is None:
            raise ModelError(f"point {point.name} is not fixed in a body, so it is not clear which body the "
                             "load acts on.", where=where, hint="Give the body explicitly (body=...).")
        return point.body

    def gravity(self, g, direction: Vector | None = None, name: str = "gravity") -> None:
        """Uniform gravity of magnitude ``g`` along the unit vector ``direction`` (default −Ey)."""
        d = -self.inertial.y if direction is None else self._check_vector(direction, f"load {name}")
        self._add_load(L.Gravity(name, g=self._value(g, f"load {name}", NONNEGATIVE, "gravitational acceleration"),
                                 direction=d))

    def force(self, name: str, point: Point | str, vector: Vector, body=None, description: str = "",
              on=None) -> L.Force:
        """A known force at ``point`` (of ``body``; default: the body the point is fixed in).

        At a point that moves over the body (``on=body``, the same as ``body=``), the force acts on the
        material point of the body momentarily there; its power uses that material point's velocity.
        """
        where = f"force {name}"
        p = self._check_point(point, where)
        return self._add_load(L.Force(name, body=self._body_of(p, on if on is not None else body, where), point=p,
                                      vector=self._check_vector(vector, where), description=description))

    def torque(self, name: str, body, vector: Vector, reaction_body=None, description: str = "") -> L.Torque:
        """A known torque on ``body`` (and its reaction on ``reaction_body``)."""
        where = f"torque {name}"
        return self._add_load(L.Torque(name, body=self._check_body(body, where),
                                       vector=self._check_vector(vector, where),
                                       reaction_body=self._check_body(reaction_body, where, True),
                                       description=description))

    def spring(self, name: str, point_a: Point | str, point_b: Point | str, stiffness, natural_length=0,
               body_a=None, body_b=None, description: str = "", on_a=None, on_b=None) -> L.Spring:
        """A linear spring between two points; ends not fixed in a body are anchored in the ground.

        ``on_a``/``on_b``: the body whose material point momentarily at ``point_a``/``point_b`` the
        spring pulls (for an end that moves over the body, such as the top of a rolling wheel).
        """
        where = f"spring {name}"
        pa, pb = self._check_point(point_a, where), self._check_point(point_b, where)
        ba = self._body_of(pa, on_a if on_a is not None else body_a, where)
        bb = self._check_body(on_b if on_b is not None else body_b, where, True) \
            if (body_b is not None or on_b is not None) else pb.body
        ref = self.inertial.ref
        ma = L.check_end(name, "spring", pa, ba, on_a is not None, ref)
        mb = L.check_end(name, "spring", pb, bb, on_b is not None, ref)
        return self._add_load(L.Spring(name, point_a=pa, body_a=ba, point_b=pb, body_b=bb, moving_a=ma, moving_b=mb,
                                       stiffness=self._value(stiffness, where, NONNEGATIVE, "stiffness"),
                                       natural_length=self._value(natural_length, where, NONNEGATIVE, "natural length"),
                                       description=description))

    def torsional_spring(self, name: str, body_a, stiffness, angle, natural_angle=0, body_b=None,
                         axis: Vector | None = None, description: str = "") -> L.TorsionalSpring:
        """A torsional spring: torque −K (angle − angle0) about ``axis`` (default Ez) on ``body_a``."""
        where = f"torsional spring {name}"
        return self._add_load(L.TorsionalSpring(
            name, body_a=self._check_body(body_a, where), body_b=self._check_body(body_b, where, True),
            stiffness=self._value(stiffness, where, NONNEGATIVE, "stiffness"), angle=_expr(angle, where),
            natural_angle=_expr(natural_angle, where),
            axis=self.inertial.z if axis is None else self._check_vector(axis, where), description=description))

    def damper(self, name: str, point_a: Point | str, law, along: Vector | None = None,
               point_b: Point | str | None = None, body_a=None, body_b=None, description: str = "",
               on_a=None, on_b=None) -> L.Damper:
        """A damper of any force law f(v) (``law`` in the symbol ``rigidkin.v`` or a callable).

        ``on_a``/``on_b`` as for :meth:`spring`: v then uses the material velocity of that body there.
        """
        where = f"damper {name}"
        pa = self._check_point(point_a, where)
        pb = self._check_point(point_b, where) if point_b is not None else None
        ob = on_b if on_b is not None else body_b
        bb = self._check_body(ob, where, True) if ob is not None else (pb.body if pb else None)
        ba = self._body_of(pa, on_a if on_a is not None else body_a, where)
        ref = self.inertial.ref
        ma = L.check_end(name, "damper", pa, ba, on_a is not None, ref)
        mb = pb is not None and L.check_end(name, "damper", pb, bb, on_b is not None, ref)
        return self._add_load(L.Damper(name, point_a=pa, body_a=ba, law=law,
                                       along=None if along is None else self._check_vector(along, where),
                                       point_b=pb, body_b=bb, moving_a=ma, moving_b=mb, description=description))

    def impulse(self, name: str, point: Point | str, vector: Vector, body=None, description: str = "",
                on=None) -> L.Impulse:
        """An impulse F̂ applied at ``point`` (used by the impulse–momentum law); ``on`` as for :meth:`force`."""
        where = f"impulse {name}"
        p = self._check_point(point, where)
        return self._add_load(L.Impulse(name, body=self._body_of(p, on if on is not None else body, where), point=p,
                                        vector=self._check_vector(vector, where), description=description))

    def friction(self, name: str, body, centre: Point | str, normal: Vector, mu, normal_force, radius=0,
                 against_body=None, against_point: Point | str | None = None,
                 description: str = "") -> L.SlidingFriction:
        """Coulomb sliding friction at a contact whose normal force is known (or a named reaction)."""
        where = f"friction {name}"
        return self._add_load(L.SlidingFriction(
            name, body=self._check_body(body, where), centre=self._check_point(centre, where),
            radius=self._value(radius, where, NONNEGATIVE, "radius"), normal=self._check_vector(normal, where),
            mu=self._value(mu, where, NONNEGATIVE, "friction coefficient µ"),
            normal_force=_expr(normal_force, where), against_body=self._check_body(against_body, where, True),
            against_point=self._check_point(against_point, where) if against_point is not None else None,
            description=description))
