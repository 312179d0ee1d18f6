"""Rest on several rolling supports and exact friction thresholds, against hand impulse–momentum and
closed forms: a block rocking on rolling corners comes to rest on both; a cylinder on an incline at
µ = tan β / 3 exactly (and one ulp either side) rolls in one mode with no events."""

import math

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.numeric import simulate

G = 9.81


def rocking_block(tilt=0.2, b=0.4, h=0.6, m=2.0):
    """A block (width b, height h) standing on its corner A at tilt θ, both lower corners rolling (no slip)."""
    s = rk.System("rocking-block")
    m_, g = s.parameter("m", "kg", value=m), s.parameter("g", "m/s^2", value=G)
    b_, h_ = s.parameter("b", "m", value=b), s.parameter("h", "m", value=h)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=b / 2 * math.sin(tilt) + h / 2 * math.cos(tilt),
                     rate=0)
    th = s.coordinate("theta", "tilt, counter-clockwise", initial=tilt, rate=0)
    B = s.frame("B", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    box = s.body("box", rk.shapes.RectangularPlate(m_, b_, h_), frame=B, at=Gp)
    A = s.point("A", Gp, -b_ / 2 * B.x - h_ / 2 * B.y, body=box)
    C = s.point("C", Gp, b_ / 2 * B.x - h_ / 2 * B.y, body=box)
    floor = s.line(s.origin, s.inertial.y)
    s.contact("A", box, floor, centre=A, friction="rolling", normal_name="N_A", friction_name="F_A")
    s.contact("C", box, floor, centre=C, friction="rolling", normal_name="N_C", friction_name="F_C")
    s.gravity(g)
    return s


@pytest.mark.slow
def test_block_rocking_on_rolling_corners_comes_to_rest_on_both():
    b, h, m = 0.4, 0.6, 2.0
    res = simulate(rocking_block(0.2, b, h, m), 1.5, restitution=0.0)
    assert res.stop_reason == "completed" and res.reached_end
    impacts = [ev for ev in res.events if ev.kind == "impact"]
    assert len(impacts) >= 5
    alpha = math.atan2(b, h)
    for ev in impacts[:5]:
        w0, w1 = ev.state["dot(theta)"], ev.after["dot(theta)"]
        # Housner: angular momentum about the new corner, ω⁺ = (1 − (3/2) sin²α) ω⁻
        assert w1 == pytest.approx((1 - 1.5 * math.sin(alpha)**2) * w0, rel=1e-9)
        # the new corner's impulse by hand at θ = 0: v_G = ω ẑ × (G − corner), m Δv_G = (−F, N)
        new, old = ("C", "A") if w0 < 0 else ("A", "C")
        sx_old, sx_new = (b / 2, -b / 2) if new == "C" else (-b / 2, b / 2)
        vgx0, vgy0 = -w0 * h / 2, w0 * sx_old
        vgx1, vgy1 = -w1 * h / 2, w1 * sx_new
        imp = ev.impact["contacts"]
        assert imp[new]["normal_impulse"] == pytest.approx(m * (vgy1 - vgy0), rel=1e-9)
        assert imp[new]["tangential_impulse"] == pytest.approx(-m * (vgx1 - vgx0), rel=1e-9)
        assert imp[old]["normal_impulse"] == 0.0 or abs(imp[old]["normal_impulse"]) < 1e-12
    last = res.segments[-1]
    assert last.mode["A"] != "open" and last.mode["C"] != "open"
    assert "statically indeterminate" in impacts[-1].detail
    rest = res.t > last.t0 + 1e-9
    # at rest on both corners: N_A = N_C = m g / 2 (the lever rule); no friction needed
    assert np.allclose(res["N_A"][rest], m * G / 2, rtol=1e-9)
    assert np.allclose(res["N_C"][rest], m * G / 2, rtol=1e-9)
    assert np.max(np.abs(res["dot(theta)"][rest])) == 0.0


def cylinder(beta, mu, m=2.0, r=0.3):
    s = rk.System("cylinder-on-incline")
    m_, r_ = s.parameter("m", "kg", value=m), s.parameter("r", "m", value=r)
    g, b = s.parameter("g", "m/s^2", value=G), s.parameter("beta", "rad", value=beta)
    mu_ = s.parameter("mu", "", value=mu)
    x = s.coordinate("x", "centre down the slope", kind="length", initial=0, rate=0)
    phi = s.coordinate("phi", "turn, clockwise seen", initial=0, rate=0)
    inc = s.frame("I", angle=-b, basis=("es", "en", "ez"))
    D = s.frame("D", parent=inc, angle=-phi)
    C = s.point("C", s.origin, x * inc.es + r_ * inc.en)
    disk = s.body("cyl", rk.shapes.Disk(m_, r_), frame=D, at=C)
    s.contact("ground", disk, s.line(s.origin, inc.en), centre=C, radius=r_, friction=mu_, normal_name="N",
              friction_name="F")
    s.gravity(g)
    return s


@pytest.mark.parametrize("side", [-1, 0, 1])
def test_cylinder_at_the_exact_rolling_threshold_one_mode_no_events(side):
    beta, m = math.radians(30), 2.0
    mu_star = math.tan(beta) / 3                 # rolling needs F = m g sin β / 3 ≤ µ m g cos β
    mu = float(np.nextafter(mu_star, np.inf * side)) if side else mu_star
    res = simulate(cylinder(beta, mu, m), 2.0, max_events=50)
    assert res.stop_reason == "completed" and not res.events
    assert len(res.segments) == 1 and res.segments[0].mode == {"ground": "stick"}
    a = 2 * G * math.sin(beta) / 3                # rolling: a = g sin β / (1 + I/(m r²)), I = m r²/2
    assert np.max(np.abs(res["x"] - a * res.t**2 / 2)) < 1e-9
    assert np.allclose(res["N"], m * G * math.cos(beta), rtol=1e-12)
    assert np.allclose(np.abs(res["F"]), m * G * math.sin(beta) / 3, rtol=1e-12)


def test_cylinder_clearly_below_the_threshold_slips_from_the_start():
    beta, m = math.radians(30), 2.0
    mu = 0.9 * math.tan(beta) / 3
    res = simulate(cylinder(beta, mu, m), 1.0, max_events=50)
    assert not res.events and res.segments[0].mode == {"ground": "slip"}
    a = G * (math.sin(beta) - mu * math.cos(beta))          # sliding: the centre accelerates with µk
    assert np.max(np.abs(res["x"] - a * res.t**2 / 2)) < 1e-9


def test_a_paradox_at_the_start_returns_the_result_with_its_stop_reason():
    import json
    import sys

    sys.path.insert(0, __file__.rsplit("/", 1)[0])
    from test_contacts_lcp import rod

    from rigidkin.numeric.contacts.contact_modes import ContactParadox

    theta = math.atan(2.0)                      # Painlevé: µ = 2 above µ* = 4/3, sliding from the start
    s = rod(2.0, theta, 0.0)
    res = simulate(s, 0.05, initial_state={"dot(x)": -1.0})
    assert not res.reached_end and res.stop_reason == "no-consistent-mode"
    assert res.t_final == 0.0 and [e.kind for e in res.events] == ["stop"]
    assert res.final_state["theta"] == pytest.approx(theta) and res.final_state["dot(x)"] == -1.0
    assert "µ* = 1.33333" in res.message
    d = json.loads(res.to_json())
    assert d["stop_reason"] == "no-consistent-mode" and d["final_state"]["dot(x)"] == -1.0
    with pytest.raises(ContactParadox):
        simulate(s, 0.05, initial_state={"dot(x)": -1.0}, raise_on_stop=True)
