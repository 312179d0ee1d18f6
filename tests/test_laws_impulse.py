"""Impulse–momentum and work–energy answer the cards rod-impulse, paper-pull and slip-to-roll."""

import pytest
import sympy as sp
from sympy import cos, sin, sqrt
from sympy.physics.vector import dynamicsymbols

from rigidkin.base.errors import RigidkinError
from rigidkin.derive.laws import energy, impulse
from rigidkin.examples import build

t = dynamicsymbols._t


def P(s, name):
    return s.parameters[name]


def test_rod_impulse_card():
    s = build("rod-impulse")
    m, l, K, F = (P(s, n) for n in ["m", "l", "K", "F_hat"])
    th = s.coordinates[0]
    # (a) angular velocity just after the impulse
    res = impulse.impulsive(s)
    w = res.rate(th)
    assert sp.simplify(w - 6 * F / (m * l)) == 0
    # the pivot's reaction impulse cancels the blow: the mass centre stays at rest (linear impulse = 0)
    Rx, Ry = res.reaction_impulses["R_Ox_hat"], res.reaction_impulses["R_Oy_hat"]
    assert sp.simplify(Rx + F * cos(th)) == 0 and sp.simplify(Ry + F * sin(th)) == 0
    # (b) largest angle afterwards, by conservation of energy (spring K θ²/2; gravity does no work)
    theta_max = energy.energy_balance(s, {th: 0, th.diff(t): w}, {th.diff(t): 0}, th)[th]
    assert sp.simplify(theta_max - F * sqrt(3 / (m * K))) == 0
    assert sp.simplify(theta_max - w * sqrt(m * l**2 / (12 * K))) == 0


def test_rod_impulse_before_rate_and_configuration():
    s = build("rod-impulse")
    m, l, F = (P(s, n) for n in ["m", "l", "F_hat"])
    th = s.coordinates[0]
    w0 = sp.Symbol("w0")
    res = impulse.impulsive(s, before={th.diff(t): w0}, at={th: 0})
    assert sp.simplify(res.rate(th) - w0 - 6 * F / (m * l)) == 0
    assert res.reaction_impulses["R_Ox_hat"] == -F and res.reaction_impulses["R_Oy_hat"] == 0


def test_paper_pull_card():
    s = build("paper-pull")
    mu, g, r, dt, V = (P(s, n) for n in ["mu", "g", "r", "dt", "V"])
    x, phi = s.coordinates
    res = impulse.interval(s, {x.diff(t): 0, phi.diff(t): 0}, duration=dt)
    assert sp.simplify(res.rate(x) - mu * g * dt) == 0            # (a) v = µ g Δt, along +Ex
    assert sp.simplify(res.rate(phi) - 2 * mu * g * dt / r) == 0  # (b) ω = 2µgΔt/r, counter-clockwise
    # the sheet must still be faster than the contact point at the end: 3µgΔt < V
    (cond,) = res.conditions
    assert cond[1] == "<" and sp.simplify(cond[0] - (3 * mu * g * dt - V)) == 0


def test_slip_to_roll_card():
    s = build("slip-to-roll")
    mu, g, r, d, beta = (P(s, n) for n in ["mu", "g", "r", "d", "beta"])
    x, phi = s.coordinates
    # (a) frictionless stretch: energy, with the angular momentum about C conserved (no moment)
    cons = impulse.conserved_momenta(s, substitutions={mu: 0})
    assert [c.label for c in cons] == ["angular momentum of cylinder about its mass centre, along Ez"]
    end = energy.energy_balance(s, {x: 0, x.diff(t): 0, phi.diff(t): 0}, {x: d}, [x.diff(t), phi.diff(t)],
                                substitutions={mu: 0}, conserved=cons)
    vB = end[x.diff(t)]
    assert sp.simplify(vB - sqrt(2 * g * d * sin(beta))) == 0 and end[phi.diff(t)] == 0
    # (b), (c): sliding with friction until the slip speed vanishes
    res = impulse.interval(s, {x.diff(t): vB, phi.diff(t): 0}, until="ground")
    den = 3 * mu * cos(beta) - sin(beta)
    assert sp.simplify(res.duration - vB / (g * den)) == 0
    v = res.rate(x)
    assert sp.simplify(v - 2 * mu * cos(beta) * vB / den) == 0
    assert sp.simplify(res.rate(phi) - v / r) == 0
    # numerically, with the card's values: t_s > 0
    vals = s.parameter_values()
    assert float(res.duration.subs(vals)) > 0


def test_slip_never_stops_with_small_friction():
    s = build("slip-to-roll")
    mu, g, d, beta = (P(s, n) for n in ["mu", "g", "d", "beta"])
    x, phi = s.coordinates
    vB = sqrt(2 * g * d * sin(beta))
    with pytest.raises(RigidkinError, match="never reached"):
        impulse.interval(s, {x.diff(t): vB, phi.diff(t): 0}, until="ground", substitutions={mu: sp.Rational(1, 10)})


def test_interval_refuses_nonconstant_forces():
    s = build("disk-spring-incline")   # the spring force changes with θ
    th = s.coordinates[0]
    with pytest.raises(RigidkinError, match="not constant"):
        impulse.interval(s, {th.diff(t): 0}, duration=1)
    with pytest.raises(RigidkinError, match="no impulse load"):
        impulse.impulsive(s)
