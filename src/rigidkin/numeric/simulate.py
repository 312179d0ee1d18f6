"""Simulation through contact and friction modes, switching exactly where a mode ends.

``simulate`` integrates every coordinate and rate with scipy's ``solve_ivp`` (DOP853, tight
tolerances, dense output) in one regime of one mode at a time.  The quantities whose zero ends the
regime (``modes.Watch``) are solve_ivp events, located by brentq on the dense output to machine
precision in time.  At an event the next mode is chosen from the same model: a contact opens (the
state carries over, the degrees of freedom increase), an impact resolves by impulse–momentum
(``impact``), slipping turns into rolling if the friction needed is within µN, sticking turns into
slipping in the direction the friction saturates.  A mode the model cannot represent (a contact
that would open without a coordinate to open with) stops the simulation with the reason.

Phases change parameter values on the way (a frictionless stretch, then a rough one):
``phases=[Phase({"mu": 0}, until=x - d), Phase()]``.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.errors import InputError
from ..derive.derivation import derivation_of
from ..model.constraints import Coulomb
from ..model.inputs import inputs_of
from .contacts.contact_modes import confirm, decide
from .contacts.modes import Hybrid
from .contacts.slack_start import start_modes, start_slack
from .contacts.transition import transition as _transition
from .contacts.vocabulary import OPEN, ModeUnavailable, describe_mode
from .inputs import ACTIVE, binding, placeholders
from .large.route import numeric_route, simulate_tree
from .large.tree import NotATree
from .restitution import restitution_map
from .result import Event, Segment, SimulationResult, build_result
from .rhs import RHS, SimulationError, compile_functions
from .state import StateLayout, assembled_changes, initial_values, parameter_vector

t = dynamicsymbols._t

METHODS = ("DOP853", "Radau", "RK45", "BDF", "LSODA")


@dataclass(frozen=True)
class Phase:
    """A stretch of the motion with its own parameter values, ending when ``until`` reaches zero.

    ``params`` override the simulation's parameters (name → number or string with unit);
    ``until`` is a sympy expression of the coordinates, rates, time and parameters (the phase ends
    when it crosses zero), ``duration`` a length of time; the last phase runs to the end.
    """

    params: Mapping = field(default_factory=dict)
    until: sp.Expr | None = None
    duration: float | None = None
    name: str = ""


def hybrid_of(system) -> Hybrid:
    """The system's Hybrid (numeric functions of its modes), kept with the system's derivations."""
    return derivation_of(system).hybrid(lambda: Hybrid(system))


def _span(t_span) -> tuple[float, float]:
    if isinstance(t_span, (int, float)):
        t_span = (0.0, float(t_span))
    try:
        t0, t1 = (float(v) for v in t_span)
    except (TypeError, ValueError):
        raise InputError(f"t_span must be an end time or (start, end), not {t_span!r}.", where="simulate") from None
    if not (np.isfinite(t0) and np.isfinite(t1)) or t1 <= t0:
        raise InputError(f"the time span ({t0}, {t1}) is empty or not finite.", where="simulate",
                         hint="Give an end time after the start, e.g. --t-end 3.")
    return t0, t1


def initial_conditions(system, initial: Mapping | None = None, params=None, mode: Mapping | None = None,
                       t0: float = 0.0) -> tuple[np.ndarray, dict, int]:
    """The full initial state (q, q̇) and a consistent (mode, regime) at it.

    Coordinates and rates given in ``initial`` win; then the declared ``initial``/``rate`` of each
    coordinate; the dependent coordinates without a value follow from the constraints of the mode
    (their integrated relations and rate relations), the rest are zero.  A contact that the values
    put apart (gap > 0) or that they move apart (normal speed > 0) starts open; one they push into
    its surface is an error.  The coordinates are then put onto the bilateral position constraints by
    Newton's method from the values given or declared, the dependent ones moving (a given value that moves
    is a warning; a start that cannot be assembled is refused naming the constraint and its residual:
    :func:`rigidkin.numeric.state.assemble`); a given rate that contradicts a closed constraint is an
    error; a start outside a contact's domain of validity (a disk past lying flat) is refused.
    """
    hyb = hybrid_of(system)
    lay = hyb.layout
    p = parameter_vector(system, lay, params)
    explicit, declared = initial_values(system, lay, initial)
    given = {**declared, **explicit}
    cand, slack = start_modes(hyb, mode)       # ropes and cables started slack: .contacts.slack_start
    n = lay.n
    where = f"initial state of {system.name}"
    for _ in range(len(hyb.contacts) + 1):
        y = np.zeros(2 * n)
        for i, v in given.items():
            y[i] = v
        try:
            cand = hyb.derivable(cand)      # at rest on two supports that both hold it from slipping: shared friction
            rel_slots, rel_fn, rate_slots, rate_fn = hyb.relation_functions(cand, integrated=True)
            at_rest = not hyb.solution(cand).coordinates
        except ModeUnavailable:
            rel_slots, at_rest = None, True
        if at_rest:
            # the candidate mode cannot be derived or leaves no degree of freedom (too many closed
            # contacts): open the unilateral contacts the given configuration already separates first
            apart = [nm for nm, c in hyb.contacts.items() if cand[nm] != OPEN and c.unilateral
                     and hyb.contact_state(nm, t0, y, p)[0] > 1e-9 * max(1.0, float(np.max(np.abs(y))))]
            if apart:
                for nm in apart:
                    cand[nm] = OPEN
                continue
            if rel_slots is None:
                hyb.relation_functions(cand, integrated=True)       # ModeUnavailable: the model's reason
        for s, v in zip(rel_slots, rel_fn(t0, *y, *p) if rel_slots else ()):
            if s not in given and np.isfinite(float(v)):       # no real value: left to the assembly's refusal
                y[s] = float(v)
        y = hyb.assemble(cand, t0, y, p, where)                 # Newton onto the bilateral constraints
        for s, v in zip(rate_slots, rate_fn(t0, *y, *p) if rate_slots else ()):
            if n + s not in given:
                y[n + s] = float(v)
        scale = max(1.0, float(np.max(np.abs(y))))
        opened = []
        for name, c in hyb.contacts.items():
            if cand[name] == OPEN:
                continue
            gap, vn, _ = hyb.contact_state(name, t0, y, p)
            if gap < -1e-9 * scale:
                raise InputError(f"the initial state puts contact {name} {-gap:.6g} into its surface.", where=where,
                                 hint="Give coordinates that keep the bodies outside the surfaces they touch.")
            if c.unilateral and (gap > 1e-9 * scale or vn > 1e-9 * scale):
                opened.append(name)
        if opened:
            for name in opened:
                cand[name] = OPEN
            continue
        # the values left conflict with closed constraints: declared ones yield, given ones are errors
        bad = []
        rel = dict(zip(rel_slots, map(float, rel_fn(t0, *y, *p)))) if rel_slots else {}
        for s, want in rel.items():
            if np.isfinite(want) and abs(y[s] - want) > 1e-9 * max(1.0, abs(want)):
                if s in explicit and hyb._depends_on(cand, lay.coordinates[s]):
                    bad.append(f"{lay.names[s]} = {y[s]:g} (the constraints give {want:.6g})")
                elif s not in explicit:
                    y[s] = want
        rates = dict(zip(rate_slots, map(float, rate_fn(t0, *y, *p)))) if rate_slots else {}
        for s, want in rates.items():
            if abs(y[n + s] - want) > 1e-9 * max(1.0, abs(want)):
                if n + s in explicit:
                    bad.append(f"{lay.labels[n + s]} = {y[n + s]:g} (the constraints give {want:.6g})")
                else:
                    y[n + s] = want
        if bad:
            raise InputError("the initial state violates the constraints of the mode "
                             f"({describe_mode(system, cand)}): {'; '.join(bad)}.", where=where,
                             hint="Give only the independent coordinates and rates, or values that satisfy "
                                  "the constraints (a contact they would push into its surface cannot start "
                                  "closed).")
        # the contact problem over every touching contact: settle's repair of the candidate is tried
        # first, then every combination in a fixed order; all of them where a contact slides (Painlevé)
        keep = start_slack(hyb, slack, t0, y, p, where)
        try:
            proposal, _, _ = hyb.settle(cand, t0, y, p)
        except SimulationError:
            proposal = None
        dec = decide(hyb, t0, y, p, proposal, every=_sliding(hyb, cand, t0, y, p), keep=keep)
        mode_, k = dec.mode, dec.regime
        y = hyb.project_rates(mode_, t0, hyb.assemble(mode_, t0, y, p, where), p)
        start_slack(hyb, slack, t0, y, p, where)        # the free lengths at the assembled start
        _check_domain(hyb.model(mode_, k), t0, y, p, where)
        return y, mode_, k
    raise InputError("no set of open and closed contacts fits the initial state.", where=system.name)


def _check_domain(model, t_, y, p, where: str) -> None:
    """Refuse a starting state outside a contact's domain of validity (a disk leaned past lying flat)."""
    vals = model.watch_values(t_, np.concatenate([y, [0.0]]), p)
    for w, v in zip(model.watches, vals):
        if w.kind == "domain" and not v > 0:
            raise InputError(f"the initial state lies outside the configurations the geometry of contact {w.name} "
                             f"describes: {w.quantity} = {v:.6g}, and it holds only while {w.quantity} > 0.",
                             where=where, hint="Start on the side that the model was derived for (a disk: "
                                               "a lean below 90°, not past lying flat).")


def _sliding(hyb, mode, t_, y, p) -> bool:
    """Whether a closed Coulomb contact slides at the state (where the contact problem may have several
    solutions, so that every candidate is checked)."""
    for name, c in hyb.contacts.items():
        if mode[name] != OPEN and isinstance(c.friction, Coulomb) and c.unilateral and hyb.kin.planar:
            _, _, s_ = hyb.contact_state(name, t_, y, p)
            if s_ is not None and abs(s_) > 1e-9 * max(1.0, float(np.max(np.abs(y)))):
                return True
    return False


def simulate(system, t_span, initial_state: Mapping | None = None, params: Mapping | None = None, *,
             inputs: Mapping | None = None, **options) -> SimulationResult:
    """:func:`simulate_motion` with the system's inputs u(t) given by ``inputs`` (name → a number, an expression
    of t, a table (times, values) or a function of (t, state): :mod:`rigidkin.numeric.inputs`).  ``options``:
    those of :func:`simulate_motion` (phases, mode, restitution, method, tolerances, n_points, …)."""
    if not inputs_of(system):
        binding(system, None, inputs, ())                     # refuses inputs given to a system without any
        return simulate_motion(system, t_span, initial_state, params, **options)
    if numeric_route(system) is not None:
        raise InputError("inputs are not supported on the numeric route of large trees of bodies.",
                         where=system.name, hint="Write the input as a load of the parameters and t instead.")
    base = {**placeholders(system), **dict(params or {})}
    lay = StateLayout.of(system)
    bind = binding(system, lay, inputs, parameter_vector(system, lay, base))
    token = ACTIVE.set(bind)
    try:
        return simulate_motion(system, t_span, initial_state, base, **options)
    finally:
        ACTIVE.reset(token)


def simulate_motion(system, t_span, initial_state: Mapping | None = None, params: Mapping | None = None, *,
                    phases: Sequence[Phase] | None = None, mode: Mapping | None = None, restitution=None,
             method: str = "DOP853", rtol: float = 1e-11, atol: float = 1e-13, max_step: float | None = None,
             n_points: int = 1001, max_events: int = 1000, rest_speed: float = 1e-5,
             energy_tol: float = 1e-6, residual_tol: float = 1e-6,
             progress: Callable[[float, float], None] | None = None,
             raise_on_stop: bool = False) -> SimulationResult:
    """Simulate ``system`` over ``t_span`` (an end time, or (start, end)) through its contact modes.

    ``initial_state`` maps ``theta`` / ``dot(theta)`` to values (default: the declared initial
    values; dependent coordinates from the constraints); ``params`` overrides parameter values
    (numbers are SI, strings carry units: ``{"beta": "30 deg"}``); ``phases`` splits the motion into
    stretches with their own parameters; ``mode`` fixes the starting state of contacts;
    ``restitution`` is e for every contact or a dict by contact, rope or cable (0: a contact closes on impact, a
    rope jerks taut; a bounce slower than ``rest_speed`` closes it too; None: each one's ``System.restitution``, or 0).
    ``max_step`` defaults to 1/100 of the span.
    Returns a :class:`SimulationResult` with time histories, events, energy and constraint monitors;
    a run that stops early (at t = 0 too: a contact paradox at the start) returns its result with
    ``stop_reason`` and ``message``, and raises only with ``raise_on_stop=True``.
    """
    t0, t1 = _span(t_span)
    max_step = (t1 - t0) / 100 if max_step is None else float(max_step)   # no event hides inside one step
    if method not in METHODS:
        raise InputError(f"unknown integration method '{method}'.", where="simulate", hint=f"Use {', '.join(METHODS)}.")
    # past the symbolic limit: a tree of pins goes numeric
    tree = numeric_route(system) if not phases and not mode else None
    if tree is not None:
        try:
            return simulate_tree(system, tree, (t0, t1), initial_state, params, method=method, rtol=rtol, atol=atol,
                                 max_step=max_step, n_points=n_points, energy_tol=energy_tol,
                                 residual_tol=residual_tol, progress=progress)
        except NotATree:
            pass
    hyb = hybrid_of(system)
    lay: StateLayout = hyb.layout
    n = lay.n
    phases = list(phases or [Phase()])
    base = dict(params or {})
    pvecs = [parameter_vector(system, lay, {**base, **dict(ph.params)}) for ph in phases]
    e_of = restitution_map(system, restitution)
    for pv in pvecs:                     # µs ≥ µk with the values of this run
        for name, c in hyb.contacts.items():
            if isinstance(c.friction, Coulomb) and c.friction.two:
                mu_s, mu_k = hyb._param_value(c.friction.static, pv), hyb._param_value(c.friction.kinetic, pv)
                if mu_s < mu_k:
                    raise InputError(f"contact {name} has a static coefficient of friction µs = {mu_s:g} smaller "
                                     f"than its kinetic one µk = {mu_k:g}.", where="parameters",
                                     hint="Give µs ≥ µk (a single µ means both).")
    try:
        y_q, mode_, k = initial_conditions(system, initial_state, {**base, **dict(phases[0].params)}, mode, t0)
    except SimulationError as exc:         # the contact problem at the start (a paradox): a stop, explained
        if raise_on_stop:
            raise
        return _stopped_at_start(system, lay, initial_state, t0, exc)
    explicit, declared = initial_values(system, lay, initial_state)
    assembled = assembled_changes(lay, {**declared, **explicit}, y_q)
    until_fns = [_phase_function(lay, ph) for ph in phases]
    y = np.concatenate([y_q, [0.0]])      # the last slot: work of non-conservative loads and impulses
    segments: list[Segment] = []
    events: list[Event] = []
    notes: list[str] = [f"the starting value {nm} = {a:.10g} was given and the constraints need {b:.10g}: the start is "
                        "assembled there (Newton's method from the value given)" for nm, (a, b) in assembled.items()
                        if lay.names.index(nm) in explicit]
    assembled = {nm: v for nm, v in assembled.items() if lay.names.index(nm) not in explicit}   # declared ones
    assembled.update({lay.labels[i]: (v, float(y_q[i])) for i, v in declared.items()     # declared rates the
                      if i >= n and i not in explicit                                     # constraints overrule
                      and abs(float(y_q[i]) - v) > 1e-9 * max(1.0, abs(v))})
    status, message, stop = "completed", f"reached t = {t1:g}", "completed"
    ph, ph_start = 0, t0
    t_now = t0
    zero_steps = 0
    report = (lambda tt: progress(tt, t1)) if progress is not None else None
    from scipy.integrate import solve_ivp  # here: importing simulate stays quick (sweeps never need it)

    while t_now < t1:
        p = pvecs[ph]
        model = hyb.model(mode_, k)
        mismatch = hyb.relation_mismatch(mode_, t_now, y, p)
        if mismatch:
            status, stop = "stopped", "relation-mismatch"
            message = (f"at t = {t_now:.10g} the mode ({describe_mode(system, mode_)}) was derived with the "
                       "dependent coordinates integrated from the declared initial configuration, and the state "
                       "differs from that by " + ", ".join(f"{nm}: {d:.4g}" for nm, d in mismatch)
                       + "; its equations depend on these coordinates, so the simulation cannot continue exactly. "
                       "(The constant of integration of such a relation is fixed by the declared initial values "
                       "of the coordinates; a mode entered later may need another one.)")
            break
        rhs = RHS(model.rates, lay, p, label=system.name, progress=report)
        fns = []
        zero = 1e-9 * max(1.0, float(np.max(np.abs(y[:2 * n]))))
        watch_of = []                    # the watch behind each event function
        for i, w in enumerate(model.watches):
            if i in model.steady:        # at rest, and the watch has no explicit time: it cannot change
                continue
            watch_of.append(i)
            fns.append(_event(lambda tt, yy, i=i, p=p, model=model: model.watch_values(tt, yy, p)[i], w.direction,
                              t_now, y, zero))
        phase_slot = None
        if ph < len(phases) - 1:
            g = until_fns[ph]
            if g is not None:
                g0 = g(t_now, y, p, ph_start)
                if g0 == 0.0:
                    raise InputError(f"phase {ph + 1}'s end condition is already zero where the phase begins "
                                     f"(t = {t_now:g}).", where="phases")
                phase_slot = len(fns)
                fns.append(_event(lambda tt, yy, g=g, p=p, s=ph_start: g(tt, yy, p, s), 0, t_now, y, 0.0))
        try:
            sol = solve_ivp(rhs, (t_now, t1), y, method=method, rtol=rtol, atol=atol, dense_output=True,
                            events=fns or None, max_step=max_step)
        except SimulationError:
            raise
        except (ValueError, ZeroDivisionError, FloatingPointError) as exc:
            raise SimulationError(f"the integration failed at t ≈ {t_now:.10g}: {exc}.", where=system.name) from None
        if sol.status == -1:
            raise SimulationError(f"the integration failed at t = {sol.t[-1]:.10g} ({sol.message}); state: "
                                  + _state_text(lay, sol.y[:, -1]) + ".", where=system.name,
                                  hint="The motion may reach a singular configuration; try method='Radau' or "
                                       "looser tolerances.")
        desc = model.description if len(phases) == 1 else f"phase {ph + 1}: {model.description}"
        segments.append(Segment(t_now, float(sol.t[-1]), dict(mode_), k, desc, ph, sol.sol, model, p, rhs.calls))
        t_prev, t_now = t_now, float(sol.t[-1])
        y = np.array(sol.y[:, -1], dtype=float)
        if sol.status == 0:
            break
        fired = [i for i, te in enumerate(sol.t_events) if len(te)]
        i = min(fired, key=lambda j: abs(sol.t_events[j][-1] - t_now))
        y = np.array(sol.y_events[i][-1], dtype=float)
        before = lay.as_dict(y)
        zero_steps = zero_steps + 1 if t_now - t_prev <= 1e-12 * max(1.0, abs(t_now)) else 0
        if zero_steps > 25 or len(events) >= max_events:
            status, stop = "stopped", ("accumulation" if zero_steps > 25 else "max-events")
            message = (f"the mode keeps switching at t = {t_now:.10g} (chattering or an accumulation of events)"
                       if zero_steps > 25 else f"stopped after {max_events} events (max_events)")
            break
        if i == phase_slot:
            p_new = pvecs[ph + 1]
            E_old = sum(model.energy(t_now, y, p))
            ph, ph_start = ph + 1, t_now
            try:
                mode_, k, nts = hyb.settle(mode_, t_now, y, p_new)
            except ModeUnavailable as exc:
                status, message, stop = "stopped", str(exc), "mode-unavailable"
                events.append(Event(f"phase {ph} ends", "stop", "", t_now, before, before,
                                    model.description, "", str(exc)))
                break
            y[:2 * n] = hyb.project_rates(mode_, t_now, y[:2 * n], p_new)
            E_new = sum(hyb.model(mode_, k).energy(t_now, y, p_new))
            y[2 * n] += E_new - E_old
            name = phases[ph - 1].name or f"phase {ph} ends"
            events.append(Event(name, "phase", "", t_now, before, lay.as_dict(y), model.description,
                                hyb.model(mode_, k).description, "; ".join(nts)))
            continue
        w = model.watches[watch_of[i]]
        if w.kind == "domain":           # the contact geometry ends here (a disk lying flat): no model beyond
            status, stop = "stopped", "outside-domain"
            message = f"at t = {t_now:.10g} {w.label} ({w.quantity} = 0): {w.detail}."
            seg = segments[-1]           # the equations are singular on the boundary itself: end just before it
            segments[-1] = replace(seg, t1=t_now - 1e-6 * (t_now - seg.t0))
            events.append(Event(f"{w.label}: the simulation stops", "stop", w.name, t_now, before, before,
                                model.description, "", w.detail))
            break
        try:
            mode_, k, y, ev = _transition(hyb, model, w, t_now, y, p, e_of, rest_speed)
            mode2, k2, note = confirm(hyb, hyb.model(mode_, k), t_now, y, p)     # every touching contact
            if note:
                mode_, k = mode2, k2
                y[:2 * n] = hyb.project_rates(mode_, t_now, y[:2 * n], p)
                ev = replace(ev, after=lay.as_dict(y), mode_after=hyb.model(mode_, k).description,
                             detail="; ".join(filter(None, [ev.detail, note])))
        except (ModeUnavailable, SimulationError) as exc:
            status = "stopped"
            stop = getattr(exc, "stop_reason", None) or ("mode-unavailable" if isinstance(exc, ModeUnavailable)
                                                      else "no-consistent-mode")
            reason = exc.message[0].lower() + exc.message[1:]
            message = f"{w.label} at t = {t_now:.10g}, but {reason}" + (f" {exc.hint}" if exc.hint else "")
            events.append(Event(f"{w.label}: the simulation stops", "stop", w.name, t_now, before, before,
                                model.description, "", reason))
            break
        events.append(ev)
    if progress is not None:
        progress(t_now, t1)
    result = build_result(system, lay, segments, events, status, message, n_points=n_points,
                          energy_tol=energy_tol, residual_tol=residual_tol, notes=notes)
    if result.stop_reason == "completed":      # else the monitors stopped it (constraint or energy drift)
        result.stop_reason = stop
    result.assembled = assembled          # declared coordinates (and rates) the constraints moved: (declared, now)
    if raise_on_stop and result.stop_reason != "completed":
        exc = SimulationError(result.message, where=system.name)
        exc.stop_reason, exc.result = result.stop_reason, result
        raise exc
    for wmsg in result.warnings:
        warnings.warn(wmsg, RuntimeWarning, stacklevel=2)
    return result


def _stopped_at_start(system, lay: StateLayout, initial_state, t0: float, exc) -> SimulationResult:
    """The result of a run that cannot start: the initial state as given (dependent coordinates as
    declared), one stop event saying why, and ``stop_reason``."""
    explicit, declared = initial_values(system, lay, initial_state)
    y = np.zeros(2 * lay.n)
    for i, v in {**declared, **explicit}.items():
        y[i] = v
    stop = getattr(exc, "stop_reason", None) or ("mode-unavailable" if isinstance(exc, ModeUnavailable)
                                              else "no-consistent-mode")
    message = exc.message + (f" {exc.hint}" if exc.hint else "")
    state = lay.as_dict(y)
    ev = Event("the simulation cannot start", "stop", "", t0, state, state, "", "", exc.message)
    nan = np.zeros(1)
    return SimulationResult(system.name, system.title, lay, np.array([t0]), y[None, :].copy(), np.zeros(1, dtype=int),
                            {}, {"T": nan, "U": nan, "E": nan, "W": nan}, {}, [ev], [], "stopped", message, 0.0,
                            "not integrated", stop_reason=stop)


def _event(fn, direction, t_start, y_start, zero):
    """A terminal solve_ivp event.  A watch that starts at zero (the event that began this mode, or
    one that coincides with it) counts as lying on its untriggered side for the first 1e-10 of
    relative time while it stays within rounding of zero, so that the first crossing after it is
    bracketed and found, and the start itself is never taken for a root.  (A watch that cannot
    change in a mode at rest is no event at all: ``ModeModel.steady``.)"""
    nudge = direction != 0 and abs(fn(t_start, y_start)) <= zero
    window = 1e-10 * max(1.0, abs(t_start))

    def event(tt, yy):
        g = fn(tt, yy)
        if nudge and tt - t_start <= window and abs(g) <= zero:
            return -direction * 1e-300       # still at the start's zero (within rounding of the state)
        return g

    event.terminal = True
    event.direction = direction
    return event


def _state_text(lay, y) -> str:
    return ", ".join(f"{k} = {v:.6g}" for k, v in lay.as_dict(y).items())


def _phase_function(lay: StateLayout, ph: Phase):
    if ph.until is None and ph.duration is None:
        return None
    if ph.until is not None and ph.duration is not None:
        raise InputError("a phase ends either when 'until' reaches zero or after 'duration', not both.",
                         where="phases")
    if ph.duration is not None:
        d = float(ph.duration)
        if not d > 0:
            raise InputError(f"a phase duration must be positive, not {d}.", where="phases")
        return lambda tt, yy, p, start: tt - start - d
    if not isinstance(ph.until, sp.Basic):
        raise InputError(f"a phase's 'until' must be a sympy expression of the state (e.g. x - d), not "
                         f"{ph.until!r}.", where="phases")
    f = compile_functions(lay.arguments(), [lay.to_plain(ph.until)])
    n = lay.n
    return lambda tt, yy, p, start: float(f(tt, *yy[:2 * n], *p)[0])
