"""Energy: kinetic and potential energy, the power of non-conservative loads, and the work–energy law.

T = Σ ½ m v̄·v̄ + ½ H̄·ω over the bodies; U = Σ of the potentials of the conservative loads (gravity
−m g r̄·e_g, springs K (ℓ − ℓ0)²/2, torsional springs K (θ − θ0)²/2).  Every other load and every
reaction has a power F·v_P (at the material point where it acts) or τ·ω; a reaction whose constraint
velocity vanishes does no work (a rolling contact: the contact point of the body does not move
relative to the surface; a smooth normal force: it is perpendicular to the contact point's velocity).

The work–energy law dE/dt = Σ P_nc (E = T + U) is one scalar equation: for a system with one degree
of freedom and scleronomic constraints it is q̇ times the equation of motion, so dividing by q̇ gives
the EOM (method ``work-energy``).  ``energy_balance`` applies the integrated form
E(end) = E(start) between two states of a conservative motion.

All expressions are in the independent coordinates of the mode (``ModeSetup.scalar``).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ...base import algebra
from ...base.errors import RigidkinError
from ...base.printing import text
from ..mode import ModeSetup, setup_mode
from .methods import NotApplicable
from .newton_euler import BalanceEquation

t = dynamicsymbols._t

METHOD = "work-energy"


@dataclass(frozen=True)
class Power:
    """The power of one non-conservative load or one constraint's reactions on the system."""

    name: str
    power: sp.Expr
    why: str
    kind: str            # "load" or "constraint"

    @property
    def is_zero(self) -> bool:
        return self.power == 0

    def __iter__(self):  # unpack as (name, power, why)
        return iter((self.name, self.power, self.why))


def _cache(setup: ModeSetup) -> dict:
    return setup.__dict__.setdefault("_law_cache", {})


def _note(setup: ModeSetup, section: str, title: str, equations, why: str) -> None:
    """Record a step once in the setup's current trace (values are cached, the trace may change)."""
    if any(st.title == title and st.section == section for st in setup.trace.steps):
        return
    setup.trace.add(section, title, equations, why)


# ---------------------------------------------------------------------------------------------------
def kinetic_energies(setup: ModeSetup) -> list[tuple[str, sp.Expr]]:
    """(body name, T_body) with T_body = ½ m v̄·v̄ + ½ ω·Ī·ω, in the independent coordinates."""
    key = ("energy", "T")
    cache = _cache(setup)
    if key not in cache:
        cache[key] = _kinetic(setup)
    for name, T in cache[key]:
        _note(setup, "Inertia and momentum", f"Kinetic energy of {name}", [(sp.Symbol(f"T_{name}"), T)],
              "T = ½ m v̄·v̄ + ½ H̄·ω with H̄ = Ī·ω.")
    return cache[key]


def _kinetic(setup: ModeSetup) -> list:
    kin, out = setup.kin, []
    for body in setup.system.bodies.values():
        if body.is_massless:
            continue
        v = kin.velocity(body.centre)
        w = kin.omega_of(body)
        T = body.mass * v.dot(v) / 2 + (w.dot(body.inertia.dot(w)) / 2 if w != Vector(0) else 0)
        T = kin.simplify_expr(setup.scalar(T))
        out.append((body.name, T))
    return out


def kinetic_energy(setup: ModeSetup) -> sp.Expr:
    """The kinetic energy T of all bodies, in the independent coordinates of the mode."""
    return sum((T for _, T in kinetic_energies(setup)), sp.Integer(0))


def potentials(setup: ModeSetup) -> list[tuple[str, sp.Expr]]:
    """(load name, U_load) for every conservative load (gravity, springs), in the independent coordinates."""
    key = ("energy", "U")
    cache = _cache(setup)
    if key not in cache:
        cache[key] = _potentials(setup)
    for name, U, why in cache[key]:
        _note(setup, "Inertia and momentum", f"Potential energy of {name}", [(sp.Symbol(f"U_{name}"), U)], why)
    return [(name, U) for name, U, _ in cache[key]]


def _potentials(setup: ModeSetup) -> list:
    kin, out = setup.kin, []
    for ld in setup.loads:
        if not getattr(ld, "conservative", False):
            continue
        U = ld.potential(kin)
        if U is None:
            continue
        U = kin.simplify_expr(setup.scalar(U))
        why = {"gravity": "U = −m g r̄·e_g for each body (zero at the origin).",
               "spring": "U = K (ℓ − ℓ0)²/2 with ℓ the distance between the ends.",
               "torsional spring": "U = K (θ − θ0)²/2."}.get(ld.kind, "potential of a conservative load.")
        out.append((ld.name, U, why))
    return out


def potential_energy(setup: ModeSetup) -> sp.Expr:
    """The potential energy U of gravity and springs, in the independent coordinates of the mode."""
    return sum((U for _, U in potentials(setup)), sp.Integer(0))


def _application_power(setup: ModeSetup, app) -> sp.Expr:
    kin = setup.kin
    if app.is_torque:
        return app.vector.dot(kin.omega_of(app.body))
    loc = app.location if app.location is not None else kin.position(app.point)
    return app.vector.dot(kin.material_velocity(app.body, loc))


def _constraint_why(setup: ModeSetup, constraint, zero: bool) -> str:
    kind = getattr(constraint, "kind", "constraint")
    state = setup.states.get(constraint.name)
    if not zero:
        return (f"the reactions of {kind} {constraint.name} do work: the surface or part they act through "
                "moves, so the point where they act has a velocity along them.")
    if kind == "contact" and state == "stick":
        return ("rolling contact: the contact point of the body does not move relative to the surface "
                "(v_P = 0), so the normal and friction reactions do no work.")
    if kind == "contact":
        return ("smooth normal reaction: it is perpendicular to the velocity of the contact point, so it does "
                "no work (the sliding friction, if any, is listed separately).")
    if kind == "pin":
        return ("pin reactions: the pinned point does not move, or the equal and opposite reactions on the two "
                "bodies act at points with the same velocity; no net work.")
    if kind == "collar":
        return ("collar: the track's normal force is perpendicular to the sliding, and its couple acts on a "
                "collar that does not turn relative to the track; no work.")
    return "workless: the constraint makes the velocity along each of its reactions zero."


def _load_why(ld, zero: bool) -> str:
    kind = getattr(ld, "kind", "load")
    if kind == "sliding friction":
        return ("sliding friction: P = F_f·v_rel ≤ 0 against a fixed surface (−µ|N||v_slip|); energy is "
                "dissipated." if not zero else "sliding friction with no slip speed in this mode: no work.")
    if kind == "damper":
        return "damper: P = f(v) v, dissipated for a damping law."
    if kind == "torque":
        return "applied torque: P = τ·ω."
    if kind == "force":
        return "applied force: P = F·v of the point where it acts." + (" Zero here." if zero else "")
    return f"{kind}: P = F·v." + (" Zero here." if zero else "")


def nonconservative_power(setup: ModeSetup) -> list[Power]:
    """The power of every non-conservative load and of every constraint's reactions, with the reason.

    Each item unpacks as (name, power, why); constraints whose reactions do no work (rolling contacts,
    smooth normal reactions, pins, collars) have power 0 and say why.
    """
    key = ("energy", "Pnc")
    cache = _cache(setup)
    if key not in cache:
        cache[key] = _powers(setup)
    for p in cache[key]:
        title = f"Power of the reactions of {p.name}" if p.kind == "constraint" else f"Power of {p.name}"
        _note(setup, "Free-body diagram", title, [(sp.Symbol(f"P_{p.name}"), p.power)], p.why)
    return cache[key]


def _powers(setup: ModeSetup) -> list[Power]:
    kin = setup.kin
    by_source: dict[tuple, sp.Expr] = {}
    order: list[tuple] = []
    constraint_sources = set(setup.system.constraints)
    load_sources = {ld.name: ld for ld in setup.loads}
    for app in setup.applications:
        src = app.source
        if src in load_sources and getattr(load_sources[src], "conservative", False):
            continue
        kind = "constraint" if app.reaction is not None else "load"
        label = (kind, src)
        if label not in by_source:
            by_source[label] = sp.Integer(0)
            order.append(label)
        by_source[label] += _application_power(setup, app)
    out = []
    for label in order:
        kind, src = label
        P = kin.simplify_expr(setup.scalar(by_source[label]))
        zero = P == 0 or kin.is_zero(P)
        if zero:
            P = sp.Integer(0)
        if kind == "constraint" and src in constraint_sources:
            why = _constraint_why(setup, setup.system.constraints[src], zero)
        elif src in load_sources:
            why = _load_why(load_sources[src], zero)
        else:
            why = "power F·v."
        out.append(Power(src, P, why, kind))
    return out


def energy(system, mode: dict | None = None, substitutions: dict | None = None) -> sp.Expr:
    """The total mechanical energy E = T + U of ``system`` in ``mode``, in its independent coordinates."""
    setup = setup_mode(system, mode, None, substitutions)
    return kinetic_energy(setup) + potential_energy(setup)


def first_integral(system, mode: dict | None = None, substitutions: dict | None = None) -> sp.Expr:
    """E = T + U, constant along every motion when no load or reaction does work (any number of DOF)."""
    setup = setup_mode(system, mode, None, substitutions)
    working = [p for p in nonconservative_power(setup) if p.power != 0]
    if working:
        raise NotApplicable("energy is not a first integral here: "
                            + "; ".join(f"{p.name} has power {text(p.power)}" for p in working) + ".",
                            where=system.name, hint="The work–energy law dE/dt = ΣP_nc still holds.")
    E = kinetic_energy(setup) + potential_energy(setup)
    if algebra.plain_state(E)[0].has(t):
        raise NotApplicable("energy depends explicitly on time (a frame, point or load driven by a law in t), "
                            "so it is not conserved.",
                            where=system.name)
    setup.trace.add("Answers", "Energy integral", [(sp.Symbol("E"), E)],
                    "every non-conservative power is zero, so dE/dt = 0: E = T + U is constant.")
    return E


# work–energy law ----------------------------------------------------------------------------------
def _unknown_reactions(expr, setup) -> list:
    return [r for r in setup.reactions if expr.has(r)]


def equations(setup: ModeSetup) -> list[BalanceEquation]:
    """dE/dt = Σ P_nc, divided by q̇ (one degree of freedom): the equation of motion."""
    red, kin, tr = setup.reduction, setup.kin, setup.trace
    if len(red.independent) != 1:
        raise NotApplicable(f"the work–energy law is one scalar equation, but this mode has {len(red.independent)} "
                            "degrees of freedom, so it cannot give all the equations of motion.",
                            where=setup.system.name, hint="Use newton-euler, lagrange or kane; energy is still a "
                                                         "check (rigidkin check).")
    (q,) = red.independent
    u = q.diff(t)
    T, U = kinetic_energy(setup), potential_energy(setup)
    powers = nonconservative_power(setup)
    P = sum((p.power for p in powers), sp.Integer(0))
    bad = _unknown_reactions(P, setup)
    if bad:
        names = ", ".join(p.name for p in powers if _unknown_reactions(p.power, setup))
        raise NotApplicable(f"the power of {names} involves the reaction(s) {', '.join(map(str, bad))}, which the "
                            "work–energy law alone does not determine.", where=setup.system.name,
                            hint="Use Euler's laws (newton-euler) for this mode.")
    E = T + U
    dE = sp.diff(E, t)
    tr.add("Balance laws", "Mechanical energy", [(sp.Symbol("E"), E)], "E = T + U.")
    tr.add("Balance laws", "Work–energy law", [(sp.Derivative(sp.Symbol("E"), t), P)],
           "the rate of change of the mechanical energy equals the power of the non-conservative loads "
           "and reactions: dE/dt = Σ F_nc·v + τ_nc·ω.")
    expr = red.reduce(dE - P)            # the dependent rates and accelerations in terms of q̇, q̈
    plain, back = algebra.plain_state(expr, [q])
    fwd = {v: k for k, v in back.items()}
    s = fwd.get(u)
    if s is None:
        raise NotApplicable("the energy balance does not involve the rate of the coordinate.", where=setup.system.name)
    rest = plain.xreplace({s: 0})
    if not algebra.is_zero(rest):
        raise NotApplicable(f"the energy balance has terms that do not vanish with {text(u)}: {_cause(rest, back)}, "
                            f"so it is not {text(u)} times the equation of motion.", where=setup.system.name,
                            hint="Use newton-euler.")
    acc = q.diff(t, 2)
    if sp.count_ops(plain) <= algebra.SIMPLIFY_LIMIT:
        row = sp.cancel(sp.expand(plain) / s)
        if sp.denom(sp.together(row)).has(s):
            raise NotApplicable("the energy balance is not q̇ times an equation of motion (its power is not "
                                "proportional to q̇).", where=setup.system.name)
        row = sp.expand(row.xreplace(back))
        c = row.coeff(acc)
        lhs = -(row - c * acc)
    else:
        c, lhs = _divided_by_rate(plain, s, fwd.get(acc), back, setup)
    if c == 0:
        raise NotApplicable("the energy balance does not involve the acceleration.", where=setup.system.name)
    lhs, rhs = lhs, kin.simplify_expr(c) * acc
    eq = BalanceEquation(f"work–energy: dE/dt = ΣP_nc, divided by {text(u)}", "system", METHOD,
                            kin.simplify_expr(lhs), rhs)
    tr.add("Balance laws", "Equation of motion from the work–energy law", [(eq.lhs, eq.rhs)],
           f"dE/dt − ΣP_nc = {text(u)}·(equation of motion) for one degree of freedom; divided by {text(u)}.")
    return [eq]


def _divided_by_rate(plain, s, a, back, setup):
    """(coefficient of q̈, the rest) of (dE/dt − ΣP_nc)/q̇ without expanding a large expression: the
    balance is a cubic in q̇ with no constant term (T is quadratic in the rates), so its quotient by q̇
    is Σ c_k q̇^(k−1), c_k = (∂^k/∂q̇^k at q̇ = 0)/k! — checked at random states."""
    coeffs, d = [], plain
    for k in (1, 2, 3):
        d = sp.diff(d, s)
        coeffs.append(d.xreplace({s: 0}) / sp.factorial(k))
    row = sum((c * s ** k for k, c in enumerate(coeffs)), sp.Integer(0))
    if not algebra.is_zero(plain - s * row):
        raise NotApplicable("the energy balance is not q̇ times an equation of motion (its power is not "
                            "proportional to q̇).", where=setup.system.name)
    if a is None:
        return sp.Integer(0), row.xreplace(back)
    c = sp.diff(row, a)
    if c != 0 and not algebra.is_zero(sp.diff(c, a)):
        raise NotApplicable("the energy balance is not linear in the acceleration.", where=setup.system.name)
    return c.xreplace(back), -row.xreplace({a: 0}).xreplace(back)


def _cause(rest, back) -> str:
    """What keeps power flowing at rest: a driving law (explicit t), or the terms themselves."""
    if rest.has(t):
        return "the constraints or loads depend on t explicitly (a driven motion or moving support does work)"
    left = rest.xreplace(back)
    shown = text(left) if sp.count_ops(left) < 60 else "a power that does not vanish at rest"
    return f"{shown} remains at rest (a load whose power is not proportional to the rate)"


def energy_balance(system, start: dict, end: dict, unknowns, mode: dict | None = None,
                   substitutions: dict | None = None, conserved: list | None = None, choose=None):
    """Solve E(end) = E(start), and Q(end) = Q(start) for each ``conserved`` Q(q, q̇), for ``unknowns``.

    ``start`` and ``end`` map coordinates and rates (q, q̇, of any coordinate) to values; ``unknowns``
    are among the ``end`` quantities (a coordinate or a rate).  Every non-conservative power must be
    zero in the mode.  Returns a dict unknown → value; where the balance is quadratic, the root is
    chosen by ``choose`` (a callable on the list of roots) or the positive one.
    """
    setup = setup_mode(system, mode, None, substitutions)
    tr = setup.trace
    working = [p for p in nonconservative_power(setup) if p.power != 0]
    if working:
        raise RigidkinError("energy is not conserved in this mode: "
                            + "; ".join(f"{p.name} has power {text(p.power)}" for p in working) + ".",
                            hint="Use the work–energy law with the work of these loads, or impulse–momentum.")
    E = kinetic_energy(setup) + potential_energy(setup)
    unknowns = list(unknowns) if isinstance(unknowns, (list, tuple)) else [unknowns]
    dummies = {u: sp.Dummy(str(u)) for u in unknowns}
    E0, E1 = _at_state(E, start, setup), _at_state(E, end, setup, dummies)
    eqs = [sp.Eq(E1, E0)]
    for Q in conserved or []:
        Q = getattr(Q, "expr", Q)
        eqs.append(sp.Eq(_at_state(Q, end, setup, dummies), _at_state(Q, start, setup)))
    sols = sp.solve(eqs, list(dummies.values()), dict=True)
    if not sols:
        raise RigidkinError("the energy balance has no solution for " + ", ".join(map(text, unknowns)) + ".",
                            hint="The end state may be out of reach with this energy.")
    back = {v: k for k, v in dummies.items()}
    sols = [{back[k]: algebra.readable(v) for k, v in s.items()} for s in sols]
    if choose is not None:
        sol = choose(sols)
    else:
        sol = _positive(sols, setup)
    tr.add("Answers", "Energy balance", [(E1.xreplace(back), E0)] + [(k, v) for k, v in sol.items()],
           "E = T + U is conserved: every non-conservative power is zero in this mode.")
    return sol


def _at_state(E, state: dict, setup, dummies: dict | None = None) -> sp.Expr:
    """E at ``state``: its rates, then the unknowns (as dummies), then its coordinates substituted."""
    rates = {k: sp.sympify(v) for k, v in state.items() if isinstance(k, sp.Derivative)}
    coords = {k: sp.sympify(v) for k, v in state.items() if not isinstance(k, sp.Derivative)}
    e = E.xreplace(rates)
    if dummies:
        e = e.xreplace({k: v for k, v in dummies.items() if isinstance(k, sp.Derivative)})
        e = e.xreplace({k: v for k, v in dummies.items() if not isinstance(k, sp.Derivative)})
    e = e.xreplace(coords)
    left = algebra.functions_of_time(e) | {d for d in e.atoms(sp.Derivative)}
    if left:
        raise RigidkinError("the state leaves " + ", ".join(map(text, left)) + " unknown in the energy.",
                            hint="Give every coordinate and rate of the start and end states.")
    return e


def _positive(sols, setup):
    ref = setup.kin.reference_values()
    best = []
    for s in sols:
        ok = True
        for v in s.values():
            if v.is_negative or (v.is_real is False):
                ok = False
                break
            try:
                val = complex(sp.sympify(v).xreplace({k: sp.Float(x) for k, x in ref.items()}).evalf())
            except (TypeError, ValueError):
                continue
            if abs(val.imag) > 1e-12 or val.real < 0:
                ok = False
        if ok:
            best.append(s)
    if len(best) != 1:
        raise RigidkinError(f"the energy balance has {len(sols)} solutions and {len(best)} of them are "
                            "non-negative, so the answer is ambiguous.", hint="Pass choose= to pick a root.")
    return best[0]
