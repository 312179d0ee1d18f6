"""Constraints: pins, contacts (sliding or rolling, on lines and circles) and collars on tracks.

A constraint contributes, in a given state, *rows*: a scalar velocity expression that must vanish
(linear in the coordinate rates; with its position-level gap when it has one) together with the
unknown reaction that enforces it.  A row whose velocity expression vanishes identically is built
into the coordinates the user chose; it still brings its reaction.  A contact can be ``open`` (no
rows), ``slip`` (normal row; Coulomb friction as a load) or ``stick`` (normal and tangential rows:
rolling without slip).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base.algebra import functions_of_time
from ..base.errors import ModelError
from .friction3d import SlidingFriction3D, slip_validity
from .friction_kinds import ROLLING, SMOOTH, Coulomb  # noqa: F401  (public here too: constraints.Coulomb ...)
from .loads import Application, SlidingFriction
from .points import Point

kin_t = dynamicsymbols._t


@dataclass(frozen=True, eq=False)
class Row:
    """One scalar constraint: ``velocity`` = 0, enforced by the unknown ``reaction``."""

    constraint: str
    label: str
    velocity: sp.Expr
    reaction: sp.Symbol
    applications: tuple[Application, ...]
    gap: sp.Expr | None = None
    unilateral: bool = False
    kind: str = "force"      # "force", "normal", "tangential", "torque", "tension"


@dataclass(eq=False)
class Constraint:
    """Base class of constraints."""

    name: str
    description: str = field(default="", kw_only=True)

    kind = "constraint"
    states: ClassVar[tuple[str, ...]] = ("closed",)

    def default_state(self, kin) -> str:
        return self.states[0]

    def rows(self, kin, state: str) -> list[Row]:
        raise NotImplementedError

    def loads(self, kin, state: str) -> list:
        return []

    def reactions(self) -> list[sp.Symbol]:
        return []


def _two_sided(symbol, direction, kind, body_a, point_a, body_b, point_b, label, source, loc=None):
    """The reaction ``symbol``·``direction`` on ``body_a`` and its opposite on ``body_b`` (if any).

    A force acts at a point (``point_a``/``point_b``, or the location ``loc``); a torque (``kind ==
    "torque"``) acts on the body as a whole.
    """
    torque = kind == "torque"
    apps = [Application(body_a, None if torque else point_a, symbol * direction, label, source, reaction=symbol,
                        location=None if torque else loc)]
    if body_b is not None:
        apps.append(Application(body_b, None if torque else point_b, -symbol * direction, label, source,
                                reaction=symbol, location=None if torque else loc))
    return tuple(apps)


def by_law(kin, obj) -> bool:
    """True for a point not fixed in a body, or a frame, that moves by a given law of t alone: its position
    (orientation) involves t and no coordinate — a driven support, a shaft turned at Ω."""
    if isinstance(obj, Point):
        if obj.body is not None or obj.parent is None:
            return False
        exprs = list(kin.position(obj).to_matrix(kin.F.ref))
    else:
        if obj.parent is None:
            return False
        exprs = list(obj.ref.dcm(kin.F.ref))
    return any(sp.sympify(e).has(kin_t) for e in exprs) and not any(functions_of_time(e) for e in exprs)


@dataclass(eq=False)
class Pin(Constraint):
    """A point of ``body_a`` held at a point of ``body_b`` (or fixed in the ground): a pin / fixed point.

    Reaction force components along the basis of ``basis_frame`` (the inertial frame by default):
    two in a planar problem, three in 3D.  In 3D an ``axis`` (a hinge) adds reaction torques about
    the two directions perpendicular to it; without one the pin is a ball joint.
    """

    point: Point = None
    body_a: object = None
    body_b: object | None = None
    point_b: Point | None = None
    basis_frame: object | None = None
    axis: str | None = None        # 3D hinge axis, e.g. "B.z" (frame name . axis)
    prefix: str | None = None

    kind = "pin"

    @property
    def _prefix(self) -> str:
        return self.prefix or f"R_{self.name}"

    def _symbols(self, n):
        return [sp.Symbol(f"{self._prefix}{c}", real=True) for c in "xyz"[:n]]

    def reactions(self):
        return self._symbols(3)

    def rows(self, kin, state):
        frame = self.basis_frame or kin.F
        pb = self.point_b or self.point
        va = kin.material_velocity(self.body_a, kin.position(self.point))
        vb = kin.material_velocity(self.body_b, kin.position(pb)) if self.body_b is not None else Vector(0)
        if self.body_b is None and (pb is not self.point or by_law(kin, pb)):
            vb = kin.velocity(pb)       # a point of the ground, or one that moves by a law of t (a driven support)
        rel = va - vb
        n = 2 if kin.planar else 3
        out = []
        for sym, e, axis in zip(self._symbols(n), (frame.x, frame.y, frame.z), frame.basis):
            gap = (kin.position(self.point) - kin.position(pb)).dot(e)
            out.append(Row(self.name, f"pin {self.name}: velocity along {axis}", rel.dot(e), sym,
                           _two_sided(sym, e, "force", self.body_a, self.point, self.body_b, pb,
                                      f"pin reaction {sym}", self.name), gap=gap))
        if not kin.planar and self.axis is not None:
            a_frame, a_axis = kin.system.axis_of(self.axis, where=f"pin {self.name}")
            others = [c for c in "xyz" if c != a_axis]
            w = kin.omega_of(self.body_a) - (kin.omega_of(self.body_b) if self.body_b else Vector(0))
            if self.body_b is None and by_law(kin, a_frame):
                w = w - kin.omega(a_frame)     # the hinge's axis turns by a law of t: the shaft it is on turns so
            for c in others:
                e = a_frame.unit(c)
                sym = sp.Symbol(f"M_{self.name}{c}", real=True)
                out.append(Row(self.name, f"hinge {self.name}: rotation about {c}", w.dot(e), sym,
                               _two_sided(sym, e, "torque", self.body_a, None, self.body_b, None,
                                          f"hinge torque {sym}", self.name), kind="torque"))
        return out


@dataclass(eq=False)
class Contact(Constraint):
    """A body touching a surface with a profile: a point (radius 0), a circle or a sphere of ``radius``.

    ``centre`` is the profile's centre, a point fixed in ``body`` (not necessarily its mass centre).
    The contact point is P = C − radius·n, n the surface normal into the body.  ``friction`` is
    ``"smooth"``, ``"rolling"`` (no slip) or ``Coulomb(mu)``.  ``unilateral`` contacts can only push:
    their normal reaction must stay ≥ 0 and they open when it reaches zero.
    """

    body: object = None
    centre: Point = None
    radius: sp.Expr = sp.Integer(0)
    surface: object = None
    friction: object = SMOOTH
    unilateral: bool = True
    normal_name: str | None = None
    friction_name: str | None = None
    arc: object = None          # model.profiles.Arc: the part of the profile that exists (None: all of it)

    kind = "contact"
    states = ("slip", "stick", "open")

    @property
    def N(self) -> sp.Symbol:
        return sp.Symbol(self.normal_name or f"N_{self.name}", real=True)

    @property
    def F(self) -> sp.Symbol:
        return sp.Symbol(self.friction_name or f"F_{self.name}", real=True)

    def reactions(self):
        return [self.N] if self.friction == SMOOTH else [self.N, self.F]

    def default_state(self, kin):
        if self.unilateral and self._apart_at_reference(kin):
            return "open"
        if self.friction == ROLLING:
            return "stick"
        if isinstance(self.friction, Coulomb) and kin.is_zero(self.slip_velocity(kin)):
            return "stick"
        return "slip"

    def _apart_at_reference(self, kin) -> bool:
        """True when the gap is clearly positive in the reference configuration (declared initial values)."""
        gap = self.gap(kin)
        if gap == 0 or not gap.free_symbols:
            return bool(gap.is_positive)
        try:
            val = complex(gap.xreplace({k: sp.Float(v) for k, v in kin.reference_values().items()}).evalf())
        except (TypeError, ValueError):
            return False
        return abs(val.imag) < 1e-12 and val.real > 1e-9

    # geometry ---------------------------------------------------------------------------------
    def normal(self, kin) -> Vector:
        return self.surface.normal_at(kin.position(self.centre), kin)

    def location(self, kin) -> Vector:
        """Position of the contact point P from the origin."""
        return kin.position(self.centre) - self.radius * self.normal(kin)

    def gap(self, kin) -> sp.Expr:
        return kin.simplify_expr(self.surface.gap(kin.position(self.centre), self.radius, kin))

    def relative_velocity(self, kin) -> Vector:
        loc = self.location(kin)
        v = kin.material_velocity(self.body, loc)
        if self.surface.body is not None:
            v = v - kin.material_velocity(self.surface.body, loc)
        else:
            v = v - self.surface.velocity_at(loc, kin)  # a ground surface may move with its point, and turn
        return v

    def tangents(self, kin) -> list[Vector]:
        n = self.normal(kin)
        if kin.planar:
            return [kin.simplify_vector(kin.F.z.cross(n))]
        return kin.tangent_basis(n)

    def slip_velocity(self, kin) -> sp.Expr:
        """The slip speed v_rel·t (planar) — zero while rolling."""
        return kin.simplify_expr(self.relative_velocity(kin).dot(self.tangents(kin)[0]))

    # rows ------------------------------------------------------------------------------------
    def rows(self, kin, state):
        if state == "open":
            return []
        if state not in self.states:
            raise ModelError(f"contact state '{state}' is not one of {self.states}.", where=f"contact {self.name}")
        if state == "stick" and self.friction == SMOOTH:
            raise ModelError("a smooth contact cannot stick (it has no friction).", where=f"contact {self.name}")
        n = self.normal(kin)
        loc = self.location(kin)
        v = self.relative_velocity(kin)
        sb = self.surface.body
        out = [Row(self.name, f"contact {self.name}: normal velocity", kin.simplify_expr(v.dot(n)), self.N,
                   _two_sided(self.N, n, "force", self.body, None, sb, None,
                              f"normal reaction {self.N}", self.name, loc=loc),
                   gap=self.gap(kin), unilateral=self.unilateral, kind="normal")]
        if state == "stick":
            tangents = self.tangents(kin)
            for i, tv in enumerate(tangents):
                sym = self.F if len(tangents) == 1 else sp.Symbol(f"{self.F.name}{i + 1}", real=True)
                out.append(Row(self.name, f"contact {self.name}: no slip", kin.simplify_expr(v.dot(tv)), sym,
                               _two_sided(sym, tv, "force", self.body, None, sb, None,
                                          f"friction (no-slip) reaction {sym}", self.name, loc=loc),
                               kind="tangential"))
        return out

    def loads(self, kin, state):
        if state != "slip" or not isinstance(self.friction, Coulomb):
            return []
        kind, extra = SlidingFriction, {}
        if not kin.planar:              # the slip direction anywhere in the tangent plane (model.friction3d)

            kind, extra = SlidingFriction3D, {"contact": self}
        return [kind(self.name, body=self.body, centre=self.centre, radius=self.radius,
                     normal=self.normal(kin), mu=self.friction.mu, normal_force=self.N,
                     against_body=self.surface.body,
                     against_surface=self.surface if self.surface.body is None else None,
                     normal_unilateral=self.unilateral, sign_symbol=sp.Symbol(f"sigma_{self.name}"), **extra)]

    def validity(self, setup, react) -> list:
        """In 3D: slipping while |v_s| > 0, sticking within the friction cone (model.friction3d)."""

        return slip_validity(self, setup, react)


@dataclass(eq=False)
class Collar(Constraint):
    """A collar (prismatic joint): ``body`` slides along a straight track without turning relative to it.

    The track passes through ``through`` along the unit vector ``along``, fixed in the ground or in
    ``track_body``.  Reactions: the normal force(s) on the collar at ``point`` and a reaction couple.
    ``friction`` may be ``Coulomb(mu)`` (planar), acting along the track against the sliding.
    """

    body: object = None
    point: Point = None
    through: Point = None
    along: Vector = None
    track_body: object | None = None
    friction: object = SMOOTH
    normal_name: str | None = None
    couple_name: str | None = None

    kind = "collar"
    states = ("slip",)

    @property
    def N(self) -> sp.Symbol:
        return sp.Symbol(self.normal_name or f"N_{self.name}", real=True)

    @property
    def M(self) -> sp.Symbol:
        return sp.Symbol(self.couple_name or f"M_{self.name}", real=True)

    def reactions(self):
        return [self.N, self.M]

    def _normals(self, kin):
        if kin.planar:
            return [kin.simplify_vector(kin.F.z.cross(self.along))]
        return kin.tangent_basis(self.along)

    def rows(self, kin, state):
        loc = kin.position(self.point)
        v = kin.material_velocity(self.body, loc)
        w = kin.omega_of(self.body)
        if self.track_body is not None:
            v = v - kin.material_velocity(self.track_body, loc)
            w = w - kin.omega_of(self.track_body)
        out = []
        normals = self._normals(kin)
        for i, nv in enumerate(normals):
            sym = self.N if len(normals) == 1 else sp.Symbol(f"{self.N.name}{i + 1}", real=True)
            gap = (loc - kin.position(self.through)).dot(nv)
            out.append(Row(self.name, f"collar {self.name}: velocity across the track",
                           kin.simplify_expr(v.dot(nv)), sym,
                           _two_sided(sym, nv, "force", self.body, self.point, self.track_body, None,
                                      f"track normal force {sym}", self.name, loc=loc if self.track_body else None),
                           gap=kin.simplify_expr(gap), kind="normal"))
        axes = [kin.F.z] if kin.planar else [kin.F.x, kin.F.y, kin.F.z]
        for i, e in enumerate(axes):
            sym = self.M if len(axes) == 1 else sp.Symbol(f"{self.M.name}{'xyz'[i]}", real=True)
            out.append(Row(self.name, f"collar {self.name}: no rotation relative to the track",
                           kin.simplify_expr(w.dot(e)), sym,
                           _two_sided(sym, e, "torque", self.body, None, self.track_body, None,
                                      f"track reaction couple {sym}", self.name), kind="torque"))
        return out

    def loads(self, kin, state):
        if not isinstance(self.friction, Coulomb):
            return []
        # friction along the track: normal is the track normal, the contact is at the collar point
        return [SlidingFriction(self.name, body=self.body, centre=self.point, radius=sp.Integer(0),
                                normal=self._normals(kin)[0], mu=self.friction.mu, normal_force=self.N,
                                against_body=self.track_body, normal_unilateral=False,
                                sign_symbol=sp.Symbol(f"sigma_{self.name}"))]


@dataclass(eq=False)
class Cable(Constraint):
    """An inextensible cable (string, rope) through ``points``, taut with tension T ≥ 0.

    ``points`` are the cable's ends and the small frictionless pulleys or eyes it runs over, in
    order; ``bodies`` the body each is fixed in (None: the ground).  While taut its length
    Σ |P_{k+1} − P_k| equals ``length``; the tension T pulls each point towards its neighbours (an end
    towards the next point, a pulley on a body along the sum of both directions).  A cable can only
    pull: it goes slack when T reaches zero (the gap length − Σ|…| opens).
    """

    points: tuple = ()
    bodies: tuple = ()
    length: sp.Expr = None
    tension_name: str | None = None

    kind = "cable"
    states = ("slip", "open")

    @property
    def T(self) -> sp.Symbol:
        return sp.Symbol(self.tension_name or f"T_{self.name}", real=True)

    def reactions(self):
        return [self.T]

    def _units(self, kin):
        pos = [kin.position(p) for p in self.points]
        segs = [pos[k + 1] - pos[k] for k in range(len(pos) - 1)]
        lens = [kin.magnitude(d) for d in segs]
        units = [kin.simplify_vector(d / ell) for d, ell in zip(segs, lens)]
        return pos, lens, units

    def rows(self, kin, state):
        if state == "open":
            return []
        pos, lens, units = self._units(kin)
        total = sum(lens, sp.Integer(0))
        velocity = sum((kin.velocity(self.points[k + 1]) - kin.velocity(self.points[k])).dot(units[k])
                       for k in range(len(units)))
        apps = []
        T = self.T
        for k, (p, b) in enumerate(zip(self.points, self.bodies)):
            if b is None:
                continue
            pull = Vector(0)
            if k + 1 < len(self.points):
                pull += units[k]
            if k > 0:
                pull -= units[k - 1]
            apps.append(Application(b, p, T * pull, f"cable tension {T}", self.name, reaction=T))
        return [Row(self.name, f"cable {self.name}: length", kin.simplify_expr(velocity), T, tuple(apps),
                    gap=kin.simplify_expr(self.length - total), unilateral=True, kind="tension")]
