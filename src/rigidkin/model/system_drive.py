"""Driven bodies and prescribed coordinates for :class:`rigidkin.System`: motions given as laws of time
(see ``model.drives`` and ``model.prescribed_coordinates``)."""

from __future__ import annotations

from dataclasses import replace

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.algebra import functions_of_time
from ..base.errors import ModelError
from .bodies import Body
from .drives import Drive, check_prescribed
from .frames import Frame
from .points import Point
from .prescribed_coordinates import PrescribedCoordinate
from .shapes import Massless, Shape
from .values import _expr

t = dynamicsymbols._t


class DriveMethods:
    """``System.drive`` (a shaft, turntable or support whose motion is prescribed) and ``System.prescribe`` (a
    coordinate given as a law of t), mixed into System."""

    def drive(self, name: str, frame: Frame, at: Point | str | None = None, shape: Shape | None = None,
              basis: Frame | None = None, torque: str | None = None, force: str | None = None,
              description: str = "", joint: Point | str | None = None, carrier=None) -> Body:
        """A driven body ``name``: its frame and its point ``at`` (default the origin) move by given laws of t.

        Write the law in the frame's angle (``s.frame("S", angle=Omega*t, axis="y")``) and in the point's
        offset (``s.point("P", offset=A*sp.cos(omega*t)*F.y)``); ``shape`` is massless by default (a
        shaft, a turntable, a support).  Pins, contacts and collars attach other bodies to it like to any
        body.  The drive brings, as reactions, the force it applies at ``at`` (``F_<name>x, y, z`` along
        ``basis``, the inertial frame by default; prefix ``force``) and the torque it applies: about the
        axis the frame turns about the drive torque ``T_<name>`` (or ``torque``), positive in the sense
        of the frame's angle — "the torque needed to turn the shaft" — and the bearing torques
        ``M_<name>x ...`` about the frame's other axes.  The drive acts at ``joint`` (default ``at``): give the
        motor's joint when the shape is placed elsewhere (a driven arm placed at its mass centre, turned
        about its end), so that ``T_<name>`` is the torque at the joint.  ``carrier``: the body the drive is
        mounted on (a rotor spun by a motor in a free gimbal, an elbow turned by a law on a free upper arm):
        the laws are then relative to it — the frame turned from the carrier's frame by a law of t, the
        joint a point of the carrier — and the carrier takes the opposite efforts.  Returns the body.
        """
        where = f"driven body {name}"
        self._check_frame(frame, where)
        if frame is self.inertial and at is None:
            raise ModelError("a driven body with the inertial frame at the origin does not move: it is the ground.",
                             where=where, hint="Give the point whose motion is prescribed (at=...), or a frame "
                                               "turned by a law of t.")
        p = self._check_point(at, where) if at is not None else self.origin
        if basis is not None:
            self._check_frame(basis, where)
        j = self._check_point(joint, where) if joint is not None else p
        c = self._check_body(carrier, where, allow_none=True)
        if c is None:                       # relative to the ground: checked here; on a carrier: when solved
            check_prescribed(self, frame, p, where)
            check_prescribed(self, frame, j, where)
        if c is not None and p.body is c:       # mounted at a point of its carrier: its own point there
            p = self.point(f"{p.name}_{name}", p, description=f"the point {p.name} of {c.name}, carried by {name}")
        if p.body is not None:
            raise ModelError(f"the point {p.name} is already fixed in body {p.body.name}.", where=where,
                             hint="Give the driven body a point of its own (a point located by a law of t).")
        body = self.body(name, shape if shape is not None else Massless(), frame, p, description=description)
        self._claim(name, "constraint", "constraint", owner=f"drive of {name}")
        con = Drive(name, body=body, point=j, basis_frame=basis, force_prefix=force, torque_name=torque, carrier=c,
                    description=description)
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"drive of {name}")
        self.constraints[name] = con
        return body

    def prescribe(self, coordinate, law=None, rate=None, effort: str | None = None, on=None, against=None,
                  description: str = "") -> PrescribedCoordinate:
        """Drive the declared ``coordinate`` by a law of t: q = ``law`` (or q̇ = ``rate`` when only its rate is given).

        E.g. a crank turned at Ω: ``s.prescribe(phi, Omega*t)``; a cart shaken by an actuator:
        ``s.prescribe(x, A*sp.sin(omega*t))``.  The equations of motion are written for the free coordinates;
        the effort the actuator needs, ``Q_<coordinate>`` (or ``effort``), a torque for an angle and a force for
        a length, positive in the sense of the coordinate, is a reaction like any other.  It acts on the body the
        coordinate moves (``on``) and, opposite, on the body across its joint (``against``; the ground when there
        is none); both are found from where the coordinate is used when not given.  The constraint is named
        ``drive_<coordinate>``.  A generalised speed (an angular-velocity component ``w``, System.angular_speeds or a
        quaternion frame) is prescribed the same way, ``s.prescribe(w, Omega)``: w = law, its effort the torque about
        that axis of the frame.
        """
        info = speed = None
        for c in self._coordinates.values():
            if c.symbol == coordinate or c.name == coordinate:
                info = c
        for group in self.speed_groups.values():     # a generalised speed w: its quasi-coordinate π, π̇ = w
            for i, (n, w) in enumerate(zip(group.names, group.speeds)):
                if w == coordinate or n == coordinate or (info is not None and info.symbol == group.quasi[i]):
                    info, speed = self._coordinates[f"{n}_int"], (group, i)
        name = getattr(getattr(coordinate, "func", None), "__name__", str(coordinate))
        where = f"prescribed coordinate {name}"
        if info is None:
            raise ModelError(f"{coordinate!r} is not a coordinate or a speed of this system.", where=where,
                             hint="Declare it with s.coordinate(...) first, then prescribe the returned q(t).")
        if speed is not None:               # a speed's law is the speed itself: w = law
            if law is not None and rate is not None:
                raise ModelError("give the law of the speed once.", where=where)
            law, rate = None, law if law is not None else rate
        if (law is None) == (rate is None):
            raise ModelError("give the law of the coordinate or the law of its rate, one of them.", where=where,
                             hint=f"s.prescribe({info.name}, Omega*t) or s.prescribe({info.name}, rate=Omega).")
        given = _expr(law if law is not None else rate, where)
        coords = set(self.coordinates)
        bad = functions_of_time(given) & coords
        if bad or given.has(*[q.diff(t) for q in coords]):
            raise ModelError(f"the law {given} involves the coordinates: a prescribed motion is a function of t and "
                             "the parameters alone.", where=where)
        q = info.symbol
        f = sp.sympify(given) if law is not None else None
        g = sp.sympify(sp.diff(given, t) if law is not None else given)
        label = info.name if speed is None else speed[0].names[speed[1]]
        name_c = f"drive_{label}"
        self._claim(name_c, "constraint", "constraint", owner=where)
        con = PrescribedCoordinate(name_c, coordinate=q, law=f, rate_law=g, effort_name=effort or f"Q_{label}",
                                   speed=speed,
                                   on=self._check_body(on, where, allow_none=True),
                                   against=self._check_body(against, where, allow_none=True),
                                   against_given=against is not None, coordinate_kind=info.kind,
                                   description=description)
        self._claim(con.Q.name, "reaction", owner=where)
        vals = self.parameter_values()
        start = {}
        try:
            if f is not None:
                start["initial"] = float(sp.sympify(f.xreplace({t: sp.Integer(0)})).xreplace(vals))
            start["rate"] = float(sp.sympify(g.xreplace({t: sp.Integer(0)})).xreplace(vals))
        except (TypeError, ValueError):
            pass
        for key, v in start.items():
            given_v = getattr(info, key)
            if given_v is not None and abs(given_v - v) > 1e-9 * max(1.0, abs(v)):
                raise ModelError(f"the {key} value {given_v:g} of {info.name} disagrees with its law, which gives "
                                 f"{v:g} at t = 0.", where=where,
                                 hint=f"Remove the {key} value of {info.name}: the law fixes it.")
        self._coordinates[info.name] = replace(info, prescribed=f if f is not None else None,
                                               prescribed_rate=g, **start)
        if speed is not None and "rate" in start:
            group, i = speed
            group.initial = tuple(start["rate"] if j == i else v for j, v in enumerate(group.initial))
        self.constraints[name_c] = con
        return con
