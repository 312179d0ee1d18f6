"""``rigidkin sweep PROBLEM --param NAME=START:STOP:COUNT … -o table.csv``: many simulations at once.

Every combination of the ``--param`` axes (parameters, or initial values such as ``theta`` and
``dot(theta)``) is one run; ``--set`` and ``--initial`` fix the others.  Each run is integrated in
compiled code until ``--stop-at`` (a reaction reaching zero, ``N_A``, or a state value,
``theta=1.2``; by default the first unilateral contact that stops pushing) or ``--t-end``.  The table
has one row per run: its parameters, each event's time and state, its final state; it is written as
CSV, or as Parquet when ``-o`` names a ``.parquet`` file (pyarrow), chunk by chunk (memory bounded by the chunk:
:mod:`rigidkin.numeric.sweeps.stream`); the terminal shows how the runs ended and the range and percentiles of
every event's time; ``--plot`` draws an event quantity against a swept parameter, or a map over two.
``--workers N`` runs on a local Dask cluster, ``--scheduler ADDRESS`` on a remote one; ``--backend gpu`` on an
NVIDIA GPU (CuPy).
"""

from __future__ import annotations

import sys
import time

from ..base.errors import InputError
from ..base.outfile import check_outputs, check_target
from ..base.textsafe import terminal_safe
from ..base.units import MAX_MAGNITUDE
from ..io.derivation_cache import read_kept, write_kept
from ..io.load import value as quantity
from .common import guarded, open_problem, problem_inputs, source_of
from .deadline import set_step
from .options import add_no_cache, add_timeout, chunk, end_time, threads, tolerance, workers
from .quantities import checked, checked_events, checked_values, units_of
from .simulate import _pairs as pairs


def register(sub) -> None:

    p = sub.add_parser("sweep", help="simulate over a grid of parameters and initial values (compiled, parallel)",
                       description="Simulate one problem over a grid of parameter values and initial states, in "
                                   "compiled code, and write one table row per run.")
    p.add_argument("problem", help="a problem file or a bundled example name")
    p.add_argument("--param", nargs="+", action="extend", default=[], metavar="NAME=START:STOP:COUNT",
                   help="a swept parameter or initial value: l=1:3:50, theta=0.1:1.2:100 (or NAME=V1,V2,V3)")
    p.add_argument("--set", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="fixed parameter values; units allowed: --set \"beta=30 deg\"")
    p.add_argument("--initial", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="fixed initial coordinates and rates: --initial theta=0.2 \"dot(theta)=0\"")
    p.add_argument("--t-end", type=end_time, default=10.0, metavar="T",
                   help="end time of every run: seconds or a time with its unit ('500 ms'; default 10 s)")
    p.add_argument("--stop-at", nargs="+", action="extend", default=[], metavar="EVENT",
                   help="events that end a run: a reaction reaching zero (N_A) or NAME=VALUE "
                        "(default: any unilateral contact stops pushing)")
    p.add_argument("--record", nargs="+", action="extend", default=[], metavar="EVENT",
                   help="further events to record without stopping")
    p.add_argument("--mode", nargs="+", action="extend", default=[], metavar="CONTACT=STATE",
                   help="the mode to integrate: open, slip or stick per contact (default: all closed)")
    p.add_argument("-o", "--output", required=True, metavar="TABLE",
                   help="the table of runs: CSV, or Parquet for a .parquet or .pq file (needs pyarrow: "
                        "pip install 'rigidkin[parquet]')")
    p.add_argument("--plot", metavar="PNG", help="a figure of an event quantity (--plot-y) against the first swept "
                                                  "parameter, or a map over the first two when two are swept")
    p.add_argument("--plot-x", nargs="+", default=None, metavar="AXIS",
                   help="the swept parameter(s) of the figure: one (a curve) or two (a map)")
    p.add_argument("--plot-y", default=None, metavar="COLUMN",
                   help="the quantity drawn: a column of the table (\"N_A: theta\"), or an event's name for its time "
                        "(default: the first event's time)")
    p.add_argument("--rtol", type=tolerance, default=1e-10, help="relative tolerance (default 1e-10)")
    p.add_argument("--atol", type=tolerance, default=1e-12, help="absolute tolerance (default 1e-12)")
    p.add_argument("--threads", type=threads, default=None, metavar="N", help="local threads (default: all cores)")
    p.add_argument("--workers", type=workers, default=None, metavar="N",
                   help="run on a local Dask cluster of N worker processes")
    p.add_argument("--scheduler", metavar="ADDRESS", help="run on the Dask cluster at ADDRESS (tcp://host:8786)")
    p.add_argument("--chunk", type=chunk, default=None, metavar="RUNS", help="runs per task (default: automatic)")
    p.add_argument("--backend", choices=("auto", "c", "numpy", "gpu"), default="auto",
                   help="generated code: C (compiled here), numpy, or gpu (the same C, one run per GPU thread; needs "
                        "CuPy and an NVIDIA GPU) (default: the GPU when one is present, else C when a compiler is)")
    add_no_cache(p)
    add_timeout(p)
    p.set_defaults(func=run)


def _pairs(items, what) -> dict:

    return pairs(items, what)


def _value(text: str, where: str, unit: str | None = None) -> float:
    """A value of an axis: a plain number read as it is (SI; no unit registry to load), else through
    rigidkin's quantity parser (units checked against ``unit``'s dimension, and every refusal: not finite,
    too large, not a quantity)."""
    from ..numeric.sweeps.sweep_record import plain_number

    v = plain_number(text)
    if v is not None and abs(v) <= MAX_MAGNITUDE:
        return v
    return checked(text, unit, where) if unit else quantity(text, where)


def parse_axes(raw: dict, units: dict) -> dict:
    """The ``--param`` axes with their values in SI, each checked against the dimension of what it names."""
    return {name: parse_axis(v, f"--param {name}", units.get(name)) for name, v in raw.items()}


def parse_axis(text: str, where: str, unit: str | None = None):
    """``START:STOP:COUNT`` → (start, stop, count); ``V1,V2,…`` → a list; values may carry units."""
    text = text.strip()
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise InputError(f"'{text}' is not START:STOP:COUNT.", where=where, hint="For example theta=0.1:1.2:100.")
        try:
            count = int(parts[2])
        except ValueError:
            raise InputError(f"the count '{parts[2]}' is not a whole number.", where=where) from None
        if count < 1 or count > 10_000_000:
            raise InputError(f"the count {count} must be between 1 and 10^7.", where=where)
        return _value(parts[0], where, unit), _value(parts[1], where, unit), count
    values = [_value(v, where, unit) for v in text.split(",") if v.strip()]
    if not values:
        raise InputError(f"'{text}' gives no values.", where=where)
    return values


def run(args) -> int:
    from ..numeric.sweeps.gpu import resolve_backend
    from ..numeric.sweeps.stream import CHUNK, write_sweep
    from ..numeric.sweeps.summary import Summary
    from ..numeric.sweeps.sweep_record import OffConstraints
    from ..numeric.sweeps.tables import require_parquet, table_format

    check_target(args.output, "the sweep table")
    if table_format(args.output) == "parquet":
        require_parquet(args.output, "the sweep table")        # said before anything is derived or run
    if args.plot:
        from ..numeric.figure import figure_formats

        check_target(args.plot, "the figure", figure_formats())
    check_outputs({"-o": args.output, "--plot": args.plot}, problem_inputs(args))
    raw = _pairs(args.param, "--param")
    for name, v in raw.items():                  # the form of every axis, before anything is read or derived
        parse_axis(v, f"--param {name}")
    sets, initial, mode = _pairs(args.set, "--set"), _pairs(args.initial, "--initial"), _pairs(args.mode, "--mode")
    scheduler = args.scheduler or ("local" if args.workers else None)
    backend = resolve_backend(args.backend) if scheduler is None else args.backend
    start = time.perf_counter()
    source = _from_record(args, raw, sets, initial, mode, backend, CHUNK) \
        if scheduler is None and backend != "numpy" else None
    derived = units = None
    if source is None:
        derived, source, vary, units = _full_route(args, raw, sets, initial, mode, scheduler, backend, CHUNK)
    else:
        vary = source.vary
    set_step(f"Sweeping {source.runs:,} runs")
    x_axes, y_column = _plot_columns(args, list(raw)) if args.plot else ((), None)
    keep = (*x_axes, y_column) if args.plot else ()
    progress = _Progress(sys.stderr.isatty() and source.runs > CHUNK)
    start = time.perf_counter() if derived is not None else start
    try:
        try:
            summary, first = write_sweep(source, args.output, progress=progress, summary=Summary(source.runs, keep))
        except OffConstraints:        # a later chunk starts off the record's constraints: all again, the full way
            derived, source, vary, units = _full_route(args, raw, sets, initial, mode, scheduler, backend, CHUNK)
            start = time.perf_counter()
            summary, first = write_sweep(source, args.output, progress=progress, summary=Summary(source.runs, keep))
    finally:
        progress.close()
    if derived is not None:
        derived.save()
        if first.record is not None:
            _keep_record(args, mode, {**first.record, "units": units})
    elapsed = time.perf_counter() - start
    say = _safe_print(terminal_safe)
    counts = summary.status_counts()
    say(f"{source.runs} runs of {first.system_name} ({first.backend}) in {elapsed:.3g} s: "
        + ", ".join(f"{v} {k}" for k, v in counts.items()))
    for line in summary.lines()[1:]:
        say(line)
    say(f"Wrote the table to {args.output}")
    if args.plot:
        from ..numeric.sweeps.sweep_plot import plot_sweep

        plot_sweep(args.plot, first.system_name, summary, x_axes, y_column,
                   {k: len(v) for k, v in _axis_values(vary).items()} if summary.stride == 1 else None)
        say(f"Wrote the figure to {args.plot}")
    bad = [k for k, v in counts.items() if k not in ("reached the end time", "terminal event")]
    if bad:
        say(f"rigidkin: warning: some runs ended early ({', '.join(bad)}); see the status column.", file=sys.stderr)
    return 0


def _full_route(args, raw, sets, initial, mode, scheduler, backend, stream):
    """The sweep derived from the problem (the derivation cache, or sympy): (the opened problem, the
    :class:`~rigidkin.numeric.sweeps.sweep.Prepared` sweep, its axes in SI, the units of its quantities)."""
    from ..numeric.sweeps.sweep import Prepared

    derived = guarded(args, open_problem, args)
    system = derived.system
    units = units_of(system)
    vary = parse_axes(raw, units)
    initial = checked_values(initial, units, "--initial")
    stop_at = checked_events(args.stop_at, units, "--stop-at")
    record = checked_events(args.record, units, "--record")
    source = Prepared(system, vary, params=sets, initial=initial, t_end=args.t_end, stop_at=stop_at or None,
                      record=record, mode=mode, rtol=args.rtol, atol=args.atol,
                      workers=args.workers if scheduler else args.threads, scheduler=scheduler, chunk=args.chunk,
                      backend=backend, keep_record=not args.no_cache, stream=stream)
    return derived, source, vary, units


def _axis_values(vary) -> dict:
    from ..numeric.sweeps.sweep_plan import axes_of

    return axes_of(vary)


def _plot_columns(args, axes: list[str]) -> tuple[tuple[str, ...], str | None]:
    """The figure's swept parameters (one: a curve; two: a map) and its quantity (a table column; None: the
    first event's time, named once the events are known)."""
    x = tuple(args.plot_x or axes[:2] or ["run"])
    if len(x) > 2:
        raise InputError("a figure draws against one swept parameter, or maps over two.", where="--plot-x")
    for name in x:
        if name not in axes and name != "run":
            raise InputError(f"'{name}' is not a swept parameter of this sweep.", where="--plot-x",
                             hint=f"Swept: {', '.join(axes) or 'none'}.")
    y = args.plot_y
    if y is not None and ":" not in y and y not in ("run", "status"):
        y = f"{y}: t"                   # an event's name: its time
    return x, y
def _record_options(args, mode) -> tuple:
    from ..numeric.sweeps.sweep_record import options_key

    return options_key(mode, args.stop_at, args.record, args.backend)


def _from_record(args, vary, sets, initial, mode, backend="c", stream=None):
    """The sweep from its numeric record when a previous sweep of this problem kept one (no sympy imported,
    nothing derived), ready to stream ``stream`` runs at a time; None: take the full route."""
    from ..numeric.sweeps.sweep_record import SUFFIX, run

    rec = read_kept(source_of(args), _record_options(args, mode), SUFFIX, use=not args.no_cache)
    units = rec.get("units") if rec is not None else None
    if not isinstance(units, dict) or not all(isinstance(u, str | None) for u in units.values()):
        return None                              # no record, or one kept without the units: the full route
    vary = parse_axes(vary, units)
    initial = checked_values(initial, units, "--initial")
    source = run(rec, vary, sets, initial, args.t_end, args.rtol, args.atol, args.threads, args.chunk, stream,
                 backend)
    if source is not None:
        source.vary = vary
    return source


def _keep_record(args, mode, record: dict) -> None:
    from ..numeric.sweeps.sweep_record import SUFFIX

    write_kept(source_of(args), _record_options(args, mode), SUFFIX, record, use=not args.no_cache)


def _safe_print(safe):
    import builtins

    return lambda *a, **kw: builtins.print(*(safe(x) for x in a), **kw)


class _Progress:
    """A rich progress bar over runs on stderr (distributed sweeps report as chunks finish)."""

    def __init__(self, enabled: bool):
        self.enabled = enabled
        self.bar = None
        self.task = None

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

            self.bar = Progress(TextColumn("sweeping"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                                console=Console(stderr=True), transient=True)
            self.bar.start()
            self.task = self.bar.add_task("sweep", total=total)
        self.bar.update(self.task, completed=done)

    def close(self):
        if self.bar is not None:
            self.bar.stop()
