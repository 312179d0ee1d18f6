"""Time in every answer: integrals and events of a system driven by a law of t say that they hold only for
that law; the rod on a shaft turned at constant Ω has the Jacobi integral (checked by hand), not the
conservation of T + U; a support or coordinate moved by a law of t has no energy integral."""

import sys
from pathlib import Path

import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.analysis.events import extreme
from rigidkin.analysis.integrals import energy_integral, first_integrals
from rigidkin.base.errors import RigidkinError
from rigidkin.examples import build

sys.path.insert(0, str(Path(__file__).parent))
from test_prescribed_coordinates import shaken_cart  # noqa: E402

t = rk.t


def shaft():
    s = build("driven-shaft")
    P = s.parameters
    th = s.coordinate_info["theta"].symbol
    return s, P["m"], P["l"], P["g"], P["Omega"], th


def test_rod_on_a_spinning_shaft_has_the_jacobi_integral_by_hand():
    s, m, l, g, W, th = shaft()
    sol = s.solve()
    ei = energy_integral(sol, {th: sp.Rational(1, 2), th.diff(t): 0})
    assert ei.name == "Jacobi integral" and "only for the given driving law" in ei.note and "Omega*t" in ei.note
    # by hand: T = ⅙ m l²(θ̇² + Ω² sin²θ), U = −½ m g l cos θ; h = T₂ − T₀ + U constant
    th0 = sp.Rational(1, 2)
    hand = W**2 * (sp.sin(th) ** 2 - sp.sin(th0) ** 2) + 3 * g / l * (sp.cos(th) - sp.cos(th0))
    assert sp.simplify(ei.rate_squared - hand) == 0
    found = {fi.name: fi for fi in first_integrals(sol)}
    assert "energy" not in found                     # the motor does work: T + U is not constant
    h = found["Jacobi integral"]
    u = th.diff(t)
    by_hand = m * l**2 / 6 * (u**2 - W**2 * sp.sin(th) ** 2) - m * g * l / 2 * sp.cos(th)
    assert sp.simplify(h.expression - by_hand) == 0
    assert "only for the given driving law" in h.why


@pytest.mark.slow
def test_event_of_a_driven_system_names_its_driving_law():
    s, m, l, g, W, th = shaft()
    sol = s.solve()
    ev = extreme(sol, th, {th: sp.Rational(1, 2), th.diff(t): 0})
    vals = s.parameter_values()
    # θ̇ = 0 again where cos θ = 3g/(Ω² l) − cos θ0 (the Jacobi integral by hand)
    want = sp.acos(3 * g / (W**2 * l) - sp.cos(sp.Rational(1, 2))).subs(vals)
    assert float(sp.sympify(ev.value).subs(vals)) == pytest.approx(float(want), rel=1e-9)
    assert any("only for the given driving law" in n and "Omega*t" in n for n in ev.notes)


def test_no_energy_integral_when_the_law_puts_t_in_the_equations():
    s = shaken_cart()[0]
    with pytest.raises(RigidkinError, match=r"depends explicitly on time \(the driving law x = A\*sin\(omega\*t\)\)"):
        energy_integral(s.solve())
    assert not [fi for fi in first_integrals(s.solve()) if fi.name in ("energy", "Jacobi integral")]


def test_an_undriven_system_keeps_its_plain_energy_integral():
    s = rk.System("pendulum")
    m, l, g = s.parameter("m", "kg"), s.parameter("l", "m"), s.parameter("g", "m/s^2")
    th = s.coordinate("theta", initial=0.3)
    R = s.frame("R", angle=th)
    s.pin("O", s.origin, s.body("bob", rk.shapes.PointMass(m), frame=R, at=s.point("B", offset=-l * R.y)))
    s.gravity(g)
    ei = energy_integral(s.solve())
    assert ei.name == "energy integral" and ei.note == ""
    assert sp.simplify(ei.rate_squared - 2 * g / l * (sp.cos(th) - sp.cos(sp.Rational(3, 10)))) == 0
