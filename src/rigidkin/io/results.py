"""A solution as plain data (JSON): every expression is ``str(expr)`` of the sympy expression.

``sympy.parse_expr`` reads each string back (coordinates print as ``theta(t)``, rates as
``Derivative(theta(t), t)``).  ``regimes`` lists every regime (one for most problems; one per sign of the
slip speed where sliding friction acts), each with its ``index``, its ``label`` and the conditions that
define it.  The top-level ``eom``, ``accelerations``, ``reactions`` and ``validity`` are those of one regime,
the one ``regime`` names (``{"index": 0, "label": ..., "of": N}``): with ``of`` > 1 they hold only
under that regime's conditions and the others are in ``regimes``.  ``answers`` holds each
answer's exact value (a string, null when unanswered), ``answer_text`` its sentence (or the reason it
was not answered), ``answer_data`` the same as data: exact value and its number at the parameters'
values, tolerance, and for events whether and when they happen and every coordinate and rate there.
The file ``results.schema.json`` next to this module is the JSON Schema of the whole object.
"""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.units import from_si, si_unit
from ..derive import named
from ..derive.closed_forms import structured

t = dynamicsymbols._t


def _s(expr) -> str:
    return str(expr)


def _condition(c) -> dict:
    return {"expression": _s(c.expr), "relation": c.relation, "label": c.label}


def regime_data(regime, system=None) -> dict:
    """One regime: its conditions, validity, equations of motion, mass matrix and forcing (M q̈ = f),
    accelerations and reactions.

    Where the closed form is too large to read (derive.closed_forms) the accelerations are ``null`` unless they were
    computed (M q̈ = f gives them; their closed form is too large to be data anyone reads), and the
    reactions are written in terms of q̈.
    """
    acc = regime.accelerations
    large = structured(regime)
    return {
        "label": regime.describe(),
        "conditions": [_condition(c) for c in regime.conditions],
        "validity": [_condition(c) for c in regime.validity],
        "eom": [_s(e) for e in regime.eom],
        "mass_matrix": [[_s(x) for x in regime.mass_matrix.row(i)] for i in range(regime.mass_matrix.rows)],
        "forcing": [_s(x) for x in regime.forcing],
        "accelerations": None if large else {q.func.__name__: _s(a) for q, a in acc.items()},
        "reactions": {k: _s(v) for k, v in regime.reactions.items()},
        # statically indeterminate reactions (derive/indeterminate.py): named, with the combinations determined
        "indeterminate": regime.indeterminate.data() if getattr(regime, "indeterminate", None) else None,
        "named": _named(regime, system) if large else None,
    }


def _named(regime, system) -> dict:
    """M and f of a structured regime with named common sub-expressions (derive/named.py)."""
    form = named.of_regime(regime, system)
    M, f = form.mass_matrix, form.forcing
    return {"note": named.NOTE,
            "subexpressions": [{"name": str(s), "expression": _s(e)} for s, e in form.names],
            "mass_matrix": [[_s(x) for x in M.row(i)] for i in range(M.rows)],
            "forcing": [_s(x) for x in f]}


def answer_value(answer) -> str:
    """The value of an answer as a string sympy reads back, or its text when it is not an expression."""
    v = answer.value
    if isinstance(v, sp.Basic):
        return _s(v)
    if isinstance(v, tuple | list) and v and all(isinstance(x, sp.Basic) for x in v):
        return _s(list(v))
    if isinstance(v, dict) and v and all(isinstance(x, sp.Basic) for x in (*v.keys(), *v.values())):
        return _s(dict(v))          # e.g. the rates just after an impulse: {Derivative(theta(t), t): ...}
    return answer.text


def _numeric(expr, values: dict):
    """The number an expression takes at the parameters' values (None where it is not one)."""
    try:
        e = sp.sympify(expr)
        v = complex(e.xreplace({k: sp.Float(x) for k, x in values.items()}).evalf())
    except (TypeError, ValueError, AttributeError, sp.SympifyError):
        return None
    if v != v or abs(v.imag) > 1e-9 * max(1.0, abs(v.real)) or abs(v.real) == float("inf"):
        return None
    return float(v.real)


def _key(k) -> str:
    """q(t) → "q", q̇ → "dot(q)", a reaction symbol → its name."""
    if isinstance(k, sp.Derivative):
        return f"dot({_key(k.expr)})" if k.derivative_count == 1 else f"ddot({_key(k.expr)})"
    if isinstance(k, sp.Function):
        return k.func.__name__
    return str(k)


def _quantity(expr, values) -> dict:
    return {"exact": _s(expr), "numeric": _numeric(expr, values)}


def _state(state: dict, values) -> dict:
    return {_key(k): _quantity(v, values) for k, v in state.items()}


def answer_data(a, values: dict) -> dict:
    """One answer as data: exact value, its number, tolerance, and what the kind adds (events: whether
    and when they happen and the state of every coordinate; equilibria: M, C, K, frequencies)."""
    d = a.details or {}
    out: dict[str, Any] = {"answered": True, "kind": a.question.kind, "text": a.text, "exact": a.exact,
                           "tolerance": a.tolerance, "note": a.note or None}
    v = a.value
    if isinstance(v, sp.Basic) and not isinstance(v, sp.Eq):
        out["value"] = _quantity(v, values)
    elif isinstance(v, sp.Eq):
        out["value"] = {"exact": _s(v), "numeric": None}
    elif isinstance(v, dict) and v:
        out["value"] = {"exact": answer_value(a), "numeric": None}
        out["state"] = _state(v, values)
    elif isinstance(v, tuple | list) and v and all(isinstance(x, sp.Basic) for x in v):
        out["value"] = {"exact": _s(list(v)), "numeric": None}
    else:
        out["value"] = None
    if "happens" in d:
        out["happens"] = bool(d["happens"])
    if d.get("time") is not None:
        out["time"] = float(d["time"])
    if a.question.kind in ("event", "extreme", "impulse", "interval", "phases") and d.get("end_state"):
        out["state"] = _state(d["end_state"], values)
    if d.get("equilibria"):
        out["equilibria"] = [{
            "configuration": _state(e.configuration, values),
            "M": [[_s(x) for x in e.M.row(i)] for i in range(e.M.rows)],
            "C": [[_s(x) for x in e.C.row(i)] for i in range(e.C.rows)],
            "K": [[_s(x) for x in e.K.row(i)] for i in range(e.K.rows)],
            "natural_frequencies": [_quantity(w, values) for w in e.natural_frequencies],
            "damping_ratios": [_quantity(z, values) for z in e.damping_ratios],
            "stability": e.stability} for e in d["equilibria"]]
    return out


def solution_data(sol, spec=None, answers: dict | None = None, notes: list[str] | None = None) -> dict[str, Any]:
    """The JSON object ``rigidkin solve --format json`` prints."""
    s = sol.system
    regimes = [{"index": i, **regime_data(r, sol.system)} for i, r in enumerate(sol.regimes)]
    first = regimes[0]
    data: dict[str, Any] = {
        "name": s.name,
        "title": s.title,
        "file": str(spec.path) if spec is not None else None,
        "method": sol.method,
        "coordinates": {
            c.name: {"symbol": _s(c.symbol), "sense": c.sense, "kind": c.kind,
                     "independent": c.symbol in sol.coordinates}
            for c in s.coordinate_info.values()},
        "parameters": {
            p.name: {"symbol": _s(p.symbol), "unit": p.unit, "description": p.description, "value": p.value,
                     "si_unit": si_unit(p.dimension), "value_in_unit": p.value_in_unit}
            for p in s.parameter_info.values()},
        "definitions": {
            n: {"symbol": n, "expression": _s(d.expression), "unit": d.unit, "description": d.description,
                "value": d.value, "si_unit": si_unit(d.dimension), "value_in_unit": from_si(d.value, d.unit)}
            for n, d in getattr(s, "definitions", {}).items()},
        "relations": {q.func.__name__: _s(e) for q, e in sol.relations.items()},
        "regime": {"index": 0, "label": first["label"], "of": len(regimes)},
        "eom": first["eom"],
        "accelerations": first["accelerations"],
        "reactions": first["reactions"],
        "validity": first["validity"],
        "indeterminate": first["indeterminate"],
        "regimes": regimes,
        "answers": {},
        "answer_text": {},
        "notes": list(notes or []),
        "warnings": list(sol.warnings),
    }
    data["answer_data"] = {}
    values = {p.symbol: p.value for p in s.parameter_info.values() if p.value is not None}
    for name, a in (answers or {}).items():
        if isinstance(a, str):            # not answered: the reason
            data["answers"][name] = None
            data["answer_text"][name] = a
            data["answer_data"][name] = {"answered": False, "reason": a}
        else:
            data["answers"][name] = answer_value(a)
            data["answer_text"][name] = a.text
            data["answer_data"][name] = answer_data(a, values)
    return data
