"""The Whipple bicycle against the published benchmark.

Reference: J. P. Meijaard, J. M. Papadopoulos, A. Ruina and A. L. Schwab, "Linearized dynamics
equations for the balance and steer of a bicycle: a benchmark and review", Proc. R. Soc. A 463
(2007) 1955–1982, doi:10.1098/rspa.2007.1857.  The matrices are the paper's eq. (A 1)-(A 24)
results printed in its §5 (also in sympy's ``physics/mechanics/tests/test_kane3.py`` state matrix
and in BicycleParameters' ``benchmark_matrices``); the eigenvalues are the paper's Table 2 (b)-(c)
at v = 0, 1, ..., 10 m/s, as transcribed in D. L. Peterson's Whipple eigenvalue test (14 decimals);
the weave and capsize speeds are Table 2 (a).  Nothing here is computed from these numbers: the
model is built from Table 1's parameters only and linearised by rigidkin.numeric.large.projected.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import rigidkin as rk
from rigidkin.examples import bicycle

pytestmark = pytest.mark.slow

PUBLISHED = {
    "M": [[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]],
    "C1": [[0.0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]],
    "K0": [[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]],
    "K2": [[0.0, 76.59734589573222], [0.0, 2.65431523794604]],
}

#: Table 2: eigenvalues at v = 0 ... 10 m/s (real, castering, and the weave pair re ± im i).
TABLE2 = {
    0: [-5.53094371765393, -3.13164324790656, 3.13164324790656, 5.53094371765393],
    1: [-3.13423125066578, -7.11008014637442, (3.52696170990070, 0.80774027519930)],
    2: [-3.07158645641514, -8.67387984831735, (2.68234517512745, 1.68066296590675)],
    3: [-2.63366137253667, -10.35101467245920, (1.70675605663975, 2.31582447384325)],
    4: [-1.42944427361326, -12.15861426576450, (0.41325331521125, 3.07910818603206)],
    5: [-0.32286642900409, -14.07838969279820, (-0.77534188219585, 4.46486771378823)],
    6: [-0.00406690076970, -16.08537123098030, (-1.52644486584142, 5.87673060598709)],
    7: [0.10268170574766, -18.15788466125262, (-2.13875644258362, 7.19525913329805)],
    8: [0.14327879765713, -20.27940894394569, (-2.69348683581097, 8.46037971396931)],
    9: [0.15790184030917, -22.43788559040858, (-3.21675402252485, 9.69377351531791)],
    10: [0.16105338653172, -24.62459635017404, (-3.72016840437287, 10.90681139476287)],
}
WEAVE_SPEED, CAPSIZE_SPEED = 4.29238253634111, 6.02426201538837


def _expected(v):
    out = []
    for e in TABLE2[v]:
        if isinstance(e, tuple):
            out += [complex(e[0], e[1]), complex(e[0], -e[1])]
        else:
            out.append(complex(e))
    return np.array(sorted(out, key=lambda z: (round(z.real, 8), z.imag)))


def _sorted(ev):
    return np.array(sorted(ev, key=lambda z: (round(z.real, 8), z.imag)))


@pytest.fixture(scope="module")
def model():
    return bicycle.projected()


@pytest.fixture(scope="module")
def matrices(model):
    return bicycle.lean_steer_matrices(model)


def test_model_structure(model):
    """Three degrees of freedom; the pitch is fixed by the front contact; the rear contact normal is
    built into the coordinates; roll inertia M_φφ = T_xx, the paper's closed form (eq. A 5)."""
    s = model.system
    phi, delta, thR, x, y, psi, thB, thF = s.coordinates
    assert model.independent == (phi, delta, thR)
    assert set(model.dependent) == {x, y, psi, thB, thF}
    assert [s.coordinates[i] for i in model.holonomic_coordinates()] == [thB]
    assert len(model.rows) == 5            # front normal, two no-slip rows at each wheel
    p = bicycle.BENCHMARK
    Txx = (p["IRxx"] + p["mR"] * p["rR"] ** 2 + p["IBxx"] + p["mB"] * p["zB"] ** 2 + p["IHxx"]
           + p["mH"] * p["zH"] ** 2 + p["IFxx"] + p["mF"] * p["rF"] ** 2)
    M = model.mass_matrix(bicycle.upright(model), [0.0, 0.0, 0.0])
    assert M[0, 0] == pytest.approx(Txx, rel=1e-14)
    # leaned and steered, the front wheel still touches the ground: the gap closes by Newton
    q = model.configuration([0.2, 0.3, 0, 0, 0, 0, 0, 0])
    assert abs(float(np.ravel(model.gaps(q)[0])[0])) < 1e-13
    assert q[6] != 0.0
    # the closed-form solve would not finish: it says so at once and points to the projected equations
    with pytest.raises(rk.ModelError, match="projected"):
        s.solve()


def test_lean_steer_matrices_equal_the_benchmark(matrices):
    for name, want in PUBLISHED.items():
        np.testing.assert_allclose(matrices[name], np.array(want), rtol=0, atol=1e-10, err_msg=name)


@pytest.mark.parametrize("v", range(11))
def test_eigenvalues_equal_table_2(model, v):
    """The direct linearisation at each speed (not the matrices) gives Table 2's eigenvalues."""
    lin = bicycle.linearise_at(model, float(v))
    ev = _sorted(np.linalg.eigvals(lin.state_matrix()))
    np.testing.assert_allclose(ev, _expected(v), rtol=0, atol=1e-10)


def test_weave_and_capsize_speeds(matrices):
    """Self-stable between the weave speed and the capsize speed (Table 2 (a))."""
    def growth(v):
        return float(np.max(bicycle.eigenvalues(matrices, v).real))

    vw = brentq(growth, 4.0, 5.0, xtol=1e-14)
    vc = brentq(growth, 6.0, 7.0, xtol=1e-14)
    assert vw == pytest.approx(WEAVE_SPEED, abs=1e-10)
    assert vc == pytest.approx(CAPSIZE_SPEED, abs=1e-10)


def test_nonlinear_bicycle_balances_itself_in_the_stable_speed_range(model, matrices):
    """The full nonlinear equations (numpy, double precision): a small roll-rate kick follows the
    linear benchmark response at 5 m/s and dies out; at 3 m/s (below the weave speed) it grows."""
    f = model.rhs()
    rR, g = bicycle.BENCHMARK["rR"], bicycle.BENCHMARK["g"]
    kick = 0.01

    def run(v, t_end):
        y0 = np.concatenate([bicycle.upright(model), [0.0, 0.0, -v / rR]])
        y0[8] = kick                                   # roll rate
        return solve_ivp(f, (0, t_end), y0, rtol=1e-10, atol=1e-12, dense_output=True)

    def linear(v, ts):
        M, C, K = matrices["M"], v * matrices["C1"], g * matrices["K0"] + v**2 * matrices["K2"]
        A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
        lam, V = np.linalg.eig(A)
        c = np.linalg.solve(V, np.array([0, 0, kick, 0]))
        return np.real((V * c) @ np.exp(np.outer(lam, ts)))[0]

    ts = np.linspace(0, 6, 601)
    fast = run(5.0, 6.0)
    assert fast.status == 0
    roll = fast.sol(ts)[0]
    np.testing.assert_allclose(roll, linear(5.0, ts), rtol=0, atol=0.01 * np.abs(roll).max())
    assert np.abs(roll[-100:]).max() < 0.05 * np.abs(roll).max()
    slow = run(3.0, 3.0)
    roll3 = slow.sol(ts[:301])[0]
    assert np.abs(roll3[-50:]).max() > 2 * np.abs(roll3[:100]).max()
