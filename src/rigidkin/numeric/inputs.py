"""Input histories for a simulation: each input u(t) of a system (:mod:`rigidkin.model.inputs`) given as

* a number (held constant) or a sympy expression of time ``rigidkin.t`` (and parameters), e.g.
  ``2*sin(3*t)``;
* a table of samples ``(times, values)`` (two sequences, or an (n, 2) array of rows t, u):
  interpolated linearly, held at the end values outside the table;
* a Python callable ``u(t, state)`` for feedback, ``state`` a dict ``{"x": …, "dot(x)": …}`` of the
  current coordinates and rates (e.g. ``lambda t, s: -k*s["theta"] - c*s["dot(theta)"]``).

An input is bound in the parameter vector (its slot is set at each evaluation of the equations, so
every mode, reaction and energy monitor sees the same u(t)).  :func:`binding` makes that function;
:data:`ACTIVE` holds it while a simulation runs.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from contextvars import ContextVar

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.errors import InputError
from ..model.inputs import inputs_of
from .compiled.codesafe import safe_lambdify

t = dynamicsymbols._t

#: The input binding of the simulation in progress: (t, y, p) → p with the inputs' slots set (None: none).
ACTIVE: ContextVar = ContextVar("rigidkin_inputs", default=None)


def _table(name, value) -> Callable:
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 2 and arr.shape[1] == 2 and arr.shape[0] != 2:
        arr = arr.T
    if arr.ndim != 2 or arr.shape[0] != 2 or arr.shape[1] < 2:
        raise InputError(f"the table of input {name} is not two rows (times, values) of at least two samples.",
                         where=f"input {name}", hint="Give (times, values), e.g. ([0, 1, 2], [0, 5, 5]).")
    ts, us = arr
    if not np.all(np.isfinite(arr)) or np.any(np.diff(ts) <= 0):
        raise InputError(f"the times of input {name}'s table are not finite and increasing.", where=f"input {name}")
    return lambda tt, y, ts=ts, us=us: float(np.interp(tt, ts, us))


def _expression(name, expr, system, layout, p0) -> Callable:
    e = sp.sympify(expr)
    params = {s: float(v) for s, v in zip(layout.parameter_symbols, p0)}
    inputs = {i.symbol for i in inputs_of(system).values()}
    e = e.xreplace({s: v for s, v in params.items() if s not in inputs})
    extra = e.free_symbols - {t}
    if extra or e.atoms(sp.core.function.AppliedUndef):
        raise InputError(f"the history of input {name}, {e}, depends on {', '.join(map(str, extra)) or 'a coordinate'}"
                         " as well as on time.", where=f"input {name}",
                         hint="Write it in t and the parameters, or give a function of (t, state) for feedback.")
    f = safe_lambdify([t], [e], where=f"input {name}")
    return lambda tt, y, f=f: float(f(tt)[0])


def _callable(name, fn, layout) -> Callable:
    labels = layout.labels

    def call(tt, y):
        try:
            v = float(fn(tt, dict(zip(labels, map(float, y[:len(labels)])))))
        except (TypeError, ValueError) as err:
            raise InputError(f"the function given for input {name} did not return a number at t = {tt:g} ({err}).",
                             where=f"input {name}", hint="It is called as u(t, state) with state a dict of the "
                                                         "coordinates and rates by name.") from None
        return v

    return call


def binding(system, layout, inputs: Mapping | None, p0) -> Callable | None:
    """(t, y, p) → p with every input's slot set to its value, from ``inputs`` (name → history); None when
    the system has no inputs.  Refuses an unknown name and an input left without a history."""
    declared = inputs_of(system)
    given = dict(inputs or {})
    unknown = [k for k in given if str(k) not in declared]
    if unknown:
        raise InputError(f"{', '.join(map(str, unknown))} is not an input of {system.name}.", where="simulate inputs",
                         hint=f"Inputs: {', '.join(declared) or 'none (declare them with System.input)'}.")
    if not declared:
        return None
    for k, i in declared.items():                 # the history declared with the input (a problem file's)
        if k not in {str(g) for g in given} and i.history is not None:
            given[k] = i.history
    missing = [k for k in declared if k not in {str(g) for g in given}]
    if missing:
        raise InputError(f"the inputs {', '.join(missing)} have no history.", where="simulate",
                         hint="Give each input as a number, an expression of t, a table (times, values) or a "
                              "function of (t, state): simulate(..., inputs={'" + missing[0] + "': ...}); in a "
                              "problem file, history = \"...\" (an expression of t) in its [inputs] table.")
    fns = []
    for key, value in given.items():
        name = str(key)
        slot = layout.parameters.index(name)
        if callable(value) and not isinstance(value, sp.Basic):
            f = _callable(name, value, layout)
        elif isinstance(value, (list, tuple, np.ndarray)):
            f = _table(name, value)
        elif isinstance(value, (int, float, sp.Basic)) and not isinstance(value, bool):
            f = _expression(name, value, system, layout, p0)
        else:
            raise InputError(f"{value!r} is not a history for input {name}.", where=f"input {name}",
                             hint="Give a number, an expression of t, a table (times, values) or a function of "
                                  "(t, state).")
        fns.append((slot, f))

    def bind(tt, y, p):
        p = np.array(p, dtype=float)
        for slot, f in fns:
            p[slot] = f(tt, y)
        return p

    return bind


def placeholders(system) -> dict:
    """Parameter overrides that give each input a value (0) until it is bound at each evaluation."""
    return dict.fromkeys(inputs_of(system), 0.0)


def histories(system, layout, times, Y, params) -> dict:
    """The inputs' values at each sample (name → array) under the binding of the simulation in progress: what
    the equations saw, feedback included; {} when the system has no inputs or none is bound."""
    bind = ACTIVE.get()
    declared = inputs_of(system)
    if bind is None or not declared:
        return {}
    slots = {name: layout.parameters.index(name) for name in declared if name in layout.parameters}
    out = {name: np.empty(len(times)) for name in slots}
    for j, tt in enumerate(times):
        p = bind(float(tt), Y[:, j], params)
        for name, slot in slots.items():
            out[name][j] = p[slot]
    return out
