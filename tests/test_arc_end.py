"""Issue 29.7: a half cylinder whose contact point reaches the end of its arc goes on on the edge there, and
from the edge onto its flat face (or back onto the arc).

The body: a semicircular disk (mass m, radius r, mass centre G at b = 4r/(3π) from the flat-face centre O along
toward = −B.y), free in the plane (x, y of O, tilt θ) on the floor y = 0.  On the arc O is at height r and the
contact point below it; the arc margin is cos θ, so the arc ends at θ = ±π/2, where the diameter is vertical
and the edge E2 = O − r B.x (E1 = O + r B.x for θ = −π/2) is the contact point.  About the edge,
G − E2 = (u, v) = (r cos θ + b sin θ, r sin θ − b cos θ), v = ρ sin(θ − δ) with ρ = √(r² + b²), tan δ = b/r.
I_G = m r²/2 − m b²; about the edge I_E = I_G + m ρ² = 3 m r²/2; on the arc about the contact point
I_P(θ) = m (3r²/2 − 2 r b cos θ).

Every expected value below is worked out by hand from these (energy integrals, impulse–momentum, statics)
and evaluated with scipy's quad; none is read from the engine.
"""

import numpy as np
import pytest
from scipy.integrate import quad

import rigidkin as rk
from rigidkin.numeric.simulate import simulate

M, R, G = 1.0, 0.1, 9.81
B = 4 * R / (3 * np.pi)
RHO, DELTA = np.hypot(R, B), np.arctan2(B, R)
I_G, I_E = M * R**2 / 2 - M * B**2, 1.5 * M * R**2


def half_disk(friction):
    s = rk.System("half disk on the floor")
    m, r, g = s.parameter("m", "kg", value=M), s.parameter("r", "m", value=R), s.parameter("g", "m/s^2", value=G)
    th = s.coordinate("theta", "tilt, counter-clockwise")
    x = s.coordinate("x", "flat-face centre along Ex", kind="length")
    y = s.coordinate("y", "flat-face centre above the floor", kind="length", initial=R)
    F = s.inertial
    O1 = s.point("O1", s.origin, x * F.Ex + y * F.Ey, description="centre of the flat face")
    body = s.body("half", rk.shapes.SemicircularDisk(m, r), frame=s.frame("B", angle=th), at=O1)
    s.contact("P", body, s.line(s.origin, F.Ey), centre=O1, radius=r, friction=friction)
    s.gravity(g)
    return s


@pytest.fixture(scope="module")
def rolling():
    return half_disk("rolling")


def _v(th):
    return R * np.sin(th) - B * np.cos(th)


def _arc_time(w0, th1):
    """Rolling on the arc from θ = 0 at θ̇0 = w0: ½ I_P(θ) θ̇² + m g (r − b cos θ) = ½ I_P(0) w0² + m g (r − b)."""
    def rate(th):
        return np.sqrt((M * (1.5 * R**2 - 2 * R * B) * w0**2 - 2 * M * G * B * (1 - np.cos(th)))
                       / (M * (1.5 * R**2 - 2 * R * B * np.cos(th))))
    return quad(lambda th: 1 / rate(th), 0, th1, epsabs=1e-13, epsrel=1e-12)[0], rate(th1)


def _edge_time(th_a, v_top):
    """Pivoting about a fixed edge: ½ I_E θ̇² + m g v(θ) = m g v_top; the time from θ_a to the top
    θ_top = δ + asin(v_top/ρ), with θ = θ_top − s² to remove the endpoint's 1/√ singularity."""
    top = DELTA + np.arcsin(v_top / RHO)
    s_a = np.sqrt(top - th_a)
    return quad(lambda s_: 2 * s_ / np.sqrt(2 * M * G * (v_top - _v(top - s_**2)) / I_E) if s_ > 0 else
                2 / np.sqrt(2 * M * G * RHO * np.cos(top - DELTA) / I_E), 0, s_a, epsabs=1e-13, epsrel=1e-12)[0]


def test_rolling_half_disk_rocks_on_its_edge_and_back(rolling):
    """θ̇0 = 12 rad/s rolling: the arc ends at θ = π/2 with ½ I_E ω1² = ½ I_P(0) w0² − m g b; the edge E2 is then
    the contact point (velocity zero: no impact, no jump).  On the edge G rises to v_top = r + I_E ω1²/(2 m g)
    < ρ (it does not tip over) and falls back; at θ = π/2 again the arc takes the contact back with θ̇ = −ω1,
    rolls through θ = 0 and reaches θ = −π/2 at t1 + t_edge + 2 t1, where E1 takes it."""
    w0 = 12.0
    res = simulate(rolling, 1.0, {"theta": 0.0, "dot(theta)": w0})
    assert res.stop_reason == "completed"
    ev = res.events
    assert [e.kind for e in ev[:3]] == ["arc", "arc-back", "arc"]
    assert ev[0].name == "the arc of P ends: the edge P_edge2 takes the contact"
    js = res.to_dict()["events"][0]
    assert (js["kind"], js["name"]) == ("arc", ev[0].name) and "P_edge2 takes the contact" in js["detail"]
    assert ev[1].name == "the edge P_edge2 hands the contact back to the arc of P"
    assert ev[2].name == "the arc of P ends: the edge P_edge1 takes the contact"
    assert (ev[0].mode_before, ev[0].mode_after) == ("P rolling", "P open, P_edge2 sticking")
    t1, _ = _arc_time(w0, np.pi / 2)
    w1 = np.sqrt((M * (1.5 * R**2 - 2 * R * B) * w0**2 - 2 * M * G * B) / I_E)
    a = ev[0].state
    assert ev[0].t == pytest.approx(t1, rel=1e-8) and a["theta"] == pytest.approx(np.pi / 2, abs=1e-9)
    assert a["dot(theta)"] == pytest.approx(w1, rel=1e-8)
    # the edge's velocity at the hand-over: v_O + θ̇ ez × (E2 − O) = (ẋ + r θ̇ sin θ, ẏ − r θ̇ cos θ) = 0
    assert abs(a["dot(x)"] + R * a["dot(theta)"]) < 1e-9 and abs(a["dot(y)"]) < 1e-9
    assert all(abs(ev[0].after[k] - a[k]) < 1e-9 for k in a)            # no impulse
    # on the edge: N = m (g + θ̈ u − θ̇² v), θ̈ = −m g u / I_E, at θ = π/2 (u = b, v = r)
    j = int(np.argmax(res.segment == 1))
    assert res.t[j] == pytest.approx(t1, rel=1e-12)
    acc = -M * G * B / I_E
    assert res["N_P_edge2"][j] == pytest.approx(M * (G + acc * B - w1**2 * R), rel=1e-6)
    t_edge = 2 * _edge_time(np.pi / 2, R + I_E * w1**2 / (2 * M * G))
    assert ev[1].t == pytest.approx(t1 + t_edge, rel=1e-7)
    assert ev[1].state["theta"] == pytest.approx(np.pi / 2, abs=1e-9)
    assert ev[1].state["dot(theta)"] == pytest.approx(-w1, rel=1e-7)
    assert ev[2].t == pytest.approx(3 * t1 + t_edge, rel=1e-7)
    assert ev[2].state["theta"] == pytest.approx(-np.pi / 2, abs=1e-9)
    assert res.energy_drift < 1e-7


def test_an_edge_that_approaches_at_the_hand_over_strikes(rolling):
    """A closed arc hands over with the edge at rest (above); were the edge approaching (here the state at the
    hand-over with ẏ = −0.5 put in by hand), the hand-over is a plastic no-slip impact at E2: the angular momentum
    about E2 is kept, H = I_G ω + m (G − E2) × v_G = I_E ω + m b ẏ (G − E2 = (b, r), v_G = (−r ω, ẏ + b ω)), so
    ω⁺ = ω + m b ẏ / I_E, and E2 at rest after (ẋ⁺ = −r ω⁺, ẏ⁺ = 0)."""
    from rigidkin.numeric.contacts.transition import transition
    from rigidkin.numeric.simulate import hybrid_of

    res = simulate(rolling, 0.25, {"theta": 0.0, "dot(theta)": 12.0})
    ev, seg = res.events[0], res.segments[0]
    hyb = hybrid_of(rolling)
    lay = hyb.layout
    y = np.array([ev.state[k] for k in lay.labels] + [0.0])
    y[lay.labels.index("dot(y)")] = -0.5
    w = next(w_ for w_ in seg.model.watches if w_.kind == "arc")
    mode, _, y2, out = transition(hyb, seg.model, w, ev.t, y, seg.params, {"P": 0.0}, 1e-5)
    wa = ev.state["dot(theta)"] + M * B * -0.5 / I_E
    after = lay.as_dict(y2)
    assert out.name == "the arc of P ends: the edge P_edge2 strikes the surface" and mode["P"] == "open"
    assert after["dot(theta)"] == pytest.approx(wa, rel=1e-9)
    assert after["dot(x)"] == pytest.approx(-R * wa, rel=1e-9) and abs(after["dot(y)"]) < 1e-12


def test_released_on_its_edge_it_rocks_back_onto_the_arc(rolling):
    """At rest on the edge E2 at θ0 = 1.9 < π/2 + δ (G on the arc's side of the edge): it pivots back to θ = π/2,
    θ̇ = −√(2 m g (v(θ0) − r)/I_E), at t = edge time from π/2 to θ0; then the arc rolls on to θ = −θ0 (energy)."""
    th0 = 1.9
    res = simulate(rolling, 1.0, {"theta": th0, "y": R * np.sin(th0), "dot(theta)": 0.0})
    assert res.stop_reason == "completed"
    assert res.segments[0].description.startswith("P open, P_edge2 sticking")
    back = res.events[0]
    assert back.kind == "arc-back" and back.t == pytest.approx(_edge_time(np.pi / 2, _v(th0)), rel=1e-7)
    assert back.state["dot(theta)"] == pytest.approx(-np.sqrt(2 * M * G * (_v(th0) - R) / I_E), rel=1e-7)
    assert res.events[1].kind == "arc" and res.events[1].contact == "P"
    assert min(res.q["theta"]) == pytest.approx(-th0, abs=2e-3)        # sampled near the turning point


def test_a_no_slip_edge_cannot_let_it_fall_flat(rolling):
    """At rest on E2 past the top (θ0 = 2.0 > π/2 + δ) it pivots towards the flat face; on a no-slip edge
    N = m (g + θ̈ u − θ̇² v) with θ̈ = −m g u / I_E and ½ I_E θ̇² = m g (v(θ0) − v(θ)) reaches zero before θ = π
    (there N = m (g/3 − b θ̇²) < 0), where flight would need the edge to sink: the run stops and says why."""
    th0 = 2.0
    res = simulate(rolling, 1.0, {"theta": th0, "y": R * np.sin(th0), "dot(theta)": 0.0})
    assert res.stop_reason == "no-consistent-mode" and "P_edge2" in res.message
    th = res.final_state["theta"]
    u, v = R * np.cos(th) + B * np.sin(th), _v(th)
    w2 = 2 * M * G * (_v(th0) - v) / I_E
    assert res.final_state["dot(theta)"] ** 2 == pytest.approx(w2, rel=1e-7)
    assert np.pi / 2 + DELTA < th < np.pi
    assert abs(G - G * u**2 / (1.5 * R**2) - w2 * v) < 1e-6 * G          # N = 0 by hand where it stops


@pytest.mark.slow
def test_frictionless_edge_slides_back_onto_the_arc():
    """Smooth: at rest on E2 at θ0 = 1.9, G falls straight down (x_G fixed) while E2 slides; y_G = v(θ), ẏ_G = u θ̇,
    so ½ (I_G + m u²) θ̇² + m g v(θ) = m g v(θ0).  At θ = π/2 (u = b) the arc takes the contact back, sliding, with
    θ̇² = 2 m g (v(θ0) − r)/(I_G + m b²); the motion is symmetric, so it swings to θ = −θ0 on E1."""
    th0 = 1.9
    res = simulate(half_disk("smooth"), 0.8, {"theta": th0, "y": R * np.sin(th0), "dot(theta)": 0.0,
                                              "dot(x)": 0.0})
    assert res.stop_reason == "completed"
    back = res.events[0]
    assert back.kind == "arc-back" and (back.mode_before, back.mode_after) == ("P open, P_edge2 closed", "P closed")
    assert back.state["dot(theta)"] == pytest.approx(-np.sqrt(2 * M * G * (_v(th0) - R) / (I_G + M * B**2)),
                                                     rel=1e-7)
    assert [e.kind for e in res.events[:2]] == ["arc-back", "arc"] and res.events[1].contact == "P"
    assert res.events[1].name.endswith("the edge P_edge1 takes the contact")
    assert min(res.q["theta"]) == pytest.approx(-th0, abs=2e-3)
    xg = res.q["x"] + B * np.sin(res.q["theta"])                           # x_G = x + b sin θ stays put
    assert np.max(np.abs(xg - xg[0])) < 1e-8 and res.energy_drift < 1e-7


def _landing(ev, mu):
    """Impulse–momentum at θ = π (flat face landing on E1, E2 already touching), e = 0: both edges end with zero
    normal speed, so v_Gy⁺ = 0 and ω⁺ = 0; S = Λ1 + Λ2 = −m v_Gy⁻; sliding (if |v_Gx⁻| > µ S/m) takes
    v_Gx⁺ = v_Gx⁻ − µ S sgn(v_Gx⁻)/m, else v_Gx⁺ = 0 with the friction impulse m v_Gx⁻; moments about G:
    r (Λ2 − Λ1) + b (Fx1 + Fx2) = −I_G ω⁻."""
    a = ev.state
    w, vx, vy = a["dot(theta)"], a["dot(x)"] - B * a["dot(theta)"], a["dot(y)"]   # G = O + b (sin θ, −cos θ)
    S = -M * vy
    Fx = -mu * S * np.sign(vx) if abs(vx) > mu * S / M else -M * vx
    d = (-I_G * w - B * Fx) / R                      # Λ2 − Λ1
    return (S - d) / 2, (S + d) / 2, vx + Fx / M, -(0.5 * M * (vx**2 + vy**2) + 0.5 * I_G * w**2)


@pytest.mark.parametrize("friction, w0, mu", [pytest.param(0.5, 13.0, 0.5, marks=pytest.mark.slow),
                                              ("smooth", 20.0, 0.0)])
def test_half_disk_rolls_off_its_arc_onto_its_flat_face(friction, w0, mu):
    """Fast enough to pass G over the edge (½ I_E ω1² > m g (ρ − r)) it falls onto the flat face: E1 lands with an
    impact (impulses by hand, energy lost), then it rests on both edges with N1 = N2 = m g/2 (statics: G midway)."""
    s = half_disk(friction)
    start = {"theta": 0.0, "dot(theta)": w0} | ({"dot(x)": -R * w0} if friction != "smooth" else {})
    res = simulate(s, 0.8, start)
    assert res.stop_reason == "completed"
    ev = res.events
    assert ev[0].kind == "arc" and ev[0].state["theta"] == pytest.approx(np.pi / 2, abs=1e-9)
    if friction == "smooth":     # x_G keeps its speed b w0; ½ (I_G + m b² sin²θ) θ̇² + m g (r − b cos θ) conserved
        w1 = np.sqrt((I_G * w0**2 - 2 * M * G * B) / (I_G + M * B**2))
    else:
        w1 = np.sqrt((M * (1.5 * R**2 - 2 * R * B) * w0**2 - 2 * M * G * B) / I_E)
    assert ev[0].state["dot(theta)"] == pytest.approx(w1, rel=1e-8)
    land = [e for e in ev if e.kind == "impact"]
    assert land and land[0].contact == "P_edge1" and land[0].state["theta"] == pytest.approx(np.pi, abs=1e-9)
    if friction == "smooth":     # on the edge: ½ (I_G + m u²) θ̇² + m g v conserved (u = b at π/2, −r at π)
        wl = np.sqrt(((I_G + M * B**2) * w1**2 + 2 * M * G * (R - B)) / (I_G + M * R**2))
        assert land[0].state["dot(theta)"] == pytest.approx(wl, rel=1e-7)
    L1, L2, vx_after, dT = _landing(land[0], mu)
    imp = land[0].impact
    assert imp["contacts"]["P_edge1"]["normal_impulse"] == pytest.approx(L1, rel=1e-7)
    assert imp["contacts"]["P_edge2"]["normal_impulse"] == pytest.approx(L2, rel=1e-7)
    assert imp["energy_change"] <= 0 and imp["energy_change"] == pytest.approx(dT + 0.5 * M * vx_after**2, rel=1e-7)
    after = land[0].after
    assert abs(after["dot(theta)"]) < 1e-9 and abs(after["dot(y)"]) < 1e-9
    assert after["dot(x)"] == pytest.approx(vx_after, rel=1e-7, abs=1e-12)
    end = res.final_state
    assert end["theta"] == pytest.approx(np.pi, abs=1e-9) and abs(end["y"]) < 1e-9
    assert res["N_P_edge1"][-1] == pytest.approx(M * G / 2, rel=1e-7)
    assert res["N_P_edge2"][-1] == pytest.approx(M * G / 2, rel=1e-7)
    if friction == "smooth":
        assert end["dot(x)"] == pytest.approx(B * w0, rel=1e-8)        # the horizontal momentum, unchanged


def test_edges_take_their_arc_contacts_restitution():
    """e = 0.5 given for P: the landing edge leaves at −e times its approach speed (Newton's law)."""
    res = simulate(half_disk("smooth"), 0.3, {"theta": 0.0, "dot(theta)": 20.0}, restitution={"P": 0.5})
    land = [e for e in res.events if e.kind == "impact"][0]
    assert land.contact == "P_edge1"
    assert land.impact["separation_speed"] == pytest.approx(-0.5 * land.impact["approach_speed"], rel=1e-9)


def test_dropped_on_its_edge_it_pivots_on_it(rolling):
    """Dropped without spin, flat face down and tilted (θ0 = π − 0.3), from h = 1 cm above the strike: E2 = O − r B.x
    is lowest and strikes when y = r sin θ0, after t* = √(2h/g), at v_G⁻ = (0, −g t*).  A plastic no-slip impact
    leaves E2 at rest: the angular momentum about E2 is kept, I_E ω⁺ = m (u v_Gy⁻ − v v_Gx⁻), so
    ω⁺ = m u v_Gy⁻ / I_E and v_G⁺ = ω⁺ (−v, u); the impulse on the body is m (v_G⁺ − v_G⁻).  (From higher up the
    spin it takes would need a pulling edge at once: N = m (g + θ̈ u − ω⁺² v) < 0.)"""
    th0, h = np.pi - 0.3, 0.01
    y0 = R * np.sin(th0) + h
    t_star = np.sqrt(2 * h / G)
    res = simulate(rolling, 1.001 * t_star, {"theta": th0, "y": y0, "dot(theta)": 0.0, "dot(x)": 0.0})
    hit = res.events[0]
    assert (hit.kind, hit.contact) == ("impact", "P_edge2") and hit.t == pytest.approx(t_star, rel=1e-9)
    assert res.segments[0].description == "P open"
    u, v, vy = R * np.cos(th0) + B * np.sin(th0), _v(th0), -G * t_star
    w = M * u * vy / I_E
    assert hit.after["dot(theta)"] == pytest.approx(w, rel=1e-8)
    imp = hit.impact["contacts"]["P_edge2"]
    assert imp["normal_impulse"] == pytest.approx(M * (w * u - vy), rel=1e-8)
    assert abs(imp["tangential_impulse"]) == pytest.approx(abs(M * w * v), rel=1e-8)
    assert hit.impact["energy_change"] == pytest.approx(0.5 * I_E * w**2 - 0.5 * M * vy**2, rel=1e-8)
    assert hit.mode_after == "P open, P_edge2 sticking"


def test_a_half_disk_at_rest_on_its_flat_face_stays():
    s = half_disk(0.5)
    res = simulate(s, 0.2, {"theta": np.pi, "y": 0.0})
    assert res.stop_reason == "completed" and not res.events
    assert res["N_P_edge1"][-1] == pytest.approx(M * G / 2, rel=1e-9)
    assert res["N_P_edge2"][-1] == pytest.approx(M * G / 2, rel=1e-9)


def test_outputs_unchanged_where_the_arc_never_ends(rolling):
    """Rocking gently (θ0 = 0.3 at rest) the edges never appear: no events, mode words and reactions as before."""
    res = simulate(rolling, 0.5, {"theta": 0.3, "dot(theta)": 0.0})
    assert res.stop_reason == "completed" and not res.events
    assert [s_.description for s_ in res.segments] == ["P rolling"]
    assert not any("edge" in k for k in res.reactions)
    assert max(res.q["theta"]) == pytest.approx(0.3, abs=1e-6)


def test_without_a_coordinate_to_leave_the_arc_it_stops_with_the_reason():
    """O kept at height r by the coordinates (x, θ only): the edge cannot take over; reason arc-end, and a hint."""
    s = rk.System("half disk on x and theta")
    m, r, g = s.parameter("m", "kg", value=M), s.parameter("r", "m", value=R), s.parameter("g", "m/s^2", value=G)
    th = s.coordinate("theta", "tilt", initial=0, rate=15)
    x = s.coordinate("x", "flat-face centre along Ex", kind="length")
    O1 = s.point("O1", s.origin, x * s.inertial.Ex + r * s.inertial.Ey)
    body = s.body("half", rk.shapes.SemicircularDisk(m, r), frame=s.frame("B", angle=th), at=O1)
    s.contact("P", body, s.line(s.origin, s.inertial.Ey), centre=O1, radius=r, friction="rolling")
    s.gravity(g)
    res = simulate(s, 1.0)
    assert res.stop_reason == "arc-end" and res.final_state["theta"] == pytest.approx(np.pi / 2, abs=1e-8)
    assert "P_edge2" in res.message and "height of its flat-face centre" in res.message
