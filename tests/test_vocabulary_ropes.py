"""Issue 15: profiles that are arcs (half shapes touch with their curved face only) and ropes over
pulleys with inertia (no slip, a tension per segment, belt friction).

Every expected value is derived by hand in the test's docstring (closed forms), never read from the
engine.
"""

import numpy as np
import pytest
import sympy as sp
from test_vocabulary import rolling_disk

import rigidkin as rk
from rigidkin.base.errors import RigidkinError
from rigidkin.io.problem import parse_problem

t = sp.Symbol("t")


# 3. profiles that are arcs --------------------------------------------------------------------------------
HALF = """
title = "Half cylinder rocking on the floor"
[parameters]
m = { unit = "kg", value = 1 }
r = { unit = "m", value = 0.1 }
g = { unit = "m/s^2", value = 9.81 }
[coordinates]
theta = { sense = "rotation, counter-clockwise", initial = 0, rate = 15 }
x = { sense = "centre of the flat face along Ex", kind = "length" }
[frames]
B = { angle = "theta" }
[points]
O1 = { offset = "x*Ex + r*Ey", description = "centre of the flat face" }
[bodies]
half = { shape = "half_cylinder", mass = "m", radius = "r", frame = "B", at = "O1", toward = "-y" }
[constraints.P]
type = "contact"
body = "half"
centre = "O1"
surface = { type = "line", point = "O", normal = "Ey", name = "floor" }
radius = "r"
friction = "rolling"
ARC
[loads]
gravity = { type = "gravity", g = "g" }
"""


def half_cylinder(arc: str = ""):
    system, _ = parse_problem(HALF.replace("ARC", arc), "half.toml")
    return system, system.coordinates[0]


def test_half_cylinder_touches_only_on_its_curved_half():
    """The curved face (toward −B.y) touches while the downward direction is within π/2 of −B.y:
    (−Ey)·(−B.y) = cos θ ≥ 0."""
    system, th = half_cylinder()
    sol = system.solve()
    arcs = [c for c in sol.validity if "on its arc" in c.label]
    assert len(arcs) == 1 and sp.simplify(arcs[0].expr - sp.cos(th)) == 0


def test_equilibria_off_the_arc_are_not_equilibria():
    """Only θ = 0 remains (θ = π puts the contact on the missing half); rocking without slip about it:
    ω² = m g b / I_P with b = 4r/(3π), I_P = m(3r²/2 − 2 r b), i.e. ω² = 8g/(r(9π − 16))."""
    from rigidkin.analysis.equilibrium import equilibria

    system, th = half_cylinder()
    eqs = equilibria(system.solve())
    assert [e.configuration[th] for e in eqs] == [0]
    g, r = system.parameters["g"], system.parameters["r"]
    assert sp.simplify(eqs[0].natural_frequencies[0] ** 2 - 8 * g / (r * (9 * sp.pi - 16))) == 0
    full, th2 = half_cylinder("arc = false")
    assert sorted(float(e.configuration[th2]) for e in equilibria(full.solve())) == [0.0, pytest.approx(np.pi)]


def test_simulation_stops_where_the_curved_face_ends():
    """Released at θ = 0 with θ̇0 = 15 rad/s it rolls to θ = π/2, where the edge meets the floor.
    Energy: ½ I_P(0) θ̇0² + m g (r − b) = ½ I_P(π/2) θ̇² + m g r, I_P(π/2) = 3 m r²/2."""
    from rigidkin.numeric.simulate import simulate

    system, th = half_cylinder()
    res = simulate(system, 2.0)
    assert res.stop_reason == "arc-end"
    assert res.final_state["theta"] == pytest.approx(np.pi / 2, abs=1e-8)
    r, g = 0.1, 9.81
    b = 4 * r / (3 * np.pi)
    w2 = ((1.5 * r**2 - 2 * r * b) * 15**2 - 2 * g * b) / (1.5 * r**2)
    assert res.final_state["dot(theta)"] == pytest.approx(np.sqrt(w2), rel=1e-7)


def test_an_arc_given_in_the_file():
    """A quarter arc each side of −B.y narrowed to π/4: the contact holds while cos θ ≥ cos(π/4)."""
    from rigidkin.numeric.simulate import simulate

    system, th = half_cylinder('arc = { toward = "-B.y", half_angle = "pi/4" }')
    arcs = [c for c in system.solve().validity if "on its arc" in c.label]
    assert sp.simplify(arcs[0].expr - (sp.cos(th) - sp.sqrt(2) / 2)) == 0
    res = simulate(system, 2.0)
    assert res.stop_reason == "arc-end" and res.final_state["theta"] == pytest.approx(np.pi / 4, abs=1e-8)


def test_arc_toward_must_be_fixed_in_the_body():
    with pytest.raises(RigidkinError, match="fixed in half"):
        half_cylinder('arc = { toward = "-Ey" }')


# 4. ropes over pulleys with inertia -------------------------------------------------------------------------
def _hanging(s, name, x, depth, mass):
    """A block (a point mass) hanging at abscissa ``x`` and depth ``depth`` below the axle line."""
    P = s.point(name, offset=x * s.inertial.x - depth * s.inertial.y)
    s.body(f"block_{name}", rk.shapes.PointMass(mass), frame=s.inertial, at=P)
    return P


def test_atwood_machine_with_a_massive_pulley():
    """Disk pulley (M, R) on a fixed axle, blocks m1 (left) and m2 (right), no slip:
    ÿ1 = (m1 − m2) g/(m1 + m2 + M/2), T1 = m1 (g − ÿ1), T2 = m2 (g + ÿ1); R φ̇ = ẏ1 = −ẏ2."""
    from rigidkin.model.ropes import Wrap

    s = rk.System("atwood")
    m1, m2, M = s.parameter("m1", "kg", value=3), s.parameter("m2", "kg", value=1), s.parameter("M", "kg", value=2)
    R, g = s.parameter("R", "m", value=0.1), s.parameter("g", "m/s^2", value=9.81)
    y1 = s.coordinate("y1", "depth of block 1 below the axle", kind="length", initial=1.0)
    y2 = s.coordinate("y2", "depth of block 2 below the axle", kind="length", initial=1.0)
    phi = s.coordinate("phi", "pulley rotation, counter-clockwise")
    pulley = s.body("pulley", rk.shapes.Disk(M, R), frame=s.frame("P", angle=phi), at=s.origin)
    A, B = _hanging(s, "A", -R, y1, m1), _hanging(s, "B", R, y2, m2)
    s.pin("O", s.origin, pulley)
    s.rope("rope", [A, Wrap(pulley, R, "cw"), B], tensions=("T1", "T2"))
    s.gravity(g)
    sol = s.solve()
    a = (m1 - m2) * g / (m1 + m2 + M / 2)
    assert sp.simplify(sol.accelerations[y1] - a) == 0
    assert sp.simplify(sol.reactions["T1"] - m1 * (g - a)) == 0
    assert sp.simplify(sol.reactions["T2"] - m2 * (g + a)) == 0
    assert sp.simplify(sol.rate_relations[phi.diff(t)] - y1.diff(t) / R) == 0
    assert sol.check().ok and sol.warnings == ()
    taut = [c for c in sol.validity if "taut" in c.label]
    assert len(taut) == 2


def test_block_hoisted_by_a_drum():
    """Drum (I = M ρ²/2, torque τ counter-clockwise) winding the rope of a block m hanging on its right:
    ÿ = (m g − τ/ρ)/(m + I/ρ²) (y downward), T = m (g − ÿ)."""
    from rigidkin.model.ropes import Wrap

    s = rk.System("hoist")
    m, M = s.parameter("m", "kg", value=10), s.parameter("M", "kg", value=4)
    rho, g, tau = s.parameter("rho", "m", value=0.2), s.parameter("g", "m/s^2", value=9.81), \
        s.parameter("tau", "N*m", value=30)
    y = s.coordinate("y", "depth of the block below the axle", kind="length", initial=2.0)
    phi = s.coordinate("phi", "drum rotation, counter-clockwise")
    drum = s.body("drum", rk.shapes.Disk(M, rho), frame=s.frame("D", angle=phi), at=s.origin)
    A = _hanging(s, "A", rho, y, m)
    s.pin("O", s.origin, drum)
    s.torque("motor", drum, tau * s.inertial.z)
    s.rope("rope", [A, Wrap(drum, rho, "ccw")], tensions=("T",))
    s.gravity(g)
    sol = s.solve()
    I = M * rho**2 / 2
    a = (m * g - tau / rho) / (m + I / rho**2)
    assert sp.simplify(sol.accelerations[y] - a) == 0
    assert sp.simplify(sol.reactions["T"] - m * (g - a)) == 0
    assert sol.check().ok


def test_two_pulleys_fixed_and_moving():
    """Rope from a ceiling anchor down round a moving pulley (M2, r2: its own weight), up over a fixed pulley
    (M1, r1) and down to a block m.  No slip: r2 φ̇2 = −ẏ2, r1 φ̇1 = 2ẏ2, ẏ3 = −2ẏ2.  With I = M r²/2:
    ÿ2 = (M2 − 2m) g/(M2 + 4m + 4 I1/r1² + I2/r2²), T3 = m(g + 2ÿ2), T2 = T3 + 2 I1 ÿ2/r1²,
    T1 = T2 + I2 ÿ2/r2²."""
    from rigidkin.model.ropes import Wrap

    s = rk.System("two-pulleys")
    m, M1, M2 = (s.parameter(n, "kg", value=v) for n, v in (("m", 1.0), ("M1", 2.0), ("M2", 5.0)))
    r1, r2, g = s.parameter("r1", "m", value=0.1), s.parameter("r2", "m", value=0.15), \
        s.parameter("g", "m/s^2", value=9.81)
    y2 = s.coordinate("y2", "depth of the moving pulley's centre", kind="length", initial=1.0)
    y3 = s.coordinate("y3", "depth of the block", kind="length", initial=1.0)
    phi1 = s.coordinate("phi1", "fixed pulley, counter-clockwise")
    phi2 = s.coordinate("phi2", "moving pulley, counter-clockwise")
    F = s.inertial
    p1 = s.body("p1", rk.shapes.Disk(M1, r1), frame=s.frame("P1", angle=phi1), at=s.origin)
    C2 = s.point("C2", offset=-(r1 + r2) * F.x - y2 * F.y)
    p2 = s.body("p2", rk.shapes.Disk(M2, r2), frame=s.frame("P2", angle=phi2), at=C2)
    anchor = s.point("A", offset=-(r1 + 2 * r2) * F.x)
    B = _hanging(s, "B", r1, y3, m)
    s.pin("O", s.origin, p1)
    s.rope("rope", [anchor, Wrap(p2, r2, "ccw"), Wrap(p1, r1, "cw"), B], tensions=("T1", "T2", "T3"))
    s.gravity(g)
    sol = s.solve(independent=[y2])
    I1, I2 = M1 * r1**2 / 2, M2 * r2**2 / 2
    a = (M2 - 2 * m) * g / (M2 + 4 * m + 4 * I1 / r1**2 + I2 / r2**2)
    T3 = m * (g + 2 * a)
    T2 = T3 + 2 * I1 * a / r1**2
    T1 = T2 + I2 * a / r2**2
    assert sp.simplify(sol.accelerations[y2] - a) == 0
    for name, expected in (("T1", T1), ("T2", T2), ("T3", T3)):
        assert sp.simplify(sol.reactions[name] - expected) == 0, name
    assert sp.simplify(sol.rate_relations[y3.diff(t)] + 2 * y2.diff(t)) == 0
    assert sol.warnings == ()


def test_rope_errors_name_the_problem():
    from rigidkin.model.ropes import Wrap

    s, disk, T, th, m, r = rolling_disk()
    with pytest.raises(rk.ModelError, match="tension names"):
        s.rope("r1", [s.origin, Wrap(disk, r, "cw"), s.origin], tensions=("T1",))
    with pytest.raises(rk.ModelError, match="end T of the rope moves relative to the ground"):
        s.rope("r2", [s.origin, Wrap(disk, r, "cw"), T])
    with pytest.raises(rk.ModelError, match="'cw' or 'ccw'"):
        s.rope("r3", [s.origin, Wrap(disk, r, "left")])


ATWOOD_FILE = """
title = "Atwood machine with a massive pulley"
[parameters]
m1 = { unit = "kg", value = 3 }
m2 = { unit = "kg", value = 1 }
M = { unit = "kg", value = 2 }
R = { unit = "m", value = 0.1 }
g = { unit = "m/s^2", value = 9.81 }
[coordinates]
y1 = { sense = "depth of block 1 below the axle", kind = "length", initial = 1, rate = 0 }
y2 = { sense = "depth of block 2 below the axle", kind = "length", initial = 1 }
phi = { sense = "pulley rotation, counter-clockwise" }
[frames]
P = { angle = "phi" }
[points]
A = { offset = "-R*Ex - y1*Ey" }
B = { offset = "R*Ex - y2*Ey" }
[bodies]
pulley = { shape = "disk", mass = "M", radius = "R", frame = "P", at = "O" }
block1 = { shape = "point_mass", mass = "m1", frame = "F", at = "A" }
block2 = { shape = "point_mass", mass = "m2", frame = "F", at = "B" }
[constraints]
axle = { type = "pin", point = "O", body_a = "pulley" }
rope = { type = "rope", path = ["A", { pulley = "pulley", radius = "R", sense = "cw" }, "B"], tensions = ["T1", "T2"] }
[loads]
gravity = { type = "gravity", g = "g" }
"""


def test_rope_in_a_problem_file_solved_and_simulated():
    """ÿ1 = (m1 − m2) g/(m1 + m2 + M/2) = 2g/5 with the values; from rest y1(t) = 1 + ÿ1 t²/2."""
    from rigidkin.numeric.simulate import simulate
    from rigidkin.report.text import problem_text

    system, _ = parse_problem(ATWOOD_FILE, "atwood.toml")
    sol = system.solve()
    m1, m2, M, g = (system.parameters[n] for n in ("m1", "m2", "M", "g"))
    y1 = system.coordinates[0]
    assert sp.simplify(sol.accelerations[y1] - (m1 - m2) * g / (m1 + m2 + M / 2)) == 0
    assert "T1: tension of rope rope between A and pulley" in problem_text(sol)
    res = simulate(system, 0.5)
    assert res.final_state["y1"] == pytest.approx(1 + 0.5 * (2 * 9.81 / 5) * 0.25, rel=1e-9)


def test_rope_file_errors_name_the_field():
    bad = ATWOOD_FILE.replace('sense = "cw"', 'sense = "left"')
    with pytest.raises(RigidkinError, match="atwood.toml, line"):
        parse_problem(bad, "atwood.toml")
    bad = ATWOOD_FILE.replace('{ pulley = "pulley"', '{ pulley = "wheel"')
    with pytest.raises(RigidkinError, match="no body named 'wheel'"):
        parse_problem(bad, "atwood.toml")



def test_belt_friction_on_a_pulley_capstan():
    """With µ on the pulley the rope grips while T1 ≤ T2 e^{µπ} and T2 ≤ T1 e^{µπ} (wrap angle π): with
    T1 = m1 g (M + 4 m2)/(M + 2m1 + 2m2) and T2 = m2 g (M + 4 m1)/(…)."""
    text = ATWOOD_FILE.replace('sense = "cw" }', 'sense = "cw", mu = "mu" }').replace(
        '[coordinates]', 'mu = { unit = "", value = 0.3 }\n[coordinates]')
    system, _ = parse_problem(text, "atwood.toml")
    sol = system.solve()
    m1, m2, M, g, mu = (system.parameters[n] for n in ("m1", "m2", "M", "g", "mu"))
    T1 = g * m1 * (M + 4 * m2) / (M + 2 * m1 + 2 * m2)
    T2 = g * m2 * (M + 4 * m1) / (M + 2 * m1 + 2 * m2)
    grips = [c.expr for c in sol.validity if "grips" in c.label]
    wanted = [T1 * sp.exp(mu * sp.pi) - T2, T2 * sp.exp(mu * sp.pi) - T1]
    assert len(grips) == 2 and all(any(sp.simplify(gx - w) == 0 for gx in grips) for w in wanted)


def test_half_shapes_carry_their_arcs_only_on_their_curved_face():
    """A hemisphere touching by its curved face (centre O, radius r) has the arc π/2 about toward; a
    contact at another centre or radius (or arc=False) is a full circle."""
    s = rk.System("bowl")
    m, r = s.parameter("m", "kg"), s.parameter("r", "m")
    th = s.coordinate("theta", "tilt")
    B = s.frame("B", angle=th)
    O1 = s.point("O1", s.origin, r * s.inertial.y)
    h = s.body("h", rk.shapes.Hemisphere(m, r, toward="-y"), frame=B, at=O1)
    floor = s.line(s.origin, s.inertial.y)
    c = s.contact("P", h, floor, centre=O1, radius=r)
    assert c.arc is not None and c.arc.half_angle == sp.pi / 2 and c.arc.toward == -B.y
    assert s.contact("Q", h, floor, centre=O1, radius=r, arc=False).arc is None
    assert s.contact("S", h, floor, centre=h.centre, radius=r / 2).arc is None


def test_simulation_stops_when_the_rope_goes_slack():
    """A motor torque c t (counter-clockwise) on the Atwood pulley: (m1 + m2 + M/2) ÿ1 = (m1 − m2) g + c t/R,
    T1 = m1 (g − ÿ1) reaches zero when ÿ1 = g, at t* = R g (2 m2 + M/2)/c; until then the energy balance
    (with the motor's work) holds."""
    from rigidkin.model.ropes import Wrap
    from rigidkin.numeric.simulate import simulate

    s = rk.System("atwood with a motor")
    m1, m2, M = s.parameter("m1", "kg", value=3), s.parameter("m2", "kg", value=1), s.parameter("M", "kg", value=2)
    R, g, c = s.parameter("R", "m", value=0.1), s.parameter("g", "m/s^2", value=9.81), \
        s.parameter("c", "N*m/s", value=2.0)
    y1 = s.coordinate("y1", "depth of block 1 below the axle", kind="length", initial=1.0, rate=0)
    y2 = s.coordinate("y2", "depth of block 2 below the axle", kind="length", initial=1.0)
    phi = s.coordinate("phi", "pulley rotation, counter-clockwise")
    pulley = s.body("pulley", rk.shapes.Disk(M, R), frame=s.frame("P", angle=phi), at=s.origin)
    A, B = _hanging(s, "A", -R, y1, m1), _hanging(s, "B", R, y2, m2)
    s.pin("O", s.origin, pulley)
    s.torque("motor", pulley, c * rk.t * s.inertial.z)
    s.rope("rope", [A, Wrap(pulley, R, "cw"), B], tensions=("T1", "T2"))
    s.gravity(g)
    res = simulate(s, 2.0)
    t_star = 0.1 * 9.81 * (2 * 1 + 2 / 2) / 2.0
    assert res.stop_reason == "slack" and res.t_final == pytest.approx(t_star, rel=1e-9)
    # y1(t) = 1 + ((m1 − m2) g t²/2 + c t³/(6R))/(m1 + m2 + M/2)
    y_star = 1 + ((3 - 1) * 9.81 * t_star**2 / 2 + 2.0 * t_star**3 / (6 * 0.1)) / (3 + 1 + 1)
    assert res.final_state["y1"] == pytest.approx(y_star, rel=1e-9)
    assert res.energy_drift < 1e-8
