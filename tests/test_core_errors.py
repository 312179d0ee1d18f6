"""Bad models raise ModelError/ConstraintError naming what is involved and the degrees of freedom."""

import pytest
import sympy as sp
from helpers import rod_pendulum

import rigidkin as rk
from rigidkin.base.errors import ConstraintError, ModelError


def pendulum():
    """The rod of helpers.rod_pendulum with no pin yet."""
    s, rod, th, R, (m, l, g) = rod_pendulum(pin=False)
    return s, rod, th, R, l


def test_under_determined_missing_support():
    # a rod on a pin needs the pin; without it the vertical force balance cannot hold
    s, rod, *_ = pendulum()
    with pytest.raises(ModelError) as err:
        s.solve()
    msg = str(err.value)
    assert "Euler's 1st law for rod along Ey" in msg and "1 degree(s) of freedom" in msg
    assert "constraint (with its reaction) is missing" in msg


def test_over_constrained_names_constraints_and_dof():
    s = rk.System("slider")
    m = s.parameter("m", "kg")
    x = s.coordinate("x", "position along Ex", kind="length")
    y = s.coordinate("y", "height", kind="length")
    F = s.inertial
    C = s.point("C", offset=x * F.x + y * F.y)
    b = s.body("block", rk.shapes.PointMass(m), frame=F, at=C)
    s.contact("floor", b, s.line(s.origin, F.y))
    s.contact("floor2", b, s.line(s.origin, F.y))
    with pytest.raises(ConstraintError) as err:
        s.solve()
    msg = str(err.value)
    assert "floor2" in msg and "over-constrained" in msg and "1 degrees of freedom" in msg


def test_structure_has_no_dof():
    s = rk.System("stuck")
    m = s.parameter("m", "kg")
    x = s.coordinate("x", "along Ex", kind="length")
    F = s.inertial
    C = s.point("C", offset=x * F.x)
    b = s.body("block", rk.shapes.PointMass(m), frame=F, at=C)
    s.contact("wall", b, s.line(s.origin, F.x))
    sol = s.solve()                     # no degree of freedom: a mode at rest, reactions from statics
    assert sol.coordinates == () and sol.reactions["N_wall"] == 0


def test_statically_indeterminate_reactions_named():
    # a pendulum held by two coincident pins: the pin reactions cannot be separated
    s, rod, th, R, l = pendulum()
    s.pin("O", s.origin, rod)
    s.pin("O2", s.origin, rod)
    with pytest.raises(ConstraintError) as err:
        s.solve()
    assert "R_O" in str(err.value) and "R_O2" in str(err.value)


def test_unknown_names_and_wrong_objects():
    s, rod, th, R, l = pendulum()
    with pytest.raises(ModelError, match="already used"):
        s.parameter("m", "kg")
    with pytest.raises(ModelError, match="no point named 'Q'"):
        s.pin("P", "Q", rod)
    with pytest.raises(ModelError, match="expected a vector"):
        s.point("Z", offset=3)
    with pytest.raises(rk.RigidkinError, match="not a unit"):
        s.parameter("k", "furlongs_per_blorp")
    with pytest.raises(ModelError, match="friction must be"):
        s.contact("c", rod, s.line(s.origin, s.inertial.y), friction="sticky")
    with pytest.raises(ModelError, match="mode names 'nope'"):
        s.pin("O", s.origin, rod)
        s.solve(mode={"nope": "open"})


def test_force_on_a_point_without_body():
    s, rod, th, R, l = pendulum()
    Q = s.point("Q", offset=l * s.inertial.x)
    with pytest.raises(ModelError, match="not fixed in a body"):
        s.force("push", Q, 3 * s.inertial.x)


def test_pendulum_doctest_value():
    s, rod, th, R, l = pendulum()
    s.pin("O", s.origin, rod)
    sol = s.solve()
    g = s.parameters["g"]
    assert sp.simplify(sol.accelerations[th] + 3 * g * sp.sin(th) / (2 * l)) == 0


def test_point_declared_fixed_in_a_body_that_moves_relative_to_it():
    s = rk.System("disk")
    m, r = s.parameter("m", "kg"), s.parameter("r", "m")
    x = s.coordinate("x", "centre along Ex", kind="length")
    phi = s.coordinate("phi", "rotation")
    F = s.inertial
    D = s.frame("D", angle=phi)
    C = s.point("C", offset=x * F.x + r * F.y)
    disk = s.body("disk", rk.shapes.Disk(m, r), frame=D, at=C)
    s.point("P", C, -r * F.y, body=disk)          # the contact point is not a material point of the disk
    with pytest.raises(ModelError, match="point P is declared fixed in body disk, but it moves"):
        s.solve()


def test_nothing_to_move():
    with pytest.raises(ModelError, match="no bodies"):
        rk.System("empty").solve()
    s = rk.System("still")
    s.body("b", rk.shapes.PointMass(s.parameter("m")), frame=s.inertial, at=s.origin)
    with pytest.raises(ModelError, match="no coordinates"):
        s.solve()
    s = rk.System("unused")
    x = s.coordinate("x", "along Ex", kind="length")
    s.coordinate("y", "never used", kind="length")
    s.body("b", rk.shapes.PointMass(s.parameter("m")), frame=s.inertial, at=s.point("P", offset=x * s.inertial.x))
    with pytest.raises(ModelError, match="coordinates y locate no point"):
        s.solve()


def test_strings_are_refused_in_the_python_api():
    s, rod, th, R, l = pendulum()
    with pytest.raises(ModelError, match="got the string 'l/2'"):
        s.spring("k", "G", s.origin, "l/2")


def test_a_constraint_row_with_accelerations_is_named():
    """A point placed by a rate (x' Ex) makes its no-slip row hold an acceleration: refused as such (the
    check compared symbols of other assumptions, never matched, and the row was reported as redundant)."""
    from sympy.physics.vector import dynamicsymbols

    s = rk.System("acc")
    m = s.parameter("m", "kg", "mass", value=1.0)
    x, y = s.coordinate("x", kind="length"), s.coordinate("y", kind="length")
    P = s.point("P", offset=x.diff(dynamicsymbols._t) * s.inertial.x + y * s.inertial.y)
    b = s.body("b", rk.shapes.PointMass(m), frame=s.inertial, at=P)
    s.contact("c", b, s.plane(s.origin, s.inertial.y, name="ground"), friction="rolling")
    with pytest.raises(ConstraintError, match="a constraint row involves accelerations"):
        s.solve()
