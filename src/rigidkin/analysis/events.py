"""Events along a one-degree-of-freedom motion, in closed form where sympy can, numerically otherwise.

An event is a condition g = 0 on the state: a reaction reaches zero (a contact opens), a slip speed
vanishes, the rate vanishes (a turning point), a coordinate reaches a value.  Along a conservative
motion the energy integral gives q̇² as a function of q, so g becomes a function of q alone and the
event is a root of it: the first root beyond the start in the direction of motion, before the motion
turns back.  Each answer says whether the event happens at all and whether every unilateral contact
still pushes on the way there (otherwise a different contact opens first, and that is reported).
Where sympy finds no closed form, the root is bracketed and refined numerically, and the tolerance
is stated.
"""

from __future__ import annotations

import contextlib
import math
from dataclasses import dataclass, field, replace

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import InputError, RegimeError, RigidkinError
from ..base.printing import text
from ..model.drives import driving_note
from ..numeric.simulate import Phase as SimPhase
from ..numeric.simulate import simulate
from .integrals import along_motion, energy_integral, single_regime
from .states import at_state, full_state, state_from_names

t = dynamicsymbols._t

#: Value used for a symbolic start value that has no number (to choose among candidate roots).
DEFAULT_PROBE = 0.3


def brentq(*args, **kwargs):
    """scipy's bracketed root finder, imported when first needed (scipy is slow to import)."""
    from scipy.optimize import brentq as root

    return root(*args, **kwargs)


@dataclass(frozen=True)
class Event:
    """Where (and whether) the condition ``condition = 0`` is met along the motion from ``start``."""

    name: str
    condition: sp.Expr
    happens: bool
    coordinate: sp.Expr
    value: sp.Expr | None = None          # the coordinate at the event (exact when ``exact``)
    rate: sp.Expr | None = None           # q̇ at the event
    configuration: dict = field(default_factory=dict)   # every coordinate at the event
    exact: bool = True
    tolerance: float | None = None
    notes: tuple = ()
    time: float | None = None             # t at the event, where it was found by simulation
    state: dict = field(default_factory=dict)   # every coordinate and rate at the event

    def __str__(self) -> str:
        if not self.happens:
            return f"{self.name}: does not happen ({'; '.join(self.notes)})"
        q = text(self.coordinate)
        v = text(self.value) if self.exact else f"{float(self.value):.12g} (± {self.tolerance:g})"
        return f"{self.name}: {q} = {v}"


def numeric_values(solution, extra: dict | None = None) -> dict:
    """Numbers for every parameter (its value, or 1) and for extra symbols (``extra`` or the probe)."""
    vals = {}
    for p in solution.system.parameter_info.values():
        vals[p.symbol] = p.value if p.value is not None else 1.0
    for k, v in (extra or {}).items():
        vals[k] = v
    return vals


def _num(expr, values: dict) -> float:
    e = sp.sympify(expr)
    free = e.free_symbols - set(values)
    sub = {**values, **{s: DEFAULT_PROBE for s in free}}
    val = complex(e.xreplace({k: sp.Float(v) for k, v in sub.items()}).evalf())
    return val.real if abs(val.imag) < 1e-9 * max(1, abs(val.real)) else float("nan")


def condition_expression(solution, when, regime=None) -> sp.Expr:
    """``when`` (an Eq, or an expression meaning = 0) as an expression of the state, names resolved.

    Reaction names become their solved expressions (in ``regime``, default the single one);
    ``slip(contact)`` becomes the contact's slip speed.
    """
    if isinstance(when, sp.Eq):
        expr = when.lhs - when.rhs
    else:
        expr = sp.sympify(when)
    regime = regime or single_regime(solution)
    setup = solution.setup
    repl = {}
    for name, value in regime.reactions.items():
        for s in expr.free_symbols:
            if s.name == name:
                repl[s] = value
    for f in expr.atoms(sp.Function):
        if f.func.__name__ == "slip":
            cname = str(f.args[0])
            c = solution.system.constraints.get(cname)
            if c is None or not hasattr(c, "slip_velocity"):
                raise RigidkinError(f"slip({cname}): there is no contact named '{cname}'.")
            repl[f] = setup.scalar(c.slip_velocity(setup.kin))
    expr = expr.xreplace(repl)
    return setup.scalar(expr) if setup is not None else expr


def _direction(solution, integral, values) -> tuple[int, str]:
    q = integral.coordinate
    q0, u0 = integral.start
    u0n = _num(u0, values)
    if abs(u0n) > 1e-12:
        return (1 if u0n > 0 else -1), ""
    acc = single_regime(solution).accelerations[q].xreplace({q.diff(t): 0}).xreplace(integral.branch)
    acc = acc.xreplace({q: q0})
    a0 = _num(acc, values)
    if abs(a0) > 1e-12:
        return (1 if a0 > 0 else -1), ""
    return 1, (f"the start is an equilibrium; an infinitesimal push in the positive sense of "
               f"{q.func.__name__} is assumed")


#: Seconds sympy may spend looking for a closed-form root before the numerical fallback.
SOLVE_SECONDS = 8.0


def _roots(expr, qs: sp.Symbol) -> list | None:
    """Closed-form real roots of expr(qs) = 0, or None when sympy finds none (in time) it can return."""
    if algebra.is_transcendental_in(expr, qs):
        return None
    try:
        with algebra.time_limit(SOLVE_SECONDS):
            sol = sp.solve(expr, qs)
    except (NotImplementedError, ValueError, TypeError, TimeoutError):
        return None
    return list(sol)


def _plain(expr, q):
    qs = sp.Symbol(q.func.__name__, real=True)
    return sp.sympify(expr).xreplace({q: qs}), qs


def _first_turning_point(integral, values, direction, q0n) -> float | None:
    """The first root of q̇²(q) beyond the start in the direction of motion (numerically)."""
    f_expr, qs = _plain(integral.rate_squared, integral.coordinate)
    f = sp.lambdify(qs, f_expr.xreplace({k: sp.Float(v) for k, v in values.items()}), "math")
    step, span = 1e-3, 50.0
    x_prev, f_prev = q0n + direction * 1e-9, None
    try:
        f_prev = f(x_prev)
    except (ValueError, ZeroDivisionError):
        return None
    x = x_prev
    while abs(x - q0n) < span:
        x = x + direction * step
        try:
            fx = f(x)
        except (ValueError, ZeroDivisionError):
            return x
        if isinstance(fx, complex) or fx < 0:
            return brentq(lambda s: f(s), x_prev, x, xtol=1e-14) if f_prev > 0 else x_prev
        x_prev, f_prev = x, fx
        step = min(step * 1.2, 0.05)
    return None


def one_coordinate(solution, what: str):
    """The single independent coordinate, or a clear refusal naming the ones there are."""
    if len(solution.coordinates) != 1:
        names = ", ".join(q.func.__name__ for q in solution.coordinates)
        raise RigidkinError(f"{what} is found along a motion of one degree of freedom, and this mode has "
                            f"{len(solution.coordinates)} ({names}).",
                            hint="Ask with a mode that leaves one coordinate free (a contact that rolls or sticks).")
    return solution.coordinates[0]


#: Longest simulated time the numerical event search covers.
SIMULATION_HORIZON = 30.0


def event(solution, when, start: dict | None = None, name: str = "event", mode: dict | None = None) -> Event:
    """The first configuration after ``start`` where ``when`` holds.

    Along a conservative one-degree-of-freedom motion this is a root of a function of the coordinate
    (closed form where sympy finds one); otherwise the motion is simulated and the event located by
    the integrator's event machinery, with the tolerance stated.  For a system driven by a law of t the
    notes say that the answer holds only for that law.
    """
    try:
        integral = energy_integral(solution, start)
    except RigidkinError as exc:
        ev = _verified(solution, event_by_simulation(solution, when, start, name, reason=exc.message, mode=mode))
    else:
        ev = _verified(solution, _event_1dof(solution, integral, when, name))
    note = driving_note(solution.system)        # a driven system's event is that of its driving law only
    return replace(ev, notes=tuple(ev.notes) + (note,)) if note else ev


def _verified(solution, ev: Event) -> Event:
    """Back-substitution: the condition vanishes at the reported state (identically, or to the event's
    tolerance at the parameters' values), else the event is refused with the residual."""
    if not ev.happens or not ev.state:
        return ev
    r = algebra.readable(at_state(ev.condition, ev.state))
    if ev.exact and algebra.is_zero(r):
        return ev
    values = numeric_values(solution)
    v = _num(r, values)
    if math.isnan(v) and isinstance(r, sp.Pow) and r.exp == sp.Rational(1, 2):
        v = _num(r.base, values)        # q̇ = √(q̇²(q)) at a turning point: q̇² rounds to a tiny negative
    scale = max(1.0, sum(abs(_num(a, values)) for a in sp.Add.make_args(sp.expand(ev.condition.xreplace(
        {k: x for k, x in ev.state.items() if isinstance(k, sp.Derivative)}).xreplace(
        {k: x for k, x in ev.state.items() if not isinstance(k, sp.Derivative)})))))
    tol = 1e-9 if ev.exact else max(1e-6, 10 * (ev.tolerance or 0))
    if not math.isnan(v) and abs(v) <= tol * scale:
        return ev
    raise RigidkinError(f"the event '{ev.name}' fails its back-substitution: its condition {text(ev.condition)} "
                        f"is {text(r)} ≈ {v:.6g} at the reported state, not 0.",
                        hint="This is a defect in rigidkin; please report the problem.")


def event_by_simulation(solution, when, start: dict | None = None, name: str = "event",
                        horizon: float = SIMULATION_HORIZON, reason: str = "", mode: dict | None = None) -> Event:
    """Locate the event by simulating from ``start`` (every parameter needs a value).

    The simulator switches modes by itself (a contact opens, a slip stops); when the event asked for is
    exactly such a switch it is that switch's time and state.  A condition on a reaction holds only in
    the mode it was written for, so the answer says so when the mode changes first.
    """

    system = solution.system
    missing = [p.name for p in system.parameter_info.values() if p.value is None]
    if missing:
        raise RigidkinError(f"there is no closed form ({reason.rstrip('.')}), and a numerical search needs "
                            f"values for the parameters {', '.join(missing)}.",
                            hint="Give the parameters values in the problem.")
    given = dict(start or {})
    state = full_state(system, given)
    for qd, rel in solution.relations.items():          # dependent coordinates and rates follow the mode
        if qd not in given:
            state[qd] = at_state(rel, state)
    for ud, rel in solution.rate_relations.items():
        if ud not in given:
            state[ud] = at_state(rel, state)
    values = numeric_values(solution)
    initial = {}
    for k, v in state.items():
        key = f"dot({k.args[0].func.__name__})" if isinstance(k, sp.Derivative) else k.func.__name__
        initial[key] = float(_num(v, values))
    names = set(solution.regimes[0].reactions)
    on_reaction = any(getattr(s, "name", None) in names for s in sp.sympify(
        when.lhs - when.rhs if isinstance(when, sp.Eq) else when).free_symbols)
    regime = solution.regimes[0]
    if len(solution.regimes) > 1:
        try:
            regime = solution.regime_at({**state, **values})
        except RegimeError:
            if on_reaction:
                raise
    g = condition_expression(solution, when, regime)
    contact_states = {k: v for k, v in dict(mode or {}).items()
                      if getattr(system.constraints.get(k), "kind", "") == "contact"}

    def g_at(named: dict) -> float:
        return _num(at_state(g, state_from_names(system, named)), values)

    g_start = _num(at_state(g, state), values)
    phases = [SimPhase(until=g, name=name), SimPhase()]
    if abs(g_start) < 1e-12:   # the condition holds at the start (a turning point from rest): step off it
        phases.insert(0, SimPhase(duration=1e-7, name="_start"))
    try:
        res = simulate(system, horizon, initial, mode=contact_states or None, phases=phases)
    except InputError:          # the simulator's own switch ends where the condition is already zero
        res = simulate(system, horizon, initial, mode=contact_states or None)
    notes = [f"found by simulation ({reason.rstrip('.')}); time located to about 1e-10 s"] if reason else []
    hits = [e for e in res.events if e.kind == "phase" and e.name == name]
    switches = [e for e in res.events if e.kind not in ("phase",)]
    tol = 1e-6 * max(1.0, abs(g_start))
    first = None
    for e in switches:
        if hits and e.t > hits[0].t + 1e-12:
            break
        if abs(g_at(e.state)) <= tol:          # the asked event is this very switch
            first = e
            break
        if on_reaction:                        # a reaction's formula holds only in the mode it was derived for
            return Event(name, g, False, solution.coordinates[0], notes=tuple(notes + [
                f"it does not happen in this mode: first {e.name} at t = {e.t:.6g} "
                f"({_named_state_text(e.state)}), and the mode changes there"]))
    if first is None and hits:
        first = hits[0]
        before = [e for e in switches if e.t < first.t]
        if before:
            notes.append(f"first {before[0].name} at t = {before[0].t:.6g}; the event happens in the motion "
                         "that follows")
    if first is None:
        why = f"it does not happen within {horizon:g} s of simulated motion"
        if switches:
            why += f" (the mode changes: first {switches[0].name} at t = {switches[0].t:.6g})"
        if res.status != "completed":
            why += f"; the simulation stopped: {res.message}"
        return Event(name, g, False, solution.coordinates[0], notes=tuple(notes + [why]))
    at = state_from_names(system, first.state)
    config = {c.symbol: at[c.symbol] for c in system.coordinate_info.values() if c.symbol in at}
    q = solution.coordinates[0]
    notes.append(f"at t = {first.t:.10g}")
    return Event(name, g, True, q, config[q], at.get(q.diff(t)), config, False, 1e-9, tuple(notes),
                 time=float(first.t), state=at)


def _named_state_text(named: dict) -> str:
    return ", ".join(f"{k} = {v:.6g}" for k, v in named.items())


def _event_1dof(solution, integral, when, name) -> Event:
    q = integral.coordinate
    q0, u0 = integral.start
    g = condition_expression(solution, when)
    is_rate_event = bool(g.has(q.diff(t)) and not sp.sympify(g.xreplace({q.diff(t): 0})).has(q))
    if is_rate_event:
        g_q = integral.rate_squared
    else:
        g_q = along_motion(solution, g, integral)
    values = numeric_values(solution)
    extra = {s: DEFAULT_PROBE for s in sorted(sp.sympify(q0).free_symbols | sp.sympify(u0).free_symbols, key=str)
             if s not in values}
    values.update(extra)
    notes = []
    direction, note = _direction(solution, integral, values)
    if note:
        notes.append(note)
    if extra:
        notes.append("roots chosen for " + ", ".join(f"{s} = {v}" for s, v in extra.items()))
    q0n = _num(q0, values)
    turn = _first_turning_point(integral, values, direction, q0n)
    expr, qs = _plain(g_q, q)
    candidates = _roots(algebra.readable(expr), qs)
    if candidates:
        # trigonometric equations: sympy returns principal roots; add their periodic images and mirrors,
        # and keep only those that satisfy the equation
        fnum = expr.xreplace({k: sp.Float(v) for k, v in values.items()})
        extra_c = []
        for c in candidates:
            for k in (-2, -1, 1, 2, 0):
                for cand in (c + 2 * k * sp.pi, -c + 2 * k * sp.pi):
                    if cand == c:
                        continue
                    try:
                        val = abs(complex(fnum.xreplace({qs: sp.Float(_num(cand, values))}).evalf()))
                    except (TypeError, ValueError):
                        continue
                    if val < 1e-9:
                        extra_c.append(cand)
        candidates = candidates + extra_c
    chosen, exact = None, True
    if candidates:
        best = None
        for c in candidates:
            v = _num(c, values)
            if math.isnan(v) or (v - q0n) * direction <= 1e-9:
                continue
            if turn is not None and (v - turn) * direction > 1e-9 and not is_rate_event:
                continue
            if best is None or abs(v - q0n) < abs(best[1] - q0n):
                best = (c, v)
        if best is not None:
            chosen = (algebra.readable(best[0]), best[1])
    if chosen is None and not candidates:
        # numeric bracketing between the start and the turning point (or a long span)
        f = sp.lambdify(qs, expr.xreplace({k: sp.Float(v) for k, v in values.items()}), "math")
        end = turn if turn is not None else q0n + direction * 4 * math.pi
        xs = np.linspace(q0n + direction * 1e-7, end, 2001)
        vals = []
        for x in xs:
            try:
                vals.append(float(f(x)))
            except (ValueError, TypeError, ZeroDivisionError):
                vals.append(float("nan"))
        for i in range(len(xs) - 1):
            if np.isfinite(vals[i]) and np.isfinite(vals[i + 1]) and vals[i] * vals[i + 1] <= 0:
                root = brentq(f, xs[i], xs[i + 1], xtol=1e-13, rtol=1e-13)
                chosen, exact = (sp.Float(root), root), False
                break
    if chosen is None:
        why = "the condition is never met before the motion turns back" if turn is not None else \
            "the condition is never met along the motion"
        if turn is not None:
            why += f" (turning point at {text(q)} ≈ {turn:.6g})"
        return Event(name, g, False, q, notes=tuple(notes + [why]))
    value, vnum = chosen
    # is every unilateral contact still pushing on the way?
    regime = single_regime(solution)
    for cond in regime.validity:
        h = along_motion(solution, cond.expr, integral)
        hp, hs = _plain(h, q)
        hf = sp.lambdify(hs, hp.xreplace({k: sp.Float(v) for k, v in values.items()}), "math")
        prev = None
        for x in np.linspace(q0n, vnum, 400)[1:-1]:
            try:
                hv = float(hf(x))
            except (ValueError, TypeError, ZeroDivisionError):
                continue
            if hv < -1e-9 * max(1.0, abs(hv)):
                where = x
                if prev is not None:           # the crossing itself, not the grid point after it
                    with contextlib.suppress(ValueError, TypeError, ZeroDivisionError):
                        where = brentq(lambda s, hf=hf: float(hf(s)), prev, x, xtol=1e-13)
                notes.append(f"{cond.label} fails first, at {text(q)} ≈ {where:.6g} (where it reaches its "
                             "limit): the event is not reached in this mode")
                return Event(name, g, False, q, notes=tuple(notes))
            prev = x
    rate = sp.sqrt(integral.rate_squared.xreplace({q: value}))
    rate = algebra.readable(direction * rate)
    config = {q: value}
    for qd, rel in {**solution.relations, **integral.branch}.items():
        config[qd] = algebra.readable(rel.xreplace({q: value}))
    state = {**config, q.diff(t): rate}
    for ud, rel in solution.rate_relations.items():
        state[ud] = algebra.readable(at_state(rel, state))
    return Event(name, g, True, q, value, rate, config, exact, None if exact else 1e-12, tuple(notes),
                 state=state)


def extreme(solution, coordinate=None, start: dict | None = None) -> Event:
    """The largest excursion of the coordinate after ``start``: where q̇ first vanishes."""
    integral = energy_integral(solution, start)
    q = integral.coordinate
    if coordinate is not None and coordinate != q:
        raise RigidkinError(f"{coordinate} is not the independent coordinate {q} of this solution.")
    return event(solution, sp.Eq(q.diff(t), 0), start, name=f"extreme of {q.func.__name__}")


def threshold(solution, holds: sp.Rel, start: dict | None = None, over: tuple | None = None,
              vary=None) -> dict:
    """The smallest start rate for which ``holds`` (e.g. N ≥ 0) is true along the whole motion.

    ``over`` is the range (a, b) of the coordinate the motion must cover (default: a full turn from the
    start).  Returns {"rate": the threshold start rate (exact), "rate_squared": its square,
    "critical": the configuration where the condition is tightest}.
    """
    q = one_coordinate(solution, "a threshold")
    u0 = sp.Symbol("_u0", positive=True)
    st = dict(start or {})
    st[q.diff(t)] = u0
    integral = energy_integral(solution, st)
    h = holds.lhs - holds.rhs if isinstance(holds, sp.Rel) else sp.sympify(holds)
    sense = 1 if not isinstance(holds, sp.Rel) or holds.rel_op in (">=", ">") else -1
    h = sense * along_motion(solution, condition_expression(solution, h), integral)
    hp, qs = _plain(h, q)
    q0 = integral.start[0]
    a, b = over if over is not None else (q0, q0 + 2 * sp.pi)
    crit = _roots(sp.diff(hp, qs), qs) or []
    pts = [sp.sympify(a), sp.sympify(b)] + [c for c in crit if not c.has(u0)]
    values = numeric_values(solution, {u0: 10.0})
    an, bn = _num(a, values), _num(b, values)
    inside = [p for p in pts if an - 1e-12 <= _num(p, values) <= bn + 1e-12]
    worst = min(inside, key=lambda p: _num(hp.xreplace({qs: p}), values))
    h_at = algebra.readable(hp.xreplace({qs: worst}))
    try:
        with algebra.time_limit(SOLVE_SECONDS):
            sols = [s for s in sp.solve(h_at, u0) if _num(s, values) > 0]
    except (NotImplementedError, TimeoutError):
        return _threshold_numeric(h_at, u0, values, worst)
    if not sols:
        raise RigidkinError("no start rate makes the condition hold at its tightest point.")
    rate = algebra.readable(sp.sqrt(algebra.readable(sols[0] ** 2)))
    return {"rate": rate, "rate_squared": algebra.readable(rate**2), "critical": worst, "exact": True,
            "tolerance": None}


def _threshold_numeric(h_at, u0, values, worst) -> dict:
    """The threshold start rate as a number (bracketed root of the condition at its tightest point)."""
    f = sp.lambdify(u0, h_at.xreplace({k: sp.Float(v) for k, v in values.items() if k != u0}), "math")
    xs = np.geomspace(1e-6, 1e4, 400)
    vals = [float(f(x)) for x in xs]
    for a, b, fa, fb in zip(xs, xs[1:], vals, vals[1:]):
        if fa * fb <= 0:
            root = brentq(f, a, b, xtol=1e-13, rtol=1e-12)
            rate = sp.Float(root)
            return {"rate": rate, "rate_squared": rate**2, "critical": worst, "exact": False, "tolerance": 1e-12}
    raise RigidkinError("no start rate makes the condition hold at its tightest point (searched numerically "
                        "up to 1e4).")
