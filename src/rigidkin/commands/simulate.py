"""``rigidkin simulate PROBLEM --t-end T``: simulate through contact and friction modes.

``--set NAME=VALUE`` gives parameter values (``--set "beta=30 deg"``; a bare number is SI),
``--initial NAME=VALUE`` initial coordinates and rates (``--initial theta=1e-6 "dot(theta)=0"``),
``--mode CONTACT=open|slip|stick`` the starting state of a contact (a rope or cable: open|taut), ``--restitution E`` (or
``CONTACT=E``) the coefficient of restitution of impacts, ``--input NAME=EXPR`` an input u(t) as an
expression of t and the parameters (read by the restricted expression parser).  ``--plot``, ``--csv`` write the figure
and the histories; ``--json`` prints the events, the final state and the energy drift.
"""

from __future__ import annotations

import math
import sys
import time
import warnings

from ..base.errors import InputError
from ..base.limits import check_memory, history_bytes
from ..base.outfile import check_outputs, check_target
from ..base.textsafe import terminal_safe
from .common import guarded, json_safe, open_problem, problem_inputs
from .deadline import set_step
from .options import EXIT_STOPPED, add_no_cache, add_timeout, end_time, points, start_time, tolerance
from .quantities import checked_values, units_of


def register(sub) -> None:

    p = sub.add_parser("simulate", help="simulate the motion, switching contact and friction modes exactly",
                       description="Simulate a problem through its contact modes (contacts opening, impacts, "
                                   "rolling and slipping), with events located exactly.")
    p.add_argument("problem", help="a problem file or a bundled example name")
    p.add_argument("--t-end", type=end_time, required=True, metavar="T",
                   help="end time: seconds (5) or a time with its unit ('500 ms', '2 min')")
    p.add_argument("--t-start", type=start_time, default=0.0, metavar="T0",
                   help="start time: seconds or a time with its unit ('20 ms'; default 0)")
    p.add_argument("--set", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="parameter values; units allowed: --set \"beta=30 deg\" m=2")
    p.add_argument("--initial", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="initial coordinates and rates: --initial theta=1e-6 \"dot(theta)=0\"")
    p.add_argument("--mode", nargs="+", action="extend", default=[], metavar="CONTACT=STATE",
                   help="starting state of a contact: open, slip or stick; of a rope or cable: open (slack) or taut")
    p.add_argument("--restitution", nargs="+", action="extend", default=[], metavar="E|CONTACT=E",
                   help="coefficient of restitution of impacts, for all contacts or per contact (or per rope or "
                        "cable: its jerk; default: the restitution in the problem file, else 0)")
    p.add_argument("--input", nargs="+", action="extend", default=[], metavar="NAME=EXPR",
                   help="an input u(t) as an expression of t and the parameters, e.g. --input \"F=3*sin(2*t)\" "
                        "(default: the input's history in the problem file)")
    p.add_argument("--plot", metavar="PNG", help="write a figure of the histories")
    p.add_argument("--csv", metavar="CSV", help="write the histories as CSV")
    p.add_argument("--json", action="store_true", help="print events, final state and energy drift as JSON")
    p.add_argument("--points", type=points, default=1001,
                   help="samples in the histories (default 1001; refused when they would not fit in memory)")
    p.add_argument("--rtol", type=tolerance, default=1e-11, help="relative tolerance (default 1e-11)")
    p.add_argument("--atol", type=tolerance, default=1e-13, help="absolute tolerance (default 1e-13)")
    p.add_argument("--method", default="DOP853", help="solve_ivp method: DOP853 (default) or Radau, BDF, …")
    add_no_cache(p)
    add_timeout(p)
    p.set_defaults(func=run)


def _pairs(items: list[str], what: str) -> dict:
    out = {}
    for item in items:
        if "=" not in item:
            raise InputError(f"'{item}' is not NAME=VALUE.", where=what,
                             hint=f"Write {what} NAME=VALUE, e.g. {what} theta=0.1 (quote values with spaces).")
        name, value = item.split("=", 1)
        name, value = name.strip(), value.strip()
        if not name or not value:
            raise InputError(f"'{item}' has an empty name or value.", where=what)
        out[name] = value
    return out


def _restitution(items: list[str]):
    if not items:
        return None                 # each contact's coefficient from the problem file (or 0)
    if len(items) == 1 and "=" not in items[0]:
        return _number(items[0], "--restitution")
    return {k: _number(v, "--restitution") for k, v in _pairs(items, "--restitution").items()}


def _inputs(given: dict, system) -> dict:
    """Each ``--input NAME=EXPR`` read by the restricted expression parser (no eval): an expression of t."""
    from ..io.expressions import parse_scalar
    from ..io.problem import system_scope

    scope = system_scope(system, reactions=False)
    return {name: parse_scalar(text, scope, f"--input {name}") for name, text in given.items()}


def _number(text: str, where: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise InputError(f"'{text}' is not a number.", where=where) from None
    if not math.isfinite(v):
        raise InputError(f"'{text}' is not a finite number.", where=where, hint="Give a number from 0 to 1.")
    return v


class _Progress:
    """A rich progress bar on stderr, shown only when a run takes longer than a second."""

    def __init__(self, enabled: bool):
        self.enabled = enabled
        self.start = time.monotonic()
        self.bar = None
        self.task = None

    def __call__(self, t_: float, t_end: float) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            if time.monotonic() - self.start < 1.0:
                return
            from rich.console import Console
            from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

            self.bar = Progress(TextColumn("simulating"), BarColumn(), TextColumn("t = {task.fields[t]:.4g} s"),
                                TimeElapsedColumn(), console=Console(stderr=True), transient=True)
            self.bar.start()
            self.task = self.bar.add_task("sim", total=t_end, t=t_)
        self.bar.update(self.task, completed=t_, t=t_)

    def close(self):
        if self.bar is not None:
            self.bar.stop()


def _simulate(system, span, **kw):
    """:func:`rigidkin.numeric.simulate`, an arithmetic overflow anywhere in it reported as the model stopping."""
    from ..numeric import simulate
    from ..numeric.rhs import SimulationError

    try:
        return simulate(system, span, **kw)
    except (OverflowError, ZeroDivisionError, FloatingPointError) as exc:
        raise SimulationError(f"the arithmetic failed while simulating ({exc}).", where=system.name,
                              hint="A load or a relation of the model grows beyond floating-point range; check "
                                   "its expressions and the initial state.") from None


def check_points(system, points: int) -> None:
    """Refuse ``--points`` whose histories would not fit in memory (estimated before anything is sampled)."""

    n, n_c = len(system.coordinate_info), len(system.constraints)
    columns = 2 * n + 1 + 8 * n_c + 6          # t, state, work; reactions (6 at a 3D joint), friction limits; T, U, E
    check_memory(history_bytes(points, columns), f"{points:,} samples of {columns} histories", "--points",
                 hint="Ask for fewer samples (the default 1001 draws a smooth figure; events are exact whatever the "
                      "sampling).")


def run(args) -> int:
    """Exit status 0, or 3 (EXIT_STOPPED) when the simulation stops before its end time."""
    from ..numeric.figure import figure_formats
    from ..numeric.rhs import SimulationError

    if args.csv:
        check_target(args.csv, "the histories")
    if args.plot:
        check_target(args.plot, "the figure", figure_formats())
    check_outputs({"--csv": args.csv, "--plot": args.plot}, problem_inputs(args))
    if not args.t_end > args.t_start:
        raise InputError(f"the end time {args.t_end:g} s is not after the start time {args.t_start:g} s.",
                         where="--t-end", hint="Give --t-end greater than --t-start.")
    params = _pairs(args.set, "--set")
    initial = _pairs(args.initial, "--initial")
    mode = _pairs(args.mode, "--mode")
    restitution = _restitution(args.restitution)
    derived = guarded(args, open_problem, args)
    system = derived.system
    initial = checked_values(initial, units_of(system), "--initial")
    inputs = _inputs(_pairs(args.input, "--input"), system)
    check_points(system, args.points)
    progress = _Progress(sys.stderr.isatty() and not args.json)
    set_step(f"Simulating to t = {args.t_end:g} s")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        try:
            result = guarded(args, _simulate, system, (args.t_start, args.t_end), initial_state=initial,
                             params=params, mode=mode, restitution=restitution, method=args.method, inputs=inputs,
                             rtol=args.rtol, atol=args.atol, n_points=args.points, progress=progress)
        except SimulationError as exc:
            print(f"rigidkin: the model cannot go on: {terminal_safe(exc)}", file=sys.stderr)
            derived.save()
            return EXIT_STOPPED
        finally:
            progress.close()
    del caught
    derived.save()
    set_step("Writing the histories and the figure")
    if args.csv:
        result.write_csv(args.csv)
    if args.plot:
        result.plot(args.plot)
    if args.json:
        print(json_safe(result.to_json()))
    else:
        print(terminal_safe(result))
        print("Final state: " + ", ".join(f"{k} = {v:.10g}" for k, v in result.final_state.items()))
        for path, what in ((args.plot, "figure"), (args.csv, "histories")):
            if path:
                print(terminal_safe(f"Wrote the {what} to {path}"))
    for w in result.warnings:
        print(f"rigidkin: warning: {terminal_safe(w)}", file=sys.stderr)
    moved = getattr(result, "assembled", {})
    if moved:                        # the start put onto the position constraints (numeric.state.assemble)
        print(terminal_safe("rigidkin: note: the starting state is assembled onto the constraints: " + ", ".join(
            f"{nm} = {b:.10g} (declared {a:.10g})" for nm, (a, b) in moved.items())), file=sys.stderr)
    if not result.reached_end:       # stopped early: the model cannot go on (reason and state printed above)
        print(terminal_safe(f"rigidkin: the simulation stopped at t = {result.t_final:.10g} before the end time "
                            f"({result.stop_reason}): {result.message}"), file=sys.stderr)
        return EXIT_STOPPED
    return 0
