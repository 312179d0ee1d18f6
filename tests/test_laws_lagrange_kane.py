"""Lagrange and Kane (sympy.physics.mechanics, their own constraint handling) against Euler's laws and cards."""

import pytest
import sympy as sp
from helpers import values_match
from sympy import sin
from sympy.physics.vector import dynamicsymbols

from rigidkin.derive.laws import NotApplicable
from rigidkin.examples import build

t = dynamicsymbols._t

APPLY = ["ladder", "sphere-on-sphere", "collar-force", "boulder-push"]
RANGES = {"R": (2, 4), "r": (0.2, 1)}


@pytest.mark.parametrize("method", ["lagrange", "kane"])
@pytest.mark.parametrize("name", APPLY)
def test_same_accelerations_as_newton_euler(name, method):
    s = build(name)
    ne = s.solve()
    sol = s.solve(method=method)
    assert len(sol.regimes) == len(ne.regimes)
    coords = list(s.coordinates)
    for a, b in zip(sol.regimes, ne.regimes):
        assert dict(a.signs) == dict(b.signs)
        for q in sol.coordinates:
            assert values_match(a.accelerations[q], b.accelerations[q], coords, ranges=RANGES), (name, q)


def test_disk_in_track_five_ways():
    s = build("disk-in-track")
    m, r, R, g = (s.parameters[n] for n in ["m", "r", "R", "g"])
    th = s.coordinates[0]
    card = sp.Rational(3, 2) * m * (R - r) * th.diff(t, 2) + m * g * sin(th)
    for method in ["newton-euler", "about-point:P", "work-energy", "lagrange", "kane"]:
        sol = s.solve(method=method)
        assert values_match(sol.eom[0], card, [th], factor=True, ranges=RANGES), method
        assert sp.simplify(sol.accelerations[th] + 2 * g * sin(th) / (3 * (R - r))) == 0, method


def test_friction_set_by_a_reaction():
    """Lagrange does not apply; Kane brings the normal force into evidence with an auxiliary speed."""
    with pytest.raises(NotApplicable, match="depends on the reaction"):
        build("slip-to-roll").solve(method="lagrange")
    for name in ("slip-to-roll", "paper-pull"):
        s = build(name)
        ne, kane = s.solve(), s.solve(method="kane")
        assert any(st.title == "Auxiliary equations" for st in kane.trace.steps)
        assert len(kane.regimes) == len(ne.regimes) == 2
        for a, b in zip(kane.regimes, ne.regimes):
            for q in s.coordinates:
                assert values_match(a.accelerations[q], b.accelerations[q], list(s.coordinates)), (name, q)


def test_lagrange_uses_constraints_not_reduction():
    s = build("sphere-on-sphere")
    sol = s.solve(method="lagrange")
    steps = {st.title: st for st in sol.trace.steps}
    cons = steps["Constraints for Lagrange's equations"]
    # the gap ρ − (R + r) as a holonomic constraint, rolling as a rate constraint; all three coordinates kept
    assert len(cons.equations) == 2
    assert len(steps["Lagrange's equations"].equations) == 3
