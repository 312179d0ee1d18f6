"""Dimensional analysis: every derived equation is consistent; a wrong equation is flagged, term named."""

import pytest
import sympy as sp
from sympy import sin
from sympy.physics.vector import dynamicsymbols

from rigidkin.base.dimensions import (
    FORCE,
    DimensionMismatch,
    check_equation,
    check_solution,
    dimension_of,
    symbol_dimensions,
)
from rigidkin.base.units import LENGTH, MASS, ONE, TIME
from rigidkin.examples import build

t = dynamicsymbols._t

CARDS = ["ladder", "disk-in-track", "disk-spring-incline", "rod-impulse", "sphere-on-sphere", "collar-rod",
         "collar-force", "slip-to-roll", "paper-pull", "boulder-push"]


def test_missing_length_factor_is_flagged_and_named():
    s = build("disk-spring-incline")
    m, r, K, g, beta = (s.parameters[n] for n in ["m", "r", "K", "g", "beta"])
    th = s.coordinates[0]
    dims = symbol_dimensions(s)
    good = check_equation(sp.Rational(3, 2) * m * r**2 * th.diff(t, 2) + K * r**2 * th, m * g * r * sin(beta), dims)
    assert good.consistent and good.dimension == MASS * LENGTH**2 / TIME**2
    wrong_term = K * r * th                      # a length factor missing
    bad = check_equation(sp.Rational(3, 2) * m * r**2 * th.diff(t, 2) + wrong_term, m * g * r * sin(beta), dims)
    assert not bad.consistent
    ((term, dim, why),) = bad.offending
    assert term == wrong_term and dim == MASS * LENGTH / TIME**2
    assert bad.dimension == MASS * LENGTH**2 / TIME**2
    assert "K·r·θ" in str(bad) and "M·L·T^-2" in str(bad) and "M·L^2·T^-2" in str(bad)


def test_symbol_and_function_rules():
    s = build("ladder")
    m, l, g = (s.parameters[n] for n in ["m", "l", "g"])
    th = s.coordinates[0]
    dims = symbol_dimensions(s, s.solve().setup)
    assert dimension_of(th.diff(t, 2), dims) == ONE / TIME**2          # an angle is dimensionless
    assert dimension_of(m * g, dims) == FORCE
    assert dimension_of(sp.Symbol("N_A", real=True), dims) == FORCE   # a reaction force
    assert dimension_of(sp.sqrt(g / l), dims) == ONE / TIME
    with pytest.raises(DimensionMismatch, match="argument"):
        dimension_of(sin(l), dims)
    with pytest.raises(DimensionMismatch, match="has dimension"):
        dimension_of(l + g, dims)
    with pytest.raises(DimensionMismatch, match="not known"):
        dimension_of(sp.Symbol("zz"), dims)
    # a length coordinate: the collar's x
    s2 = build("collar-rod")
    x = s2.coordinates[0]
    assert dimension_of(x.diff(t), symbol_dimensions(s2)) == LENGTH / TIME


@pytest.mark.parametrize("name", CARDS)
def test_every_derived_equation_is_consistent(name):
    sol = build(name).solve()
    reports = check_solution(sol)
    assert reports and all(r.consistent for r in reports), [str(r) for r in reports if not r.consistent]


@pytest.mark.parametrize("method", ["about-point:P", "work-energy", "lagrange", "kane"])
def test_other_laws_equations_are_consistent(method):
    sol = build("disk-in-track").solve(method=method)
    reports = check_solution(sol)
    assert all(r.consistent for r in reports), [str(r) for r in reports if not r.consistent]


def test_answers_of_the_impulse_and_energy_laws_have_the_right_dimensions():
    from rigidkin.derive.laws import energy, impulse

    s = build("rod-impulse")
    th = s.coordinates[0]
    dims = symbol_dimensions(s)
    w = impulse.impulsive(s).rate(th)
    assert dimension_of(w, dims) == ONE / TIME                      # ω′ = 6 F̂/(m l)
    theta_max = energy.energy_balance(s, {th: 0, th.diff(t): w}, {th.diff(t): 0}, th)[th]
    assert dimension_of(theta_max, dims) == ONE                     # an angle
    s = build("slip-to-roll")
    x, phi = s.coordinates
    dims = symbol_dimensions(s)
    vB = sp.sqrt(2 * s.parameters["g"] * s.parameters["d"] * sin(s.parameters["beta"]))
    res = impulse.interval(s, {x.diff(t): vB, phi.diff(t): 0}, until="ground")
    assert dimension_of(res.duration, dims) == TIME
    assert dimension_of(res.rate(x), dims) == LENGTH / TIME
    assert dimension_of(res.rate(phi), dims) == ONE / TIME
