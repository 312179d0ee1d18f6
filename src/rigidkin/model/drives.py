"""Driven bodies: a body whose motion is a given function of time, with the effort that drives it.

A driven body (a shaft turned at Ω, a turntable, a support that vibrates as A cos ωt) has its frame's
orientation and its reference point P located by given functions of t alone: its motion is prescribed,
it has no coordinate of its own.  The drive is a constraint whose rows say so — v_P and ω of the body
equal what the law gives — rows the prescribed motion satisfies identically, so each only brings its
reaction: the force the drive applies at P (components along ``basis``, the inertial frame by default)
and the torque it applies (components along the body frame's axes).  The component about the axis the
frame turns about (its ``axis`` when it is turned by one angle from its parent) is the drive torque,
positive in the sense of the angle: "the torque needed to turn the shaft"; the other two are the
bearing torques.  Euler's laws for the body then give these efforts in closed form.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base import algebra
from ..base.errors import ModelError
from .constraints import Constraint, Row, _two_sided
from .points import Point

t = dynamicsymbols._t


def drive_axis(frame) -> int | None:
    """The index (0, 1, 2) of the frame's basis vector along the axis it turns about, if there is one."""
    if frame.axis is None or frame.parent is None:
        return None
    for i, e in enumerate((frame.x, frame.y, frame.z)):
        d = (e - frame.axis.normalize()).express(frame.ref)
        if all(algebra.is_zero(c) for c in d.to_matrix(frame.ref)):
            return i
    return None


@dataclass(eq=False)
class Drive(Constraint):
    """The prescribed motion of ``body``: its frame and its reference ``point`` given functions of t."""

    body: object = None
    point: Point = None
    basis_frame: object | None = None
    force_prefix: str | None = None
    torque_name: str | None = None
    carrier: object | None = None       # the body the drive is mounted on (None: the ground)

    kind = "drive"

    def _forces(self, n):
        p = self.force_prefix or f"F_{self.name}"
        return [sp.Symbol(f"{p}{c}", real=True) for c in "xyz"[:n]]

    def _torques(self, planar):
        """(symbol, axis index in the body frame, is_drive) for each torque component."""
        k = drive_axis(self.body.frame)
        out = []
        for i in ((2,) if planar else (0, 1, 2)):
            if i == k:
                out.append((sp.Symbol(self.torque_name or f"T_{self.name}", real=True), i, True))
            else:
                out.append((sp.Symbol(f"M_{self.name}{'xyz'[i]}", real=True), i, False))
        return out

    def reactions(self):
        return self._forces(3) + [s for s, _, _ in self._torques(False)]

    def drive_torque(self) -> sp.Symbol | None:
        """The torque about the axis the body's frame turns about (None when it turns about no one axis)."""
        for s, _, is_drive in self._torques(False):
            if is_drive:
                return s
        return None

    def reaction_label(self, sym) -> str:
        """What each effort of the drive is, with its positive sense."""
        fr = self.body.frame
        for s_, i, is_drive in self._torques(False):
            if sym == s_ and is_drive:
                return (f"torque needed to drive {self.body.name} about {fr.basis[i]}, positive in the sense of "
                        f"the angle of {fr.name}")
            if sym == s_:
                return f"bearing torque on the driven body {self.body.name} about {fr.basis[i]}"
        basis = (self.basis_frame.basis if self.basis_frame is not None else ("Ex", "Ey", "Ez"))
        return (f"force needed to drive {self.body.name}, applied at {self.point.name}, along "
                f"{basis['xyz'.index(sym.name[-1])]}")

    def _relative(self, kin, v, what: str) -> None:
        """The motion of the body relative to its carrier (the ground by default) must be the law's alone: no
        rate of a coordinate or speed in it."""
        rates = [q.diff(t) for q in kin.system.coordinates] + \
            [w for g in getattr(kin.system, "speed_groups", {}).values() for w in g.speeds]
        comps = [kin.simplify_expr(v.dot(e)) for e in (kin.F.x, kin.F.y, kin.F.z)]
        if any(sp.sympify(c).has(*rates) for c in comps):
            on = f"its carrier {self.carrier.name}" if self.carrier is not None else "the ground"
            raise ModelError(f"the {what} of the driven body {self.body.name} relative to {on} depends on the "
                             "rates of the coordinates: its motion is not prescribed.",
                             where=f"driven body {self.name}",
                             hint="Locate and turn the driven body from its carrier by laws of t alone (its joint "
                                  "fixed in it), or drive it relative to the body that carries it (carrier=).")

    def rows(self, kin, state):
        frame = self.basis_frame or kin.F
        body, P, carrier = self.body, self.point, self.carrier
        loc = kin.position(P)
        if not kin.is_zero_vector(kin.material_velocity(body, loc) - kin.velocity(P)):
            raise ModelError(f"the point {P.name} where the drive acts does not move with the driven body "
                             f"{body.name}.", where=f"driven body {body.name}",
                             hint="Give a joint fixed in the body (located from its point by a vector of its frame).")
        self._relative(kin, kin.velocity(P) - kin.material_velocity(carrier, loc), f"velocity of {P.name}")
        self._relative(kin, kin.omega_of(body) - kin.omega_of(carrier), "angular velocity")
        out = []
        n = 2 if kin.planar else 3
        for sym, e, axis in zip(self._forces(n), (frame.x, frame.y, frame.z), frame.basis):
            out.append(Row(self.name, f"drive {self.name}: velocity of {P.name} along {axis} as prescribed",
                           sp.Integer(0), sym,
                           _two_sided(sym, e, "force", body, P, carrier, P, f"drive force {sym}", self.name)))
        fr = body.frame
        for sym, i, is_drive in self._torques(kin.planar):
            e = kin.F.z if kin.planar else (fr.x, fr.y, fr.z)[i]
            what = "drive torque" if is_drive else "bearing torque"
            out.append(Row(self.name, f"drive {self.name}: rotation about {fr.basis[i]} as prescribed",
                           sp.Integer(0), sym,
                           _two_sided(sym, e, "torque", body, None, carrier, None, f"{what} {sym}", self.name),
                           kind="torque"))
        return out


def check_prescribed(system, frame, point, where: str) -> None:
    """A driven body's frame and point must be located by functions of time alone (no coordinate)."""
    coords = set(system.coordinates)
    fr = frame
    while fr is not None and fr.parent is not None:
        dcm = fr.ref.dcm(fr.parent.ref)
        bad = algebra.functions_of_time(dcm) & coords
        if bad:
            raise ModelError(f"the frame {fr.name} of a driven body turns with the coordinate(s) "
                             f"{', '.join(q.func.__name__ for q in bad)}: its motion is not prescribed.",
                             where=where, hint="Give the frame's angle as a function of t (e.g. Omega*t) and "
                                               "the other bodies coordinates of their own.")
        fr = fr.parent
    r = point.position()
    bad = set()
    for m, _f in (r.args if r != Vector(0) else ()):
        bad |= algebra.functions_of_time(m) & coords
    if bad:
        raise ModelError(f"the point {point.name} of a driven body moves with the coordinate(s) "
                         f"{', '.join(q.func.__name__ for q in bad)}: its motion is not prescribed.",
                         where=where, hint="Locate it by a function of t (e.g. A*cos(omega*t)*Ey).")


def driving_laws(system) -> list[str]:
    """Each motion the system is given as a law of t, in words: driven bodies, prescribed coordinates, frames
    turned and points moved by laws of t.  An answer drawn from the equations (an integral, an event) holds only
    for these laws: the drives do work to keep them."""
    def explicit(e) -> bool:
        return algebra.plain_state(sp.sympify(e))[0].has(t)

    out = []
    for c in system.constraints.values():
        if getattr(c, "kind", "") == "prescribed coordinate":
            q = c.coordinate.func.__name__
            out.append(f"{q} = {c.law}" if c.law is not None else f"d{q}/dt = {c.rate_law}")
    for fr in system.frames.values():
        angles = (fr.angle,) + tuple(fr.angles or ())
        if fr.parent is not None and any(a is not None and explicit(a) for a in angles):
            law = fr.angle if fr.angle is not None else ", ".join(str(a) for a in fr.angles)
            out.append(f"frame {fr.name} turned by {law}")
    for p in system.points.values():
        if p.parent is not None and any(explicit(m) for m, _f in (p.offset.args if p.offset != Vector(0) else ())):
            out.append(f"point {p.name} moved by the law {p.offset}")
    return out


def driving_note(system) -> str:
    """'' for a system with no driving law; else the sentence an answer carries."""
    laws = driving_laws(system)
    if not laws:
        return ""
    return ("holds only for the given driving law (" + "; ".join(laws) + "): the drive does work to keep it, so "
            "T + U is not conserved unless that work is counted")
