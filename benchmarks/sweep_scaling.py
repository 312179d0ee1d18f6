"""How a whole ``rigidkin sweep`` command scales with threads: 2·10⁵ (``--runs``) ladders to wall-contact loss,
``--threads`` 1, 2, 4, … up to the cores of this machine (16 where present).

    python benchmarks/sweep_scaling.py [--runs 200000] [--format csv|parquet] [--max-threads N] [--repeats 3]
                                       [--src OTHER/src]          # another tree's sources (before a change)

For each thread count: the whole command in a fresh process (start-up, the numeric record read, every chunk
planned, integrated, summarised, formatted and written; the cache folder filled by a warm-up run first), and the
integration alone in this process (the same runs, :meth:`Prepared.part` timed without a table).  The serial
share is what the command spends beyond the integration, over the command's time.  Wall seconds: parallel work;
medians of ``--repeats``.  The children keep their byte code (``PYTHONPYCACHEPREFIX``), as an installed package
does, even where ``PYTHONDONTWRITEBYTECODE`` is set.  ``sweep_serial.py`` breaks the serial part into its steps.
Not a test: a script printing a table.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
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


def timed(cmd: list[str], env: dict) -> tuple[float, float]:
    """(wall s, CPU s of the child and its threads) of one command."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, env=env, check=True, capture_output=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=200_000)
    ap.add_argument("--format", choices=("csv", "parquet"), default="csv")
    ap.add_argument("--max-threads", type=int, default=min(16, cores()))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--src", default=str(ROOT / "src"), help="the rigidkin sources the commands run")
    args = ap.parse_args()
    counts = sorted({t for t in (1, 2, 4, 8, 16) if t <= args.max_threads} | {args.max_threads})

    from rigidkin import examples
    from rigidkin.numeric.sweeps.sweep import Prepared

    prep = Prepared(examples.build("ladder"), {"theta": (0.05, 1.3, args.runs)}, stop_at="N_A", stream=args.runs)
    prep.part(0, 10)                                          # compile once
    rows, base = [], None
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, RIGIDKIN_CACHE=str(Path(tmp, "cache")), PYTHONPATH=str(Path(args.src).resolve()),
                   PYTHONPYCACHEPREFIX=str(Path(tmp, "pyc")))
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        out = Path(tmp, f"runs.{args.format}")
        subprocess.run(command(100, 1, out), env=env, check=True, capture_output=True)
        for t in counts:
            prep.workers = t
            integ, whole, cpu = [], [], []
            for _ in range(args.repeats):
                t0 = time.perf_counter()
                prep.part(0, args.runs)
                integ.append(time.perf_counter() - t0)
                w, c = timed(command(args.runs, t, out), env)
                whole.append(w)
                cpu.append(c)
            integ_s, whole_s = statistics.median(integ), statistics.median(whole)
            base = base or whole_s
            rest = max(0.0, whole_s - integ_s)
            rows.append([t, f"{whole_s:.2f}", f"{statistics.median(cpu):.2f}", f"{base / whole_s:.2f}x",
                         f"{integ_s:.2f}", f"{rest:.2f}", f"{rest / whole_s:.0%}", f"{os.getloadavg()[0]:.1f}"])
    print(table(f"{args.runs:,} ladders, whole command ({args.format}) against the integration alone",
                ["threads", "command s", "command CPU s", "speed-up", "integration s", "rest s", "rest share",
                 "load"], rows,
                f"{cores()} cores here; wall seconds (medians of {args.repeats}); integration: the same runs planned "
                "and integrated in this process (Prepared.part); the rest: start-up, record, planning, summary, "
                "table; load: the 1-minute load average after each row."))


if __name__ == "__main__":
    main()
