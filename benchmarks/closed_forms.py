"""What a user waits for: `solve` (answers included) and `check`, cold, for every bundled example and the
systems of issue 31 (four-bar, a cart with three links, a ball on a turntable, a cylinder in a rolling shell).

    python benchmarks/closed_forms.py [--src PATH] [--limit 120] [--only four_bar ...]

Each figure is one fresh process (imports excluded for the Python models; the bundled examples run the whole
command line, `rigidkin solve NAME --no-cache` and `rigidkin check NAME --no-cache`, imports included), CPU
seconds of that process.  ``--src`` times another checkout (the code before a change) with the same models,
so a before/after table is two runs of this script on the same machine.  The last column says how the
accelerations are given (closed form, or M q̈ = f; derive/closed_forms.py).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
MODELS = ("four_bar", "cart_pendulum", "ball_on_turntable", "cylinder_in_shell")

DRIVER = r"""
import sys, time
sys.path.insert(0, {here!r})
import models
from rigidkin.report.text import problem_text
what, name = sys.argv[1], sys.argv[2]
t0 = time.process_time()
s = getattr(models, name)()
sol = s.solve()
if what == "solve":
    out = problem_text(sol)
else:
    out = str(sol.check())
r = sol.regimes[0]
form = r.__dict__.get("form")
print("RESULT", time.process_time() - t0, "closed" if form is None or form.closed else "M q''=f", len(out))
"""


def _run(cmd, env, limit):
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return None, "", ""
    return time.monotonic() - t0, p.stdout, p.stderr


def model_time(what, name, src, limit):
    env = {**os.environ, "PYTHONPATH": str(src), "RIGIDKIN_NO_CACHE": "1"}
    wall, out, err = _run([sys.executable, "-c", DRIVER.format(here=str(HERE)), what, name], env, limit)
    if wall is None:
        return f"> {limit}", ""
    for line in out.splitlines():
        if line.startswith("RESULT"):
            _, sec, *form, _n = line.split()
            return f"{float(sec):.1f}", " ".join(form)
    return "error", err.strip().splitlines()[-1][:60] if err.strip() else ""


def example_time(what, name, src, limit):
    env = {**os.environ, "PYTHONPATH": str(src), "RIGIDKIN_NO_CACHE": "1"}
    code = (f"import resource, runpy, sys; sys.argv = ['rigidkin', {what!r}, {name!r}, '--no-cache']\n"
            "try:\n    runpy.run_module('rigidkin', run_name='__main__')\n"
            "except SystemExit as e:\n    code = e.code\n"
            "r = resource.getrusage(resource.RUSAGE_SELF)\nprint('RESULT', r.ru_utime + r.ru_stime, file=sys.stderr)")
    wall, out, err = _run([sys.executable, "-c", code], env, limit)
    if wall is None:
        return f"> {limit}", ""
    for line in err.splitlines():
        if line.startswith("RESULT"):
            return f"{float(line.split()[1]):.1f}", ""
    return "error", ""


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--src", default=str(HERE.parent / "src"))
    ap.add_argument("--limit", type=float, default=120)
    ap.add_argument("--only", nargs="*")
    a = ap.parse_args(argv)
    sys.path.insert(0, a.src)
    from rigidkin import examples

    names = [n for n in examples.names() if n not in ("chain", "bicycle")]
    rows = []
    for name in MODELS + tuple(names):
        if a.only and name not in a.only:
            continue
        timer = model_time if name in MODELS else example_time
        solve, form = timer("solve", name, a.src, a.limit)
        check, _ = timer("check", name, a.src, a.limit)
        rows.append((name, solve, check, form))
        print(f"| {name} | {solve} | {check} | {form} |", flush=True)
    print()
    print("| system | solve s | check s | accelerations |")
    print("| --- | --- | --- | --- |")
    for r in rows:
        print("| " + " | ".join(r) + " |")


if __name__ == "__main__":
    main()
