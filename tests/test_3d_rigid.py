"""Three-dimensional rigid-body dynamics against closed forms: Euler's 2nd law with the gyroscopic
ω × H̄ terms, principal axes, steady motions of a torque-free body, a heavy top and a gyroscope.

Every check compares rigidkin's Newton–Euler derivation (``System.solve``) with a result derived
independently by hand in the classical literature (Goldstein, Classical Mechanics §5.6–5.7; Kane &
Levinson, Dynamics: Theory and Applications §4): Lagrange's equations of the heavy top in Euler
angles, the sleeping-top criterion, the intermediate-axis instability, the gyroscope's precession.
"""

from __future__ import annotations

import random

import numpy as np
import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

import rigidkin as rk
from rigidkin.analysis.steady import linearise, residual
from rigidkin.base import algebra
from rigidkin.examples import gyroscope, heavy_top, torque_free
from rigidkin.model.principal import principal_axes

t = dynamicsymbols._t
lam = sp.Symbol("lambda")


def _num(expr, values):
    plain, back = algebra.plain_state(sp.sympify(expr))
    fwd = {s: values[back[s]] for s in plain.free_symbols if s in back}
    rest = {k: v for k, v in values.items() if isinstance(k, sp.Symbol)}
    return complex(plain.xreplace({**fwd, **rest}).evalf(30))


# principal axes ----------------------------------------------------------------------------------
def test_principal_axes_of_a_box_seen_from_a_turned_frame():
    """A box's inertia resolved in a frame turned by β about y has one product of inertia; the closed
    form recovers the box's own axes and its moments m(b²+c²)/12, m(a²+c²)/12, m(a²+b²)/12."""
    s = rk.System("box")
    m, a, b, c = (s.parameter(n) for n in "mabc")
    A = s.frame("A")
    B = s.frame("B", parent=A, angle=sp.Rational(2, 5), axis="y")
    pa = principal_axes(inertia=rk.shapes.Box(m, a, b, c).central_inertia(B), frame=A)
    vals = {m: 2.0, a: 0.5, b: 0.3, c: 0.9}
    want = sorted([2.0 * (0.3**2 + 0.9**2) / 12, 2.0 * (0.5**2 + 0.9**2) / 12, 2.0 * (0.5**2 + 0.3**2) / 12])
    got = sorted(float(sp.sympify(x).xreplace(vals)) for x in pa.moments)   # symbolic: frame order
    assert got == pytest.approx(want, rel=1e-12)
    I = rk.shapes.Box(m, a, b, c).central_inertia(B)
    for mom, ax in zip(pa.moments, pa.axes):
        # I·e = λ e, and e is one of the box's edges (±Bx, ±By, ±Bz)
        resid = I.dot(ax) - mom * ax
        assert all(abs(_num(resid.dot(e), vals)) < 1e-12 for e in (A.x, A.y, A.z))
        assert max(abs(_num(ax.dot(e), vals)) for e in (B.x, B.y, B.z)) == pytest.approx(1, abs=1e-12)
    assert _num(pa.axes[0].cross(pa.axes[1]).dot(pa.axes[2]), vals) == pytest.approx(1)


def test_principal_axes_numeric_route_and_about_a_point():
    """Rear frame of the benchmark bicycle (Meijaard et al. 2007, Table 1, I_B): two products are not
    needed — one is; a general inertia with three products goes numeric; a rod about its end."""
    s = rk.System("frame")
    F = s.inertial
    B = s.frame("B")
    pa = principal_axes(inertia=rk.shapes.Inertia(85, 9.2, 11, 2.8, 0, 0, 2.4).central_inertia(B), frame=B)
    assert [float(x) for x in pa.moments] == pytest.approx([2.0, 10.0, 11.0], rel=1e-12)   # eigenvalues of I_B
    gen = rk.shapes.Inertia(1, 3.0, 4.0, 5.0, 0.3, -0.4, 0.5).central_inertia(B)
    pa = principal_axes(inertia=gen, frame=B)
    assert sum(float(x) for x in pa.moments) == pytest.approx(12.0, rel=1e-12)          # the trace
    rebuilt = pa.dyadic().to_matrix(B.ref) - gen.to_matrix(B.ref)
    assert max(abs(float(x)) for x in rebuilt) < 1e-12
    with pytest.raises(rk.ModelError, match="no closed form"):
        Ixx = s.parameter("Ixx")
        principal_axes(inertia=rk.shapes.Inertia(1, Ixx, 4, 5, 0.3, -0.4, 0.5).central_inertia(B), frame=B)
    # a slender rod about its end: 0 along it, m l²/3 across
    m, l = s.parameter("m"), s.parameter("l")
    G = s.point("G", offset=l / 2 * F.x)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="x"), frame=B, at=G)
    end = s.point("E", offset=0, body=rod)
    pa = principal_axes(rod, about=end)
    assert {sp.simplify(x) for x in pa.moments} == {0, m * l**2 / 3}


# torque-free body ----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def book():
    s = torque_free.build()
    return s, s.solve()


@pytest.mark.slow
def test_intermediate_axis_spin_is_unstable_at_the_closed_form_rate(book):
    s, sol = book
    q1, q2, q3, x, y, z = sol.coordinates
    Om = sp.Symbol("Omega", positive=True)
    at = {q2: 0, q3: 0, q1.diff(t): Om, q2.diff(t): 0, q3.diff(t): 0, x.diff(t): 0, y.diff(t): 0, z.diff(t): 0}
    sm = linearise(sol, at)
    assert set(sm.ignorable) == {q1, x, y, z}
    P = s.parameters
    m, a, b, c = P["m"], P["a"], P["b"], P["c"]
    I1, I2, I3 = m * (b**2 + c**2) / 12, m * (a**2 + c**2) / 12, m * (a**2 + b**2) / 12
    rate = Om * sp.sqrt((I2 - I1) * (I3 - I2) / (I1 * I3))
    poly = sm.characteristic_polynomial(lam)
    assert algebra.is_zero(poly.subs(lam, rate)) and algebra.is_zero(poly.subs(lam, -rate))
    vals = {**s.parameter_values(), Om: 10.0}
    ev = sm.eigenvalues(vals)
    assert ev.real.max() == pytest.approx(float(rate.xreplace(vals)), rel=1e-10)
    # spin about the axis of the largest moment (z; a 3-2-1 sequence starts about it): no growing mode
    s2 = rk.System("book2")
    mm, aa, bb, cc = (s2.parameter(n, value=v) for n, v in zip("mabc", (1.0, 0.24, 0.16, 0.04)))
    r1, r2, r3 = (s2.coordinate(n) for n in ("r1", "r2", "r3"))
    B2 = s2.frame("B2", sequence="321", angles=(r1, r2, r3))
    s2.body("book", rk.shapes.Box(mm, aa, bb, cc), frame=B2, at=s2.origin)
    sol2 = s2.solve()
    sm2 = linearise(sol2, {r2: 0, r3: 0, r1.diff(t): 10.0, r2.diff(t): 0, r3.diff(t): 0})
    assert sm2.eigenvalues(s2.parameter_values()).real.max() < 1e-8


def test_energy_and_angular_momentum_are_conserved_in_simulation(book):
    from rigidkin.numeric.simulate import simulate

    s, _ = book
    res = simulate(s, 1.5)
    assert res.status == "completed"
    assert res.energy_drift < 1e-9
    body = s.bodies["book"]
    from rigidkin.derive.kinematics import Kinematics

    kin = Kinematics(s)
    w = kin.omega_of(body)
    H = body.inertia.dot(w)
    F = s.inertial
    comps = [H.dot(e) for e in (F.x, F.y, F.z)]
    T = H.dot(w) / 2
    vals = s.parameter_values()
    qs = s.coordinates
    args = [sp.Symbol(f"q_{i}") for i in range(len(qs))] + [sp.Symbol(f"u_{i}") for i in range(len(qs))]
    rep = {q.diff(t): args[len(qs) + i] for i, q in enumerate(qs)}
    rep2 = {q: args[i] for i, q in enumerate(qs)}
    f = sp.lambdify(args, [sp.sympify(e).xreplace(rep).xreplace(rep2).xreplace(vals) for e in comps + [T]])
    out = np.array([f(*row) for row in res.y])
    H2 = (out[:, :3] ** 2).sum(axis=1)
    assert np.ptp(H2) < 1e-9 * H2[0]
    assert np.ptp(out[:, 3]) < 1e-9 * out[0, 3]
    # the inertial components of H̄ are conserved one by one (no torque), though the book tumbles
    assert np.abs(out[:, :3] - out[0, :3]).max() < 1e-8 * np.sqrt(H2[0])
    assert np.abs(res.q["q2"]).max() > 0.5          # it does flip over: the intermediate axis is unstable


# heavy symmetric top ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def top313():
    s = heavy_top.build("313")
    return s, s.solve()


def test_top_nutation_equation_is_lagranges(top313):
    """I1 θ̈ = I1 ψ̇² sinθ cosθ − I3 ω3 ψ̇ sinθ + m g l sinθ, ω3 = φ̇ + ψ̇ cosθ (I1 about the tip)."""
    s, sol = top313
    psi, th, phi = sol.coordinates
    P = s.parameters
    m, g, l, I1, I3 = (P[k] for k in ("m", "g", "l", "I1", "I3"))
    w3 = phi.diff(t) + psi.diff(t) * sp.cos(th)
    want = (I1 * psi.diff(t) ** 2 * sp.sin(th) * sp.cos(th) - I3 * w3 * psi.diff(t) * sp.sin(th)
            + m * g * l * sp.sin(th)) / I1
    # ψ̈ and φ̈ from the conservation of the vertical and axial angular momenta
    H3 = I3 * w3
    Hz = I1 * psi.diff(t) * sp.sin(th) ** 2 + H3 * sp.cos(th)
    rng = random.Random(3)
    M, f = sol.mass_matrix, sol.forcing
    for _ in range(4):
        vals = {k: rng.uniform(0.5, 2.0) for k in (m, g, l, I3)}
        vals[I1] = vals[m] * vals[l] ** 2 + rng.uniform(0.5, 2.0)
        state = {th: rng.uniform(0.3, 1.2), psi: 0.4, phi: 0.1, psi.diff(t): rng.uniform(-2, 2),
                 th.diff(t): rng.uniform(-2, 2), phi.diff(t): rng.uniform(-5, 5)}
        plain = {**{q.diff(t): sp.Float(state[q.diff(t)]) for q in sol.coordinates},
                 **{q: sp.Float(state[q]) for q in sol.coordinates}, **vals}
        acc = M.xreplace(plain).evalf().LUsolve(f.xreplace(plain).evalf())
        assert float(acc[1]) == pytest.approx(_num(want, {**state, **vals}).real, rel=1e-9)
        # dHz/dt = 0 and dH3/dt = 0 along the motion
        for H in (Hz, H3):
            dH = sp.diff(H, t).xreplace({q.diff(t, 2): a for q, a in zip(sol.coordinates, acc)})
            assert abs(_num(dH, {**state, **vals})) < 1e-9


def test_top_steady_precession_condition(top313):
    """Steady precession at nutation θ0: m g l = ψ̇ ω3 I3 − I1 ψ̇² cos θ0 (θ̈ = 0 exactly there)."""
    s, sol = top313
    psi, th, phi = sol.coordinates
    vals = s.parameter_values()
    P = s.parameters
    m, g, l, I1, I3 = (vals[P[k]] for k in ("m", "g", "l", "I1", "I3"))
    th0, spin = 0.5, 150.0
    # the slow precession root of I1 cosθ ψ̇² − I3 φ̇ ψ̇ − I3 cosθ ψ̇² ... written with ω3 = φ̇ + ψ̇ cosθ
    a2 = I1 * np.cos(th0) - I3 * np.cos(th0)
    roots = np.roots([a2, -I3 * spin, m * g * l])
    slow = min(roots, key=abs).real
    at = {th: th0, th.diff(t): 0, psi.diff(t): slow, phi.diff(t): spin}
    res = residual(sol, at)
    assert all(abs(float(r.xreplace(vals))) < 1e-9 for r in res.values())
    at[psi.diff(t)] = slow * 1.01
    assert abs(float(residual(sol, at)[th].xreplace(vals))) > 1e-3


def test_sleeping_top_stability_criterion():
    """Upright spin ω3 (tilt angles regular there): det(λI − A) ∝ λ [(I1 λ² − m g l)² + (I3 ω3 λ)²],
    stable exactly when I3² ω3² > 4 I1 m g l."""
    s = heavy_top.build("123")
    sol = s.solve()
    al, be, phi = sol.coordinates
    w3 = sp.Symbol("omega3", positive=True)
    sm = linearise(sol, {al: 0, be: 0, al.diff(t): 0, be.diff(t): 0, phi.diff(t): w3})
    assert sm.ignorable == (phi,)
    P = s.parameters
    m, g, l, I1, I3 = (P[k] for k in ("m", "g", "l", "I1", "I3"))
    want = lam * ((I1 * lam**2 - m * g * l) ** 2 + (I3 * w3 * lam) ** 2)
    got = sm.characteristic_polynomial(lam)
    assert algebra.is_zero(sp.cancel(got * I1**2 - want))
    vals = s.parameter_values()
    crit = 2 * np.sqrt(float((I1 * m * g * l).xreplace(vals))) / vals[I3]
    assert sm.eigenvalues({**vals, w3: 1.05 * crit}).real.max() < 1e-7
    assert sm.eigenvalues({**vals, w3: 0.95 * crit}).real.max() > 1e-3


# gyroscope -------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def gyro():
    s = gyroscope.build()
    return s, s.solve()


@pytest.mark.slow
def test_gyroscope_precesses_at_mgl_over_spin_momentum(gyro):
    s, sol = gyro
    psi, th, phi = sol.coordinates
    vals = s.parameter_values()
    P = s.parameters
    m, g, l, r = (vals[P[k]] for k in ("m", "g", "l", "r"))
    I3 = m * r**2 / 2
    spin = 300.0
    Om = m * g * l / (I3 * spin)
    at = {th: 0, th.diff(t): 0, psi.diff(t): Om, phi.diff(t): spin}
    res = residual(sol, at)
    assert all(abs(float(v.xreplace(vals))) < 1e-9 for v in res.values())
    assert abs(float(residual(sol, {**at, psi.diff(t): 1.1 * Om})[th].xreplace(vals))) > 1e-3
    # reactions: the base carries the weight m g and the centripetal force m l Ω² towards the axis;
    # the bearings press on the rotor with the gyroscopic couple I3 s Ω = m g l about By
    state = {psi: 0.3, phi: 0.2, **at}
    R = {k: _num(sp.sympify(v).xreplace(vals), state).real for k, v in sol.reactions.items()}
    F = s.inertial
    A = s.frames["A"]
    assert R["R_Az"] == pytest.approx(m * g, rel=1e-9)
    radial = float(_num((R["R_Ax"] * F.x + R["R_Ay"] * F.y).dot(A.x), state).real)
    assert radial == pytest.approx(-m * l * Om**2, rel=1e-9)
    assert R["M_bearingy"] == pytest.approx(I3 * spin * Om, rel=1e-9)
    assert R["M_bearingy"] == pytest.approx(m * g * l, rel=1e-9)
    assert abs(R["M_bearingz"]) < 1e-9


def test_gyroscope_holds_the_axle_up_only_while_it_spins(gyro):
    """Without spin the unsupported axle falls: θ̈ = −m g l cosθ / (I1 + m l²) at rest."""
    s, sol = gyro
    psi, th, phi = sol.coordinates
    vals = s.parameter_values()
    P = s.parameters
    m, g, l, r = (vals[P[k]] for k in ("m", "g", "l", "r"))
    res = residual(sol, {th: 0.2, th.diff(t): 0, psi.diff(t): 0, phi.diff(t): 0})
    I1 = m * r**2 / 4
    assert float(res[th].xreplace(vals)) == pytest.approx(-m * g * l * np.cos(0.2) / (I1 + m * l**2), rel=1e-9)


@pytest.mark.slow
def test_top_about_the_tip_and_by_lagrange_agree_with_the_mass_centre_form(top313):
    """Euler's 2nd law about the fixed tip O (no inertial-moment term: O is fixed) and Lagrange's
    equations give the same motion as Euler's laws about the mass centre."""
    s, sol = top313
    for method in ("about-point:O", "lagrange"):
        other = s.solve(method=method)
        for q in sol.coordinates:
            assert algebra.is_zero(other.accelerations[q] - sol.accelerations[q]), (method, q)
