"""Euler's 2nd law about any point P, fixed or moving, on the body or not.

For a body of mass m with mass centre r̄:  M_P − (r̄ − r_P) × m a_P = d(H_P)/dt,
with H_P = H̄ + (r̄ − r_P) × m (v̄ − v_P).  The second term on the left is the inertial moment of
the acceleration of P; it vanishes when P is fixed (a_P = 0), when P is the mass centre, or when
r̄ − r_P is parallel to a_P — the law says which.  A reaction whose line of action passes through P
has no moment about P, so an equation about a pin or a rolling contact point may be free of
reactions: a single equation of motion.

P is a named point (its position, velocity and acceleration follow from its position vector; the
rate of H_P is taken by differentiating H_P in the inertial frame) or the point of a constraint: a
pin's point, a collar's point, a contact point.  At a contact, P is the *material point* of the body
that touches (its velocity v_P = v̄ + ω × (r_P − r̄), its acceleration from
``Kinematics.material_acceleration``); the geometric contact point moves along the body, so there
d(r̄ − r_P)/dt = v̄ − v_P and dH_P/dt = dH̄/dt + (r̄ − r_P) × m (ā − a_P).

The law is used with Euler's 1st law for every body (method ``about-point:P``).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ...base.errors import ModelError
from ...base.printing import text
from ...base.trace import LazyEquations
from ...base.vectorops import cross, dot_vectors, dt
from ..mode import ModeSetup
from .newton_euler import BalanceEquation, body_balances

t = dynamicsymbols._t

METHOD = "about-point"


@dataclass(frozen=True)
class Pole:
    """The point P the moments are taken about: position, velocity and acceleration from the origin."""

    name: str
    position: Vector
    velocity: Vector
    acceleration: Vector
    material: bool          # the material point of a body (a contact point): H_P's rate by the formula
    description: str


def _v(setup: ModeSetup, v: Vector) -> Vector:
    """A vector for the trace: in the independent coordinates, each component simplified."""
    if v == Vector(0):
        return v
    def tidy(e):
        e = setup.scalar(e)
        return setup.kin.simplify_expr(e) if sp.count_ops(e) <= 60 else e

    return Vector([(m.applyfunc(tidy), fr) for m, fr in v.args])


def pole(setup: ModeSetup, name: str) -> Pole:
    """Resolve ``name``: a point of the system or a constraint (pin, collar, contact)."""
    s, kin = setup.system, setup.kin
    if name in s.points and name not in s.constraints:
        p = s.points[name]
        return Pole(name, kin.position(p), kin.velocity(p), kin.acceleration(p), False, f"point {name}")
    if name in s.constraints:  # a constraint wins over a point of the same name (pin O, not the origin O)
        c = s.constraints[name]
        if c.kind in ("pin", "collar"):
            p = c.point
            also = (f"; '{name}' also names a point, which is not used here" if name in s.points
                    and s.points[name] is not p else "")
            return Pole(name, kin.position(p), kin.velocity(p), kin.acceleration(p), False,
                        f"point {p.name} of {c.kind} {name}{also}")
        if c.kind == "contact":
            loc = c.location(kin)
            return Pole(name, loc, kin.material_velocity(c.body, loc), kin.material_acceleration(c.body, loc), True,
                        f"the material point of {c.body.name} at contact {name}")
    raise ModelError(f"there is no point or constraint named '{name}' to take moments about.",
                     where=f"{METHOD} law",
                     hint=f"Points: {', '.join(s.points)}; constraints: {', '.join(s.constraints) or 'none'}.")


def _bodies(setup: ModeSetup, body) -> list[list]:
    s = setup.system
    if body is None:
        return [[b] for b in s.bodies.values()]
    names = [body] if isinstance(body, str) else list(body)
    out = []
    for n in names:
        if n not in s.bodies:
            raise ModelError(f"there is no body named '{n}'.", where=f"{METHOD} law",
                             hint=f"Bodies: {', '.join(s.bodies)}.")
        out.append(s.bodies[n])
    return [out]


def _moment_about(setup: ModeSetup, bodies, rP: Vector) -> tuple[Vector, list]:
    kin = setup.kin
    M, through = Vector(0), []
    for app in setup.applications:
        if app.body not in bodies:
            continue
        if app.is_torque:
            M += app.vector
            continue
        loc = app.location if app.location is not None else kin.position(app.point)
        arm = setup.vector(loc - rP)
        moment = cross(arm, app.vector)
        M += moment
        if app.reaction is not None and kin.is_zero_vector(moment):
            through.append(app.reaction)
    return M, through


def _vanishes(setup: ModeSetup, P: Pole, d: Vector, maP: Vector, massless: bool) -> tuple[bool, str]:
    """Whether the inertial moment −(r̄ − r_P) × m a_P vanishes, and why."""
    kin = setup.kin
    zero = kin.is_zero_vector(setup.vector(cross(d, maP)))
    if massless:
        return True, "the body is massless."
    if kin.is_zero_vector(setup.vector(P.acceleration)):
        if kin.is_zero_vector(setup.vector(P.velocity)):
            return True, f"P ({P.description}) is fixed: a_P = 0."
        return True, f"P ({P.description}) moves with constant velocity: a_P = 0."
    if kin.is_zero_vector(setup.vector(d)):
        return True, "P is the mass centre: r̄ − r_P = 0."
    if zero:
        return True, (f"r̄ − r_P is parallel to a_P = {text(_v(setup, P.acceleration))}, so their cross "
                      "product vanishes although P accelerates.")
    return False, (f"P ({P.description}) accelerates (a_P = {text(_v(setup, P.acceleration))}) and r̄ − r_P is "
                   "not parallel to a_P: the inertial moment stays in the equation.")


def equations(setup: ModeSetup, point: str, body=None) -> list[BalanceEquation]:
    """Euler's 1st law for every body and the 2nd law about ``point`` for each body (or for ``body``)."""
    kin, tr = setup.kin, setup.trace
    F = kin.F
    P = pole(setup, point)
    planar = kin.planar
    force_dirs = [(F.x, F.basis[0]), (F.y, F.basis[1])] + ([] if planar else [(F.z, F.basis[2])])
    moment_dirs = [(F.z, F.basis[2])] if planar else [(F.x, F.basis[0]), (F.y, F.basis[1]), (F.z, F.basis[2])]
    tr.add("Kinematics", f"The point P = {point}",
           LazyEquations(lambda: [(sp.Symbol("r_P"), _v(setup, P.position)),
                                  (sp.Symbol("v_P"), _v(setup, P.velocity)),
                                  (sp.Symbol("a_P"), _v(setup, P.acceleration))]),
           f"P is {P.description}." + (" At a contact the velocity and acceleration are those of the material "
                                       "point of the body there (not of the geometric contact point)."
                                       if P.material else ""))
    balances = {b.body.name: b for b in body_balances(setup)}
    out = []
    for bal in balances.values():
        for e, name in force_dirs:
            lhs = setup.scalar(dot_vectors(bal.force, e))
            rhs = setup.scalar(dot_vectors(bal.mass_accel, e))
            out.append(BalanceEquation(f"Euler's 1st law for {bal.body.name} along {name}", bal.body.name,
                                       METHOD, lhs, rhs))
    for group in _bodies(setup, body):
        label = " + ".join(b.name for b in group)
        M, through = _moment_about(setup, group, P.position)
        inertial, dHP, massless = Vector(0), Vector(0), True
        for b in group:
            if b.is_massless:
                continue
            massless = False
            m, G = b.mass, b.centre
            d = kin.position(G) - P.position
            vG, aG = kin.velocity(G), kin.acceleration(G)
            w = kin.omega_of(b)
            Hbar = b.inertia.dot(w)
            maP = m * P.acceleration
            inertial += -cross(d, maP)
            if P.material:
                dHP += dt(Hbar, F.ref) + cross(d, m * (aG - P.acceleration))
                how = "dH_P/dt = dH̄/dt + (r̄ − r_P) × m (ā − a_P) for the material point P."
            else:
                HP = Hbar + cross(d, m * (vG - P.velocity))
                dHP += dt(HP, F.ref)
                how = "H_P = H̄ + (r̄ − r_P) × m (v̄ − v_P), differentiated in the inertial frame."
                tr.add("Inertia and momentum", f"Angular momentum of {b.name} about {point}",
                       LazyEquations(lambda HP=HP: [(sp.Symbol(f"H_{point}"), _v(setup, HP))]), how)
            gone, why = _vanishes(setup, P, d, maP, False)
            tr.add("Balance laws", f"Inertial moment of {b.name} about {point}",
                   LazyEquations(lambda d=d, maP=maP: [(sp.Symbol("-(r̄ − r_P) × m a_P"), _v(setup, -d.cross(maP)))]),
                   ("It vanishes: " if gone else "") + why)
        if massless:
            tr.add("Balance laws", f"{label} is massless", [], "its moments about P balance: M_P = 0.")
        tr.add("Free-body diagram", f"Moment about {point} of the loads on {label}",
               LazyEquations(lambda M=M: [(sp.Symbol(f"M_{point}"), _v(setup, M))]),
               "reactions whose line of action passes through P have no moment about it"
               + (f": {', '.join(map(str, sorted(set(through), key=str)))}." if through else "."))
        for e, name in moment_dirs:
            lhs = _without_vanishing(setup, setup.scalar(dot_vectors(M + inertial, e)))
            rhs = setup.scalar(dot_vectors(dHP, e)) if dHP != Vector(0) else sp.Integer(0)
            out.append(BalanceEquation(f"Euler's 2nd law for {label} about {point}, along {name}", label,
                                       METHOD, lhs, rhs))
    kept = [eq for eq in out if not (eq.expr == 0 or kin.is_zero(eq.expr))]
    reactions = set(setup.reactions)
    for eq in kept:
        free = not any(eq.expr.has(r) for r in reactions)
        tr.add("Balance laws", eq.label,
               LazyEquations(lambda eq=eq: [(kin.simplify_expr(eq.lhs), kin.simplify_expr(eq.rhs))]),
               ("F = m ā" if "1st" in eq.label else "M_P − (r̄ − r_P) × m a_P = dH_P/dt")
               + ("; no reaction appears: this equation alone is an equation of motion."
                  if free and "2nd" in eq.label else ""))
    return kept


def _without_vanishing(setup: ModeSetup, moment: sp.Expr) -> sp.Expr:
    """A moment component as derived (not simplified: the equations are solved and compared as derived,
    and simplified for reading only in the trace), less the reactions whose coefficient simplifies to 0
    (a reaction through P: its arm × its direction cancels only after simplification)."""
    kin = setup.kin
    gone = {}
    for r in setup.reactions:
        if not moment.has(r):
            continue
        c = moment.diff(r)
        if c == 0 or (kin.is_zero(c) and kin.simplify_expr(c) == 0):
            gone[r] = sp.Integer(0)
    return moment.xreplace(gone) if gone else moment


def reaction_free(setup: ModeSetup, eqs) -> list[BalanceEquation]:
    """The 2nd-law equations about P that contain no reaction (each one an equation of motion)."""
    reactions = set(setup.reactions)
    accels = [q.diff(t, 2) for q in setup.reduction.independent]
    return [eq for eq in eqs if "2nd" in eq.label and not any(eq.expr.has(r) for r in reactions)
            and eq.expr.has(*accels)]
