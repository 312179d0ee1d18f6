"""Inputs u(t) in a simulation's results (a history and a CSV column per input) and on the command line
(``simulate --input NAME=EXPR``), checked against the closed-form motion of a block pushed by a known force."""

import csv
import io
from pathlib import Path

import numpy as np
import sympy as sp
from helpers import gliding_block, pushed_block, rigidkin_process

import rigidkin as rk
from rigidkin.numeric.simulate import simulate

t = rk.t

BLOCK = """
title = "Block pushed along a smooth rail"
[parameters]
m = { unit = "kg", value = 2 }
[inputs]
F = { unit = "N", description = "push along Ex", history = "3*sin(2*t)" }
[coordinates]
x = { sense = "block along Ex", kind = "length", initial = 0 }
[points]
C = { offset = "x*Ex" }
[bodies]
block = { shape = "point_mass", mass = "m", frame = "F", at = "C" }
[constraints]
rail = { type = "collar", body = "block", along = "Ex", point = "C" }
[loads]
push = { type = "force", point = "C", vector = "F*Ex" }
"""


block = pushed_block                  # helpers: F in N on a 2 kg block


def test_input_history_and_csv_column():
    res = simulate(block(), 2.0, {"x": 0.0}, inputs={"F": 3 * sp.cos(2 * t)}, n_points=41)
    ts = np.asarray(res.t)
    assert np.allclose(res.inputs["F"], 3 * np.cos(2 * ts))
    assert np.allclose(res["F"], 3 * np.cos(2 * ts))
    # x = F0 (1 − cos ωt)/(m ω²) for a push F0 cos ωt from rest
    assert np.allclose(res["x"], 3 * (1 - np.cos(2 * ts)) / (2.0 * 4), atol=1e-9)
    rows = list(csv.DictReader(io.StringIO(res.to_csv())))
    assert "F" in rows[0]
    assert np.allclose([float(r["F"]) for r in rows], 3 * np.cos(2 * ts))


def test_feedback_input_recorded_as_the_equations_saw_it():
    k, c = 8.0, 1.5
    res = simulate(block(), 3.0, {"x": 0.2}, inputs={"F": lambda tt, st: -k * st["x"] - c * st["dot(x)"]},
                   n_points=61)
    assert np.allclose(res.inputs["F"], -k * res["x"] - c * res["dot(x)"], atol=1e-9)
    # the damped oscillator m ẍ + c ẋ + k x = 0 from x = 0.2 at rest, in closed form
    m = 2.0
    wn, z = np.sqrt(k / m), c / (2 * np.sqrt(k * m))
    wd = wn * np.sqrt(1 - z**2)
    ts = np.asarray(res.t)
    x = 0.2 * np.exp(-z * wn * ts) * (np.cos(wd * ts) + z * wn / wd * np.sin(wd * ts))
    assert np.allclose(res["x"], x, atol=1e-8)


def test_no_inputs_no_columns():
    res = simulate(gliding_block(), 1.0, n_points=5)
    assert res.inputs == {}
    assert set(res.columns()) == {"t", "x", "dot(x)", "N_rail", "M_rail", "energy: T", "energy: U", "energy: E",
                                  "energy: W"}


def _cli(*args, cwd):
    return rigidkin_process(*args, cwd=cwd, env={"PATH": "/usr/bin:/bin"})


def test_cli_input_option(tmp_path: Path):
    (tmp_path / "block.toml").write_text(BLOCK)
    r = _cli("simulate", "block.toml", "--t-end", "2", "--points", "21", "--input", "F=2*cos(3*t)",
             "--csv", "h.csv", "--no-cache", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader((tmp_path / "h.csv").open()))
    ts = np.array([float(r_["t"]) for r_ in rows])
    assert np.allclose([float(r_["F"]) for r_ in rows], 2 * np.cos(3 * ts))
    assert np.allclose([float(r_["x"]) for r_ in rows], 2 * (1 - np.cos(3 * ts)) / (2.0 * 9), atol=1e-9)
    # without --input: the file's history, 3 sin 2t
    r = _cli("simulate", "block.toml", "--t-end", "2", "--points", "21", "--csv", "h2.csv", "--no-cache",
             cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader((tmp_path / "h2.csv").open()))
    ts = np.array([float(r_["t"]) for r_ in rows])
    assert np.allclose([float(r_["F"]) for r_ in rows], 3 * np.sin(2 * ts))
    # ẍ = 1.5 sin 2t from rest: x = 0.75 t − 0.375 sin 2t
    assert np.allclose([float(r_["x"]) for r_ in rows], 0.75 * ts - 0.375 * np.sin(2 * ts), atol=1e-9)


def test_cli_input_refusals(tmp_path: Path):
    (tmp_path / "block.toml").write_text(BLOCK)
    r = _cli("simulate", "block.toml", "--t-end", "1", "--input", "F=__import__('os').getcwd()", "--no-cache",
             cwd=tmp_path)
    assert r.returncode != 0 and "Traceback" not in r.stderr and "--input F" in r.stderr
    r = _cli("simulate", "block.toml", "--t-end", "1", "--input", "G=1", "--no-cache", cwd=tmp_path)
    assert r.returncode != 0 and "Traceback" not in r.stderr and "not an input" in r.stderr
