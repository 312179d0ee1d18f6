"""Batch sweeps: 10⁵ ladders to wall-contact loss as one whole ``rigidkin sweep`` command, the sweep
engine alone on 10⁴ ladders and a chain of 5 rods, each against a solve_ivp loop measured in the same run.

    python benchmarks/sweep.py [--command-runs 100000] [--baseline-runs 1000] [--runs 10000] [--dask]
    python benchmarks/sweep.py --command-only          # the whole command against the loop, nothing else
    python benchmarks/sweep.py --diffrax-only [--diffrax-runs 10000 100000 1000000] [--jax-python PATH]

The whole command is timed as a user meets it: a fresh process (``rigidkin sweep ladder --param
theta=0.05:1.3:N --stop-at N_A -o runs.csv``, and ``-o runs.parquet`` when pyarrow is installed)
that starts Python, parses its options, derives (or reads the derivation cache), compiles the model
(or loads the cached library), integrates every run and writes the table.  Its CPU seconds are the
child's (``getrusage(RUSAGE_CHILDREN)``: every thread and the compiler), its wall seconds the time
the process took; the first run uses an empty cache folder (``$RIGIDKIN_CACHE``), the repeats the
one it filled.  A breakdown of one cached run into its steps is printed beside it.

The baseline is a Python loop over ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-10, atol 1e-12)
with a plainly lambdified RHS and event, on the same model and grid: ``--baseline-runs`` runs
spread evenly over the grid, timed one by one, their mean times the number of runs (an
extrapolation; the loop's own start, derivation and lambdify are not counted, which favours it).
Every figure is given as CPU seconds (what the work costs) and wall seconds (what a person waits:
on a shared machine it also counts the time other processes hold the cores).

The anchor a JAX user would pick (``--diffrax-runs``, first): diffrax under ``vmap`` (``diffrax_ladder.py``, Tsit5,
rtol 1e-10, event by Newton root finding, float64) started as a fresh process of an interpreter that has JAX
(``--jax-python``; JAX is not a dependency of rigidkin, and without it these rows are skipped with a message),
against rigidkin's integration of the same runs after compilation (1 thread and all cores) and its whole command
(cache warm, and cold), size by size in the same run; each with its max |θ_event − acos(⅔ cos θ₀)|.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import diffrax_ladder
import numpy as np
import sympy as sp
from common import machine, median_time, table
from scipy.integrate import solve_ivp


def lambdified(system, reaction: str | None = None):
    """(rhs(t, y), event(t, y) or None, p): plain lambdify of the solved rates and of a reaction."""
    from rigidkin.numeric.compiled.codegen import kernel
    from rigidkin.numeric.state import StateLayout, parameter_vector

    k = kernel(system)
    lay = StateLayout.of(system)
    p = tuple(parameter_vector(system, lay))
    if k.M is None:
        sub = dict(zip(k.unknowns, k.b))
        f = sp.lambdify(lay.arguments(), [sp.sympify(e).xreplace(sub) for e in k.rates], "numpy")

        def rhs(t, y):
            return np.array(f(t, *y, *p), dtype=float)
    else:
        Mf = sp.lambdify(lay.arguments(), [list(k.M), list(k.f)], "numpy")
        n = k.M.rows
        rates = sp.lambdify(lay.arguments() + list(k.unknowns[:n]), list(k.rates), "numpy")

        def rhs(t, y):
            M, fv = Mf(t, *y, *p)
            acc = np.linalg.solve(np.array(M, dtype=float).reshape(n, n), np.array(fv, dtype=float))
            return np.array(rates(t, *y, *p, *acc), dtype=float)
    event = None
    if reaction is not None:
        sub = dict(zip(k.unknowns, k.b))
        g = sp.lambdify(lay.arguments(), k.outputs[k.output_names.index(reaction)].xreplace(sub), "numpy")

        def event(t, y):
            return g(t, *y, *p)
        event.terminal, event.direction = True, -1
    return rhs, event, p


def baseline(rhs, event, Y0, t_end, runs: int):
    """Median seconds per run of solve_ivp over ``runs`` rows spread over Y0; and the results."""
    idx = np.linspace(0, len(Y0) - 1, runs).astype(int)
    cpu, wall, out = [], [], {}
    for i in idx:
        t0, w0 = time.process_time(), time.perf_counter()
        sol = solve_ivp(rhs, (0, t_end), Y0[i], method="DOP853", rtol=1e-10, atol=1e-12,
                        events=[event] if event else None)
        cpu.append(time.process_time() - t0)
        wall.append(time.perf_counter() - w0)
        out[i] = sol
    return statistics.median(cpu), statistics.median(wall), out


def ladder_rows(runs: int, base_runs: int, dask: bool):
    from rigidkin import examples
    from rigidkin.numeric.compiled.batch import default_workers
    from rigidkin.numeric.sweeps.sweep import sweep

    s = examples.build("ladder")
    vary = {"theta": (0.05, 1.3, runs)}
    sweep(s, {"theta": [0.5]}, stop_at="N_A")          # derive and compile once (cached)
    rows, notes = [], []
    results = {}
    for threads in sorted({1, default_workers()}):
        wall, res = median_time(lambda threads=threads: sweep(s, vary, stop_at="N_A", workers=threads), 3,
                                clock=time.perf_counter)
        cpu, _ = median_time(lambda threads=threads: sweep(s, vary, stop_at="N_A", workers=threads), 1)
        results[threads] = (wall, cpu, res)
    rhs, event, _ = lambdified(s, "N_A")
    res = results[max(results)][2]
    per_run, per_run_wall, ref = baseline(rhs, event, res.y0, 10.0, base_runs)
    loop, loop_wall = per_run * runs, per_run_wall * runs
    th0 = res.inputs["theta"]
    err_cf = float(np.max(np.abs(res.event_state("N_A", "theta") - np.arccos(2 / 3 * np.cos(th0)))))
    err_ivp = max(max(abs(res.event_time("N_A")[i] - sol.t_events[0][0]),
                      float(np.max(np.abs(res.event_state("N_A")[i] - sol.y_events[0][0])))) for i, sol in ref.items())
    for threads, (wall, cpu, _) in sorted(results.items()):
        rows.append([f"ladder C sweep, {threads} thread(s)", runs, cpu, wall, loop / cpu, loop_wall / wall,
                     "yes" if wall < 2 else "no"])
    if dask:
        try:
            from distributed import Client, LocalCluster

            with LocalCluster(n_workers=default_workers(), threads_per_worker=1, host="127.0.0.1",
                              dashboard_address=None) as cluster, Client(cluster) as client:
                sweep(s, vary, stop_at="N_A", scheduler=client)     # workers compile / load once
                wall, dres = median_time(lambda: sweep(s, vary, stop_at="N_A", scheduler=client), 3,
                                         clock=time.perf_counter)
            same = np.array_equal(dres.result.event_y, res.result.event_y)
            rows.append([f"ladder Dask LocalCluster, {default_workers()} workers", runs, None, wall, None,
                         loop_wall / wall, "yes" if wall < 2 else "no"])
            notes.append(f"Dask results identical to the local sweep: {same}")
        except ImportError:
            notes.append("dask.distributed not installed: no Dask row")
    rows.append([f"ladder solve_ivp loop (lambdify), median of {base_runs} runs × {runs}", runs, loop, loop_wall, 1.0,
                 1.0, None])
    notes.append(f"ladder: max |θ_event − acos(2/3 cos θ0)| = {err_cf:.2e} rad over {runs} runs; max difference "
                 f"from the solve_ivp runs (event time and state) = {err_ivp:.2e}")
    return rows, notes


def chain_rows(runs: int, base_runs: int):
    from rigidkin.examples import chain
    from rigidkin.numeric.sweeps.sweep import sweep

    s = chain.build(5)
    vary = {"theta1": (0.1, 1.5, runs)}
    sweep(s, {"theta1": [0.5]}, t_end=5.0)
    wall, res = median_time(lambda: sweep(s, vary, t_end=5.0), 3, clock=time.perf_counter)
    cpu, _ = median_time(lambda: sweep(s, vary, t_end=5.0), 1)
    rhs, _, _ = lambdified(s)
    per_run, per_run_wall, ref = baseline(rhs, None, res.y0, 5.0, base_runs)
    err = max(float(np.max(np.abs(res.result.y_end[i] - sol.y[:, -1]))) for i, sol in ref.items())
    loop, loop_wall = per_run * runs, per_run_wall * runs
    return [[f"chain 5 C sweep to t = 5 s ({res.backend})", runs, cpu, wall, loop / cpu, loop_wall / wall, None],
            [f"chain 5 solve_ivp loop (lambdify M, f), median of {base_runs} × {runs}", runs, loop, loop_wall, 1.0, 1.0,
             None]], [f"chain 5: max difference of the final states from the solve_ivp runs = {err:.2e}"]


# ---------------------------------------------------------------------------------------------------
# the whole command
def rigidkin_command() -> list[str]:
    """How a user starts rigidkin: the console script beside this interpreter, else ``python -m rigidkin``."""
    script = Path(sys.executable).parent / "rigidkin"
    return [str(script)] if script.exists() else [sys.executable, "-m", "rigidkin"]


def child_env(tmp, cache) -> dict:
    """The environment of a timed command: its cache folder, and its byte code kept (``PYTHONPYCACHEPREFIX``, under
    ``tmp``) as an installed package's is, even where ``PYTHONDONTWRITEBYTECODE`` is set."""
    env = dict(os.environ, RIGIDKIN_CACHE=str(cache), PYTHONPYCACHEPREFIX=str(Path(tmp) / "pyc"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def timed_command(argv: list[str], env: dict) -> tuple[float, float, str]:
    """(CPU s of the child and its children, wall s, stdout) of one command; raises on a non-zero exit."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    w0 = time.perf_counter()
    done = subprocess.run(argv, env=env, capture_output=True, text=True, timeout=1800)
    wall = time.perf_counter() - w0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)} exited {done.returncode}: {done.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, done.stdout


#: The steps of one sweep command, timed in a fresh process by the same calls ``commands/sweep.py`` makes.
_STEPS = r"""
import json, sys, time
marks = [("start", time.process_time(), time.perf_counter())]
def mark(name): marks.append((name, time.process_time(), time.perf_counter()))
from rigidkin.cli import build_parser
args = build_parser().parse_args(sys.argv[1:])
from rigidkin.commands import sweep as cmd
vary = {n: cmd.parse_axis(v, n) for n, v in cmd._pairs(args.param, "--param").items()}
mark("imports and options")
rec = None
if hasattr(cmd, "_from_record"):             # the numeric record (a repeated sweep): no sympy, nothing derived
    from rigidkin.io.derivation_cache import read_kept
    from rigidkin.numeric.sweeps.sweep_record import SUFFIX, run
    rec = read_kept(args.problem, cmd._record_options(args, {}), SUFFIX)
if rec is not None:
    mark("numeric record read (signed JSON)")
    res = run(rec, vary, {}, {}, args.t_end, args.rtol, args.atol, args.threads, args.chunk)
    mark("runs planned, compiled library loaded, 10^5 integrations")
    res.write(args.output)
    mark("table written")
else:
    from rigidkin.commands import common
    opener = getattr(common, "open_problem", None)
    problem = opener(args) if opener else None
    system = problem.system if problem else common.load_system(args.problem)[0]
    mark("problem read" + (" (derivation cache hit)" if getattr(problem, "hit", False) else ""))
    system.solve()
    from rigidkin.numeric.compiled.codegen import compile_kernel, kernel
    model = compile_kernel(kernel(system))
    mark("derivation, kernel and compiled library")
    from rigidkin.numeric.sweeps.sweep import sweep
    res = sweep(system, vary, stop_at=args.stop_at or None, workers=args.threads)
    mark("sweep (integration)")
    res.write(args.output)
    mark("table written")
    if problem is not None and hasattr(problem, "save"):
        problem.save()
print(json.dumps([(n, c1 - c0, w1 - w0) for (_, c0, w0), (n, c1, w1) in zip(marks, marks[1:])]))
"""


def command_steps(argv: list[str], env: dict) -> list[tuple[str, float, float]]:
    """(step, CPU s, wall s) of one sweep command in a fresh process (the same calls as the command)."""
    done = subprocess.run([sys.executable, "-c", _STEPS, *argv], env=env, capture_output=True, text=True,
                          timeout=1800)
    if done.returncode != 0:
        raise RuntimeError(done.stderr.strip()[-2000:])
    return [tuple(r) for r in json.loads(done.stdout.strip().splitlines()[-1])]


def read_table(path: Path) -> dict[str, np.ndarray]:
    """The initial angle and the event's time and angle of every run, from the table the command wrote."""
    names = ("theta", "N_A: t", "N_A: theta")
    if path.suffix == ".parquet":
        import pyarrow.parquet as pq

        t = pq.read_table(path, columns=list(names))
        return {c: t.column(c).to_numpy(zero_copy_only=False) for c in names}
    import csv

    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        cols = [header.index(c) for c in names]
        rows = [[float(r[i]) if r[i] else np.nan for i in cols] for r in reader]
    data = np.array(rows)
    return {c: data[:, k] for k, c in enumerate(names)}


def command_rows(runs: int, base_runs: int, repeats: int):
    """The whole ``rigidkin sweep`` of ``runs`` ladders (CSV, Parquet) against the solve_ivp loop, interleaved:
    each repeat runs the commands and then a slice of the loop's sample, so that both meet the same load."""
    from rigidkin import examples
    from rigidkin.numeric.sweeps.sweep import plan

    try:
        import pyarrow.parquet  # noqa: F401
        formats = ["csv", "parquet"]
    except ImportError:
        formats = ["csv"]
    s = examples.build("ladder")
    _, _, Y0 = plan(s, {"theta": (0.05, 1.3, runs)})
    rhs, event, _ = lambdified(s, "N_A")
    sample = np.linspace(0, runs - 1, base_runs).astype(int)
    rows, notes, times = [], [], {fmt: [] for fmt in formats}
    loop_cpu = loop_wall = 0.0
    slice_cpu = []                    # CPU seconds per run of each slice of the loop's sample
    solved = {}
    with tempfile.TemporaryDirectory(prefix="rk-sweep-bench-") as tmp:
        cache = Path(tmp) / "cache"
        cache.mkdir(mode=0o700)
        env = child_env(tmp, cache)
        base = [*rigidkin_command(), "sweep", "ladder", "--param", f"theta=0.05:1.3:{runs}", "--stop-at", "N_A"]
        first = timed_command([*base, "-o", str(Path(tmp) / "first.csv")], env)
        for part in np.array_split(sample, repeats):
            for fmt in formats:
                times[fmt].append(timed_command([*base, "-o", str(Path(tmp) / f"runs.{fmt}")], env))
            cpu0, wall0 = time.process_time(), time.perf_counter()
            for i in part.tolist():
                solved[i] = solve_ivp(rhs, (0, 10.0), Y0[i], method="DOP853", rtol=1e-10, atol=1e-12, events=[event])
            loop_cpu += time.process_time() - cpu0
            loop_wall += time.perf_counter() - wall0
            slice_cpu.append((time.process_time() - cpu0) / max(len(part), 1))
        for fmt in formats:
            t = read_table(Path(tmp) / f"runs.{fmt}")
            th0, th = t["theta"], t["N_A: theta"]
            err = float(np.max(np.abs(th - np.arccos(2 / 3 * np.cos(th0)))))
            ivp = max(abs(t["N_A: t"][i] - sol.t_events[0][0]) for i, sol in solved.items())
            notes.append(f"{fmt}: {len(th0)} rows; max |θ_event − acos(2/3 cos θ0)| = {err:.1e} rad; "
                         f"event times within {ivp:.1e} s of the solve_ivp sample")
        steps = command_steps(["sweep", "ladder", "--param", f"theta=0.05:1.3:{runs}", "--stop-at", "N_A",
                               "-o", str(Path(tmp) / "steps.csv")], env)
    loop_cpu, loop_wall = loop_cpu / base_runs * runs, loop_wall / base_runs * runs
    th_ivp = np.array([sol.y_events[0][0][0] for sol in solved.values()])
    th_cf = np.arccos(2 / 3 * np.cos(Y0[list(solved), 0]))
    notes.append(f"solve_ivp sample: max |θ_event − closed form| = {float(np.max(np.abs(th_ivp - th_cf))):.1e} rad")
    loop_best = min(slice_cpu) * runs
    results = {"first": (first[0], first[0], first[1]),
               **{fmt: (statistics.median(t[0] for t in ts), min(t[0] for t in ts), statistics.median(t[1] for t in ts))
                  for fmt, ts in times.items()}}
    labels = {"first": "whole command, first run (empty cache: derive, compile), CSV",
              "csv": f"whole command, cached, CSV ({repeats} runs)",
              "parquet": f"whole command, cached, Parquet ({repeats} runs)"}
    for key, (cpu, best, wall) in results.items():
        rows.append([labels[key], runs, cpu, best, wall, loop_cpu / cpu, loop_best / best, loop_wall / wall])
    rows.append([f"solve_ivp loop (lambdify): {base_runs} runs timed, × {runs:,}/{base_runs}", runs, loop_cpu,
                 loop_best, loop_wall, 1.0, 1.0, 1.0])
    notes.append("median: of the repeats (the loop: all its runs); best: the fastest repeat (the loop: its fastest "
                 f"slice of {base_runs // repeats} runs), the least disturbed by other processes")
    step_rows = [[name, cpu, wall] for name, cpu, wall in steps]
    step_rows.append(["sum of the steps (the command also starts and ends the interpreter)",
                      sum(r[1] for r in step_rows), sum(r[2] for r in step_rows)])
    notes.insert(0, f"command: rigidkin sweep ladder --param theta=0.05:1.3:{runs} --stop-at N_A -o runs.csv "
                    "(and -o runs.parquet)")
    return rows, notes, step_rows


# ---------------------------------------------------------------------------------------------------
# the anchor a JAX user would pick: diffrax under vmap, same CPU, same run
def rigidkin_integration(runs: int, threads: list[int], repeats: int) -> dict[int, tuple]:
    """Per thread count: (wall s, CPU s — medians of ``repeats`` —, max |θ_event − acos(⅔ cos θ₀)|, max RHS
    evaluations) of ``batch.integrate`` over ``runs`` ladders after compilation (the runs planned chunk by chunk
    first, as the command does, not timed)."""
    from rigidkin import examples
    from rigidkin.numeric.compiled.batch import integrate
    from rigidkin.numeric.sweeps.sweep import Prepared

    prep = Prepared(examples.build("ladder"), {"theta": (0.05, 1.3, runs)}, stop_at="N_A", stream=65_536)
    parts = [prep.plan(a, min(runs, a + 65_536))[1:] for a in range(0, runs, 65_536)]
    P, Y = np.concatenate([p for p, _ in parts]), np.concatenate([y for _, y in parts])
    del parts
    _, events, model = prep._model(0)
    integrate(model, Y[:100], P[:100], (0.0, 10.0), events)          # loaded, warm
    out = {}
    for w in threads:
        walls, cpus = [], []
        for _ in range(repeats):
            c0, w0 = time.process_time(), time.perf_counter()
            res = integrate(model, Y, P, (0.0, 10.0), events, workers=w)
            walls.append(time.perf_counter() - w0)
            cpus.append(time.process_time() - c0)
        err = float(np.max(np.abs(res.event_y[:, 0, 0] - np.arccos(2 / 3 * np.cos(Y[:, 0])))))
        out[w] = (statistics.median(walls), statistics.median(cpus), err, int(np.max(res.nfev)))
    return out


def anchor_rows(sizes: list[int], python: str | None, repeats: int = 3):
    """rigidkin (integration after compilation; the whole command, cached and cold) against diffrax ``vmap``
    (integration after compilation; the whole process) on this machine, size by size, interleaved.  Medians of
    ``repeats`` up to 10⁵ runs, one run above."""
    from rigidkin.numeric.compiled.batch import default_workers

    rows, notes = [], []
    if python is None:
        return rows, ["diffrax rows skipped: no interpreter with JAX and diffrax (pip install jax diffrax in a "
                      "separate environment, then --jax-python PATH or $RIGIDKIN_JAX_PYTHON)"]
    with tempfile.TemporaryDirectory(prefix="rk-anchor-") as tmp:
        cache = Path(tmp) / "cache"
        cache.mkdir(mode=0o700)
        env = child_env(tmp, cache)
        for runs in sizes:
            k = repeats if runs <= 100_000 else 1
            argv = [*rigidkin_command(), "sweep", "ladder", "--param", f"theta=0.05:1.3:{runs}", "--stop-at", "N_A",
                    "-o", str(Path(tmp) / "runs.csv")]
            cold_env = dict(env, RIGIDKIN_CACHE=str(Path(tmp) / f"cold{runs}"))
            Path(cold_env["RIGIDKIN_CACHE"]).mkdir(mode=0o700)
            cold_cpu, cold_wall, _ = timed_command(argv, cold_env)
            timed_command(argv[:-1] + [str(Path(tmp) / "warm.csv")], env)                # fill the cache
            whole = [timed_command(argv, env)[:2] for _ in range(k)]
            cmd_cpu, cmd_wall = statistics.median(c for c, _ in whole), statistics.median(w for _, w in whole)
            load = os.getloadavg()[0]
            threads = sorted({1, default_workers()})
            mine = rigidkin_integration(runs, threads, repeats)
            for w in threads:
                wall, cpu, err, nfev = mine[w]
                rows.append([f"rigidkin C, DOP853, {w} thread(s)", f"{runs:,}", wall, cpu,
                             cmd_wall if w > 1 else None, cmd_cpu if w > 1 else None,
                             cold_wall if w > 1 else None, f"{err:.1e}", nfev, f"{load:.1f}"])
            d = diffrax_ladder.run(python, runs, repeats=k)
            if "error" in d:
                notes.append(f"diffrax, {runs:,} runs: failed: {d['error']}")
                continue
            rows.append([f"diffrax {d['diffrax']} vmap, Tsit5 (JAX {d['jax']}, {d['device']})", f"{runs:,}",
                         d["integrate_s"], d["integrate_cpu_s"], d["process_s"], d["process_cpu_s"], None,
                         f"{d['max_err']:.1e}", f"~{6 * d['max_steps']}", f"{os.getloadavg()[0]:.1f}"])
            best = min(mine.values())[0]
            notes.append(f"{runs:,} runs: diffrax / rigidkin = {d['integrate_s'] / best:.1f}× integrating (wall, "
                         f"rigidkin's faster thread count), {d['integrate_cpu_s'] / mine[1][1]:.1f}× (CPU, rigidkin "
                         f"on 1 thread); whole process {d['process_s'] / cmd_wall:.1f}× (wall), "
                         f"{d['process_cpu_s'] / cmd_cpu:.1f}× (CPU); diffrax compile {d['compile_s']:.1f} s, import "
                         f"{d['import_s']:.1f} s, {d['missed']} runs without the event; medians of {k}")
    notes.append("integrate: after compilation (rigidkin: batch.integrate on the planned runs; diffrax: the "
                 "AOT-compiled jit(vmap(solve)), results on the host); whole: a fresh process, wall and CPU "
                 "(rigidkin: `rigidkin sweep ... -o runs.csv`, cache folder warm; cold: an empty one — derive, "
                 "generate and compile C; diffrax: import, trace, compile, integrate, no table written).  Both "
                 "rtol 1e-10, atol 1e-12, float64; events located by Brent (rigidkin) / Newton (diffrax).  f evals: "
                 "rigidkin's count; diffrax's steps × 6 (Tsit5, first same as last; root finding not counted).  "
                 "load: the 1-minute load average when the row was taken.")
    return rows, notes


def print_anchor(sizes: list[int], python: str | None) -> None:
    rows, notes = anchor_rows(sizes, python)
    print(table("Ladders to wall-contact loss: rigidkin against diffrax vmap on this CPU (seconds)",
                ["what", "runs", "integrate wall", "integrate CPU", "whole wall", "whole CPU", "whole cold wall",
                 "max |θ − acos(⅔cos θ0)|", "max f evals", "load"], rows, "\n".join(notes)), flush=True)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--command-runs", type=int, default=100_000, help="ladders in the whole command")
    ap.add_argument("--repeats", type=int, default=5, help="repeats of the cached whole command")
    ap.add_argument("--command-only", action="store_true", help="only the whole command against the loop")
    ap.add_argument("--runs", type=int, default=10_000)
    ap.add_argument("--chain-runs", type=int, default=1000)
    ap.add_argument("--baseline-runs", type=int, default=1000, help="solve_ivp runs sampled for the whole command")
    ap.add_argument("--engine-baseline-runs", type=int, default=100, help="solve_ivp runs sampled for the engine")
    ap.add_argument("--dask", action="store_true", help="also time a Dask LocalCluster sweep")
    ap.add_argument("--diffrax-runs", type=int, nargs="*", default=[10_000, 100_000],
                    help="sizes of the comparison with diffrax vmap (none: skip it)")
    ap.add_argument("--diffrax-only", action="store_true", help="only the comparison with diffrax")
    ap.add_argument("--jax-python", help="an interpreter with JAX and diffrax (default: diffrax_ladder.jax_python)")
    a = ap.parse_args(argv)
    print(f"# Batch sweeps ({machine()})", flush=True)
    if a.diffrax_runs and not a.command_only:
        print_anchor(a.diffrax_runs, diffrax_ladder.jax_python(a.jax_python))
    if a.diffrax_only:
        return
    rows, notes, steps = command_rows(a.command_runs, a.baseline_runs, a.repeats)
    print(table(f"Whole command: {a.command_runs:,} ladders to wall-contact loss (CPU and wall seconds)",
                ["what", "runs", "CPU s median", "CPU s best", "wall s median", "speed-up CPU median",
                 "speed-up CPU best", "speed-up wall"], rows,
                "\n".join(notes + ["speed-up = solve_ivp loop (same model, same grid, measured in this run) / "
                                    "command; target ≥ 100×."])), flush=True)
    print(table("One cached command, step by step (a fresh process making the command's calls)",
                ["step", "CPU s", "wall s"], steps), flush=True)
    if a.command_only:
        return
    rows, notes = ladder_rows(a.runs, a.engine_baseline_runs, a.dask)
    r2, n2 = chain_rows(a.chain_runs, max(10, a.engine_baseline_runs // 5))
    print(table("Sweeps (CPU and wall seconds; compiled sweeps: median of 3)",
                ["what", "runs", "CPU s", "wall s", "speed-up CPU", "speed-up wall", "wall < 2 s"], rows + r2,
                "\n".join(notes + n2 + ["speed-up = baseline (solve_ivp loop, same process, same model) / sweep; "
                                        "targets: ladder 10⁴ runs < 2 s on 2 cores and ≥ 50×."])), flush=True)


if __name__ == "__main__":
    main()
