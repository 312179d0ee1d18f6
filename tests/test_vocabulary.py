"""Issue 15: what a problem says directly — loads at points that move over a body (``on``), the power
balance warning of ``solve``, derived quantities, arcs, ropes over massive pulleys.

Every expected value is derived by hand in the test's docstring or comment (closed forms), never read
from the engine.
"""

import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.errors import RigidkinError
from rigidkin.io.problem import parse_problem

t = sp.Symbol("t")

TOP = """
title = "Disk with a spring at its top"
[parameters]
m = { unit = "kg", value = 2 }
r = { unit = "m", value = 0.2 }
K = { unit = "N/m", value = 50 }
g = { unit = "m/s^2", value = 9.81 }
[coordinates]
theta = { sense = "rotation, positive rolling to +Ex", initial = 0.1, rate = 0 }
x = { sense = "centre along Ex", kind = "length" }
[frames]
D = { angle = "-theta" }
[points]
C = { offset = "x*F.x + r*F.y" }
T = { from = "C", offset = "r*F.y", description = "the top of the disk (moves over it)" }
[bodies]
disk = { shape = "disk", mass = "m", radius = "r", frame = "D", at = "C" }
[constraints.P]
type = "contact"
body = "disk"
surface = { type = "line", point = "O", normal = "F.y", name = "floor" }
radius = "r"
friction = "rolling"
[loads]
spring = { type = "spring", point_a = "T", point_b = "O", ENDS, stiffness = "K" }
gravity = { type = "gravity", g = "g" }
"""


def rolling_disk(top_fixed_in_disk: bool = False):
    """A uniform disk (m, r) rolling on the floor, x = r θ (θ clockwise); T its top point."""
    s = rk.System("top")
    m, r, g = s.parameter("m", "kg", value=2), s.parameter("r", "m", value=0.2), s.parameter("g", "m/s^2", value=9.81)
    th = s.coordinate("theta", "rotation, positive rolling to +Ex", initial=0.1)
    x = s.coordinate("x", "centre along Ex", kind="length")
    F = s.inertial
    D = s.frame("D", angle=-th)
    C = s.point("C", offset=x * F.x + r * F.y)
    disk = s.body("disk", rk.shapes.Disk(m, r), frame=D, at=C)
    T = s.point("T", C, r * (D.y if top_fixed_in_disk else F.y), body=disk if top_fixed_in_disk else None)
    s.contact("P", disk, s.line(s.origin, F.y, name="floor"), radius=r, friction="rolling")
    s.gravity(g)
    return s, disk, T, th, m, r


# 1. loads at points that are not material points ------------------------------------------------------
def test_spring_at_a_point_moving_over_the_body_is_refused_naming_the_point():
    s, disk, T, th, m, r = rolling_disk()
    K = s.parameter("K", "N/m", value=50)
    with pytest.raises(rk.ModelError) as err:
        s.spring("spring", T, s.origin, K, body_a=disk)
    msg = str(err.value)
    assert "point T moves relative to body disk" in msg and "on_a" in msg


def test_spring_refused_in_a_file_with_the_line():
    with pytest.raises(RigidkinError) as err:
        parse_problem(TOP.replace("ENDS", 'body_a = "disk"'), "top.toml")
    msg = str(err.value)
    assert "top.toml, line" in msg and "loads.spring" in msg and "point T" in msg


def test_spring_on_the_material_point_at_the_top_all_laws_agree():
    """Force −K(x Ex + 2r Ey) on the material point at the top; moments about the contact point:
    (3/2) m r² (−θ̈) = 2r · K x with x = r θ, so θ̈ = −4Kθ/(3m) (not −2Kθ/(3m), which a potential
    K ℓ²/2 of the moving point would give)."""
    system, _ = parse_problem(TOP.replace("ENDS", 'on_a = "disk"'), "top.toml")
    sol = system.solve()
    th = system.coordinates[0]
    K, m = system.parameters["K"], system.parameters["m"]
    assert sp.simplify(sol.accelerations[th] + 4 * K * th / (3 * m)) == 0
    assert not system.loads["spring"].conservative
    report = sol.check(laws=["work-energy", "lagrange", "kane"])
    assert report.ok, report
    assert sol.warnings == ()


def test_damper_on_the_material_point_uses_its_material_velocity():
    """Damper −c v along Ex at the top: the material point there moves at 2ẋ = 2rθ̇, so the force is
    −2crθ̇ Ex; about the contact point (3/2) m r² θ̈ = −2r · 2crθ̇, θ̈ = −8cθ̇/(3m)."""
    s, disk, T, th, m, r = rolling_disk()
    c = s.parameter("c", "N*s/m", value=3)
    with pytest.raises(rk.ModelError, match="point T"):
        s.damper("d", T, -c * rk.v, along=s.inertial.x, body_a=disk)
    s.damper("d", T, -c * rk.v, along=s.inertial.x, on_a=disk)
    sol = s.solve()
    assert sp.simplify(sol.accelerations[th] + 8 * c * th.diff(t) / (3 * m)) == 0
    assert sol.warnings == ()


def test_point_fixed_in_the_body_needs_no_on():
    """The same top point fixed in the disk (r D.y): an ordinary material point, spring conservative."""
    s, disk, T, th, m, r = rolling_disk(top_fixed_in_disk=True)
    K = s.parameter("K", "N/m", value=50)
    spring = s.spring("spring", T, s.origin, K)
    assert spring.conservative and not spring.moving_a


def test_spring_end_moving_but_fixed_in_no_body_is_refused():
    s, disk, T, th, m, r = rolling_disk()
    K = s.parameter("K", "N/m", value=50)
    x = s.coordinates[1]
    M = s.point("M", s.origin, x * s.inertial.x + 3 * r * s.inertial.y)
    with pytest.raises(rk.ModelError, match="point M moves relative to the ground"):
        s.spring("spring", T, M, K, on_a=disk)


def test_force_on_is_the_same_as_body():
    """A push P Ex on the material point at the top: (3/2) m r² θ̈ = 2r P, θ̈ = 4P/(3 m r)."""
    s, disk, T, th, m, r = rolling_disk()
    P = s.parameter("P", "N", value=5)
    s.force("push", T, P * s.inertial.x, on=disk)
    sol = s.solve()
    assert sp.simplify(sol.accelerations[th] - 4 * P / (3 * m * r)) == 0
    assert sol.warnings == ()


def test_solve_warns_when_the_models_own_laws_disagree():
    """A spring made conservative at a moving end (what the engine did before): its potential is not
    the work of its force, and the power balance says so in the output of solve."""
    from rigidkin.io.results import solution_data
    from rigidkin.report.text import problem_text

    system, _ = parse_problem(TOP.replace("ENDS", 'on_a = "disk"'), "top.toml")
    system.loads["spring"].moving_a = False          # the old, inconsistent model
    sol = system.solve()
    assert len(sol.warnings) == 1 and "disagree" in sol.warnings[0]
    assert "Warnings" in problem_text(sol)
    assert solution_data(sol)["warnings"] == list(sol.warnings)


@pytest.mark.parametrize("card", ["ladder", "disk-spring-incline", "boulder-push"])
def test_consistent_cards_give_no_warning(card):
    from rigidkin.examples import build

    assert build(card).solve().warnings == ()
