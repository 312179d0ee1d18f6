"""Acceptance of the hybrid simulator against the cards' exact answers (not against itself)."""

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.examples import build
from rigidkin.numeric import Phase, simulate


def value(system, name):
    return system.parameter_info[name].value


# ladder -----------------------------------------------------------------------------------------
LADDER_TH0 = 1e-6


@pytest.fixture(scope="module")
def ladder_run():
    s = build("ladder")
    # card (b) releases the rod from rest upright: a start just off θ = 0 (the file's own start shows more motion)
    return s, simulate(s, 7.0, initial_state={"theta": LADDER_TH0, "dot(theta)": 0.0})


def test_ladder_leaves_the_wall_at_acos_two_thirds(ladder_run):
    s, r = ladder_run
    opened = [e for e in r.events if e.kind == "opens"]
    assert len(opened) == 1 and opened[0].contact == "A"
    th0 = LADDER_TH0
    # card (b): released from rest at θ0 it leaves the wall when cos θ = (2/3) cos θ0
    assert abs(opened[0].state["theta"] - np.arccos(2 / 3 * np.cos(th0))) < 1e-8
    assert abs(opened[0].state["theta"] - np.arccos(2 / 3)) < 1e-8
    # the energy integral θ̇² = (3 g / l)(cos θ0 − cos θ) at the event
    g, l = value(s, "g"), value(s, "l")
    th = opened[0].state["theta"]
    assert abs(opened[0].state["dot(theta)"] ** 2 - 3 * g / l * (np.cos(th0) - np.cos(th))) < 1e-8
    # the wall reaction is the one that reached zero; the floor still pushes
    before = r.t < opened[0].t
    assert np.all(r["N_A"][before] >= -1e-9) and np.all(r["N_B"] > 0)


def test_ladder_free_of_the_wall_keeps_horizontal_centre_speed(ladder_run):
    s, r = ladder_run
    g, l = value(s, "g"), value(s, "l")
    opened = [e for e in r.events if e.kind == "opens"][0]
    after = (r.t > opened.t) & (r.segment == [i for i, sg in enumerate(r.segments) if sg.t0 >= opened.t][0])
    # 2 DOF after the event: x is free (no longer l sin θ)
    assert r.segments[r.segment[after][0]].mode == {"A": "open", "B": "slip", "A_floor": "open"}
    assert np.max(np.abs(r["x"][after] - l * np.sin(r["theta"][after]))) > 0.1
    # mass centre x_G = x − (l/2) sin θ moves at constant speed sqrt(g l)/3 while no other contact acts
    # (until the rod lies flat, θ = π/2, where its top would reach the floor)
    flying = after & (r["theta"] < np.pi / 2)
    vG = r["dot(x)"][flying] - l / 2 * np.cos(r["theta"][flying]) * r["dot(theta)"][flying]
    assert flying.sum() > 10
    assert np.max(np.abs(vG - np.sqrt(g * l) / 3)) < 1e-8
    # no horizontal force: N_A = 0 after
    assert np.all(r["N_A"][after] == 0)
    # then the upper end comes down onto the floor (plastic impact; smooth floor: no horizontal impulse),
    # and the rod lies flat and slides on at the same horizontal speed
    hit = [e for e in r.events if e.kind == "impact"]
    assert len(hit) == 1 and hit[0].contact == "A_floor" and hit[0].t > opened.t
    assert abs(r.final_state["theta"] - np.pi / 2) < 1e-9 and abs(r.final_state["dot(theta)"]) < 1e-9
    assert abs(r.final_state["dot(x)"] - np.sqrt(g * l) / 3) < 1e-8


def test_ladder_energy_is_conserved(ladder_run):
    _, r = ladder_run
    # conserved until the upper end strikes the floor (a plastic impact then takes its share, booked as the
    # work of the impulse)
    hit = [e for e in r.events if e.kind == "impact"][0]
    E = r.energy["E"]
    before = r.t < hit.t
    assert np.max(np.abs(E[before] - E[0])) / abs(E[0]) < 1e-9
    assert r.energy_drift < 1e-9
    assert r.max_residual < 1e-8
    assert r.warnings == []


# slip-to-roll -------------------------------------------------------------------------------------
def _card_slip_to_roll(s):
    g, beta, mu, d = (value(s, k) for k in ("g", "beta", "mu", "d"))
    vB = np.sqrt(2 * g * d * np.sin(beta))
    ts = vB / (g * (3 * mu * np.cos(beta) - np.sin(beta)))
    v = 2 * mu * np.cos(beta) * vB / (3 * mu * np.cos(beta) - np.sin(beta))
    return vB, ts, v


def test_slip_to_roll_in_two_phases_matches_the_card():
    s = build("slip-to-roll")
    x = s.coordinates[0]
    d = s.parameters["d"]
    r = simulate(s, 1.6, phases=[Phase({"mu": 0}, until=x - d, name="end of the smooth stretch"), Phase()])
    vB, ts, v = _card_slip_to_roll(s)
    rr = value(s, "r")
    end_smooth, rolls = r.events
    assert end_smooth.kind == "phase" and abs(end_smooth.state["x"] - value(s, "d")) < 1e-10
    assert abs(end_smooth.state["dot(x)"] - vB) < 1e-8          # card (a)
    assert abs(end_smooth.state["dot(phi)"]) < 1e-12
    assert rolls.kind == "sticks" and rolls.contact == "ground"
    assert abs((rolls.t - end_smooth.t) - ts) < 1e-8             # card (b)
    assert abs(rolls.state["dot(x)"] - v) < 1e-8                 # card (c)
    assert abs(rolls.state["dot(phi)"] - v / rr) < 1e-8
    # afterwards it rolls: slip speed 0 and friction within µN
    after = r.segment == 2
    assert r.segments[-1].mode == {"ground": "stick"}
    assert np.max(np.abs(r["dot(x)"][after] - rr * r["dot(phi)"][after])) < 1e-9
    assert np.all(np.abs(r["F"][after]) <= value(s, "mu") * r["N"][after])
    assert r.energy_drift < 1e-9


def test_slip_to_roll_from_the_rough_part():
    s = build("slip-to-roll")
    vB, ts, v = _card_slip_to_roll(s)
    r = simulate(s, 1.0, initial_state={"x": value(s, "d"), "dot(x)": vB, "dot(phi)": 0})
    (rolls,) = r.events
    assert abs(rolls.t - ts) < 1e-8 and abs(rolls.state["dot(x)"] - v) < 1e-8


def test_slip_to_roll_never_rolls_when_friction_is_too_small():
    # µ < tan β / 3: the slip speed grows, the card says rolling is impossible
    s = build("slip-to-roll")
    beta = value(s, "beta")
    r = simulate(s, 1.0, params={"mu": 0.9 * np.tan(beta) / 3}, initial_state={"dot(x)": 1.0})
    assert r.events == [] and r.segments[-1].mode == {"ground": "slip"}
    assert np.all(np.diff(r["dot(x)"] - value(s, "r") * r["dot(phi)"]) > 0)


# billiard ball -------------------------------------------------------------------------------------
def billiard(v0=2.0, mu=0.2):
    s = rk.System("billiard", title="Billiard ball launched sliding")
    m = s.parameter("m", "kg", value=0.17)
    r = s.parameter("r", "m", value=0.028)
    g = s.parameter("g", "m/s^2", value=9.81)
    mu_ = s.parameter("mu", "", value=mu)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=v0)
    phi = s.coordinate("phi", "rotation, clockwise", initial=0, rate=0)
    B = s.frame("B", angle=-phi)
    C = s.point("C", s.origin, x * s.inertial.x + r * s.inertial.y)
    ball = s.body("ball", rk.shapes.SolidSphere(m, r), frame=B, at=C)
    s.contact("table", ball, s.line(s.origin, s.inertial.y), radius=r, friction=mu_)
    s.gravity(g)
    return s


def test_billiard_ball_starts_rolling_at_2v0_over_7mug():
    v0, mu, g = 2.0, 0.2, 9.81
    s = billiard(v0, mu)
    r = simulate(s, 1.0)
    (ev,) = r.events
    assert ev.kind == "sticks"
    assert abs(ev.t - 2 * v0 / (7 * mu * g)) < 1e-10
    assert abs(ev.state["dot(x)"] - 5 * v0 / 7) < 1e-10
    assert abs(ev.state["dot(phi)"] - 5 * v0 / 7 / 0.028) < 1e-8
    after = r.segment == 1
    assert np.allclose(r["dot(x)"][after], 5 * v0 / 7, atol=1e-10, rtol=0)   # rolls at constant speed
    assert np.all(np.abs(r["F_table"][after]) < 1e-9)                        # no friction needed
    # kinetic energy lost while slipping equals the friction work: E − E0 = W
    assert r.energy_drift < 1e-9 and r.energy_balance != "conserved"
    assert abs(r.energy["E"][-1] - r.energy["E"][0] - (-(1 / 7) * 0.17 * v0**2)) < 1e-9


# sphere on sphere ------------------------------------------------------------------------------------
def test_sphere_on_sphere_leaves_at_cos_10_17_and_flies_as_a_projectile():
    s = build("sphere-on-sphere")
    r = simulate(s, 7.2, initial_state={"theta": 1e-6, "dot(theta)": 0.0})     # the card: released from the top
    (ev,) = r.events
    assert ev.kind == "opens" and ev.contact == "P"
    assert abs(np.cos(ev.state["phi"]) - 10 / 17) < 1e-8
    assert r.segments[-1].mode == {"P": "open"}
    g = value(s, "g")
    st = ev.state
    after = r.segment == 1
    tt = r.t[after] - ev.t
    rho, phi = r["rho"][after], r["phi"][after]
    xc, yc = rho * np.sin(phi), rho * np.cos(phi)         # C = ρ A.y, A turned by −φ
    vx = st["dot(rho)"] * np.sin(st["phi"]) + st["rho"] * np.cos(st["phi"]) * st["dot(phi)"]
    vy = st["dot(rho)"] * np.cos(st["phi"]) - st["rho"] * np.sin(st["phi"]) * st["dot(phi)"]
    assert tt[-1] > 0.3
    assert np.max(np.abs(xc - (xc[0] + vx * tt))) < 1e-8
    assert np.max(np.abs(yc - (yc[0] + vy * tt - g * tt**2 / 2))) < 1e-8
    # the spin stays what it was when the contact opened (no torque in flight)
    assert np.max(np.abs(r["dot(theta)"][after] - st["dot(theta)"])) < 1e-8
    # and the gap grows: no impact
    assert np.all(rho[1:] - value(s, "R") - value(s, "r") > 0)
    assert r.energy_drift < 1e-9


# paper pull -----------------------------------------------------------------------------------------
def test_paper_pull_end_state_equals_the_card():
    s = build("paper-pull")
    mu, g, r_, dt = (value(s, k) for k in ("mu", "g", "r", "dt"))
    r = simulate(s, dt)
    assert r.events == []
    # the sheet is faster than the contact point throughout: one regime
    assert len({seg.regime for seg in r.segments}) == 1
    f = r.final_state
    assert abs(f["dot(x)"] - mu * g * dt) < 1e-10
    assert abs(f["dot(phi)"] - 2 * mu * g * dt / r_) < 1e-9
    # the friction is µN, along +Ex (the contact tangent Ez × Ey is −Ex): F_paper = −µN
    assert abs(r["F_paper"][-1] + mu * r["N"][-1]) < 1e-12
    # the work done by the friction of the sheet is the energy gained
    assert r.energy_drift < 1e-9
    # the contact point of the cylinder stays slower than the sheet (the card's premise)
    assert np.all(r["dot(x)"] + r_ * r["dot(phi)"] < value(s, "V"))
