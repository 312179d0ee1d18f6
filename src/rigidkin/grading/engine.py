"""The engine's own derivation of a problem, for grading: the balance equations as rows, the laws a
step may name (force balance along a direction, moments about a point, work–energy), and the common
mistaken forms of each (the named mistakes the feedback looks for).

One :class:`Reference` per problem and mode, cached within a run (a class of worksheets on the same
problem derives it once).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols, outer

from ..analysis.answers import answer
from ..base.errors import RigidkinError
from ..derive.laws import energy
from ..derive.laws.newton_euler import body_balances
from ..io.load import load_system
from ..io.problem import system_scope
from ..model.speeds import quaternion_groups
from .space import Sampler, free_dim, plain_accel, to_plain

t = dynamicsymbols._t

_CACHE: dict = {}


@dataclass
class Candidate:
    """An equation ``expr = 0`` the engine writes for a law, or one of its common mistaken forms."""

    label: str
    expr: sp.Expr
    body: str | None = None
    law: str | None = None
    point: str | None = None
    mistake: str | None = None       # None: the correct form; else the cause, in words
    correct: sp.Expr | None = None   # for a mistaken form: the correct equation it stands in for


@dataclass(eq=False)
class Spot:
    """The material point of a body at a contact (moments may be taken about it), by the contact's name."""

    name: str
    location: Vector
    body: object = None

    def position(self) -> Vector:
        return self.location


@dataclass
class Reference:
    ref: str
    system: object
    spec: object
    solution: object
    setup: object
    scope: object
    unknowns: list
    sampler: Sampler
    equations: list = field(default_factory=list)     # the balance equations (expr = 0), symbolic
    _rows: dict = field(default_factory=dict)

    # ---------------------------------------------------------------------------------------------
    @property
    def kin(self):
        return self.setup.kin

    @property
    def F(self):
        return self.kin.F

    def regimes(self):
        return list(self.solution.regimes)

    def scalar(self, expr, regime=None):
        """In the independent coordinates of the mode (dependent rates, accelerations eliminated)."""
        e = self.setup.scalar(sp.sympify(expr))
        if regime is not None and regime.signs:
            e = e.xreplace(dict(regime.signs))
        return e

    def row(self, expr, regime):
        key = (sp.sympify(expr), id(regime))
        if key not in self._rows:
            self._rows[key] = self.sampler.row(to_plain(self.scalar(expr, regime)))
        return self._rows[key]

    @property
    def n_acc(self) -> int:
        return len(self.solution.coordinates)

    def determinate_like(self, rows, regime) -> bool:
        """The rows imply as many equations of motion as the engine's balance equations do (not more: an
        inconsistent set implies anything; not fewer)."""

        key = ("free", id(regime))
        if key not in self._rows:
            self._rows[key] = free_dim(self.basis(regime), self.n_acc)
        return free_dim(rows, self.n_acc) == self._rows[key]

    def basis(self, regime, exprs=None):
        return [self.row(e, regime) for e in (self.equations if exprs is None else exprs)]

    def spec_questions(self):
        return tuple(getattr(self.spec, "questions", ()) or ())

    def answers(self):
        """The answers to the problem's questions, in order (computed once)."""
        if "answers" not in self._rows:
            out, context = {}, {}
            for q in self.spec_questions():
                try:
                    a = answer(self.system, q, context)
                except RigidkinError as exc:
                    a = exc
                else:
                    context[q.name] = a
                out[q.name] = a
            self._rows["answers"] = out
        return self._rows["answers"]

    # objects by name ----------------------------------------------------------------------------
    def body(self, name):
        return self.system.bodies.get(name) if name else None

    def point_body(self, point):
        if getattr(point, "body", None) is not None:
            return point.body
        for b in self.system.bodies.values():
            if b.centre is point or b.reference is point:
                return b
        return None

    def point_of(self, name):
        """A point by name: a point of the system, a constraint's point, or a body (its mass centre)."""
        s = self.system
        if name in s.points:
            return s.points[name]
        c = s.constraints.get(name)
        if c is not None and getattr(c, "point", None) is not None:
            return c.point
        for spot in self.contact_spots():
            if spot.name == name:
                return spot
        if name in s.bodies:
            return s.bodies[name].centre
        return None

    def contact_spots(self, body=None) -> list:
        """A Spot for each contact (of ``body``) that is not open in this mode."""
        key = ("spots",)
        if key not in self._rows:
            out = []
            for name, c in self.system.constraints.items():
                if c.kind == "contact" and self.setup.states.get(name) != "open":
                    try:
                        out.append(Spot(name, self.setup.vector(c.location(self.kin)), c.body))
                    except (AttributeError, TypeError, ValueError):
                        continue
            self._rows[key] = out
        return [s for s in self._rows[key] if body is None or s.body is body]

    def body_points(self, body):
        out = [body.centre]
        for p in self.system.points.values():
            if p not in out and (p.body is body or p is body.reference):
                out.append(p)
        for c in self.system.constraints.values():       # pins joining the body to another
            p = getattr(c, "point", None)
            if p is not None and p not in out and body in (getattr(c, "body_a", None), getattr(c, "body_b", None)):
                out.append(p)
        return out

    # the laws -----------------------------------------------------------------------------------
    def balance(self, body):
        return next(b for b in body_balances(self.setup) if b.body is body)

    def force_equation(self, body, e: Vector, accel: Vector | None = None) -> sp.Expr:
        """Euler's 1st law along e: ΣF·e − m a·e (a: the mass centre's acceleration, or a given one)."""
        bal = self.balance(body)
        ma = bal.mass_accel if accel is None else body.mass * self.setup.vector(accel)
        return self.scalar(bal.force.dot(e) - ma.dot(e))

    def moment_vector(self, body, rP: Vector, loads=None) -> Vector:
        """Σ (r − r_P) × F + Σ couples on the body (its diagram, or the given (vector, location|None) loads)."""
        if loads is None:
            bal = self.balance(body)
            d = self.setup.vector(self.kin.position(body.centre) - rP)
            return bal.moment + d.cross(bal.force)
        out = Vector(0)
        for vec, loc in loads:
            out += vec if loc is None else (loc - rP).cross(vec)
        return out

    def moment_equation(self, body, P, axis: Vector, inertia_about=None, inertial: bool = True,
                        alpha: Vector | None = None, accel: Vector | None = None,
                        rotational: bool = True) -> sp.Expr:
        """Euler's 2nd law about P along ``axis``: M_P = dH̄/dt + (r̄ − r_P) × m ā.

        ``inertia_about`` (a point) replaces Ī by the inertia about that point in dH̄/dt (the mistakes);
        ``inertial=False`` writes M_P = d(I_P·ω)/dt, the form that holds only for a fixed P.
        """
        kin = self.kin
        rP = kin.position(P) if P is not None else kin.position(body.centre)
        rG = kin.position(body.centre)
        d = rG - rP
        m = body.mass
        w = kin.omega_of(body)
        a = kin.alpha(body.frame) if alpha is None else alpha
        aG = kin.acceleration(body.centre) if accel is None else accel
        Ibar = body.inertia

        def rate(I):
            return I.dot(a) + w.cross(I.dot(w))

        M = self.moment_vector(body, rP)
        if not rotational:
            rhs = d.cross(m * aG)
        elif not inertial:
            IP = Ibar + _shift(m, d, self.F)
            rhs = rate(IP)
        elif inertia_about is not None:
            dq = rG - kin.position(inertia_about)
            rhs = rate(Ibar + _shift(m, dq, self.F)) + d.cross(m * aG)
        else:
            rhs = rate(Ibar) + d.cross(m * aG)
        return self.scalar(self.setup.vector(M - rhs).dot(axis))

    def axes(self, moment: bool = False):
        F = self.F
        if self.kin.planar and moment:
            return [(F.z, F.basis[2])]
        out = [(F.x, F.basis[0]), (F.y, F.basis[1])] + ([] if self.kin.planar else [(F.z, F.basis[2])])
        return out

    def directions(self):
        """Every basis vector of every frame (force balances may be resolved along any)."""
        out = []
        for fr in self.system.frames.values():
            for v, name in zip((fr.x, fr.y, fr.z), fr.basis):
                if self.kin.planar and name == fr.basis[2]:
                    continue
                out.append((v, f"{fr.name}.{name}"))
        return out

    def energy_equation(self):

        eqs = energy.equations(self.setup)
        return [e.expr for e in eqs]


def _shift(m, d: Vector, F) -> object:
    """m (|d|² U − d⊗d): the parallel-axis term."""
    U = outer(F.x, F.x) + outer(F.y, F.y) + outer(F.z, F.z)
    return m * (d.dot(d) * U - outer(d, d))


def reference(ref: str, mode: dict | None = None) -> Reference:
    """The engine's derivation of the problem ``ref`` (a bundled name or a file path), cached per run."""
    mode = dict(mode or {})
    p = Path(ref)
    stamp = p.stat().st_mtime_ns if p.is_file() else None
    key = (ref, stamp, tuple(sorted(mode.items())))
    if key in _CACHE:
        return _CACHE[key]
    system, spec = load_system(ref)
    sol = system.solve(mode=mode) if mode else system.solve()
    setup = sol.setup
    unknowns = [q.diff(t, 2) for q in sol.coordinates] + list(setup.reactions)
    plain_unknowns = [plain_accel(q) for q in sol.coordinates] + list(setup.reactions)
    scope = system_scope(system)
    quaternions = [tuple(to_plain(e) for e in g.coordinates) for g in quaternion_groups(system)]
    r = Reference(ref, system, spec, sol, setup, scope, unknowns, Sampler(plain_unknowns, unit_groups=quaternions))
    r.equations = [e.expr for e in sol.equations]
    _CACHE[key] = r
    return r
