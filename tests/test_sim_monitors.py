"""A simulation that cannot keep its constraints or its energy balance within tolerance stops (exit 3) and says
which; a reaction that vanishes identically (by symmetry) is no watch.

Independent references: the energy of the four-bar written out by hand (three slender rods: ½ m v_G² + m L²/24
θ̇² + m g y_G) and its loop closure written by trigonometry, evaluated on the returned histories; Newton's
second law for a particle sliding along a wall on a floor: nothing pushes it into the wall, so N_wall = 0.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.numeric import simulate

sys.path.insert(0, str(Path(__file__).parent))
from test_core_more import _four_bar  # noqa: E402

L1, L2, L3, D, G = 0.3, 1.0, 0.6, 0.8, 9.81


def _energy(th1, th2, th3, w1, w2, w3):
    """(T, U) of the four-bar (m = 1), written out by hand."""
    vx1, vy1 = -L1 / 2 * np.sin(th1) * w1, L1 / 2 * np.cos(th1) * w1
    vAx, vAy = -L1 * np.sin(th1) * w1, L1 * np.cos(th1) * w1
    vx2, vy2 = vAx - L2 / 2 * np.sin(th2) * w2, vAy + L2 / 2 * np.cos(th2) * w2
    vx3, vy3 = -L3 / 2 * np.sin(th3) * w3, L3 / 2 * np.cos(th3) * w3
    T = sum((vx**2 + vy**2) / 2 + L**2 / 24 * w**2 for vx, vy, L, w in
            ((vx1, vy1, L1, w1), (vx2, vy2, L2, w2), (vx3, vy3, L3, w3)))
    U = G * (L1 / 2 * np.sin(th1) + L1 * np.sin(th1) + L2 / 2 * np.sin(th2) + L3 / 2 * np.sin(th3))
    return T, U


def _drift(r):
    """max |E − E0| relative to the scale the monitor uses (|E0|, T, |U − U0|), at every sample."""
    q, v = r.q, r.rates
    T, U = _energy(q["theta1"], q["theta2"], q["theta3"], v["dot(theta1)"], v["dot(theta2)"], v["dot(theta3)"])
    E = T + U
    return np.abs(E - E[0]) / max(abs(E[0]), float(np.max(np.abs(T))), float(np.max(np.abs(U - U[0]))))


def _loop(th1, th2, th3):
    return np.hypot(L1 * np.cos(th1) + L2 * np.cos(th2) - D - L3 * np.cos(th3),
                    L1 * np.sin(th1) + L2 * np.sin(th2) - L3 * np.sin(th3))


def test_an_energy_balance_out_of_tolerance_stops_the_run_where_it_fails():
    s = _four_bar()
    r = simulate(s, 2.0, rtol=1e-4, atol=1e-4)
    assert not r.reached_end and r.status == "stopped"
    assert r.stop_reason in ("energy-drift", "constraint-drift")
    assert r.t_final < 2.0
    q = r.q
    drift = _drift(r)
    loop = _loop(q["theta1"], q["theta2"], q["theta3"])
    assert np.all(drift[:-1] <= 1e-6 * 1.01) and np.all(loop[:-1] <= 1e-6 * 3)   # kept until the last sample
    if r.stop_reason == "energy-drift":
        assert drift[-1] > 1e-6 * 0.99 and "energy balance" in r.message
    else:
        assert "constraint" in r.message
    # tight tolerances keep both: the run completes
    r = simulate(s, 2.0)
    assert r.reached_end and r.stop_reason == "completed"
    assert np.max(_drift(r)) < 1e-8 and np.max(_loop(r.q["theta1"], r.q["theta2"], r.q["theta3"])) < 1e-9


def test_a_constraint_out_of_tolerance_stops_the_run():
    s = _four_bar()
    r = simulate(s, 2.0, rtol=1e-5, atol=1e-5, energy_tol=1.0, residual_tol=1e-10)
    assert r.stop_reason == "constraint-drift" and not r.reached_end
    assert "constraint 'pin B" in r.message
    loop = _loop(r.q["theta1"], r.q["theta2"], r.q["theta3"])
    assert loop[-1] > 1e-10 * 0.5 and np.all(loop[:-1] <= 1e-10 * 4)


def test_cli_exit_3_on_an_energy_drift(capsys):
    from rigidkin.cli import main

    rc = main(["simulate", "collar-rod", "--t-end", "200", "--rtol", "1e-3", "--atol", "1e-3", "--method", "RK45"])
    assert rc == 3
    err = capsys.readouterr().err
    assert "(energy-drift)" in err and "completed" not in err


def _corner():
    s = rk.System("corner")
    m, g = s.parameter("m", "kg", value=1.0), s.parameter("g", "m/s^2", value=9.81)
    x = s.coordinate("x", "along the wall", kind="length", initial=0, rate=1.0)
    y = s.coordinate("y", "from the wall", kind="length", initial=0)
    z = s.coordinate("z", "height", kind="length", initial=0)
    F = s.inertial
    P = s.point("P", s.origin, x * F.x + y * F.y + z * F.z)
    b = s.body("b", rk.shapes.PointMass(m), frame=F, at=P)
    s.contact("floor", b, s.plane(s.origin, F.z, name="floor"), centre=P, normal_name="N_f")
    s.contact("wall", b, s.plane(s.origin, F.y, name="wall"), centre=P, normal_name="N_w")
    s.gravity(g, -F.z)
    return s


def test_a_reaction_zero_by_symmetry_is_no_watch():
    s = _corner()
    sol = s.solve()
    assert sol.regimes[0].reactions["N_w"] == 0                 # by hand: nothing pushes it into the wall
    r = simulate(s, 1.0)
    assert r.reached_end and r.events == []                     # no "contact wall opens" at t ≈ 0
    assert r.q["x"][-1] == pytest.approx(1.0, abs=1e-9)         # slides on at ẋ = 1
    assert np.allclose(r.reactions["N_f"], 9.81) and np.allclose(r.reactions["N_w"], 0.0, atol=1e-12)
    assert math.isfinite(r.energy_drift) and r.energy_drift < 1e-12
