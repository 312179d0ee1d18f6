"""Linearisation checks its operating point; dependent coordinates are eliminated; steady motions.

Independent references: the pendulum's ω² = g/l and a cart-pendulum's A and B derived by hand;
sympy.physics.mechanics' KanesMethod linearisation of the non-minimal pendulum (x, y with the length
as a configuration constraint) and of the rolling disc (its test_linearize case); the rolling coin's
critical spin Ω² = g/(3a) (Greenwood §8.5); back-substitution of each answer into its equations.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.physics.vector import dynamicsymbols

import rigidkin as rk
from rigidkin.analysis import steady
from rigidkin.analysis.equilibrium import equilibria, linearise
from rigidkin.base import algebra
from rigidkin.examples import rolling_disk

t = dynamicsymbols._t


def _pendulum(driven=False):
    s = rk.System("pendulum")
    m, l, g = s.parameter("m", "kg", value=1), s.parameter("l", "m", value=2), s.parameter("g", "m/s^2", value=9.81)
    q = s.coordinate("q", "angle from the downward vertical")
    R = s.frame("R", angle=q)
    P = s.point("P", s.origin, -l * R.y)
    b = s.body("bob", rk.shapes.PointMass(m), frame=R, at=P)
    s.pin("O", s.origin, b)
    if driven:
        T0, w = s.parameter("T0", "N*m", value=0.5), s.parameter("w", "rad/s", value=3)
        s.torque("drive", b, T0 * sp.cos(w * t) * s.inertial.z)        # a torque given as a law in t
    s.gravity(g)
    return s, q, (m, l, g)


def _xy_pendulum():
    s = rk.System("xy pendulum")
    m, l, g = s.parameter("m", "kg", value=1), s.parameter("l", "m", value=2), s.parameter("g", "m/s^2", value=9.81)
    x = s.coordinate("x", "bob along Ex", kind="length", initial=0.3)
    y = s.coordinate("y", "bob along Ey", kind="length", initial=-1.9)
    P = s.point("P", s.origin, x * s.inertial.x + y * s.inertial.y)
    b = s.body("bob", rk.shapes.PointMass(m), frame=s.inertial, at=P)
    s.contact("rod", b, s.circle(s.origin, l, inside=True), centre=P, unilateral=False)
    s.gravity(g)
    return s, (x, y), (m, l, g)


def test_a_state_that_is_not_an_equilibrium_is_refused_with_its_residual():
    s, q, (m, l, g) = _pendulum()
    sol = s.solve()
    with pytest.raises(rk.RigidkinError, match=r"back-substitution.*q''") as exc:
        linearise(sol, {q: 0.7})
    assert "≈ -3.1598" in str(exc.value)            # q̈ = −g sin(0.7)/l with g = 9.81, l = 2
    with pytest.raises(rk.RigidkinError, match="back-substitution"):
        steady.linearise(sol, {q: 0.7, q.diff(t): 0})
    with pytest.raises(rk.InputError, match="rates are given"):
        linearise(sol, {q: 0, q.diff(t): 1})
    low = linearise(sol, {q: 0})
    assert algebra.is_zero(low.natural_frequencies[0] ** 2 - g / l)       # ω² = g/l by hand
    assert linearise(sol, {q: sp.pi}).stability == "unstable"


def test_equations_that_depend_on_time_have_no_equilibrium():
    s, q, _ = _pendulum(driven=True)
    sol = s.solve()
    with pytest.raises(rk.RigidkinError, match="depend on t explicitly"):
        equilibria(sol)
    with pytest.raises(rk.RigidkinError, match="t explicitly"):
        linearise(sol, {q: 0})


def test_non_minimal_pendulum_equilibria_eliminate_the_dependent_coordinate():
    s, (x, y), (m, l, g) = _xy_pendulum()
    sol = s.solve()
    assert sol.coordinates == (x,) and sol.dependent == (y,)
    eqs = equilibria(sol)
    by_y = {e.configuration[y]: e for e in eqs}
    assert set(by_y) == {-l, l}
    assert all(e.configuration[x] == 0 for e in eqs)
    assert algebra.is_zero(by_y[-l].natural_frequencies[0] ** 2 - g / l)
    assert by_y[-l].stability.startswith("stable") and by_y[l].stability == "unstable"
    # the dependent coordinate left open: both branches are named; a wrong one is refused
    with pytest.raises(rk.InputError, match="several configurations"):
        linearise(sol, {x: 0})
    with pytest.raises(rk.RigidkinError, match="position constraints"):
        linearise(sol, {x: 0, y: 1})
    # the question answers too (it crashed with "Cannot convert expression to float")
    from rigidkin.analysis.answers import answer
    from rigidkin.analysis.questions import Question
    text = answer(s, Question("equilibrium", "eq")).text
    assert "y = -l" in text and "stable" in text


def test_non_minimal_pendulum_against_sympy_kane_linearizer():
    """sympy's test_linearize_pendulum_kane_nonminimal: q1, q2 the bob's coordinates, gravity along N.x,
    the length a configuration constraint, linearised hanging: A = [[0, 1], [−g/L, 0]]."""
    from sympy.physics.mechanics import KanesMethod, Particle, Point, ReferenceFrame

    q1, q2 = dynamicsymbols("q1:3")
    u1, u2 = dynamicsymbols("u1:3")
    L, mm, gg = sp.symbols("L m g", positive=True)
    N = ReferenceFrame("N")
    pN = Point("N*")
    pN.set_vel(N, 0)
    A = N.orientnew("A", "axis", [sp.atan(q2 / q1), N.z])
    P = pN.locatenew("P1", q1 * N.x + q2 * N.y)
    kde = sp.Matrix([q1.diff(t) - u1, q2.diff(t) - u2])
    P.set_vel(N, P.pos_from(pN).dt(N).subs(sp.solve(kde, [q1.diff(t), q2.diff(t)])))
    f_c = sp.Matrix([P.pos_from(pN).magnitude() - L])
    f_v = sp.Matrix([P.vel(N).express(A).dot(A.x)]).applyfunc(sp.simplify)
    KM = KanesMethod(N, q_ind=[q2], u_ind=[u2], q_dependent=[q1], u_dependent=[u1], configuration_constraints=f_c,
                     velocity_constraints=f_v, acceleration_constraints=f_v.diff(t), kd_eqs=kde)
    KM.kanes_equations([Particle("pP", P, mm)], [(P, mm * gg * N.x)])
    A_ref, _, _ = KM.linearize(op_point=[{q1: L, q2: 0}, {u1: 0, u2: 0}, {u1.diff(t): 0, u2.diff(t): 0}],
                               A_and_B=True, simplify=True)
    s, (x, y), (m, l, g) = _xy_pendulum()
    mine = steady.linearise(s.solve(), {x: 0, y: -l, x.diff(t): 0})
    assert mine.states == (x, x.diff(t)) and mine.dependent == (y,)
    ref = A_ref.xreplace({L: l, gg: g, mm: m})
    assert all(algebra.is_zero(e) for e in (mine.A - ref))


def test_cart_pendulum_A_and_B_by_hand():
    """A force P on a cart (mass M) carrying a pendulum (point mass m, length l), as an input: about the
    hanging state ẍ = (P + m g θ)/M, θ̈ = −(P + (M + m) g θ)/(M l) (Newton's laws by hand)."""
    s = rk.System("cart-pendulum")
    M, m, l, g = (s.parameter(n, u, value=v) for n, u, v in (("M", "kg", 2), ("m", "kg", 1), ("l", "m", 1),
                                                              ("g", "m/s^2", 9.81)))
    P = s.parameter("P", "N", "push on the cart (the input)", value=0, positive=False)
    x = s.coordinate("x", "cart along Ex", kind="length")
    th = s.coordinate("theta", "pendulum from the downward vertical")
    F = s.inertial
    C = s.point("C", s.origin, x * F.x)
    cart = s.body("cart", rk.shapes.PointMass(M), frame=F, at=C)
    s.collar("rail", cart, along=F.x)
    R = s.frame("R", angle=th)
    B = s.point("B", C, -l * R.y)
    bob = s.body("bob", rk.shapes.PointMass(m), frame=R, at=B)
    s.pin("hinge", C, bob, cart)
    s.force("push", C, P * F.x, body=cart)
    s.gravity(g)
    sol = s.solve()
    lin = steady.linearise(sol, {x: 0, th: 0, x.diff(t): 0, th.diff(t): 0, P: 0}, inputs=[P])
    assert lin.ignorable == (x,) and lin.states == (th, x.diff(t), th.diff(t))
    A_hand = sp.Matrix([[0, 0, 1], [m * g / M, 0, 0], [-(M + m) * g / (M * l), 0, 0]])
    B_hand = sp.Matrix([0, 1 / M, -1 / (M * l)])
    assert all(algebra.is_zero(e) for e in (lin.A - A_hand))
    assert all(algebra.is_zero(e) for e in (lin.B - B_hand))


def _sympy_rolling_disc_A():
    """sympy's test_linearize_rolling_disc_kane, linearised at upright rolling with spin rate q3d."""
    import inspect

    from sympy.physics.mechanics.tests import test_linearize as T

    body = inspect.getsource(T.test_linearize_rolling_disc_kane)
    body = body[body.index("def "):body.index("    upright_nominal")] + "    return A, q1, q2, q1d, q3d, m, r, g\n"
    body = body.replace("simplify=True", "simplify=False")
    ns = dict(vars(T))
    exec(compile(body, T.__file__, "exec"), ns)     # sympy's own test source, unchanged but for the return
    return ns["test_linearize_rolling_disc_kane"]()


def test_rolling_disk_eigenvalues_against_sympy_and_the_critical_spin():
    A_ref, q1, q2, q1d, q3d, mm, r, gg = _sympy_rolling_disc_A()
    s = rolling_disk.build()
    sol = s.solve()
    psi, theta, phi = sol.coordinates
    Om = sp.Symbol("Omega", positive=True)
    sm = steady.linearise(sol, {theta: 0, theta.diff(t): 0, psi.diff(t): 0, phi.diff(t): Om})
    P = s.parameters
    unit = {P["m"]: 1, P["a"]: 1, P["g"]: 1}
    for spin in (0.3, 0.9, 2.5):
        ref = A_ref.subs({q1d: 0, q2: 0, q1: 0.4, mm: 1, r: 1, gg: 1, q3d: spin})
        ref = np.array(ref.xreplace({f: 0.7 for f in ref.atoms(AppliedUndef)}).evalf(), dtype=float)  # spin angle
        ev_ref = sorted(np.linalg.eigvals(ref), key=lambda z: (round(z.real, 9), round(z.imag, 9)))
        ev = sorted(sm.eigenvalues({**unit, Om: spin}), key=lambda z: (round(z.real, 9), round(z.imag, 9)))
        big_ref = [z for z in ev_ref if abs(z) > 1e-6]     # a defective zero eigenvalue: ±1e-8 in floats
        big = [z for z in ev if abs(z) > 1e-6]
        assert len(big) == len(big_ref) == 2
        assert np.allclose(big, big_ref, atol=1e-10)
    # the critical spin in closed form: Ω² = g/(3a); sympy's A has all eigenvalues zero there
    (crit,) = sm.critical_values(Om)
    assert algebra.is_zero(crit**2 - P["g"] / (3 * P["a"]))
    ref_crit = A_ref.subs({q1d: 0, q2: 0, q1: 0, mm: 1, r: 1, gg: 1, q3d: 1 / sp.sqrt(3)})
    ref_crit = ref_crit.xreplace({f: 0 for f in ref_crit.atoms(AppliedUndef)})
    assert set(sp.Matrix(ref_crit).applyfunc(sp.nsimplify).eigenvals()) == {0}
    # a leaning state with these rates is not a steady motion: refused with its residual
    with pytest.raises(rk.RigidkinError, match="back-substitution"):
        steady.linearise(sol, {theta: sp.Rational(1, 3), theta.diff(t): 0, psi.diff(t): 0, phi.diff(t): Om})


@pytest.mark.slow
def test_four_bar_check_compares_on_the_constraint_manifold():
    """check on a four-bar: every law agrees (work–energy included) at admissible states; off the
    manifold the power balance would not vanish, and on it a wrong residual is still caught."""
    from test_core_more import _four_bar

    from rigidkin.derive.laws.compare import compare
    from rigidkin.derive.laws.manifold import manifold_of

    s = _four_bar()
    sol = s.solve()
    report = sol.check(laws=["work-energy", "lagrange"])
    assert report.ok, str(report)
    assert any(v.law == "work-energy" and v.status == "agrees" for v in report.verdicts)
    assert not sol.warnings
    th1, th2, th3 = s.coordinates
    L1, L2, L3, d = (s.parameters[k] for k in ("L1", "L2", "L3", "d"))
    closure = L1 * sp.sin(th1) + L2 * sp.sin(th2) - L3 * sp.sin(th3)       # zero on the manifold only
    mf = manifold_of(sol)
    assert compare(closure, 0, mf)[0]
    assert not compare(closure, 0)[0]
    assert not compare(closure + sp.Rational(1, 10**6) * L1, 0, mf)[0]


def test_event_back_substitution_refuses_a_state_that_misses_the_condition():
    from rigidkin.analysis.events import Event, _verified

    s, q, (m, l, g) = _pendulum()
    sol = s.solve()
    good = Event("e", q - 1, True, q, sp.Integer(1), sp.Integer(0), {q: 1}, state={q: 1, q.diff(t): 0})
    assert _verified(sol, good) is good
    bad = Event("e", q - 1, True, q, sp.Integer(1), sp.Integer(0), {q: 1}, state={q: sp.Rational(9, 10),
                                                                                   q.diff(t): 0})
    with pytest.raises(rk.RigidkinError, match="back-substitution"):
        _verified(sol, bad)


def test_relative_equilibrium_of_a_collar_on_a_spinning_rod():
    """A collar on a smooth rod turned at the constant rate Ω (its frame's angle Ω t): x = 0 is a relative
    equilibrium, ẍ = Ω² x by hand, so the linearisation has λ = ±Ω (unstable); x = 1 is not one."""
    s = rk.System("spinning rod")
    m, Om = s.parameter("m", "kg", value=1), s.parameter("Omega", "rad/s", value=2)
    x = s.coordinate("x", "distance of the collar from the axis, along the rod", kind="length")
    R = s.frame("R", angle=Om * t)
    C = s.point("C", offset=x * R.x)
    b = s.body("collar", rk.shapes.PointMass(m), frame=s.inertial, at=C)
    s.contact("rod", b, s.line(s.origin, R.y, name="rod"), centre=C, unilateral=False, normal_name="N")
    sol = s.solve()
    lin = steady.linearise(sol, {x: 0, x.diff(t): 0})
    assert all(algebra.is_zero(e) for e in (lin.A - sp.Matrix([[0, 1], [Om**2, 0]])))
    assert lin.stability() == "unstable"
    with pytest.raises(rk.RigidkinError, match=r"back-substitution.*x''"):
        steady.linearise(sol, {x: 1, x.diff(t): 0})


def test_phases_refuse_a_driven_phase_with_the_reason():
    from rigidkin.analysis.phases import Phase, run_phases

    s, q, _ = _pendulum(driven=True)
    with pytest.raises(rk.RigidkinError, match="t explicitly"):
        run_phases(s, [Phase("swing", until=sp.Eq(q, 1))], {q: 0})


def test_non_minimal_pendulum_integral_and_event_in_closed_form():
    """The x–y pendulum released at rest from x = 1/2 (below the pivot): energy by hand,
    ½ m ẋ² l²/(l² − x²) = m g (sqrt(l² − x²) − sqrt(l² − 1/4)); at x = 0, ẋ² = g (2 l − sqrt(4 l² − 1));
    it turns back at x = −1/2."""
    from rigidkin.analysis.events import event, extreme
    from rigidkin.analysis.integrals import energy_integral

    s, (x, y), (m, l, g) = _xy_pendulum()
    sol = s.solve()
    start = {x: sp.Rational(1, 2), y: -sp.sqrt(15) / 2, x.diff(t): 0}
    integral = energy_integral(sol, start)
    by_hand = 2 * g * (l**2 - x**2) / l**2 * (sp.sqrt(l**2 - x**2) - sp.sqrt(l**2 - sp.Rational(1, 4)))
    assert algebra.is_zero(integral.rate_squared - by_hand)
    assert algebra.is_zero(integral.branch[y] + sp.sqrt(l**2 - x**2))           # the branch below the pivot
    ev = event(sol, sp.Eq(x, 0), start)
    assert ev.happens and ev.exact and algebra.is_zero(ev.configuration[y] + l)
    assert algebra.is_zero(ev.rate**2 - g * (2 * l - sp.sqrt(4 * l**2 - 1)))
    assert algebra.is_zero(extreme(sol, x, start).value + sp.Rational(1, 2))
    # the rod's pull along the motion: T = m g (3 cos θ − 2 cos θ0), cos θ = sqrt(l² − x²)/l (by hand)
    from rigidkin.analysis.answers import answer
    from rigidkin.analysis.questions import Question

    N = answer(s, Question("reaction", "N", {"reaction": "N_rod", "start": start})).value
    cos = sp.sqrt(l**2 - x**2) / l
    assert algebra.is_zero(N - m * g * (3 * cos - 2 * cos.xreplace({x: sp.Rational(1, 2)})))


def test_critical_spin_found_numerically_when_sympy_has_no_closed_form(monkeypatch):
    """The numeric route (sign changes of the lowest coefficient of det(λI − A), refined by bisection)
    finds the same critical spin as the closed form Ω² = g/(3a)."""
    from rigidkin.analysis import linear

    sol = rolling_disk.build().solve()
    psi, theta, phi = sol.coordinates
    Om = sp.Symbol("Omega", positive=True)
    sm = steady.linearise(sol, {theta: 0, theta.diff(t): 0, psi.diff(t): 0, phi.diff(t): Om})

    def no_closed_form(*args, **kwargs):
        raise NotImplementedError

    monkeypatch.setattr(linear.sp, "solve", no_closed_form)
    (crit,) = sm.critical_values(Om)
    vals = sol.system.parameter_values()
    P = sol.system.parameters
    assert abs(float(crit) - float(sp.sqrt(P["g"] / (3 * P["a"])).xreplace(vals))) < 1e-9
