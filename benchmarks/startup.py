"""Start-up of the command line: whole commands in fresh processes, wall and CPU seconds.

Each command runs ``--repeat`` times (default 7) as its own process; the table gives the median wall
time, the median CPU time of the process (user + system, from ``os.wait4``) and the CPU time as a
ratio to ``python -c "import sympy"`` measured in the same run.  "cold" runs derive the problem
(``--no-cache``); "warm" runs read the derivation cache, primed by one run first (its own folder,
``$RIGIDKIN_CACHE`` in a temporary folder).  Bytecode is written to a temporary ``PYTHONPYCACHEPREFIX``
and every command runs once before it is timed, as on an installed copy (pip compiles it).

The package is copied to a temporary folder first and run from there (``PYTHONPATH``), so that a
source file edited while this runs cannot change the derivation cache's key between two runs.
``--before REV`` also times ``--help`` and ``solve ladder`` of the package at a git revision (before
these changes: 22ff1d8), in the same run.

    python benchmarks/startup.py [--repeat N] [--before REV]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run_once(cmd: list[str], env: dict) -> tuple[float, float, int]:
    """(wall seconds, CPU seconds, exit status) of one process."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    err = proc.stderr.read().decode(errors="replace")
    proc.stderr.close()
    if proc.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} failed ({proc.returncode}):\n{err}")
    return wall, usage.ru_utime + usage.ru_stime, proc.returncode


def measure(cmd: list[str], env: dict, repeat: int, before=None) -> tuple[float, float]:
    walls, cpus = [], []
    run_once(cmd, env)                                     # bytecode, and the cache when warm
    for _ in range(repeat):
        if before is not None:
            before()
        wall, cpu, _ = run_once(cmd, env)
        walls.append(wall)
        cpus.append(cpu)
    return statistics.median(walls), statistics.median(cpus)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--before", metavar="REV", help="also time the package at this git revision")
    args = ap.parse_args()

    import rigidkin

    tmp = Path(tempfile.mkdtemp(prefix="rigidkin-startup-"))
    try:
        src = tmp / "src"
        shutil.copytree(Path(rigidkin.__file__).parent, src / "rigidkin",
                        ignore=shutil.ignore_patterns("__pycache__"))
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "RIGIDKIN_NO_CACHE")}
        env.update(PYTHONPATH=str(src), PYTHONPYCACHEPREFIX=str(tmp / "pycache"), RIGIDKIN_CACHE=str(tmp / "cache"))
        py = sys.executable
        rk = [py, "-c", "import sys; from rigidkin.cli import main; sys.argv[0] = 'rigidkin'; sys.exit(main())"]
        outputs = tmp / "cache" / "derivations"

        def forget_outputs():                 # keep the derivation, not the printed text
            for f in outputs.glob("*.out"):
                f.unlink()

        rows = [
            ("python -c pass", [py, "-c", "pass"]),
            ('python -c "import sympy"', [py, "-c", "import sympy"]),
        ]
        if args.before:
            old = tmp / "before"
            old.mkdir()
            repo = Path(__file__).resolve().parents[1]
            tar = subprocess.run(["git", "-C", str(repo), "archive", args.before, "src/rigidkin"], check=True,
                                 capture_output=True).stdout
            subprocess.run(["tar", "-x", "-C", str(old)], input=tar, check=True)
            old_env = {**env, "PYTHONPATH": str(old / "src")}
            rows += [(f"{args.before}: rigidkin --help", rk + ["--help"], None, old_env),
                     (f"{args.before}: rigidkin solve ladder", rk + ["solve", "ladder"], None, old_env)]
        rows += [
            ("rigidkin --help", rk + ["--help"]),
            ("rigidkin list", rk + ["list"]),
            ("rigidkin solve ladder (cold: derives)", rk + ["solve", "ladder", "--no-cache"]),
            ("rigidkin solve ladder (warm: output kept)", rk + ["solve", "ladder"]),
            ("rigidkin solve ladder (warm: derivation read, text written)", rk + ["solve", "ladder"],
             forget_outputs),
            ("rigidkin simulate ladder --t-end 2 (cold)", rk + ["simulate", "ladder", "--t-end", "2", "--no-cache"]),
            ("rigidkin simulate ladder --t-end 2 (warm)", rk + ["simulate", "ladder", "--t-end", "2"]),
            ("rigidkin check ladder (warm)", rk + ["check", "ladder"]),
        ]
        results = []
        for label, cmd, *more in rows:
            before = more[0] if more else None
            run_env = more[1] if len(more) > 1 else env
            wall, cpu = measure(cmd, run_env, args.repeat, before)
            results.append((label, wall, cpu))
            print(f"  {label}: {wall:.3f} s wall, {cpu:.3f} s CPU", file=sys.stderr, flush=True)
        base = results[1][2]
        load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
        print(f"\nmedians of {args.repeat} fresh processes each; load average {load:.1f} on {os.cpu_count()} cores\n")
        print("| command | wall [s] | CPU [s] | CPU / import sympy |\n| --- | ---: | ---: | ---: |")
        for label, wall, cpu in results:
            print(f"| `{label}` | {wall:.3f} | {cpu:.3f} | {cpu / base:.2f} |")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
