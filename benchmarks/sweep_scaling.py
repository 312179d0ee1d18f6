"""How a whole ``rigidkin sweep`` command scales with threads: 2·10⁵ (``--runs``) ladders to wall-contact loss,
``--threads`` 1, 2, 4, … up to the cores of this machine (16 where present).

    python benchmarks/sweep_scaling.py [--runs 200000] [--format csv|parquet] [--max-threads N]

For each thread count: the whole command in a fresh process (start-up, the numeric record read, every chunk
planned, integrated, summarised, formatted and written; the cache folder filled by a warm-up run first), and the
integration alone in this process (the same runs, :meth:`Prepared.part` timed without a table).  The serial
share is what the command spends beyond the integration, over the command's time.  Wall seconds: parallel work.
Not a test: a script printing a table.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from common import table

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))


def cores() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def command(runs: int, threads: int, out: Path) -> list[str]:
    return [sys.executable, "-m", "rigidkin", "sweep", "ladder", "--param", f"theta=0.05:1.3:{runs}", "--stop-at",
            "N_A", "--threads", str(threads), "-o", str(out)]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=200_000)
    ap.add_argument("--format", choices=("csv", "parquet"), default="csv")
    ap.add_argument("--max-threads", type=int, default=min(16, cores()))
    args = ap.parse_args()
    counts = sorted({t for t in (1, 2, 4, 8, 16) if t <= args.max_threads} | {args.max_threads})

    from rigidkin import examples
    from rigidkin.numeric.sweeps.sweep import Prepared

    prep = Prepared(examples.build("ladder"), {"theta": (0.05, 1.3, args.runs)}, stop_at="N_A", stream=args.runs)
    prep.part(0, 10)                                          # compile once
    rows, base = [], None
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, RIGIDKIN_CACHE=str(Path(tmp, "cache")), PYTHONPATH=str(ROOT / "src"))
        out = Path(tmp, f"runs.{args.format}")
        subprocess.run(command(100, 1, out), env=env, check=True, capture_output=True)
        for t in counts:
            prep.workers = t
            t0 = time.perf_counter()
            prep.part(0, args.runs)
            integ = time.perf_counter() - t0
            t0 = time.perf_counter()
            subprocess.run(command(args.runs, t, out), env=env, check=True, capture_output=True)
            whole = time.perf_counter() - t0
            base = base or whole
            rows.append([t, f"{whole:.2f}", f"{base / whole:.2f}x", f"{integ:.2f}",
                         f"{max(0.0, whole - integ):.2f}", f"{max(0.0, whole - integ) / whole:.0%}"])
    print(table(f"{args.runs:,} ladders, whole command ({args.format}) against the integration alone",
                ["threads", "command s", "speed-up", "integration s", "rest s", "rest share"], rows,
                f"{cores()} cores here; wall seconds; the rest: start-up, record, planning, summary, table."))


if __name__ == "__main__":
    main()
