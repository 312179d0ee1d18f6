"""A new user's problems on the arc edges, slack ropes and indeterminate statics, checked by hand.

* A semicircular disk (R, m) on a floor with µ = 0.4, spun off its arc: the hand-over rate and time from the
  energy integral ½ I_C(θ) θ̇² + m g (R − ρ cos θ) = E, I_C = m (3R²/2 − 2Rρ cos θ), ρ = 4R/(3π); then at
  rest on its flat face, N = m g/2 at each edge, and the mode told as sticking (not slipping) at both edges.
* A yo-yo hanging from a fixed point, free to swing (x, y, φ): taut from rest, T = m g I/(I + m r²) and
  ÿ = −g/(1 + I/(m r²)) (was refused as singular: the pivot probe fell on a point where √(d² − r²) is not real).
* A block on a rough and a rolling support pushed at height d: N_A = (m g b − P d)/(2b) by moments about C.
"""

import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad

import rigidkin as rk
from rigidkin.model.ropes import Wrap
from rigidkin.numeric.contacts.vocabulary import describe_mode

G = 9.81


def test_a_held_contact_is_told_sticking_not_slipping():
    s = rk.System("rod-on-two-supports")
    x = s.coordinate("x", "centre along Ex", kind="length")
    y = s.coordinate("y", "centre height", kind="length")
    th = s.coordinate("theta", "angle from the floor")
    R = s.frame("R", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    body = s.body("rod", rk.shapes.SlenderRod(1, 1.2, axis="x"), frame=R, at=Gp)
    floor = s.line(s.origin, s.inertial.y)
    for name, at in (("A", -0.5), ("B", 0.2)):
        s.contact(name, body, floor, centre=s.point(name, Gp, at * R.x, body=body), friction=0.4)
    assert describe_mode(s, {"A": "stick", "B": "slip"}) == "A sticking, B slipping"
    assert describe_mode(s, {"A": "stick", "B": "slip"}, held=("B",)) == "A sticking, B sticking (friction shared)"


def _half_disk(theta0, w0=0.0, y0=0.1, m=1.0, r=0.1, mu=0.4):
    s = rk.System("half disk")
    m_, r_, g_ = s.parameter("m", "kg", value=m), s.parameter("r", "m", value=r), s.parameter("g", "m/s^2", value=G)
    theta = s.coordinate("theta", "tilt, counter-clockwise", initial=theta0, rate=w0)
    x = s.coordinate("x", "flat-face centre along Ex", kind="length", rate=-r * w0)
    y = s.coordinate("y", "flat-face centre above the floor", kind="length", initial=y0)
    O1 = s.point("O1", s.origin, x * s.inertial.Ex + y * s.inertial.Ey)
    half = s.body("half", rk.shapes.SemicircularDisk(m_, r_), frame=s.frame("B", angle=theta), at=O1)
    s.contact("P", half, s.line(s.origin, s.inertial.Ey), centre=O1, radius=r_, friction=mu)
    s.gravity(g_)
    return s


@pytest.mark.slow
def test_half_disk_rolls_off_its_arc_and_comes_to_rest_on_both_edges():
    from rigidkin.numeric.simulate import simulate
    m, r, mu, w0 = 1.0, 0.1, 0.4, 13.0
    res = simulate(_half_disk(0.0, w0), 0.7)
    rho = 4 * r / (3 * math.pi)
    IC = lambda q: m * (1.5 * r**2 - 2 * r * rho * math.cos(q))                          # noqa: E731
    E = 0.5 * IC(0) * w0**2 + m * G * (r - rho)
    rate = lambda q: math.sqrt(2 * (E - m * G * (r - rho * math.cos(q))) / IC(q))       # noqa: E731
    arc = res.events[0]
    assert arc.kind == "arc" and arc.state["theta"] == pytest.approx(math.pi / 2, abs=1e-9)
    assert arc.state["dot(theta)"] == pytest.approx(rate(math.pi / 2), rel=1e-9)
    assert arc.t == pytest.approx(quad(lambda q: 1 / rate(q), 0, math.pi / 2, epsabs=1e-13)[0], rel=1e-8)
    # the landing on the flat face (θ = π): both edges' normal speeds to zero; ω⁺ = 0, Λ1 + Λ2 = −m ẏ⁻
    hit = res.events_of("impact")[0]
    wd, vy = hit.state["dot(theta)"], hit.state["dot(y)"]
    imp = hit.impact["contacts"]
    assert hit.after["dot(theta)"] == pytest.approx(0, abs=1e-9)
    assert imp["P_edge1"]["normal_impulse"] + imp["P_edge2"]["normal_impulse"] == pytest.approx(-m * vy, rel=1e-9)
    # it slides (ρ > µ R: sticking would need F = m ρ ω⁻ > µ m R ω⁻): the friction impulse is µ × the normal one
    F = imp["P_edge1"]["tangential_impulse"] + imp["P_edge2"]["tangential_impulse"]
    assert abs(F) == pytest.approx(mu * m * -vy, rel=1e-9)
    IG = m * (r**2 / 2 - rho**2)                  # moments about G: I_G (0 − ω⁻) = R (Λ2 − Λ1) + ρ |F|
    assert imp["P_edge2"]["normal_impulse"] - imp["P_edge1"]["normal_impulse"] == pytest.approx(
        (-IG * wd - rho * abs(F)) / r, rel=1e-8)
    end = res.final_state
    assert end["theta"] == pytest.approx(math.pi, abs=1e-9) and end["dot(x)"] == 0
    assert res["N_P_edge1"][-1] == pytest.approx(m * G / 2, rel=1e-9)
    assert res["N_P_edge2"][-1] == pytest.approx(m * G / 2, rel=1e-9)
    last = res.segments[-1]
    words = getattr(last, "description", None) or str(last)
    assert "slipping" not in words and "P_edge2 sticking (friction shared)" in words


@pytest.mark.slow
def test_half_disk_rocks_on_its_arc_with_the_period_of_its_energy_integral():
    """Rolling from rest at θ0 = 0.1: period 4 ∫ dθ/θ̇ with θ̇² = 2 m g ρ (cos θ − cos θ0)/I_C(θ), 0.78755 s
    (the linear 2π √(I_C(0)/(m g ρ)) = 0.78578 s); the restoring moment is m g ρ sin θ, not m g (r − ρ) sin θ."""
    from rigidkin.numeric.simulate import simulate
    r, th0 = 0.1, 0.1
    rho = 4 * r / (3 * math.pi)
    IC = lambda q: 1.5 * r**2 - 2 * r * rho * math.cos(q)                                 # noqa: E731
    period = 4 * quad(lambda u: th0 * math.cos(u) / math.sqrt(
        2 * G * rho * (math.cos(th0 * math.sin(u)) - math.cos(th0)) / IC(th0 * math.sin(u))), 0, math.pi / 2)[0]
    assert 2 * math.pi * math.sqrt(IC(0) / (G * rho)) == pytest.approx(0.78578, abs=1e-5)
    res = simulate(_half_disk(th0), 1.7, n_points=3401)
    assert res.events == [] and res.reached_end
    t, th = np.asarray(res.t), np.asarray(res["theta"])
    i = np.nonzero((th[:-1] > 0) & (th[1:] <= 0))[0]
    downs = [res.t[k] + (res.t[k + 1] - res.t[k]) * th[k] / (th[k] - th[k + 1]) for k in i]
    assert len(downs) == 2 and downs[1] - downs[0] == pytest.approx(period, rel=1e-6)
    assert max(abs(np.asarray(res["F_P"]) / np.asarray(res["N_P"]))) < 0.4         # it rolls all along (µ = 0.4)
    assert len(t) == 3401


@pytest.mark.slow
def test_half_disk_released_on_its_edge_rocks_back_or_falls_flat():
    """On its edge from rest (y = r sin θ0): pivoting on the edge, ½ (3 m r²/2) θ̇² = m g (h0 − h), h the mass
    centre's height above the edge, r sin θ − ρ cos θ; beyond θ = π − atan(r/ρ) it falls, short of it it rocks back."""
    from rigidkin.numeric.simulate import simulate
    r, m = 0.1, 1.0
    rho, IE = 4 * r / (3 * math.pi), 1.5 * m * r**2
    assert math.pi - math.atan(r / rho) == pytest.approx(math.radians(112.9965), abs=1e-5)
    th0 = 1.8
    res = simulate(_half_disk(th0, y0=r * math.sin(th0)), 0.25)
    back = res.events[0]
    assert back.kind == "arc-back" and back.state["theta"] == pytest.approx(math.pi / 2, abs=1e-9)
    h = lambda q: r * math.sin(q) - rho * math.cos(q)                                    # noqa: E731
    assert back.state["dot(theta)"] == pytest.approx(-math.sqrt(2 * m * G * (h(th0) - r) / IE), rel=1e-9)
    th0 = 2.2
    res = simulate(_half_disk(th0, y0=r * math.sin(th0)), 0.3)
    assert res.segments[0].description.startswith("P open, P_edge2 sticking")
    assert res.final_state["theta"] == pytest.approx(math.pi, abs=1e-9)


@pytest.mark.slow
def test_swinging_yoyo_taut_from_rest_by_hand():
    s = rk.System("yo-yo")
    m, R, r = s.parameter("m", "kg", value=0.1), s.parameter("R", "m", value=0.03), s.parameter("r", "m", value=0.005)
    g = s.parameter("g", "m/s^2", value=G)
    y = s.coordinate("y", "height of the centre", kind="length", initial=-0.5)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0.005)
    phi = s.coordinate("phi", "rotation, counter-clockwise")
    C = s.point("C", s.origin, x * s.inertial.Ex + y * s.inertial.Ey)
    yoyo = s.body("yoyo", rk.shapes.Disk(m, R), frame=s.frame("B", angle=phi), at=C)
    s.rope("string", [s.origin, Wrap(yoyo, r, "ccw")], tensions=("T",))    # down the drum's left side
    s.gravity(g)
    assert describe_mode(s, {}) == "string taut" and describe_mode(s, {"string": "open"}) == "string slack"
    sol = s.solve()
    t = rk.t
    at = {sp.Derivative(y, t): 0, sp.Derivative(x, t): 0}
    vals = {m: 0.1, R: 0.03, r: 0.005, g: G}
    k = (0.1 * 0.03**2 / 2) / (0.1 * 0.005**2)                              # I/(m r²) = 18
    acc = sol.accelerations[y].subs(at).subs({y: -0.5, x: 0.005}).subs(vals)
    T = sol.reactions["T"].subs(at).subs({y: -0.5, x: 0.005}).subs(vals)
    assert float(acc) == pytest.approx(-G / (1 + k), rel=1e-9)
    assert float(T) == pytest.approx(0.1 * G * k / (1 + k), rel=1e-9)
    assert float(sol.accelerations[x].subs(at).subs({y: -0.5, x: 0.005}).subs(vals)) == pytest.approx(0, abs=1e-12)


def test_block_on_a_rough_and_a_rolling_support_by_moments():
    m, b, h, d, P = 2.0, 0.2, 0.3, 0.45, 3.0
    s = rk.System("block")
    x = s.coordinate("x", "centre along Ex", kind="length")
    y = s.coordinate("y", "centre height", kind="length", initial=h)
    th = s.coordinate("theta", "tilt, counter-clockwise")
    B = s.frame("B", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.Ex + y * s.inertial.Ey)
    block = s.body("block", rk.shapes.RectangularPlate(m, 2 * b, 2 * h), frame=B, at=Gp)
    floor = s.line(s.origin, s.inertial.Ey)
    s.contact("A", block, floor, centre=s.point("A", Gp, -b * B.x - h * B.y, body=block), friction=0.4,
              normal_name="N_A", friction_name="F_A")
    s.contact("C", block, floor, centre=s.point("C", Gp, b * B.x - h * B.y, body=block), friction="rolling",
              normal_name="N_C", friction_name="F_C")
    Pp = s.parameter("P", "N", value=P)
    s.force("push", s.point("D", Gp, -b * B.x + (d - h) * B.y, body=block), Pp * s.inertial.Ex)
    s.gravity(G)
    r = s.solve(mode={"A": "stick", "C": "stick"}).regimes[0]
    assert float(r.reactions["N_A"].subs(Pp, P)) == pytest.approx((m * G * b - P * d) / (2 * b), rel=1e-12)
    assert float(r.reactions["N_C"].subs(Pp, P)) == pytest.approx((m * G * b + P * d) / (2 * b), rel=1e-12)
    assert r.indeterminate.reactions == ("F_A", "F_C")
    (combo, value), = r.indeterminate.combinations
    assert float(value.subs(Pp, P)) == pytest.approx(P, rel=1e-12)   # friction positive along −Ex: F_A + F_C = P
    # it tips about C where N_A = 0: P d = m g b
    tip, = sp.solve(r.reactions["N_A"], Pp)
    assert float(tip) == pytest.approx(m * G * b / d, rel=1e-12)
    assert any(sp.simplify(c.expr - r.reactions["N_A"]) == 0 for c in r.validity)
