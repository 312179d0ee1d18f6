"""The anchor a JAX user would pick: diffrax under ``vmap``, N ladders released from rest at θ₀ ∈ [0.05, 1.3] to the
loss of wall contact — the same problem as ``rigidkin sweep ladder --param theta=0.05:1.3:N --stop-at N_A``.

    /work/jaxenv/bin/python benchmarks/diffrax_ladder.py --runs 100000 [--device cpu|gpu] [--repeats 1]

Run with an interpreter that has JAX and diffrax (``pip install jax diffrax``; ``jax[cuda12]`` for a GPU): they are
not rigidkin's dependencies, and ``benchmarks/sweep.py`` / ``sweep_gpu.py`` start this script as a subprocess.
The model is written as a JAX user would write it by hand: a uniform rod (m = 10 kg, l = 2 m, g = 9.81 m/s²)
on a smooth wall and floor, one degree of freedom θ (from the upward vertical), θ̈ = 3g/(2l) sin θ, and the wall
reaction N_A = m (l/2)(θ̈ cos θ − θ̇² sin θ), computed from the state.  Tsit5, PID step control rtol 1e-10, atol
1e-12, float64, the event N_A = 0 located by Newton root finding (optimistix, rtol = atol = 1e-12), one
``jit(vmap(solve))`` over all runs at once.

Prints one JSON line: the device, the runs, the compile seconds (``jit(...).lower(...).compile()``), the
integration seconds of the compiled function (results on the host; the median of ``--repeats``; wall, and CPU of
every thread of the process), the largest
|θ_event − acos(⅔ cos θ₀)|, the largest number of steps and how many runs did not reach the event.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

T0 = time.perf_counter()

M, L, G = 10.0, 2.0, 9.81


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=100_000)
    ap.add_argument("--device", choices=("cpu", "gpu"), default="cpu")
    ap.add_argument("--repeats", type=int, default=1, help="timed calls of the compiled function (median)")
    ap.add_argument("--t-end", type=float, default=10.0)
    args = ap.parse_args(argv)

    import jax

    jax.config.update("jax_enable_x64", True)
    if args.device == "cpu":
        jax.config.update("jax_platforms", "cpu")
    import diffrax
    import jax.numpy as jnp
    import numpy as np
    import optimistix as optx

    try:
        dev = jax.devices("gpu" if args.device == "gpu" else "cpu")[0]
    except RuntimeError as exc:
        print(json.dumps({"error": f"JAX {jax.__version__} sees no {args.device.upper()} here ({exc}); "
                                   "pip install 'jax[cuda12]' for a GPU"}))
        sys.exit(2)
    imported = time.perf_counter() - T0

    def accel(theta):
        return 1.5 * G / L * jnp.sin(theta)

    def rates(t, y, args):
        return jnp.stack([y[1], accel(y[0])])

    def wall_reaction(t, y, args, **kwargs):
        theta, omega = y[0], y[1]
        return M * L / 2 * (accel(theta) * jnp.cos(theta) - omega ** 2 * jnp.sin(theta))

    term = diffrax.ODETerm(rates)
    solver = diffrax.Tsit5()
    control = diffrax.PIDController(rtol=1e-10, atol=1e-12)
    event = diffrax.Event(wall_reaction, root_finder=optx.Newton(rtol=1e-12, atol=1e-12))

    def one(theta0):
        sol = diffrax.diffeqsolve(term, solver, t0=0.0, t1=args.t_end, dt0=None, y0=jnp.stack([theta0, 0.0 * theta0]),
                                  stepsize_controller=control, event=event, saveat=diffrax.SaveAt(t1=True),
                                  max_steps=100_000, throw=False)
        return sol.ts[-1], sol.ys[-1], sol.stats["num_steps"], sol.event_mask

    th0 = jax.device_put(jnp.asarray(np.linspace(0.05, 1.3, args.runs)), dev)
    t0 = time.perf_counter()
    compiled = jax.jit(jax.vmap(one)).lower(th0).compile()
    compile_s = time.perf_counter() - t0
    times, cpu = [], []
    for _ in range(max(1, args.repeats)):
        t0, c0 = time.perf_counter(), time.process_time()
        t_ev, y_ev, steps, mask = jax.block_until_ready(compiled(th0))
        t_ev, y_ev, steps, mask = (np.asarray(a) for a in (t_ev, y_ev, steps, mask))
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    th0h = np.asarray(th0)
    err = float(np.max(np.abs(y_ev[:, 0] - np.arccos(2.0 / 3.0 * np.cos(th0h)))))
    print(json.dumps({"device": str(dev.device_kind if args.device == "gpu" else dev.platform),
                      "runs": args.runs, "import_s": imported, "compile_s": compile_s,
                      "integrate_s": statistics.median(times),
                      "integrate_cpu_s": statistics.median(cpu), "max_err": err, "max_steps": int(steps.max()),
                      "missed": int(np.sum(~np.asarray(mask).reshape(args.runs, -1).any(axis=1))),
                      "t_event_median": float(np.median(t_ev)), "jax": jax.__version__,
                      "diffrax": diffrax.__version__, "script_s": time.perf_counter() - T0}), flush=True)


# ---------------------------------------------------------------------------------------------------------------
# for the benchmarks that start this script (run by rigidkin's interpreter: nothing here imports JAX)
def jax_python(given: str | None = None) -> str | None:
    """An interpreter with JAX and diffrax: ``given``, ``$RIGIDKIN_JAX_PYTHON``, this one if it has them, or
    /work/jaxenv/bin/python; None when there is none."""
    import importlib.util

    for cand in (given, os.environ.get("RIGIDKIN_JAX_PYTHON")):
        if cand:
            return cand
    if importlib.util.find_spec("jax") and importlib.util.find_spec("diffrax"):
        return sys.executable
    fallback = Path("/work/jaxenv/bin/python")
    return str(fallback) if fallback.exists() else None


def run(python: str, runs: int, device: str = "cpu", repeats: int = 1, timeout: float = 1800) -> dict:
    """One fresh process of this script: its JSON line (or ``{"error": ...}``), with the process's wall and CPU
    seconds (``process_s``, ``process_cpu_s``)."""
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    w0 = time.perf_counter()
    try:
        done = subprocess.run([python, str(Path(__file__).resolve()), "--runs", str(runs), "--device", device,
                               "--repeats", str(repeats)], capture_output=True, text=True, timeout=timeout)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return {"error": str(exc)}
    wall = time.perf_counter() - w0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    lines = [ln for ln in done.stdout.splitlines() if ln.startswith("{")]
    out = json.loads(lines[-1]) if lines else {"error": done.stderr.strip()[-600:] or f"exit {done.returncode}"}
    out.update(process_s=wall, process_cpu_s=(after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime))
    return out


if __name__ == "__main__":
    main()
