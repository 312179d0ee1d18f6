"""A rope or cable started slack (mode={"string": "open"}, --mode string=open: numeric/contacts/slack_start.py).

References by hand.  A yo-yo (disk m, R, drum r; string from a fixed point O wound on the drum; coordinates y, θ)
started slack at y0 with ẏ = v0 up and no spin: its string's free length is the distance at the start, the spin
pays none out, so it flies as a projectile, gap = y − y0 = v0 t − g t²/2, until the gap closes at t* = 2 v0/g with
ẏ = −v0; then the jerk by impulse–momentum: m (ẏ⁺ + v0) = Λ, I θ̇⁺ = −r Λ, taut ẏ⁺ = r θ̇⁺, so
Λ = m v0 κ/(1 + κ) with κ = I/(m r²), ẏ⁺ = −v0/(1 + κ), θ̇⁺ = −v0/(r (1 + κ)), the energy ½ Λ v0 lost.
Started taut the same declared rates give θ̇ = v0/r (the string makes the spin).  A bob on a cable of length L
started slack at ρ0 < L below the pivot falls freely, ρ = ρ0 + g t²/2, and jerks taut at ρ = L with Λ = m v,
v = √(2 g (L − ρ0)); started with ρ0 > L it is refused naming the cable and its gap.
"""

from __future__ import annotations

import json
import math

import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.base.errors import InputError
from rigidkin.cli import main
from rigidkin.model.ropes import Wrap
from rigidkin.numeric.simulate import simulate

M_, RR, r_, G = 0.2, 0.05, 0.01, 9.81
I_ = 0.5 * M_ * RR**2
Y0, V0 = -0.5, 1.5


def _yoyo():
    s = rk.System("yo-yo")
    m, R, r = s.parameter("m", "kg", value=M_), s.parameter("R", "m", value=RR), s.parameter("r", "m", value=r_)
    g = s.parameter("g", "m/s^2", value=G)
    y = s.coordinate("y", "height of the centre", kind="length", initial=Y0, rate=V0)
    th = s.coordinate("theta", "rotation of the yo-yo, counter-clockwise", initial=0.0, rate=0.0)
    disk = s.body("yoyo", rk.shapes.Disk(m, R), frame=s.frame("D", angle=th),
                  at=s.point("C", offset=r * s.inertial.x + y * s.inertial.y))
    s.rope("string", [s.origin, Wrap(disk, r, "ccw")], tensions=("T",))     # hangs down the drum's left side
    s.gravity(g)
    return s


@pytest.fixture(scope="module")
def slack_run():
    return simulate(_yoyo(), 2 * V0 / G + 0.05, mode={"string": "slack"})


def test_a_yoyo_started_slack_flies_as_a_projectile(slack_run):
    res = slack_run
    assert "string slack" in res.segments[0].description
    for tt in (0.05, 0.1, V0 / G, 0.25):
        st = res.at(tt)
        assert st["y"] == pytest.approx(Y0 + V0 * tt - G * tt**2 / 2, abs=1e-9)
        assert st["dot(y)"] == pytest.approx(V0 - G * tt, abs=1e-9)
        assert st["dot(theta)"] == pytest.approx(0.0, abs=1e-12) and st["theta"] == pytest.approx(0.0, abs=1e-12)


def test_a_yoyo_started_slack_jerks_taut_by_impulse_momentum(slack_run):
    ev = slack_run.events[0]
    assert ev.kind == "tightens" and ev.t == pytest.approx(2 * V0 / G, rel=1e-9)
    kappa = I_ / (M_ * r_**2)
    lam = M_ * V0 * kappa / (1 + kappa)
    assert ev.impact["impulse"] == pytest.approx(lam, rel=1e-7)
    assert ev.after["dot(y)"] == pytest.approx(-V0 / (1 + kappa), rel=1e-7)
    assert ev.after["dot(theta)"] == pytest.approx(-V0 / (r_ * (1 + kappa)), rel=1e-7)
    lost = 0.5 * M_ * V0**2 - 0.5 * M_ * ev.after["dot(y)"] ** 2 - 0.5 * I_ * ev.after["dot(theta)"] ** 2
    assert lost == pytest.approx(0.5 * lam * V0, rel=1e-7)
    assert ev.impact["energy_dissipated"] == pytest.approx(lost, rel=1e-7)
    assert "string taut" in slack_run.segments[1].description


def test_a_yoyo_started_taut_spins_with_its_string():
    res = simulate(_yoyo(), 0.01, mode={"string": "taut"})
    assert "string taut" in res.segments[0].description
    assert res.at(0.0)["dot(theta)"] == pytest.approx(V0 / r_, rel=1e-9)


def test_a_bad_start_word_is_refused():
    with pytest.raises(InputError, match="not open \\(slack\\) or taut"):
        simulate(_yoyo(), 0.1, mode={"string": "loose"})


def _bob(rho0):
    s = rk.System("bob on a cable")
    m, L, g = s.parameter("m", "kg", value=0.5), s.parameter("L", "m", value=1.0), s.parameter("g", "m/s^2", value=G)
    rho = s.coordinate("rho", "distance of the bob from the pivot", kind="length", initial=rho0)
    phi = s.coordinate("phi", "angle of the cable from the downward vertical", initial=0.0)
    B = s.point("B", offset=rho * (sp.sin(phi) * s.inertial.x - sp.cos(phi) * s.inertial.y))
    s.body("bob", rk.shapes.PointMass(m), frame=s.inertial, at=B)
    s.cable("string", [s.origin, B], L, tension_name="T")
    s.gravity(g)
    return s


def test_a_cable_started_slack_falls_free_to_its_length():
    res = simulate(_bob(0.6), 0.4, mode={"string": "open"})
    ts = math.sqrt(2 * 0.4 / G)
    ev = res.events[0]
    assert ev.kind == "tightens" and ev.t == pytest.approx(ts, rel=1e-9)
    assert ev.impact["impulse"] == pytest.approx(0.5 * G * ts, rel=1e-7)
    assert ev.after["dot(rho)"] == pytest.approx(0.0, abs=1e-9)


def test_a_cable_started_slack_beyond_its_length_is_refused():
    with pytest.raises(InputError) as exc:
        simulate(_bob(1.2), 0.1, mode={"string": "open"})
    text = str(exc.value)
    assert "cable string cannot start slack" in text and "-0.2" in text and "\n" not in text.strip()


BOB = """title = "Bob on a cable"
statement = "A bob let go below the pivot with its cable slack: it falls and jerks the cable taut."

[parameters]
m = { unit = "kg", description = "mass of the bob", value = 0.5 }
L = { unit = "m", description = "length of the cable", value = 1.0 }
g = { unit = "m/s^2", description = "gravity", value = 9.81 }

[coordinates]
rho = { sense = "distance of the bob from the pivot", kind = "length", initial = 0.6 }
phi = { sense = "angle of the cable from the downward vertical", initial = 0 }

[points]
B = { from = "O", offset = "rho*(sin(phi)*Ex - cos(phi)*Ey)" }

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

[loads.gravity]
type = "gravity"
g = "g"
"""


def test_the_command_line_starts_a_cable_slack(tmp_path, capsys):
    path = tmp_path / "bob.toml"
    path.write_text(BOB)
    assert main(["simulate", str(path), "--t-end", "0.4", "--json", "--points", "5", "--mode", "string=open"]) == 0
    data = json.loads(capsys.readouterr().out)
    ev = data["events"][0]
    ts = math.sqrt(2 * 0.4 / G)
    assert ev["kind"] == "tightens" and ev["t"] == pytest.approx(ts, rel=1e-9)
    assert ev["impact"]["impulse"] == pytest.approx(0.5 * G * ts, rel=1e-7)
    assert main(["simulate", str(path), "--t-end", "0.1", "--set", "L=0.5", "--mode", "string=open"]) != 0
    assert "cable string cannot start slack" in capsys.readouterr().err


def test_a_cable_the_coordinates_keep_at_its_length_cannot_start_slack():
    """The bob at ρ = L fixed by the coordinates (φ alone): nothing lets the cable be slack, so a slack start is
    refused in one paragraph instead of a pendulum whose cable could push."""
    s = rk.System("bob on a rigid string")
    m, L, g = s.parameter("m", "kg", value=0.5), s.parameter("L", "m", value=1.0), s.parameter("g", "m/s^2", value=G)
    phi = s.coordinate("phi", "angle of the string from the downward vertical", initial=0.3)
    B = s.point("B", offset=L * (sp.sin(phi) * s.inertial.x - sp.cos(phi) * s.inertial.y))
    s.body("bob", rk.shapes.PointMass(m), frame=s.inertial, at=B)
    s.cable("string", [s.origin, B], L, tension_name="T")
    s.gravity(g)
    with pytest.raises(InputError, match="cable string cannot start slack: the coordinates keep cable string at its"):
        simulate(s, 0.1, mode={"string": "open"})
