"""Prescribed coordinates: a declared coordinate (or its rate) given as a function of time.

A crank turned by a motor at a constant rate (φ = Ω t), a cart shaken by an actuator (x = A sin ωt):
the coordinate q is declared as any other and used in frames and points, then prescribed by a law
q = f(t) (or its rate, q̇ = g(t)).  The drive is one constraint row, q̇ − ḟ(t) = 0 (with its gap
q − f(t)), so q is eliminated and the equations of motion are written for the free coordinates.  Its
reaction is the generalised force Q_q the actuator supplies along q, positive in the sense of q: a
torque for an angle, a force for a length.

On the bodies Q_q is realised by the actuator that moves q alone: for the angle of a frame R turned
from its parent about u, a torque Q_q u on the body turned by R and −Q_q u on the body across its hinge
(or the body of the parent frame, or the ground); for a length in a point's offset, a force Q_q e at
the point on its body and −Q_q e on the body the offset is measured from (or the ground), e = ∂r/∂q.
The realisation is checked: its power must be Q_q q̇ for every motion, so that it adds Q_q to the
equation of q and nothing to the others.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base import algebra
from ..base.errors import ModelError
from .constraints import Constraint, Row
from .loads import Application

t = dynamicsymbols._t


@dataclass(eq=False)
class PrescribedCoordinate(Constraint):
    """``coordinate`` = ``law`` (a function of t), or its rate = ``rate_law``; reaction: the effort ``Q``."""

    coordinate: object = None          # q(t)
    law: sp.Expr | None = None         # f(t), or None when only the rate is prescribed
    rate_law: sp.Expr = None           # ḟ(t) or the given rate g(t)
    effort_name: str | None = None
    on: object | None = None           # the body the actuator drives (found when None)
    against: object | None = None      # the body it reacts on (None: found, or the ground)
    against_given: bool = False
    coordinate_kind: str = "angle"
    speed: tuple | None = None         # (speed group, index) when a generalised speed is prescribed

    kind = "prescribed coordinate"

    @property
    def Q(self) -> sp.Symbol:
        return sp.Symbol(self.effort_name or f"Q_{self.coordinate.func.__name__}", real=True)

    def reactions(self):
        return [self.Q]

    @property
    def effort_kind(self) -> str:
        return "torque" if self.coordinate_kind == "angle" else "force"

    def reaction_label(self, sym) -> str:
        if self.speed is not None:
            group, i = self.speed
            return (f"torque needed to drive the speed {group.names[i]} (about {group.frame.basis[i]}) by the law "
                    f"{group.names[i]} = {self.rate_law}, positive along {group.frame.basis[i]}")
        q = self.coordinate.func.__name__
        what = "torque" if self.coordinate_kind == "angle" else "force" if self.coordinate_kind == "length" \
            else "generalised force"
        law = f"{q} = {self.law}" if self.law is not None else f"d{q}/dt = {self.rate_law}"
        return f"{what} needed to drive {q} by the law {law}, positive in the sense of {q}"

    def rows(self, kin, state):
        q = self.coordinate
        vel = q.diff(t) - self.rate_law
        gap = None if self.law is None else q - self.law
        law = f"{q.func.__name__} = {self.law}" if self.law is not None else \
            f"d{q.func.__name__}/dt = {self.rate_law}"
        return [Row(self.name, f"prescribed {law}", vel, self.Q, self._applications(kin), gap=gap,
                    kind=self.effort_kind)]

    # the actuator -----------------------------------------------------------------------------------
    def _applications(self, kin):
        cache = kin.__dict__.setdefault("_prescribed_apps", {})
        if self.name not in cache:
            cache[self.name] = self._realise(kin)
        return cache[self.name]

    def _realise(self, kin):
        tried = []
        for apps in self._candidates(kin):
            tried.append(apps)
            if self._power_is_Q_qdot(kin, apps):
                return tuple(apps)
        q = self.coordinate.func.__name__
        raise ModelError(f"no actuator moving {q} alone was found: the effort that drives {q} cannot be placed on "
                         "the bodies.", where=f"prescribed coordinate {q}",
                         hint=f"Use {q} as the angle of one frame (s.frame(..., angle={q})) or as a length along one "
                              "unit vector of a point's offset, with the body it moves; or name the bodies the "
                              "actuator acts between: s.prescribe(q, law, on=body, against=other_body).")

    def _candidates(self, kin):
        system, q = kin.system, self.coordinate
        label = f"effort {self.Q} driving {q.func.__name__}"
        if self.speed is not None:          # w_i: a component of the frame's angular velocity along its own axis i
            group, i = self.speed
            fr = group.frame
            e = (fr.x, fr.y, fr.z)[i]
            on = [self.on] if self.on is not None else [b for b in system.bodies.values() if b.frame is fr]
            for a in on:
                for b in self._against(system, a, fr.parent):
                    apps = [Application(a, None, self.Q * e, label, self.name, reaction=self.Q)]
                    if b is not None:
                        apps.append(Application(b, None, -self.Q * e, label, self.name, reaction=self.Q))
                    yield apps
            return
        for fr in system.frames.values():
            if fr.parent is None or fr.angle is None or fr.axis is None or not sp.sympify(fr.angle).has(q):
                continue
            c = sp.diff(fr.angle, q)
            if not algebra.is_zero(sp.diff(c, q)) or algebra.is_zero(c):
                continue
            u = fr.axis.normalize() / c
            on = [self.on] if self.on is not None else [b for b in system.bodies.values() if b.frame is fr]
            for a in on:
                for b in self._against(system, a, fr.parent):
                    apps = [Application(a, None, self.Q * u, label, self.name, reaction=self.Q)]
                    if b is not None:
                        apps.append(Application(b, None, -self.Q * u, label, self.name, reaction=self.Q))
                    yield apps
        for p in system.points.values():
            if p.parent is None or p.offset == Vector(0):
                continue
            e = Vector([(m.diff(q), f) for m, f in p.offset.args])
            if kin.is_zero_vector(e):
                continue
            e2 = kin.simplify_expr(e.dot(e))
            if algebra.is_zero(e2):
                continue
            d = kin.simplify_vector(e / e2)
            on = [self.on] if self.on is not None else [b for b in system.bodies.values()
                                                        if p.body is b or b.reference is p]
            loc_b, loc_a = kin.position(p), kin.position(p.parent)
            for a in on:
                againsts = [self.against] if self.against_given else [p.parent.body]
                for b in againsts:
                    apps = [Application(a, None, self.Q * d, label, self.name, reaction=self.Q, location=loc_b)]
                    if b is not None:
                        apps.append(Application(b, None, -self.Q * d, label, self.name, reaction=self.Q,
                                                location=loc_a))
                    yield apps

    def _against(self, system, a, parent_frame):
        if self.against_given:
            yield self.against
            return
        seen = []
        for c in system.constraints.values():
            if getattr(c, "kind", "") != "pin":
                continue
            ends = (getattr(c, "body_a", None), getattr(c, "body_b", None))
            if a in ends:
                other = ends[1] if ends[0] is a else ends[0]
                if other not in seen:
                    seen.append(other)
        for b in system.bodies.values():
            if b.frame is parent_frame and b is not a and b not in seen:
                seen.append(b)
        if None not in seen:
            seen.append(None)
        yield from seen

    def _power_is_Q_qdot(self, kin, apps) -> bool:
        """The power of the actuator's efforts is Q q̇ for every motion (Q on q's equation, nothing elsewhere)."""
        power = sp.Integer(0)
        for ap in apps:
            if ap.is_torque:
                power += ap.vector.dot(kin.omega_of(ap.body))
            else:
                loc = ap.location if ap.location is not None else kin.position(ap.point)
                power += ap.vector.dot(kin.material_velocity(ap.body, loc))
        power = sp.expand(power.xreplace({self.Q: 1}))
        q = self.coordinate
        return algebra.is_zero(power - q.diff(t))
