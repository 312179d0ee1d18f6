"""Problem files: each bundled card's TOML builds the same model as its Python example (names, values,
senses, frames, points, bodies, constraints, loads), and its [ask] becomes typed Question objects."""

import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin.base.errors import RigidkinError
from rigidkin.examples import HERE, build, names
from rigidkin.io.expressions import slip
from rigidkin.io.problem import load_problem
from rigidkin.model.constraints import Coulomb

t = dynamicsymbols._t
CARDS = ["boulder-push", "collar-force", "collar-rod", "disk-in-track", "disk-spring-incline", "ladder",
         "paper-pull", "rod-impulse", "slip-to-roll", "sphere-on-sphere"]


def test_every_card_has_a_problem_file():
    for card in CARDS:
        assert card in names()
        assert (HERE / f"{card}.toml").exists(), card
        assert (HERE / f"{card.replace('-', '_')}.py").exists(), card


def _same(a, b) -> bool:
    return sp.simplify(sp.sympify(a) - sp.sympify(b)) == 0


def _vec_same(u, frame_u, v, frame_v) -> bool:
    """Two vectors of two systems: equal components in each system's inertial frame."""
    return all(_same(a, b) for a, b in zip(u.to_matrix(frame_u), v.to_matrix(frame_v)))


@pytest.mark.parametrize("card", CARDS)
def test_file_builds_the_python_model(card):
    s, spec = load_problem(HERE / f"{card}.toml")
    p = build(card)
    assert (s.name, s.title, s.statement) == (p.name, p.title, p.statement)
    assert spec.name == card and spec.title == p.title
    # parameters: names, units, values in SI, descriptions, assumptions
    assert list(s.parameter_info) == list(p.parameter_info)
    for name, a in s.parameter_info.items():
        b = p.parameter_info[name]
        assert (a.symbol, a.unit, a.description, a.dimension) == (b.symbol, b.unit, b.description, b.dimension)
        assert a.value == pytest.approx(b.value, rel=1e-15), name
    # coordinates: order (the first are independent), senses, kinds, initial state
    assert s.coordinates == p.coordinates
    for name, a in s.coordinate_info.items():
        b = p.coordinate_info[name]
        assert (a.sense, a.kind, a.dimension, a.initial, a.rate) == (b.sense, b.kind, b.dimension, b.initial, b.rate)
    # frames: basis names and orientation
    assert list(s.frames) == list(p.frames)
    for name, fa in s.frames.items():
        fb = p.frames[name]
        assert fa.basis == fb.basis and fa.description == fb.description
        if fa.parent is not None:
            assert fa.parent.name == fb.parent.name
            assert all(_same(x, y) for x, y in zip(fa.ref.dcm(s.inertial.ref), fb.ref.dcm(p.inertial.ref)))
    # points: where they are and which body they are fixed in
    assert set(s.points) == set(p.points)
    for name, pa in s.points.items():
        pb = p.points[name]
        assert _vec_same(pa.position(), s.inertial.ref, pb.position(), p.inertial.ref), name
        assert (pa.body.name if pa.body else None) == (pb.body.name if pb.body else None), name
    # bodies
    assert list(s.bodies) == list(p.bodies)
    for name, ba in s.bodies.items():
        bb = p.bodies[name]
        assert type(ba.shape) is type(bb.shape) and ba.shape == bb.shape
        assert (ba.frame.name, ba.reference.name, ba.centre.name) == (bb.frame.name, bb.reference.name, bb.centre.name)
    # constraints and loads: kinds, reactions, friction models
    assert list(s.constraints) == list(p.constraints)
    for name, ca in s.constraints.items():
        cb = p.constraints[name]
        assert type(ca) is type(cb) and ca.reactions() == cb.reactions()
        fa, fb = getattr(ca, "friction", None), getattr(cb, "friction", None)
        assert (fa == fb) if not isinstance(fb, Coulomb) else _same(fa.mu, fb.mu)
    assert list(s.loads) == list(p.loads)
    for name, la in s.loads.items():
        assert type(la) is type(p.loads[name])


def test_questions_are_typed():
    s, spec = load_problem(HERE / "ladder.toml")
    th = s.coordinates[0]
    assert spec.eom is True and spec.reactions == ("N_A", "N_B")
    q = {q.name: q for q in spec.questions}
    ev = q["leaves_wall"]
    assert ev.kind == "event" and ev.fields["when"] == sp.Eq(sp.Symbol("N_A", real=True), 0)
    assert ev.fields["start"] == {th: 0, th.diff(t): 0}
    assert "ladder.toml, line" in ev.where and "ask.question[1]" in ev.where
    assert q["wall_reaction"].fields["reaction"] == "N_A"

    s, spec = load_problem(HERE / "slip-to-roll.toml")
    (ph,) = spec.questions
    phases = ph.fields["phase"]
    assert [p["name"] for p in phases] == ["frictionless", "sliding", "rolling"]
    mu, d = s.parameters["mu"], s.parameters["d"]
    x = s.coordinates[0]
    assert phases[0]["set"] == {mu: 0} and phases[0]["until"] == sp.Eq(x, d)
    assert phases[1]["until"] == sp.Eq(slip(sp.Symbol("ground")), 0)
    assert phases[2]["mode"] == {"ground": "stick"} and phases[2]["until"] is None

    s, spec = load_problem(HERE / "rod-impulse.toml")
    blow, largest = spec.questions
    assert largest.fields["coordinate"] == s.coordinates[0] and largest.fields["after"] == "after_blow"

    s, spec = load_problem(HERE / "paper-pull.toml")
    (iv,) = spec.questions
    x, phi = s.coordinates
    r, V = s.parameters["r"], s.parameters["V"]
    assert iv.fields["duration"] == s.parameters["dt"]
    assert iv.fields["regime"] == sp.StrictLessThan(x.diff(t) + r * phi.diff(t), V)

    s, spec = load_problem(HERE / "disk-in-track.toml")
    thr = spec.questions[1]
    N = sp.Symbol("N", real=True)
    assert thr.kind == "threshold" and thr.fields["holds"] == sp.GreaterThan(N, 0)


def test_units_are_converted(tmp_path):
    text = (HERE / "disk-spring-incline.toml").read_text()
    text = text.replace('value = "20 deg"', 'value = 20').replace('unit = "rad", description = "inclination',
                                                                  'unit = "deg", description = "inclination')
    text = text.replace('L0 = { unit = "m"', 'L0 = { unit = "cm"').replace("value = 0.5 }", "value = 50 }")
    f = tmp_path / "p.toml"
    f.write_text(text)
    s, _ = load_problem(f)
    assert s.parameter_info["beta"].value == pytest.approx(20 * 3.141592653589793 / 180)
    assert s.parameter_info["L0"].value == pytest.approx(0.5)
    assert s.parameter_info["L0"].dimension == build("disk-spring-incline").parameter_info["L0"].dimension


def test_a_duration_takes_a_unit_and_its_dimension_is_checked(tmp_path):
    """``duration = "100 ms"`` is the parameter dt = 0.1 s written as a quantity; "0.1 m" is refused, naming
    the field."""
    text = (HERE / "paper-pull.toml").read_text()
    assert 'duration = "dt"' in text
    f = tmp_path / "p.toml"
    f.write_text(text.replace('duration = "dt"', 'duration = "100 ms"'))
    _, spec = load_problem(f)
    assert float(spec.questions[0].fields["duration"]) == pytest.approx(0.1, rel=1e-15)
    f.write_text(text.replace('duration = "dt"', 'duration = "0.1 m"'))
    with pytest.raises(RigidkinError) as err:
        load_problem(f)
    assert "duration" in str(err.value)


def test_minimal_pendulum_matches_the_closed_form(tmp_path):
    f = tmp_path / "pendulum.toml"
    f.write_text('''
title = "Pendulum"
[parameters]
m = { unit = "kg" }
l = { unit = "m" }
g = { unit = "m/s^2" }
[coordinates]
theta = { sense = "from the downward vertical, counter-clockwise" }
[frames]
R = { angle = "theta" }
[points]
G = { offset = "-l/2*R.y" }
[bodies]
rod = { shape = "rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }
[constraints]
O = { type = "pin", point = "O", body_a = "rod" }
[loads]
gravity = { type = "gravity", g = "g" }
''')
    s, spec = load_problem(f)
    th = s.coordinates[0]
    g, l = s.parameters["g"], s.parameters["l"]
    assert spec.name == "pendulum" and spec.questions == ()
    assert _same(s.solve().accelerations[th], -3 * g * sp.sin(th) / (2 * l))


def test_system_scope_reads_expressions_about_a_python_model():
    from rigidkin.io import system_scope
    from rigidkin.io.expressions import parse_condition, parse_equation, parse_vector

    s = build("ladder")
    th = s.coordinates[0]
    g, l = s.parameters["g"], s.parameters["l"]
    sc = system_scope(s)
    eq = parse_equation("ddot(theta) = 3*g*sin(theta)/(2*l)", sc)
    assert _same(eq.rhs - s.solve().accelerations[th], 0) and eq.lhs == th.diff(t, 2)
    assert parse_vector("l*R.ey + x*Ex", sc) == l * s.frames["R"].y + s.coordinates[1] * s.inertial.x
    assert parse_condition("N_A >= 0", sc).lhs == sp.Symbol("N_A", real=True)
    assert _same(parse_equation("slip(A) = g", sc).rhs, g)


def test_numbers_are_in_the_parameter_unit_in_python_and_in_files(tmp_path):
    import rigidkin as rk

    p = rk.System("units")
    p.parameter("L0", "cm", value=50)
    p.parameter("beta", "deg", value=30)
    p.parameter("k", "N/m", value="3 N/cm")
    f = tmp_path / "units.toml"
    f.write_text('''title = "units"
[parameters]
L0 = { unit = "cm", value = 50 }
beta = { unit = "deg", value = 30 }
k = { unit = "N/m", value = "3 N/cm" }
[coordinates]
x = { sense = "along Ex", kind = "length" }
[points]
C = { offset = "x*Ex" }
[bodies]
b = { shape = "particle", mass = "2", frame = "F", at = "C" }
''')
    s, _ = load_problem(f)
    for name, expect in (("L0", 0.5), ("beta", 3.141592653589793 / 6), ("k", 300.0)):
        assert p.parameter_info[name].value == pytest.approx(expect)
        assert s.parameter_info[name].value == pytest.approx(expect)


def test_cable_atwood_machine(tmp_path):
    """Two masses on a rope over two small fixed pulleys: a = (m1 − m2) g/(m1 + m2), T = 2 m1 m2 g/(m1 + m2)."""
    f = tmp_path / "atwood.toml"
    f.write_text('''title = "Atwood machine"
[parameters]
m1 = { unit = "kg" }
m2 = { unit = "kg" }
g = { unit = "m/s^2" }
H = { unit = "m" }
L = { unit = "m" }
a = { unit = "m" }
[coordinates]
y1 = { sense = "height of mass 1", kind = "length" }
y2 = { sense = "height of mass 2", kind = "length" }
[points]
A = { offset = "-a*Ex + y1*Ey" }
B = { offset = "a*Ex + y2*Ey" }
P1 = { offset = "-a*Ex + H*Ey" }
P2 = { offset = "a*Ex + H*Ey" }
[bodies]
mass1 = { shape = "point_mass", mass = "m1", frame = "F", at = "A" }
mass2 = { shape = "point_mass", mass = "m2", frame = "F", at = "B" }
[constraints]
guide1 = { type = "collar", body = "mass1", along = "Ey" }
guide2 = { type = "collar", body = "mass2", along = "Ey" }
rope = { type = "cable", points = ["A", "P1", "P2", "B"], length = "L", tension_name = "T" }
[loads]
gravity = { type = "gravity", g = "g" }
[[ask.question]]
kind = "event"
when = "T = 0"
''')
    s, spec = load_problem(f)
    m1, m2, g = (s.parameters[n] for n in ("m1", "m2", "g"))
    sol = s.solve()
    y1 = s.coordinates[0]
    assert _same(sol.accelerations[y1], -(m1 - m2) * g / (m1 + m2))
    assert _same(sol.reactions["T"], 2 * m1 * m2 * g / (m1 + m2))
    assert spec.questions[0].fields["when"].lhs == sp.Symbol("T", real=True)


ROLLING_DISK = r'''title = "Rolling disk (coin) on a plane"
statement = """A thin uniform disk (mass m, radius a) rolls without slipping on a horizontal plane; \
it can lean, turn and spin."""
name = "rolling-disk"
[parameters]
m = { unit = "kg", description = "mass of the disk", value = 0.01 }
a = { unit = "m", description = "radius of the disk", value = 0.0125 }
g = { unit = "m/s^2", description = "gravitational acceleration", value = 9.81 }
[coordinates]
psi = { sense = "heading: turn of the disk's plane about Ez" }
theta = { sense = "lean of the disk's plane from the vertical, about the heading Yx", initial = 0.01 }
phi = { sense = "spin of the disk about its axle Ly; positive rolls it forward along Yx", rate = 30.0 }
x = { sense = "centre of the disk along Ex", kind = "length" }
y = { sense = "centre of the disk along Ey", kind = "length" }
z = { sense = "height of the centre of the disk above the plane", kind = "length" }
[frames]
Y = { angle = "psi", axis = "z", description = "heading frame: Yx along the line of travel" }
L = { parent = "Y", angle = "theta", axis = "x", description = "lean frame: Ly along the axle" }
D = { parent = "L", angle = "phi", axis = "y", description = "fixed in the disk" }
[points]
C = { offset = "x*Ex + y*Ey + z*Ez", description = "centre of the disk" }
[bodies]
disk = { shape = "disk", mass = "m", radius = "a", axis = "y", frame = "D", at = "C" }
[constraints.P]
type = "disk_contact"
body = "disk"
surface = { type = "plane", point = "O", normal = "Ez", name = "ground" }
axis = "D.y"
radius = "a"
friction = "rolling"
normal_name = "N"
friction_name = "F"
[loads]
gravity = { type = "gravity", g = "g", direction = "-Ez" }
'''


@pytest.mark.slow
def test_3d_disk_contact_and_frame_chain_match_the_python_rolling_disk(tmp_path):
    if "rolling-disk" not in names():
        pytest.skip("no rolling-disk example in this version")
    f = tmp_path / "rolling-disk.toml"
    f.write_text(ROLLING_DISK)
    s, _ = load_problem(f)
    p = build("rolling-disk")
    assert list(s.constraints) == list(p.constraints) and s.coordinates == p.coordinates
    assert s.statement == p.statement
    a, b = s.solve(), p.solve()
    assert a.coordinates == b.coordinates
    for q in b.coordinates:
        assert _same(a.accelerations[q] - b.accelerations[q], 0), q
