"""A disk rolling without slip on a plane in 3D (the rolling coin): contact geometry, nonholonomic rate
relations, the upright-stability threshold Ω² > m g a I1 / (I3 (I3 + m a²)), and simulation.

The independent checks: the contact point of a leaning disk drawn by hand (C − a Lz, not C − a Ez);
the velocity of the centre from v_C = ω × (C − P) written out directly; the linearised lean–heading
equations of the upright coin (Greenwood, Advanced Dynamics §8.5; O'Reilly 1996): (I1 + m a²) θ̈ =
m g a θ − (I3 + m a²) Ω ψ̇, I1 ψ̈ = I3 Ω θ̇, so λ² = −[I3 (I3 + m a²) Ω² − m g a I1] / (I1 (I1 + m a²)).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

import rigidkin as rk
from rigidkin.analysis.steady import linearise, residual
from rigidkin.base import algebra
from rigidkin.derive.kinematics import Kinematics
from rigidkin.examples import rolling_disk

t = dynamicsymbols._t
lam = sp.Symbol("lambda")
Om = sp.Symbol("Omega", positive=True)


@pytest.fixture(scope="module")
def coin():
    s = rolling_disk.build()
    return s, s.solve()


def test_contact_point_of_a_leaning_disk_is_in_its_own_plane():
    s = rolling_disk.build()
    kin = Kinematics(s)
    con = s.constraints["P"]
    P = s.parameters
    psi, theta, phi, x, y, z = s.coordinates
    L, C = s.frames["L"], s.points["C"]
    r = con.location(kin) - kin.position(C)
    assert kin.is_zero_vector(r + P["a"] * L.z)                      # C − a Lz, in the disk's plane
    assert not kin.is_zero_vector(r + P["a"] * s.inertial.z)          # not straight below the centre
    assert algebra.is_zero(con.gap(kin) - (z - P["a"] * sp.cos(theta)))
    assert not kin.planar


def test_disk_contact_refuses_bad_input():
    s = rolling_disk.build()
    disk, D = s.bodies["disk"], s.frames["D"]
    a = s.parameters["a"]
    with pytest.raises(rk.ModelError, match="unit vector"):
        s.disk_contact("Q", disk, s.plane(s.origin, s.inertial.z), axis=2 * D.y, radius=a)
    with pytest.raises(rk.ModelError, match="plane"):
        s.disk_contact("Q2", disk, s.sphere(s.origin, 3 * a), axis=D.y, radius=a)
    with pytest.raises(rk.ModelError, match="turns relative"):
        s.disk_contact("Q3", disk, s.plane(s.origin, s.inertial.z), axis=s.inertial.x, radius=a)
    with pytest.raises(rk.ModelError, match="nonzero vector"):
        s.disk_contact("Q4", disk, s.plane(s.origin, s.inertial.z), axis=0, radius=a)


def test_rolling_gives_nonintegrable_rate_relations(coin):
    s, sol = coin
    psi, theta, phi, x, y, z = s.coordinates
    a = s.parameters["a"]
    Y, L = s.frames["Y"], s.frames["L"]
    F = s.inertial
    assert set(sol.dependent) == {x, y, z}
    assert set(sol.relations) == {z}                                   # z = a cos θ only: x, y are not integrable
    assert algebra.is_zero(sol.relations[z] - a * sp.cos(theta))
    w = psi.diff(t) * F.z + theta.diff(t) * Y.x + phi.diff(t) * L.y
    vC = w.cross(a * L.z)                                               # v_C = ω × (C − P), the contact at rest
    for q, e in ((x, F.x), (y, F.y)):
        assert algebra.is_zero(sol.rate_relations[q.diff(t)] - vC.dot(e))
    # not integrable: the Frobenius test fails (d/dψ of the φ̇-coefficient of ẋ ≠ d/dφ of its ψ̇-coefficient = 0)
    cx = sp.Poly(sol.rate_relations[x.diff(t)], phi.diff(t)).coeffs()[0]
    assert not algebra.is_zero(sp.diff(cx, psi))


@pytest.mark.parametrize("shape", [pytest.param("disk", marks=pytest.mark.slow), "ring"])
def test_upright_rolling_stability_threshold(shape, coin):
    s, sol = coin if shape == "disk" else (lambda s: (s, s.solve()))(rolling_disk.build("ring"))
    psi, theta, phi = sol.coordinates
    P = s.parameters
    m, a, g = P["m"], P["a"], P["g"]
    I3 = m * a**2 / 2 if shape == "disk" else m * a**2
    I1 = m * a**2 / 4 if shape == "disk" else m * a**2 / 2
    sm = linearise(sol, {theta: 0, theta.diff(t): 0, psi.diff(t): 0, phi.diff(t): Om})
    assert set(sm.ignorable) == {psi, phi}
    lam2 = -(I3 * (I3 + m * a**2) * Om**2 - m * g * a * I1) / (I1 * (I1 + m * a**2))
    poly = sm.characteristic_polynomial(lam)
    assert algebra.is_zero(sp.cancel(poly - lam**2 * (lam**2 - lam2)))
    crit2 = m * g * a * I1 / (I3 * (I3 + m * a**2))
    assert sp.simplify(crit2 - (g / (3 * a) if shape == "disk" else g / (4 * a))) == 0
    vals = s.parameter_values()
    c = float(sp.sqrt(crit2).xreplace(vals))
    assert sm.eigenvalues({**vals, Om: 1.02 * c}).real.max() < 1e-8
    assert sm.eigenvalues({**vals, Om: 0.98 * c}).real.max() > 1e-3
    # the normal force carries the weight, the no-slip forces vanish, in steady upright rolling
    at = {theta: 0, theta.diff(t): 0, psi.diff(t): 0, phi.diff(t): Om, psi: 0.7, phi: 0.1}
    assert all(algebra.is_zero(v) for v in residual(sol, at).values())
    R = {k: algebra.readable(sp.sympify(v).xreplace({q.diff(t): at[q.diff(t)] for q in sol.coordinates})
                             .xreplace({q: at[q] for q in sol.coordinates}))
         for k, v in sol.reactions.items()}
    assert algebra.is_zero(R["N"] - m * g)
    assert algebra.is_zero(R["F1"]) and algebra.is_zero(R["F2"])


def test_coin_rolls_upright_above_the_threshold_and_falls_below(coin):
    from rigidkin.numeric.simulate import simulate

    s, _ = coin
    vals = s.parameter_values()
    P = s.parameters
    c = float(sp.sqrt(P["g"] / (3 * P["a"])).xreplace(vals))
    fast = simulate(s, 1.0, {"theta": 0.02, "dot(phi)": 2 * c})
    assert fast.status == "completed"
    assert fast.energy_drift < 1e-9                       # rolling without slip does no work
    assert fast.max_residual < 1e-9
    assert np.abs(fast.q["theta"]).max() < 0.1           # the lean stays small
    slow = simulate(s, 1.0, {"theta": 0.02, "dot(phi)": 0.5 * c})
    assert np.abs(slow.q["theta"]).max() > 0.3           # it falls over


def test_euler_about_the_contact_point_agrees(coin):
    """Euler's 2nd law about the material contact point P of the coin (a moving point: the law's
    inertial-moment term does not vanish) gives the motion found about the mass centre."""
    s, sol = coin
    other = s.solve(method="about-point:P")
    assert any("about P" in e.label for e in other.equations)
    for q in sol.coordinates:
        assert algebra.is_zero(other.accelerations[q] - sol.accelerations[q]), q
