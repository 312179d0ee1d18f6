"""Euler's 2nd law about a point: the inertial-moment term, reactions through P, agreement with Newton–Euler."""

import pytest
import sympy as sp
from helpers import values_match
from sympy import cos, sin
from sympy.physics.vector import dynamicsymbols

from rigidkin.base.errors import ModelError
from rigidkin.derive.laws import about_point
from rigidkin.derive.mode import setup_mode
from rigidkin.examples import build

t = dynamicsymbols._t


def P(s, name):
    return s.parameters[name]


def _steps(sol, word):
    return [st for st in sol.trace.steps if word in st.title]


def test_disk_in_track_about_contact_point():
    s = build("disk-in-track")
    m, r, R, g = (P(s, n) for n in ["m", "r", "R", "g"])
    th = s.coordinates[0]
    sol = s.solve(method="about-point:P")
    # the material contact point accelerates (towards C) yet the inertial moment vanishes: r̄ − r_P ∥ a_P
    (inertial,) = _steps(sol, "Inertial moment")
    assert "parallel" in inertial.why and "vanishes" in inertial.why.lower()
    (kin_step,) = _steps(sol, "The point P")
    aP = dict((str(k), v) for k, v in kin_step.equations)["a_P"]
    A = s.frames["A"]
    # card: a_P = (R − r)(1 + (R − r)/r) θ̇² towards C (er_in = A.y points from C towards O; P is beyond C)
    assert sp.simplify(aP.dot(A.y) - (R - r) * (1 + (R - r) / r) * th.diff() ** 2) == 0
    assert sp.simplify(aP.dot(A.x)) == 0
    # a single equation about P holds no reaction and is the card's EOM
    eqs = about_point.equations(setup_mode(s), "P")
    (free,) = about_point.reaction_free(setup_mode(s), eqs)
    card = sp.Rational(3, 2) * m * (R - r) * th.diff(t, 2) + m * g * sin(th)
    assert values_match(free.expr, card, [th], factor=True, ranges={"R": (2, 4), "r": (0.2, 1)})
    ne = s.solve()
    assert values_match(sol.accelerations[th], ne.accelerations[th], [th])
    assert values_match(sol.reactions["N"], ne.reactions["N"], [th], ranges={"R": (2, 4), "r": (0.2, 1)})


def test_collar_force_about_O():
    s = build("collar-force")
    m, l, g = (P(s, n) for n in ["m", "l", "g"])
    x, th = s.coordinates
    setup = setup_mode(s)
    eqs = about_point.equations(setup, "O")
    (free,) = about_point.reaction_free(setup, eqs)
    assert free.body == "rod"
    card2 = m * x.diff(t, 2) * cos(th) + 2 * m * l / 3 * th.diff(t, 2) + m * g * sin(th)
    assert values_match(free.expr, card2, [x, th], factor=True)
    # and the second EOM of Newton–Euler (mass centre) is the same equation
    ne = s.solve()
    assert values_match(free.expr, ne.eom[1], [x, th], factor=True)
    sol = build("collar-force").solve(method="about-point:O")
    (inertial,) = _steps(sol, "Inertial moment of rod")
    assert "stays in the equation" in inertial.why
    assert sp.simplify(inertial.equations[0][1].dot(sol.system.inertial.z) + m * l / 2 * cos(th) * x.diff(t, 2)) == 0
    x, th = sol.system.coordinates
    for q in (x, th):
        assert values_match(sol.accelerations[q], ne.accelerations[q], [x, th])


def test_fixed_point_and_mass_centre_reasons():
    s = build("rod-impulse")
    sol = s.solve(method="about-point:O")
    assert "fixed" in _steps(sol, "Inertial moment")[0].why
    s = build("slip-to-roll")
    sol = s.solve(method="about-point:C")
    assert "mass centre" in _steps(sol, "Inertial moment")[0].why
    ne = s.solve()
    for a, b in zip(sol.regimes, ne.regimes):
        for q in s.coordinates:
            assert values_match(a.accelerations[q], b.accelerations[q], list(s.coordinates))


def test_ladder_about_moving_foot():
    s = build("ladder")
    sol = s.solve(method="about-point:B")
    th = s.coordinates[0]
    ne = s.solve()
    assert "stays in the equation" in _steps(sol, "Inertial moment")[0].why
    assert values_match(sol.accelerations[th], ne.accelerations[th], [th])
    assert values_match(sol.reactions["N_A"], ne.reactions["N_A"], [th])


def test_unknown_point():
    s = build("ladder")
    with pytest.raises(ModelError, match="no point or constraint named 'Q'"):
        s.solve(method="about-point:Q")
    with pytest.raises(ModelError, match="needs the point"):
        s.solve(method="about-point")
