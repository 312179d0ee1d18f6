"""Impacts over every contact closed or closing, checked against impulse–momentum by hand.

(1) a contact the coordinates keep closed (a rod's foot on the floor) takes its normal and friction
impulses when the other end lands; (2) a rod bouncing flat on two supports (redundant no-slip rows)
bounces to rest with the lever rule at every bounce, deterministic under any hash seed; impact
events carry their impulses as numbers."""

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.numeric import simulate

G = 9.81
HERE = os.path.dirname(__file__)


def foot_rod(mu, theta0, v0, m=2.0, length=1.0):
    """A rod whose foot A slides on the floor (foot position x, angle θ from the floor): A's normal is
    kept by the coordinates; the other end B is a contact that lands when θ reaches 0."""
    s = rk.System("rod-foot")
    m_, l_ = s.parameter("m", "kg", value=m), s.parameter("L", "m", value=length)
    g, mu_ = s.parameter("g", "m/s^2", value=G), s.parameter("mu", "", value=mu)
    x = s.coordinate("x", "foot along Ex", kind="length", initial=0, rate=v0)
    th = s.coordinate("theta", "angle of the rod from the floor", initial=theta0, rate=0)
    R = s.frame("R", angle=th)
    Gp = s.point("G", s.point("P", s.origin, x * s.inertial.x), l_ / 2 * R.x)
    body = s.body("rod", rk.shapes.SlenderRod(m_, l_, axis="x"), frame=R, at=Gp)
    A = s.point("A", Gp, -l_ / 2 * R.x, body=body)
    B = s.point("B", Gp, l_ / 2 * R.x, body=body)
    floor = s.line(s.origin, s.inertial.y)
    s.contact("A", body, floor, centre=A, friction=mu_, normal_name="N_A", friction_name="F_A")
    s.contact("B", body, floor, centre=B, friction=mu_, normal_name="N_B", friction_name="F_B")
    s.gravity(g)
    return s


@pytest.mark.parametrize("e", [0.0, 0.5])
def test_foot_kept_closed_by_the_coordinates_takes_its_impulses_when_the_rod_lands(e):
    m, L, mu = 2.0, 1.0, 0.3
    res = simulate(foot_rod(mu, 0.3, 2.0, m, L), 0.25, restitution=e)
    ev = next(ev for ev in res.events if ev.kind == "impact")
    assert ev.contact == "B"
    xd0, w0 = ev.state["dot(x)"], ev.state["dot(theta)"]
    assert w0 < 0 and xd0 > 0
    # by hand, at θ = 0: v_G = (ẋ, L ω/2), A at −L/2 and B at +L/2 from G, I_G = m L²/12
    #   m (L/2) Δω = N_A + N_B,  (m L²/12) Δω = (L/2)(N_B − N_A),  B: ω⁺ = −e ω⁻,
    #   both ends slide forward: F = µ N against the slip (positive along −Ex), m Δẋ = −µ (N_A + N_B)
    dw = -(1 + e) * w0
    n_a, n_b = m * L * dw / 6, m * L * dw / 3
    xd1 = xd0 - mu * (n_a + n_b) / m
    assert xd1 > 0                                       # it does slide on: the sliding candidate holds
    assert ev.after["dot(theta)"] == pytest.approx(-e * w0, abs=1e-12)
    assert ev.after["dot(x)"] == pytest.approx(xd1, rel=1e-12)
    imp = ev.impact["contacts"]
    assert imp["A"]["normal_impulse"] == pytest.approx(n_a, rel=1e-12)
    assert imp["B"]["normal_impulse"] == pytest.approx(n_b, rel=1e-12)
    assert imp["A"]["tangential_impulse"] == pytest.approx(mu * n_a, rel=1e-12)
    assert imp["B"]["tangential_impulse"] == pytest.approx(mu * n_b, rel=1e-12)
    assert ev.impact["held"] == ["A"]
    T = lambda s_: 0.5 * m * (s_["dot(x)"]**2 + (L * s_["dot(theta)"] / 2)**2) + m * L**2 / 24 * s_["dot(theta)"]**2  # noqa: E731
    assert ev.impact["energy_change"] == pytest.approx(T(ev.after) - T(ev.state), rel=1e-10)
    assert ev.impact["velocity_jump"]["dot(x)"] == pytest.approx(xd1 - xd0, rel=1e-12)
    json.dumps(ev.to_dict())                             # plain numbers


def test_without_the_foots_friction_the_speed_after_would_be_higher():
    # the difference the foot makes: µ N_A more slowing, N_A = N_B / 2 (the 15 % of the ladder's case)
    m, L, mu = 2.0, 1.0, 0.3
    ev = next(ev for ev in simulate(foot_rod(mu, 0.3, 2.0, m, L), 0.25).events if ev.kind == "impact")
    w0, xd0 = ev.state["dot(theta)"], ev.state["dot(x)"]
    only_b = xd0 + mu * L * w0 / 3
    both = xd0 + mu * L * w0 / 2
    assert ev.after["dot(x)"] == pytest.approx(both, rel=1e-12) and abs(both - only_b) > 0.1


def two_supports(mu, a=0.5, b=0.2, drop=0.2, m=1.5, length=1.2):
    """A rod held level (centre x, y; tilt θ) falling onto supports under its points at −a and +b."""
    s = rk.System("rod-on-two-supports")
    m_, l_ = s.parameter("m", "kg", value=m), s.parameter("l", "m", value=length)
    g = s.parameter("g", "m/s^2", value=G)
    mu_ = s.parameter("mu", "", value=mu, positive=False)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=drop, rate=0)
    th = s.coordinate("theta", "tilt, counter-clockwise", initial=0, rate=0)
    R = s.frame("R", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    body = s.body("rod", rk.shapes.SlenderRod(m_, l_, axis="x"), frame=R, at=Gp)
    A = s.point("A", Gp, -a * R.x, body=body)
    B = s.point("B", Gp, b * R.x, body=body)
    floor = s.line(s.origin, s.inertial.y)
    fr = mu_ if mu > 0 else rk.Coulomb(mu_)
    s.contact("A", body, floor, centre=A, friction=fr, normal_name="N_A", friction_name="F_A")
    s.contact("B", body, floor, centre=B, friction=fr, normal_name="N_B", friction_name="F_B")
    s.gravity(g)
    return s


@pytest.mark.parametrize("mu", [0.0, 0.5])
def test_rod_bouncing_flat_on_two_supports_to_rest_with_the_lever_rule(mu):
    m, a, b, drop, e = 1.5, 0.5, 0.2, 0.2, 0.5
    res = simulate(two_supports(mu, a, b, drop, m), 1.0, restitution=e, max_events=200)
    assert res.stop_reason == "completed" and res.reached_end
    impacts = [ev for ev in res.events if ev.kind == "impact"]
    assert len(impacts) >= 10
    v = math.sqrt(2 * G * drop)                          # by hand: each bounce leaves with e v and lands with it
    t_hit = math.sqrt(2 * drop / G)
    for ev in impacts:
        assert ev.t == pytest.approx(t_hit, abs=1e-9)
        assert ev.state["dot(y)"] == pytest.approx(-v, abs=1e-9)
        imp = ev.impact["contacts"]
        p_a, p_b = imp["A"]["normal_impulse"], imp["B"]["normal_impulse"]
        # lever rule: P_A a = P_B b about the centre, P_A + P_B = m (1 + e) v
        assert p_a + p_b == pytest.approx(m * (1 + e) * v, rel=1e-9)
        assert p_a / p_b == pytest.approx(b / a, rel=1e-9)
        assert abs(imp["A"]["tangential_impulse"]) < 1e-12 and abs(imp["B"]["tangential_impulse"]) < 1e-12
        assert ev.after["dot(theta)"] == pytest.approx(0.0, abs=1e-12)
        if ev is impacts[-1]:            # leaves slower than the rest speed: it stays on both supports
            assert ev.after["dot(y)"] == 0.0 and ev.impact["separation_speed"] == pytest.approx(e * v, abs=1e-9)
        else:
            assert ev.after["dot(y)"] == pytest.approx(e * v, abs=1e-9)
        if mu > 0:       # the no-slip rows repeat each other: the split of the friction impulse is a choice
            assert set(ev.impact["indeterminate"]) == {"F_A", "F_B"}
        t_hit += 2 * e * v / G
        v *= e
    # the bounce times accumulate at t₁ + 2 e v₀ / (g (1 − e)); after that the rod rests on both supports
    t_inf = math.sqrt(2 * drop / G) + 2 * e * math.sqrt(2 * G * drop) / (G * (1 - e))
    assert res.segments[-1].t0 == pytest.approx(t_inf, abs=1e-3)
    assert all(res.segments[-1].mode[c] != "open" for c in ("A", "B"))
    late = res.t > t_inf + 1e-3
    assert np.allclose(res["N_A"][late] + res["N_B"][late], m * G, rtol=1e-9)
    assert np.allclose(res["N_A"][late] * a, res["N_B"][late] * b, rtol=1e-9)


SCRIPT = """
import sys
sys.path.insert(0, {here!r})
from test_contacts_impulses import two_supports
from rigidkin.numeric import simulate
res = simulate(two_supports(0.5), 1.0, restitution=0.5, max_events=200)
for ev in res.events:
    print(repr(ev.t), ev.kind, ev.contact, sorted(ev.after.items()), ev.detail)
print(res.stop_reason, res.segments[-1].mode)
"""


@pytest.mark.slow
def test_two_supports_identical_under_three_hash_seeds():
    outs = []
    for seed in ("0", "1", "12345"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        run = subprocess.run([sys.executable, "-c", SCRIPT.format(here=HERE)], env=env, capture_output=True,
                             text=True, timeout=600)
        assert run.returncode == 0, run.stderr[-2000:]
        outs.append(run.stdout)
    assert outs[0].count("impact") >= 10
    assert outs[0] == outs[1] == outs[2]


def _sphere_by_hand(m, r, u0, e, mu):
    """A sphere (I = 2/5 m r²) striking a rough floor z = 0, by hand: P_n = m (1 + e) |v_z|; the slip
    s = (v_x − r ω_y, v_y + r ω_x) changes by (7/2m) P_t, so it slides (P_t = −µ P_n ŝ) while
    |s| > (7/2) µ P_n / m, else it sticks (P_t = −(2m/7) s)."""
    vx, vy, vz, wx, wy, wz = u0
    I = 0.4 * m * r**2
    pn = m * (1 + e) * -vz
    s = np.array([vx - r * wy, vy + r * wx])
    sliding = np.linalg.norm(s) > 3.5 * mu * pn / m
    pt = -mu * pn * s / np.linalg.norm(s) if sliding else -2 * m / 7 * s
    after = np.array([vx + pt[0] / m, vy + pt[1] / m, -e * vz, wx + r * pt[1] / I, wy - r * pt[0] / I, wz])
    return after, pn, pt, sliding


@pytest.mark.parametrize("spin,slides", [((5.0, -60.0, 3.0), True), ((2.0, -5.0, 3.0), False)])
def test_sphere_striking_a_rough_floor_in_3d_slides_or_sticks_as_by_hand(spin, slides):
    from rigidkin.numeric.contacts.contact_lcp import ContactRows, impulse_problem

    m, r, e, mu = 0.5, 0.1, 0.6, 0.3
    I = 0.4 * m * r**2
    M = np.diag([m, m, m, I, I, I])
    u0 = np.array([0.8, -0.3, -3.0, *spin])
    Jn = np.array([0, 0, 1.0, 0, 0, 0])
    Jt1 = np.array([1.0, 0, 0, 0, -r, 0])
    Jt2 = np.array([0, 1.0, 0, r, 0, 0])
    res = impulse_problem(M, u0, [ContactRows("P", Jn, 0.0, Jt1, 0.0, mu, mu, False, e, ((Jt2, 0.0),))])
    after, pn, pt, sliding = _sphere_by_hand(m, r, u0, e, mu)
    assert sliding == slides
    assert res.states["P"] == ("slide+" if slides else "stick")
    assert np.allclose(res.u, after, rtol=1e-12, atol=1e-12)
    assert res.normal["P"] == pytest.approx(pn, rel=1e-12)
    assert res.tangential["P"] == pytest.approx(pt[0], rel=1e-12, abs=1e-14)
    assert res.further["P"][0] == pytest.approx(pt[1], rel=1e-12, abs=1e-14)
    assert res.energy_change < 0
    assert res.count == 1


@pytest.mark.parametrize("vx,spin,slides", [(0.2, 0.0, False), (3.0, 0.0, True), (0.5, -150.0, True),
                                            (0.3, 8.0, False)])
def test_sphere_dropped_spinning_onto_a_rough_floor_in_3d_rebounds_as_by_hand(vx, spin, slides):
    """A billiard ball (quaternion, body angular speeds) dropped 5 cm with forward speed and spin onto a
    rough table, e = 0.5: rebound velocity and spin against :func:`_sphere_by_hand` (sliding or sticking)."""
    sys.path.insert(0, HERE)
    from test_friction3d import MU, R, _omega, billiard

    m = 0.17
    res = simulate(billiard(), 0.11, initial_state={"z": R + 0.05, "dot(x)": vx, "wy": spin}, restitution=0.5,
                   max_events=3)
    ev = next(ev for ev in res.events if ev.kind == "impact")
    w0 = _omega(ev.state)                          # the spin in flight (constant: a sphere, gravity only)
    u0 = [ev.state["dot(x)"], ev.state["dot(y)"], ev.state["dot(z)"], *w0]
    after, pn, pt, sliding = _sphere_by_hand(m, R, u0, 0.5, MU)
    assert sliding == slides
    assert ev.impact["contacts"]["P"]["state"] == ("slide+" if sliding else "stick")
    assert ev.impact["contacts"]["P"]["normal_impulse"] == pytest.approx(pn, rel=1e-10)
    assert math.hypot(*ev.impact["contacts"]["P"]["tangential_impulses"]) == pytest.approx(np.linalg.norm(pt),
                                                                                          rel=1e-9)
    for k, v in zip(("dot(x)", "dot(y)", "dot(z)"), after[:3]):
        assert ev.after[k] == pytest.approx(v, abs=1e-10)
    assert np.allclose(_omega(ev.after), after[3:], rtol=1e-9, atol=1e-8)
    assert ev.impact["energy_change"] < 0


@pytest.mark.parametrize("dims", [2, 3])
def test_coincident_contacts_share_friction_where_only_one_split_fits(dims):
    """A point mass striking the floor at two coincident contacts (µ = 0.1 and 1.0), e = 0, with
    |v_x| = 0.5 |v_z|: it can stop (stick) only if the rough contact carries the friction. By hand:
    u⁺ = 0, total impulse m(−v_x, −v_z); the smooth-ish contact's share must stay in its cone."""
    from rigidkin.numeric.contacts.contact_lcp import ContactRows, impulse_problem

    m = 2.0
    M = np.eye(dims) * m
    u0 = np.array([1.0, -2.0] if dims == 2 else [1.0, 0.0, -2.0])
    Jn = np.eye(dims)[-1]
    Jt = np.eye(dims)[0]
    extra = ((np.eye(dims)[1], 0.0),) if dims == 3 else ()
    rows = [ContactRows(name, Jn, 0.0, Jt, 0.0, mu, mu, False, 0.0, extra) for name, mu in (("A", 0.1), ("B", 1.0))]
    res = impulse_problem(M, u0, rows)
    assert res.states == {"A": "stick", "B": "stick"}
    assert np.allclose(res.u, 0.0, atol=1e-12)
    assert res.normal["A"] + res.normal["B"] == pytest.approx(m * 2.0, rel=1e-12)
    assert res.tangential["A"] + res.tangential["B"] == pytest.approx(-m * 1.0, rel=1e-12)
    for name, mu in (("A", 0.1), ("B", 1.0)):
        assert abs(res.tangential[name]) <= mu * res.normal[name] + 1e-12
        assert res.normal[name] >= -1e-12
    assert set(res.indeterminate) >= {"A:normal", "B:normal"}


def test_ladder_on_a_rough_floor_lands_flat_with_both_floor_impulses_in_the_json(tmp_path, capsys):
    """The ladder card with a rough floor (µ = 0.1 under both ends): it slides, leaves the wall and lands
    flat; the foot B (kept on the floor by the coordinates) takes its impulses too. By hand at θ = π/2,
    e = 0: N_B = m l ω⁻/6, N_Af = m l ω⁻/3, F = µ N at each, ẋ⁺ = ẋ⁻ − µ (N_B + N_Af)/m."""
    from pathlib import Path

    from rigidkin.cli import main

    src = (Path(HERE).parent / "examples" / "ladder.toml").read_text()
    src = src.replace('normal_name = "N_B"\n', 'normal_name = "N_B"\nfriction_name = "F_B"\nfriction = 0.1\n')
    src = src.replace('normal_name = "N_Af"\n', 'normal_name = "N_Af"\nfriction_name = "F_Af"\nfriction = 0.1\n')
    path = tmp_path / "ladder-rough.toml"
    path.write_text(src)
    code = main(["simulate", str(path), "--t-end", "1.5", "--json", "--points", "20"])
    out, err = capsys.readouterr()
    assert code == 0, err
    d = json.loads(out)
    ev = next(e for e in d["events"] if "impact" in e)
    m, length, mu = 10.0, 2.0, 0.1
    w0, xd0 = ev["state"]["dot(theta)"], ev["state"]["dot(x)"]
    assert ev["state"]["theta"] == pytest.approx(math.pi / 2, abs=1e-9) and w0 > 0 and xd0 > 0
    n_b, n_af = m * length * w0 / 6, m * length * w0 / 3
    imp = ev["impact"]["contacts"]
    assert imp["B"]["normal_impulse"] == pytest.approx(n_b, rel=1e-10)
    assert imp["A_floor"]["normal_impulse"] == pytest.approx(n_af, rel=1e-10)
    assert imp["B"]["tangential_impulse"] == pytest.approx(mu * n_b, rel=1e-10)
    assert imp["A_floor"]["tangential_impulse"] == pytest.approx(mu * n_af, rel=1e-10)
    assert ev["state_after"]["dot(x)"] == pytest.approx(xd0 - mu * (n_b + n_af) / m, rel=1e-10)
    assert ev["state_after"]["dot(theta)"] == 0.0 and ev["impact"]["held"] == ["B"]
