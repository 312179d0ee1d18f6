"""Rotational springs and dampers between two bodies (and a body and the ground).

Reference by hand: two disks on one fixed axle (each pinned at its centre O), disk 2's frame turned from
disk 1's by φ.  A spring k (natural angle φ0) and a damper c between them, a spring K and damper C from
disk 1 to the ground:  I₁ θ̈ = k(φ − φ0) + c φ̇ − K θ − C θ̇,  I₂ (θ̈ + φ̈) = −k(φ − φ0) − c φ̇.
"""

import numpy as np
import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.base.errors import ModelError
from rigidkin.numeric import simulate


def two_disks():
    s = rk.System("two disks")
    m1, m2, r = s.parameter("m1", "kg", value=1.0), s.parameter("m2", "kg", value=2.0), s.parameter("r", "m", value=0.2)
    k, c = s.parameter("k", "N*m/rad", value=3.0), s.parameter("c", "N*m*s/rad", value=0.4)
    K, C = s.parameter("K", "N*m/rad", value=5.0), s.parameter("C", "N*m*s/rad", value=0.1)
    phi0 = s.parameter("phi0", "rad", value=0.3)
    th = s.coordinate("theta", "of disk 1 from Ex, counter-clockwise")
    ph = s.coordinate("phi", "of disk 2 from disk 1, counter-clockwise")
    A = s.frame("A", angle=th)
    B = s.frame("B", parent=A, angle=ph)
    d1 = s.body("d1", rk.shapes.Disk(m1, r), frame=A, at=s.origin)
    P = s.point("P")
    d2 = s.body("d2", rk.shapes.Disk(m2, r), frame=B, at=P)
    s.pin("O1", s.origin, d1)
    s.pin("O2", P, d2)
    s.rotational_spring("between", d2, k, body_b=d1, natural_angle=phi0)
    s.rotational_damper("between_c", d2, c, body_b=d1)
    s.rotational_spring("to_ground", d1, K)
    s.rotational_damper("to_ground_c", d1, C)
    return s, (m1, m2, r, k, c, K, C, phi0), (th, ph)


def test_equations_match_the_hand_derivation():
    s, (m1, m2, r, k, c, K, C, phi0), (th, ph) = two_disks()
    assert s.loads["between"].angle == ph
    t = rk.t
    sol = s.solve()
    assert sol.setup.kin.planar                      # torques about Ez keep the problem planar
    acc = sol.accelerations
    I1, I2 = m1 * r**2 / 2, m2 * r**2 / 2
    a1 = (k * (ph - phi0) + c * ph.diff(t) - K * th - C * th.diff(t)) / I1
    a2 = (-k * (ph - phi0) - c * ph.diff(t)) / I2 - a1
    assert sp.simplify(acc[th] - a1) == 0
    assert sp.simplify(acc[ph] - a2) == 0


def test_energy_balance_in_simulation():
    s, *_ = two_disks()
    res = simulate(s, 2.0, {"theta": 0.5, "phi": -0.2})
    assert res.reached_end and res.energy_drift < 1e-8
    assert abs(res["dot(theta)"][-1]) < 1.0                  # damped


def test_refusals():
    s, params, _ = two_disks()
    with pytest.raises(ModelError, match="two different bodies"):
        s.rotational_spring("self", "d1", params[3], body_b="d1")
    with pytest.raises(ModelError, match="not a unit vector"):
        s.rotational_damper("bad", "d1", params[4], axis=2 * s.inertial.z)
    # a frame turned about another axis: the angle must be given
    q = s.coordinate("q")
    T = s.frame("T", angle=q, axis="x")
    s.body("tilted", rk.shapes.Disk(params[0], params[2]), frame=T, at=s.point("Q"))
    with pytest.raises(ModelError, match="cannot be read from their frames"):
        s.rotational_spring("tilt", "tilted", params[3])
    sp_ = s.rotational_spring("tilt2", "tilted", params[3], angle=q, axis=T.x)
    assert sp_.angle == q and np.isclose(float(sp_.potential(None).subs({params[3]: 2, q: 1})), 1.0)
