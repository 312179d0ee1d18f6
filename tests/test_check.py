"""Cross-check: every law that applies, compared; disagreements and wrong expectations are caught."""

import pytest
import sympy as sp
from helpers import rod_pendulum
from sympy import cos, sin
from sympy.physics.vector import dynamicsymbols

import rigidkin as rk
from rigidkin.base.printing import text
from rigidkin.derive.laws.crosscheck import compare, cross_check, expectation, numerically_equal
from rigidkin.examples import build

t = dynamicsymbols._t


def _by_law(report):
    out = {}
    for v in report.verdicts:
        out.setdefault(v.law, []).append(v)
    return out


@pytest.mark.slow
def test_disk_in_track_five_ways_agree():
    rep = build("disk-in-track").solve().check()
    laws = _by_law(rep)
    assert set(laws) == {"about-point:P", "work-energy", "lagrange", "kane"}   # + the reference, newton-euler
    assert all(v.status == "agrees" for vs in laws.values() for v in vs)
    assert rep.ok and "All agree." in str(rep)
    assert any(v.equation.endswith("reaction-free 2nd law") for v in laws["about-point:P"])


def test_collar_force_second_eom_about_O():
    rep = build("collar-force").solve().check(laws=["about-point:O", "work-energy"])
    laws = _by_law(rep)
    (row,) = [v for v in laws["about-point:O"] if "reaction-free" in v.equation]
    assert row.status == "agrees" and row.equation.startswith("rod")
    assert laws["work-energy"][0].status == "does not apply" and "2 degrees of freedom" in laws["work-energy"][0].how
    assert rep.ok


def _pendulum(shape):
    return rod_pendulum(shape)[0]


def test_a_disagreement_is_reported_with_both_expressions():
    from rigidkin.derive.laws.crosscheck import _compare_solutions

    good = _pendulum(lambda m, l: rk.shapes.SlenderRod(m, l, axis="y")).solve()
    wrong = _pendulum(lambda m, l: rk.shapes.PointMass(m)).solve()    # a different inertia
    th = good.coordinates[0]
    (v,) = [v for v in _compare_solutions(good, wrong, "lagrange") if v.equation == text(th.diff(t, 2))]
    assert v.status == "disagrees" and v.failed
    assert v.ours is not None and v.reference is not None
    assert not compare(v.ours, v.reference)[0]


def test_compare_decides_symbolically_or_numerically():
    x = sp.Symbol("x", positive=True)
    assert compare(sin(x) ** 2, 1 - cos(x) ** 2) == (True, "symbolic: the difference simplifies to 0")
    big = sum(sin(k * x) ** 2 for k in range(1, 40))
    ok, how = compare(big, sum(1 - cos(k * x) ** 2 for k in range(1, 40)))
    assert ok and how.startswith("numeric") and "24 random" in how
    assert not numerically_equal(sin(x), sin(x) + 1e-6)


@pytest.mark.slow
def test_expectation_equivalent_and_wrong():
    s = build("collar-force")
    m, l, g, P = (s.parameters[n] for n in ["m", "l", "g", "P"])
    x, th = s.coordinates
    sol = s.solve()
    right = sp.Eq(m * x.diff(t, 2) * cos(th) + 2 * m * l / 3 * th.diff(t, 2) + m * g * sin(th), 0)
    assert expectation(sol, right).equivalent
    first = sp.Eq(m * x.diff(t, 2) + m * l / 2 * (th.diff(t, 2) * cos(th) - th.diff() ** 2 * sin(th)), P)
    assert expectation(sol, first).equivalent
    wrong = sp.Eq(m * x.diff(t, 2) * cos(th) + m * l / 3 * th.diff(t, 2) + m * g * sin(th), 0)
    e = expectation(sol, wrong)
    assert not e.equivalent
    assert any(a is not None and a.has(th.diff(t, 2)) for a, _ in e.differences)
    assert e.dimensions.consistent
    no_accel = expectation(sol, m * g)
    assert not no_accel.equivalent and "neither an acceleration" in no_accel.how


def test_expected_reaction():
    s = build("rod-impulse")            # the pin at the mass centre carries the weight, nothing else
    m, g = s.parameters["m"], s.parameters["g"]
    sol = s.solve()
    Ry, Rx = sp.Symbol("R_Oy", real=True), sp.Symbol("R_Ox", real=True)
    assert expectation(sol, sp.Eq(Ry, m * g)).equivalent
    assert expectation(sol, Rx).equivalent
    wrong = expectation(sol, sp.Eq(Ry, 2 * m * g))
    assert not wrong.equivalent and "reactions" in wrong.how
    assert sp.simplify(wrong.residual + m * g) == 0 or sp.simplify(wrong.residual - m * g) == 0


def test_expectation_in_a_regime():
    s = build("boulder-push")
    m, g, beta, P, mu = (s.parameters[n] for n in ["m", "g", "beta", "P", "mu"])
    x = s.coordinates[0]
    up = sp.Rational(7, 5) * m * x.diff(t, 2) + m * g * sin(beta) - P * (1 - mu)
    e = expectation(s.solve(), up)
    assert e.equivalent and e.regime is not None
    rep = cross_check(s.solve(), laws=["kane"])
    assert rep.ok and len([v for v in rep.verdicts if v.equation.startswith(text(x.diff(t, 2)))]) == 2


def test_check_is_recorded_in_the_trace_once():
    sol = build("rod-impulse").solve()
    sol.check()
    sol.check()
    titles = [st.title for st in sol.trace.section("Checks")]
    assert titles.count("Cross-check: kane") == 1 and "Dimensions" in titles
    assert "agrees" in next(st for st in sol.trace.section("Checks") if st.title == "Cross-check: lagrange").why
