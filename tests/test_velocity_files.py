"""Problem files: [inputs], knife edges, velocity constraints, rotational springs and restitution per contact.

References: the Chaplygin sleigh's closed form (v̇ = aω², (I + ma²)ω̇ = −m a v ω, lateral force
N = I m v ω/(I + ma²)); the cart-pendulum written in Python with the same input; a ball bouncing on a
floor with Newton's law (rebound speed e v, bounces accumulating at t = t₁ (1 + 2e/(1 − e))).
"""

import math

import numpy as np
import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.base.errors import RigidkinError
from rigidkin.io.problem import parse_problem
from rigidkin.numeric import simulate

SLEIGH = """title = "Chaplygin sleigh"
statement = "A sleigh on a knife edge a distance a behind its mass centre."

[parameters]
m = { unit = "kg", description = "mass", value = 1.3 }
I = { unit = "kg*m^2", description = "central moment of inertia", value = 0.45 }
a = { unit = "m", description = "distance of the edge behind G", value = 0.3 }

[coordinates]
x = { sense = "of G along Ex", kind = "length", initial = 0.1, rate = 0.8 }
y = { sense = "of G along Ey", kind = "length", initial = -0.2, rate = 0.45 }
theta = { sense = "of the sleigh's axis from Ex, counter-clockwise", initial = 0 }

[frames]
B = { angle = "theta" }

[points]
G = { from = "O", offset = "x*Ex + y*Ey" }
P = { from = "G", offset = "-a*bx", body = "sleigh", description = "the knife edge" }

[bodies.sleigh]
shape = "inertia"
mass = "m"
Izz = "I"
frame = "B"
at = "G"

[constraints.edge]
type = "knife_edge"
body = "sleigh"
point = "P"
direction = "by"
reaction_name = "N"
"""

CART = """title = "Cart-pendulum pushed by a force input"

[parameters]
M = { unit = "kg", description = "cart", value = 2.0 }
m = { unit = "kg", description = "rod", value = 0.5 }
l = { unit = "m", description = "rod length", value = 0.8 }
g = { unit = "m/s^2", description = "gravity", value = 9.81 }

[inputs]
F = { unit = "N", description = "force on the cart, positive along Ex", history = "3*sin(2*t)" }

[coordinates]
x = { sense = "of the cart along Ex", kind = "length" }
theta = { sense = "of the rod from the downward vertical, counter-clockwise", initial = 0.2 }

[frames]
R = { angle = "theta" }

[points]
C = { from = "O", offset = "x*Ex" }
G = { from = "C", offset = "-l/2*ry" }

[bodies.cart]
shape = "point_mass"
mass = "M"
frame = "F"
at = "C"

[bodies.rod]
shape = "slender_rod"
mass = "m"
length = "l"
axis = "y"
frame = "R"
at = "G"

[constraints.rail]
type = "collar"
body = "cart"
along = "Ex"
point = "C"

[constraints.hinge]
type = "pin"
point = "C"
body_a = "rod"
body_b = "cart"

[loads.gravity]
type = "gravity"
g = "g"

[loads.push]
type = "force"
point = "C"
vector = "F*Ex"
body = "cart"

[loads.stiff]
type = "rotational_spring"
body_a = "rod"
body_b = "cart"
stiffness = 0
"""

BALL = """title = "Bouncing ball"

[parameters]
m = { unit = "kg", description = "mass", value = 1 }
r = { unit = "m", description = "radius", value = 0.1 }
g = { unit = "m/s^2", description = "gravity", value = 9.81 }

[coordinates]
y = { sense = "height of the centre", kind = "length", initial = 1.0 }

[points]
C = { from = "O", offset = "y*Ey" }

[bodies.ball]
shape = "point_mass"
mass = "m"
frame = "F"
at = "C"

[constraints.floor]
type = "contact"
body = "ball"
surface = { type = "line", point = "O", normal = "Ey" }
radius = "r"
restitution = 0.5

[loads.gravity]
type = "gravity"
g = "g"
"""


def test_sleigh_file_knife_edge():
    s, _ = parse_problem(SLEIGH, "sleigh.toml")
    res = simulate(s, 2.0)
    m, inertia, a = 1.3, 0.45, 0.3
    th = res["theta"]
    v = res["dot(x)"] * np.cos(th) + res["dot(y)"] * np.sin(th)
    w = res["dot(theta)"]
    # the edge at P = G − a bx moves along bx only: sideways speed of G is a ω
    lateral = -res["dot(x)"] * np.sin(th) + res["dot(y)"] * np.cos(th)
    assert np.max(np.abs(lateral - a * w)) < 1e-9
    # v̇ = a ω² and the lateral force by hand, along the history
    assert np.max(np.abs(np.gradient(v, res.t)[5:-5] - a * w[5:-5] ** 2)) < 1e-4
    assert np.max(np.abs(res["N"] - inertia * m * v * w / (inertia + m * a**2))) < 1e-8
    # the same constraint written as an expression in the rates
    general = SLEIGH.replace('type = "knife_edge"\nbody = "sleigh"\npoint = "P"\ndirection = "by"',
                             'type = "velocity_constraint"\nexpression = "-sin(theta)*dot(x) + cos(theta)*dot(y) - '
                             'a*dot(theta)"')
    assert general != SLEIGH
    s2, _ = parse_problem(general, "sleigh2.toml")
    res2 = simulate(s2, 2.0)
    assert np.max(np.abs(res2["theta"] - th)) < 1e-9
    assert np.max(np.abs(res2["N"] - res["N"])) < 1e-8


def test_cart_file_input_history_and_rotational_spring():
    s, _ = parse_problem(CART, "cart.toml")
    F = s.inputs["F"]
    assert F.unit == "N" and sp.simplify(F.history - 3 * sp.sin(2 * rk.t)) == 0
    assert "F(t)" in str(s.solve().accelerations[s.coordinates[0]])
    res = simulate(s, 1.5)                            # the history declared in the file
    other = simulate(s, 1.5, inputs={"F": lambda t, st: 3 * math.sin(2 * t)})
    for k in ("x", "theta", "dot(x)", "dot(theta)"):
        assert np.max(np.abs(res[k] - other[k])) < 1e-8
    assert s.loads["stiff"].angle == s.coordinates[1]      # the rod's angle relative to the cart


def test_ball_file_restitution():
    s, _ = parse_problem(BALL, "ball.toml")
    assert s.restitutions == {"floor": 0.5}
    res = simulate(s, 1.0)
    first = [e for e in res.events if e.kind == "impact"][0]
    t1 = math.sqrt(2 * 0.9 / 9.81)
    assert abs(first.t - t1) < 1e-9
    assert abs(first.after["dot(y)"] + 0.5 * first.state["dot(y)"]) < 1e-9
    # the option given to simulate wins over the file's
    res0 = simulate(s, 1.0, restitution=0.0)
    assert [e for e in res0.events if e.kind == "impact"][0].after["dot(y)"] == pytest.approx(0.0, abs=1e-12)


def test_file_errors_name_the_field():
    with pytest.raises(RigidkinError, match="restitution"):
        parse_problem(BALL.replace("restitution = 0.5", "restitution = 1.5"), "ball.toml")
    with pytest.raises(RigidkinError, match="inputs"):
        parse_problem(CART.replace('F = { unit = "N"', 'F = { units = "N"'), "cart.toml")
    with pytest.raises(RigidkinError, match="unit vector"):
        parse_problem(SLEIGH.replace('direction = "by"', 'direction = "2*by"'), "sleigh.toml")
