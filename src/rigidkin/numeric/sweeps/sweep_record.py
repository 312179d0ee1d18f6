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

from ...base.errors import InputError
from ..compiled import batch
from ..compiled.cache import CacheError, build
from . import exprtree
from .gpu import GpuModel
from .sweep_plan import axes_of, axis_length, check_runs, complete, declared_state, runs_grid
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
    planner = planner_of(rec, vary, params, initial)
    return None if planner is None else planner(0, planner.runs)


def planner_of(rec: dict, vary: dict, params: dict, initial: dict, stream: int | None = None):
    """The :class:`Planner` of the sweep's runs, sized for a sweep held whole or (``stream``) streamed that many
    runs at a time; None: take the full route."""

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
    runs = check_runs([axis_length(spec) for spec in vary.values()], n_c, n_p, len(rec["events"]) + 2 * n_con + 2,
                      chunk=stream)
    planner = Planner(rec, axes_of(vary), base_p, Y0, given, runs)
    # A start off its constraints: the full route assembles it or says why.  A sweep held whole is checked here;
    # a streamed one here for its first chunk, and each later chunk as it is planned (OffConstraints).
    if not planner.on_constraints(0, min(runs, int(stream or runs) or 1)):
        return None
    planner.checked = int(stream or runs) or 1
    return planner


class OffConstraints(Exception):
    """A chunk of a streamed sweep has starts off the record's constraints: the sweep must take the full route
    (which assembles them, or says why not) from the beginning."""


class Planner:
    """The runs of a sweep from its record, any chunk of them: (inputs, P, Y) of runs ``first`` … ``stop - 1``,
    or None where a value is not finite (take the full route, which says so)."""

    def __init__(self, rec, axes, base_p, y0, given, runs):
        self.rec, self.axes, self.base_p, self.y0, self.given, self.runs = rec, axes, base_p, y0, given, runs
        self.checked = 0            # runs before this one were checked against the constraints by planner_of

    def __call__(self, first: int, stop: int):
        rec, given = self.rec, set(self.given)
        inputs, P, Y = runs_grid(None, self.base_p, self.y0, rec["parameters"], rec["labels"], given,
                                 rows=(first, stop), axes=self.axes)
        if not np.all(np.isfinite(P)) or not np.all(np.isfinite(Y)):
            return None
        rel = ([(i, tr) for i, tr in rec["coordinates"]], [(i, tr) for i, tr in rec["rates"]])
        complete(Y, P, rel, given)
        if not np.all(np.isfinite(Y)):
            return None
        return inputs, P, Y

    def checked_plan(self, first: int, stop: int):
        """:meth:`__call__`, and runs past those :func:`planner_of` checked held to the constraints (OffConstraints)."""
        planned = self(first, stop)
        if planned is not None and stop > self.checked and not self.on_constraints(first, stop, planned):
            raise OffConstraints(first)
        return planned

    def on_constraints(self, first: int, stop: int, planned=None) -> bool:
        """Whether every start of runs ``first`` … ``stop - 1`` (``planned``: their plan, made already) lies on the
        record's position constraints."""
        planned = planned or self(first, stop)
        if planned is None:
            return True             # not finite: said when the chunk is run
        _, P, Y = planned
        cols = [np.zeros(len(Y)), *Y.T, *P.T]
        n = self.rec["n"]
        tol = 1e-9 * np.maximum(1.0, np.max(np.abs(Y[:, :n]), axis=1)) if n else 1e-9
        return all(not np.any(~(np.abs(exprtree.evaluate(tree, cols, len(Y))) <= tol)) for tree in self.rec["starts"])


class _Loaded:
    """A compiled model as the batch integrator uses it: the library and the parameter count."""

    backend = "c"

    def __init__(self, ffi, lib, n_p: int):
        self.ffi, self.lib = ffi, lib
        self.kernel = SimpleNamespace(np_=n_p)      # what integrate reads of a kernel: the parameter count


def run(rec: dict, vary: dict, params: dict, initial: dict, t_end: float, rtol: float, atol: float,
        threads: int | None, chunk: int | None, stream: int | None = None, backend: str = "c"):
    """The sweep from the record (a :class:`~rigidkin.numeric.sweeps.sweep_result.SweepResult`), or None.
    ``stream``: nothing is run yet; the :class:`RecordSweep` that runs it that many runs at a time.
    ``backend``: ``"c"``, or ``"gpu"`` (the record's C file in its device form)."""
    if not _valid(rec):
        return None
    planner = planner_of(rec, vary, params, initial, stream)
    if planner is None:
        return None
    if backend == "gpu":
        model = GpuModel(rec["source"], len(rec["parameters"]))
    else:
        try:
            ffi, lib = build(rec["source"], rec["cdef"])
        except CacheError:
            return None
        model = _Loaded(ffi, lib, len(rec["parameters"]))
    out = RecordSweep(rec, planner, model, float(t_end), rtol, atol, threads, chunk)
    if stream is not None:
        return out
    planned = planner(0, planner.runs)
    return None if planned is None else out.integrate(0, *planned)


class RecordSweep:
    """A sweep answered from its record, run in parts as :class:`rigidkin.numeric.sweeps.sweep.Prepared` is."""

    def __init__(self, rec, planner: Planner, model, t_end, rtol, atol, threads, chunk):
        self.rec, self.planner, self.model, self.runs = rec, planner, model, planner.runs
        self.t_end, self.rtol, self.atol, self.threads, self.chunk = t_end, rtol, atol, threads, chunk
        self.events = [batch.Event(nm, o, d, term) for nm, o, d, term in rec["events"]]
        self.layout = Layout(rec["labels"], rec["parameters"], rec["n"])

    #: Chunks may be planned in a thread while the previous one is integrated (the planner is numpy only).
    plan_ahead = True

    def plan(self, first: int, stop: int):
        """(inputs, P, Y) of runs ``first`` … ``stop - 1``, or None where a value is not finite; OffConstraints where
        a start is off the constraints."""
        return self.planner.checked_plan(first, stop)

    def part(self, first: int, stop: int, planned=None):
        """Runs ``first`` … ``stop - 1`` (``planned``: their :meth:`plan`, made ahead): their SweepResult."""
        planned = planned or self.plan(first, stop)
        if planned is None:
            raise InputError("the sweep's values are not all finite numbers.", where="sweep")
        return self.integrate(first, *planned)

    def integrate(self, first: int, inputs, P, Y):
        """The planned runs integrated: their SweepResult."""
        res = batch.integrate(self.model, Y, P, (0.0, self.t_end), self.events, self.rtol, self.atol, np.inf,
                              workers=self.threads, chunk=self.chunk)
        return SweepResult(self.rec["system"], self.layout, inputs, P, Y, res, self.model.backend, first=first)
