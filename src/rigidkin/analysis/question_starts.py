"""A question's starting state (its ``start`` or ``at`` table) put onto the position constraints by the one rule
for starting states (:func:`rigidkin.numeric.state.assemble`), or refused naming the constraint and its residual.

The coordinates the question gives, the ones it leaves out completed from the constraints' closed forms (else the
declared ``initial``, else zero), are checked numerically with the parameters' values (and the question's ``set``)
in the question's mode.  A start already on the constraints is kept exactly as written; one that Newton's method
moves is answered from the assembled values, with a warning naming what moved; one that cannot be assembled is an
InputError naming the constraint and its residual.  Nothing is checked where a parameter has no value.
"""

from __future__ import annotations

import warnings

import numpy as np
import sympy as sp

from ..base.errors import InputError, RigidkinError
from ..derive.derivation import derivation_of
from ..numeric.contacts.modes import Hybrid
from ..numeric.contacts.vocabulary import OPEN, ModeUnavailable
from ..numeric.state import assembled_changes, initial_values, parameter_vector
from .linear import dependent_coordinates


def _number(value, values: dict) -> float | None:
    try:
        v = complex(sp.sympify(value).xreplace(values).evalf())
    except (TypeError, ValueError, sp.SympifyError):
        return None
    return v.real if abs(v.imag) <= 1e-12 * max(1.0, abs(v.real)) and np.isfinite(v.real) else None


def assembled_start(system, start: dict, mode: dict | None = None, substitutions: dict | None = None,
                    where: str = "start") -> dict:
    """``start`` ({q or q̇: value}) with its coordinates on the position constraints of ``mode``: unchanged
    (exact) when it is on them within the assembly tolerance, else the assembled values (a RuntimeWarning says
    which moved); InputError from :func:`rigidkin.numeric.state.assemble` when it cannot be assembled."""
    coords = {k: v for k, v in start.items() if not isinstance(k, sp.Derivative)}
    if not coords or any(p.value is None for p in system.parameter_info.values()):
        return start
    hyb = derivation_of(system).hybrid(lambda: Hybrid(system))
    lay = hyb.layout
    subs = {str(getattr(k, "name", k)): v for k, v in (substitutions or {}).items()}
    if any(_number(v, {}) is None for v in subs.values()):
        return start
    p = parameter_vector(system, lay, {k: _number(v, {}) for k, v in subs.items()})
    values = {s: float(v) for s, v in zip(lay.parameter_symbols, p)}
    full = {name: (mode or {}).get(name) or c.default_state(hyb.kin) for name, c in hyb.contacts.items()}
    if all(st == OPEN for st in full.values()) and not hyb.position_constraints(full).labels:
        return start
    given = {}
    for k, v in coords.items():
        x = _number(v, values)
        if x is None or k not in lay.coordinates:
            return start                       # not a number with the parameters' values: nothing to check
        given[lay.coordinates.index(k)] = x
    _, declared = initial_values(system, lay)
    y = np.zeros(2 * lay.n)
    for i, x in {**{i: x for i, x in declared.items() if i < lay.n}, **given}.items():
        y[i] = x
    for k, v in start.items():                 # the given rates: the relations of the mode may use them
        if isinstance(k, sp.Derivative) and k.expr in lay.coordinates and (x := _number(v, values)) is not None:
            y[lay.n + lay.coordinates.index(k.expr)] = x
    try:
        rel_slots, rel_fn, _, _ = hyb.relation_functions(full, integrated=True)
    except ModeUnavailable:
        return start
    for s, v in zip(rel_slots, rel_fn(0.0, *y, *p) if rel_slots else ()):
        if s < lay.n and np.isfinite(float(v)):     # the mode's closed forms (x = l sin θ on the wall) decide
            y[s] = float(v)
    y = hyb.assemble(full, 0.0, y, p, where)
    scale = max(1.0, float(np.max(np.abs(y[:lay.n]))))
    for name in hyb.contacts:                      # a closed contact, unilateral too, touches its surface
        gap = float(hyb.contact_state(name, 0.0, y, p)[0]) if full[name] != OPEN else 0.0
        if not abs(gap) <= 1e-9 * scale:
            raise InputError(f"the starting state cannot be assembled onto the position constraints: contact {name} "
                             f"keeps a gap of {abs(gap):.4g} although the question's mode has it closed.",
                             where=where, hint="Give starting values of the coordinates at which the closed contacts "
                                               "touch their surfaces, or set the contact's mode to open.")
    moved = assembled_changes(lay, given, y)
    if not moved:
        return start
    warnings.warn(f"{where}: the starting state is not on the constraints; it is assembled onto them (Newton's "
                  "method from the values given): " + ", ".join(f"{nm} = {b:.10g} (given {a:.10g})"
                                                                for nm, (a, b) in moved.items()),
                  RuntimeWarning, stacklevel=2)
    out = dict(start)
    for nm in moved:
        i = lay.names.index(nm)
        out[lay.coordinates[i]] = sp.Float(float(y[i]), 15)
    out.update(_closed_form(system, lay, y, start, moved, mode, substitutions, values))
    return out


def _closed_form(system, lay, y, start, moved, mode, substitutions, values) -> dict:
    """The moved coordinates in closed form (the position constraints solved by sympy on the branch Newton's
    method found, e.g. θ = asin(c/l)), or {} where sympy finds none."""
    qs = [lay.coordinates[lay.names.index(nm)] for nm in moved]
    known = {q: start.get(q, sp.Float(float(y[i]), 15)) for i, q in enumerate(lay.coordinates) if q not in qs}
    try:
        sol = system.solve(mode=dict(mode or {}), substitutions=dict(substitutions or {}))
        rel = {q: sp.sympify(sol.relations[q]).xreplace(known) for q in qs if q in sol.relations}
        found = [rel] if len(rel) == len(qs) else dependent_coordinates(sol, qs, known, values)
    except (RigidkinError, TypeError, ValueError):
        return {}
    for conf in found:
        nums = [_number(conf.get(q), values) for q in qs]
        if all(x is not None and abs(x - y[lay.coordinates.index(q)]) <= 1e-9 * max(1.0, abs(x))
               for x, q in zip(nums, qs)):
            return {q: conf[q] for q in qs}
    return {}


def question_fields(system, fields: dict, where: str = "") -> dict:
    """A question's fields with its ``start`` and ``at`` assembled onto the constraints of its mode."""
    out = dict(fields)
    for key in ("start", "at"):
        if out.get(key):
            out[key] = assembled_start(system, dict(out[key]), dict(out.get("mode") or {}),
                                       dict(out.get("set") or {}), f"{where or 'question'}, {key}")
    return out
