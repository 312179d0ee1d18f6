"""Impacts: impulse–momentum at the instant a separated point reaches its surface, against hand results."""

import numpy as np
import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.numeric import simulate

G = 9.81


def dropped_disk(friction="smooth", h=0.8, vx=0.0):
    """A disk of radius r whose centre starts h above its touching height, with horizontal speed vx."""
    s = rk.System("drop", title="Disk dropped on the floor")
    m = s.parameter("m", "kg", value=2.0)
    r = s.parameter("r", "m", value=0.1)
    g = s.parameter("g", "m/s^2", value=G)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=vx)
    y = s.coordinate("y", "centre height", kind="length", initial=0.1 + h, rate=0)
    phi = s.coordinate("phi", "rotation, clockwise", initial=0, rate=0)
    D = s.frame("D", angle=-phi)
    C = s.point("C", s.origin, x * s.inertial.x + y * s.inertial.y)
    disk = s.body("disk", rk.shapes.SolidSphere(m, r), frame=D, at=C)
    s.contact("floor", disk, s.line(s.origin, s.inertial.y), radius=r, friction=friction)
    s.gravity(g)
    return s


@pytest.fixture(scope="module")
def bouncing():
    s = dropped_disk()
    return s, simulate(s, 2.0, restitution=0.5)


def test_bounces_follow_newtons_restitution(bouncing):
    _, r = bouncing
    h, e = 0.8, 0.5
    v0 = np.sqrt(2 * G * h)
    impacts = r.events_of("impact")
    assert impacts[0].contact == "floor" and impacts[0].mode_before == "floor open"
    # impact k happens at t1 + 2 v0 (e + … + e^(k−1)) / g with speed v0 e^(k−1) before it
    t_k = np.sqrt(2 * h / G)
    for k, ev in enumerate(impacts[:6]):
        assert abs(ev.t - t_k) < 1e-9
        assert abs(ev.state["dot(y)"] + v0 * e**k) < 1e-8
        assert abs(ev.after["dot(y)"] - v0 * e ** (k + 1)) < 1e-8
        t_k += 2 * v0 * e ** (k + 1) / G


def test_bouncing_comes_to_rest_at_the_accumulation_time(bouncing):
    s, r = bouncing
    h, e = 0.8, 0.5
    v0 = np.sqrt(2 * G * h)
    t_inf = np.sqrt(2 * h / G) + 2 * v0 * e / (G * (1 - e))
    last = r.events[-1]
    # it closes when a bounce would leave slower than rest_speed (1e-5 m/s): the flights left are ~1e-6 s
    assert last.kind == "impact" and last.mode_after == "floor closed"
    assert 0 < t_inf - last.t < 4 * 1e-5 * e / (G * (1 - e))
    assert r.segments[-1].mode == {"floor": "slip"}               # closed and at rest on the floor
    assert abs(r.final_state["y"] - 0.1) < 1e-9 and abs(r.final_state["dot(y)"]) < 1e-6
    # the energy lost in the impacts is the whole drop m g h: E − E0 = W (impulse work)
    assert abs(r.energy["W"][-1] + 2.0 * G * h) < 1e-6
    assert r.energy_drift < 1e-9
    assert r.status == "completed"


def test_tilted_rod_striking_the_floor_with_one_end():
    m_, l_, th0, h, e = 3.0, 1.2, 0.5, 0.3, 0.4
    s = rk.System("rod-drop")
    m = s.parameter("m", "kg", value=m_)
    l = s.parameter("l", "m", value=l_)
    g = s.parameter("g", "m/s^2", value=G)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=l_ / 2 * np.sin(th0) + h, rate=0)
    th = s.coordinate("theta", "angle of the rod from Ex, counter-clockwise", initial=th0, rate=0)
    R = s.frame("R", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="x"), frame=R, at=Gp)
    B = s.point("B", Gp, -l / 2 * R.x, body=rod)
    s.contact("B", rod, s.line(s.origin, s.inertial.y), centre=B)
    s.gravity(g)
    r = simulate(s, np.sqrt(2 * h / G) + 0.05, restitution=e)
    ev = r.events_of("impact")[0]
    v = np.sqrt(2 * G * h)
    # by hand: m (v_y⁺ + v) = P, I ω⁺ = r_x P (r_GB = −(l/2)(cos θ0, sin θ0)), v_y⁺ + ω⁺ r_x = e v
    vy, w, P = sp.symbols("vy w P")
    rx = -l_ / 2 * np.cos(th0)
    sol = sp.solve([m_ * (vy + v) - P, m_ * l_**2 / 12 * w - rx * P, vy + w * rx - e * v], [vy, w, P], dict=True)[0]
    assert abs(ev.t - np.sqrt(2 * h / G)) < 1e-9
    assert abs(ev.after["dot(y)"] - float(sol[vy])) < 1e-9
    assert abs(ev.after["dot(theta)"] - float(sol[w])) < 1e-9
    assert abs(ev.after["dot(x)"]) < 1e-12                      # a smooth floor gives no horizontal impulse
    assert r.segments[-1].mode == {"B": "open"}                  # the end bounces off (e v > 0)


def test_plastic_impact_on_a_rough_floor_starts_rolling():
    # a sphere dropped with horizontal speed and no spin onto a perfectly rough floor (e = 0): the impulse
    # passes through the contact point, so the angular momentum about it is kept: v⁺ = 5 v⁻ / 7, rolling
    vx = 1.5
    s = dropped_disk("rolling", h=0.2, vx=vx)
    r = simulate(s, 0.4)
    (ev,) = r.events
    assert ev.kind == "impact"
    assert abs(ev.after["dot(x)"] - 5 * vx / 7) < 1e-10
    assert abs(ev.after["dot(phi)"] - 5 * vx / 7 / 0.1) < 1e-9
    assert abs(ev.after["dot(y)"]) < 1e-12
    assert r.segments[-1].mode == {"floor": "stick"}
    last = r.segment == 1
    assert np.allclose(r["dot(x)"][last], 5 * vx / 7, rtol=0, atol=1e-10)


@pytest.mark.parametrize("mu, sticks", [(0.1, False), (0.5, True)])
def test_impact_on_a_coulomb_floor_sticks_or_slides(mu, sticks):
    # sliding: the friction impulse µ Λ_n with Λ_n = m v (e = 0) gives v_x⁺ = v_x − µ v, ω⁺ = (5/2) µ v / r;
    # sticking (µ v ≥ 2 v_x / 7): rolling at 5 v_x / 7.  Either way the impulses pass through the contact
    # point, so the ball ends rolling at 5 v_x / 7.
    vx, h, r_ = 1.5, 0.2, 0.1
    s = dropped_disk(mu, h=h, vx=vx)
    res = simulate(s, 1.5)
    ev = res.events[0]
    v = np.sqrt(2 * G * h)
    assert ev.kind == "impact" and abs(ev.after["dot(y)"]) < 1e-12
    if sticks:
        assert abs(ev.after["dot(x)"] - 5 * vx / 7) < 1e-10
        assert res.segments[1].mode == {"floor": "stick"} and len(res.events) == 1
    else:
        assert abs(ev.after["dot(x)"] - (vx - mu * v)) < 1e-10
        assert abs(ev.after["dot(phi)"] - 2.5 * mu * v / r_) < 1e-9
        assert res.events[1].kind == "sticks"
    assert abs(res.final_state["dot(x)"] - 5 * vx / 7) < 1e-9
