"""Restitution of a rope or cable in a problem file, and simulate(restitution={rope: e}).

References: a bob whirled on a string with v0² = 3.2 g L goes slack where T = m v²/L + m g cos φ = 0
(cos φ_s = (2gL − v0²)/(3gL) = −0.4), flies on a parabola and jerks taut where it meets the circle of radius L
again; by impulse–momentum the jerk with coefficient e gives the impulse m (1 + e) v_r, (1 + e) times the plastic
one m v_r (v_r the radial speed there, found by hand), and the radial speed after is −e v_r.  The same bob built
with the Python API and s.restitution("string", e) gives the same jerk.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq

import rigidkin as rk
from rigidkin.base.errors import InputError, RigidkinError
from rigidkin.io.problem import parse_problem
from rigidkin.numeric.simulate import simulate

MB, L_, G = 0.5, 1.0, 9.81
V0 = math.sqrt(3.2 * G * L_)

BOB = f"""title = "Bob whirled on a string"
statement = "A bob on a string whirled from the bottom with v0^2 = 3.2 g L: the string goes slack and jerks taut."

[parameters]
m = {{ unit = "kg", description = "mass of the bob", value = {MB!r} }}
L = {{ unit = "m", description = "length of the string", value = {L_!r} }}
g = {{ unit = "m/s^2", description = "gravity", value = {G!r} }}

[coordinates]
rho = {{ sense = "distance of the bob from the pivot", kind = "length", initial = {L_!r} }}
phi = {{ sense = "angle of the string from the downward vertical", initial = 0, rate = {V0 / L_!r} }}

[points]
B = {{ from = "O", offset = "rho*(sin(phi)*Ex - cos(phi)*Ey)" }}

[bodies.bob]
shape = "point_mass"
mass = "m"
frame = "F"
at = "B"

[constraints.string]
type = "cable"
points = ["O", "B"]
length = "L"
tension_name = "T"
restitution = 0.3

[loads.gravity]
type = "gravity"
g = "g"
"""
ROPE = BOB.replace('type = "cable"\npoints = ["O", "B"]\nlength = "L"\ntension_name = "T"',
                   'type = "rope"\npath = ["O", "B"]\ntensions = ["T"]')


def _python(e=None):
    """The same bob with the Python API."""
    s = rk.System("bob on a string")
    m, L, g = s.parameter("m", "kg", value=MB), s.parameter("L", "m", value=L_), s.parameter("g", "m/s^2", value=G)
    rho = s.coordinate("rho", "distance of the bob from the pivot", kind="length", initial=L_)
    phi = s.coordinate("phi", "angle of the string from the downward vertical", initial=0.0, rate=V0 / L_)
    F = s.inertial
    B = s.point("B", offset=rho * (sp.sin(phi) * F.x - sp.cos(phi) * F.y))
    s.body("bob", rk.shapes.PointMass(m), frame=F, at=B)
    s.cable("string", [s.origin, B], L, tension_name="T")
    s.gravity(g)
    if e is not None:
        s.restitution("string", e)
    return s


def _by_hand():
    """The instant the string re-tightens and the bob's radial speed v_r there (outward): circular motion to
    cos φ_s = −0.4, then a parabola from there until x² + y² = L²."""
    cs = (2 * G * L_ - V0**2) / (3 * G * L_)
    phis = math.acos(cs)
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
    vr = float(np.array([vx, vy - G * tau]) @ np.array([x, y]) / L_)
    return tau, vr


@pytest.fixture(scope="module")
def hand():
    return _by_hand()


def _jerk(system, **kw):
    res = simulate(system, 1.23, **kw)
    assert res.stop_reason == "completed"
    return res.events_of("tightens")[0]


@pytest.mark.parametrize("text", [BOB, ROPE], ids=["cable", "rope"])
def test_file_restitution_gives_the_jerk_of_the_python_api(text, hand):
    """restitution = 0.3 in the file: System.restitutions as s.restitution("string", 0.3) gives it, the same
    jerk as the Python-built bob, impulse (1 + e) × the plastic one m v_r, and radial speed −e v_r after."""
    _, vr = hand
    s, _ = parse_problem(text, "bob.toml")
    assert s.restitutions == {"string": 0.3}
    jerk = _jerk(s)
    api = _jerk(_python(0.3))
    assert jerk.t == pytest.approx(api.t, rel=1e-10)
    assert jerk.impact["impulse"] == pytest.approx(api.impact["impulse"], rel=1e-9)
    assert jerk.state["dot(rho)"] == pytest.approx(vr, rel=1e-7)
    assert jerk.impact["impulse"] == pytest.approx((1 + 0.3) * MB * vr, rel=1e-7)
    assert jerk.after["dot(rho)"] == pytest.approx(-0.3 * vr, rel=1e-7)
    assert "rebounds slack (e = 0.3)" in jerk.detail
    # without the field: the plastic jerk, impulse m v_r, no radial speed after
    plain, _ = parse_problem(text.replace("restitution = 0.3\n", ""), "bob.toml")
    assert plain.restitutions == {}
    plastic = _jerk(plain)
    assert plastic.impact["impulse"] == pytest.approx(MB * vr, rel=1e-7)
    assert jerk.impact["impulse"] == pytest.approx(1.3 * plastic.impact["impulse"], rel=1e-9)
    assert plastic.after["dot(rho)"] == pytest.approx(0.0, abs=1e-9)


def test_file_restitution_may_be_a_parameter():
    """e as an expression of a dimensionless parameter: its value is used."""
    text = BOB.replace("[parameters]\n", '[parameters]\ne = { unit = "1", value = 0.6 }\n').replace(
        "restitution = 0.3", 'restitution = "e/2"')
    s, _ = parse_problem(text, "bob.toml")
    assert s.restitutions == {"string": pytest.approx(0.3)}


@pytest.mark.parametrize("table", ["cable", "rope"])
@pytest.mark.parametrize("value, words", [
    ("1.5", ["cable string is 1.5", "must lie in [0, 1]", "jerk"]),
    ("-0.2", ["is -0.2", "must lie in [0, 1]"]),
    ('"L"', ["has dimension L (m)", "the term L"]),
    ('"2 m"', ["has dimension L (m)", "2 m"]),
    ('"0.1*phi"', ["must be a constant", "depends on phi"]),
    ('"k"', ["needs the value of the parameter k"]),
    ('"q"', ["'q' is not declared"]),
    ("true", ["expected an expression"]),
])
def test_bad_restitution_is_refused_at_its_line(table, value, words):
    text = BOB if table == "cable" else ROPE
    text = text.replace("[parameters]\n", '[parameters]\nk = { unit = "1" }\n').replace(
        "restitution = 0.3", f"restitution = {value}")
    if table == "rope":
        words = [w.replace("cable string", "rope string") for w in words]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(InputError) as info:
            parse_problem(text, "bob.toml")
    msg = str(info.value)
    line = text.splitlines().index(f"restitution = {value}") + 1
    assert f"bob.toml, line {line}, constraints.string.restitution" in msg, msg
    assert "\n" not in msg
    for w in words:
        assert w in msg, (w, msg)


def test_contact_restitution_takes_the_same_check():
    """A contact's restitution is checked the same way (a length parameter is not a coefficient)."""
    ball = BOB.replace('type = "cable"\npoints = ["O", "B"]\nlength = "L"\ntension_name = "T"',
                       'type = "contact"\nbody = "bob"\nsurface = { type = "line", point = "O", normal = "Ey" }')
    s, _ = parse_problem(ball, "ball.toml")
    assert s.restitutions == {"string": 0.3}
    with pytest.raises(InputError, match=r"contact string has dimension L \(m\)"):
        parse_problem(ball.replace("restitution = 0.3", 'restitution = "L"'), "ball.toml")
    with pytest.raises(InputError, match=r"contact string is 2; it must lie in \[0, 1\] \(e of its impacts"):
        parse_problem(ball.replace("restitution = 0.3", "restitution = 2"), "ball.toml")


def test_simulate_takes_a_rope_name(hand):
    """simulate(restitution={"string": e}) wins over the declared e: impulse m (1 + e) v_r; a number is e of
    every contact and leaves the rope's own; a name of nothing, a value outside [0, 1] or not a number is
    refused."""
    _, vr = hand
    s = _python(0.3)
    half = _jerk(s, restitution={"string": 0.5})
    assert half.impact["impulse"] == pytest.approx(1.5 * MB * vr, rel=1e-7)
    assert half.after["dot(rho)"] == pytest.approx(-0.5 * vr, rel=1e-7)
    plastic = _jerk(s, restitution={"string": 0})
    assert plastic.impact["impulse"] == pytest.approx(MB * vr, rel=1e-7)
    assert plastic.after["dot(rho)"] == pytest.approx(0.0, abs=1e-9)
    kept = _jerk(s, restitution=0.9)                     # every contact (there are none): the rope keeps 0.3
    assert kept.impact["impulse"] == pytest.approx(1.3 * MB * vr, rel=1e-7)
    from_file = _jerk(parse_problem(ROPE, "bob.toml")[0], restitution={"string": 0.5})
    assert from_file.impact["impulse"] == pytest.approx(half.impact["impulse"], rel=1e-9)
    with pytest.raises(RigidkinError, match="bob is not a contact, rope or cable .* ropes and cables: string"):
        simulate(s, 1.0, restitution={"bob": 0.3})
    with pytest.raises(RigidkinError, match=r"restitution of string is 1.3; it must lie in \[0, 1\]"):
        simulate(s, 1.0, restitution={"string": 1.3})
    with pytest.raises(RigidkinError, match="must be a number, not 'x'"):
        simulate(s, 1.0, restitution={"string": "x"})


def test_command_line_restitution_names_a_rope(hand, tmp_path, capsys):
    """rigidkin simulate FILE --restitution string=0.5 wins over the file's 0.3: impulse m (1 + 0.5) v_r."""
    from rigidkin.cli import main

    _, vr = hand
    path = tmp_path / "bob.toml"
    path.write_text(BOB, encoding="utf-8")
    assert main(["simulate", str(path), "--t-end", "1.23", "--restitution", "string=0.5"]) == 0
    out = capsys.readouterr().out
    assert f"impulse T = {1.5 * MB * vr:.6g}" in out and "rebounds slack (e = 0.5)" in out, out
