"""Answering questions: one entry point for the ``[ask]`` section of a problem file and the Python API.

``answer(system, question)`` solves what the question needs (the mode it names, or the default one)
and returns an ``Answer``: an exact sympy value where a closed form exists, with a numeric reading at
the parameters' values, or a number with its tolerance.  ``answer_all`` answers a list in order, so
that a question can start ``after`` an earlier one (the extreme swing after an impulse).
"""

from __future__ import annotations

import math

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import InputError, RegimeError, RigidkinError
from ..base.printing import text
from ..derive.laws import impulse as law
from ..derive.solution import repeatable
from .equilibrium import equilibria, known_values
from .events import _num, condition_expression, event, extreme, threshold
from .integrals import along_motion, energy_integral, first_integrals
from .phases import Phase, run_phases
from .question_starts import question_fields
from .questions import KINDS, Answer, Question

t = dynamicsymbols._t


def _reading(expr, system, kind: str | None = None) -> str:
    """' ≈ 0.8411 (48.19°)': the value at the parameters' values, when it is a number there."""
    values = numeric_values_from(system)
    try:
        v = _num(expr, values)
    except (TypeError, ValueError):
        return ""
    if math.isnan(v) or sp.sympify(expr).is_number and sp.sympify(expr).is_Integer:
        return ""
    missing = sp.sympify(expr).free_symbols - set(values)
    if missing:
        return ""
    out = f" ≈ {v:.6g}"
    if kind == "angle":
        out += f" ({math.degrees(v):.4g}°)"
    return out


def numeric_values_from(system) -> dict:
    return {p.symbol: p.value for p in system.parameter_info.values() if p.value is not None}


def _kind_of(system, q) -> str | None:
    try:
        return system.coordinate_of(q).kind
    except KeyError:
        return None


def _solution(system, fields):
    mode = dict(fields.get("mode") or {})
    subs = dict(fields.get("set") or {})
    return system.solve(mode=mode, substitutions=subs)


def _start(fields, context) -> dict:
    start = dict(fields.get("start") or {})
    after = fields.get("after")
    if after:
        if after not in context:
            raise InputError(f"'after = {after}' names no earlier question.", hint="Ask that question first.")
        prev = context[after]
        end = prev.details.get("end_state")
        if end is None:
            raise InputError(f"the answer to '{after}' has no end state to start from.")
        start = {**end, **start}
    return start


def answer(system, question: Question, context: dict | None = None) -> Answer:
    """Answer one question about ``system``."""
    repeatable()
    context = context if context is not None else {}
    kind, f = question.kind, dict(question.fields)
    if kind not in KINDS:
        raise InputError(f"unknown question kind '{kind}'.", where=question.where, hint=f"Kinds: {', '.join(KINDS)}.")
    try:
        f = question_fields(system, f, question.where or question.name)    # the one rule for starting states
        return _HANDLERS[kind](system, question, f, context)
    except RigidkinError as exc:
        if question.where and not exc.where:
            exc.where = question.where
        raise


def answer_all(system, questions) -> list[Answer]:
    """Answer questions in order; each may start ``after`` an earlier one (by name)."""
    context, out = {}, []
    for q in questions:
        a = answer(system, q, context)
        context[q.name] = a
        out.append(a)
    return out


# handlers -------------------------------------------------------------------------------------------
def _eom(system, question, f, context):
    sol = _solution(system, f)
    if len(sol.regimes) == 1:
        lines = [f"{text(e)} = 0" for e in sol.eom]
        return Answer(question, tuple(sol.eom), "; ".join(lines))
    parts = []
    for r in sol.regimes:
        parts.append(f"while {r.describe()}: " + "; ".join(f"{text(e)} = 0" for e in r.eom))
    return Answer(question, tuple(r.eom for r in sol.regimes), " | ".join(parts))


def _reaction(system, question, f, context):
    sol = _solution(system, f)
    name = str(f.get("reaction"))
    regime = sol.regimes[0]
    if name in getattr(regime.indeterminate, "reactions", ()):     # two supports sharing friction (statics)
        raise RigidkinError(f"{name} is statically indeterminate in this mode: the balance laws determine only "
                            + "; ".join(f"{text(c)} = {text(v)}" for c, v in regime.indeterminate.combinations) + ".",
                            where=question.where, hint=f"Reactions determined: {', '.join(regime.reactions)}.")
    if name not in regime.reactions:
        raise InputError(f"there is no reaction named '{name}'.", where=question.where,
                         hint=f"Reactions: {', '.join(regime.reactions)}.")
    start = _start(f, context)
    if start and len(sol.coordinates) == 1:
        integral = energy_integral(sol, start)
        value = along_motion(sol, regime.reactions[name], integral)
        return Answer(question, value, f"{name} = {text(value)} along the motion from "
                                       f"{_state_text(integral.start, integral.coordinate)}",
                      details={"integral": integral.equation})
    if len(sol.regimes) > 1:
        if start:
            raise RigidkinError("the reaction along a motion needs one regime, and this mode has "
                                f"{len(sol.regimes)} (the sense of slip): give the contact's mode.")
        values = tuple(r.reactions[name] for r in sol.regimes)
        return Answer(question, values, " | ".join(f"while {r.describe()}: {name} = {text(r.reactions[name])}"
                                                   for r in sol.regimes))
    value = regime.reactions[name]
    return Answer(question, value, f"{name} = {text(value)}")


def _state_text(start, q):
    q0, u0 = start
    return f"{text(q)} = {text(q0)}, {text(q.diff(t))} = {text(u0)}"


def _integral(system, question, f, context):
    sol = _solution(system, f)
    start = _start(f, context)
    if len(sol.coordinates) == 1:
        try:
            integral = energy_integral(sol, start)
            lhs, rhs = integral.equation
            return Answer(question, sp.Eq(lhs, rhs), f"{text(lhs)} = {text(rhs)} ({integral.name})", note=integral.note)
        except RigidkinError:
            pass
    found = first_integrals(sol, start)
    if not found:
        return Answer(question, (), "no first integral: energy is not conserved and no coordinate is cyclic")
    lines = [f"{fi.name}: {text(fi.expression)} = {text(fi.value)}" for fi in found]
    return Answer(question, tuple(found), "; ".join(lines), details={"integrals": found})


def _event(system, question, f, context):
    sol = _solution(system, f)
    ev = event(sol, f["when"], _start(f, context), name=question.name, mode=f.get("mode"))
    if not ev.happens:
        return Answer(question, None, f"does not happen: {'; '.join(ev.notes)}", details={"happens": False})
    q = ev.coordinate
    parts = [f"{text(k)} = {text(v)}{_reading(v, system, _kind_of(system, k))}"
             for k, v in ev.configuration.items()]
    end = dict(ev.state) if ev.state else {**ev.configuration, q.diff(t): ev.rate}
    rates = [f"{text(k)} = {text(v)}{_reading(v, system)}" for k, v in end.items()
             if isinstance(k, sp.Derivative)]
    when = f["when"]
    cond = text(when) if isinstance(when, sp.Eq) else f"{text(when)} = 0"
    head = f"at t = {ev.time:.10g}: " if ev.time is not None else ""
    return Answer(question, ev.value, head + ", ".join(parts + rates) + f" (where {cond})", exact=ev.exact,
                  tolerance=ev.tolerance, note="; ".join(ev.notes),
                  details={"happens": True, "configuration": ev.configuration, "rate": ev.rate,
                           "end_state": end, "time": ev.time})


def _extreme(system, question, f, context):
    sol = _solution(system, f)
    coord = f.get("coordinate")
    ev = extreme(sol, coord, _start(f, context))
    if not ev.happens:
        return Answer(question, None, f"no turning point: {'; '.join(ev.notes)}", note="; ".join(ev.notes))
    q = ev.coordinate
    reading = _reading(ev.value, system, _kind_of(system, q))
    return Answer(question, ev.value, f"{text(q)}_max = {text(ev.value)}{reading}",
                  exact=ev.exact, tolerance=ev.tolerance, note="; ".join(ev.notes),
                  details={"end_state": {**ev.configuration, q.diff(t): 0}})


def _threshold(system, question, f, context):
    sol = _solution(system, f)
    over = f.get("over")
    res = threshold(sol, f["holds"], _start(f, context), over=tuple(over) if over else None)
    q = sol.coordinates[0]
    out = f"the smallest start rate: {text(q.diff(t))}² = {text(res['rate_squared'])}"
    value = res["rate_squared"]
    expr = f.get("expression")
    if expr is not None:
        value = algebra.readable(sp.sympify(expr).xreplace({q.diff(t): res["rate"]}))
        out += f"; {text(expr)} = {text(value)}"
    out += f" (tightest at {text(q)} = {text(res['critical'])})"
    return Answer(question, value, out, details=res, exact=res.get("exact", True), tolerance=res.get("tolerance"),
                  note="" if res.get("exact", True) else "no closed form in time: found numerically (relative "
                                                               "tolerance 1e-12)")


def _equilibrium(system, question, f, context):
    sol = _solution(system, f)
    if len(sol.regimes) > 1:
        raise RigidkinError("at an equilibrium nothing slides, so a contact with sliding friction sticks there: "
                            "ask with its mode set to 'stick'.")
    eqs = equilibria(sol)
    lines = [str(e) + _in_numbers(e, known_values(sol)) for e in eqs]
    return Answer(question, tuple(eqs), "; ".join(lines), details={"equilibria": eqs})


def _in_numbers(e, values) -> str:
    """An equilibrium's position and natural frequencies as numbers with the parameters' values (where every
    parameter they hold has one): ` (θ ≈ 0.994407; ω_n ≈ 5.03062 rad/s)`."""
    parts = []
    for q, v in e.configuration.items():
        if sp.sympify(v).free_symbols and not (sp.sympify(v).free_symbols - set(values)):
            parts.append(f"{text(q)} ≈ {_num(v, values):.6g}")
    for w in e.natural_frequencies:
        if not (sp.sympify(w).free_symbols - set(values)):
            parts.append(f"ω_n ≈ {_num(w, values):.6g} rad/s")
    return f" ({'; '.join(parts)})" if parts else ""


def _phases(system, question, f, context):
    phases = []
    for i, p in enumerate(f.get("phase") or []):
        phases.append(Phase(str(p.get("name", f"phase {i + 1}")), dict(p.get("mode") or {}),
                            dict(p.get("set") or {}), p.get("until")))
    res = run_phases(system, phases, _start(f, context))
    lines = []
    for r in res:
        line = str(r)
        if r.happens and r.duration is not None:
            rates = {k: v for k, v in r.end_state.items() if isinstance(k, sp.Derivative)}
            line += "; at its end " + ", ".join(f"{text(k)} = {text(v)}" for k, v in rates.items())
        if r.notes:
            line += " [" + "; ".join(r.notes) + "]"
        lines.append(line)
    return Answer(question, tuple(res), "\n".join(lines), details={"phases": res,
                                                                   "end_state": res[-1].end_state if res else {}})


def _value(system, question, f, context):
    sol = _solution(system, f)
    at = _start({"start": f.get("at"), "after": f.get("after")}, context)
    note = ""
    try:
        regime = sol.regime_at(at) if len(sol.regimes) > 1 else sol.regimes[0]
    except RegimeError:
        if f.get("mode"):
            raise
        # no slip starts from this state: the sliding contacts stick, if their friction can hold them
        stick = {k: "stick" for k, v in sol.states.items() if v == "slip"}
        sol = system.solve(mode={**dict(sol.states), **stick}, substitutions=dict(f.get("set") or {}))
        regime = sol.regimes[0]
        note = f"at rest relative to {', '.join(stick)}: sticking (no slip starts from this state)"
        values = {**numeric_values_from(system)}
        for cond in regime.validity:
            try:
                v = _num(cond.expr.xreplace({k: x for k, x in at.items() if isinstance(k, sp.Derivative)})
                         .xreplace({k: x for k, x in at.items() if not isinstance(k, sp.Derivative)}), values)
            except (TypeError, ValueError):
                continue                  # not a number at this state (a coordinate not given)
            if v == v and not cond.holds(v, 1e-9):
                raise RigidkinError(f"at this state no slip starts, yet {cond.label} fails "
                                    f"({text(cond.expr)} = {v:.4g}): the friction cannot hold the contact.") from None
    expr = condition_expression(sol, f["expression"], regime)
    expr = expr.xreplace({q.diff(t, 2): a for q, a in regime.accelerations.items()})
    rates = {k: v for k, v in at.items() if isinstance(k, sp.Derivative)}
    value = algebra.readable(sp.sympify(expr).xreplace(rates).xreplace(
        {k: v for k, v in at.items() if not isinstance(k, sp.Derivative)}))
    return Answer(question, value, f"{text(f['expression'])} = {text(value)}{_reading(value, system)}", note=note)


def _impulse(system, question, f, context):

    start = _start(f, context)
    before = {k: v for k, v in start.items() if isinstance(k, sp.Derivative)}
    at = {k: v for k, v in start.items() if not isinstance(k, sp.Derivative)}
    res = law.impulsive(system, mode=dict(f.get("mode") or {}), before=before or None, at=at or None,
                        substitutions=dict(f.get("set") or {}))
    parts = [f"{text(k)} = {text(v)}{_reading(v, system)}" for k, v in res.rates.items()]
    parts += [f"{k} = {text(v)}" for k, v in res.reaction_impulses.items()]
    end = {**start, **res.rates}
    return Answer(question, dict(res.rates), "just after: " + ", ".join(parts),
                  details={"end_state": end, "reaction_impulses": dict(res.reaction_impulses)})


def selects(regime, q, sign: int) -> bool:
    """Whether ``q > 0`` (``sign`` 1) or ``q < 0`` (``sign`` −1) is the condition of ``regime``: each of its
    conditions is that sign of ±q (a regime without conditions holds everywhere)."""
    ok = True
    for c in regime.conditions:
        csign = 1 if c.relation in (">", ">=") else -1
        if algebra.is_zero(c.expr - q):
            ok &= csign == sign
        elif algebra.is_zero(c.expr + q):
            ok &= csign == -sign
        else:
            ok = False
    return ok


def _regime_index(system, f) -> int | None:
    """The regime a relation such as ``dot(x) + r*dot(phi) < V`` selects (matched to a regime condition)."""
    rel = f.get("regime")
    if rel is None:
        return None
    if not isinstance(rel, sp.Rel):
        raise InputError("regime must be a condition such as 'dot(x) > 0'.")
    q = rel.lhs - rel.rhs
    sign = 1 if rel.rel_op in (">", ">=") else -1
    sol = _solution(system, f)
    setup = sol.setup
    q = setup.scalar(q)
    for i, r in enumerate(sol.regimes):
        if selects(r, q, sign):
            return i
    raise InputError(f"the condition {text(rel)} does not select one of the regimes: "
                     + "; ".join(r.describe() for r in sol.regimes) + ".")


def _interval(system, question, f, context):

    start = _start(f, context)
    res = law.interval(system, start, duration=f.get("duration"), until=f.get("until"),
                       mode=dict(f.get("mode") or {}), substitutions=dict(f.get("set") or {}),
                       regime=_regime_index(system, f))
    parts = [f"{text(k)} = {text(v)}{_reading(v, system)}" for k, v in res.rates.items()]
    head = "at the end"
    if res.duration is not None and f.get("duration") is None:
        head = f"after Δt = {text(res.duration)}{_reading(res.duration, system)}"
    note = "; ".join(f"{text(e)} {r} 0 ({d})" for e, r, d in res.conditions) if res.conditions else ""
    end = {**start, **res.rates}
    return Answer(question, dict(res.rates), f"{head}: " + ", ".join(parts), note=note,
                  details={"end_state": end, "duration": res.duration})


_HANDLERS = {
    "eom": _eom, "reaction": _reaction, "integral": _integral, "event": _event, "extreme": _extreme,
    "threshold": _threshold, "equilibrium": _equilibrium, "phases": _phases, "value": _value,
    "impulse": _impulse, "interval": _interval,
}
