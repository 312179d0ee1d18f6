"""The same equations before and after a speed change: every bundled example (and issue 31's models) solved
and cross-checked, each law's equations evaluated at random states at 30 digits.

    python benchmarks/same_equations.py --out after.json [--src PATH] [--only ladder ...]
    python benchmarks/same_equations.py --compare before.json after.json

For each system: the reference solution's M and f as derived and as printed (readable), its equations of
motion, its accelerations and reactions (closed form, or in terms of q̈ when given as M q̈ = f); then
``check()``'s verdicts, and for every law it ran, that law's balance equations (``lhs − rhs``) and M, f.
Every expression is evaluated at the same random values of every coordinate, rate, acceleration and
parameter (``mpmath`` at 30 digits); ``--compare`` reports any value that moved by more than 1e-20
relatively, and any verdict that changed.  Not a timing: run it on the tree before and after a change
(``--src``) and compare the two files.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
MODELS = ("four_bar", "cart_pendulum")
DIGITS = 30
RTOL = 1e-20


def _values(exprs, seed: int = 7, n: int = 2) -> list:
    """Each expression at ``n`` random states (every symbol random), as strings of 30 significant digits."""
    import mpmath
    import sympy as sp

    from rigidkin.base import algebra

    exprs = [sp.sympify(e) for e in exprs]
    if not exprs:
        return []
    plain, _ = algebra.plain_state(sp.Matrix(exprs))
    syms = sorted(plain.free_symbols, key=str)
    fn = sp.lambdify(syms, list(plain), modules="mpmath")
    out = []
    with mpmath.workdps(DIGITS):
        for k in range(n):
            # each symbol's value from its own name: the same state whichever symbols an expression keeps
            args = [mpmath.mpf(random.Random(f"{seed}-{k}-{s.name}").uniform(0.3, 1.3)) for s in syms]
            try:
                vals = fn(*args)
            except (ZeroDivisionError, ValueError):
                out.append(["undefined"] * len(exprs))
                continue
            out.append([mpmath.nstr(mpmath.mpc(v), DIGITS) for v in vals])
    return out


def _regime_exprs(r, prefix: str) -> dict:
    from rigidkin.derive import closed_forms

    d = {f"{prefix}M raw": list(r.raw_mass_matrix), f"{prefix}f raw": list(r.raw_forcing),
         f"{prefix}M": list(r.mass_matrix), f"{prefix}f": list(r.forcing), f"{prefix}eom": list(r.eom)}
    if not closed_forms.structured(r) and len(r.raw_forcing) <= 3:
        d[f"{prefix}accelerations"] = [r.accelerations[q] for q in r.accelerations]
    d[f"{prefix}reactions"] = [r.reactions[k] for k in sorted(r.reactions)]
    return d


def record(name: str) -> dict:
    """The values of one system's equations (reference solution, the check's laws)."""
    from rigidkin import examples
    from rigidkin.derive.laws import solve_with
    from rigidkin.derive.laws.crosscheck import _mode_args, candidate_laws

    sys.path.insert(0, str(HERE))
    import models

    system = getattr(models, name)() if name in MODELS else examples.build(name)
    sol = system.solve()
    exprs = {}
    for i, r in enumerate(sol.regimes):
        exprs.update(_regime_exprs(r, f"regime {i} "))
    report = sol.check()
    mode, independent, subs = _mode_args(sol)
    for law in candidate_laws(sol):
        try:
            other = solve_with(system, law, mode, independent, subs)
        except Exception:            # noqa: BLE001  (a law that does not apply: its verdict says so)
            continue
        exprs[f"{law} equations"] = [e.expr for e in other.equations]
        for i, r in enumerate(other.regimes):
            exprs[f"{law} regime {i} M raw"] = list(r.raw_mass_matrix)
            exprs[f"{law} regime {i} f raw"] = list(r.raw_forcing)
    vals = {k: _values(v) for k, v in exprs.items()}
    verdicts = [[v.law, v.equation, v.status] for v in report.verdicts]
    return {"values": vals, "verdicts": verdicts, "ok": report.ok}


def compare(before: dict, after: dict) -> int:
    import mpmath

    bad = 0
    with mpmath.workdps(DIGITS):
        for name in sorted(set(before) | set(after)):
            a, b = before.get(name), after.get(name)
            if a is None or b is None:
                print(f"{name}: only in {'after' if a is None else 'before'}")
                continue
            if a["verdicts"] != b["verdicts"]:
                bad += 1
                print(f"{name}: verdicts differ\n  before {a['verdicts']}\n  after  {b['verdicts']}")
            n = 0
            for key in sorted(set(a["values"]) | set(b["values"])):
                va, vb = a["values"].get(key), b["values"].get(key)
                if va is None or vb is None:
                    print(f"{name}: {key} only {'after' if va is None else 'before'}")
                    continue
                for ra, rb in zip(va, vb):
                    if len(ra) != len(rb):
                        bad += 1
                        print(f"{name}: {key}: {len(ra)} expressions before, {len(rb)} after")
                        break
                    for x, y in zip(ra, rb):
                        n += 1
                        if "undefined" in (x, y):
                            if x != y:
                                bad += 1
                                print(f"{name}: {key}: {x} before, {y} after")
                            continue
                        x, y = mpmath.mpmathify(x), mpmath.mpmathify(y)
                        if abs(x - y) > RTOL * max(1, abs(x), abs(y)):
                            bad += 1
                            print(f"{name}: {key}: {x} before, {y} after")
            print(f"{name}: {n} values compared, verdicts {'same' if a['verdicts'] == b['verdicts'] else 'DIFFER'}")
    print("the same equations" if not bad else f"{bad} differences")
    return 1 if bad else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--src", default=str(HERE.parent / "src"))
    ap.add_argument("--out")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--one", help=argparse.SUPPRESS)        # a child process: one system, JSON on stdout
    ap.add_argument("--compare", nargs=2, metavar=("BEFORE", "AFTER"))
    a = ap.parse_args(argv)
    if a.compare:
        return compare(*(json.loads(Path(p).read_text()) for p in a.compare))
    if a.one:
        sys.path.insert(0, a.src)
        print("RECORD " + json.dumps(record(a.one)))
        return 0
    sys.path.insert(0, a.src)
    from rigidkin import examples

    names = list(MODELS) + [n for n in examples.names() if n not in ("chain", "bicycle")]
    out = {}
    env = {**os.environ, "PYTHONPATH": a.src, "RIGIDKIN_NO_CACHE": "1"}
    for name in names:
        if a.only and name not in a.only:
            continue
        p = subprocess.run([sys.executable, __file__, "--src", a.src, "--one", name], env=env,
                           capture_output=True, text=True)
        line = [x for x in p.stdout.splitlines() if x.startswith("RECORD ")]
        if not line:
            print(f"{name}: failed: {p.stderr.strip().splitlines()[-1:] if p.stderr.strip() else ''}")
            continue
        out[name] = json.loads(line[0][7:])
        print(f"{name}: {sum(len(v) for v in out[name]['values'].values())} states recorded", flush=True)
    Path(a.out).write_text(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
