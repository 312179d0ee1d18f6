"""Euler's 1st law and Euler's 2nd law about the mass centre, for every body.

For each body: F = m ā (the sum of the forces on the free-body diagram, reactions included) and
M̄ = d(H̄)/dt with H̄ = Ī·ω (the rate taken in the inertial frame: Ī·α + ω × Ī·ω when Ī is fixed in
the body).  Each is resolved into scalar equations along the inertial basis (in a planar problem:
the two in-plane force equations and the moment equation about Ez; in 3D the moment equations along
the body's own axes, Euler's equations in their usual form).  A massless body gives
ΣF = 0 and ΣM = 0 about its reference point.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ...base.errors import ModelError
from ...base.trace import LazyEquations
from ...base.vectorops import cross, dt, in_frame
from ..mode import ModeSetup

t = dynamicsymbols._t


@dataclass(frozen=True)
class BalanceEquation:
    """A scalar balance equation ``lhs = rhs`` (loads on the left, inertia on the right)."""

    label: str
    body: str
    law: str
    lhs: sp.Expr
    rhs: sp.Expr

    @property
    def expr(self) -> sp.Expr:
        """The equation as ``expr = 0``."""
        return self.lhs - self.rhs


@dataclass(frozen=True)
class BodyBalance:
    """The vector balance of one body: resultant force, moment about the mass centre, ā, dH̄/dt."""

    body: object
    force: Vector
    moment: Vector
    mass_accel: Vector
    momentum_rate: Vector
    omega: Vector
    v_centre: Vector


def body_loads(setup: ModeSetup, body) -> tuple[Vector, Vector, list]:
    """Resultant force on ``body`` and its moment about the body's mass centre."""
    kin = setup.kin
    rG = kin.position(body.centre)
    F, M, apps = Vector(0), Vector(0), []
    for app in setup.applications:
        if app.body is not body:
            continue
        apps.append(app)
        if app.is_torque:
            M += app.vector
        else:
            loc = app.location if app.location is not None else kin.position(app.point)
            F += app.vector
            M += cross(loc - rG, app.vector)
    return F, M, apps


def body_balances(setup: ModeSetup) -> list[BodyBalance]:
    """F, M̄, m ā and dH̄/dt of every body, in the independent coordinates of the mode."""
    key = ("balances",)
    cache = setup.__dict__.setdefault("_law_cache", {})
    if key in cache:
        return cache[key]
    kin = setup.kin
    out = []
    for body in setup.system.bodies.values():
        F, M, _ = body_loads(setup, body)
        G = body.centre
        w = kin.omega_of(body)
        H = body.inertia.dot(w) if not body.is_massless else Vector(0)
        dH = dt(H, kin.F.ref) if Vector(0) != H else Vector(0)
        a = kin.acceleration(G) if not body.is_massless else Vector(0)
        out.append(BodyBalance(body, _ind(setup, F), _ind(setup, M), _ind(setup, body.mass * a),
                               _ind(setup, dH), _ind(setup, w), _ind(setup, kin.velocity(G))))
    cache[key] = out
    return out


def _ind(setup: ModeSetup, v):
    return setup.vector(v)


def equations(setup: ModeSetup) -> list[BalanceEquation]:
    """The scalar Newton–Euler equations of every body, recorded in the trace as they are formed."""
    kin, tr = setup.kin, setup.trace
    F = kin.F
    n_force = 2 if kin.planar else 3
    out = []
    for bal in body_balances(setup):
        b = bal.body
        apps = [app for app in setup.applications if app.body is b]    # body_loads' list, its sums not redone
        tr.add("Free-body diagram", f"Loads on {b.name}",
               LazyEquations(lambda apps=apps: [(sp.Symbol(a.label.replace(" ", "_")), _ind(setup, a.vector))
                                                for a in apps]),
               "every force and torque on the body; reactions are unknowns: "
               + (", ".join(str(a.reaction) for a in apps if a.reaction is not None) or "none") + ".")
        if not b.is_massless:
            tr.add("Inertia and momentum", f"Inertia and angular momentum of {b.name}",
                   LazyEquations(lambda b=b: [(sp.Symbol(f"I_{b.name}"), b.inertia),
                                              (sp.Symbol(f"H_{b.centre.name}"),
                                               _ind(setup, b.inertia.dot(kin.omega_of(b))))]),
                   f"{b.shape.kind} ({', '.join(f'{k} = {v}' for k, v in b.shape.dimensions.items())}); "
                   "H̄ = Ī·ω.")
        ref = "mass centre" if not b.is_massless else "reference point"
        # each vector resolved once into its components (the same products Vector.dot forms per axis)
        force, mass_accel = in_frame(bal.force, F.ref), in_frame(bal.mass_accel, F.ref)
        for i in range(n_force):
            out.append(BalanceEquation(f"Euler's 1st law for {b.name} along {F.basis[i]}", b.name,
                                       "newton-euler", setup.scalar(force[i]), setup.scalar(mass_accel[i])))
        # planar: the moment equation about Ez; in 3D along the body's own axes (Euler's equations)
        fr = F if kin.planar else b.frame
        moment, rate = in_frame(bal.moment, fr.ref), in_frame(bal.momentum_rate, fr.ref)
        for i in ((2,) if kin.planar else (0, 1, 2)):
            out.append(BalanceEquation(f"Euler's 2nd law for {b.name} about its {ref}, along {fr.basis[i]}",
                                       b.name, "newton-euler", setup.scalar(moment[i]), setup.scalar(rate[i])))
    kept = []
    for eq in out:
        if eq.expr == 0 or kin.is_zero(eq.expr):
            continue
        kept.append(eq)
    unknowns = {q.diff(t, 2) for q in setup.reduction.independent} | set(setup.reactions)
    for eq in kept:
        if not eq.expr.has(*unknowns) and not eq.expr.has(*[sc.symbol for sc in setup.sign_choices]):
            raise ModelError(
                f"{eq.label} reads {eq.lhs} = {eq.rhs}, which involves no unknown and does not hold: no "
                "reaction can carry this load component.", where=eq.body,
                hint="Add the constraint (and its reaction) that carries it, or check the load's direction.")
    for eq in kept:
        tr.add("Balance laws", eq.label,
               LazyEquations(lambda eq=eq: [(kin.simplify_expr(eq.lhs), kin.simplify_expr(eq.rhs))]),
               "F = m ā" if "1st" in eq.label else "M̄ = dH̄/dt (rate in the inertial frame)")
    return kept
