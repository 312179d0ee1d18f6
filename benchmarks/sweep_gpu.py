"""The GPU backend on a GPU machine, against diffrax ``vmap`` on the same card in the same call: 10⁷ (``--runs``)
ladders released from θ₀ ∈ [0.05, 1.3] to the loss of wall contact, and the event angle's error against the closed
form acos(⅔ cos θ₀).

    pip install cupy-cuda12x                            # rigidkin's GPU backend (optional)
    python -m venv jaxenv && jaxenv/bin/pip install 'jax[cuda12]' diffrax      # the anchor, kept apart
    python benchmarks/sweep_gpu.py [--runs 10000000] [--c-runs 100000] [--diffrax-runs N] [--jax-python PATH]

One script, a few minutes at most start to finish (10⁷ runs: planning ≈ 10 s, compiling ≈ 10 s each side).
It prints the card; for rigidkin's ``--backend gpu`` (CuPy, NVRTC): the compile time (first call), the
integration time of every run (a warm-up of 10⁴ runs first; host→device copies and results back included) and the
largest |θ_event − acos(⅔ cos θ₀)|; for diffrax (``diffrax_ladder.py --device gpu`` in a fresh process of an
interpreter with JAX for CUDA: Tsit5, rtol 1e-10, atol 1e-12, Newton event, float64; ``--diffrax-runs``, default
``--runs``): its compile time, the median of 3 integrations and its error; and the C backend on this machine's cores
over ``--c-runs`` of the same runs, with the largest difference between the GPU's and C's event times there.
Where CuPy, JAX for CUDA or a device is missing, that part says so and is skipped; the C part always runs.
Not a test: a script printing a table.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import diffrax_ladder
import numpy as np
from common import machine, table

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "src"))

T0 = time.perf_counter()


def closed_form_error(theta0: np.ndarray, theta: np.ndarray) -> float:
    return float(np.max(np.abs(theta - np.arccos(2 / 3 * np.cos(theta0)))))


def rigidkin_gpu(ladder, vary, runs: int):
    """(row, event times, index of the runs) of ``--backend gpu``, or (None, None, message) without CuPy or a GPU."""
    from rigidkin.numeric.sweeps import gpu
    from rigidkin.numeric.sweeps.sweep import Prepared

    if not gpu.gpu_present():
        return None, None, ("rigidkin --backend gpu: skipped — no CuPy or no CUDA device here (pip install "
                            "cupy-cuda12x on a machine with an NVIDIA GPU)")
    import cupy

    card = cupy.cuda.runtime.getDeviceProperties(0)["name"].decode()
    g = Prepared(ladder, vary, stop_at="N_A", backend="gpu", stream=runs)
    t0 = time.perf_counter()
    _, P, Y = g.plan(0, runs)
    plan_s = time.perf_counter() - t0
    _, events, model = g._model(0)
    t0 = time.perf_counter()
    model.function()
    compile_s = time.perf_counter() - t0
    model.integrate_batch(Y[:10_000], P[:10_000], 0.0, 10.0, events, 1e-10, 1e-12, np.inf, 1_000_000)
    cupy.cuda.Device().synchronize()
    t0 = time.perf_counter()
    res = model.integrate_batch(Y, P, 0.0, 10.0, events, 1e-10, 1e-12, np.inf, 1_000_000)
    gpu_s = time.perf_counter() - t0
    err = closed_form_error(Y[:, 0], res.event_y[:, 0, 0])
    row = [f"rigidkin --backend gpu (DOP853, NVRTC; planning {plan_s:.1f} s)", card, f"{runs:,}", compile_s, gpu_s,
           f"{err:.2e}"]
    return row, res.event_t[:, 0], f"rigidkin gpu: {int(np.sum(res.status != 1))} runs without the event"


def diffrax_gpu(python: str | None, runs: int):
    """(row or None, note) of diffrax vmap on the GPU, in a fresh process."""
    if python is None:
        return None, ("diffrax on the GPU: skipped — no interpreter with JAX and diffrax (pip install "
                      "'jax[cuda12]' diffrax in a separate environment; --jax-python PATH)")
    d = diffrax_ladder.run(python, runs, device="gpu", repeats=3, timeout=600)
    if "error" in d:
        return None, f"diffrax on the GPU: skipped — {d['error']}"
    row = [f"diffrax {d['diffrax']} vmap, Tsit5 (JAX {d['jax']})", d["device"], f"{runs:,}", d["compile_s"],
           d["integrate_s"], f"{d['max_err']:.2e}"]
    return row, (f"diffrax: whole process {d['process_s']:.1f} s (import {d['import_s']:.1f} s), "
                 f"{d['missed']} runs without the event, max steps {d['max_steps']}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10_000_000)
    ap.add_argument("--c-runs", type=int, default=100_000)
    ap.add_argument("--diffrax-runs", type=int, default=None, help="runs of the diffrax side (default: --runs)")
    ap.add_argument("--jax-python", help="an interpreter with JAX for CUDA and diffrax")
    args = ap.parse_args()
    print(f"# GPU sweeps ({machine()})", flush=True)

    from rigidkin import examples
    from rigidkin.numeric.compiled.batch import default_workers, integrate
    from rigidkin.numeric.sweeps.sweep import Prepared

    ladder = examples.build("ladder")
    vary = {"theta": (0.05, 1.3, args.runs)}
    rows, notes = [], []
    grow, gpu_t, note = rigidkin_gpu(ladder, vary, args.runs)
    notes.append(note)
    if grow:
        rows.append(grow)
    drow, note = diffrax_gpu(diffrax_ladder.jax_python(args.jax_python), args.diffrax_runs or args.runs)
    notes.append(note)
    if drow:
        rows.append(drow)
    if grow and drow:
        notes.append(f"on the card: diffrax / rigidkin = {drow[4] / grow[4]:.1f}× integrating "
                     f"({drow[2]} and {grow[2]} runs)")

    idx = np.linspace(0, args.runs - 1, min(args.c_runs, args.runs)).astype(int)
    theta0 = np.linspace(0.05, 1.3, args.runs)[idx]          # the same runs as the grid's (its axis is a linspace)
    c = Prepared(ladder, {"theta": theta0.tolist()}, stop_at="N_A", backend="c", stream=len(idx))
    _, Pc, Yc = c.plan(0, len(idx))
    _, cev, cmodel = c._model(0)
    integrate(cmodel, Yc[:100], Pc[:100], (0.0, 10.0), cev)
    t0 = time.perf_counter()
    ref = integrate(cmodel, Yc, Pc, (0.0, 10.0), cev)
    c_s = time.perf_counter() - t0
    rows.append([f"rigidkin --backend c (DOP853, {default_workers()} threads)", "this machine's cores", f"{len(idx):,}",
                 None, c_s, f"{closed_form_error(Yc[:, 0], ref.event_y[:, 0, 0]):.2e}"])
    if gpu_t is not None:
        notes.append(f"max |t_gpu − t_c| over the C backend's {len(idx):,} runs: "
                     f"{float(np.max(np.abs(ref.event_t[:, 0] - gpu_t[idx]))):.2e} s")
    notes.append("integrate s: wall seconds after compilation (the GPU rows: host→device copies and results back "
                 f"included); the whole script took {time.perf_counter() - T0:.0f} s; {os.cpu_count()} CPUs")
    print(table("Ladders to wall-contact loss", ["what", "device", "runs", "compile s", "integrate s",
                                                 "max |θ − acos(2/3 cos θ0)|"], rows, "\n".join(notes)), flush=True)


if __name__ == "__main__":
    main()
