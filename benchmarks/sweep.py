"""Batch sweeps: 10⁴ ladder runs to wall-contact loss, and a chain of 5 rods, against solve_ivp loops.

    python benchmarks/sweep.py [--runs 10000] [--baseline-runs 100] [--dask]

The baseline is a Python loop over ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-10, atol 1e-12)
with a plainly lambdified RHS and event, on the same model: its median time per run (over
``--baseline-runs`` runs spread over the same grid) times the number of runs.  Every figure is
given twice: CPU seconds of this process (all threads; what the work costs) and wall seconds (what
a person waits: on a shared machine it also counts the time other processes hold the cores).
Speed-ups are CPU ratios; the wall ratio is shown beside them.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
import sympy as sp
from common import machine, median_time, table
from scipy.integrate import solve_ivp


def lambdified(system, reaction: str | None = None):
    """(rhs(t, y), event(t, y) or None, p): plain lambdify of the solved rates and of a reaction."""
    from rigidkin.numeric.codegen import kernel
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
    from rigidkin.numeric.batch import default_workers
    from rigidkin.numeric.sweep import sweep

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
    from rigidkin.numeric.sweep import sweep

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


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10_000)
    ap.add_argument("--chain-runs", type=int, default=1000)
    ap.add_argument("--baseline-runs", type=int, default=100)
    ap.add_argument("--dask", action="store_true", help="also time a Dask LocalCluster sweep")
    a = ap.parse_args(argv)
    print(f"# Batch sweeps ({machine()})", flush=True)
    rows, notes = ladder_rows(a.runs, a.baseline_runs, a.dask)
    r2, n2 = chain_rows(a.chain_runs, max(10, a.baseline_runs // 5))
    print(table("Sweeps (CPU and wall seconds; compiled sweeps: median of 3)",
                ["what", "runs", "CPU s", "wall s", "speed-up CPU", "speed-up wall", "wall < 2 s"], rows + r2,
                "\n".join(notes + n2 + ["speed-up = baseline (solve_ivp loop, same process, same model) / sweep; "
                                        "targets: ladder 10⁴ runs < 2 s on 2 cores and ≥ 50×."])), flush=True)


if __name__ == "__main__":
    main()
