"""A repeated sweep from its numeric record: the same table to the byte, without sympy, and never a stale one.

The first ``rigidkin sweep`` of a problem keeps a record (layout, parameter values, the constraints as
expression trees, events, the C source); the next one answers from it.  Checked here: the trees evaluate as
lambdify does (at random and special states), the repeat writes the same bytes and imports no sympy, the
ladder's release angle is the closed form cos θ = ⅔ cos θ0, and every case the record cannot answer — a
changed file, a value with a unit, an unknown name, a tampered record — takes the full route with the
full route's answer or error.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest
import sympy as sp

from rigidkin.cli import main
from rigidkin.commands import sweep as sweep_command
from rigidkin.io import derivation_cache as dc
from rigidkin.numeric.sweeps import exprtree


# expression trees --------------------------------------------------------------------------------
def test_trees_evaluate_as_lambdify_at_random_and_special_states():
    x, y, p = sp.symbols("x y p", real=True)
    exprs = [sp.sqrt(x**2 + y**2) * sp.cos(x) - p / 3, sp.atan2(y, x) + sp.Rational(3, 2) * x**-2,
             sp.exp(-p * y) * sp.sin(2 * x) ** 3 - sp.pi * sp.Abs(y), sp.asin(sp.sin(x) / 2) + sp.tanh(y) * p**0.25]
    args = [x, y, p]
    index = {a: i for i, a in enumerate(args)}
    rng = np.random.default_rng(1)
    cols = [np.concatenate([rng.uniform(-2, 2, 50), [0.0, math.pi / 2, -math.pi / 2, math.pi, 1.0]])
            for _ in args]
    cols[2] = np.abs(cols[2]) + 0.1
    for e in exprs:
        tree = exprtree.encode(e, index)
        assert exprtree.valid(tree, len(args))
        with np.errstate(all="ignore"):
            want = sp.lambdify(args, e, "numpy")(*cols)
        got = exprtree.evaluate(tree, cols, len(cols[0]))
        np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-14)


def test_trees_refuse_what_they_cannot_hold():
    x = sp.Symbol("x")
    with pytest.raises(exprtree.NotEncodable):
        exprtree.encode(sp.besselj(0, x), {x: 0})
    with pytest.raises(exprtree.NotEncodable):
        exprtree.encode(x + sp.Symbol("other"), {x: 0})
    assert not exprtree.valid(["a", 5], 3)                       # an argument out of range
    assert not exprtree.valid(["__import__", ["n", 1.0]], 1)     # no such function
    assert not exprtree.valid(["+"], 1) and not exprtree.valid("x", 1)


# the command ---------------------------------------------------------------------------------------
def _sweep(capsys, out, *extra, problem="ladder"):
    rc = main(["sweep", problem, "--param", "theta=0.05:1.3:400", "--stop-at", "N_A", "-o", str(out), *extra])
    text = capsys.readouterr()
    return rc, text.out + text.err


def _no_derivation(monkeypatch):
    def refuse(args):
        raise AssertionError("the problem was read and derived")
    monkeypatch.setattr(sweep_command, "open_problem", refuse)


def _release_angles(path) -> tuple[np.ndarray, np.ndarray]:
    import csv

    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    th0 = np.array([float(r["theta"]) for r in rows])
    th = np.array([float(r["N_A: theta"]) for r in rows])
    return th0, th


def test_repeat_answers_from_the_record_with_the_same_bytes(cache, tmp_path, capsys, monkeypatch):
    first, second = tmp_path / "a.csv", tmp_path / "b.csv"
    rc, said = _sweep(capsys, first)
    assert rc == 0 and "400 runs of ladder (c)" in said
    assert list((cache / "derivations").glob("*.rec"))
    _no_derivation(monkeypatch)
    rc, said2 = _sweep(capsys, second)
    assert rc == 0 and said2.split(" in ")[0] == said.split(" in ")[0]
    assert first.read_bytes() == second.read_bytes()
    th0, th = _release_angles(second)
    assert np.max(np.abs(np.cos(th) - 2 / 3 * np.cos(th0))) < 1e-11       # the release: cos θ = ⅔ cos θ0


def test_record_route_values_and_end_time(cache, tmp_path, capsys, monkeypatch):
    """--set, --initial and --t-end are the run's own: the record answers with them as the full route does."""
    full, rec = tmp_path / "full.csv", tmp_path / "rec.csv"
    extra = ["--set", "g=3.7", "--initial", "dot(theta)=0.2", "--t-end", "0.4"]
    assert _sweep(capsys, tmp_path / "seed.csv")[0] == 0                  # keeps the record
    monkeypatch.setenv("RIGIDKIN_NO_CACHE", "1")
    assert _sweep(capsys, full, *extra)[0] == 0                           # the full route, nothing kept or read
    monkeypatch.delenv("RIGIDKIN_NO_CACHE")
    _no_derivation(monkeypatch)
    assert _sweep(capsys, rec, *extra)[0] == 0
    assert full.read_bytes() == rec.read_bytes()


def test_what_the_record_cannot_answer_takes_the_full_route(cache, tmp_path, capsys, monkeypatch):
    assert _sweep(capsys, tmp_path / "seed.csv")[0] == 0
    calls, real = [], sweep_command.open_problem
    monkeypatch.setattr(sweep_command, "open_problem", lambda args: calls.append(1) or real(args))
    assert _sweep(capsys, tmp_path / "unit.csv", "--set", "g=370 cm/s^2")[0] == 0   # a unit: parsed in full
    assert len(calls) == 1
    rc, said = _sweep(capsys, tmp_path / "bad.csv", "--set", "nonesuch=1")
    assert rc == 2 and "nonesuch" in said and "Traceback" not in said and len(calls) == 2
    # a tampered record is not read (its signature fails) and the answer is still right
    recs = list((cache / "derivations").glob("*.rec"))
    assert len(recs) == 1
    data = recs[0].read_bytes()
    assert b'"system": "ladder"' in data
    recs[0].write_bytes(data.replace(b'"system": "ladder"', b'"system": "laddex"'))   # well formed, not signed
    out = tmp_path / "again.csv"
    rc, said = _sweep(capsys, out)
    assert rc == 0 and "runs of ladder (c)" in said and len(calls) == 3
    assert b"laddex" not in recs[0].read_bytes()                 # removed, then kept anew by the full route
    th0, th = _release_angles(out)
    assert np.max(np.abs(np.cos(th) - 2 / 3 * np.cos(th0))) < 1e-11


def test_a_changed_file_is_never_answered_from_an_old_record(cache, tmp_path, capsys):
    from pathlib import Path

    from rigidkin import examples

    src = Path(examples.__file__).parent / "ladder.toml"
    text = src.read_text(encoding="utf-8")
    problem = tmp_path / "ladder.toml"
    problem.write_text(text, encoding="utf-8")
    assert _sweep(capsys, tmp_path / "one.csv", problem=str(problem))[0] == 0
    problem.write_text(text + "\n# the same ladder, one comment more\n", encoding="utf-8")
    assert dc.key_of(str(problem)) is not None
    before = set((cache / "derivations").glob("*.rec"))
    assert _sweep(capsys, tmp_path / "two.csv", problem=str(problem))[0] == 0
    assert len(set((cache / "derivations").glob("*.rec")) - before) == 1       # a new record for the new content


@pytest.mark.slow
def test_the_repeat_imports_no_sympy(tmp_path):
    env = {**os.environ, "RIGIDKIN_CACHE": str(tmp_path / "cache")}
    env.pop("RIGIDKIN_NO_CACHE", None)
    code = ("import sys; from rigidkin.cli import main; rc = main(sys.argv[1:]); "
            "print('SYMPY' if 'sympy' in sys.modules else 'NO-SYMPY', rc)")
    argv = ["sweep", "ladder", "--param", "theta=0.1:1.2:1000", "--stop-at", "N_A", "-o", str(tmp_path / "t.csv")]
    first = subprocess.run([sys.executable, "-c", code, *argv], env=env, capture_output=True, text=True, timeout=300)
    assert first.returncode == 0 and "SYMPY 0" in first.stdout, first.stderr
    again = subprocess.run([sys.executable, "-c", code, *argv], env=env, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0 and "NO-SYMPY 0" in again.stdout, again.stderr
