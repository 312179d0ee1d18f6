"""A sweep's numeric record: what a repeated ``rigidkin sweep`` of the same problem needs, as numbers.

The derivation cache gives a solved model back, but reading it imports sympy and rigidkin's model (about a
second of CPU) — most of a cached sweep of 10⁵ runs, whose integration takes less.  A sweep needs none of
the symbols: the state's layout (names), the parameters' values, the constraints that complete each initial
state (as trees of :mod:`rigidkin.numeric.sweeps.exprtree`, data and not code), the events (output, direction,
terminal) and the generated C source (to find its compiled library in the code cache, which checks it
byte for byte).  The first sweep of a problem keeps this record beside the derivation, signed the same way
(HMAC with the cache folder's own key) and keyed by the problem's content, rigidkin's code and the options
that shape the model (mode, events, backend).  A repeated sweep reads it and imports numpy only.

The full route is taken whenever the record cannot answer exactly as it would: no record, a value with a
unit (``--set "beta=30 deg"``), a name the record does not know (the full route says what is wrong), a model
with several regimes, a Dask cluster, or the numpy backend.
"""

from __future__ import annotations

import math
import re
from types import SimpleNamespace

import numpy as np

from ..compiled import batch
from ..compiled.cache import CacheError, build
from . import exprtree
from .sweep_plan import axis_length, check_runs, complete, declared_state, runs_grid
from .sweep_result import SweepResult

VERSION = 2                # 2: the start gaps a record checks before it answers
SUFFIX = ".rec"
_PLAIN = re.compile(r"[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?")


def options_key(mode: dict, stop_at, record, backend: str) -> tuple:
    """What shapes the compiled model and its events (the record's key beside the problem)."""
    return ("sweep-record", VERSION, tuple(sorted(mode.items())), tuple(stop_at or ()), tuple(record or ()),
            "c" if backend in ("auto", "c") else backend)


def make(system, layout, rel: tuple[list, list], events, source: str, cdef: str, starts=()) -> dict | None:
    """The record of a sweep's model (None where a constraint could not be written as a tree); ``starts``: the
    gaps (trees) that vanish at an assembled start."""
    if any(not isinstance(expr, list) for group in rel for _, expr in group):
        return None

    n = layout.n
    y_base = [float(v) for v in declared_state(system, n)]
    info = system.parameter_info
    base_p = [None if info[name].value is None else float(info[name].value) for name in layout.parameters]
    if not all(math.isfinite(v) for v in y_base) or not all(v is None or math.isfinite(v) for v in base_p):
        return None
    return {"version": VERSION, "system": system.name, "labels": list(layout.labels),
            "parameters": list(layout.parameters), "n": n, "base_p": base_p, "y_base": y_base,
            "coordinates": [[i, tree] for i, tree in rel[0]], "rates": [[i, tree] for i, tree in rel[1]],
            "starts": list(starts),
            "counts": [len(system.coordinate_info), len(system.parameter_info), len(system.constraints)],
            "events": [[e.name, e.output, e.direction, bool(e.terminal)] for e in events],
            "source": source, "cdef": cdef}


def _valid(rec: dict) -> bool:
    try:
        n, labels, params = rec["n"], rec["labels"], rec["parameters"]
        n_args = 1 + 2 * n + len(params)
        return (rec.get("version") == VERSION and isinstance(rec["system"], str) and len(labels) == 2 * n
                and all(isinstance(x, str) for x in labels + params) and len(rec["base_p"]) == len(params)
                and len(rec["y_base"]) == 2 * n and isinstance(rec["source"], str) and isinstance(rec["cdef"], str)
                and all(isinstance(i, int) and 0 <= i < 2 * n and exprtree.valid(tr, n_args)
                        for i, tr in rec["coordinates"] + rec["rates"])
                and all(exprtree.valid(tr, n_args) for tr in rec["starts"])
                and all(isinstance(nm, str) and isinstance(o, int) and d in (-1, 0, 1) and isinstance(term, bool)
                        for nm, o, d, term in rec["events"]) and len(rec["counts"]) == 3)
    except (KeyError, TypeError, ValueError):
        return False


class Layout:
    """The state's names, as a record keeps them (what a sweep's table needs of a StateLayout)."""

    def __init__(self, labels, parameters, n):
        self.labels, self.parameters, self.n = tuple(labels), tuple(parameters), n

    def index(self, name: str) -> int:
        return self.labels.index(name)


def plain_number(text) -> float | None:
    """A number written plainly — sign, digits, point, exponent; no unit, no ``nan``, no ``1_000`` — else None."""
    text = str(text).strip()
    return float(text) if _PLAIN.fullmatch(text) else None


def plan(rec: dict, vary: dict, params: dict, initial: dict):
    """(inputs, P, Y) as :func:`rigidkin.numeric.sweeps.sweep.plan` makes them, or None (take the full route)."""

    labels, names = rec["labels"], rec["parameters"]
    base_p = list(rec["base_p"])
    for name, value in params.items():
        v = plain_number(value)
        if name not in names or v is None:
            return None
        base_p[names.index(name)] = v
    if any(v is None or not math.isfinite(v) for v in base_p):
        return None
    Y0 = np.array(rec["y_base"], dtype=float)
    given: set[int] = set()
    for name, value in initial.items():
        v = plain_number(value)
        if name not in labels or v is None:
            return None
        Y0[labels.index(name)] = v
        given.add(labels.index(name))
    if any(k not in names and k not in labels for k in vary):
        return None
    n_c, n_p, n_con = rec["counts"]
    check_runs([axis_length(spec) for spec in vary.values()], n_c, n_p, len(rec["events"]) + 2 * n_con + 2)
    inputs, P, Y = runs_grid(vary, base_p, Y0, names, labels, given)
    if not np.all(np.isfinite(P)) or not np.all(np.isfinite(Y)):
        return None
    rel = ([(i, tr) for i, tr in rec["coordinates"]], [(i, tr) for i, tr in rec["rates"]])
    complete(Y, P, rel, given)
    if not np.all(np.isfinite(Y)):
        return None
    cols = [np.zeros(len(Y)), *Y.T, *P.T]
    tol = 1e-9 * np.maximum(1.0, np.max(np.abs(Y[:, :rec["n"]]), axis=1)) if rec["n"] else 1e-9
    for tree in rec["starts"]:        # a start off its constraints: the full route assembles it or says why
        if np.any(~(np.abs(exprtree.evaluate(tree, cols, len(Y))) <= tol)):
            return None
    return inputs, P, Y


class _Loaded:
    """A compiled model as the batch integrator uses it: the library and the parameter count."""

    backend = "c"

    def __init__(self, ffi, lib, n_p: int):
        self.ffi, self.lib = ffi, lib
        self.kernel = SimpleNamespace(np_=n_p)      # what integrate reads of a kernel: the parameter count


def run(rec: dict, vary: dict, params: dict, initial: dict, t_end: float, rtol: float, atol: float,
        threads: int | None, chunk: int | None):
    """The sweep from the record (a :class:`~rigidkin.numeric.sweeps.sweep_result.SweepResult`), or None."""
    if not _valid(rec):
        return None
    planned = plan(rec, vary, params, initial)
    if planned is None:
        return None
    inputs, P, Y = planned

    try:
        ffi, lib = build(rec["source"], rec["cdef"])
    except CacheError:
        return None
    model = _Loaded(ffi, lib, len(rec["parameters"]))
    events = [batch.Event(nm, o, d, term) for nm, o, d, term in rec["events"]]
    res = batch.integrate(model, Y, P, (0.0, float(t_end)), events, rtol, atol, np.inf, workers=threads, chunk=chunk)
    layout = Layout(rec["labels"], rec["parameters"], rec["n"])
    return SweepResult(rec["system"], layout, inputs, P, Y, res, "c")
