"""Knife edges and general velocity constraints: the Chaplygin sleigh against its closed-form equations.

A sleigh of mass m and central inertia I on a knife edge a distance a behind its mass centre G:
with v the forward speed of G and ω the turning rate, v̇ = aω², (I + ma²)ω̇ = −m a v ω (Neimark and
Fufaev; by hand: the edge forbids sideways motion of P, so G's sideways speed is aω; Euler's laws in
the body axes).  The edge's lateral force N (along the body's y on the sleigh) follows from the moment
about G by hand: I ω̇ = −a N, so N = I m v ω/(I + ma²).
"""

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

import rigidkin as rk
from rigidkin.base.errors import ModelError
from rigidkin.numeric import simulate

M_, I_, A_ = 1.3, 0.45, 0.3


def sleigh(general=False):
    t = rk.t
    s = rk.System("sleigh")
    m = s.parameter("m", "kg", value=M_)
    inertia = s.parameter("I", "kg*m^2", value=I_)
    a = s.parameter("a", "m", value=A_)
    x = s.coordinate("x", "of G along Ex", kind="length")
    y = s.coordinate("y", "of G along Ey", kind="length")
    th = s.coordinate("theta", "of the sleigh's axis B.x from Ex, counter-clockwise")
    B = s.frame("B", angle=th)
    G = s.point("G", offset=x * s.inertial.x + y * s.inertial.y)
    body = s.body("sleigh", rk.shapes.Inertia(mass=m, Izz=inertia), frame=B, at=G)
    P = s.point("P", G, -a * B.x, body=body)
    if general:
        s.velocity_constraint("edge", -sp.sin(th) * x.diff(t) + sp.cos(th) * y.diff(t) - a * th.diff(t))
    else:
        s.knife_edge("edge", body, P, B.y)
    return s, (m, inertia, a), (x, y, th)


@pytest.mark.parametrize("general", [False, True])
def test_sleigh_equations_match_the_closed_form(general):
    s, (m, inertia, a), coords = sleigh(general)
    sol = s.solve()
    t = rk.t
    x, y, th = coords
    v, w, c = sp.symbols("v omega c", real=True)
    # a state of the sleigh: forward speed v, turning rate ω at heading c
    state = {x.diff(t): v * sp.cos(c) - a * w * sp.sin(c), y.diff(t): v * sp.sin(c) + a * w * sp.cos(c),
             th.diff(t): w, th: c}
    acc = dict(sol.accelerations)
    # accelerations of the independent coordinates x, y (θ is dependent: the edge gives θ̇)
    known = {q: acc[q].xreplace(state) for q in acc}
    assert set(known) == {x, y}
    xa, ya = known[x], known[y]
    # v̇ = d/dt(ẋ cos θ + ẏ sin θ) = ẍ cos θ + ÿ sin θ + ω (−ẋ sin θ + ẏ cos θ) = ẍ cos θ + ÿ sin θ + a ω²
    vdot = sp.simplify(xa * sp.cos(c) + ya * sp.sin(c) + w * (a * w))
    # sideways: d/dt(−ẋ sin θ + ẏ cos θ) = a ω̇ = −ẍ sin θ + ÿ cos θ − ω v
    wdot = sp.simplify((-xa * sp.sin(c) + ya * sp.cos(c) - w * v) / a)
    assert sp.simplify(vdot - a * w**2) == 0
    assert sp.simplify(wdot + m * a * v * w / (inertia + m * a**2)) == 0
    name = "lambda_edge" if general else "N_edge"
    N = sp.simplify(dict(sol.reactions)[name].xreplace(state))
    assert sp.simplify(N - inertia * m * v * w / (inertia + m * a**2)) == 0


def test_sleigh_simulation_matches_an_independent_integration():
    s, _, coords = sleigh()
    v0, w0, c0 = 0.8, 1.5, 0.2
    x0 = {"x": 0.1, "y": -0.2, "theta": c0, "dot(x)": v0 * np.cos(c0) - A_ * w0 * np.sin(c0),
          "dot(y)": v0 * np.sin(c0) + A_ * w0 * np.cos(c0)}
    res = simulate(s, 3.0, x0)
    assert res.reached_end
    assert abs(res["dot(theta)"][0] - w0) < 1e-12          # the dependent rate from the constraint

    def closed(_, z):
        v, w, th, x, y = z
        return [A_ * w**2, -M_ * A_ * v * w / (I_ + M_ * A_**2), w,
                v * np.cos(th) - A_ * w * np.sin(th), v * np.sin(th) + A_ * w * np.cos(th)]

    ref = solve_ivp(closed, (0, 3.0), [v0, w0, c0, 0.1, -0.2], rtol=1e-11, atol=1e-13, dense_output=True)
    z = ref.sol(res.t)
    th = res["theta"]
    v = res["dot(x)"] * np.cos(th) + res["dot(y)"] * np.sin(th)
    assert np.max(np.abs(v - z[0])) < 1e-7
    assert np.max(np.abs(res["dot(theta)"] - z[1])) < 1e-7
    assert np.max(np.abs(th - z[2])) < 1e-7
    assert np.max(np.abs(res["x"] - z[3])) < 1e-7 and np.max(np.abs(res["y"] - z[4])) < 1e-7
    # the lateral force by hand, N = I m v ω/(I + m a²), along the history
    assert np.max(np.abs(res["N_edge"] - I_ * M_ * z[0] * z[1] / (I_ + M_ * A_**2))) < 1e-6
    # the sleigh ends up moving straight: ω → 0, and energy is conserved (the edge does no work)
    assert abs(z[1][-1]) < abs(w0)
    assert res.energy_drift < 1e-8


def test_knife_edge_refusals():
    s, _, (x, y, th) = sleigh()
    body = s.bodies["sleigh"]
    B = s.frames["B"]
    with pytest.raises(ModelError, match="not a unit vector"):
        s.knife_edge("e2", body, "P", 2 * B.y)
    with pytest.raises(ModelError, match="turns relative"):
        s.knife_edge("e3", body, "P", s.inertial.y)
    with pytest.raises(ModelError, match="no rate"):
        s.velocity_constraint("c1", x - y)
    with pytest.raises(ModelError, match="not linear"):
        s.velocity_constraint("c2", x.diff(rk.t) * y.diff(rk.t))


def test_state_space_refuses_a_nonholonomic_reduction():
    """The sleigh's equations depend on θ, which the edge gives only through θ̇: no state (q, q̇) of x, y."""
    from rigidkin.analysis.state_space import state_space
    from rigidkin.base.errors import RigidkinError

    s, _, _ = sleigh()
    with pytest.raises(RigidkinError, match="nonholonomic"):
        state_space(s.solve(), {"x": 0, "y": 0})


def test_general_constraint_reaction_is_the_incline_normal_force():
    """A particle held by ẏ = k ẋ (a smooth incline of slope k = tan α through the origin): by hand,
    ẍ = −g sin α cos α, and the reaction λ (−k Ex + Ey) is the normal force, of magnitude m g cos α."""
    t = rk.t
    s = rk.System("incline")
    m, g, k = s.parameter("m", "kg"), s.parameter("g", "m/s^2"), s.parameter("k")
    x = s.coordinate("x", "along Ex", kind="length")
    y = s.coordinate("y", "along Ey", kind="length")
    C = s.point("C", offset=x * s.inertial.x + y * s.inertial.y)
    s.body("bead", rk.shapes.PointMass(m), frame=s.inertial, at=C)
    s.velocity_constraint("incline", y.diff(t) - k * x.diff(t))
    s.gravity(g)
    sol = s.solve()
    alpha = sp.atan(k)
    acc = sol.accelerations[x]
    assert sp.simplify(acc + g * sp.sin(alpha) * sp.cos(alpha)) == 0
    lam = sol.reactions["lambda_incline"]
    assert sp.simplify(lam * sp.sqrt(1 + k**2) - m * g * sp.cos(alpha)) == 0
