"""Friction modes and the limits of a model: stick → slip, slip that reverses, a contact that cannot open."""

import numpy as np

import rigidkin as rk
from rigidkin.examples import build
from rigidkin.numeric import simulate

G = 9.81


def driven_disk(c=2.0, mu=0.3):
    """A disk at rest on a rough floor, driven by a torque c·t that grows from zero."""
    s = rk.System("driven-disk")
    m = s.parameter("m", "kg", value=1.5)
    r = s.parameter("r", "m", value=0.2)
    g = s.parameter("g", "m/s^2", value=G)
    mu_ = s.parameter("mu", "", value=mu)
    cc = s.parameter("c", "N*m/s", value=c)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    phi = s.coordinate("phi", "rotation, clockwise", initial=0, rate=0)
    D = s.frame("D", angle=-phi)
    C = s.point("C", s.origin, x * s.inertial.x + r * s.inertial.y)
    disk = s.body("disk", rk.shapes.Disk(m, r), frame=D, at=C)
    s.contact("floor", disk, s.line(s.origin, s.inertial.y), radius=r, friction=mu_)
    s.torque("drive", disk, -cc * rk.t * s.inertial.z, description="clockwise torque c t")
    s.gravity(g)
    return s


def test_rolling_disk_starts_to_slip_when_the_friction_needed_reaches_mu_n():
    m, r, c, mu = 1.5, 0.2, 2.0, 0.3
    s = driven_disk(c, mu)
    res = simulate(s, 2.0)
    assert res.segments[0].mode == {"floor": "stick"}      # at rest: it rolls, no slip needed
    (ev,) = res.events
    assert ev.kind == "slips"
    # rolling: F = m a, τ − F r = I a / r with I = m r²/2, so F = (2/3) τ / r reaches µ m g at t* = 3 µ m g r/(2c)
    t_star = 3 * mu * m * G * r / (2 * c)
    assert abs(ev.t - t_star) < 1e-9
    v_star = c * t_star**2 / (2 * (1.5 * m * r))              # ∫ a dt with a = τ r/(I + m r²)
    assert abs(ev.state["dot(x)"] - v_star) < 1e-9
    # then it spins faster than it rolls: friction µ m g forward, ẍ = µ g, and the slip speed ẋ − r φ̇ < 0
    after = res.segment == 1
    tt = res.t[after] - ev.t
    assert np.max(np.abs(res["dot(x)"][after] - (v_star + mu * G * tt))) < 1e-8
    assert np.all((res["dot(x)"] - r * res["dot(phi)"])[after][1:] < 0)
    assert np.allclose(np.abs(res["F_floor"][after]), mu * res["N_floor"][after], rtol=1e-12)
    assert res.energy_drift < 1e-9


def sliding_block(mu, beta=0.5, v0=3.0):
    """A particle sliding up a rough incline (coordinate s up the slope) with speed v0."""
    s = rk.System("block")
    m = s.parameter("m", "kg", value=1.0)
    g = s.parameter("g", "m/s^2", value=G)
    b = s.parameter("beta", "rad", value=beta)
    mu_ = s.parameter("mu", "", value=mu)
    q = s.coordinate("s", "distance up the incline", kind="length", initial=0, rate=v0)
    I = s.frame("I", angle=b)
    P = s.point("P", s.origin, q * I.x)
    blk = s.body("block", rk.shapes.PointMass(m), frame=s.inertial, at=P)
    s.contact("incline", blk, s.line(s.origin, I.y), friction=mu_)
    s.gravity(g)
    return s


def test_slip_that_cannot_stick_reverses():
    beta, v0, mu = 0.5, 3.0, 0.2                        # µ < tan β: the block slides back down
    res = simulate(sliding_block(mu, beta, v0), 2.0)
    (ev,) = res.events
    t_up = v0 / (G * (np.sin(beta) + mu * np.cos(beta)))
    assert abs(ev.t - t_up) < 1e-10
    assert abs(ev.state["dot(s)"]) < 1e-10
    after = res.segment == 1
    tt = res.t[after] - ev.t
    assert np.max(np.abs(res["dot(s)"][after] + G * (np.sin(beta) - mu * np.cos(beta)) * tt)) < 1e-9
    assert res.status == "completed"


def test_block_that_sticks_comes_to_rest_and_stays():
    # µ > tan β: the block comes to rest and stays (a mode with no degree of freedom: at rest)
    res = simulate(sliding_block(0.9, 0.5, 3.0), 2.0)
    assert res.status == "completed"
    (ev,) = res.events
    assert ev.kind == "sticks"
    t_up = 3.0 / (G * (np.sin(0.5) + 0.9 * np.cos(0.5)))
    assert abs(ev.t - t_up) < 1e-10
    after = res.segment == 1
    assert np.all(res["dot(s)"][after] == 0.0) and np.ptp(res["s"][after]) == 0.0


def test_contact_without_a_coordinate_to_open_stops_where_its_reaction_vanishes():
    s = build("disk-in-track")
    R, r = (s.parameter_info[k].value for k in ("R", "r"))
    v0 = np.sqrt(2 * G * (R - r))
    res = simulate(s, 3.0, initial_state={"theta": 0, "dot(theta)": v0 / (R - r)})
    assert res.status == "stopped"
    ev = res.events[-1]
    assert ev.kind == "stop" and ev.contact == "P"
    assert "no coordinate that lets P leave its surface" in res.message
    # N = m (R − r) θ̇² + m g cos θ and (3/4) v² = (3/4) v0² − g (R − r)(1 − cos θ) give cos θ = −2/7 here
    assert abs(np.cos(ev.state["theta"]) + 2 / 7) < 1e-8
    assert abs(res.t_final - ev.t) == 0
