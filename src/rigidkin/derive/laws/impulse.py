"""Impulse–momentum: linear and angular, for impulsive loads and for constant forces over an interval.

For each body, F̂ = m (v̄′ − v̄) and M̂_G = H̄′ − H̄ (H̄ = Ī·ω), the impulses summed over the free-body
diagram.

* ``impulsive``: impulses F̂ (``System.impulse``) act during an instant.  The configuration does not
  change, finite forces (gravity, springs) give no impulse, and the constraints of the mode hold
  before and after, carried by unknown reaction impulses (a pin's R̂).  Unknowns: the independent
  rates just after and the reaction impulses, from the linear equations of every body.
* ``interval``: in one regime of the mode (the direction of sliding friction fixed) the forces are
  constant — the reactions from Euler's 1st law (the normal force N = m g cos β) and the friction
  µN with its sign — so the impulses over Δt are F Δt and M̄ Δt.  Given the duration, the rates at
  the end follow; given an end condition (a slip speed reaching zero), the time it takes as well.
  The law refuses, with the reason, when a force is not constant or the momentum depends on the
  configuration (which changes during the interval).
* ``conserved_momenta``: the momentum components whose force or moment is zero in a mode.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ...base import algebra
from ...base.errors import ModelError, RigidkinError
from ...base.printing import text
from ...base.trace import Trace
from ..kinematics import linear_form
from ..mode import ModeSetup, setup_mode
from . import solve_with

t = dynamicsymbols._t


@dataclass(frozen=True)
class ImpulseResult:
    """Rates after an impulse or at the end of an interval, reaction impulses, and the interval's length."""

    rates: Mapping                      # q̇ (independent and dependent) → value after / at the end
    reaction_impulses: Mapping          # reaction name + "_hat" → impulse (impulsive loads)
    duration: sp.Expr | None            # Δt (given, or found from the end condition)
    conditions: tuple                   # (expression, relation, description): where the answer holds
    equations: tuple                    # (lhs, rhs, label) impulse–momentum equations
    trace: Trace = field(compare=False)

    def rate(self, q) -> sp.Expr:
        """The rate of coordinate ``q`` (a dynamicsymbol) after / at the end."""
        return self.rates[q.diff(t)] if not isinstance(q, sp.Derivative) else self.rates[q]


@dataclass(frozen=True)
class Momentum:
    """A component of a body's linear momentum m v̄·e or angular momentum H̄·e (a function of the state)."""

    label: str
    expr: sp.Expr


def _dirs(setup):
    F = setup.kin.F
    force = [(F.x, F.basis[0]), (F.y, F.basis[1])] + ([] if setup.kin.planar else [(F.z, F.basis[2])])
    moment = [(F.z, F.basis[2])] if setup.kin.planar else [(F.x, F.basis[0]), (F.y, F.basis[1]),
                                                           (F.z, F.basis[2])]
    return force, moment


def momenta(setup: ModeSetup) -> list[tuple]:
    """(body, label, direction kind, expr) for m v̄·e and H̄·e of each body, in the independent rates."""
    kin = setup.kin
    force, moment = _dirs(setup)
    out = []
    for b in setup.system.bodies.values():
        if b.is_massless:
            continue
        p = b.mass * kin.velocity(b.centre)
        H = b.inertia.dot(kin.omega_of(b))
        for e, name in force:
            out.append((b, f"linear momentum of {b.name} along {name}", "force",
                        kin.simplify_expr(setup.scalar(p.dot(e))), e))
        for e, name in moment:
            out.append((b, f"angular momentum of {b.name} about its mass centre, along {name}", "moment",
                        kin.simplify_expr(setup.scalar(H.dot(e))) if Vector(0) != H else sp.Integer(0), e))
    return out


def _resultants(setup: ModeSetup, body, apps, replace=None):
    """Resultant of ``apps`` on ``body`` and its moment about the body's mass centre (or reference)."""
    kin = setup.kin
    rG = kin.position(body.centre)
    Fr, M = Vector(0), Vector(0)
    for app in apps:
        if app.body is not body:
            continue
        vec = app.vector if replace is None else Vector([(m.xreplace(replace), fr) for m, fr in app.vector.args]) \
            if app.vector != Vector(0) else app.vector
        if app.is_torque:
            M += vec
        else:
            loc = app.location if app.location is not None else kin.position(app.point)
            Fr += vec
            M += (loc - rG).cross(vec)
    return Fr, M


def _state_values(state: Mapping | None, system) -> dict:
    return {k: sp.sympify(v) for k, v in (state or {}).items()}


def _after_symbols(setup):
    return {q.diff(t): sp.Symbol(f"{q.func.__name__}_dot_after", real=True) for q in setup.reduction.independent}


def _solve_linear(eqs, unknowns, what: str, where: str):
    A, b = linear_form(eqs, unknowns)
    sol = sp.linsolve((A, -b), unknowns)
    if not sol:
        raise ModelError(f"the impulse–momentum equations for {what} are inconsistent.", where=where,
                         hint="A constraint that would carry the impulse is missing.")
    (vals,) = list(sol)
    free = set().union(*[sp.sympify(v).free_symbols for v in vals]) & set(unknowns)
    if free:
        raise ModelError(f"the impulse–momentum equations do not determine {', '.join(map(str, free))}.",
                         where=where, hint="The impulse problem is indeterminate (redundant supports).")
    return dict(zip(unknowns, vals))


def impulsive(system, mode: dict | None = None, before: Mapping | None = None, at: Mapping | None = None,
              substitutions: dict | None = None) -> ImpulseResult:
    """Rates just after the system's impulses, and the reaction impulses of the constraints.

    ``before``: rates just before (q̇ → value; default: the declared initial rates, else the symbols);
    ``at``: the configuration at the instant (q → value; default: symbolic).
    """
    setup = setup_mode(system, mode, None, substitutions)
    kin, red = setup.kin, setup.reduction
    tr = Trace(law="impulse-momentum")
    impulses = []
    for ld in system.loads.values():
        if getattr(ld, "kind", "") == "impulse":
            impulses.extend(ld.impulses(kin))
    if not impulses:
        raise ModelError("the system has no impulse load.", where=system.name,
                         hint="Add one with System.impulse(name, point, vector).")
    hats = {row.reaction: sp.Symbol(f"{row.reaction.name}_hat", real=True) for row in setup.rows}
    reaction_apps = [a for row in setup.rows for a in row.applications]
    tr.add("Free-body diagram", "Impulses", [(sp.Symbol(a.label.replace(" ", "_")), a.vector) for a in impulses],
           "during the instant only impulsive loads and the constraints' reaction impulses "
           + (", ".join(map(str, hats.values())) or "(none)")
           + " act; finite forces (gravity, springs) give no impulse, and the configuration does not change.")
    after = _after_symbols(setup)
    pre = _state_values(before, system)
    for q in red.independent:
        if q.diff(t) not in pre:
            info = system.coordinate_of(q)
            pre[q.diff(t)] = sp.nsimplify(info.rate) if info.rate is not None else q.diff(t)
    conf = _state_values(at, system)
    force, moment = _dirs(setup)
    eqs, labels = [], []
    for b in system.bodies.values():
        Fh, Mh = _resultants(setup, b, impulses)
        Rf, Rm = _resultants(setup, b, reaction_apps, hats)
        Fh, Mh = Fh + Rf, Mh + Rm
        p = b.mass * kin.velocity(b.centre) if not b.is_massless else Vector(0)
        H = b.inertia.dot(kin.omega_of(b)) if not b.is_massless else Vector(0)
        for (e, name), kind in [(d, "force") for d in force] + [(d, "moment") for d in moment]:
            imp = (Fh if kind == "force" else Mh).dot(e)
            mom = (p if kind == "force" else H).dot(e) if (p if kind == "force" else H) != Vector(0) else 0
            mom = setup.scalar(sp.sympify(mom))
            lhs = kin.simplify_expr(setup.scalar(imp)).xreplace(conf) if conf else kin.simplify_expr(setup.scalar(imp))
            change = mom.xreplace(after) - mom.xreplace(pre)
            rhs = kin.simplify_expr(change.xreplace(conf) if conf else change)
            if lhs == 0 and rhs == 0:
                continue
            what = ("linear impulse on" if kind == "force" else "angular impulse about the mass centre of")
            label = f"{what} {b.name} along {name}"
            eqs.append(lhs - rhs)
            labels.append((lhs, rhs, label))
            tr.add("Balance laws", label.capitalize(), [(lhs, rhs)],
                   "F̂ = m (v̄′ − v̄)" if kind == "force" else "M̂_G = H̄′ − H̄ (H̄ = Ī·ω)")
    unknowns = list(after.values()) + [h for h in hats.values() if any(e.has(h) for e in eqs)]
    sol = _solve_linear(eqs, unknowns, "the velocities just after", system.name)
    sol = {k: kin.simplify_expr(v) for k, v in sol.items()}
    rates = {}
    for qd, sym in after.items():
        rates[qd] = sol[sym]
    for qd, expr in red.rate_map.items():
        e = setup.scalar(expr).xreplace(rates)
        rates[qd] = kin.simplify_expr(e.xreplace(conf) if conf else e)
    reacts = {str(h): sol.get(h, sp.Integer(0)) for h in hats.values()}
    conds = []
    for sym, row in setup.unilateral:
        h = hats[sym]
        if str(h) in reacts:
            conds.append((reacts[str(h)], ">=", f"{row.constraint} pushes during the impulse (else it opens)"))
    tr.add("Answers", "Rates just after the impulse", [(sp.Symbol(f"{text(k)}′"), v) for k, v in rates.items()],
           "all unknowns solved from the impulse–momentum equations at once.")
    if reacts:
        tr.add("Answers", "Reaction impulses", [(sp.Symbol(k), v) for k, v in reacts.items()],
               "the impulses the constraints give so that they still hold just after.")
    return ImpulseResult(MappingProxyType(rates), MappingProxyType(reacts), None, tuple(conds), tuple(labels), tr)


# ---------------------------------------------------------------------------------------------------
def _regime_at(sol, start: dict, values: dict):
    """The regime of ``sol`` whose sign conditions hold at the start state."""
    if len(sol.regimes) == 1:
        return sol.regimes[0]
    for r in sol.regimes:
        ok = True
        for c in r.conditions:
            v = sp.sympify(c.expr).xreplace(start)
            v = v.xreplace({k: v2 for k, v2 in start.items() if not isinstance(k, sp.Derivative)})
            sign = _sign(v, values)
            if sign is None:
                raise RigidkinError(f"the sign of {text(c.expr)} ({c.label}) at the start cannot be decided.",
                                    hint="Give numeric start values, parameter values, or regime=INDEX.")
            if not {">": sign > 0, "<": sign < 0, ">=": sign >= 0, "<=": sign <= 0}[c.relation]:
                ok = False
        if ok:
            return r
    raise RigidkinError("no regime's conditions hold at the start (a slip speed is zero there?).",
                        hint="Start in a state where the contact slips, or use the rolling mode.")


def _sign(v, values) -> int | None:
    v = sp.sympify(v)
    if v.is_positive:
        return 1
    if v.is_negative:
        return -1
    if v.is_zero:
        return 0
    try:
        x = float(v.xreplace({k: sp.Float(w) for k, w in values.items()}))
    except (TypeError, ValueError):
        return None
    return 1 if x > 0 else -1 if x < 0 else 0


def interval(system, start: Mapping, duration=None, until=None, mode: dict | None = None,
             substitutions: dict | None = None, regime: int | None = None) -> ImpulseResult:
    """Rates at the end of an interval of constant forces, and its length when ``until`` is given.

    ``start`` maps rates (and coordinates, if needed) to their values at the start; ``duration`` is the
    interval's length Δt (a symbol or value), or ``until`` an end condition: an expression of the state
    that reaches zero (or ``sp.Eq``), or the name of a contact, meaning that its slip speed vanishes.
    """

    if (duration is None) == (until is None):
        raise ModelError("give either the duration of the interval or the end condition (until=...).",
                         where="impulse-momentum interval")
    setup = setup_mode(system, mode, None, substitutions)
    kin, red = setup.kin, setup.reduction
    tr = Trace(law="impulse-momentum")
    sol = solve_with(system, "newton-euler", dict(mode or {}), None, dict(substitutions or {}))
    start = _state_values(start, system)
    values = system.parameter_values()
    reg = sol.regimes[regime] if regime is not None else _regime_at(sol, start, values)
    signs = dict(reg.signs)
    react = {sp.Symbol(k, real=True): v for k, v in reg.reactions.items()}
    if reg.conditions:
        tr.add("Solving", "Regime", [], "the interval lies in the regime where "
               + " and ".join(str(c) for c in reg.conditions) + " (from the start state).")
    if react:
        tr.add("Solving", "Reactions from Euler's laws", [(k, v) for k, v in react.items()],
               "the reactions in this regime, as functions of the state.")
    dt = sp.Symbol("Delta_t", positive=True) if duration is None else sp.sympify(duration)
    after = {q.diff(t): sp.Symbol(f"{q.func.__name__}_dot_end", real=True) for q in red.independent}
    force, moment = _dirs(setup)
    eqs, labels = [], []
    coords = set(system.coordinates)
    for b in system.bodies.values():
        Fr, M = _resultants(setup, b, setup.applications)
        p = b.mass * kin.velocity(b.centre) if not b.is_massless else Vector(0)
        H = b.inertia.dot(kin.omega_of(b)) if not b.is_massless else Vector(0)
        for (e, name), kind in [(d, "force") for d in force] + [(d, "moment") for d in moment]:
            load = (Fr if kind == "force" else M).dot(e)
            load = kin.simplify_expr(setup.scalar(load).xreplace(signs).xreplace(react).xreplace(signs))
            if algebra.functions_of_time(load) or algebra.plain_state(load)[0].has(t):
                raise RigidkinError(f"the {'force' if kind == 'force' else 'moment'} on {b.name} along {name} "
                                    f"is {text(load)}, which is not constant over the interval, so its impulse "
                                    "is not F Δt.", where=system.name,
                                    hint="Integrate the equations of motion instead (simulate).")
            mvec = p if kind == "force" else H
            mom = setup.scalar(mvec.dot(e)) if mvec != Vector(0) else sp.Integer(0)
            A, _ = linear_form([mom], list(after))
            if any(algebra.functions_of_time(c) & coords for c in A):
                raise RigidkinError(f"the {'linear' if kind == 'force' else 'angular'} momentum of {b.name} along "
                                    f"{name} depends on the configuration, which changes during the interval.",
                                    where=system.name, hint="Integrate the equations of motion instead.")
            if load == 0 and mom == 0:
                continue
            lhs = kin.simplify_expr(load * dt)
            rhs = kin.simplify_expr(mom.xreplace(after) - mom.xreplace(start))
            what = "linear impulse on" if kind == "force" else "angular impulse about the mass centre of"
            label = f"{what} {b.name} along {name} over Δt"
            eqs.append(lhs - rhs)
            labels.append((lhs, rhs, label))
            tr.add("Balance laws", label.capitalize(), [(lhs, rhs)],
                   "∫F dt = F Δt = m v̄(t₁) − m v̄(t₀): the force is constant" if kind == "force" else
                   "∫M̄ dt = M̄ Δt = H̄(t₁) − H̄(t₀): the moment is constant")
    unknowns = list(after.values())
    vals = _solve_linear(eqs, unknowns, "the rates at the end", system.name)
    rates = {qd: kin.simplify_expr(vals[s]) for qd, s in after.items()}
    conds = []
    if until is not None:
        cond = _end_condition(setup, until)
        g = setup.scalar(cond).xreplace(rates)
        g = g.xreplace({k: v for k, v in start.items() if not isinstance(k, sp.Derivative)})
        roots = [r for r in sp.solve(sp.Eq(g, 0), dt)]
        if len(roots) != 1:
            raise RigidkinError(f"the end condition {text(cond)} = 0 gives {len(roots)} solutions for Δt.",
                                where=system.name)
        T = kin.simplify_expr(roots[0])
        sgn = _sign(T, values) if not T.free_symbols - set(values) else None
        if T.is_nonpositive or (sgn is not None and sgn <= 0):
            raise RigidkinError(f"the end condition {text(cond)} = 0 is never reached: it would take "
                                f"Δt = {text(T)}, which is not positive with these values.", where=system.name,
                                hint="In this regime the motion does not reach the event (e.g. the friction is "
                                     "too small for the slip to stop).")
        conds.append((T, ">", "the event lies ahead (Δt > 0); otherwise it is never reached"))
        tr.add("Answers", "Duration of the interval", [(sp.Symbol("Delta_t"), T)],
               f"the end condition {text(cond)} = 0 at the end of the interval.")
        rates = {k: kin.simplify_expr(v.xreplace({dt: T})) for k, v in rates.items()}
        dt = T
    for qd, expr in red.rate_map.items():
        rates[qd] = kin.simplify_expr(setup.scalar(expr).xreplace(rates))
    for c in reg.conditions:
        end = kin.simplify_expr(sp.sympify(c.expr).xreplace(rates).xreplace(
            {k: v for k, v in start.items() if not isinstance(k, sp.Derivative)}))
        if end.is_zero or kin.is_zero(end):
            continue            # the end condition itself: the regime ends there
        conds.append((end, c.relation, f"{c.label} at the end of the interval: the rates change linearly in "
                                       "time, so the regime then holds throughout"))
    tr.add("Answers", "Rates at the end of the interval", [(sp.Symbol(f"{text(k)}(t₁)"), v) for k, v in rates.items()],
           "solved from the impulse–momentum equations.")
    return ImpulseResult(MappingProxyType(rates), MappingProxyType({}), dt, tuple(conds), tuple(labels), tr)


def _end_condition(setup: ModeSetup, until):
    if isinstance(until, str):
        c = setup.system.constraints.get(until)
        if c is None or c.kind != "contact":
            raise ModelError(f"'{until}' is not a contact whose slip speed could vanish.", where="until",
                             hint="Name a contact: " + ", ".join(n for n, k in setup.system.constraints.items()
                                                                 if k.kind == "contact") + ".")
        return c.slip_velocity(setup.kin)
    if isinstance(until, sp.Eq):
        return until.lhs - until.rhs
    return sp.sympify(until)


def conserved_momenta(system, mode: dict | None = None, substitutions: dict | None = None) -> list[Momentum]:
    """The momentum components m v̄·e and H̄·e whose force or moment vanishes in ``mode`` (constant in time)."""

    setup = setup_mode(system, mode, None, substitutions)
    kin = setup.kin
    sol = solve_with(system, "newton-euler", dict(mode or {}), None, dict(substitutions or {}))
    out = []
    for b, label, kind, expr, e in momenta(setup):
        if expr == 0:
            continue
        Fr, M = _resultants(setup, b, setup.applications)
        load = setup.scalar((Fr if kind == "force" else M).dot(e))
        if all(kin.is_zero(load.xreplace(dict(reg.signs)).xreplace(
                {sp.Symbol(k, real=True): v for k, v in reg.reactions.items()})) for reg in sol.regimes):
            out.append(Momentum(label, expr))
            setup.trace.add("Answers", f"Conserved: {label}", [(sp.Symbol("p"), expr)],
                            "its force (or moment) is zero in this mode, so it keeps its value.")
    return out


def unreduced_equations(setup: ModeSetup, rates: list, contact_names: set, contact_rows: list) -> tuple:
    """Every body's impulse–momentum equations along each direction, unreduced, for an impact.

    Returns E, R, C (sympy matrices) and the names of the reactions in R: E·(u⁺ − u⁻) = R·r + C·Λ, u the
    ``rates``, r the impulses of the mode's constraint rows other than the contacts ``contact_names``,
    Λ those of ``contact_rows`` (a list of Rows per contact, normal first).  A contact whose normal the
    coordinates keep (a ladder's foot on the floor) takes its normal impulse from these equations, as
    its reaction does in ``solve``.
    """
    kin = setup.kin
    force, moment = _dirs(setup)
    rows = [r for r in setup.rows if r.constraint not in contact_names] + [r for rs in contact_rows for r in rs]
    E, RC = [], []
    for b in setup.system.bodies.values():
        p = b.mass * kin.velocity(b.centre) if not b.is_massless else Vector(0)
        H = b.inertia.dot(kin.omega_of(b)) if not b.is_massless else Vector(0)
        loads = [_resultants(setup, b, row.applications) for row in rows]
        for (e, _name), kind in [(d, "force") for d in force] + [(d, "moment") for d in moment]:
            vec = p if kind == "force" else H
            mom = setup.scalar(vec.dot(e)) if vec != Vector(0) else sp.Integer(0)
            A, _ = linear_form([mom], rates)
            E.append(list(A))
            RC.append([sp.diff(setup.scalar((Fr if kind == "force" else Mr).dot(e)), row.reaction)
                       for row, (Fr, Mr) in zip(rows, loads)])
    nb = len([r for r in setup.rows if r.constraint not in contact_names])
    RC = sp.Matrix(RC) if RC else sp.zeros(0, len(rows))
    return (sp.Matrix(E), RC[:, :nb], RC[:, nb:],
            tuple(str(r.reaction) for r in setup.rows if r.constraint not in contact_names))
