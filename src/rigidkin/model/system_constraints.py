"""The constraint-building methods of :class:`rigidkin.System` (pins, contacts, collars, cables, ropes).
"""

from __future__ import annotations

from sympy.physics.vector import Vector, dynamicsymbols

from ..base.errors import ModelError
from . import constraints as C
from .checks import NONNEGATIVE, POSITIVE
from .frames import Frame
from .points import Point
from .profiles import arc_for
from .rolling3d import DiskContact
from .ropes import build_rope
from .surfaces import Circle, Line
from .velocity_constraints import VelocityConstraintMethods

t = dynamicsymbols._t


class ConstraintMethods(VelocityConstraintMethods):
    """Pins, contacts, collars, cables and ropes, each checked as it is added (mixed into System); knife edges
    and velocity constraints from :mod:`rigidkin.model.velocity_constraints`."""

    # constraints --------------------------------------------------------------------------------
    def _add_constraint(self, c):
        self.constraints[c.name] = c
        return c

    def pin(self, name: str, point: Point | str, body_a, body_b=None, point_b=None, basis: Frame | None = None,
            axis: str | None = None, prefix: str | None = None, description: str = "") -> C.Pin:
        """Hold ``point`` of ``body_a`` at ``point_b`` of ``body_b`` (fixed in the ground if None)."""
        self._claim(name, "constraint", "constraint")
        where = f"pin {name}"
        p = self._check_point(point, where)
        a = self._check_body(body_a, where)
        b = self._check_body(body_b, where, allow_none=True)
        pb = self._check_point(point_b, where) if point_b is not None else None
        if basis is not None:
            self._check_frame(basis, where)
        con = C.Pin(name, point=p, body_a=a, body_b=b, point_b=pb, basis_frame=basis, axis=axis, prefix=prefix,
                    description=description)
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"pin {name}")
        return self._add_constraint(con)

    def contact(self, name: str, body, surface, centre: Point | str | None = None, radius=0,
                friction="smooth", unilateral: bool = True, normal_name: str | None = None,
                friction_name: str | None = None, description: str = "", arc=None) -> C.Contact:
        """A contact of ``body`` with ``surface`` through a profile (point, circle or sphere of ``radius``).

        ``arc``: the part of the profile that exists, ``(toward, half_angle)`` with ``toward`` fixed in the
        body (a half cylinder's curved face: its ``toward``, π/2 — the default for half shapes touching by
        their curved face); ``False``: the whole circle.  Leaving the arc ends the contact's validity.

        ``friction``: ``"smooth"``, ``"rolling"`` (no slip), or a coefficient µ (Coulomb friction), or
        ``{"static": µs, "kinetic": µk}`` (sticks while |F| ≤ µs N, slides with µk N).
        """
        self._claim(name, "constraint", "constraint")
        where = f"contact {name}"
        b = self._check_body(body, where)
        c = self._check_point(centre, where) if centre is not None else b.centre
        if not isinstance(surface, (Line, Circle)):
            raise ModelError("surface must be a line/plane or circle/sphere (System.line, System.circle).",
                             where=where)
        fr = self._friction(friction, where)
        rad = self._value(radius, where, NONNEGATIVE, "radius")
        con = C.Contact(name, body=b, centre=c, radius=rad,
                        surface=surface, friction=fr,
                        unilateral=unilateral, normal_name=normal_name, friction_name=friction_name,
                        description=description, arc=arc_for(arc, b, c, rad, where))
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"contact {name}")
        return self._add_constraint(con)

    def disk_contact(self, name: str, body, surface, axis: Vector, radius, centre: Point | str | None = None,
                     friction="smooth", unilateral: bool = True, normal_name: str | None = None,
                     friction_name: str | None = None, description: str = ""):
        """A thin disk (wheel, coin) of ``radius`` and unit ``axis`` (fixed in ``body``) touching a plane
        at its rim, in 3D: see :mod:`rigidkin.model.rolling3d`."""

        self._claim(name, "constraint", "constraint")
        where = f"contact {name}"
        b = self._check_body(body, where)
        c = self._check_point(centre, where) if centre is not None else b.centre
        con = DiskContact(name, body=b, centre=c, radius=self._value(radius, where, POSITIVE, "radius"),
                          surface=surface, friction=self._friction(friction, where), unilateral=unilateral,
                          normal_name=normal_name,
                          friction_name=friction_name, description=description,
                          axis=self._check_vector(axis, where))
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"contact {name}")
        return self._add_constraint(con)

    def collar(self, name: str, body, along: Vector, through: Point | str | None = None,
               point: Point | str | None = None, track_body=None, friction="smooth",
               normal_name: str | None = None, couple_name: str | None = None, description: str = "") -> C.Collar:
        """A collar: ``body`` slides along a straight track (through ``through``, direction ``along``)."""
        self._claim(name, "constraint", "constraint")
        where = f"collar {name}"
        b = self._check_body(body, where)
        p = self._check_point(point, where) if point is not None else b.reference
        thr = self._check_point(through, where) if through is not None else self.origin
        con = C.Collar(name, body=b, point=p, through=thr, along=self._check_vector(along, where),
                       track_body=self._check_body(track_body, where, True), friction=self._friction(friction, where),
                       normal_name=normal_name, couple_name=couple_name, description=description)
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"collar {name}")
        return self._add_constraint(con)

    def cable(self, name: str, points, length, bodies=None, tension_name: str | None = None,
              description: str = "") -> C.Cable:
        """An inextensible cable through ``points`` (ends and pulleys), taut with tension T ≥ 0.

        ``bodies`` gives the body of each point (default: the body each point is fixed in, or the
        ground); ``length`` is the cable's length between its ends.
        """
        self._claim(name, "constraint", "constraint")
        where = f"cable {name}"
        pts = tuple(self._check_point(p, where) for p in points)
        if len(pts) < 2:
            raise ModelError("a cable needs at least its two ends.", where=where)
        if bodies is None:
            bs = tuple(p.body for p in pts)
        else:
            if len(bodies) != len(pts):
                raise ModelError(f"give one body (or None) for each of the {len(pts)} points.", where=where)
            bs = tuple(self._check_body(b, where, allow_none=True) for b in bodies)
        con = C.Cable(name, points=pts, bodies=bs, length=self._value(length, where, POSITIVE, "length"),
                      tension_name=tension_name,
                      description=description)
        self._claim(con.T.name, "reaction", owner=f"cable {name}")
        return self._add_constraint(con)

    def rope(self, name: str, path, tensions=None, description: str = ""):
        """A rope over pulleys with inertia that it does not slip on: ``path`` = end, Wrap(pulley, radius,
        "cw"|"ccw"), …, end (see :mod:`rigidkin.model.ropes`); one tension per straight segment, each ≥ 0."""

        self._claim(name, "constraint", "constraint")
        con = build_rope(self, name, path, tensions, description)
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"rope {name}")
        return self._add_constraint(con)

    def restitution(self, contact, e) -> None:
        """The coefficient of restitution e of ``contact``'s impacts (Newton's law: the normal speed after an
        impact is −e times the speed before), 0 ≤ e ≤ 1; a simulation uses it unless told otherwise.  A rope's or
        cable's e is that of its jerk as it re-tightens (default 0: it jerks taut)."""
        where = f"restitution of {contact}"
        con = self.constraints.get(contact if isinstance(contact, str) else getattr(contact, "name", None))
        if con is None or getattr(con, "kind", "") not in ("contact", "rope", "cable"):
            known = [n for n, c in self.constraints.items() if getattr(c, "kind", "") in ("contact", "rope", "cable")]
            raise ModelError(f"{contact!r} is not a contact, rope or cable of this system.", where=where,
                             hint=f"Contacts: {', '.join(known) or 'none'}.")
        value = self._value(e, where, NONNEGATIVE, "coefficient of restitution")
        number = float(value.xreplace(self.parameter_values())) if value.free_symbols else float(value)
        if not 0.0 <= number <= 1.0:
            raise ModelError(f"the coefficient of restitution {value} = {number:g} is not in [0, 1].", where=where)
        if getattr(self, "_restitutions", None) is None:
            self._restitutions = {}
        self._restitutions[con.name] = number

    @property
    def restitutions(self) -> dict:
        """Contact name → its declared coefficient of restitution."""
        return dict(getattr(self, "_restitutions", None) or {})
