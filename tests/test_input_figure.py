"""The figure of a simulation with inputs u(t) draws them: a panel of lines named by the input and its unit,
with the history the equations saw (here a known push, compared with the expression given)."""

import numpy as np
import sympy as sp
from helpers import gliding_block, pushed_block

import rigidkin as rk
from rigidkin.numeric.simulate import simulate


def _panel(fig, ylabel):
    found = [ax for ax in fig.axes if ax.get_ylabel() == ylabel]
    assert len(found) == 1, [ax.get_ylabel() for ax in fig.axes]
    return found[0]


def test_the_figure_draws_each_input_with_its_history(tmp_path):
    res = simulate(pushed_block("N"), 2.0, {"x": 0.0}, inputs={"F": 3 * sp.cos(2 * rk.t)}, n_points=41)
    fig = res.plot(tmp_path / "run.png")
    assert (tmp_path / "run.png").stat().st_size > 0
    ax = _panel(fig, "inputs")
    lines = [ln for ln in ax.get_lines() if ln.get_label() == "F [N]"]
    assert len(lines) == 1
    tt, u = np.asarray(lines[0].get_xdata()), np.asarray(lines[0].get_ydata())
    assert len(tt) == len(res.t)
    assert np.allclose(u, 3 * np.cos(2 * tt), atol=1e-12)          # the push given, F = 3 cos 2t N
    assert fig.axes[-1] is ax and ax.get_xlabel() == "t [s]"


def test_an_input_is_drawn_in_the_unit_it_was_declared_in():
    res = simulate(pushed_block("kN"), 1.0, {"x": 0.0}, inputs={"F": lambda tt, st: 1500.0}, n_points=11)
    ax = _panel(res.plot(), "inputs")
    (line,) = [ln for ln in ax.get_lines() if ln.get_label() == "F [kN]"]
    assert np.allclose(line.get_ydata() * 1000.0, res.inputs["F"])        # the equations saw newtons
    assert np.allclose(res.inputs["F"], 1500.0)
    (ln,) = res.plot(quantities=["F"]).axes[0].get_lines()              # one panel of the input alone
    assert ln.get_label() == "F [kN]" and np.allclose(ln.get_ydata(), 1.5)


def test_no_inputs_no_panel():
    fig = simulate(gliding_block(), 1.0, n_points=5).plot()
    assert [ax.get_ylabel() for ax in fig.axes] == ["coordinates", "rates", "reactions [N, N·m]", "energy [J]"]
