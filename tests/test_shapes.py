"""The shape library against inertia computed here by direct integration over the body."""

import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.model.frames import Frame, make_reference_frame

m, r, L, a, b, c = sp.symbols("m r L a b c", positive=True)
x, y, z, rho, th, ph = sp.symbols("x y z rho th ph", real=True)


@pytest.fixture
def B():
    return Frame("B", make_reference_frame("B", ("bx", "by", "bz"), ("x", "y", "z")), ("bx", "by", "bz"))


def components(I, B):
    e = (B.x, B.y, B.z)
    return sp.Matrix(3, 3, lambda i, j: sp.simplify(e[i].dot(I).dot(e[j])))


def tensor(density_integral):
    """Central inertia tensor and mass centre from a function integrating f over the body."""
    M = density_integral(1)
    cx, cy, cz = (density_integral(v) / M for v in (x, y, z))
    def I(f):
        return density_integral(f)
    T = sp.Matrix([[I(y**2 + z**2), -I(x * y), -I(x * z)],
                   [-I(x * y), I(x**2 + z**2), -I(y * z)],
                   [-I(x * z), -I(y * z), I(x**2 + y**2)]])
    d = sp.Matrix([cx, cy, cz])
    shift = (d.dot(d) * sp.eye(3) - d * d.T)
    return M, d, T - M * shift  # per unit density


def test_semicircular_disk(B):
    # plate in the x-y plane, flat edge along x, curved half towards -y; axis z
    def integ(f):
        fp = sp.sympify(f).subs({x: rho * sp.cos(th), y: -rho * sp.sin(th), z: 0})
        return sp.integrate(sp.integrate(fp * rho, (rho, 0, r)), (th, 0, sp.pi))
    M, d, T = tensor(integ)
    shape = rk.shapes.SemicircularDisk(m, r, axis="z", toward="-y")
    assert sp.simplify(d[1] + 4 * r / (3 * sp.pi)) == 0
    assert sp.simplify(shape.centre_offset(B).dot(B.y) - d[1]) == 0
    assert sp.simplify(components(shape.central_inertia(B), B) - m * T / M) == sp.zeros(3)


def test_half_cylinder(B):
    def integ(f):
        fp = sp.sympify(f).subs({x: rho * sp.cos(th), y: -rho * sp.sin(th)})
        return sp.integrate(sp.integrate(sp.integrate(fp * rho, (rho, 0, r)), (th, 0, sp.pi)), (z, -L / 2, L / 2))
    M, d, T = tensor(integ)
    shape = rk.shapes.HalfCylinder(m, r, L, axis="z", toward="-y")
    assert sp.simplify(components(shape.central_inertia(B), B) - m * T / M) == sp.zeros(3)


def test_hemisphere(B):
    # curved half towards -y: y = -rho cos(ph)
    def integ(f):
        sub = {x: rho * sp.sin(ph) * sp.cos(th), z: rho * sp.sin(ph) * sp.sin(th), y: -rho * sp.cos(ph)}
        fp = sp.sympify(f).subs(sub)
        return sp.integrate(sp.integrate(sp.integrate(fp * rho**2 * sp.sin(ph), (rho, 0, r)),
                                         (ph, 0, sp.pi / 2)), (th, 0, 2 * sp.pi))
    M, d, T = tensor(integ)
    shape = rk.shapes.Hemisphere(m, r, toward="-y")
    assert sp.simplify(d[1] + 3 * r / 8) == 0
    got = components(shape.central_inertia(B), B)
    assert sp.simplify(got - m * T / M) == sp.zeros(3)
    assert sp.simplify(got[0, 0] - sp.Rational(83, 320) * m * r**2) == 0


def test_box_and_plate(B):
    def integ(f):
        return sp.integrate(sp.sympify(f), (x, -a / 2, a / 2), (y, -b / 2, b / 2), (z, -c / 2, c / 2))
    M, d, T = tensor(integ)
    assert sp.simplify(components(rk.shapes.Box(m, a, b, c).central_inertia(B), B) - m * T / M) == sp.zeros(3)
    def integ2(f):
        return sp.integrate(sp.sympify(f).subs(z, 0), (x, -a / 2, a / 2), (y, -b / 2, b / 2))
    M2, _, T2 = tensor(integ2)
    plate = rk.shapes.RectangularPlate(m, a, b, a_axis="x", b_axis="y").central_inertia(B)
    assert sp.simplify(components(plate, B) - m * T2 / M2) == sp.zeros(3)


@pytest.mark.parametrize("shape, axis_value, trans_value", [
    (rk.shapes.SlenderRod(m, L, axis="x"), 0, m * L**2 / 12),
    (rk.shapes.ThinRing(m, r, axis="x"), m * r**2, m * r**2 / 2),
    (rk.shapes.Disk(m, r, axis="x"), m * r**2 / 2, m * r**2 / 4),
    (rk.shapes.Disk(m, r, L, axis="x"), m * r**2 / 2, m * r**2 / 4 + m * L**2 / 12),
    (rk.shapes.HollowCylinder(m, r, axis="x"), m * r**2, m * r**2 / 2),
    (rk.shapes.SolidSphere(m, r), 2 * m * r**2 / 5, 2 * m * r**2 / 5),
    (rk.shapes.SphericalShell(m, r), 2 * m * r**2 / 3, 2 * m * r**2 / 3),
    (rk.shapes.PointMass(m), 0, 0),
])
def test_textbook_values(B, shape, axis_value, trans_value):
    I = components(shape.central_inertia(B), B)
    assert sp.simplify(I[0, 0] - axis_value) == 0
    assert sp.simplify(I[1, 1] - trans_value) == 0 and sp.simplify(I[2, 2] - trans_value) == 0


def test_given_inertia_about_reference_point_is_transferred(B):
    # a rod of length L about its end: m L²/3; the centre L/2 along x
    shape = rk.shapes.Inertia(m, 0, m * L**2 / 3, m * L**2 / 3, centre=(L / 2, 0, 0), about="reference")
    I = components(shape.central_inertia(B), B)
    assert sp.simplify(I[1, 1] - m * L**2 / 12) == 0
