"""Batch sweeps: against the closed form of the ladder, single solve_ivp runs, the simulator, Dask."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import rigidkin as rk
from rigidkin.cli import main
from rigidkin.examples import chain
from rigidkin.numeric.compiled import codegen
from rigidkin.numeric.rhs import make_rhs
from rigidkin.numeric.sweeps.sweep import sweep

G = 9.81
needs_c = pytest.mark.skipif(not codegen.c_available(), reason="no C compiler")


pytestmark = pytest.mark.usefixtures("code_cache")      # conftest: compiled once per session


@pytest.fixture(scope="module")
def ladder_sweep(ladder):
    return sweep(ladder, {"theta": (0.05, 1.3, 40)}, stop_at="N_A")


def test_ladder_leaves_the_wall_at_the_closed_form_angle(ladder_sweep):
    th0 = ladder_sweep.inputs["theta"]
    th = ladder_sweep.event_state("N_A", "theta")
    np.testing.assert_allclose(th, np.arccos(2 / 3 * np.cos(th0)), rtol=0, atol=1e-9)
    # energy: θ̇² = (3 g / l)(cos θ0 − cos θ) from rest at θ0 (l = 2)
    w = ladder_sweep.event_state("N_A", "dot(theta)")
    np.testing.assert_allclose(w ** 2, 3 * G / 2 * (np.cos(th0) - np.cos(th)), rtol=1e-9)
    assert np.all(ladder_sweep.status == 1)
    # the foot stays on the constraint x = l sin θ
    np.testing.assert_allclose(ladder_sweep.event_state("N_A", "x"), 2 * np.sin(th), atol=1e-9)


def test_ladder_sweep_equals_single_solve_ivp_runs(ladder, ladder_sweep):
    """The compiled batch integrator equals scipy's DOP853 on the lambdified RHS, run by run, to 1e-8."""
    rhs = make_rhs(ladder)
    sol = ladder.solve()
    import sympy as sp

    from rigidkin.numeric.state import StateLayout

    lay = StateLayout.of(ladder)
    NA = sp.lambdify(lay.arguments(), lay.to_plain(sol.reactions["N_A"]))

    def wall(t, y):
        return NA(t, *y, 10.0, 2.0, G)
    wall.terminal, wall.direction = True, -1
    for r in (0, 17, 39):
        y0 = ladder_sweep.y0[r]
        ref = solve_ivp(rhs, (0, 10), y0, method="DOP853", rtol=1e-10, atol=1e-12, events=wall)
        assert ladder_sweep.event_time("N_A")[r] == pytest.approx(ref.t_events[0][0], abs=1e-8)
        np.testing.assert_allclose(ladder_sweep.event_state("N_A")[r], ref.y_events[0][0], atol=1e-8)


def test_ladder_sweep_equals_the_simulator(ladder, ladder_sweep):
    from rigidkin.numeric import simulate

    for r in (3, 30):
        th0 = float(ladder_sweep.inputs["theta"][r])
        res = simulate(ladder, 5.0, initial_state={"theta": th0, "dot(theta)": 0.0})
        ev = next(e for e in res.events if e.contact == "A")
        assert ladder_sweep.event_time("N_A")[r] == pytest.approx(ev.t, abs=1e-8)
        for name in ("theta", "x", "dot(theta)", "dot(x)"):
            assert ladder_sweep.event_state("N_A", name)[r] == pytest.approx(ev.state[name], abs=1e-8)


def test_time_scales_with_sqrt_l_over_g(ladder):
    """Dimensional analysis: from the same θ0 the time to leave the wall is sqrt(l/g) times a number."""
    res = sweep(ladder, {"l": [0.5, 2.0, 8.0], "g": [1.62, 9.81]}, initial={"theta": 0.3}, stop_at="N_A")
    scaled = res.event_time("N_A") / np.sqrt(res.params[:, 1] / res.params[:, 2])
    np.testing.assert_allclose(scaled, scaled[0], rtol=1e-9)
    assert len(res) == 6


@needs_c
def test_numpy_backend_equals_c(ladder):
    kw = dict(vary={"theta": [0.2, 0.9]}, stop_at="N_A")
    c = sweep(ladder, backend="c", **kw)
    n = sweep(ladder, backend="numpy", **kw)
    assert n.backend == "numpy" and c.backend == "c"
    np.testing.assert_allclose(n.event_time("N_A"), c.event_time("N_A"), atol=1e-9)


def test_chain_conserves_energy_to_t_end():
    """A 3-rod chain (implicit kernel: LU in C) keeps its energy: T + V at t_end equals its start."""
    n = 3
    res = sweep(chain.build(n), {"theta1": [0.3, 1.0]}, t_end=2.0, form="implicit")
    assert np.all(res.status == 0)

    def energy(y, m=1.0, l=1.0):
        th, w = y[:n], y[n:]
        T = V = 0.0
        vx = vy = 0.0
        px = py = 0.0
        for i in range(n):
            gy = py - l / 2 * math.cos(th[i])
            gvx = vx + l / 2 * math.cos(th[i]) * w[i]
            gvy = vy + l / 2 * math.sin(th[i]) * w[i]
            T += 0.5 * m * (gvx ** 2 + gvy ** 2) + 0.5 * m * l ** 2 / 12 * w[i] ** 2
            V += m * G * gy
            px, py = px + l * math.sin(th[i]), py - l * math.cos(th[i])
            vx, vy = vx + l * math.cos(th[i]) * w[i], vy + l * math.sin(th[i]) * w[i]
        return T + V

    for r in range(len(res)):
        e0, e1 = energy(res.y0[r]), energy(res.result.y_end[r])
        assert e1 == pytest.approx(e0, abs=1e-8 * max(1.0, abs(e0)))
    assert res.result.t_end == pytest.approx([2.0, 2.0])


@needs_c
@pytest.mark.slow
def test_dask_local_cluster_gives_identical_results(ladder):
    pytest.importorskip("distributed")
    vary = {"theta": (0.1, 1.2, 30), "l": [1.0, 3.0]}
    local = sweep(ladder, vary, stop_at="N_A")
    seen = []
    dist = sweep(ladder, vary, stop_at="N_A", scheduler="local", workers=2, chunk=16,
                 progress=lambda done, total: seen.append((done, total)))
    assert np.array_equal(local.result.event_t, dist.result.event_t)
    assert np.array_equal(local.result.event_y, dist.result.event_y)
    assert np.array_equal(local.result.y_end, dist.result.y_end)
    assert seen[-1] == (60, 60) and len(seen) == 4     # progress as each chunk of 16 runs finishes


def test_cli_writes_one_row_per_run(tmp_path, capsys):
    out, fig = tmp_path / "t.csv", tmp_path / "t.png"
    code = main(["sweep", "ladder", "--param", "theta=0.2:1.0:5", "l=1,2", "--stop-at", "N_A", "-o", str(out),
                 "--plot", str(fig)])
    assert code == 0
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 10
    for row in rows:
        th0, th = float(row["theta"]), float(row["N_A: theta"])
        assert math.cos(th) == pytest.approx(2 / 3 * math.cos(th0), abs=1e-9)
        assert row["status"] == "terminal event"
    assert fig.stat().st_size > 1000
    assert "10 runs of ladder" in capsys.readouterr().out


def test_cli_state_event_and_defaults(tmp_path):
    out = tmp_path / "s.csv"
    assert main(["sweep", "ladder", "--param", "theta=0.2:0.4:3", "--stop-at", "theta=0.8", "--record", "N_A",
                 "-o", str(out)]) == 0
    rows = list(csv.DictReader(out.open()))
    for row in rows:
        assert float(row["theta=0.8: theta"]) == pytest.approx(0.8, abs=1e-12)
        assert row["N_A: t"] == ""          # the wall still pushes at 0.8 rad (it lets go at acos(2/3 cos θ0))


@pytest.mark.parametrize("argv, message", [
    (["--param", "mass=1:2:3"], "neither a parameter nor a coordinate"),
    (["--param", "theta=1:2"], "START:STOP:COUNT"),
    (["--param", "theta=1:2:x"], "not a whole number"),
    (["--stop-at", "N_Q"], "not an event"),
    (["--t-end", "-1"], "positive"),
    (["--set", "l"], "NAME=VALUE"),
])
def test_cli_errors_are_one_paragraph(tmp_path, capsys, argv, message):
    code = main(["sweep", "ladder", *argv, "-o", str(tmp_path / "x.csv")])
    err = capsys.readouterr().err
    assert code == 2 and message in err and "Traceback" not in err


@pytest.mark.slow
def test_each_run_starts_in_its_own_friction_regime_and_stops_when_it_ends():
    """Boulder-push: sliding friction at the plate opposes ẋ; moving down, the boulder stops at t = |v0|/a."""
    s = rk.examples.build("boulder-push")
    res = sweep(s, {"dot(x)": [-1.0, -0.5, 0.0, 0.5]}, t_end=1.0)
    m, P, mu, beta = 500.0, 3000.0, 0.3, math.radians(15)
    a_down = 5 * (P * (1 + mu) - m * G * math.sin(beta)) / (7 * m)     # regime ẋ < 0
    a_up = 5 * (P * (1 - mu) - m * G * math.sin(beta)) / (7 * m)       # regime ẋ > 0
    name = "slip speed at plate"
    t_stop = res.event_time(name)
    assert t_stop[0] == pytest.approx(1.0 / a_down, rel=1e-10)
    assert t_stop[1] == pytest.approx(0.5 / a_down, rel=1e-10)
    assert list(res.status) == [1, 1, 6, 0]              # the run at rest fits no sliding regime
    assert res.result.y_end[3, 2] == pytest.approx(0.5 + a_up * 1.0, rel=1e-10)   # ẋ at t_end
    # rolling on the incline: r φ̇ = ẋ holds along the way
    assert res.result.y_end[3, 3] * 0.6 == pytest.approx(res.result.y_end[3, 2], rel=1e-10)
