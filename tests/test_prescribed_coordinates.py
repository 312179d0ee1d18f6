"""Prescribed coordinates (System.prescribe, `prescribed = "..."` in [coordinates]): the equations of the free
coordinates and the effort the drive needs, against hand derivations, virtual work and an independent
integration."""

from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

import rigidkin as rk
from rigidkin.base.errors import ModelError
from rigidkin.numeric.simulate import simulate

t = rk.t
VALUES = {"M": 2.0, "m": 0.5, "l": 0.8, "g": 9.81, "A": 0.05, "omega": 5.0}


def shaken_cart():
    """A cart driven x = A sin ωt carrying a point-mass pendulum."""
    s = rk.System("shaken")
    M, m, l, g, A, w = (s.parameter(n, u, value=VALUES[n]) for n, u in
                        (("M", "kg"), ("m", "kg"), ("l", "m"), ("g", "m/s^2"), ("A", "m"), ("omega", "rad/s")))
    x = s.coordinate("x", "cart along Ex", kind="length")
    th = s.coordinate("theta", "bob from the downward vertical", initial=0.3)
    C = s.point("C", offset=x * s.inertial.x)
    cart = s.body("cart", rk.shapes.PointMass(M), frame=s.inertial, at=C)
    R = s.frame("R", angle=th)
    bob = s.body("bob", rk.shapes.PointMass(m), frame=R, at=s.point("B", C, -l * R.y))
    s.collar("rail", cart, s.inertial.x, point=C)
    s.pin("hinge", C, bob, body_b=cart)
    s.gravity(g)
    s.prescribe(x, A * sp.sin(w * t))
    return s, (M, m, l, g, A, w), x, th


def hand_cart(M, m, l, g, A, w, th):
    """By hand: l θ̈ = −g sin θ − ẍ cos θ with ẍ = −Aω² sin ωt; F = (M+m)ẍ + m l(θ̈ cos θ − θ̇² sin θ)."""
    xdd = -A * w**2 * sp.sin(w * t)
    thdd = (-g * sp.sin(th) + A * w**2 * sp.sin(w * t) * sp.cos(th)) / l
    F = (M + m) * xdd + m * l * (thdd * sp.cos(th) - th.diff(t) ** 2 * sp.sin(th))
    return thdd, F


def test_shaken_cart_equation_and_force_by_hand():
    s, (M, m, l, g, A, w), x, th = shaken_cart()
    sol = s.solve()
    assert tuple(sol.coordinates) == (th,)                  # written for the free coordinate only
    thdd, F = hand_cart(M, m, l, g, A, w, th)
    assert sp.simplify(sol.accelerations[th] - thdd) == 0
    assert sp.simplify(sol.reactions["Q_x"] - F) == 0
    con = s.constraints["drive_x"]
    assert "force needed to drive x" in con.reaction_label(con.Q)
    assert s.coordinate_info["x"].prescribed == A * sp.sin(w * t)


def test_shaken_cart_simulation_records_the_force_and_follows_the_law():
    s, (M, m, l, g, A, w), x, th = shaken_cart()
    res = simulate(s, 1.5, {"theta": 0.3}, n_points=31, rtol=1e-10, atol=1e-12)
    v = VALUES
    ts = np.asarray(res.t)
    assert np.allclose(res["x"], v["A"] * np.sin(v["omega"] * ts), atol=1e-8)

    def rhs(tt, y):
        return [y[1], (-v["g"] * np.sin(y[0]) + v["A"] * v["omega"] ** 2 * np.sin(v["omega"] * tt)
                       * np.cos(y[0])) / v["l"]]
    ref = solve_ivp(rhs, (0, 1.5), [0.3, 0.0], t_eval=ts, rtol=1e-11, atol=1e-12)
    assert np.allclose(res["theta"], ref.y[0], atol=1e-6)
    xdd = -v["A"] * v["omega"] ** 2 * np.sin(v["omega"] * ts)
    thdd = np.array([rhs(tt, yy)[1] for tt, yy in zip(ts, ref.y.T)])
    F = (v["M"] + v["m"]) * xdd + v["m"] * v["l"] * (thdd * np.cos(ref.y[0]) - ref.y[1] ** 2 * np.sin(ref.y[0]))
    assert np.allclose(res.reactions["Q_x"], F, atol=1e-5)


FILE = """
title = "Pendulum on a shaken cart"
[parameters]
M = { unit = "kg", value = 2 }
m = { unit = "kg", value = 0.5 }
l = { unit = "m", value = 0.8 }
g = { unit = "m/s^2", value = 9.81 }
A = { unit = "m", value = 0.05 }
omega = { unit = "rad/s", value = 5 }
[coordinates]
x = { sense = "cart along Ex", kind = "length", prescribed = "A*sin(omega*t)", drive_effort = "F_drive" }
theta = { sense = "bob from the downward vertical", initial = 0.3 }
[frames]
R = { angle = "theta", basis = ["rx", "ry", "rz"] }
[points]
C = { offset = "x*Ex" }
B = { from = "C", offset = "-l*ry" }
[bodies]
cart = { shape = "point_mass", mass = "M", frame = "F", at = "C" }
bob = { shape = "point_mass", mass = "m", frame = "R", at = "B" }
[constraints]
rail = { type = "collar", body = "cart", along = "Ex", point = "C" }
hinge = { type = "pin", point = "C", body_a = "bob", body_b = "cart" }
[loads]
gravity = { type = "gravity", g = "g" }
"""


def test_prescribed_in_a_problem_file(tmp_path: Path):
    from rigidkin.io.problem import load_problem

    p = tmp_path / "shaken.toml"
    p.write_text(FILE)
    s, _ = load_problem(p)
    sol = s.solve()
    P = s.parameters
    th = s.coordinate_info["theta"].symbol
    thdd, F = hand_cart(P["M"], P["m"], P["l"], P["g"], P["A"], P["omega"], th)
    assert sp.simplify(sol.accelerations[th] - thdd) == 0
    assert sp.simplify(sol.reactions["F_drive"] - F) == 0


def test_drive_effort_without_a_law_is_refused(tmp_path: Path):
    from rigidkin.base.errors import RigidkinError
    from rigidkin.io.problem import load_problem

    p = tmp_path / "bad.toml"
    p.write_text(FILE.replace('prescribed = "A*sin(omega*t)", ', ""))
    with pytest.raises(RigidkinError, match="drive_effort"):
        load_problem(p)


def slider_crank(rate=False):
    """Crank OA (massless, length r) turned at Ω, massless rod AB (length L), slider of mass m at B pushed back by P."""
    s = rk.System("slider-crank")
    r, L, m, P, W = (s.parameter(n, u, value=v) for n, u, v in
                     (("r", "m", 0.1), ("L", "m", 0.3), ("m", "kg", 1.5), ("P", "N", 20.0), ("Omega", "rad/s", 10.0)))
    phi = s.coordinate("phi", "crank from Ex, counter-clockwise")
    psi = s.coordinate("psi", "rod from Ex, counter-clockwise")
    Cf, Df = s.frame("C", angle=phi), s.frame("D", angle=psi)
    crank = s.body("crank", rk.shapes.Massless(), frame=Cf, at=s.origin)
    A = s.point("A", offset=r * Cf.x, body=crank)
    A2 = s.point("A2", A, 0)
    rod = s.body("rod", rk.shapes.Massless(), frame=Df, at=A2)
    B = s.point("B", A2, L * Df.x, body=rod)
    slider = s.body("slider", rk.shapes.PointMass(m), frame=s.inertial, at=s.point("S", B, 0))
    s.pin("O", s.origin, crank)
    s.pin("Apin", A2, rod, body_b=crank, point_b=A)
    s.pin("Bpin", B, slider, body_b=rod)
    s.collar("guide", slider, s.inertial.x)
    s.force("gas", "S", -P * s.inertial.x)
    if rate:
        s.prescribe(phi, rate=W, effort="T_motor")
    else:
        s.prescribe(phi, W * t, effort="T_motor")
    return s, (r, L, m, P, W), phi, psi


@pytest.mark.parametrize("rate", [False, True])
def test_slider_crank_torque_by_virtual_work(rate):
    s, (r, L, m, P, W), phi, psi = slider_crank(rate)
    sol = s.solve()
    assert tuple(sol.coordinates) == ()                 # no degree of freedom left
    T = sol.reactions["T_motor"]
    vals = s.parameter_values()
    # virtual work: T δφ − P δx_B = m ẍ_B δx_B, x_B = r cos φ + √(L² − r² sin² φ), φ = Ω t
    ph = sp.Symbol("ph")
    xb = r * sp.cos(ph) + sp.sqrt(L**2 - r**2 * sp.sin(ph) ** 2)
    hand = ((m * sp.diff(xb.subs(ph, W * t), t, 2) + P) * sp.diff(xb, ph).subs(ph, W * t)).subs(vals)
    for t0 in (0.05, 0.2, 0.37):
        ph0 = float((W * t0).subs(vals))
        ps0 = float(sp.asin(-r * sp.sin(ph0) / L).subs(vals))
        got = T.subs(vals).subs({phi.diff(t): vals[W], phi: ph0, psi: ps0}).subs(t, t0)
        assert float(got) == pytest.approx(float(hand.subs(t, t0)), rel=1e-9, abs=1e-12)


def test_refusals():
    s, (M, m, l, g, A, w), x, th = shaken_cart()
    with pytest.raises(ModelError, match="involves the coordinates"):
        s.prescribe(th, th * t)
    with pytest.raises(ModelError, match="not a coordinate"):
        s.prescribe(sp.Symbol("z"), t)
    with pytest.raises(ModelError, match="one of them"):
        s.prescribe(th)
    s2 = rk.System("p")
    q = s2.coordinate("q", initial=0.5)
    with pytest.raises(ModelError, match="disagrees with its law"):
        s2.prescribe(q, 2 * t)


def governor_by_a_prescribed_angle():
    """A rod hinged on a massless vertical shaft whose angle φ is a coordinate prescribed φ = Ω t (3D)."""
    s = rk.System("governor-q")
    m, l = s.parameter("m", "kg", value=2.0), s.parameter("l", "m", value=0.8)
    g, W = s.parameter("g", "m/s^2", value=9.81), s.parameter("Omega", "rad/s", value=6.0)
    phi = s.coordinate("phi", "shaft angle about Ey")
    th = s.coordinate("theta", "rod from the downward shaft", initial=0.5)
    S = s.frame("S", angle=phi, axis="y")
    shaft = s.body("shaft", rk.shapes.Massless(), frame=S, at=s.origin)
    R = s.frame("R", S, angle=th, axis="z")
    O2 = s.point("O2", s.origin, 0)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=s.point("G", O2, -l / 2 * R.y))
    s.pin("bearing", s.origin, shaft, axis="S.y")
    s.pin("O", O2, rod, body_b=shaft, point_b=s.origin, axis="S.z")
    s.gravity(g, -s.inertial.y)
    s.prescribe(phi, W * t, effort="T_motor")
    return s, (m, l, g, W), th


def test_rod_on_a_shaft_turned_by_a_prescribed_angle():
    from rigidkin.analysis.equilibrium import equilibria

    s, (m, l, g, W), th = governor_by_a_prescribed_angle()
    sol = s.solve()
    assert tuple(sol.coordinates) == (th,)
    assert sp.simplify(sol.accelerations[th] - (W**2 * sp.cos(th) - 3 * g / (2 * l)) * sp.sin(th)) == 0
    # Euler's second law about the shaft's axis by hand: T = d/dt(⅓ m l² sin²θ Ω) = ⅔ m l² Ω sin θ cos θ θ̇
    T_hand = sp.Rational(2, 3) * m * l**2 * W * sp.sin(th) * sp.cos(th) * th.diff(t)
    assert sp.simplify(sol.reactions["T_motor"] - T_hand) == 0
    # the relative equilibrium cos θ* = 3g/(2lΩ²), its frequency Ω sin θ*
    eqs = [e for e in equilibria(sol) if e.natural_frequencies]
    assert eqs and all("relative equilibrium" in e.notes[0] for e in eqs)
    star = sp.acos(3 * g / (2 * l * W**2))
    e = next(e for e in eqs if sp.simplify(e.configuration[th] - star) == 0)
    assert sp.simplify(e.natural_frequencies[0] ** 2 - W**2 * sp.sin(star) ** 2) == 0


def test_equilibria_refused_when_the_law_keeps_t():
    from rigidkin.analysis.equilibrium import equilibria
    from rigidkin.base.errors import RigidkinError

    with pytest.raises(RigidkinError, match="depend on t explicitly"):
        equilibria(shaken_cart()[0].solve())


def test_a_prescribed_speed_against_eulers_equations():
    """A box on a ball joint whose spin speed w3 about its axis b3 a motor holds at Ω: Euler's equations by hand,
    I1 ẇ1 = (I2 − I3) w2 Ω, I2 ẇ2 = (I3 − I1) Ω w1, and the motor torque M3 = −(I1 − I2) w1 w2."""
    s = rk.System("spun-box")
    m = s.parameter("m", "kg", value=1.0)
    I1, I2, I3 = (s.parameter(n, "kg*m^2", value=v) for n, v in (("I1", 0.2), ("I2", 0.5), ("I3", 0.3)))
    W = s.parameter("Omega", "rad/s", value=4.0)
    B = s.frame("B", quaternion=True, speeds=("w1", "w2", "w3"), rates=(0.1, 0.2, None))
    box = s.body("box", rk.shapes.Inertia(mass=m, Ixx=I1, Iyy=I2, Izz=I3), frame=B, at=s.origin)
    s.pin("ball", s.origin, box)
    w1, w2, w3 = B.speeds
    s.prescribe(w3, W)
    sol = s.solve()
    acc = {str(k.func.__name__): v for k, v in sol.accelerations.items()}
    assert set(acc) == {"w1_int", "w2_int"}
    assert sp.simplify(acc["w1_int"] - (I2 - I3) * w2 * W / I1) == 0
    assert sp.simplify(acc["w2_int"] - (I3 - I1) * W * w1 / I2) == 0
    assert sp.simplify(sol.reactions["Q_w3"] - (I2 - I1) * w1 * w2) == 0
    res = simulate(s, 1.0, n_points=11)
    assert np.allclose(res["dot(w3_int)"], 4.0)
    assert np.allclose(res.reactions["Q_w3"], 0.3 * res["dot(w1_int)"] * res["dot(w2_int)"], atol=1e-9)


def test_no_actuator_for_a_coordinate_that_turns_no_body_alone_is_refused():
    s = rk.System("hidden")
    m, l = s.parameter("m", "kg"), s.parameter("l", "m")
    q, p = s.coordinate("q"), s.coordinate("p")
    A = s.frame("A", angle=q)
    Bf = s.frame("B", A, angle=p)
    rod = s.body("rod", rk.shapes.PointMass(m), frame=Bf, at=s.point("G", offset=-l * Bf.y))
    s.pin("O", s.origin, rod)
    s.prescribe(q, t)
    with pytest.raises(ModelError, match="no actuator moving q alone"):
        s.solve()
