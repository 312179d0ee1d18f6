"""The simulate API: parameters with units, initial states, the right-hand side, outputs and errors."""

import json

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.base.errors import InputError, RigidkinError
from rigidkin.examples import build
from rigidkin.numeric import SimulationError, make_rhs, simulate
from rigidkin.numeric.rhs import RHS
from rigidkin.numeric.state import StateLayout

G = 9.81


def test_make_rhs_gives_the_card_equation(ladder):
    rhs = make_rhs(ladder, mode={"A": "slip", "B": "slip"})
    l = ladder.parameter_info["l"].value
    for th, thd in [(0.3, 0.0), (0.7, 1.3)]:
        y = np.array([th, l * np.sin(th), thd, l * np.cos(th) * thd])
        dy = rhs(0.0, y)
        assert abs(dy[2] - 3 * G / (2 * l) * np.sin(th)) < 1e-12          # card (a): θ̈ = (3g/2l) sin θ
        assert abs(dy[1] - l * np.cos(th) * thd) < 1e-12                  # ẋ from the rate relation
        assert abs(dy[3] - l * (np.cos(th) * dy[2] - np.sin(th) * thd**2)) < 1e-12   # ẍ = d²(l sin θ)/dt²
    # parameters bound by value, with units
    rhs2 = make_rhs(ladder, mode={"A": "slip", "B": "slip"}, params={"l": "100 cm", "g": 1.0})
    assert abs(rhs2(0.0, np.array([0.5, 0.0, 0.0, 0.0]))[2] - 1.5 * np.sin(0.5)) < 1e-12


def test_rhs_never_returns_a_nan():
    s = build("ladder")
    lay = StateLayout.of(s)
    f = RHS(lambda t, *a: [1.0, np.nan, 0.0, 0.0], lay, np.zeros(3), label="ladder")
    with pytest.raises(SimulationError, match=r"t = 0\.25 .*theta = 0\.1"):
        f(0.25, np.array([0.1, 0.2, 0.0, 0.0]))


def test_parameters_with_units_and_initial_state_on_the_rough_part():
    s = build("slip-to-roll")
    beta, mu, d = np.radians(20), 0.3, 1.0
    vB = np.sqrt(2 * G * d * np.sin(beta))
    r = simulate(s, 1.0, params={"beta": "20 deg", "mu": mu}, initial_state={"x": "100 cm", "dot(x)": vB})
    (ev,) = r.events
    assert abs(ev.t - vB / (G * (3 * mu * np.cos(beta) - np.sin(beta)))) < 1e-8
    assert abs(ev.state["dot(x)"] - 2 * mu * np.cos(beta) * vB / (3 * mu * np.cos(beta) - np.sin(beta))) < 1e-8


def test_bad_parameters_and_states_are_clear_errors(ladder):
    with pytest.raises(InputError, match="'nope' is not a parameter"):
        simulate(ladder, 1.0, params={"nope": 1})
    with pytest.raises(InputError, match="not in units of"):
        simulate(build("slip-to-roll"), 1.0, params={"beta": "3 kg"})
    with pytest.raises(InputError, match="'psi' is not a coordinate"):
        simulate(ladder, 1.0, initial_state={"psi": 1})
    with pytest.raises(InputError, match="empty or not finite"):
        simulate(ladder, -1.0)
    s = rk.System("no-values")
    m = s.parameter("m", "kg")
    x = s.coordinate("x", kind="length", initial=0, rate=1)
    s.body("b", rk.shapes.PointMass(m), frame=s.inertial, at=s.point("P", s.origin, x * s.inertial.x))
    with pytest.raises(InputError, match="the parameters m have no value"):
        simulate(s, 1.0)
    for err in (InputError, SimulationError):
        assert issubclass(err, RigidkinError)


def test_initial_rates_that_separate_a_contact_start_it_open(ladder):
    # the foot pushed away from the wall faster than the rod turns: the top leaves the wall at once
    r = simulate(ladder, 0.5, initial_state={"theta": 0.3, "dot(x)": 0.5})
    assert r.segments[0].mode == {"A": "open", "B": "slip", "A_floor": "open"}
    # pushing the foot towards the wall would drive the top into it
    with pytest.raises(InputError, match="violates the constraints"):
        simulate(ladder, 0.5, initial_state={"theta": 0.3, "dot(x)": -0.5})
    with pytest.raises(InputError, match="into its surface"):
        simulate(ladder, 0.5, initial_state={"theta": 0.3, "x": 0.1})


def test_outputs_csv_json_plot_and_dense_state(ladder, tmp_path):
    r = simulate(ladder, 6.0, n_points=301, initial_state={"theta": 1e-6, "dot(theta)": 0.0})   # card (b): upright
    text = r.to_csv(tmp_path / "h.csv")
    head = text.splitlines()[0].split(",")
    assert head[:6] == ["t", "mode", "theta", "x", "dot(theta)", "dot(x)"]
    assert {"N_A", "N_B", "energy: T", "energy: U", "energy: E", "energy: W"} <= set(head)
    rows = text.splitlines()[1:]
    assert len(rows) == len(r.t) and float(rows[-1].split(",")[0]) == 6.0
    d = json.loads(r.to_json())
    assert {"events", "final_state", "energy_drift"} <= set(d)
    assert d["events"][0]["name"] == "contact A opens" and set(d["events"][0]["state"]) == {
        "theta", "x", "dot(theta)", "dot(x)"}
    # the dense output between samples agrees with the card's equation θ̈ = (3g/2l) sin θ integrated by hand
    from scipy.integrate import solve_ivp

    l = 2.0
    card = solve_ivp(lambda t, y: [y[1], 1.5 * G / l * np.sin(y[0])], (0, 4.5), [1e-6, 0.0], method="DOP853",
                     rtol=1e-12, atol=1e-16, dense_output=True)
    for t_ in (2.0, 4.0, 4.4):
        assert abs(r.at(t_)["theta"] - card.sol(t_)[0]) < 1e-8 * max(1.0, card.sol(t_)[0])
    fig = r.plot(tmp_path / "f.png")
    assert (tmp_path / "f.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(fig.axes) >= 4


def test_a_mode_entered_with_another_constant_of_integration_continues_exactly():
    # a sphere dropped onto the fixed sphere off the line φ = r θ/(R + r) the rolling relation was integrated
    # from: after the (plastic) impact it rolls with its own constant of integration (the mode's equations keep
    # φ as a coordinate), then leaves where N = 0. By hand, rolling from (φa, φ̇a) conserves
    # (7/10) m (R+r)² φ̇² + m g (R+r) cos φ, and N = 0 where g cos φ = (R+r) φ̇²:
    # cos φ_leave = (10 cos φa + 7 (R+r) φ̇a²/g)/17.
    s = build("sphere-on-sphere")
    R, r_, g = 1.0, 0.1, 9.81
    res = simulate(s, 2.0, initial_state={"theta": 0.0, "phi": 0.3, "rho": R + r_ + 0.05})
    assert res.events[0].kind == "impact"
    after = res.events[0].after
    phia, wa = after["phi"], after["dot(phi)"]
    assert abs((R + r_) * after["dot(phi)"] - r_ * after["dot(theta)"]) < 1e-9     # rolling after the impact
    leave = [e for e in res.events if e.kind == "opens"]
    assert leave, res.message
    cos_leave = (10 * np.cos(phia) + 7 * (R + r_) * wa**2 / g) / 17
    assert abs(np.cos(leave[0].state["phi"]) - cos_leave) < 1e-8
