"""Sweeps: one model simulated over many parameter sets and initial states at once.

``sweep(system, vary={...})`` builds the grid of runs (every combination of the varied parameters
and initial values), completes each initial state through the constraints of the mode (dependent
coordinates and rates), and integrates all runs in compiled C (:mod:`rigidkin.numeric.batch`) in
one mode until a stop event: by default the first unilateral contact that stops pushing (the mode
ends there).  Each run gives one row: its parameters and initial values, the time and state of
each event, its final state.  With ``scheduler=`` (an address, or ``workers=N`` for a local
cluster) the runs are distributed over a Dask cluster in chunks; the results are identical to the
local sweep, run for run, because every run is integrated by the same generated code.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..errors import InputError, RigidkinError
from . import batch
from .codegen import CompiledModel, Kernel, compile_kernel, kernel
from .state import StateLayout, parameter_vector, quantity

t = dynamicsymbols._t


@dataclass(frozen=True)
class StopAt:
    """An event of a sweep: ``name`` (a reaction reaching zero, or ``q=VALUE`` / ``dot(q)=VALUE``)."""

    name: str
    expr: sp.Expr | None        # None: the kernel output of that name
    direction: int
    terminal: bool


@dataclass
class SweepResult:
    """The runs of a sweep: their inputs (``columns`` of the grid) and the batch result."""

    system_name: str
    layout: StateLayout
    inputs: dict[str, np.ndarray]          # varied parameters and initial values, per run
    params: np.ndarray                     # runs × n_p (every parameter)
    y0: np.ndarray                         # runs × 2n
    result: batch.BatchResult
    backend: str

    def __len__(self) -> int:
        return len(self.result)

    @property
    def status(self) -> np.ndarray:
        return self.result.status

    def event_time(self, name: str) -> np.ndarray:
        return self.result.event_t[:, self._event(name)]

    def event_state(self, name: str, slot: str | None = None) -> np.ndarray:
        y = self.result.event_y[:, self._event(name)]
        return y if slot is None else y[:, self.layout.index(slot)]

    def _event(self, name):
        try:
            return self.result.event_names.index(name)
        except ValueError:
            raise InputError(f"'{name}' is not an event of this sweep.",
                             hint=f"Events: {', '.join(self.result.event_names)}.") from None

    def columns(self) -> dict[str, np.ndarray]:
        """The table: one column per input, parameter, event time and state, final time and state, status."""
        cols: dict[str, np.ndarray] = {"run": np.arange(len(self))}
        for j, name in enumerate(self.layout.parameters):
            cols[name] = self.params[:, j]
        for name, values in self.inputs.items():
            if name not in cols:
                cols[name] = values
        for k, ev in enumerate(self.result.event_names):
            cols[f"{ev}: t"] = self.result.event_t[:, k]
            for i, lab in enumerate(self.layout.labels):
                cols[f"{ev}: {lab}"] = self.result.event_y[:, k, i]
        cols["end: t"] = self.result.t_end
        for i, lab in enumerate(self.layout.labels):
            cols[f"end: {lab}"] = self.result.y_end[:, i]
        cols["status"] = status_text(self.result.status)
        return cols

    def metadata(self) -> dict[str, str]:
        """What a Parquet table keeps beside its columns: the system, the backend, the events."""
        return {"rigidkin.system": self.system_name, "rigidkin.backend": self.backend,
                "rigidkin.events": "\n".join(self.result.event_names)}

    def write(self, path) -> Path:
        """Write the table to ``path``: Parquet for ``.parquet``/``.pq`` (needs pyarrow), CSV otherwise; whole or
        not at all (OutputError: why not).  See :mod:`rigidkin.numeric.tables`."""
        from .tables import write_table

        return write_table(self.columns(), path, "the sweep table", self.metadata())

    def to_csv(self, path) -> Path:
        """Write the table as CSV (numbers as ``repr`` writes them, missing values empty, names neutralised)."""
        from .tables import write_csv

        return write_csv(self.columns(), path, "the sweep table")

    def to_parquet(self, path) -> Path:
        """Write the table as Parquet (needs pyarrow; missing values as nulls)."""
        from .tables import write_parquet

        return write_parquet(self.columns(), path, "the sweep table", self.metadata())

    def plot(self, path, x: str | None = None, y: str | None = None) -> Path:
        """A figure of one table column against another (default: the first event's time against the first input)."""
        from matplotlib.figure import Figure

        from .figure import save_figure

        cols = self.columns()
        x = x or (next(iter(self.inputs)) if self.inputs else "run")
        if y is None:
            y = f"{self.result.event_names[0]}: t" if self.result.event_names else "end: t"
        for c in (x, y):
            if c not in cols:
                raise InputError(f"'{c}' is not a column of the sweep table.", hint=f"Columns: {', '.join(cols)}.")
        fig = Figure(figsize=(7, 4.5), layout="constrained")
        ax = fig.subplots()
        xs, ys = np.asarray(cols[x], dtype=float), np.asarray(cols[y], dtype=float)
        order = np.argsort(xs, kind="stable")
        ax.plot(xs[order], ys[order], ".", ms=3 if len(xs) > 200 else 6)
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        ax.set_title(f"{self.system_name}: {len(self)} runs")
        ax.grid(alpha=0.3)
        return save_figure(fig, path, dpi=120)


def status_text(codes: np.ndarray) -> np.ndarray:
    """The status of each run in words (:data:`rigidkin.numeric.batch.STATUS`), as an object array."""
    codes = np.asarray(codes).reshape(-1)
    if not codes.size:
        return np.empty(0, dtype=object)
    u, inverse = np.unique(codes, return_inverse=True)
    words = np.array([batch.STATUS.get(int(c), f"status {int(c)}") for c in u.tolist()], dtype=object)
    return words[inverse.reshape(-1)]


# ---------------------------------------------------------------------------------------------------
def axis(spec) -> np.ndarray:
    """Values of a swept quantity: an array, or ``(start, stop, count)`` (inclusive, evenly spaced)."""
    if isinstance(spec, tuple) and len(spec) == 3:
        start, stop, count = spec
        if int(count) != count or count < 1:
            raise InputError(f"the count of a sweep axis must be a whole number ≥ 1, not {count}.")
        return np.linspace(float(start), float(stop), int(count))
    arr = np.atleast_1d(np.asarray(spec, dtype=float))
    if arr.ndim != 1 or not np.all(np.isfinite(arr)):
        raise InputError("the values of a sweep axis must be finite numbers.")
    return arr


def event_aliases(system, mode) -> dict[str, str]:
    """The names simulate gives contacts' events (``contact A opens``) → the reaction that reaches zero (``N_A``)."""
    from ..mode import setup_mode

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
    from ..mode import setup_mode

    return [str(r) for r, _ in setup_mode(system, mode).unilateral]


def axis_length(spec) -> int:
    """How many values an axis spec gives, without making them."""
    if isinstance(spec, tuple) and len(spec) == 3:
        try:
            return max(int(spec[2]), 0)
        except (TypeError, ValueError, OverflowError):
            raise InputError(f"the count of a sweep axis must be a whole number ≥ 1, not {spec[2]!r}.") from None
    return int(np.size(spec))


def check_size(system, vary: Mapping | None, grid: bool = True, events: int = 4) -> int:
    """The number of runs of a sweep, refused (InputError) when its table would not fit in memory.

    Every run keeps its parameters, inputs, initial and final states, and each event's time and
    state (``events``: how many events, estimated); see :data:`rigidkin.limits.MEMORY_LIMIT`.
    """
    from ..limits import check_memory, sweep_bytes

    lengths = [axis_length(spec) for spec in (vary or {}).values()]
    runs = (math.prod(lengths) if grid else max(lengths)) if lengths else 1
    n, n_p = len(system.coordinate_info), len(system.parameter_info)
    per_run = 3 * n_p + 2 * len(lengths) + 6 * 2 * n + 2 * events * (2 * n + 1) + 8
    check_memory(sweep_bytes(runs, per_run), f"a sweep of {runs:,} runs", "sweep",
                 hint="Use fewer values per axis (or fewer axes), or split the sweep into several and join the "
                      "tables.")
    return runs


def plan(system, vary: Mapping | None = None, params: Mapping | None = None, initial: Mapping | None = None,
         mode: Mapping | None = None, grid: bool = True, events: int = 4) -> tuple[dict, np.ndarray, np.ndarray]:
    """The runs: (inputs per run, parameters runs × n_p, initial states runs × 2n).

    ``vary`` maps parameter names or initial values (``theta``, ``dot(theta)``) to axis specs; with
    ``grid`` every combination is a run, otherwise the axes are zipped (equal lengths).  The size is
    checked (:func:`check_size`) before anything is allocated.
    """
    from ..mode import setup_mode

    check_size(system, vary, grid, events)
    layout = StateLayout.of(system)
    base_p = parameter_vector(system, layout, params)
    n = layout.n
    y_base = np.zeros(2 * n)
    given: set[int] = set()
    for i, c in enumerate(system.coordinate_info.values()):
        if c.initial is not None:
            y_base[i] = float(c.initial)
        if c.rate is not None:
            y_base[n + i] = float(c.rate)
    for key, value in (initial or {}).items():
        i = layout.index(str(key))
        y_base[i] = quantity(value, None, f"initial {key}")
        given.add(i)
    axes: dict[str, np.ndarray] = {}
    for key, spec in (vary or {}).items():
        axes[str(key)] = axis(spec)
    if grid:
        mesh = np.meshgrid(*axes.values(), indexing="ij") if axes else []
        inputs = {k: m.ravel() for k, m in zip(axes, mesh)}
        runs = int(np.prod([len(a) for a in axes.values()])) if axes else 1
    else:
        lengths = {len(a) for a in axes.values()}
        if len(lengths) > 1:
            raise InputError("zipped sweep axes must have equal lengths.", hint="Use a grid, or give equal counts.")
        inputs = dict(axes)
        runs = lengths.pop() if lengths else 1
    P = np.tile(base_p, (runs, 1))
    Y = np.tile(y_base, (runs, 1))
    for name, values in inputs.items():
        if name in layout.parameters:
            P[:, layout.parameters.index(name)] = values
        else:
            try:
                i = layout.index(name)
            except InputError:
                raise InputError(f"'{name}' is neither a parameter nor a coordinate or rate of {system.name}.",
                                 where="sweep", hint=f"Parameters: {', '.join(layout.parameters)}; state: "
                                                     f"{', '.join(layout.labels)}.") from None
            Y[:, i] = values
            given.add(i)
    if not np.all(np.isfinite(P)) or not np.all(np.isfinite(Y)):
        raise InputError("the sweep's values are not all finite numbers.", where="sweep")
    # dependent coordinates and rates from the constraints of the mode, run by run (vectorised)
    red = setup_mode(system, dict(mode or {})).reduction
    args = layout.arguments()
    for q, expr in red.coord_map.items():
        i = layout.coordinates.index(q)
        if i not in given:
            Y[:, i] = _vector_eval(args, layout.to_plain(expr), [np.zeros(runs), *Y.T, *P.T], runs)
    cols = [np.zeros(runs), *Y.T, *P.T]
    for q in red.dependent:
        i = layout.coordinates.index(q)
        if n + i not in given:
            Y[:, n + i] = _vector_eval(args, layout.to_plain(red.rate_map[q.diff(t)]), cols, runs)
    return inputs, P, Y


#: lambdify's namespace: numpy's own functions (``modules="numpy"`` would star-import numpy's every submodule,
#: a tenth of a second at each command's start).
_NUMPY = ({"numpy": np}, np)


def _vector_eval(args, expr, columns, runs) -> np.ndarray:
    """``expr`` (of the layout's arguments) at every run at once."""
    from .codesafe import safe_lambdify

    f = safe_lambdify(args, [expr], modules=list(_NUMPY), cse=False, where="sweep")
    with np.errstate(all="ignore"):
        return np.broadcast_to(np.asarray(f(*columns)[0], dtype=float), (runs,)).copy()


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
          progress: Callable[[int, int], None] | None = None) -> SweepResult:
    """Simulate ``system`` for every combination of ``vary`` (parameters and initial values).

    One mode (``mode``, default: every contact closed) is integrated.  Each run starts in the regime
    whose sign conditions its initial state satisfies (``regime`` forces one); a run that fits none
    (a slip speed exactly zero) is not integrated and says so in its status.  ``stop_at``: events
    that end a run (default: a unilateral contact stops pushing, the regime's sign condition or
    another validity condition fails — the mode or regime ends there); ``record``: further events
    recorded without stopping.  ``scheduler``: a Dask scheduler address, a ``distributed.Client``,
    or ``"local"`` (a LocalCluster of ``workers`` processes).

    >>> import numpy as np
    >>> from rigidkin import examples
    >>> from rigidkin.numeric.sweep import sweep
    >>> res = sweep(examples.build("ladder"), {"theta": (0.2, 0.6, 3)}, stop_at="N_A")
    >>> [f"{v:.9f}" for v in np.cos(res.event_state("N_A", "theta")) / np.cos([0.2, 0.4, 0.6])]   # 2/3
    ['0.666666667', '0.666666667', '0.666666667']
    """
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
    layout = StateLayout.of(system)
    stops = [stop_at] if isinstance(stop_at, str) else list(stop_at or [])
    inputs, P, Y = plan(system, vary, params, initial, mode, grid,
                        events=len(stops) + len(record) + 2 * len(system.constraints) + 2)
    if regime is not None or form == "implicit":
        which = np.full(len(Y), regime or 0)
    else:
        n_regimes = len(system.solve(mode=mode).regimes)
        which = np.zeros(len(Y), dtype=int) if n_regimes == 1 else _assign_regimes(system, mode, layout, Y, P)
    parts, used, names = {}, "c", None
    groups = [int(r) for r in np.unique(which) if r >= 0] or [0]
    done = 0
    for r in groups:
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
            aliases.get(str(s).strip(), s) for s in record) if s not in stops]
        extra = [e for e in events if e.expr is not None]
        if extra:
            k = k.with_outputs([e.name for e in extra], [e.expr for e in extra])
        bev = [batch.Event(e.name, k.output_index(e.name), e.direction, e.terminal) for e in events]
        names = names or tuple(e.name for e in bev)
        idx = np.flatnonzero(which == r)
        if not len(idx):
            continue
        sub_progress = None if progress is None else (lambda d, _t, base=done: progress(base + d, len(Y)))
        if scheduler is None:
            model = compile_kernel(k, backend)
            res = batch.integrate(model, Y[idx], P[idx], (0.0, t_end), bev, rtol, atol, max_step, workers=workers,
                                  chunk=chunk)
            if sub_progress:
                sub_progress(len(idx), len(idx))
            used = model.backend
        else:
            from .batch_dask import integrate_dask

            res = integrate_dask(k, Y[idx], P[idx], (0.0, t_end), bev, rtol, atol, max_step, scheduler=scheduler,
                                 workers=workers, chunk=chunk, progress=sub_progress)
            used = "c (dask)"
        done += len(idx)
        parts[r] = (idx, res)
    return SweepResult(system.name, layout, inputs, P, Y, _merge(parts, Y, names or ()), used)


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
