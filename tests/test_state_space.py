"""Inputs and the state-space form: a cart-pendulum pushed by a force input F(t).

Reference: sympy.physics.mechanics — the same cart (a particle M on a rail) and uniform rod (m, l,
hinged at the cart) built with KanesMethod, F a specified dynamicsymbol, and KanesMethod.linearize
(A_and_B=True), as in sympy's own linearisation tests (test_linearize.py) and its cart-pendulum
System example (test_system.py), at the hanging (θ = 0) and upright (θ = π) states.
"""

import numpy as np
import pytest
import sympy as sp
from sympy.physics import mechanics as me

import rigidkin as rk
from rigidkin.analysis.state_space import state_space
from rigidkin.base.errors import RigidkinError


def cart_pendulum(values=False):
    s = rk.System("cart-pendulum")
    v = (lambda x: x) if values else (lambda x: None)
    M = s.parameter("M", "kg", value=v(2.0))
    m = s.parameter("m", "kg", value=v(0.5))
    l = s.parameter("l", "m", value=v(0.8))
    g = s.parameter("g", "m/s^2", value=v(9.81))
    F = s.input("F", "N", "force on the cart, positive along Ex")
    x = s.coordinate("x", "of the cart along Ex", kind="length")
    th = s.coordinate("theta", "of the rod from the downward vertical, counter-clockwise")
    C = s.point("C", offset=x * s.inertial.x)
    cart = s.body("cart", rk.shapes.PointMass(M), frame=s.inertial, at=C)
    R = s.frame("R", angle=th)
    G = s.point("G", C, -l / 2 * R.y)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
    s.collar("rail", cart, s.inertial.x, point=C)
    s.pin("hinge", C, rod, body_b=cart)
    s.gravity(g)
    s.force("push", C, F * s.inertial.x)
    return s


def sympy_reference(theta0):
    """A and B from sympy.physics.mechanics (Kane's method) at θ = theta0, rates and F zero."""
    M, m, l, g = sp.symbols("M m l g", positive=True)
    q1, q2, u1, u2, F = me.dynamicsymbols("q1 q2 u1 u2 F")
    N = me.ReferenceFrame("N")
    A = N.orientnew("A", "Axis", [q2, N.z])
    A.set_ang_vel(N, u2 * N.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    Cp = O.locatenew("C", q1 * N.x)
    Cp.set_vel(N, u1 * N.x)
    Go = Cp.locatenew("G", -l / 2 * A.y)
    Go.v2pt_theory(Cp, N, A)
    cart = me.Particle("cart", Cp, M)
    rod = me.RigidBody("rod", Go, A, m, (me.inertia(A, 0, 0, m * l**2 / 12), Go))
    loads = [(Cp, -M * g * N.y + F * N.x), (Go, -m * g * N.y)]
    km = me.KanesMethod(N, [q1, q2], [u1, u2], kd_eqs=[q1.diff() - u1, q2.diff() - u2])
    km.kanes_equations([cart, rod], loads)
    op = {q1: 0, q2: theta0, u1: 0, u2: 0, F: 0, u1.diff(): 0, u2.diff(): 0}
    A_, B_, r = km.linearize(A_and_B=True, op_point=op, simplify=True)
    assert list(r) == [F]
    return A_, B_, {"M": M, "m": m, "l": l, "g": g}


@pytest.mark.parametrize("theta0", [0, sp.pi])
def test_cart_pendulum_A_and_B_equal_sympy_linearize(theta0):
    ss = state_space(cart_pendulum().solve(), {"x": 0, "theta": theta0})
    A_ref, B_ref, syms = sympy_reference(theta0)
    ours = {p.name: p for p in ss.A.free_symbols | ss.B.free_symbols}
    to_ref = {ours[k]: syms[k] for k in ours}
    assert ss.states == ("x", "theta", "dot(x)", "dot(theta)") and ss.inputs == ("F",)
    assert sp.simplify(ss.A.xreplace(to_ref) - A_ref) == sp.zeros(4, 4)
    assert sp.simplify(ss.B.xreplace(to_ref) - B_ref) == sp.zeros(4, 1)
    # the upright state is unstable (a positive real eigenvalue), the hanging one oscillates
    A_num, *_ = ss.numeric({"M": 2.0, "m": 0.5, "l": 0.8, "g": 9.81})
    re_max = np.linalg.eigvals(A_num).real.max()
    assert (re_max > 1.0) if theta0 == sp.pi else (abs(re_max) < 1e-9)


def test_outputs_C_and_D_with_a_reaction():
    """C and D for θ and the hinge's horizontal force; D by hand: R_x = m ā_Gx = m (ẍ + l θ̈/2) at θ = 0."""
    s = cart_pendulum()
    ss = state_space(s.solve(), {"theta": 0}, outputs=["theta", "dot(x)", "R_hingex"])
    assert ss.C[0, :] == sp.Matrix([[0, 1, 0, 0]]) and ss.C[1, :] == sp.Matrix([[0, 0, 1, 0]])
    assert ss.D[0, 0] == 0 and ss.D[1, 0] == 0
    m, l = s.parameters["m"], s.parameters["l"]
    assert sp.simplify(ss.D[2, 0] - m * (ss.B[2, 0] + l / 2 * ss.B[3, 0])) == 0
    # and its θ-row of C: R_x = m(ẍ + l θ̈/2) with the A rows
    assert sp.simplify(ss.C[2, 1] - m * (ss.A[2, 1] + l / 2 * ss.A[3, 1])) == 0


def test_state_space_refusals():
    s = cart_pendulum(values=True)
    sol = s.solve()
    with pytest.raises(RigidkinError, match="back-substitution"):
        state_space(sol, {"theta": 0.3})
    with pytest.raises(RigidkinError, match="not an input"):
        state_space(sol, {"theta": 0}, inputs={"T": 1})
    with pytest.raises(RigidkinError, match="not an independent coordinate"):
        state_space(sol, {"theta": 0}, outputs=["nope"])
    with pytest.raises(RigidkinError, match="have no value"):
        state_space(cart_pendulum().solve(), {"theta": 0}).numeric({"M": 1})
    # a constant push F* and the cart accelerating is no steady motion either
    with pytest.raises(RigidkinError, match="back-substitution"):
        state_space(sol, {"theta": 0}, inputs={"F": 1.0})


def test_input_prints_as_a_function_of_time():
    s = cart_pendulum()
    eom = str(s.solve().accelerations[s.coordinates[0]])
    assert "F(t)" in eom
    assert s.inputs["F"].unit == "N"


# simulation with inputs ---------------------------------------------------------------------------------
def _reference(force, t_end, y0):
    """The cart-pendulum's equations written by hand (Lagrange, rod of mass m, length l hinged at the cart):
    (M + m) ẍ + (m l/2)(θ̈ cos θ − θ̇² sin θ) = F,  (m l²/3) θ̈ + (m l/2)(ẍ cos θ + g sin θ) = 0;
    integrated with scipy's solve_ivp."""
    from scipy.integrate import solve_ivp

    M, m, l, g = 2.0, 0.5, 0.8, 9.81

    def f(tt, z):
        x, th, xd, thd = z
        F = force(tt, {"x": x, "theta": th, "dot(x)": xd, "dot(theta)": thd})
        Mm = np.array([[M + m, m * l / 2 * np.cos(th)], [m * l / 2 * np.cos(th), m * l**2 / 3]])
        rhs = np.array([F + m * l / 2 * thd**2 * np.sin(th), -m * l / 2 * g * np.sin(th)])
        return [xd, thd, *np.linalg.solve(Mm, rhs)]

    return solve_ivp(f, (0, t_end), y0, rtol=1e-11, atol=1e-13, dense_output=True)


def _compare(res, ref):
    z = ref.sol(res.t)
    for i, name in enumerate(("x", "theta", "dot(x)", "dot(theta)")):
        assert np.max(np.abs(res[name] - z[i])) < 1e-6, name


def test_simulate_with_an_expression_a_table_and_feedback():
    from rigidkin.numeric import simulate

    s = cart_pendulum(values=True)
    y0 = {"x": 0.0, "theta": 0.2, "dot(x)": 0.0, "dot(theta)": 0.0}
    z0 = [0.0, 0.2, 0.0, 0.0]
    t_ = rk.t
    res = simulate(s, 2.0, y0, inputs={"F": 3 * sp.sin(2 * t_)})
    _compare(res, _reference(lambda tt, st: 3 * np.sin(2 * tt), 2.0, z0))
    assert res.energy_drift < 1e-6                 # the input's work is counted in the energy balance
    table = ([0.0, 0.5, 1.0, 2.0], [0.0, 4.0, -2.0, -2.0])
    res = simulate(s, 2.0, y0, inputs={"F": table})
    _compare(res, _reference(lambda tt, st: float(np.interp(tt, *table)), 2.0, z0))
    # feedback: a PD law on the cart's position
    law = lambda tt, st: -5.0 * st["x"] - 2.0 * st["dot(x)"] + 1.0  # noqa: E731
    res = simulate(s, 2.0, y0, inputs={"F": law})
    _compare(res, _reference(law, 2.0, z0))


def test_simulate_refuses_missing_and_unknown_inputs():
    from rigidkin.base.errors import InputError
    from rigidkin.numeric import simulate

    s = cart_pendulum(values=True)
    with pytest.raises(InputError, match="no history"):
        simulate(s, 1.0, {"theta": 0.1})
    with pytest.raises(InputError, match="not an input"):
        simulate(s, 1.0, {"theta": 0.1}, inputs={"F": 0, "G": 1})
    with pytest.raises(InputError, match="increasing"):
        simulate(s, 1.0, {"theta": 0.1}, inputs={"F": ([0, 0], [1, 2])})
    with pytest.raises(InputError, match="as well as on time"):
        simulate(s, 1.0, {"theta": 0.1}, inputs={"F": s.coordinates[0]})


def test_equilibria_hold_the_input_at_zero():
    """The unforced cart-pendulum's equilibria (F* = 0): hanging, with ω² = 6 g (M + m) / (l (4M + m)) by hand
    from (M + m) ẍ + (m l/2) θ̈ = 0 and (m l²/3) θ̈ + (m l/2) ẍ + (m g l/2) θ = 0; upright, unstable."""
    from rigidkin.analysis.equilibrium import equilibria

    s = cart_pendulum(values=True)
    found = {str(e).split(":")[0]: e for e in equilibria(s.solve())}
    assert set(found) == {"equilibrium θ = 0, x = 0", "equilibrium θ = pi, x = 0"}
    M, m, l, g = 2.0, 0.5, 0.8, 9.81
    hanging = found["equilibrium θ = 0, x = 0"]
    assert "stable" in str(hanging) and "unstable" not in str(hanging)
    assert "unstable" in str(found["equilibrium θ = pi, x = 0"])
    w2 = 6 * g * (M + m) / (l * (4 * M + m))
    assert abs(float(sp.sympify(str(hanging).split("ω_n = ")[1].replace("·", "*")).subs(
        {"g": g, "M": M, "m": m, "l": l})) - w2 ** 0.5) < 1e-9
