"""Driven bodies for :class:`rigidkin.System`: a body moved by a given law of time (see ``model.drives``)."""

from __future__ import annotations

from ..base.errors import ModelError
from .bodies import Body
from .drives import Drive, check_prescribed
from .frames import Frame
from .points import Point
from .shapes import Massless, Shape


class DriveMethods:
    """``System.drive``: a shaft, turntable or support whose motion is prescribed (mixed into System)."""

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
