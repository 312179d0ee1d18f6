"""Peak memory of whole ``rigidkin sweep`` commands of 10⁴ … 10⁶ (``--runs``) ladders to wall-contact loss, CSV
and Parquet: a sweep streams to its table chunk by chunk, so the peak should not grow with the runs.

    python benchmarks/sweep_memory.py [--runs 10000 100000 1000000] [--formats csv parquet]

Each command is a fresh process (``rigidkin sweep ladder --param l=0.5:2.5:N --initial theta=0.3 --stop-at N_A
-o runs.csv``) after one warm-up run that fills the cache folder (derivation, compiled library, numeric record);
its peak resident memory is the child's ``ru_maxrss`` (``os.wait4``), its CPU seconds user + system of the
child and its threads, its wall seconds the time it took.  Not a test: a script printing a table.
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


def command(runs: int, out: Path) -> list[str]:
    return [sys.executable, "-m", "rigidkin", "sweep", "ladder", "--param", f"l=0.5:2.5:{runs}", "--initial",
            "theta=0.3", "--stop-at", "N_A", "-o", str(out)]


def measure(cmd: list[str], env: dict) -> tuple[float, float, float, int]:
    """(wall s, CPU s, peak RSS MB, exit status) of one child process."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    err = proc.stderr.read().decode()
    if proc.returncode:
        print(err, file=sys.stderr)
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, proc.returncode


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, nargs="+", default=[10_000, 100_000, 1_000_000])
    ap.add_argument("--formats", nargs="+", default=["csv", "parquet"])
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, RIGIDKIN_CACHE=str(Path(tmp, "cache")), PYTHONPATH=str(ROOT / "src"))
        measure(command(10, Path(tmp, "warm.csv")), env)
        rows = []
        for fmt in args.formats:
            for runs in args.runs:
                out = Path(tmp, f"runs.{fmt}")
                wall, cpu, rss, rc = measure(command(runs, out), env)
                size = out.stat().st_size / 2**20 if out.exists() else float("nan")
                rows.append([fmt, f"{runs:,}", f"{wall:.1f}", f"{cpu:.1f}", f"{rss:.0f}", f"{size:.0f}",
                             "ok" if rc == 0 else f"exit {rc}"])
                out.unlink(missing_ok=True)
    print(table("Whole sweep commands: peak memory", ["table", "runs", "wall s", "CPU s", "peak RSS MB", "file MB",
                                                        "status"], rows,
                f"{os.cpu_count()} cores; one warm-up run filled the cache folder first."))


if __name__ == "__main__":
    main()
