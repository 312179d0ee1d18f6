"""Where the serial time of a whole ``rigidkin sweep`` command goes: 2·10⁵ (``--runs``) ladders to wall-contact loss
answered from the numeric record (the cache folder warm), at ``--threads`` 1 and 2 (and more where the machine has
them), step by step.

    python benchmarks/sweep_serial.py [--runs 200000] [--threads 1 2] [--format csv|parquet] [--repeats 3]
    python benchmarks/sweep_serial.py --profile          # and a cProfile of the main thread (1 thread)

Each command is a fresh process running the console script's code (``rigidkin.cli.main``) with timers put around
the functions it calls — nothing else changed: interpreter start (``python -c pass``), imports, reading the
options, the numeric record (signed JSON), loading the compiled library (cffi), then per chunk planning (the
grid's values, each state completed), integrating (the threads), the summary, the table's columns, and in the
writer thread formatting and writing; the rest of the main thread (waiting for the writer at the end, printing)
is "other".  Main-thread steps are given as wall and CPU (``time.thread_time``): the CPU figure is what the step
costs whatever else runs on the machine; the serial part is the command's wall time less the integration's.
Not a test: a script printing tables.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from common import machine, table

ROOT = Path(__file__).resolve().parent.parent

#: The child: the command's own code with timers around the functions it calls.
_CHILD = r"""
import sys, time, json, threading
T = {}
def add(name, w, c):
    if threading.current_thread().name.startswith("rk-plan"):
        name += " (planning thread)"
    a = T.setdefault(name, [0.0, 0.0, 0]); a[0] += w; a[1] += c; a[2] += 1
w0, c0 = time.perf_counter(), time.thread_time()
import rigidkin.cli as cli
import rigidkin.commands.sweep as cmd
import rigidkin.numeric.sweeps.gpu, rigidkin.numeric.sweeps.stream as stream, rigidkin.numeric.sweeps.summary as summ
import rigidkin.numeric.sweeps.sweep_record as rec, rigidkin.numeric.sweeps.sweep_result as sres
import rigidkin.numeric.sweeps.tables as tables, rigidkin.numeric.compiled.batch as batch
add("imports", time.perf_counter() - w0, time.thread_time() - c0)
def timed(owner, attr, name):
    f = getattr(owner, attr)
    def g(*a, **k):
        w, c = time.perf_counter(), time.thread_time()
        try:
            return f(*a, **k)
        finally:
            add(name, time.perf_counter() - w, time.thread_time() - c)
    setattr(owner, attr, g)
timed(cmd, "read_kept", "numeric record read (signed JSON)")
timed(rec, "build", "compiled library loaded (cffi)")
timed(rec, "planner_of", "planner made")
timed(rec.Planner, "__call__", "planning (grid values, states completed)")
timed(batch, "integrate", "integration (threads)")
timed(rec, "SweepResult", "results assembled")
timed(summ.Summary, "add", "summary")
timed(sres.SweepResult, "columns", "table columns")
timed(sres.SweepResult, "metadata", "table metadata")
def blocks(f):
    def g(*a, **k):
        it = f(*a, **k)
        while True:
            w, c = time.perf_counter(), time.thread_time()
            try:
                x = next(it)
            except StopIteration:
                add("writer: format (writer thread)", time.perf_counter() - w, time.thread_time() - c)
                return
            add("writer: format (writer thread)", time.perf_counter() - w, time.thread_time() - c)
            yield x
    return g
stream.csv_text_blocks = blocks(stream.csv_text_blocks)
timed(stream, "arrow_table", "writer: format (writer thread)")
timed(stream, "write_sweep", "write_sweep (wall, all chunks)")
parse = cli.build_parser
def build_parser():
    w, c = time.perf_counter(), time.thread_time()
    p = parse()
    add("options (argparse, every command registered)", time.perf_counter() - w, time.thread_time() - c)
    return p
cli.build_parser = build_parser
rc = cli.main(sys.argv[1:])
total_w, total_c = time.perf_counter() - w0, time.thread_time() - c0
print(json.dumps({"steps": T, "main_wall": total_w, "main_cpu": total_c,
                  "process_cpu": time.process_time()}), file=sys.stderr)
sys.exit(rc)
"""


def run_child(argv: list[str], env: dict) -> tuple[dict, float, float]:
    """(the child's timers, its process wall s, its CPU s) of one command."""
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    w0 = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", _CHILD, *argv], env=env, capture_output=True, text=True,
                          timeout=1800)
    wall = time.perf_counter() - w0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(done.stderr[-2000:])
    data = json.loads(done.stderr.strip().splitlines()[-1])
    return data, wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def bare_start(env: dict, repeats: int) -> tuple[float, float]:
    """(wall s, CPU s) of ``python -c pass``: the interpreter's own start and end."""
    import resource

    walls, cpus = [], []
    for _ in range(repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        w0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "pass"], env=env, check=True)
        walls.append(time.perf_counter() - w0)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append((after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime))
    return statistics.median(walls), statistics.median(cpus)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=200_000)
    ap.add_argument("--threads", type=int, nargs="+", default=None)
    ap.add_argument("--format", choices=("csv", "parquet"), default="csv")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--profile", action="store_true", help="also a cProfile of the main thread at 1 thread")
    ap.add_argument("--src", default=str(ROOT / "src"), help="the rigidkin sources to time (before: another tree)")
    args = ap.parse_args()
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    threads = args.threads or sorted({t for t in (1, 2, 4, 8, 16) if t <= cores} | {cores})
    print(f"# Serial part of a whole sweep command ({machine()}; sources: {args.src})", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, RIGIDKIN_CACHE=str(Path(tmp, "cache")), PYTHONPATH=str(Path(args.src).resolve()),
                   PYTHONPYCACHEPREFIX=str(Path(tmp, "pyc")))          # byte code kept, as an installed package's
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        out = Path(tmp, f"runs.{args.format}")
        base = ["sweep", "ladder", "--param", f"theta=0.05:1.3:{args.runs}", "--stop-at", "N_A", "-o", str(out)]
        subprocess.run([sys.executable, "-m", "rigidkin", *base[:3], "theta=0.05:1.3:10", *base[4:]], env=env,
                       check=True, capture_output=True)                    # derive, compile, keep the record
        start_w, start_c = bare_start(env, 5)
        summary, steps_by_t = [], {}
        for t in threads:
            runs = [run_child([*base, "--threads", str(t)], env) for _ in range(args.repeats)]
            runs.sort(key=lambda r: r[1])
            data, wall, cpu = runs[len(runs) // 2]                          # the median command by wall time
            steps = data["steps"]
            integ = steps.get("integration (threads)", [0, 0, 0])
            steps_by_t[t] = (data, wall, cpu)
            serial = wall - integ[0]
            summary.append([t, wall, cpu, integ[0], serial, f"{serial / wall:.0%}", f"{os.getloadavg()[0]:.1f}"])
        print(table(f"{args.runs:,} ladders, whole command ({args.format}): median of {args.repeats} by wall time",
                    ["threads", "command wall s", "command CPU s", "integration wall s", "serial wall s",
                     "serial share", "load"], summary,
                    f"{cores} cores here; serial = command wall − integration wall (start-up, record, planning, "
                    "summary, table, waiting for the writer)."), flush=True)
        for t, (data, wall, cpu) in steps_by_t.items():
            steps = data["steps"]
            inner = {k: v for k, v in steps.items() if not k.startswith("write_sweep")}
            main_listed = sum(v[0] for k, v in inner.items() if "thread)" not in k)
            main_listed_c = sum(v[1] for k, v in inner.items() if "thread)" not in k)
            rows = [["interpreter start and end (python -c pass)", start_w, start_c, ""]]
            rows += [[k, v[0], v[1], v[2]] for k, v in inner.items()]
            rows.append(["other main thread (waiting for the writer, printing, exit)",
                         data["main_wall"] - main_listed, data["main_cpu"] - main_listed_c, ""])
            rows.append(["the process", wall, cpu, ""])
            print(table(f"{t} thread(s): the command step by step (writer and planning thread steps overlap the main "
                        "thread's)",
                        ["step", "wall s", "CPU s", "calls"], rows), flush=True)
        if args.profile:
            import cProfile
            import pstats

            prof = Path(tmp, "main.prof")
            subprocess.run([sys.executable, "-m", "cProfile", "-o", str(prof), "-m", "rigidkin", *base,
                            "--threads", "1"], env=env, check=True, capture_output=True)
            del cProfile
            st = pstats.Stats(str(prof))
            st.sort_stats("tottime").print_stats(25)


if __name__ == "__main__":
    main()
