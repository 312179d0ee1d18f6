"""Driven bodies: a body moved by a given law of t, and the effort the law needs (System.drive, driven = true).

Each answer is checked against what a student derives by hand: the equation of motion of the free coordinate
in closed form, the relative equilibrium and its frequency, the drive torque as the rate of the angular
momentum about the shaft (Euler's second law, with the momentum integrated over the rod here by sympy), the
drive force as m a_G − ΣF of the rest (Euler's first law), and a simulation's recorded effort against the hand
formula along the computed motion.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from helpers import rigidkin_process
from sympy.physics.vector import dynamicsymbols

import rigidkin as rk
from rigidkin import examples
from rigidkin.base.errors import ConstraintError, ModelError
from rigidkin.io.problem import parse_problem
from rigidkin.numeric.simulate import simulate

t = dynamicsymbols._t
ROOT = Path(__file__).resolve().parents[1]


def _zero(e) -> bool:
    return sp.simplify(sp.expand_trig(sp.sympify(e))) == 0


def _shaft_system():
    """The rod on a shaft turned at Ω, written here (the bundled example is checked against it below)."""
    s = rk.System("shaft")
    m, l, g = s.parameter("m", "kg", value=2.0), s.parameter("l", "m", value=0.8), s.parameter("g", "m/s^2", value=9.81)
    Om = s.parameter("Omega", "rad/s", value=6.0)
    th = s.coordinate("theta", "angle of the rod from the downward shaft", initial=0.5)
    S = s.frame("S", angle=Om * t, axis="y")
    shaft = s.drive("shaft", S)
    R = s.frame("R", S, angle=th, axis="z")
    G = s.point("G", offset=-l / 2 * R.y)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
    s.pin("O", s.origin, rod, shaft, axis="S.z")
    s.gravity(g, -s.inertial.y)
    return s, (m, l, g, Om, th)


@pytest.fixture(scope="module")
def shaft():
    s, syms = _shaft_system()
    return s, s.solve(), syms


def test_shaft_equation_of_motion_and_relative_equilibrium(shaft):
    s, sol, (m, l, g, Om, th) = shaft
    acc = sol.accelerations[th]
    # by hand (Lagrange in the turning frame): ⅓ m l² θ̈ = ⅓ m l² Ω² sinθ cosθ − m g (l/2) sinθ
    assert _zero(acc - (Om**2 * sp.sin(th) * sp.cos(th) - 3 * g / (2 * l) * sp.sin(th)))
    x = sp.Symbol("x")
    f = acc.subs(th, x)
    assert t not in f.free_symbols                              # a steady rotation: no explicit t in the EOM
    star = sp.acos(3 * g / (2 * l * Om**2))
    assert _zero(f.subs(x, star))                                          # cos θ* = 3g/(2lΩ²)
    # small oscillations about θ*: ω_n² = −∂θ̈/∂θ = Ω² sin²θ*
    w2 = -sp.diff(f, x).subs(x, star)
    assert _zero(w2 - Om**2 * (1 - (3 * g / (2 * l * Om**2))**2))


def test_shaft_torque_is_the_rate_of_angular_momentum_about_the_axis(shaft):
    s, sol, (m, l, g, Om, th) = shaft
    # by hand: a rod element at distance u from O is at u sinθ from the shaft's axis and turns with it at Ω
    # (the swing θ̇ moves it in the shaft's plane, which adds nothing about the axis):
    u = sp.Symbol("u", positive=True)
    H_axis = sp.integrate(m / l * (u * sp.sin(th))**2 * Om, (u, 0, l))    # = ⅓ m l² sin²θ Ω
    # Euler's 2nd law about the fixed axis Ey through O: gravity (along Ey) and the pin force at O have no moment
    T_hand = sp.diff(H_axis, t)
    T = sol.reactions["T_shaft"]
    assert _zero(T - T_hand)
    # zero at the relative equilibrium (no swing: constant H), and positive while the rod rises away from the axis
    assert _zero(T.subs(th.diff(t), 0))
    # the bearing torque and the drive force by Euler's laws for the rod (the shaft is massless)
    yG = -l / 2 * sp.cos(th)
    ay = sp.diff(yG, t, 2).subs(th.diff(t, 2), sol.accelerations[th])
    Fy = sol.reactions["F_shafty"]
    assert _zero(Fy - m * (ay + g))
    assert _zero(sol.reactions["R_Oy"] - Fy)


def test_shaft_every_law_agrees(shaft):
    s, sol, (m, l, g, Om, th) = shaft
    for method in ("lagrange", "kane"):
        other = s.solve(method)
        assert _zero(other.accelerations[th] - sol.accelerations[th]), method


def test_simulation_records_the_drive_torque(shaft):
    s, sol, (m, l, g, Om, th) = shaft
    r = simulate(s, 2.0, {"theta": 0.3, "dot(theta)": 0.0}, n_points=201)
    q, qd = r.q["theta"], r.rates["dot(theta)"]
    hand = 2.0 * 0.8**2 * 6.0 * np.sin(2 * q) * qd / 3          # ⅓ m l² Ω θ̇ sin 2θ along the computed motion
    assert np.max(np.abs(r.reactions["T_shaft"] - hand)) < 1e-8 * max(1.0, np.max(np.abs(hand)))
    assert np.max(np.abs(hand)) > 1.0                               # the rod swings: the torque is not trivial
    # the energy of the rod changes by the work of the drive: E − E0 − W stays at round-off
    E, W = r.energy["E"], r.energy["W"]
    assert abs(E[-1] - E[0]) > 0.1
    assert np.max(np.abs(E - E[0] - W)) < 1e-6


def test_hinge_whose_axis_turns_by_a_law_is_on_the_shaft():
    """The issue's own words: a rod hinged on a vertical shaft turning at Ω, its frame's angle written Omega*t,
    pinned with no body on the other side.  The hinge's axis turns by a law, so the hinge is on the shaft: its
    torque about the shaft's axis is the torque needed to turn it (the same as the driven body's T)."""
    s = rk.System("direct")
    m, l, g = s.parameter("m", "kg"), s.parameter("l", "m"), s.parameter("g", "m/s^2")
    Om = s.parameter("Omega", "rad/s")
    th = s.coordinate("theta")
    S = s.frame("S", angle=Om * t, axis="y")
    R = s.frame("R", S, angle=th, axis="z")
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=s.point("G", offset=-l / 2 * R.y))
    s.pin("O", s.origin, rod, axis="S.z")
    s.gravity(g, -s.inertial.y)
    sol = s.solve()
    assert _zero(sol.accelerations[th] - (Om**2 * sp.cos(th) - 3 * g / (2 * l)) * sp.sin(th))
    u = sp.Symbol("u", positive=True)
    H_axis = sp.integrate(m / l * (u * sp.sin(th))**2 * Om, (u, 0, l))
    assert _zero(sol.reactions["M_Oy"] - sp.diff(H_axis, t))


def test_pin_at_a_point_moved_by_a_law():
    """A pendulum pinned at a point that moves as A cos ωt, with no support body: the pin moves with the point,
    and its reaction is the force the support must give."""
    v = rk.System("vibrating-pin")
    A, w = v.parameter("A", "m"), v.parameter("omega", "rad/s")
    m, l, g = v.parameter("m", "kg"), v.parameter("l", "m"), v.parameter("g", "m/s^2")
    th = v.coordinate("theta")
    P = v.point("P", offset=A * sp.cos(w * t) * v.inertial.y)
    R = v.frame("R", angle=th)
    bob = v.body("bob", rk.shapes.PointMass(m), frame=R, at=v.point("B", P, offset=-l * R.y))
    v.pin("P", P, bob)
    v.gravity(g)
    sol = v.solve()
    acc = sol.accelerations[th]
    assert _zero(l * acc + (g - A * w**2 * sp.cos(w * t)) * sp.sin(th))
    yB = A * sp.cos(w * t) - l * sp.cos(th)
    assert _zero(sol.reactions["R_Py"] - m * (sp.diff(yB, t, 2).subs(th.diff(t, 2), acc) + g))


def test_hinge_against_a_prescribed_motion_is_refused_with_the_way_out():
    """A hinge to the ground whose axis is fixed in the rod (not in the turning shaft) forbids the rotation the
    law imposes: refused, saying what to write instead."""
    s = rk.System("bad")
    m, l = s.parameter("m", "kg"), s.parameter("l", "m")
    Om = s.parameter("Omega", "rad/s")
    th = s.coordinate("theta")
    S = s.frame("S", angle=Om * t, axis="y")
    R = s.frame("R", S, angle=th, axis="z")
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=s.point("G", offset=-l / 2 * R.y))
    s.pin("O", s.origin, rod, axis="R.z")
    with pytest.raises(ConstraintError) as err:
        s.solve()
    msg = str(err.value)
    assert "hinge O: rotation about" in msg and "prescribed" in msg and "s.drive" in msg


def test_a_driven_body_needs_a_prescribed_motion():
    s = rk.System("bad")
    th = s.coordinate("theta")
    S = s.frame("S", angle=th)
    with pytest.raises(ModelError, match="turns with the coordinate"):
        s.drive("shaft", S)
    with pytest.raises(ModelError, match="is the ground"):
        s.drive("still", s.inertial)


def test_pendulum_on_a_vibrating_support():
    """The support moves as A cos ωt along Ey: l θ̈ = −(g − A ω² cos ωt) sin θ, and the force it needs."""
    s = rk.System("vibrating")
    m, l, g = s.parameter("m", "kg", value=1.0), s.parameter("l", "m", value=0.5), s.parameter("g", "m/s^2", value=9.81)
    A, w = s.parameter("A", "m", value=0.02), s.parameter("omega", "rad/s", value=40.0)
    th = s.coordinate("theta", "angle from the downward vertical", initial=0.3)
    F = s.inertial
    P = s.point("P", offset=A * sp.cos(w * t) * F.y)
    s.drive("support", F, at=P)
    R = s.frame("R", angle=th)
    bob = s.body("bob", rk.shapes.PointMass(m), frame=R, at=s.point("B", P, offset=-l * R.y))
    s.pin("P", P, bob, "support")
    s.gravity(g)
    sol = s.solve()
    acc = sol.accelerations[th]
    assert _zero(l * acc + (g - A * w**2 * sp.cos(w * t)) * sp.sin(th))
    # Euler's 1st law for the bob (the support is massless): the support's force is m a_B + m g Ey
    xB, yB = l * sp.sin(th), A * sp.cos(w * t) - l * sp.cos(th)
    sub = {th.diff(t, 2): acc}
    Fx = sol.reactions["F_supportx"]
    Fy = sol.reactions["F_supporty"]
    assert _zero(Fx - m * sp.diff(xB, t, 2).subs(sub))
    assert _zero(Fy - m * (sp.diff(yB, t, 2).subs(sub) + g))
    assert _zero(sol.reactions["M_supportz"])
    # the laws that eliminate the reactions agree, t and all
    assert _zero(s.solve("lagrange").accelerations[th] - acc)


def test_bead_in_a_slot_of_a_turntable_2d():
    """A bead in a smooth radial slot of a turntable turned at Ω (planar): r̈ = Ω² r, the slot pushes with
    N = 2 m Ω ṙ (Coriolis), and the turntable needs T = d/dt (m r² Ω) = 2 m Ω r ṙ."""
    s = rk.System("turntable")
    m, Om = s.parameter("m", "kg", value=0.2), s.parameter("Omega", "rad/s", value=3.0)
    x = s.coordinate("x", "bead along the slot", kind="length", initial=0.1)
    y = s.coordinate("y", "bead across the slot", kind="length")
    T = s.frame("T", angle=Om * t)
    table = s.drive("table", T, description="a massless turntable")
    bead = s.body("bead", rk.shapes.PointMass(m), frame=T, at=s.point("B", offset=x * T.x + y * T.y))
    s.contact("slot", bead, s.line(s.origin, T.y, body=table), unilateral=False)
    sol = s.solve()
    assert tuple(sol.coordinates) == (x,)                      # y is held by the slot
    assert _zero(sol.accelerations[x] - Om**2 * x)
    N = sol.reactions["N_slot"]
    assert _zero(N - 2 * m * Om * x.diff(t))
    assert _zero(sol.reactions["T_table"] - sp.diff(m * x**2 * Om, t))


def test_problem_file_through_the_command_line(tmp_path):
    """The bundled problem file (a driven body in [bodies]) solved by ``python -m rigidkin solve``."""
    run = rigidkin_process("solve", "driven-shaft", "--format", "json", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    out = json.loads(run.stdout)
    theta = sp.Function("theta")(t)
    names = {"theta": sp.Function("theta"), "t": t, **{n: sp.Symbol(n, positive=True) for n in
                                                        ("m", "l", "g", "Omega")}}
    m, l, g, Om = (names[n] for n in ("m", "l", "g", "Omega"))
    acc = sp.sympify(out["accelerations"]["theta"], locals=names)
    assert _zero(acc - (Om**2 * sp.cos(theta) - 3 * g / (2 * l)) * sp.sin(theta))
    T = sp.sympify(out["reactions"]["T_motor"], locals=names)
    assert _zero(T - m * l**2 * Om * sp.sin(2 * theta) * theta.diff(t) / 3)
    assert "T_motor = Ω·m·l²·θ̇·sin(2·θ)/3" in out["answer_text"]["motor_torque"]
    eq = out["answer_text"]["relative_equilibrium"]
    assert "acos(3·g/(2·Ω²·l))" in eq and "stable" in eq


def test_bundled_example_python_and_file_agree(shaft):
    _, sol, (m, l, g, Om, th) = shaft
    py = examples.build("driven-shaft").solve()
    text = (examples.HERE / "driven-shaft.toml").read_text()
    fs = parse_problem(text[:text.find("[[ask.question]]")], "driven-shaft.toml")[0].solve()
    for other in (py, fs):
        assert _zero(other.accelerations[th] - sol.accelerations[th])
        assert _zero(other.reactions["T_motor"]
                     - sol.reactions["T_shaft"])


def test_free_body_diagram_shows_the_drive_torque(shaft):
    from rigidkin.report.fbd import free_body_diagram

    s, sol, _ = shaft
    fbd = free_body_diagram(sol)
    on_shaft = fbd.loads_on("shaft")
    assert any(d.reaction == "T_shaft" and d.kind == "torque" for d in on_shaft)
    assert any(d.reaction == "F_shafty" and d.kind == "force" for d in on_shaft)
    fbd.close()


def test_equilibrium_refused_where_the_law_of_t_stays_in_the_equations():
    """A support vibrating as A cos ωt leaves t in the EOM: no equilibrium, said with the reason (the hanging
    state is not called unstable with a frequency that depends on t)."""
    from rigidkin.analysis.equilibrium import equilibria

    s = rk.System("vibrating")
    m, l, g = s.parameter("m", "kg", value=1.0), s.parameter("l", "m", value=0.5), s.parameter("g", "m/s^2", value=9.81)
    A, w = s.parameter("A", "m", value=0.02), s.parameter("omega", "rad/s", value=40.0)
    th = s.coordinate("theta", "angle from the downward vertical", initial=0.3)
    P = s.point("P", offset=A * sp.cos(w * t) * s.inertial.y)
    s.drive("support", s.inertial, at=P)
    R = s.frame("R", angle=th)
    bob = s.body("bob", rk.shapes.PointMass(m), frame=R, at=s.point("B", P, offset=-l * R.y))
    s.pin("P", P, bob, "support")
    s.gravity(g)
    with pytest.raises(rk.RigidkinError, match="depend on t explicitly"):
        equilibria(s.solve())


def test_reactions_at_an_instant(shaft):
    """``reactions_at`` takes the instant t of a driven motion: F_shaftx turns with the shaft."""
    s, sol, (m, l, g, Om, th) = shaft
    state = {th: 0.7, th.diff(t): 1.3}
    vals = {m: 2.0, l: 0.8, g: 9.81, Om: 6.0}
    for when in (0.0, 0.4):
        got = sol.reactions_at({**state, t: when})
        for name in ("F_shaftx", "F_shaftz", "T_shaft"):
            want = float(sol.reactions[name].subs(state).subs(vals).subs(t, when))
            assert abs(got[name] - want) < 1e-9 * max(1.0, abs(want)), (name, when)
    assert abs(sol.reactions_at({**state, t: 0.0})["F_shaftx"] - sol.reactions_at({**state, t: 0.4})["F_shaftx"]) > 0.1


def test_sphere_rolling_on_a_turntable_3d():
    """A uniform sphere (radius a) rolling on a massless turntable turned at Ω: its centre's velocity turns at
    (2/7)Ω, v̇ = (2/7) Ω ez × v, so the spin's horizontal part changes as a ω̇_h × ez = v̇ − Ω ez × v
    = −(5/7) Ω ez × v (no slip: v = ω × a ez + Ω ez × r).  Checked at a state where the body axes are the
    inertial ones (quaternion 1), with the accelerations from M u̇ = f."""
    from rigidkin.derive.evaluation import accelerations_at

    s = rk.System("ball-on-turntable")
    m, a = s.parameter("m", "kg", value=0.1), s.parameter("a", "m", value=0.02)
    Om, g = s.parameter("Omega", "rad/s", value=3.0), s.parameter("g", "m/s^2", value=9.81)
    x, y, z = (s.coordinate(n, f"centre along E{n}", kind="length") for n in "xyz")
    F = s.inertial
    table = s.drive("table", s.frame("T", angle=Om * t))
    B = s.frame("B", quaternion=True)
    ball = s.body("ball", rk.shapes.SolidSphere(m, a), frame=B, at=s.point("C", offset=x * F.x + y * F.y + z * F.z))
    s.contact("P", ball, s.plane(s.origin, F.z, body=table), radius=a, friction="rolling", unilateral=False)
    s.gravity(g, -F.z)
    sol = s.solve()
    e = [s.coordinate_info[f"B_e{i}"].symbol for i in range(4)]
    w = (0.7, -0.4, 1.1)
    r = (0.1, -0.05)
    state = {x: r[0], y: r[1], z: 0.02, e[0]: 1.0, e[1]: 0.0, e[2]: 0.0, e[3]: 0.0}
    state.update({q.diff(t): wi for q, wi in zip(sol.coordinates, w)})      # the body's angular speeds
    dw = list(accelerations_at(sol, state).values())
    Omega, rad = 3.0, 0.02
    vx, vy = w[1] * rad - Omega * r[1], -w[0] * rad + Omega * r[0]
    assert dw[0] == pytest.approx(5 / 7 * Omega * vx / rad, rel=1e-9)
    assert dw[1] == pytest.approx(5 / 7 * Omega * vy / rad, rel=1e-9)
    assert dw[2] == pytest.approx(0.0, abs=1e-9)


def test_driven_arm_with_mass_turned_by_a_law():
    """A uniform rod (mass m, length l) turned about its end O in a vertical plane by the law φ = φ0 sin ωt:
    the motor at O must give T = I_O φ̈ + m g (l/2) sin φ (Euler's 2nd law about the fixed point O), and the
    joint force is m a_G − m g; a second rod hinged at its tip swings under it (a driven double pendulum)."""
    s = rk.System("driven-arm")
    m, l, g = s.parameter("m", "kg", value=1.5), s.parameter("l", "m", value=0.6), s.parameter("g", "m/s^2", value=9.81)
    p0, w = s.parameter("phi0", "rad", value=0.4), s.parameter("omega", "rad/s", value=2.0)
    th = s.coordinate("theta", "angle of the hanging rod from the downward vertical", initial=0.2)
    phi = p0 * sp.sin(w * t)
    A = s.frame("A", angle=phi)
    arm = s.drive("arm", A, at=s.point("G1", offset=-l / 2 * A.y), shape=rk.shapes.SlenderRod(m, l, axis="y"),
                  joint=s.origin, torque="T_motor")
    tip = s.point("tip", offset=-l * A.y)
    R = s.frame("R", angle=th)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=s.point("G2", tip, offset=-l / 2 * R.y))
    s.pin("tip", tip, rod, arm)
    s.gravity(g)
    sol = s.solve()
    # by hand: the hanging rod's pin force Q at the tip (from Euler's 1st law for it) acts on the arm at the tip;
    # about O: T − m g (l/2) sin φ + (r_tip × (−Q))·Ez = (⅓ m l²) φ̈
    acc = sol.accelerations[th]
    sub = {th.diff(t, 2): acc}
    xt, yt = l * sp.sin(phi), -l * sp.cos(phi)
    x2, y2 = xt + l / 2 * sp.sin(th), yt - l / 2 * sp.cos(th)
    Qx = m * sp.diff(x2, t, 2).subs(sub)
    Qy = m * (sp.diff(y2, t, 2).subs(sub) + g)
    T_hand = m * l**2 / 3 * sp.diff(phi, t, 2) + m * g * l / 2 * sp.sin(phi) + (xt * Qy - yt * Qx)
    vals = {m: 1.5, l: 0.6, g: 9.81, p0: 0.4, w: 2.0}
    T = sol.reactions["T_motor"]
    for st in ({th: 0.3, th.diff(t): -1.2, t: 0.7}, {th: -1.0, th.diff(t): 0.5, t: 2.1}):
        a = float(T.subs(st).subs(vals))
        b = float(T_hand.subs(st).subs(vals))
        assert a == pytest.approx(b, rel=1e-9), st
        assert abs(a) > 0.05
    # the hanging rod: (⅓ m l²) θ̈ about the tip, with the tip's acceleration as a moving support
    at = [sp.diff(xt, t, 2), sp.diff(yt, t, 2)]
    hand = (-(m * g + m * at[1]) * l / 2 * sp.sin(th) - m * at[0] * l / 2 * sp.cos(th)) / (m * l**2 / 3)
    assert _zero(acc - hand)
    for method in ("lagrange", "kane"):
        assert _zero(s.solve(method).accelerations[th] - acc), method


def test_rotor_spun_on_a_free_pendulum_by_a_motor():
    """A disk (mass M, radius r) at the end of a pendulum rod (mass m, length l), spun relative to the rod by a
    motor at a constant rate s (carrier=): the disk's absolute rate is θ̇ + s, so the spin adds nothing to the
    EOM, (⅓ m l² + M l² + ½ M r²) θ̈ = −(m l/2 + M l) g sin θ, and the motor torque is the rate of the disk's
    spin momentum, T = ½ M r² θ̈ (Euler's 2nd law for the disk about its centre); the rod takes −T."""
    s = rk.System("rotor-pendulum")
    m, M, l = s.parameter("m", "kg", value=1.0), s.parameter("M", "kg", value=2.0), s.parameter("l", "m", value=0.5)
    r, g, sp_rate = s.parameter("r", "m", value=0.1), s.parameter("g", "m/s^2", value=9.81), s.parameter("s", "rad/s")
    th = s.coordinate("theta", "angle of the rod from the downward vertical", initial=0.4)
    A = s.frame("A", angle=th)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=A, at=s.point("G", offset=-l / 2 * A.y))
    s.pin("O", s.origin, rod)
    D = s.frame("D", A, angle=sp_rate * t, description="turned by the motor relative to the rod")
    C = s.point("C", offset=-l * A.y, body=rod)
    s.drive("rotor", D, at=C, shape=rk.shapes.Disk(M, r, axis="z"), carrier=rod, torque="T_motor")
    s.gravity(g)
    sol = s.solve()
    I = m * l**2 / 3 + M * l**2 + M * r**2 / 2
    acc = sol.accelerations[th]
    assert _zero(acc + (m * l / 2 + M * l) * g * sp.sin(th) / I)
    assert _zero(sol.reactions["T_motor"] - M * r**2 / 2 * acc)
    assert not sol.reactions["T_motor"].has(sp_rate)
    # the pin at O carries the whole: its force is the total mass times the acceleration of the mass centre + weight
    for method in ("lagrange", "kane"):
        assert _zero(s.solve(method).accelerations[th] - acc), method


def test_a_carrier_drive_needs_a_law_relative_to_the_carrier():
    s = rk.System("bad-carrier")
    m, l = s.parameter("m", "kg"), s.parameter("l", "m")
    th = s.coordinate("theta")
    A = s.frame("A", angle=th)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=A, at=s.point("G", offset=-l / 2 * A.y))
    s.pin("O", s.origin, rod)
    # the rotor's frame is turned from the ground, not from the rod: relative to the rod it turns by −θ
    D = s.frame("D", angle=t)
    s.drive("rotor", D, at=s.point("C", offset=-l * A.y, body=rod), shape=rk.shapes.Disk(m, l, axis="z"),
            carrier=rod)
    with pytest.raises(ModelError, match="not prescribed"):
        s.solve()


def test_relative_equilibrium_answer_of_the_shaft(shaft):
    """``equilibria`` finds cos θ* = 3g/(2lΩ²), stable, with ω_n = Ω sin θ* (the small oscillation of a
    one-arm governor), and calls it a relative equilibrium."""
    from rigidkin.analysis.equilibrium import equilibria

    s, sol, (m, l, g, Om, th) = shaft
    found = equilibria(sol)
    star = sp.acos(3 * g / (2 * l * Om**2))
    hits = [e for e in found if _zero(e.configuration[th] - star)]
    assert len(hits) == 1
    e = hits[0]
    assert e.stability.startswith("stable")
    assert _zero(e.natural_frequencies[0]**2 - Om**2 * sp.sin(star)**2)
    assert str(e).startswith("relative equilibrium")


ROTOR_FILE = """
title = "Rotor spun on a pendulum"
[parameters]
m = { unit = "kg", value = 1 }
M = { unit = "kg", value = 2 }
l = { unit = "m", value = 0.5 }
r = { unit = "m", value = 0.1 }
g = { unit = "m/s^2", value = 9.81 }
s = { unit = "rad/s", value = 30 }
[coordinates]
theta = { sense = "angle of the rod from the downward vertical", initial = 0.4 }
[frames]
A = { angle = "theta", basis = ["ax", "ay", "az"] }
D = { parent = "A", angle = "s*t", basis = ["dx", "dy", "dz"] }
[points]
G = { offset = "-l/2*ay" }
C = { offset = "-l*ay", body = "arm" }
Cr = { from = "C" }
[bodies]
arm = { shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "A", at = "G" }
rotor = { shape = "disk", mass = "M", radius = "r", length = "r/10", axis = "z", frame = "D", at = "Cr", \
driven = true, drive_carrier = "arm", drive_joint = "C", drive_torque = "T_motor" }
[constraints]
O = { type = "pin", point = "O", body_a = "arm" }
[loads]
gravity = { type = "gravity", g = "g" }
"""


def test_drive_on_a_carrier_in_a_problem_file():
    s, _ = parse_problem(ROTOR_FILE, "rotor.toml")
    sol = s.solve()
    P = {n: sym for n, sym in s.parameters.items()}
    th = s.coordinate_info["theta"].symbol
    M, m, l, r, g = (P[n] for n in ("M", "m", "l", "r", "g"))
    I_rotor = M * r**2 / 2                    # a disk (solid cylinder) about its axis, whatever its length
    I = m * l**2 / 3 + M * l**2 + I_rotor
    acc = sol.accelerations[th]
    assert _zero(acc + (m * l / 2 + M * l) * g * sp.sin(th) / I)
    assert _zero(sol.reactions["T_motor"] - I_rotor * acc)


def test_drive_fields_without_driven_are_refused():
    text = ROTOR_FILE.replace("driven = true, ", "")
    with pytest.raises(rk.InputError, match="driven body"):
        parse_problem(text, "rotor.toml")
