"""A rope or cable that goes slack moves free and re-tightens with a jerk (numeric/contacts/slack.py, jerk.py).

Checked against closed forms and impulse–momentum by hand: a yo-yo whose hand moves by y_H = A sin Ωt (the string
goes slack where T = (g + ÿ_H)/(1/m + r²/I) reaches zero, flies free on a parabola with constant spin, and jerks
taut where the free length, paid out by the drum as it turns, equals the distance from the hand), and a pendulum
bob on a cable swung so high that the cable goes slack (T = m v²/L + m g cos φ = 0) and jerks taut where its
parabola meets the circle of radius L.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad
from scipy.optimize import brentq

import rigidkin as rk
from rigidkin.model.ropes import Wrap
from rigidkin.numeric.simulate import simulate

M_, RR, r_, G, A_, W_ = 0.2, 0.05, 0.01, 9.81, 0.1, 15.0       # yo-yo: mass, disk radius, drum radius; hand
I_ = 0.5 * M_ * RR**2
Y0, TH0, WD0 = -0.5, 0.0, -50.0                                    # centre height, angle, spin at t = 0
VY0 = A_ * W_ + r_ * WD0                                           # the taut string: ẏ − r θ̇ = ẏ_H


def _yoyo(e=None):
    s = rk.System("yo-yo")
    m, R, r = s.parameter("m", "kg", value=M_), s.parameter("R", "m", value=RR), s.parameter("r", "m", value=r_)
    g, A = s.parameter("g", "m/s^2", value=G), s.parameter("A", "m", value=A_)
    W = s.parameter("Omega", "rad/s", value=W_)
    y = s.coordinate("y", "height of the centre", kind="length", initial=Y0, rate=VY0)
    th = s.coordinate("theta", "rotation of the yo-yo, counter-clockwise", initial=TH0, rate=WD0)
    H = s.point("H", offset=A * sp.sin(W * rk.t) * s.inertial.y)
    s.drive("hand", s.inertial, at=H)
    disk = s.body("yoyo", rk.shapes.Disk(m, R), frame=s.frame("D", angle=th),
                  at=s.point("C", offset=r * s.inertial.x + y * s.inertial.y))
    s.rope("string", [(H, "hand"), Wrap(disk, r, "ccw")], tensions=("T",))     # hangs down the drum's left side
    s.gravity(g)
    if e is not None:
        s.restitution("string", e)
    return s


def _taut(t):
    """The taut yo-yo by hand: m ÿ = T − m g, I θ̈ = −r T, ẏ − r θ̇ = ẏ_H give ÿ = (k/m)(g + ÿ_H) − g with
    k = 1/(1/m + r²/I), integrated twice from the start."""
    km = 1.0 / (1.0 + M_ * r_**2 / I_)
    vy = VY0 + (km - 1) * G * t + km * A_ * W_ * (math.cos(W_ * t) - 1)
    y = Y0 + VY0 * t + (km - 1) * G * t**2 / 2 + km * (A_ * math.sin(W_ * t) - A_ * W_ * t)
    hand, vhand = A_ * math.sin(W_ * t), A_ * W_ * math.cos(W_ * t)
    return y, vy, TH0 + (y - Y0 - hand) / r_, (vy - vhand) / r_


def _by_hand(e=0.0):
    """Slack instant, the state there, the re-tightening instant, and the state just after the jerk."""
    ts = math.asin(G / (A_ * W_**2)) / W_                # T = k (g − A Ω² sin Ωt) = 0
    ys, vs, ths, ws = _taut(ts)
    ls = A_ * math.sin(W_ * ts) - ys                     # free length where it goes slack

    def gap(t):                                          # ℓ − L: the drum pays out −r Δθ as it turns
        tau = t - ts
        y = ys + vs * tau - G * tau**2 / 2
        return ls - r_ * ws * tau - (A_ * math.sin(W_ * t) - y)

    grid = np.linspace(ts + 1e-4, ts + 1.0, 20001)
    vals = [gap(t) for t in grid]
    j = next(i for i in range(len(vals) - 1) if vals[i] > 0 >= vals[i + 1])
    tr = brentq(gap, grid[j], grid[j + 1], xtol=1e-15)
    vy_, w_ = vs - G * (tr - ts), ws
    vh = A_ * W_ * math.cos(W_ * tr)
    # impulse P up the string at the drum's left point: m Δẏ = P, I Δθ̇ = −r P, and the string's speed after:
    # ẏ⁺ − r θ̇⁺ − ẏ_H = −e (ẏ⁻ − r θ̇⁻ − ẏ_H)
    approach = vh - vy_ + r_ * w_
    P = (1 + e) * approach / (1 / M_ + r_**2 / I_)
    return dict(ts=ts, ys=ys, vs=vs, ths=ths, ws=ws, ls=ls, tr=tr, vy_before=vy_, w_before=w_, vh=vh, P=P,
                vy_after=vy_ + P / M_, w_after=w_ - r_ * P / I_, approach=approach)


@pytest.fixture(scope="module")
def yoyo_run():
    return simulate(_yoyo(), 0.44)


def test_yoyo_goes_slack_where_the_tension_reaches_zero(yoyo_run):
    h = _by_hand()
    res = yoyo_run
    assert res.stop_reason == "completed"
    slack = [e for e in res.events if e.kind == "slack"]
    assert slack and slack[0].name == "rope string goes slack (T = 0)"
    ev = slack[0]
    assert ev.t == pytest.approx(h["ts"], rel=1e-9)
    assert ev.state["y"] == pytest.approx(h["ys"], rel=1e-8)
    assert ev.state["dot(y)"] == pytest.approx(h["vs"], rel=1e-8)
    assert ev.state["dot(theta)"] == pytest.approx(h["ws"], rel=1e-8)
    assert "string slack" in ev.mode_after and f"free length {h['ls']:.6g}" in ev.detail


def test_yoyo_flies_free_on_a_parabola_with_constant_spin(yoyo_run):
    h = _by_hand()
    res = yoyo_run
    for frac in (0.25, 0.5, 0.9):
        tt = h["ts"] + frac * (h["tr"] - h["ts"])
        tau = tt - h["ts"]
        st = res.at(tt)
        assert st["y"] == pytest.approx(h["ys"] + h["vs"] * tau - G * tau**2 / 2, rel=1e-8, abs=1e-10)
        assert st["dot(y)"] == pytest.approx(h["vs"] - G * tau, rel=1e-8, abs=1e-10)
        assert st["dot(theta)"] == pytest.approx(h["ws"], rel=1e-9)
        assert st["theta"] == pytest.approx(h["ths"] + h["ws"] * tau, rel=1e-8)
    mid = np.searchsorted(res.t, h["ts"] + 0.5 * (h["tr"] - h["ts"]))
    assert res["T"][mid] == 0.0                       # no tension while slack


def test_yoyo_jerks_taut_by_impulse_momentum(yoyo_run):
    h = _by_hand()
    res = yoyo_run
    jerks = [e for e in res.events if e.kind == "tightens"]
    assert len(jerks) == 1
    ev = jerks[0]
    assert ev.t == pytest.approx(h["tr"], rel=1e-9)
    assert ev.name.startswith("rope string re-tightens (jerk), impulse T = ")
    num = ev.impact
    assert num["impulse"] == pytest.approx(h["P"], rel=1e-7) and num["impulse"] > 0
    assert ev.state["dot(y)"] == pytest.approx(h["vy_before"], rel=1e-8)
    assert ev.after["dot(y)"] == pytest.approx(h["vy_after"], rel=1e-7)
    assert ev.after["dot(theta)"] == pytest.approx(h["w_after"], rel=1e-7)
    assert num["velocity_jump"]["dot(y)"] == pytest.approx(h["P"] / M_, rel=1e-7)
    # e = 0: the string's speed after is zero; kinetic energy relative to the hand (which moves at v_H through
    # the instant) never increases: the hand's work P v_H minus what the jerk dissipates, ½ P × approach speed
    assert ev.after["dot(y)"] - r_ * ev.after["dot(theta)"] == pytest.approx(h["vh"], rel=1e-9)
    dT = 0.5 * M_ * (h["vy_after"]**2 - h["vy_before"]**2) + 0.5 * I_ * (h["w_after"]**2 - h["w_before"]**2)
    lost = 0.5 * h["P"] * h["approach"]
    assert num["energy_change"] == pytest.approx(dT, rel=1e-7)
    assert num["energy_dissipated"] == pytest.approx(lost, rel=1e-7) and lost > 0
    assert num["work_of_moving_ends"] == pytest.approx(h["P"] * h["vh"], rel=1e-7)
    rel_before = 0.5 * M_ * (h["vy_before"] - h["vh"])**2 + 0.5 * I_ * h["w_before"]**2
    rel_after = 0.5 * M_ * (h["vy_after"] - h["vh"])**2 + 0.5 * I_ * h["w_after"]**2
    assert rel_after <= rel_before and rel_before - rel_after == pytest.approx(lost, rel=1e-7)
    assert "slack" not in ev.mode_after and "slack" in ev.mode_before
    assert abs(res.energy_drift) < 1e-6                # E − W, with the hand's work and the jerk's change in W


def test_yoyo_events_in_the_json(yoyo_run):
    data = json.loads(yoyo_run.to_json())
    assert data["stop_reason"] == "completed"
    kinds = [e["kind"] for e in data["events"]]
    assert kinds[:2] == ["slack", "tightens"]
    jerk = data["events"][1]
    assert jerk["impact"]["impulse_name"] == "T" and "velocity_jump" in jerk["impact"]
    assert "goes slack" in data["events"][0]["name"] and "re-tightens (jerk)" in jerk["name"]


def test_a_string_with_restitution_rebounds_slack():
    """e = 0.5 (System.restitution): P = (1 + e) × approach/(1/m + r²/I), and the string leaves at e times the
    approach speed, so it stays slack."""
    h = _by_hand(0.5)
    res = simulate(_yoyo(0.5), h["tr"] + 1e-3)
    ev = next(e for e in res.events if e.kind == "tightens")
    assert ev.t == pytest.approx(h["tr"], rel=1e-9)
    assert ev.impact["impulse"] == pytest.approx(h["P"], rel=1e-7)
    assert ev.after["dot(y)"] - r_ * ev.after["dot(theta)"] - h["vh"] == pytest.approx(0.5 * h["approach"], rel=1e-7)
    assert "string slack" in ev.mode_after and "rebounds slack" in ev.detail
    assert res.stop_reason == "completed"


L_, MB, V0 = 1.0, 0.5, math.sqrt(3.2 * 9.81 * 1.0)        # cable pendulum: length, bob mass, speed at the bottom


def _pendulum():
    s = rk.System("bob on a string")
    m, L, g = s.parameter("m", "kg", value=MB), s.parameter("L", "m", value=L_), s.parameter("g", "m/s^2", value=G)
    rho = s.coordinate("rho", "distance of the bob from the pivot", kind="length", initial=L_)
    phi = s.coordinate("phi", "angle of the string from the downward vertical", initial=0.0, rate=V0 / L_)
    F = s.inertial
    B = s.point("B", offset=rho * (sp.sin(phi) * F.x - sp.cos(phi) * F.y))
    s.body("bob", rk.shapes.PointMass(m), frame=F, at=B)
    s.cable("string", [s.origin, B], L, tension_name="T")
    s.gravity(g)
    return s


def _pendulum_by_hand():
    """T = m v²/L + m g cos φ = 0 with v² = v0² − 2gL(1 − cos φ): cos φ_s = (2gL − v0²)/(3gL) = −0.4; the time
    there t_s = ∫ L dφ / v(φ); a parabola from there until x² + y² = L²: the radial speed v_r there (outward)."""
    cs = (2 * G * L_ - V0**2) / (3 * G * L_)
    phis = math.acos(cs)
    ts = quad(lambda f: L_ / math.sqrt(V0**2 - 2 * G * L_ * (1 - math.cos(f))), 0, phis, epsabs=1e-13)[0]
    vs = math.sqrt(-G * L_ * cs)
    x0, y0 = L_ * math.sin(phis), -L_ * math.cos(phis)
    vx, vy = vs * math.cos(phis), vs * math.sin(phis)

    def gap(tau):
        return L_**2 - (x0 + vx * tau)**2 - (y0 + vy * tau - G * tau**2 / 2)**2

    grid = np.linspace(1e-6, 2.0, 20001)
    vals = [gap(tt) for tt in grid]
    j = next(i for i in range(len(vals) - 1) if vals[i] > 0 >= vals[i + 1])
    tau = brentq(gap, grid[j], grid[j + 1], xtol=1e-15)
    x, y = x0 + vx * tau, y0 + vy * tau - G * tau**2 / 2
    v = np.array([vx, vy - G * tau])
    n = np.array([x, y]) / L_                                # outward along the string
    vr = float(v @ n)
    phir = math.atan2(x, -y)
    vt = float((v - vr * n) @ np.array([math.cos(phir), math.sin(phir)]))
    return dict(ts=ts, phis=phis, vs=vs, tr=ts + tau, phir=phir, vr=vr, vt=vt)


def test_pendulum_string_goes_slack_and_jerks_taut():
    """The jerk (e = 0) takes the radial velocity away: impulse m v_r, the tangential velocity kept, kinetic
    energy lost ½ m v_r²."""
    h = _pendulum_by_hand()
    res = simulate(_pendulum(), 1.5)
    assert res.stop_reason == "completed"
    slack = next(e for e in res.events if e.kind == "slack")
    assert slack.t == pytest.approx(h["ts"], rel=1e-8)
    assert slack.state["phi"] == pytest.approx(h["phis"], rel=1e-8)
    assert slack.state["dot(phi)"] * L_ == pytest.approx(h["vs"], rel=1e-8)
    jerk = next(e for e in res.events if e.kind == "tightens")
    assert jerk.t == pytest.approx(h["tr"], rel=1e-9)
    assert h["vr"] > 0 and jerk.state["dot(rho)"] == pytest.approx(h["vr"], rel=1e-7)
    assert math.remainder(jerk.state["phi"] - h["phir"], 2 * math.pi) == pytest.approx(0.0, abs=1e-8)
    assert jerk.impact["impulse"] == pytest.approx(MB * h["vr"], rel=1e-7)
    assert jerk.after["dot(rho)"] == pytest.approx(0.0, abs=1e-9)
    assert jerk.after["dot(phi)"] * L_ == pytest.approx(h["vt"], rel=1e-7)
    assert jerk.impact["energy_change"] == pytest.approx(-0.5 * MB * h["vr"]**2, rel=1e-7)
    assert jerk.impact["energy_change"] < 0 and jerk.impact["work_of_moving_ends"] == 0.0
    assert abs(res.energy_drift) < 1e-6


def test_a_cable_with_restitution_rebounds_and_stays_slack_to_the_end():
    """System.restitution("string", 0.3): the radial speed after is −e v_r, the impulse m (1 + e) v_r; the
    cable stays slack to the end and the run completes."""
    system = _pendulum()
    system.restitution("string", 0.3)
    assert system.restitutions == {"string": 0.3}
    h = _pendulum_by_hand()
    res = simulate(system, h["tr"] + 0.01)
    assert res.stop_reason == "completed"
    assert [e.kind for e in res.events] == ["slack", "tightens"]
    jerk = res.events[1]
    assert jerk.t == pytest.approx(h["tr"], rel=1e-9)
    assert jerk.impact["impulse"] == pytest.approx(MB * 1.3 * h["vr"], rel=1e-7)
    assert jerk.after["dot(rho)"] == pytest.approx(-0.3 * h["vr"], rel=1e-7)
    assert "rebounds slack" in jerk.detail and "string slack" in jerk.mode_after
    assert res.final_state["rho"] < L_
    with pytest.raises(rk.ModelError, match="not a contact, rope or cable"):
        system.restitution("bob", 0.3)


def test_a_string_the_coordinates_keep_at_its_length_stops_where_it_goes_slack():
    """With the bob at ρ = L fixed by the coordinates (φ alone) nothing lets the string go slack: a stop, not a
    pendulum that goes on as if the string could push."""
    s = rk.System("bob on a rigid string")
    m, L, g = s.parameter("m", "kg", value=MB), s.parameter("L", "m", value=L_), s.parameter("g", "m/s^2", value=G)
    phi = s.coordinate("phi", "angle of the string from the downward vertical", initial=0.0, rate=V0 / L_)
    B = s.point("B", offset=L * (sp.sin(phi) * s.inertial.x - sp.cos(phi) * s.inertial.y))
    s.body("bob", rk.shapes.PointMass(m), frame=s.inertial, at=B)
    s.cable("string", [s.origin, B], L, tension_name="T")
    s.gravity(g)
    res = simulate(s, 1.5)
    assert res.stop_reason == "slack" and "keep cable string at its length" in res.message
    assert res.t_final == pytest.approx(_pendulum_by_hand()["ts"], rel=1e-8)


def test_a_yoyo_that_stays_slack_to_the_end_completes():
    h = _by_hand()
    res = simulate(_yoyo(), 0.5 * (h["ts"] + h["tr"]))
    assert res.stop_reason == "completed" and [e.kind for e in res.events] == ["slack"]
    assert "string slack" in res.segments[-1].description


def test_a_rope_over_pulleys_still_stops_where_it_goes_slack():
    """Two segments over a pulley with inertia: which one takes up the slack is not followed (stop "slack")."""
    s = rk.System("atwood with a motor")
    m1, m2, M = s.parameter("m1", "kg", value=3), s.parameter("m2", "kg", value=1), s.parameter("M", "kg", value=2)
    R, g, c = s.parameter("R", "m", value=0.1), s.parameter("g", "m/s^2", value=9.81), \
        s.parameter("c", "N*m/s", value=2.0)
    y1 = s.coordinate("y1", "depth of block 1", kind="length", initial=1.0, rate=0)
    y2 = s.coordinate("y2", "depth of block 2", kind="length", initial=1.0)
    phi = s.coordinate("phi", "pulley rotation, counter-clockwise")
    pulley = s.body("pulley", rk.shapes.Disk(M, R), frame=s.frame("P", angle=phi), at=s.origin)
    ends = []
    for nm, x, yq, mq in (("A", -R, y1, m1), ("B", R, y2, m2)):
        P = s.point(nm, offset=x * s.inertial.x - yq * s.inertial.y)
        s.body(f"block_{nm}", rk.shapes.PointMass(mq), frame=s.inertial, at=P)
        ends.append(P)
    s.pin("O", s.origin, pulley)
    s.torque("motor", pulley, c * rk.t * s.inertial.z)
    s.rope("rope", [ends[0], Wrap(pulley, R, "cw"), ends[1]], tensions=("T1", "T2"))
    s.gravity(g)
    res = simulate(s, 2.0)
    assert res.stop_reason == "slack" and "runs over pulleys" in res.message


@pytest.mark.slow
def test_a_string_that_would_push_at_the_start_starts_slack():
    """Hand y_H = A cos Ωt from rest: taut, T = k (g − A Ω²) < 0 at t = 0, so the string starts slack; the yo-yo
    falls from rest, y = y0 − g t²/2 (no spin), until A cos Ωt − y = ℓ0 = A − y0; then the jerk."""
    s = rk.System("yo-yo")
    m, R, r = s.parameter("m", "kg", value=M_), s.parameter("R", "m", value=RR), s.parameter("r", "m", value=r_)
    g, A = s.parameter("g", "m/s^2", value=G), s.parameter("A", "m", value=A_)
    W = s.parameter("Omega", "rad/s", value=W_)
    y = s.coordinate("y", "height of the centre", kind="length", initial=Y0, rate=0.0)
    th = s.coordinate("theta", "rotation of the yo-yo, counter-clockwise", initial=0.0, rate=0.0)
    H = s.point("H", offset=A * sp.cos(W * rk.t) * s.inertial.y)
    s.drive("hand", s.inertial, at=H)
    disk = s.body("yoyo", rk.shapes.Disk(m, R), frame=s.frame("D", angle=th),
                  at=s.point("C", offset=r * s.inertial.x + y * s.inertial.y))
    s.rope("string", [(H, "hand"), Wrap(disk, r, "ccw")], tensions=("T",))
    s.gravity(g)
    res = simulate(s, 0.3)
    assert res.stop_reason == "completed" and "string slack" in res.segments[0].description

    def gap(tt):
        return (A_ - Y0) - (A_ * math.cos(W_ * tt) - (Y0 - G * tt**2 / 2))

    grid = np.linspace(1e-4, 0.3, 3001)
    j = next(i for i in range(len(grid) - 1) if gap(grid[i]) > 0 >= gap(grid[i + 1]))
    tr = brentq(gap, grid[j], grid[j + 1], xtol=1e-15)
    ev = res.events[0]
    assert ev.kind == "tightens" and ev.t == pytest.approx(tr, rel=1e-9)
    vy, vh = -G * tr, -A_ * W_ * math.sin(W_ * tr)
    P = (vh - vy) / (1 / M_ + r_**2 / I_)
    assert ev.impact["impulse"] == pytest.approx(P, rel=1e-7)
    assert ev.after["dot(y)"] == pytest.approx(vy + P / M_, rel=1e-7)
    assert ev.after["dot(theta)"] == pytest.approx(-r_ * P / I_, rel=1e-7)


def test_a_jerk_while_a_contact_touches_is_refused_with_its_reason():
    """A block on a smooth floor tied to the wall by a cable of length L and pushed by F = F1 − F0 cos ωt toward
    the wall: slack from the start, x = L + (F1 t²/2 − F0 (1 − cos ωt)/ω²)/m, back at x = L with speed; the jerk
    with the floor contact closed is not modelled: the run stops there, saying so."""
    s = rk.System("tethered block")
    m, L = s.parameter("m", "kg", value=1.0), s.parameter("L", "m", value=1.0)
    F0, F1 = s.parameter("F0", "N", value=2.0), s.parameter("F1", "N", value=0.5)
    w = s.parameter("w", "rad/s", value=4.0)
    g = s.parameter("g", "m/s^2", value=G)
    x = s.coordinate("x", "distance from the wall", kind="length", initial=1.0)
    y = s.coordinate("y", "height above the floor", kind="length", initial=0.0)
    B = s.point("B", offset=x * s.inertial.x + y * s.inertial.y)
    block = s.body("block", rk.shapes.PointMass(m), frame=s.inertial, at=B)
    s.contact("floor", block, s.line(s.origin, s.inertial.y), centre=B)
    s.cable("tether", [s.origin, B], L, tension_name="T")
    s.force("push", B, (F1 - F0 * sp.cos(w * rk.t)) * s.inertial.x)
    s.gravity(g)
    res = simulate(s, 3.0)

    def back(tt):
        return 0.5 * tt**2 / 2 - 2.0 * (1 - math.cos(4.0 * tt)) / 4.0**2        # (x − L) m

    grid = np.linspace(1e-3, 3.0, 3001)
    j = next(i for i in range(len(grid) - 1) if back(grid[i]) < 0 <= back(grid[i + 1]))
    assert res.stop_reason == "jerk-with-contacts" and "floor" in res.message
    assert res.t_final == pytest.approx(brentq(back, grid[j], grid[j + 1], xtol=1e-15), rel=1e-8)


@pytest.mark.slow
def test_a_swinging_yoyo_retightens_where_the_geometry_says_and_jerks_by_impulse_momentum():
    """The centre free in x and y (the string swings). From the state where it goes slack: a parabola with
    constant spin; the string, fixed to the drum where it left it (the material point P_s), is taut again
    when L + r × (the counter-clockwise angle from the tangent point Q to P_s) equals the free length L_s (the
    tangent point from the hand by hand: |Q − C| = r, (Q − H) ⟂ (Q − C), the rope going on counter-clockwise);
    the jerk: m Δv = −P e, I Δω = ((Q − C) × (−P e))·Ez, and (v⁺ + ω⁺ Ez × (Q − C))·e = v_H·e."""
    s = rk.System("swinging yo-yo")
    m, R, r = s.parameter("m", "kg", value=M_), s.parameter("R", "m", value=RR), s.parameter("r", "m", value=r_)
    g, A = s.parameter("g", "m/s^2", value=G), s.parameter("A", "m", value=A_)
    W = s.parameter("Omega", "rad/s", value=W_)
    x = s.coordinate("x", "abscissa of the centre", kind="length", initial=0.05, rate=0.0)
    y = s.coordinate("y", "height of the centre", kind="length", initial=Y0, rate=1.0)
    th = s.coordinate("theta", "rotation of the yo-yo, counter-clockwise", initial=0.0)
    H = s.point("H", offset=A * sp.sin(W * rk.t) * s.inertial.y)
    s.drive("hand", s.inertial, at=H)
    disk = s.body("yoyo", rk.shapes.Disk(m, R), frame=s.frame("D", angle=th),
                  at=s.point("C", offset=x * s.inertial.x + y * s.inertial.y))
    s.rope("string", [(H, "hand"), Wrap(disk, r, "ccw")], tensions=("T",))
    s.gravity(g)
    res = simulate(s, 0.4)
    assert res.stop_reason == "completed"
    slack, jerk = res.events_of("slack")[0], res.events_of("tightens")[0]
    st, ts = slack.state, slack.t

    def free(tt):                                   # parabola, constant spin
        tau = tt - ts
        return (np.array([st["x"] + st["dot(x)"] * tau, st["y"] + st["dot(y)"] * tau - G * tau**2 / 2]),
                st["theta"] + st["dot(theta)"] * tau)

    def tangent(tt, c):                             # (Q, its angle about C, L) from the hand at tt
        h = np.array([0.0, A_ * math.sin(W_ * tt)])
        d = h - c
        beta, half = math.atan2(d[1], d[0]), math.acos(r_ / np.linalg.norm(d))
        for alpha in (beta + half, beta - half):
            q = c + r_ * np.array([math.cos(alpha), math.sin(alpha)])
            if (q - h) @ np.array([-math.sin(alpha), math.cos(alpha)]) > 0:     # goes on counter-clockwise
                return q, alpha, float(np.linalg.norm(q - h))
        raise AssertionError("no tangent")

    c_s, th_s = free(ts)
    _, alpha_s, L_s = tangent(ts, c_s)

    def gap(tt):
        c, th_ = free(tt)
        _, alpha, L = tangent(tt, c)
        turn = (th_ - th_s) - math.remainder(alpha - alpha_s, 2 * math.pi)
        return L_s - (L + r_ * turn)

    grid = np.linspace(ts + 1e-4, 0.4, 4001)
    j = next(i for i in range(len(grid) - 1) if gap(grid[i]) > 0 >= gap(grid[i + 1]))
    tr = brentq(gap, grid[j], grid[j + 1], xtol=1e-15)
    assert jerk.t == pytest.approx(tr, rel=1e-8)
    mid = 0.5 * (ts + tr)
    c_mid, th_mid = free(mid)
    assert [res.at(mid)["x"], res.at(mid)["y"], res.at(mid)["theta"]] == pytest.approx([*c_mid, th_mid], rel=1e-8)
    b = jerk.state
    c, _ = free(jerk.t)
    q, _, L = tangent(jerk.t, c)
    e = (q - np.array([0.0, A_ * math.sin(W_ * jerk.t)])) / L
    v, w = np.array([b["dot(x)"], b["dot(y)"]]), b["dot(theta)"]
    arm = q - c
    vh = np.array([0.0, A_ * W_ * math.cos(W_ * jerk.t)])

    def rim_along(v_, w_):
        return float((v_ + w_ * np.array([-arm[1], arm[0]])) @ e)

    cross = arm[0] * (-e[1]) - arm[1] * (-e[0])                  # ((Q − C) × (−e))·Ez per unit impulse
    dv_dP, dw_dP = -e / M_, cross / I_
    P = (vh @ e - rim_along(v, w)) / (rim_along(dv_dP, dw_dP))
    assert P > 0 and jerk.impact["impulse"] == pytest.approx(P, rel=1e-6)
    assert [jerk.after["dot(x)"], jerk.after["dot(y)"], jerk.after["dot(theta)"]] == pytest.approx(
        [*(v + P * dv_dP), w + P * dw_dP], rel=1e-6, abs=1e-9)
    rel_before = 0.5 * M_ * float((v - vh) @ (v - vh)) + 0.5 * I_ * w**2
    v2, w2 = v + P * dv_dP, w + P * dw_dP
    assert 0.5 * M_ * float((v2 - vh) @ (v2 - vh)) + 0.5 * I_ * w2**2 < rel_before
