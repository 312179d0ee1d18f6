"""Contacts and friction as one complementarity problem, checked against closed forms and hand
impulse–momentum (never against the engine's own output)."""

import math

import numpy as np
import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.io.problem import parse_problem
from rigidkin.numeric import simulate

G = 9.81


def incline(beta, mu_s, mu_k=None, m=2.0):
    """A block (a point mass) on a rough incline: x down the slope, y off it (so the contact can open)."""
    s = rk.System("block-on-incline")
    m_ = s.parameter("m", "kg", value=m)
    g = s.parameter("g", "m/s^2", value=G)
    b = s.parameter("beta", "rad", value=beta)
    ms = s.parameter("mu_s", "", value=mu_s)
    mk = s.parameter("mu_k", "", value=mu_s if mu_k is None else mu_k)
    x = s.coordinate("x", "distance of the block down the slope", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "distance of the block off the slope", kind="length", initial=0, rate=0)
    I = s.frame("I", angle=-b, basis=("es", "en", "ez"))
    G_ = s.point("G", offset=x * I.es + y * I.en)
    blk = s.body("block", rk.shapes.PointMass(m_), frame=I, at=G_)
    s.contact("ground", blk, s.line(s.origin, I.en), centre=G_, friction={"static": ms, "kinetic": mk},
              normal_name="N", friction_name="F")
    s.gravity(g)
    return s


INCLINE_TOML = """
title = "Block on a rough incline"
[parameters]
m = { unit = "kg", value = 2 }
g = { unit = "m/s^2", value = 9.81 }
beta = { unit = "rad", value = "30 deg" }
mu_s = { unit = "", value = 0.6 }
mu_k = { unit = "", value = 0.4 }
[coordinates]
x = { sense = "distance of the block down the slope", kind = "length", initial = 0, rate = 0 }
y = { sense = "distance of the block off the slope", kind = "length", initial = 0, rate = 0 }
[frames]
I = { angle = "-beta", basis = ["es", "en", "ez"] }
[points]
G = { offset = "x*es + y*en" }
[bodies]
block = { shape = "point_mass", mass = "m", frame = "I", at = "G" }
[constraints.ground]
type = "contact"
body = "block"
surface = { type = "line", point = "O", normal = "en" }
friction = { static = "mu_s", kinetic = "mu_k" }
normal_name = "N"
friction_name = "F"
[loads]
gravity = { type = "gravity", g = "g" }
"""


# (a) a mode with no degree of freedom is an ordinary mode ------------------------------------------
def test_sticking_block_is_a_mode_at_rest_with_reactions_from_statics():
    s = incline(0.4, 0.6, 0.4)
    sol = s.solve(mode={"ground": "stick"})
    assert sol.coordinates == ()                          # no degree of freedom: q̇ = 0, q̈ = 0
    m, beta = 2.0, 0.4
    vals = {"m": m, "g": G, "beta": beta, "mu_s": 0.6, "mu_k": 0.4}
    subs = {sym: vals[str(sym)] for sym in sol.reactions["N"].free_symbols | sol.reactions["F"].free_symbols}
    # statics across and along the slope: N = m g cos β, F = m g sin β (F positive up the slope, along −es)
    assert float(sol.reactions["N"].subs(subs)) == pytest.approx(m * G * math.cos(beta), rel=1e-14)
    assert float(sol.reactions["F"].subs(subs)) == pytest.approx(m * G * math.sin(beta), rel=1e-14)
    # validity: sticking holds while |F| ≤ µs N (the static coefficient, not the kinetic one)
    conds = [c for c in sol.regimes[0].validity if "within" in c.label]
    assert conds and all("µs" in c.label for c in conds)
    assert all(c.expr.has(s.parameter_info["mu_s"].symbol) and not c.expr.has(s.parameter_info["mu_k"].symbol)
               for c in conds)


# (b) static and kinetic friction: the block released from rest -------------------------------------
@pytest.mark.parametrize("beta,mu_s,mu_k", [(0.4, 0.6, 0.4), (math.radians(30), 0.6, 0.4), (0.5, 0.9, 0.2)])
def test_block_released_on_incline_stays_when_tan_beta_within_mu_s(beta, mu_s, mu_k):
    assert math.tan(beta) <= mu_s
    res = simulate(incline(beta, mu_s, mu_k), 1.5)
    assert res.reached_end and res.stop_reason == "completed"
    assert res.segments[0].mode == {"ground": "stick"} and not res.events
    assert np.max(np.abs(res["x"])) == 0.0 and np.max(np.abs(res["dot(x)"])) == 0.0
    assert np.allclose(res["N"], 2.0 * G * math.cos(beta), rtol=1e-13)


def test_block_stays_exactly_at_the_limit_tan_beta_equal_to_mu_s():
    beta = 0.5
    res = simulate(incline(beta, math.tan(beta), 0.3), 2.0)
    assert res.reached_end and not res.events
    assert res.segments[0].mode == {"ground": "stick"}
    assert np.max(np.abs(res["x"])) == 0.0


@pytest.mark.parametrize("beta,mu_s,mu_k", [(math.radians(30), 0.5, 0.4), (0.7, 0.6, 0.1), (0.5, 0.5, 0.5)])
def test_block_released_on_incline_slides_with_kinetic_friction(beta, mu_s, mu_k):
    assert math.tan(beta) > mu_s
    res = simulate(incline(beta, mu_s, mu_k), 1.0)
    assert res.reached_end and not res.events
    assert res.segments[0].mode == {"ground": "slip"}
    a = G * (math.sin(beta) - mu_k * math.cos(beta))       # the closed form
    t = res.t
    assert np.max(np.abs(res["x"] - a * t**2 / 2)) < 1e-10
    assert np.max(np.abs(res["dot(x)"] - a * t)) < 1e-10


def test_static_and_kinetic_friction_in_a_problem_file():
    system, _ = parse_problem(INCLINE_TOML, "incline.toml")
    fr = system.constraints["ground"].friction
    assert str(fr.static) == "mu_s" and str(fr.kinetic) == "mu_k"
    stays = simulate(system, 1.0)                          # tan 30° = 0.577 ≤ µs = 0.6
    assert stays.reached_end and np.max(np.abs(stays["x"])) == 0.0
    slides = simulate(system, 1.0, params={"mu_s": 0.55})  # tan 30° > µs: slides with µk = 0.4
    a = G * (0.5 - 0.4 * math.cos(math.radians(30)))
    assert slides["x"][-1] == pytest.approx(a / 2, rel=1e-10)


def test_a_single_mu_keeps_meaning_both_and_mu_s_below_mu_k_is_refused():
    fr = rk.Coulomb(0.3)
    assert fr.static == fr.kinetic == 0.3
    with pytest.raises(rk.ModelError, match="µs"):
        rk.Coulomb(0.3, 0.2)
    bad = INCLINE_TOML.replace('friction = { static = "mu_s", kinetic = "mu_k" }', 'friction = { static = 0.2, '
                               'kinetic = 0.4 }')
    with pytest.raises(rk.RigidkinError, match="static coefficient"):
        parse_problem(bad, "incline.toml")
    with pytest.raises(rk.InputError, match="smaller than its kinetic"):     # parameters: checked with values
        simulate(incline(0.3, 0.2, 0.4), 0.1)


# (e) impacts: one impulse problem over every contact closed or closing -------------------------------
def rod(mu, theta0, drop, supports=None, m=1.5, length=1.2):
    """A rod (centre x, y; angle θ from the floor, counter-clockwise) above a rough floor y = 0.

    Contacts at the ends A (−l/2 along the rod) and B (+l/2), or at ``supports`` = (a, b): the rod's
    points at −a and +b from its centre."""
    s = rk.System("rod-drop")
    m_ = s.parameter("m", "kg", value=m)
    l_ = s.parameter("l", "m", value=length)
    g = s.parameter("g", "m/s^2", value=G)
    mu_ = s.parameter("mu", "", value=mu)
    a, b = supports or (length / 2, length / 2)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=a * math.sin(theta0) + drop, rate=0)
    th = s.coordinate("theta", "angle of the rod from the floor, counter-clockwise", initial=theta0, rate=0)
    R = s.frame("R", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    body = s.body("rod", rk.shapes.SlenderRod(m_, l_, axis="x"), frame=R, at=Gp)
    A = s.point("A", Gp, -a * R.x, body=body)
    B = s.point("B", Gp, b * R.x, body=body)
    floor = s.line(s.origin, s.inertial.y)
    s.contact("A", body, floor, centre=A, friction=mu_, normal_name="N_A", friction_name="F_A")
    s.contact("B", body, floor, centre=B, friction=mu_, normal_name="N_B", friction_name="F_B")
    s.gravity(g)
    return s


def hand_impact(m, I, points, u0, e, mu):
    """Impulse–momentum by hand for a planar body (u = (vx, vy, ω)) striking the floor at ``points``
    (offsets (rx, ry) from the centre): every combination of stick / slide ± per point, the one whose
    impulses push, stay within the friction cone and slide against the slip."""
    import itertools

    vx0, vy0, w0 = u0
    sols = []
    for states in itertools.product(("stick", 1, -1), repeat=len(points)):
        # unknowns: vx, vy, ω, then (Pn, Pt) per point
        k = 3 + 2 * len(points)
        A, b = np.zeros((k, k)), np.zeros(k)
        A[0, 0], A[1, 1], A[2, 2] = m, m, I
        b[:3] = m * vx0, m * vy0, I * w0
        row = 3
        for i, ((rx, ry), st) in enumerate(zip(points, states)):
            pn, pt = 3 + 2 * i, 4 + 2 * i
            A[0, pt] -= 1                               # m Δvx = Σ Pt
            A[1, pn] -= 1                               # m Δvy = Σ Pn
            A[2, pn] -= rx                              # I Δω = Σ (rx Pn − ry Pt)
            A[2, pt] += ry
            A[row, 1], A[row, 2] = 1, rx                # v_Py after = −e v_Py before
            b[row] = -e * (vy0 + w0 * rx)
            row += 1
            if st == "stick":
                A[row, 0], A[row, 2] = 1, -ry           # v_Px after = 0
            else:
                A[row, pt], A[row, pn] = 1, st * mu     # Pt = −σ µ Pn
            row += 1
        x = np.linalg.lstsq(A, b, rcond=None)[0]
        ok = np.allclose(A @ x, b, atol=1e-12)
        for i, ((_rx, ry), st) in enumerate(zip(points, states)):
            pn, pt = x[3 + 2 * i], x[4 + 2 * i]
            slip = x[0] - x[2] * ry
            ok &= pn >= -1e-12
            ok &= abs(pt) <= mu * pn + 1e-12 if st == "stick" else st * slip >= -1e-12
        if ok:
            sols.append(x[:3])
    assert sols, "no hand solution"
    return sols[0]


@pytest.mark.slow
@pytest.mark.parametrize("mu,e", [(0.8, 0.0), (0.1, 0.0), (0.8, 0.5)])
def test_rod_dropped_at_an_angle_onto_a_rough_floor(mu, e):
    m, length, theta0, drop = 1.5, 1.2, math.radians(30), 0.3
    res = simulate(rod(mu, theta0, drop, m=m, length=length), math.sqrt(2 * drop / G) + 0.01, restitution=e)
    ev = res.events[0]
    assert ev.kind == "impact" and ev.contact == "A"
    t_hit = math.sqrt(2 * drop / G)
    assert ev.t == pytest.approx(t_hit, abs=1e-10)
    v0 = G * t_hit
    assert ev.state["dot(y)"] == pytest.approx(-v0, abs=1e-9)
    a = length / 2
    I = m * length**2 / 12
    rx, ry = -a * math.cos(theta0), -a * math.sin(theta0)
    vx, vy, w = hand_impact(m, I, [(rx, ry)], (0.0, -v0, 0.0), e, mu)
    assert ev.after["dot(x)"] == pytest.approx(vx, abs=1e-9)
    assert ev.after["dot(y)"] == pytest.approx(vy, abs=1e-9)
    assert ev.after["dot(theta)"] == pytest.approx(w, abs=1e-9)
    T = lambda s_: 0.5 * m * (s_["dot(x)"]**2 + s_["dot(y)"]**2) + 0.5 * I * s_["dot(theta)"]**2  # noqa: E731
    assert T(ev.after) <= T(ev.state)


@pytest.mark.slow
@pytest.mark.parametrize("e", [0.0, 0.5])
def test_rod_falling_flat_onto_two_supports_takes_both_impulses_at_once(e):
    m, length, drop, (a, b) = 1.5, 1.2, 0.2, (0.5, 0.2)
    res = simulate(rod(0.5, 0.0, drop, supports=(a, b), m=m, length=length), math.sqrt(2 * drop / G) + 0.01,
                   restitution=e)
    ev = res.events[0]
    assert ev.kind == "impact"
    v0 = math.sqrt(2 * G * drop)
    # by hand: both supports stop (or reverse by e) together, so ω⁺ = 0, v⁺ = e v0, and the impulses
    # split as the lever rule says: P_A = m(1+e)v0·b/(a+b), P_B = m(1+e)v0·a/(a+b)
    assert ev.after["dot(theta)"] == pytest.approx(0.0, abs=1e-9)
    assert ev.after["dot(y)"] == pytest.approx(e * v0, abs=1e-9)
    assert "N_A = " in ev.detail and "N_B = " in ev.detail
    imp = dict(part.split(" = ") for part in ev.detail.replace("impulse ", "").split(", ") if " = " in part)
    assert float(imp["N_A"]) == pytest.approx(m * (1 + e) * v0 * b / (a + b), rel=1e-5)    # 6 digits printed
    assert float(imp["N_B"]) == pytest.approx(m * (1 + e) * v0 * a / (a + b), rel=1e-5)
    assert res.energy["T"][res.t > ev.t][0] <= res.energy["T"][res.t < ev.t][-1] + 1e-12


# (c) the contact problem over all contacts: Painlevé's paradox is reported, not guessed ----------------
@pytest.mark.slow
def test_painleve_rod_reported_with_the_critical_coefficient():
    from rigidkin.numeric.contacts.contact_modes import ContactParadox

    # a rod (half-length a) leaning at tan θ = 2 with its lower end sliding away from its centre:
    # N = m g / (1 + 3cos²θ − 3µ sinθ cosθ) by hand, which changes sign through ∞ at µ* = 4/3
    theta = math.atan(2.0)
    m, length = 1.5, 1.2
    s = rod(2.0, theta, 0.0, m=m, length=length)
    with pytest.raises(ContactParadox, match="no solution") as err:
        simulate(s, 0.05, initial_state={"dot(x)": -1.0}, raise_on_stop=True)
    msg = str(err.value)
    mu_star = (1 + 3 * math.cos(theta)**2) / (3 * math.sin(theta) * math.cos(theta))
    assert mu_star == pytest.approx(4 / 3)
    assert f"µ* = {mu_star:.6g}" in msg
    N = m * G / (1 + 3 * math.cos(theta)**2 - 3 * 2.0 * math.sin(theta) * math.cos(theta))
    assert f"would be {N:.4g}" in msg
    assert err.value.stop_reason == "no-consistent-mode"
    # below the critical coefficient the same start slides with A closed and N > 0
    ok = simulate(rod(1.0, theta, 0.0, m=m, length=length), 0.01, initial_state={"dot(x)": -1.0})
    assert ok.segments[0].mode["A"] == "slip" and ok["N_A"][0] == pytest.approx(
        m * G / (1 + 3 * math.cos(theta)**2 - 3 * math.sin(theta) * math.cos(theta)), rel=1e-9)


# (d) stick–slip: a block on a belt, a spring to the wall, µs > µk ----------------------------------------
def belt(m=1.0, k=10.0, v=0.5, mu_s=0.6, mu_k=0.4):
    s = rk.System("stick-slip")
    m_ = s.parameter("m", "kg", value=m)
    k_ = s.parameter("k", "N/m", value=k)
    V = s.parameter("V", "m/s", value=v)
    g = s.parameter("g", "m/s^2", value=G)
    ms = s.parameter("mu_s", "", value=mu_s)
    mk = s.parameter("mu_k", "", value=mu_k)
    x = s.coordinate("x", "stretch of the spring", kind="length", initial=0, rate=0)
    F = s.inertial
    P = s.point("P", s.origin, x * F.x)
    S = s.point("S", s.origin, V * rk.t * F.x, description="a point of the belt")
    blk = s.body("block", rk.shapes.PointMass(m_), frame=F, at=P)
    s.contact("belt", blk, s.line(S, F.y, name="belt"), friction={"static": ms, "kinetic": mk},
              normal_name="N", friction_name="F")
    s.spring("spring", P, s.origin, k_, 0, body_a=blk)
    s.gravity(g)
    return s


@pytest.mark.slow
@pytest.mark.parametrize("cycles", [60, 1000])
def test_stick_slip_limit_cycle_against_the_closed_form(cycles):
    m, k, v, mu_s, mu_k = 1.0, 10.0, 0.5, 0.6, 0.4
    w = math.sqrt(k / m)
    x_s, x_k = mu_s * m * G / k, mu_k * m * G / k        # slip starts at k x = µs m g; slides about x_k
    d = x_s - x_k
    stick = 2 * d / v                                    # carried from 2 x_k − x_s to x_s at the belt speed
    alpha = math.atan2(v / w, d)
    slip = (math.pi + 2 * alpha) / w                     # from x_s back to 2 x_k − x_s, where ẋ = v again
    t_first = math.asin(v / (x_k * w)) / w               # from rest: slides until ẋ reaches v
    t_end = t_first + cycles * (stick + slip) - slip / 2
    res = simulate(belt(m, k, v, mu_s, mu_k), t_end, max_events=4 * cycles, n_points=201)
    assert res.reached_end
    ev = res.events
    assert [e.kind for e in ev] == ["sticks", "slips"] * cycles          # no chatter: two events a cycle
    assert ev[0].t == pytest.approx(t_first, abs=1e-9)
    ts = np.array([e.t for e in ev])
    sticks, slips = ts[1::2] - ts[0::2], ts[2::2] - ts[1:-1:2]
    x1 = x_k * (1 - math.cos(w * t_first))              # where the first stick begins
    assert sticks[0] == pytest.approx((x_s - x1) / v, abs=1e-8)
    assert np.max(np.abs(sticks[1:] - stick)) < 1e-8    # then the limit cycle, every cycle alike
    assert np.max(np.abs(slips - slip)) < 1e-8
    assert all(e.state["x"] == pytest.approx(x_s, abs=1e-9) for e in ev[1::2])
    assert all(e.state["x"] == pytest.approx(2 * x_k - x_s, abs=1e-9) for e in ev[2::2])


@pytest.mark.slow
def test_identical_runs_give_identical_events_bit_for_bit():
    s = belt()
    runs = [simulate(s, 6.0, n_points=11) for _ in range(20)]
    ref = [(e.t, e.kind, tuple(e.state.values()), tuple(e.after.values())) for e in runs[0].events]
    assert len(ref) >= 5
    for r in runs[1:]:
        assert [(e.t, e.kind, tuple(e.state.values()), tuple(e.after.values())) for e in r.events] == ref
    fresh = simulate(belt(), 6.0, n_points=11)          # a system built again gives the same too
    assert [(e.t, e.kind, tuple(e.state.values())) for e in fresh.events] == [r[:3] for r in ref]


def test_block_sliding_up_a_rough_incline_comes_to_rest_and_sticks():
    # thrown up the slope with µs ≥ tan β: it stops once and stays (no chatter, one event)
    beta, mu_s, mu_k, v0 = 0.4, 0.6, 0.45, 2.0
    s = incline(beta, mu_s, mu_k)
    res = simulate(s, 2.0, initial_state={"dot(x)": -v0})
    assert res.reached_end and [e.kind for e in res.events] == ["sticks"]
    t_stop = v0 / (G * (math.sin(beta) + mu_k * math.cos(beta)))
    assert res.events[0].t == pytest.approx(t_stop, abs=1e-10)
    after = res.segment == 1
    assert res.segments[1].mode == {"ground": "stick"}
    assert np.all(res["dot(x)"][after] == 0.0) and np.ptp(res["x"][after]) == 0.0


# a box pushed at height d: it slides or tips first, as the closed form says ---------------------------
def pushed_box(mu_s, mu_k, b=0.5, h=1.0, d=0.4, c=2.0, m=1.0):
    s = rk.System("pushed-box")
    m_ = s.parameter("m", "kg", value=m)
    g = s.parameter("g", "m/s^2", value=G)
    b_, h_, d_ = s.parameter("b", "m", value=b), s.parameter("h", "m", value=h), s.parameter("d", "m", value=d)
    c_ = s.parameter("c", "N/s", value=c)
    ms, mk = s.parameter("mu_s", "", value=mu_s), s.parameter("mu_k", "", value=mu_k)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=h / 2, rate=0)
    th = s.coordinate("theta", "tilt, counter-clockwise", initial=0, rate=0)
    B = s.frame("B", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    box = s.body("box", rk.shapes.RectangularPlate(m_, b_, h_), frame=B, at=Gp)
    back = s.point("A", Gp, -b_ / 2 * B.x - h_ / 2 * B.y, body=box)
    front = s.point("C", Gp, b_ / 2 * B.x - h_ / 2 * B.y, body=box)
    push = s.point("P", Gp, -b_ / 2 * B.x + (d_ - h_ / 2) * B.y, body=box)
    floor = s.line(s.origin, s.inertial.y)
    fr = {"static": ms, "kinetic": mk}
    s.contact("A", box, floor, centre=back, friction=fr, normal_name="N_A", friction_name="F_A")
    s.contact("C", box, floor, centre=front, friction=fr, normal_name="N_C", friction_name="F_C")
    s.force("push", push, c_ * rk.t * s.inertial.x)
    s.gravity(g)
    return s


@pytest.mark.slow
@pytest.mark.parametrize("mu_s", [0.3, pytest.param(0.8, marks=pytest.mark.slow)])
def test_box_pushed_at_height_slides_or_tips_first(mu_s):
    b, h, d, c, m = 0.5, 1.0, 0.4, 2.0, 1.0
    t_slide, t_tip = mu_s * m * G / c, m * G * b / (2 * c * d)  # P = µs m g, or P d = m g b / 2
    res = simulate(pushed_box(mu_s, 0.8 * mu_s, b, h, d, c, m), min(t_slide, t_tip) + 0.02, max_events=5)
    ev = res.events[0]
    assert res.segments[0].mode == {"A": "stick", "C": "slip"}      # at rest; C's friction carried with A's
    if mu_s < b / (2 * d):
        assert ev.kind == "slips" and ev.t == pytest.approx(t_slide, abs=1e-9)
    else:
        assert ev.kind == "opens" and ev.contact == "A" and ev.t == pytest.approx(t_tip, abs=1e-9)
        assert res.segments[1].mode == {"A": "open", "C": "stick"}


def test_statically_indeterminate_rest_is_reported_with_what_is_determined():
    s = rod(0.5, 0.0, 0.0, supports=(0.5, 0.2))
    # both supports sticking: the two no-slip rows repeat each other, so only the friction sum is determined
    both = s.solve(mode={"A": "stick", "B": "stick"}).regimes[0]
    assert both.indeterminate.reactions == ("F_A", "F_B") and "F_A" not in both.reactions
    assert [(str(c), v) for c, v in both.indeterminate.combinations] == [("F_A + F_B", 0)]
    # the normal forces are determined (lever rule) and the friction is carried by A alone here
    held = s.solve(mode={"A": "stick", "B": "slip"})
    assert held.coordinates == () and held.setup.held == ("B",)
    vals = {"m": 1.5, "g": G}
    n_a = float(held.reactions["N_A"].subs({sym: vals[str(sym)] for sym in held.reactions["N_A"].free_symbols}))
    assert n_a == pytest.approx(1.5 * G * 0.2 / 0.7, rel=1e-12)
    assert any("statically indeterminate" in step.title for step in held.setup.trace.steps)


@pytest.mark.slow
def test_painleve_non_uniqueness_is_reported_not_guessed():
    from rigidkin.numeric.contacts.contact_modes import ContactParadox

    # the same rod turning fast (θ̇² > g/(a sin θ)): N = m(g − a sinθ θ̇²)/(1 + 3cos²θ − 3µ sinθ cosθ) > 0
    # while sliding, and the free end A would also rise (ÿ_A = −g + a sinθ θ̇² > 0) if it opened
    theta, a, m, w = math.atan(2.0), 0.6, 1.5, 5.0
    s = rod(2.0, theta, 0.0, m=m, length=2 * a)
    start = {"dot(theta)": w, "dot(y)": a * math.cos(theta) * w, "dot(x)": -1.0 - a * math.sin(theta) * w}
    with pytest.raises(ContactParadox, match="2 solutions") as err:
        simulate(s, 0.05, initial_state=start, raise_on_stop=True)
    assert err.value.stop_reason == "ambiguous"
    N = m * (G - a * math.sin(theta) * w**2) / (1 + 3 * math.cos(theta)**2 - 6 * math.sin(theta) * math.cos(theta))
    assert N > 0 and f"would be {N:.4g}" in str(err.value)



def test_phases_answer_with_a_phase_at_rest():
    from rigidkin.analysis.phases import Phase, run_phases

    slip = sp.Function("slip")
    s = incline(0.4, 0.6, 0.45)
    x = s.coordinates[0]
    res = run_phases(s, [Phase("sliding up", {"ground": "slip"}, {}, sp.Eq(slip(sp.Symbol("ground")), 0)),
                         Phase("at rest", {"ground": "stick"})], start={x.diff(rk.t): -2})
    g, beta, mu_k = (s.parameters[k] for k in ("g", "beta", "mu_k"))
    assert sp.simplify(res[0].duration - 2 / (g * (sp.sin(beta) + mu_k * sp.cos(beta)))) == 0
    assert res[1].duration is None and any("µ_s ≥ tan(β)" in n for n in res[1].notes)


# a rod leaning on a smooth wall and a rough floor, released from rest ----------------------------------
def leaning_rod(mu_s, mu_k, theta0, m=10.0, l=2.0):
    """The ladder card with friction at the foot B (θ from the wall, x the foot's distance from it)."""
    s = rk.System("rough-ladder")
    m_, l_ = s.parameter("m", "kg", value=m), s.parameter("l", "m", value=l)
    g = s.parameter("g", "m/s^2", value=G)
    ms, mk = s.parameter("mu_s", "", value=mu_s), s.parameter("mu_k", "", value=mu_k)
    th = s.coordinate("theta", "angle of the rod from the wall", initial=theta0, rate=0)
    x = s.coordinate("x", "foot from the wall", kind="length", initial=l*math.sin(theta0), rate=0)
    R = s.frame("R", angle=th)
    B = s.point("B", s.origin, x * s.inertial.x)
    Gp = s.point("G", B, l_ / 2 * R.y)
    rod = s.body("rod", rk.shapes.SlenderRod(m_, l_, axis="y"), frame=R, at=Gp)
    A = s.point("A", B, l_ * R.y, body=rod)
    Bb = s.point("Bf", B, 0 * R.y, body=rod)
    s.contact("A", rod, s.line(s.origin, s.inertial.x), centre=A, normal_name="N_A")
    s.contact("B", rod, s.line(s.origin, s.inertial.y), centre=Bb, friction={"static": ms, "kinetic": mk},
              normal_name="N_B", friction_name="F_B")
    s.gravity(g)
    return s


@pytest.mark.slow
@pytest.mark.parametrize("mu_s", [0.4, 0.2])
def test_rod_leaning_on_a_rough_floor_stays_when_tan_theta_within_2_mu_s(mu_s):
    theta0, m = 0.6, 10.0
    res = simulate(leaning_rod(mu_s, 0.8 * mu_s, theta0, m=m), 0.3, n_points=31)
    assert res.reached_end
    if math.tan(theta0) <= 2 * mu_s:
        # statics: N_B = m g, N_A = F_B = (m g / 2) tan θ
        assert res.segments[0].mode == {"A": "slip", "B": "stick"} and not res.events
        assert res["N_B"][0] == pytest.approx(m * G, rel=1e-12)
        assert res["N_A"][0] == pytest.approx(m * G * math.tan(theta0) / 2, rel=1e-12)
        assert res["F_B"][0] == pytest.approx(m * G * math.tan(theta0) / 2, rel=1e-12)
        assert np.ptp(res["theta"]) == 0.0
    else:
        assert res.segments[0].mode["B"] == "slip" and res["theta"][-1] > theta0
        assert np.allclose(np.abs(res["F_B"]), 0.8 * mu_s * res["N_B"], rtol=1e-12)

