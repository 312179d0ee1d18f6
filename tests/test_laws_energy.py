"""Energy: T, U and the power of non-conservative loads against closed forms and against Euler's laws."""

import pytest
import sympy as sp
from helpers import values_match
from sympy import cos, sin
from sympy.physics.vector import dynamicsymbols

from rigidkin.derive.laws import energy as E
from rigidkin.derive.mode import setup_mode
from rigidkin.examples import build

t = dynamicsymbols._t

CARDS = ["ladder", "disk-in-track", "disk-spring-incline", "rod-impulse", "sphere-on-sphere", "collar-rod",
         "collar-force", "slip-to-roll", "paper-pull", "boulder-push"]


def P(s, name):
    return s.parameters[name]


def test_disk_in_track_energy_closed_form():
    s = build("disk-in-track")
    st = setup_mode(s)
    m, r, R, g = (P(s, n) for n in ["m", "r", "R", "g"])
    th = s.coordinates[0]
    # ½ m v_C² + ½ (m r²/2) φ̇² with v_C = (R − r) θ̇ and r φ̇ = (R − r) θ̇
    T_card = m * ((R - r) * th.diff()) ** 2 / 2 + m * r**2 / 4 * ((R - r) / r * th.diff()) ** 2
    assert sp.simplify(E.kinetic_energy(st) - T_card) == 0
    assert sp.simplify(E.potential_energy(st) + m * g * (R - r) * cos(th)) == 0
    (p,) = E.nonconservative_power(st)
    assert p.power == 0 and "rolling" in p.why
    assert sp.simplify(E.energy(s) - T_card + m * g * (R - r) * cos(th)) == 0


def test_ladder_and_spring_potentials():
    s = build("ladder")
    st = setup_mode(s)
    m, l, g = (P(s, n) for n in ["m", "l", "g"])
    th = s.coordinates[0]
    assert sp.simplify(E.potential_energy(st) - m * g * l / 2 * cos(th)) == 0
    assert sp.simplify(E.kinetic_energy(st) - m * l**2 * th.diff() ** 2 / 6) == 0
    assert all(p.power == 0 and "smooth" in p.why for p in E.nonconservative_power(st))
    s = build("disk-spring-incline")
    st = setup_mode(s)
    K, r, m, g, beta = (P(s, n) for n in ["K", "r", "m", "g", "beta"])
    th = s.coordinates[0]
    U = dict(E.potentials(st))
    assert sp.simplify(U["spring"] - K * (r * th) ** 2 / 2) == 0
    assert sp.simplify(U["gravity"] - m * g * (r * cos(beta) - r * th * sin(beta))) == 0


def test_sliding_friction_dissipates():
    s = build("slip-to-roll")
    st = setup_mode(s)
    x, phi = s.coordinates
    mu, N = P(s, "mu"), sp.Symbol("N", real=True)
    powers = {(p.kind, p.name): p for p in E.nonconservative_power(st)}
    fr = powers[("load", "ground")]
    assert powers[("constraint", "ground")].power == 0
    sigma = [sc.symbol for sc in st.sign_choices][0]
    slip = [sc.quantity for sc in st.sign_choices][0]
    # with σ = sign(slip speed): P = −µ N |slip speed| ≤ 0
    for sgn in (1, -1):
        Pw = fr.power.subs(sigma, sgn)
        assert values_match(Pw, -mu * N * sgn * st.scalar(slip), [x, phi])
    assert "dissipated" in fr.why


@pytest.mark.parametrize("name", CARDS)
def test_energy_rate_equals_power_along_newton_euler(name):
    """dE/dt = Σ P_nc when the accelerations and reactions of Euler's laws are substituted."""
    s = build(name)
    sol = s.solve()
    st = setup_mode(s)
    Et = E.kinetic_energy(st) + E.potential_energy(st)
    Pnc = sum((p.power for p in E.nonconservative_power(st)), sp.Integer(0))
    for reg in sol.regimes:
        acc = {q.diff(t, 2): a for q, a in reg.accelerations.items()}
        react = {sp.Symbol(k, real=True): v for k, v in reg.reactions.items()}
        resid = (sp.diff(Et, t) - Pnc).xreplace(reg.signs).xreplace(react).xreplace(acc)
        assert values_match(resid, 0, list(sol.coordinates)), name


def test_work_energy_eom_single_dof():
    s = build("disk-spring-incline")
    st = setup_mode(s)
    (eq,) = E.equations(st)
    m, r, K, beta, g = (P(s, n) for n in ["m", "r", "K", "beta", "g"])
    th = s.coordinates[0]
    card = sp.Rational(3, 2) * m * r**2 * th.diff(t, 2) + K * r**2 * th - m * g * r * sin(beta)
    assert values_match(eq.expr, card, [th], factor=True)
    with pytest.raises(Exception, match="degrees of freedom"):
        E.equations(setup_mode(build("collar-rod")))


def test_first_integral_multi_dof_and_refusal():
    s = build("collar-rod")   # two degrees of freedom, conservative
    E_ = E.first_integral(s)
    sol = s.solve()
    acc = {q.diff(t, 2): a for q, a in sol.accelerations.items()}
    assert values_match(sp.diff(E_, t).xreplace(acc), 0, list(s.coordinates))
    with pytest.raises(Exception, match="not a first integral"):
        E.first_integral(build("slip-to-roll"))
