"""A contact's geometry holds in a domain (a disk on a plane: while it does not lie flat); outside it no
answer is given.

Independent references: the lowest point of a leaning disk's rim found by sampling the rim (a circle of
radius a about C in the plane normal to its axle), so its height above the plane is z − a|cos θ|; the
free fall of a non-spinning coin about its contact point conserves energy, so at the moment it lies flat
(θ = π/2) its centre is on the plane (z = a cos θ = 0).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.analysis.equilibrium import equilibria
from rigidkin.derive.kinematics import Kinematics
from rigidkin.examples import rolling_disk
from rigidkin.numeric import simulate


@pytest.fixture(scope="module")
def coin():
    return rolling_disk.build()


def _lowest_rim_height(z, a, theta):
    """Height of the lowest point of the rim, by sampling: the rim is C + a (cos s e1 + sin s e2) with e1, e2
    spanning the disk's plane; for a lean θ about the heading, e1 = heading, e2 = (0, −sin θ, cos θ)."""
    s = np.linspace(0.0, 2 * np.pi, 200001)
    return z + a * np.min(np.sin(s) * np.cos(theta))


def test_gap_is_the_true_distance_inside_the_domain(coin):
    kin = Kinematics(coin)
    con = coin.constraints["P"]
    psi, theta, phi, x, y, z = coin.coordinates
    a = coin.parameters["a"]
    gap = con.gap(kin)
    (dom, what, why), = con.domain(kin)
    for th in (0.0, 0.4, 1.2, 1.5):
        vals = {theta: th, z: 0.02, a: 0.0125, psi: 0.3, phi: 1.0, x: 0.1, y: -0.2}
        assert float(dom.subs(vals)) == pytest.approx(np.cos(th), abs=1e-12)
        assert float(gap.subs(vals)) == pytest.approx(_lowest_rim_height(0.02, 0.0125, th), abs=1e-9)
    # past lying flat the formula is not the distance: the domain says so
    vals = {theta: 3.0, z: 0.02, a: 0.0125}
    assert float(dom.subs(vals)) < 0
    assert abs(float(gap.subs(vals)) - _lowest_rim_height(0.02, 0.0125, 3.0)) > 0.02
    assert "flat" in what


def test_a_start_past_lying_flat_is_refused(coin):
    with pytest.raises(rk.InputError, match=r"cos\(θ\) = -0.98999"):
        simulate(coin, 0.1, {"theta": 3.0})


def test_a_falling_coin_stops_where_it_lies_flat(coin):
    res = simulate(coin, 1.0, {"theta": 1.2, "dot(theta)": 3.0, "dot(phi)": 0.0})
    assert not res.reached_end
    assert res.stop_reason == "outside-domain"
    assert "lie flat" in res.message
    ev = res.events[-1]
    assert ev.kind == "stop"
    assert ev.state["theta"] == pytest.approx(np.pi / 2, abs=1e-9)
    assert abs(ev.state["z"]) < 1e-9                      # z = a cos θ = 0 there
    assert res.energy_drift < 1e-8
    assert np.all(res.q["z"] >= -1e-12)                    # never under the floor


def test_equilibria_outside_the_domain_are_not_listed(coin):
    theta = coin.coordinates[1]
    confs = [e.configuration[theta] for e in equilibria(coin.solve())]
    assert confs == [0]                                    # θ = π (a disk upside down) is not the model's


def test_cli_stops_with_exit_3(capsys):
    from rigidkin.cli import main

    rc = main(["simulate", "rolling-disk", "--t-end", "1", "--initial", "theta=1.2", "dot(theta)=3",
               "dot(phi)=0"])
    err = capsys.readouterr().err
    assert rc == 3
    assert "outside-domain" in err and "lie flat" in err


def test_the_answers_state_the_domain(coin):
    theta = coin.coordinates[1]
    conds = [c for c in coin.solve().regimes[0].validity if "lying flat" in c.label]
    assert len(conds) == 1 and (conds[0].expr - sp.cos(theta)).simplify() == 0
