"""Loads on bodies: gravity, forces, torques, springs, dampers and Coulomb sliding friction.

A load says, for the current kinematics, which forces act at which points of which bodies and which
torques act on which bodies (``Application`` records), and, where it is conservative, its potential
energy.  Sliding friction also says on which sign of which slip speed its direction depends (a
``SignChoice``): the solver splits the solution into one regime per sign, never hiding ``sign()``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.physics.vector import Vector

from ..base import algebra
from ..base.errors import ModelError
from .points import Point


def moves_in(point: Point, body, inertial) -> bool:
    """Whether ``point`` moves relative to ``body`` (None: the ground), i.e. is not one of its material points.

    A point declared fixed in the body, or located from its mass centre by a vector fixed in the body's
    frame, is a material point.  For the ground, a point whose motion is prescribed in time only (a
    driven anchor) counts as fixed: the load's end there acts on whatever drives it.  ``inertial`` is
    the inertial sympy ReferenceFrame.
    """
    if body is not None and (point.body is body or point is body.centre):
        return False
    if body is not None:
        drift = (point.position() - body.centre.position()).dt(body.frame.ref)
        if drift == 0:
            return False
        return not all(algebra.is_zero(c) for c in drift.to_matrix(inertial))
    velocity = point.position().dt(inertial)
    return velocity != 0 and any(c.atoms(AppliedUndef) for c in velocity.to_matrix(inertial))


def check_end(load_name: str, kind: str, point: Point, body, explicit: bool, inertial) -> bool:
    """Refuse a load end at a point that is not a material point of the body it acts on, unless the user
    said ``on`` (the force then acts on the material point of that body momentarily there).

    Returns True when the end is such a momentary material point (so the load's power must use the
    body's material velocity there, and a spring is no longer conservative through its length).
    """
    if not moves_in(point, body, inertial):
        return False
    if explicit and body is not None:
        return True
    what = f"body {body.name}" if body is not None else "the ground (it is fixed in no body)"
    raise ModelError(
        f"point {point.name} moves relative to {what}, so it is not a material point of it: the {kind}'s end "
        f"there acts on no definite point, and its power and its potential would disagree.",
        where=f"{kind} {load_name}",
        hint="Fix the point in the body it should act on (body = ... in [points], or a vector fixed in that body's "
             "frame), or say that the force acts on the material point of a body momentarily at that place: "
             "on_a = BODY / on_b = BODY for a spring's or damper's end (on = BODY for a force).")


@dataclass(frozen=True, eq=False)
class Application:
    """A force ``vector`` applied at ``point`` of ``body`` (``point`` None: a torque on ``body``)."""

    body: object
    point: Point | None
    vector: Vector
    label: str
    source: str
    reaction: sp.Symbol | None = None  # the unknown scalar this application carries, if any
    location: Vector | None = None      # position from the origin when the point is not a named point

    @property
    def is_torque(self) -> bool:
        return self.point is None and self.location is None


@dataclass(frozen=True, eq=False)
class SignChoice:
    """A sign σ = ±1 a load depends on: σ = sign(``quantity``), described by ``label``."""

    symbol: sp.Symbol
    quantity: sp.Expr
    label: str
    load: str
    rate_based: bool = True   # the quantity is a slip speed (state); False: a reaction (solved)


@dataclass(eq=False)
class Load:
    """Base class of loads."""

    name: str
    description: str = field(default="", kw_only=True)

    kind = "load"
    conservative = False

    def applications(self, kin) -> list[Application]:
        raise NotImplementedError

    def potential(self, kin) -> sp.Expr | None:
        return None

    def sign_choices(self, kin) -> list[SignChoice]:
        return []


@dataclass(eq=False)
class Gravity(Load):
    """Uniform gravity of magnitude ``g`` along the unit vector ``direction``: m g at each mass centre."""

    g: sp.Expr = sp.Symbol("g", positive=True)
    direction: Vector = None

    kind = "gravity"
    conservative = True

    def applications(self, kin):
        out = []
        for body in kin.system.bodies.values():
            if body.is_massless:
                continue
            out.append(Application(body, body.centre, body.mass * self.g * self.direction,
                                   f"weight of {body.name}", self.name))
        return out

    def potential(self, kin):
        return sum((-body.mass * self.g * kin.position(body.centre).dot(self.direction)
                    for body in kin.system.bodies.values() if not body.is_massless), sp.Integer(0))


@dataclass(eq=False)
class Force(Load):
    """A known force ``vector`` at ``point`` of ``body`` (an expression of parameters, state, time)."""

    body: object = None
    point: Point = None
    vector: Vector = None

    kind = "force"

    def applications(self, kin):
        return [Application(self.body, self.point, self.vector, self.description or f"force {self.name}",
                            self.name)]


@dataclass(eq=False)
class Torque(Load):
    """A known torque ``vector`` on ``body`` (and ``−vector`` on ``reaction_body``, if given)."""

    body: object = None
    vector: Vector = None
    reaction_body: object | None = None

    kind = "torque"

    def applications(self, kin):
        out = [Application(self.body, None, self.vector, self.description or f"torque {self.name}", self.name)]
        if self.reaction_body is not None:
            out.append(Application(self.reaction_body, None, -self.vector,
                                   f"reaction of torque {self.name}", self.name))
        return out


@dataclass(eq=False)
class Spring(Load):
    """Linear spring between ``point_a`` (on ``body_a``) and ``point_b`` (on ``body_b``, or the ground).

    Tension K (ℓ − ℓ0) with ℓ = |r_a − r_b| computed from the positions; potential K (ℓ − ℓ0)²/2.
    """

    point_a: Point = None
    body_a: object = None
    point_b: Point = None
    body_b: object | None = None
    stiffness: sp.Expr = None
    natural_length: sp.Expr = sp.Integer(0)
    moving_a: bool = False   # point_a is the material point of body_a momentarily there (``on_a``)
    moving_b: bool = False

    kind = "spring"

    @property
    def conservative(self) -> bool:
        """K (ℓ − ℓ0)²/2 is its potential only when both ends are material points (or fixed anchors)."""
        return not (self.moving_a or self.moving_b)

    def length(self, kin) -> sp.Expr:
        d = kin.position(self.point_a) - kin.position(self.point_b)
        return kin.magnitude(d)

    def applications(self, kin):
        d = kin.position(self.point_a) - kin.position(self.point_b)
        ell = kin.magnitude(d)
        tension = self.stiffness * (ell - self.natural_length)
        if self.natural_length == 0:
            force_on_a = -self.stiffness * d
        else:
            force_on_a = kin.simplify_vector(-tension * d / ell)
        out = [Application(self.body_a, self.point_a, force_on_a, f"spring {self.name} on {self.body_a.name}",
                           self.name)]
        if self.body_b is not None:
            out.append(Application(self.body_b, self.point_b, -force_on_a,
                                   f"spring {self.name} on {self.body_b.name}", self.name))
        return out

    def potential(self, kin):
        if not self.conservative:
            return None
        return self.stiffness * (self.length(kin) - self.natural_length) ** 2 / 2


@dataclass(eq=False)
class TorsionalSpring(Load):
    """Torsional spring: torque −K (angle − angle0) about ``axis`` on ``body_a`` (+ on ``body_b``)."""

    body_a: object = None
    body_b: object | None = None
    stiffness: sp.Expr = None
    angle: sp.Expr = None
    natural_angle: sp.Expr = sp.Integer(0)
    axis: Vector = None

    kind = "torsional spring"
    conservative = True

    def torque(self) -> sp.Expr:
        """The torque on ``body_a`` about ``axis``: −K (angle − angle0)."""
        return -self.stiffness * (self.angle - self.natural_angle)

    def applications(self, kin):
        torque = self.torque() * self.axis
        out = [Application(self.body_a, None, torque, f"{self.kind} {self.name} on {self.body_a.name}", self.name)]
        if self.body_b is not None:
            out.append(Application(self.body_b, None, -torque, f"{self.kind} {self.name} on {self.body_b.name}",
                                   self.name))
        return out

    def potential(self, kin):
        return self.stiffness * (self.angle - self.natural_angle) ** 2 / 2


#: The symbol a damper law is written in: the speed v along the damper's direction.
V = sp.Symbol("v", real=True)


@dataclass(eq=False)
class Damper(Load):
    """A damper whose force is any law f(v) of a speed v: F = f(v) u on ``body_a`` at ``point_a``.

    v = (v_a − v_b)·u, with u the unit vector ``along`` (or, when ``along`` is None, the unit vector
    from ``point_b`` to ``point_a``), and v_a, v_b the velocities of the ends: of the points themselves
    when they are material points of ``body_a``/``body_b`` (or fixed anchors), of the material points of
    the bodies momentarily there when given with ``on`` (``moving_a``/``moving_b``).  The power is then
    f(v) v.  A linear damper is ``law = -c*v``; a cubic one ``-c*v**3``.  ``law`` is an expression in
    the symbol ``rigidkin.model.loads.V`` or a callable of v.
    """

    point_a: Point = None
    body_a: object = None
    law: sp.Expr | Callable = None
    along: Vector | None = None
    point_b: Point | None = None
    body_b: object | None = None
    moving_a: bool = False
    moving_b: bool = False

    kind = "damper"

    def _direction(self, kin) -> Vector:
        if self.along is not None:
            return self.along
        if self.point_b is None:
            raise ModelError("a damper with no second point needs a direction 'along'.",
                             where=f"damper {self.name}")
        d = kin.position(self.point_a) - kin.position(self.point_b)
        return kin.simplify_vector(d / kin.magnitude(d))

    def speed(self, kin) -> sp.Expr:
        u = self._direction(kin)
        va = self._end_velocity(kin, self.point_a, self.body_a, self.moving_a)
        vb = self._end_velocity(kin, self.point_b, self.body_b, self.moving_b) if self.point_b is not None \
            else Vector(0)
        return (va - vb).dot(u)

    @staticmethod
    def _end_velocity(kin, point, body, moving) -> Vector:
        return kin.material_velocity(body, kin.position(point)) if moving else kin.velocity(point)

    def force_law(self, v: sp.Expr) -> sp.Expr:
        if callable(self.law) and not isinstance(self.law, sp.Basic):
            return sp.sympify(self.law(v))
        return sp.sympify(self.law).xreplace({V: v})

    def applications(self, kin):
        u = self._direction(kin)
        f = self.force_law(self.speed(kin))
        out = [Application(self.body_a, self.point_a, f * u, f"damper {self.name} on {self.body_a.name}",
                           self.name)]
        if self.body_b is not None:
            out.append(Application(self.body_b, self.point_b, -f * u,
                                   f"damper {self.name} on {self.body_b.name}", self.name))
        return out


@dataclass(eq=False)
class SlidingFriction(Load):
    """Coulomb sliding friction F_f = −µ|N| v_rel/|v_rel| at a contact point of ``body``.

    The contact point is ``centre − radius·normal`` (a point of ``body``).  ``v_rel`` is the velocity
    of that material point relative to the touching surface, which may move: ``against_body`` (a
    body whose material point is there) or ``against_point`` (a point whose velocity the surface
    shares, such as a plate that translates with it).  ``normal_force`` is the magnitude of the
    normal force: a reaction symbol solved with the rest, or a known expression.  In a planar
    problem v_rel = s t with t = Ez × n, and F_f = −µ|N| σ t with σ = sign(s): one regime per sign.
    """

    body: object = None
    centre: Point = None
    radius: sp.Expr = sp.Integer(0)
    normal: Vector = None
    mu: sp.Expr = None
    normal_force: sp.Expr = None
    against_body: object | None = None
    against_point: Point | None = None
    against_surface: object | None = None
    normal_unilateral: bool = True
    sign_symbol: sp.Symbol = None
    normal_sign_symbol: sp.Symbol | None = None

    kind = "sliding friction"

    def __post_init__(self):
        if self.sign_symbol is None:
            self.sign_symbol = sp.Symbol(f"sigma_{self.name}")

    def contact_location(self, kin) -> Vector:
        return kin.position(self.centre) - self.radius * self.normal

    def relative_velocity(self, kin) -> Vector:
        loc = self.contact_location(kin)
        v = kin.material_velocity(self.body, loc)
        if self.against_body is not None:
            v = v - kin.material_velocity(self.against_body, loc)
        elif self.against_surface is not None:
            v = v - self.against_surface.velocity_at(loc, kin)
        elif self.against_point is not None:
            v = v - kin.velocity(self.against_point)
        return v

    def tangent(self, kin) -> Vector:
        return kin.simplify_vector(kin.F.z.cross(self.normal))

    def slip_speed(self, kin) -> sp.Expr:
        return kin.simplify_expr(self.relative_velocity(kin).dot(self.tangent(kin)))

    def _abs_normal(self) -> sp.Expr:
        N = sp.sympify(self.normal_force)
        if isinstance(N, sp.Symbol) and not N.is_positive:
            if self.normal_unilateral:
                return N
            if self.normal_sign_symbol is None:
                self.normal_sign_symbol = sp.Symbol(f"sigma_{N.name}")
            return self.normal_sign_symbol * N
        return sp.Abs(N) if not N.is_nonnegative else N

    def sign_choices(self, kin):
        if not kin.planar:
            return []
        out = [SignChoice(self.sign_symbol, self.slip_speed(kin), f"slip speed at {self.name}", self.name)]
        N = sp.sympify(self.normal_force)
        if isinstance(N, sp.Symbol) and not N.is_positive and not self.normal_unilateral:
            self._abs_normal()
            out.append(SignChoice(self.normal_sign_symbol, N, f"normal force at {self.name}", self.name,
                                  rate_based=False))
        return out

    def applications(self, kin):
        loc = self.contact_location(kin)
        if kin.planar:
            force = -self.mu * self._abs_normal() * self.sign_symbol * self.tangent(kin)
        else:
            v = self.relative_velocity(kin)
            force = -self.mu * self._abs_normal() * v / kin.magnitude(v)
        out = [Application(self.body, None, force, f"sliding friction {self.name} on {self.body.name}",
                           self.name, location=loc)]
        if self.against_body is not None:
            out.append(Application(self.against_body, None, -force,
                                   f"sliding friction {self.name} on {self.against_body.name}", self.name,
                                   location=loc))
        return out


@dataclass(eq=False)
class Impulse(Load):
    """An impulse F̂ (a force integrated over an instant) at ``point`` of ``body``.

    It has no finite force during the motion (``applications`` is empty); the impulse–momentum law
    reads ``impulses``.
    """

    body: object = None
    point: Point = None
    vector: Vector = None

    kind = "impulse"

    def applications(self, kin):
        return []

    def impulses(self, kin) -> list[Application]:
        return [Application(self.body, self.point, self.vector, self.description or f"impulse {self.name}",
                            self.name)]
