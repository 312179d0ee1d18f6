"""A solution as plain data (JSON): every expression is ``str(expr)`` of the sympy expression.

``sympy.parse_expr`` reads each string back (coordinates print as ``theta(t)``, rates as
``Derivative(theta(t), t)``).  The top-level ``eom``, ``accelerations`` and ``reactions`` are those of
the first regime; ``regimes`` lists every regime (one for most problems; one per sign of the slip
speed where sliding friction acts) with the conditions that define it.
"""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.physics.vector import dynamicsymbols

t = dynamicsymbols._t


def _s(expr) -> str:
    return str(expr)


def _condition(c) -> dict:
    return {"expression": _s(c.expr), "relation": c.relation, "label": c.label}


def regime_data(regime) -> dict:
    """One regime: its conditions, validity, equations of motion, mass matrix and forcing (M q̈ = f),
    accelerations and reactions.

    With more than ``READABLE_DOF`` degrees of freedom the accelerations are ``null`` unless they were
    computed (M q̈ = f gives them; their closed form is too large to be data anyone reads), and the
    reactions are written in terms of q̈.
    """
    from ..solution import READABLE_DOF, LazyMap

    acc = regime.accelerations
    large = regime.mass_matrix.rows > READABLE_DOF and isinstance(acc, LazyMap) and not acc.computed
    return {
        "conditions": [_condition(c) for c in regime.conditions],
        "validity": [_condition(c) for c in regime.validity],
        "eom": [_s(e) for e in regime.eom],
        "mass_matrix": [[_s(x) for x in regime.mass_matrix.row(i)] for i in range(regime.mass_matrix.rows)],
        "forcing": [_s(x) for x in regime.forcing],
        "accelerations": None if large else {q.func.__name__: _s(a) for q, a in acc.items()},
        "reactions": {k: _s(v) for k, v in regime.reactions.items()},
    }


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


def solution_data(sol, spec=None, answers: dict | None = None, notes: list[str] | None = None) -> dict[str, Any]:
    """The JSON object ``rigidkin solve --format json`` prints."""
    s = sol.system
    regimes = [regime_data(r) for r in sol.regimes]
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
            p.name: {"symbol": _s(p.symbol), "unit": p.unit, "description": p.description, "value": p.value}
            for p in s.parameter_info.values()},
        "definitions": {
            n: {"symbol": n, "expression": _s(d.expression), "unit": d.unit, "description": d.description,
                "value": d.value}
            for n, d in getattr(s, "definitions", {}).items()},
        "relations": {q.func.__name__: _s(e) for q, e in sol.relations.items()},
        "eom": first["eom"],
        "accelerations": first["accelerations"],
        "reactions": first["reactions"],
        "validity": first["validity"],
        "regimes": regimes,
        "answers": {},
        "answer_text": {},
        "notes": list(notes or []),
        "warnings": list(sol.warnings),
    }
    for name, a in (answers or {}).items():
        if isinstance(a, str):            # not answered: the reason
            data["answers"][name] = None
            data["answer_text"][name] = a
        else:
            data["answers"][name] = answer_value(a)
            data["answer_text"][name] = a.text
    return data
