"""Sweeps: one model simulated over many parameter sets and initial states at once.

``sweep(system, vary={...})`` builds the grid of runs (every combination of the varied parameters
and initial values), completes each initial state through the constraints of the mode (dependent
coordinates and rates), and integrates all runs in compiled C (:mod:`rigidkin.numeric.compiled.batch`) in
one mode until a stop event: by default the first unilateral contact that stops pushing (the mode
ends there).  Each run gives one row: its parameters and initial values, the time and state of
each event, its final state.  With ``scheduler=`` (an address, or ``workers=N`` for a local
cluster) the runs are distributed over a Dask cluster in chunks; the results are identical to the
local sweep, run for run, because every run is integrated by the same generated code.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base.errors import InputError, RigidkinError
from ...derive.mode import setup_mode
from ..compiled import batch
from ..compiled.batch import INTEGRATOR_C, INTEGRATOR_CDEF
from ..compiled.codegen import CompiledModel, compile_kernel, kernel
from ..compiled.codesafe import safe_lambdify
from ..compiled.csource import _CDEF, c_source
from ..compiled.kernel import Kernel
from ..state import StateLayout, parameter_vector, quantity
from .batch_dask import integrate_dask
from .exprtree import NotEncodable, encode
from .gpu import GpuModel, resolve_backend
from .sweep_plan import axes_of, axis, axis_length, check_runs, complete, declared_state, runs_grid, sweep_runs  # noqa: F401  (public here)
from .sweep_record import make
from .sweep_result import SweepResult, status_text  # noqa: F401  (public through here)
from .sweep_start import assemble_runs, start_gaps

t = dynamicsymbols._t


@dataclass(frozen=True)
class StopAt:
    """An event of a sweep: ``name`` (a reaction reaching zero, or ``q=VALUE`` / ``dot(q)=VALUE``)."""

    name: str
    expr: sp.Expr | None        # None: the kernel output of that name
    direction: int
    terminal: bool


# ---------------------------------------------------------------------------------------------------
def event_aliases(system, mode) -> dict[str, str]:
    """The names simulate gives contacts' events (``contact A opens``) → the reaction that reaches zero (``N_A``)."""

    return {f"contact {row.constraint} opens": str(r) for r, row in setup_mode(system, mode).unilateral}


def stop_event(layout: StateLayout, k: Kernel, spec: str, terminal: bool = True,
               aliases: Mapping[str, str] | None = None) -> StopAt:
    """``N_A`` or ``contact A opens`` (a reaction reaching zero, by its name or the event's name in
    simulate's output), or ``theta=1.2`` / ``dot(theta)=0`` (a state value)."""
    spec = str(spec).strip()
    spec = (aliases or {}).get(spec, spec)
    if "=" in spec:
        name, _, value = spec.partition("=")
        name = name.strip()
        i = layout.index(name)          # clear error for an unknown coordinate
        v = quantity(value.strip(), None, f"event {spec}")
        q, u = layout.plain_symbols()
        sym = (q + u)[i]
        return StopAt(f"{name}={value.strip()}", sym - v, 0, terminal)
    if spec in k.output_names:
        return StopAt(spec, None, -1, terminal)
    raise InputError(f"'{spec}' is not an event of this model.", where="stop-at",
                     hint=f"Use a reaction ({', '.join(k.output_names) or 'none'}) reaching zero"
                          f"{' or its event (' + ', '.join(aliases) + ')' if aliases else ''}, or "
                          f"NAME=VALUE with a coordinate or rate ({', '.join(layout.labels)}).")


def _mode_events(system, mode) -> list[str]:

    return [str(r) for r, _ in setup_mode(system, mode).unilateral]


def check_size(system, vary: Mapping | None, grid: bool = True, events: int = 4, chunk: int | None = None) -> int:
    """The number of runs of a sweep, refused (InputError) when its table would not fit in memory.

    Every run keeps its parameters, inputs, initial and final states, and each event's time and
    state (``events``: how many events, estimated); see :data:`rigidkin.base.limits.MEMORY_LIMIT`.
    """
    lengths = [axis_length(spec) for spec in (vary or {}).values()]
    return check_runs(lengths, len(system.coordinate_info), len(system.parameter_info), events, grid, chunk)


def plan(system, vary: Mapping | None = None, params: Mapping | None = None, initial: Mapping | None = None,
         mode: Mapping | None = None, grid: bool = True, events: int = 4) -> tuple[dict, np.ndarray, np.ndarray]:
    """The runs: (inputs per run, parameters runs × n_p, initial states runs × 2n).

    ``vary`` maps parameter names or initial values (``theta``, ``dot(theta)``) to axis specs; with
    ``grid`` every combination is a run, otherwise the axes are zipped (equal lengths).  The size is
    checked (:func:`check_size`) before anything is allocated.
    """

    check_size(system, vary, grid, events)
    layout = StateLayout.of(system)
    base_p = parameter_vector(system, layout, params)
    y_base = declared_state(system, layout.n)
    given: set[int] = set()
    for key, value in (initial or {}).items():
        i = layout.index(str(key))
        y_base[i] = quantity(value, None, f"initial {key}")
        given.add(i)

    def unknown(name):
        return InputError(f"'{name}' is neither a parameter nor a coordinate or rate of {system.name}.",
                          where="sweep", hint=f"Parameters: {', '.join(layout.parameters)}; state: "
                                              f"{', '.join(layout.labels)}.")

    inputs, P, Y = runs_grid(vary, base_p, y_base, layout.parameters, layout.labels, given, grid, unknown)
    if not np.all(np.isfinite(P)) or not np.all(np.isfinite(Y)):
        raise InputError("the sweep's values are not all finite numbers.", where="sweep")
    rel, symbolic = relations(system, mode, layout), functools.partial(_vector_eval, layout.arguments())
    rough = Y.copy()
    complete(Y, P, rel, given, symbolic)
    unreal = ~np.isfinite(Y)             # a relation with no real value here: the assembly says why
    Y[unreal] = rough[unreal]
    if assemble_runs(system, mode, layout, Y, P):    # simulate's rule: Newton onto the constraints, or refused
        complete(Y, P, ([], rel[1]), given, symbolic)
    return inputs, P, Y


def relations(system, mode, layout: StateLayout) -> tuple[list, list]:
    """The constraints of the mode as (state slot, expression) pairs: the dependent coordinates, then the
    dependent rates, each an expression of the layout's arguments (t, q, u, p) — a tree of
    :mod:`rigidkin.numeric.sweeps.exprtree` where it can be one, else the sympy expression."""

    red = setup_mode(system, dict(mode or {})).reduction
    index = {a: i for i, a in enumerate(layout.arguments())}

    def tree(expr):
        plain = layout.to_plain(expr)
        try:
            return encode(plain, index)
        except NotEncodable:
            return plain

    n = layout.n
    coords = [(layout.coordinates.index(q), tree(expr)) for q, expr in red.coord_map.items()]
    rates = [(n + layout.coordinates.index(q), tree(red.rate_map[q.diff(t)])) for q in red.dependent]
    return coords, rates


def _condition_events(system, mode, regime: int, layout: StateLayout) -> list[StopAt]:
    """The regime's sign conditions and the validity conditions other than unilateral contacts, as events."""
    reg = system.solve(mode=mode).regime(regime)
    out, seen = [], set()
    for c in (*reg.conditions, *reg.validity):
        if c.kind == "validity" and "unilateral" in c.label:
            continue                      # the reaction's own event covers it
        name = c.label
        while name in seen:
            name += "'"
        seen.add(name)
        holds_positive = c.relation in (">", ">=")
        out.append(StopAt(name, layout.to_plain(c.expr), -1 if holds_positive else 1, True))
    return out


#: lambdify's namespace: numpy's own functions (``modules="numpy"`` would star-import numpy's every submodule,
#: a tenth of a second at each command's start).
_NUMPY = ({"numpy": np}, np)


def _vector_eval(args, expr, columns, runs) -> np.ndarray:
    """``expr`` (of the layout's arguments) at every run at once."""
    f = safe_lambdify(args, [expr], modules=list(_NUMPY), cse=False, where="sweep")
    with np.errstate(all="ignore"):
        return np.broadcast_to(np.asarray(f(*columns)[0], dtype=float), (runs,)).copy()


def _assign_regimes(system, mode, layout: StateLayout, Y: np.ndarray, P: np.ndarray) -> np.ndarray:
    """The regime whose sign conditions hold at each run's initial state (-1: none holds)."""
    sol = system.solve(mode=mode)
    runs = len(Y)
    which = np.full(runs, -1)
    cols = [np.zeros(runs), *Y.T, *P.T]
    for i, reg in enumerate(sol.regimes):
        ok = np.ones(runs, dtype=bool)
        for c in reg.conditions:
            v = _vector_eval(layout.arguments(), layout.to_plain(c.expr), cols, runs)
            ok &= {">": v > 0, ">=": v >= 0, "<": v < 0, "<=": v <= 0}[c.relation]
        which[(which < 0) & ok] = i
    return which


def sweep(system, vary: Mapping | None = None, params: Mapping | None = None, initial: Mapping | None = None, *,
          t_end: float = 10.0, stop_at: Sequence[str] | str | None = None, record: Sequence[str] = (),
          mode: Mapping | None = None, regime: int | None = None, grid: bool = True, rtol: float = 1e-10,
          atol: float = 1e-12, max_step: float = np.inf, workers: int | None = None, scheduler=None,
          chunk: int | None = None, form: str = "auto", backend: str = "auto",
          progress: Callable[[int, int], None] | None = None, keep_record: bool = False) -> SweepResult:
    """Simulate ``system`` for every combination of ``vary`` (parameters and initial values).

    One mode (``mode``, default: every contact closed) is integrated.  Each run starts in the regime
    whose sign conditions its initial state satisfies (``regime`` forces one); a run that fits none
    (a slip speed exactly zero) is not integrated and says so in its status.  ``stop_at``: events
    that end a run (default: a unilateral contact stops pushing, the regime's sign condition or
    another validity condition fails — the mode or regime ends there); ``record``: further events
    recorded without stopping.  ``scheduler``: a Dask scheduler address, a ``distributed.Client``,
    or ``"local"`` (a LocalCluster of ``workers`` processes).  ``keep_record``: make the sweep's numeric
    record (``result.record``, :mod:`rigidkin.numeric.sweeps.sweep_record`) where one can answer a repeat.
    ``backend``: ``"c"``, ``"numpy"``, ``"gpu"`` (:mod:`rigidkin.numeric.sweeps.gpu`) or ``"auto"`` (the GPU
    when one is present, else C when a compiler is).  The whole sweep is held in memory; a sweep of any
    size streams to a table with :func:`rigidkin.numeric.sweeps.stream.write_sweep` over :class:`Prepared`.

    >>> import numpy as np
    >>> from rigidkin import examples
    >>> from rigidkin.numeric.sweeps.sweep import sweep
    >>> res = sweep(examples.build("ladder"), {"theta": (0.2, 0.6, 3)}, stop_at="N_A")
    >>> [f"{v:.9f}" for v in np.cos(res.event_state("N_A", "theta")) / np.cos([0.2, 0.4, 0.6])]   # 2/3
    ['0.666666667', '0.666666667', '0.666666667']
    """
    prep = Prepared(system, vary, params, initial, t_end=t_end, stop_at=stop_at, record=record, mode=mode,
                    regime=regime, grid=grid, rtol=rtol, atol=atol, max_step=max_step, workers=workers,
                    scheduler=scheduler, chunk=chunk, form=form, backend=backend, keep_record=keep_record,
                    stream=None)
    return prep.part(0, prep.runs, progress)


class Prepared:
    """A sweep made ready to run in parts: its axes, base values, constraints, kernels and events, once.

    ``part(first, stop)`` integrates runs ``first`` … ``stop - 1`` (in the order of the whole grid) and gives
    their :class:`SweepResult` (its ``run`` column counts from ``first``).  ``stream``: the runs held at once
    when the sweep is written chunk by chunk (the memory check counts those, not the whole sweep); None: the
    whole sweep is held (checked whole).
    """

    def __init__(self, system, vary=None, params=None, initial=None, *, t_end=10.0, stop_at=None, record=(),
                 mode=None, regime=None, grid=True, rtol=1e-10, atol=1e-12, max_step=np.inf, workers=None,
                 scheduler=None, chunk=None, form="auto", backend="auto", keep_record=False, stream=None):
        mode = dict(mode or {})
        try:
            t_end = float(t_end)
        except (TypeError, ValueError):
            raise InputError(f"the end time must be a number, not {t_end!r}.", where="sweep") from None
        if not np.isfinite(t_end) or t_end <= 0:
            raise InputError(f"the end time must be a positive finite number, not {t_end}.", where="sweep")
        for name, tol in (("rtol", rtol), ("atol", atol)):
            if not isinstance(tol, (int, float)) or not math.isfinite(tol) or not 0 < tol < 1:
                raise InputError(f"the tolerance {name} = {tol!r} must be a positive number below 1.", where="sweep",
                                 hint="For example rtol=1e-10, atol=1e-12.")
        self.system, self.mode, self.t_end, self.stop_at, self.record = system, mode, t_end, stop_at, record
        self.regime, self.form, self.rtol, self.atol, self.max_step = regime, form, rtol, atol, max_step
        self.workers, self.scheduler, self.chunk, self.keep_record = workers, scheduler, chunk, keep_record
        self.backend = resolve_backend(backend) if scheduler is None else backend
        self.layout = layout = StateLayout.of(system)
        stops = [stop_at] if isinstance(stop_at, str) else list(stop_at or [])
        self.runs = check_size(system, vary, grid, len(stops) + len(record) + 2 * len(system.constraints) + 2,
                               chunk=stream)
        self.grid, self.vary = grid, vary
        self.base_p = parameter_vector(system, layout, params)
        self.y_base = declared_state(system, layout.n)
        self.given: set[int] = set()
        for key, value in (initial or {}).items():
            i = layout.index(str(key))
            self.y_base[i] = quantity(value, None, f"initial {key}")
            self.given.add(i)
        self.axes = axes_of(vary)
        sweep_runs(self.axes, grid)                 # zipped axes of unequal lengths: said before anything runs
        for name in self.axes:
            if name not in layout.parameters and name not in layout.labels:
                raise _unknown(system, layout, name)
        self.rel = relations(system, mode, layout)
        self.n_regimes = None if (regime is not None or form == "implicit") else len(system.solve(mode=mode).regimes)
        self.models: dict = {}
        self.names = None
        self.record_kept = None

    def plan(self, first: int, stop: int):
        """(inputs, P, Y) of runs ``first`` … ``stop - 1``: the grid's values, each state completed."""
        layout, given = self.layout, set(self.given)
        inputs, P, Y = runs_grid(self.vary, self.base_p, self.y_base, layout.parameters, layout.labels, given,
                                 self.grid, functools.partial(_unknown, self.system, layout), (first, stop), self.axes)
        if not np.all(np.isfinite(P)) or not np.all(np.isfinite(Y)):
            raise InputError("the sweep's values are not all finite numbers.", where="sweep")
        symbolic = functools.partial(_vector_eval, layout.arguments())
        rough = Y.copy()
        complete(Y, P, self.rel, given, symbolic)
        unreal = ~np.isfinite(Y)             # a relation with no real value here: the assembly says why
        Y[unreal] = rough[unreal]
        if assemble_runs(self.system, self.mode, layout, Y, P, first=first):   # simulate's rule, or refused
            complete(Y, P, ([], self.rel[1]), given, symbolic)
        return inputs, P, Y

    def _model(self, r: int):
        """Regime ``r``'s kernel (with the sweep's events as outputs), its events, and its compiled model."""
        if r in self.models:
            return self.models[r]
        system, mode, layout, form, stop_at = self.system, self.mode, self.layout, self.form, self.stop_at
        k = kernel(system, mode, r, form)
        stops = [stop_at] if isinstance(stop_at, str) else list(stop_at or [])
        aliases = event_aliases(system, mode)
        stops = [aliases.get(str(s).strip(), s) for s in stops]
        events = [stop_event(layout, k, s, True, aliases) for s in stops]
        if stop_at is None:
            events = [stop_event(layout, k, s, True) for s in _mode_events(system, mode)]
            if form != "implicit":
                events += _condition_events(system, mode, r, layout)
        events += [stop_event(layout, k, s, False, aliases) for s in dict.fromkeys(
            aliases.get(str(s).strip(), s) for s in self.record) if s not in stops]
        extra = [e for e in events if e.expr is not None]
        if extra:
            k = k.with_outputs([e.name for e in extra], [e.expr for e in extra])
        bev = [batch.Event(e.name, k.output_index(e.name), e.direction, e.terminal) for e in events]
        model = None
        if self.scheduler is None:
            model = compile_kernel(k, "c" if self.backend == "gpu" else self.backend)
            if self.backend == "gpu":
                model = GpuModel(c_source(k) + INTEGRATOR_C, k.np_)
        self.models[r] = (k, bev, model)
        return self.models[r]

    def part(self, first: int, stop: int, progress: Callable[[int, int], None] | None = None) -> SweepResult:
        """Runs ``first`` … ``stop - 1`` integrated: their :class:`SweepResult`."""
        inputs, P, Y = self.plan(first, stop)
        system, mode, layout = self.system, self.mode, self.layout
        if self.n_regimes is None:
            which = np.full(len(Y), self.regime or 0)
        else:
            which = np.zeros(len(Y), dtype=int) if self.n_regimes == 1 else _assign_regimes(system, mode, layout, Y, P)
        parts, used = {}, "c"
        groups = [int(r) for r in np.unique(which) if r >= 0] or [0]
        done = 0
        for r in groups:
            k, bev, model = self._model(r)
            self.names = self.names or tuple(e.name for e in bev)
            idx = np.flatnonzero(which == r)
            if not len(idx):
                continue
            sub_progress = None if progress is None else (lambda d, _t, base=done: progress(base + d, len(Y)))
            if self.scheduler is None:
                res = batch.integrate(model, Y[idx], P[idx], (0.0, self.t_end), bev, self.rtol, self.atol,
                                      self.max_step, workers=self.workers, chunk=self.chunk)
                if sub_progress:
                    sub_progress(len(idx), len(idx))
                used = model.backend
                if self.keep_record and self.n_regimes == 1 and used in ("c", "gpu") and self.record_kept is None:
                    self.record_kept = _record(system, mode, layout, k, bev)
            else:
                res = integrate_dask(k, Y[idx], P[idx], (0.0, self.t_end), bev, self.rtol, self.atol, self.max_step,
                                     scheduler=self.scheduler, workers=self.workers, chunk=self.chunk,
                                     progress=sub_progress)
                used = "c (dask)"
            done += len(idx)
            parts[r] = (idx, res)
        out = SweepResult(system.name, layout, inputs, P, Y, _merge(parts, Y, self.names or ()), used, first=first)
        out.record = self.record_kept
        return out


def _unknown(system, layout, name):
    return InputError(f"'{name}' is neither a parameter nor a coordinate or rate of {system.name}.",
                      where="sweep", hint=f"Parameters: {', '.join(layout.parameters)}; state: "
                                          f"{', '.join(layout.labels)}.")


def _record(system, mode, layout: StateLayout, k: Kernel, events) -> dict | None:
    """The numeric record of this sweep's model (see :mod:`rigidkin.numeric.sweeps.sweep_record`)."""

    index = {a: i for i, a in enumerate(layout.arguments())}
    try:                 # the gaps each start must close (a record answers only starts already assembled)
        starts = [encode(g, index) for g in start_gaps(system, mode, layout)]
    except NotEncodable:
        return None
    return make(system, layout, relations(system, mode, layout), events, c_source(k) + INTEGRATOR_C,
                _CDEF + INTEGRATOR_CDEF, starts)


def _merge(parts: dict, Y: np.ndarray, names: tuple) -> batch.BatchResult:
    """The runs of every regime group back in grid order; runs that fit no regime keep status 6."""
    n, ny, ne = Y.shape[0], Y.shape[1], len(names)
    out = batch.BatchResult(names, np.full((n, ne), np.nan), np.full((n, ne, ny), np.nan), np.zeros(n), Y.copy(),
                            np.full(n, 6), np.zeros(n, dtype=int))
    for idx, res in parts.values():
        if res.event_names != names:
            raise RigidkinError("the regimes of this mode give different events.", where="sweep",
                                hint="Sweep one regime at a time (regime=...).")
        out.event_t[idx], out.event_y[idx], out.t_end[idx] = res.event_t, res.event_y, res.t_end
        out.y_end[idx], out.status[idx], out.nfev[idx] = res.y_end, res.status, res.nfev
    return out


def model_of(system, mode=None, regime=0, form="auto", backend="auto") -> CompiledModel:
    """The compiled model a sweep of ``system`` uses."""
    return compile_kernel(kernel(system, mode, regime, form), backend)
