"""The GPU backend on a GPU machine: 10⁷ (``--runs``) ladders released from θ₀ ∈ [0.05, 1.3] to the loss of wall
contact, one run per GPU thread, and the event angle's error against the closed form acos(⅔ cos θ₀).

    pip install cupy-cuda12x       # on a machine with an NVIDIA GPU
    python benchmarks/sweep_gpu.py [--runs 10000000] [--c-runs 100000]

Prints the card, the compile time (NVRTC, first call), the integration time of the runs on the GPU (a warm-up of
10⁴ runs first), the largest |θ_event − acos(⅔ cos θ₀)|, and the C backend on this machine's cores over
``--c-runs`` of the same runs with the largest difference between the two backends' event times there.  A few
minutes at most.  Without CuPy or a GPU it says so and stops.  Not a test: a script printing a table.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from common import table

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "src"))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10_000_000)
    ap.add_argument("--c-runs", type=int, default=100_000)
    args = ap.parse_args()

    from rigidkin import examples
    from rigidkin.numeric.sweeps import gpu
    from rigidkin.numeric.sweeps.sweep import Prepared

    if not gpu.gpu_present():
        print("no CuPy or no CUDA device here: nothing to measure (pip install cupy-cuda12x on a GPU machine)")
        return
    import cupy

    card = cupy.cuda.runtime.getDeviceProperties(0)["name"].decode()
    ladder = examples.build("ladder")
    vary = {"theta": (0.05, 1.3, args.runs)}
    g = Prepared(ladder, vary, stop_at="N_A", backend="gpu", stream=args.runs)
    _, P, Y = g.plan(0, args.runs)
    _, events, model = g._model(0)
    t0 = time.perf_counter()
    model.function()
    compile_s = time.perf_counter() - t0
    model.integrate_batch(Y[:10_000], P[:10_000], 0.0, 10.0, events, 1e-10, 1e-12, np.inf, 1_000_000)
    cupy.cuda.Device().synchronize()
    t0 = time.perf_counter()
    res = model.integrate_batch(Y, P, 0.0, 10.0, events, 1e-10, 1e-12, np.inf, 1_000_000)
    gpu_s = time.perf_counter() - t0
    th0, th = Y[:, 0], res.event_y[:, 0, 0]
    err = float(np.max(np.abs(th - np.arccos(2 / 3 * np.cos(th0)))))

    c = Prepared(ladder, vary, stop_at="N_A", backend="c", stream=args.runs)
    _, cev, cmodel = c._model(0)
    from rigidkin.numeric.compiled.batch import integrate

    idx = np.linspace(0, args.runs - 1, min(args.c_runs, args.runs)).astype(int)
    t0 = time.perf_counter()
    ref = integrate(cmodel, Y[idx], P[idx], (0.0, 10.0), cev)
    c_s = time.perf_counter() - t0
    diff = float(np.max(np.abs(ref.event_t[:, 0] - res.event_t[idx, 0])))
    rows = [["gpu", card, f"{args.runs:,}", f"{compile_s:.2f}", f"{gpu_s:.3f}", f"{err:.2e}", f"{diff:.2e}"],
            ["c", "this machine's cores", f"{len(idx):,}", "", f"{c_s:.3f}",
             f"{float(np.max(np.abs(ref.event_y[:, 0, 0] - np.arccos(2 / 3 * np.cos(Y[idx, 0]))))):.2e}", ""]]
    print(table("Ladders to wall-contact loss", ["backend", "device", "runs", "compile s", "integrate s",
                                                 "max |θ - acos(2/3 cos θ0)|", "max |t_gpu - t_c|"], rows,
                "integrate s: wall seconds, host→device copies and results back included."))


if __name__ == "__main__":
    main()
