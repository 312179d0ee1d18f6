"""Problems beyond the cards, each against an independent derivation written here."""

import pytest
import sympy as sp
from helpers import benchmark_models, solve_accels, values_match
from sympy import cos, pi, sin, sqrt
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

import rigidkin as rk
from rigidkin.analysis.equilibrium import equilibria

t = rk.t


def test_rocking_half_disk_off_centre_rolling():
    """A semicircular disk rocking without slip on a floor: profile centre O is not the mass centre."""
    s = rk.System("rocking half-disk")
    m, r, g = s.parameter("m", "kg", value=1), s.parameter("r", "m", value=0.3), s.parameter("g", "m/s^2", value=9.81)
    th = s.coordinate("theta", "rotation of the disk, counter-clockwise, zero with the flat face up")
    x = s.coordinate("x", "position of the centre O of the flat face along Ex", kind="length")
    F = s.inertial
    B = s.frame("B", angle=th)
    with pytest.raises(rk.ModelError, match="already used by the fixed origin"):
        s.point("O", offset=x * F.x)
    O = s.point("Q", offset=x * F.x + r * F.y)
    disk = s.body("disk", rk.shapes.SemicircularDisk(m, r, axis="z", toward="-y"), frame=B, at=O)
    s.contact("P", disk, s.line(s.origin, F.y), centre=O, radius=r, friction="rolling")
    s.gravity(g)
    sol = s.solve()
    assert sol.coordinates == (th,)
    # rolling: x = −r θ
    assert sp.simplify(sol.relations[x] + r * th) == 0
    (eq,) = [e for e in equilibria(sol) if e.configuration[th] == 0]
    d = 4 * r / (3 * pi)
    # independent: small rocking about the contact point, I_P = I_G + m (r − d)², restoring m g d θ
    IG = m * r**2 / 2 - m * d**2
    wn_expected = sqrt(g * d / ((IG + m * (r - d) ** 2) / m))
    assert sp.simplify(eq.natural_frequencies[0] - wn_expected) == 0
    # the full nonlinear EOM against Lagrange: G at O + d(sin θ, −cos θ), O at (−rθ, r)
    q = dynamicsymbols("q")
    xg, yg = -r * q + d * sin(q), r - d * cos(q)
    L = m * (xg.diff(t) ** 2 + yg.diff(t) ** 2) / 2 + IG * q.diff(t) ** 2 / 2 - m * g * yg
    LM = LagrangesMethod(L, [q])
    LM.form_lagranges_equations()
    acc = LM.rhs()[1].subs({q.diff(t): th.diff(t)}).subs(q, th)
    assert values_match(sol.accelerations[th], acc, [th])


def test_disk_rolling_on_a_cart_pushed_by_a_force():
    """A disk rolls without slip on a cart (a moving surface) that a force P pushes along a smooth floor."""
    s = rk.System("disk on cart")
    m, M, r, P = (s.parameter(n, u) for n, u in (("m", "kg"), ("M", "kg"), ("r", "m"), ("P", "N")))
    g = s.parameter("g", "m/s^2")
    X = s.coordinate("X", "cart position along Ex", kind="length")
    x = s.coordinate("x", "disk centre position along Ex", kind="length")
    phi = s.coordinate("phi", "disk rotation, clockwise")
    F = s.inertial
    Ccart = s.point("K", offset=X * F.x)
    cart = s.body("cart", rk.shapes.PointMass(M), frame=F, at=Ccart)
    s.collar("floor", cart, along=F.x)
    C = s.point("C", offset=x * F.x + r * F.y)
    D = s.frame("D", angle=-phi)
    disk = s.body("disk", rk.shapes.Disk(m, r), frame=D, at=C)
    top = s.line(Ccart, F.y, body=cart, name="cart top")
    s.contact("P", disk, top, radius=r, friction="rolling")
    s.force("push", Ccart, P * F.x)
    s.gravity(g)
    sol = s.solve()
    assert set(sol.coordinates) == {X, x}
    # independent: Lagrange with the rolling relation r φ̇ = ẋ − Ẋ built in
    q1, q2 = dynamicsymbols("q1 q2")
    T = M * q1.diff(t) ** 2 / 2 + m * q2.diff(t) ** 2 / 2 + m * r**2 / 4 * ((q2.diff(t) - q1.diff(t)) / r) ** 2
    from sympy.physics.mechanics import Point, ReferenceFrame
    N = ReferenceFrame("N")
    K = Point("K")
    K.set_vel(N, q1.diff(t) * N.x)
    LM = LagrangesMethod(T, [q1, q2], forcelist=[(K, P * N.x)], frame=N)
    LM.form_lagranges_equations()
    rhs = LM.rhs()
    on = {q1.diff(t): X.diff(t), q2.diff(t): x.diff(t)}
    assert values_match(sol.accelerations[X], rhs[2].subs(on), [X, x])
    assert values_match(sol.accelerations[x], rhs[3].subs(on), [X, x])
    # by hand: the disk's centre accelerates at P/(3M + m), the cart at 3P/(3M + m)
    assert sp.simplify(sol.accelerations[x] - P / (3 * M + m)) == 0


@pytest.mark.parametrize("law, expected_force", [("lin", lambda c, v: -c * v), ("cubic", lambda c, v: -c * v**3)])
def test_block_with_damper_any_force_law(law, expected_force):
    s = rk.System("damped block")
    m, k, c, g, beta = (s.parameter(n) for n in ("m", "k", "c", "g", "beta"))
    x = s.coordinate("x", "down the incline from the spring's natural length", kind="length")
    I = s.frame("I", angle=-beta)
    C = s.point("C", offset=x * I.x)
    block = s.body("block", rk.shapes.PointMass(m), frame=I, at=C)
    s.collar("incline", block, along=I.x)
    s.spring("spring", C, s.origin, k)
    v = rk.v
    s.damper("damper", C, -c * v if law == "lin" else -c * v**3, along=I.x)
    s.gravity(g)
    sol = s.solve()
    card = m * x.diff(t, 2) + k * x - m * g * sin(beta) - expected_force(c, x.diff(t))
    assert values_match(sol.accelerations[x], solve_accels([card], [x])[x], [x])


def test_friction_against_moving_collar_regimes():
    """A collar with Coulomb friction on a track: |N| depends on the sign of N (bilateral) and of the slip."""
    s = rk.System("collar with friction")
    m, mu, g, P = (s.parameter(n) for n in ("m", "mu", "g", "P"))
    x = s.coordinate("x", "along the track", kind="length")
    F = s.inertial
    C = s.point("C", offset=x * F.x)
    b = s.body("collar", rk.shapes.PointMass(m), frame=F, at=C)
    s.collar("track", b, along=F.x, friction=mu)
    s.force("pull", C, P * (F.x + F.y))   # pulls along and upwards
    s.gravity(g)
    sol = s.solve()
    assert len(sol.regimes) == 4
    # moving +x with N = m g − P > 0: m ẍ = P − µ (m g − P)
    reg = sol.regime_at({x.diff(t): 1.0, P: 1.0, m: 1.0, g: 9.81, mu: 0.3})
    a = reg.accelerations[x]
    assert values_match(a, (P - mu * (m * g - P)) / m, [x], ranges={"P": (0.1, 0.5), "g": (5, 10)})


def test_atwood_machine_with_a_cable_over_pulleys():
    """Two masses hang from a rope over two small fixed pulleys: a = (m1 − m2) g/(m1 + m2) downwards for
    m1, T = 2 m1 m2 g/(m1 + m2) (by hand)."""
    s = rk.System("atwood")
    m1, m2, g, H, L, a = (s.parameter(n) for n in ("m1", "m2", "g", "H", "L", "a"))
    y1 = s.coordinate("y1", "height of mass 1", kind="length")
    y2 = s.coordinate("y2", "height of mass 2", kind="length")
    F = s.inertial
    A = s.point("A", offset=-a * F.x + y1 * F.y)
    B = s.point("B", offset=a * F.x + y2 * F.y)
    P1, P2 = s.point("P1", offset=-a * F.x + H * F.y), s.point("P2", offset=a * F.x + H * F.y)
    b1 = s.body("mass1", rk.shapes.PointMass(m1), frame=F, at=A)
    b2 = s.body("mass2", rk.shapes.PointMass(m2), frame=F, at=B)
    s.collar("guide1", b1, along=F.y)
    s.collar("guide2", b2, along=F.y)
    s.cable("rope", [A, P1, P2, B], L, tension_name="T")
    s.gravity(g)
    sol = s.solve()
    assert sol.coordinates == (y1,)
    assert sp.simplify(sol.relations[y2] - (2 * H + 2 * a - L - y1)) == 0
    assert sp.simplify(sol.accelerations[y1] + (m1 - m2) * g / (m1 + m2)) == 0
    assert sp.simplify(sol.reactions["T"] - 2 * m1 * m2 * g / (m1 + m2)) == 0
    assert "taut" in sol.validity[0].label


def test_cable_slack_mode_drops_the_tension():
    s = rk.System("hanging")
    m, g, L = (s.parameter(n) for n in ("m", "g", "L"))
    y = s.coordinate("y", "height of the mass", kind="length")
    F = s.inertial
    A = s.point("A", offset=y * F.y)
    b = s.body("mass", rk.shapes.PointMass(m), frame=F, at=A)
    s.collar("guide", b, along=F.y)
    s.cable("rope", [A, s.origin], L, tension_name="T")
    s.gravity(g)
    taut = s.solve()                    # taut, the rope and the guide fix the mass: at rest, statics
    assert taut.coordinates == ()
    assert sp.simplify(taut.reactions["T"].subs(y, -L) - m * g) == 0     # hanging below O: T = m g
    free = s.solve(mode={"rope": "open"})
    assert sp.simplify(free.accelerations[y] + g) == 0


_four_bar = benchmark_models().four_bar        # the benchmarks' four-bar: one copy of the model


@pytest.mark.slow
def test_four_bar_linkage_closed_loop():
    """A four-bar linkage: the loop closure relates the rates; the accelerations against LagrangesMethod with
    the two closure equations as holonomic constraints; simulated, the loop stays closed and energy constant."""
    from rigidkin.numeric.simulate import simulate

    s = _four_bar()
    th1, th2, th3 = s.coordinates
    sol = s.solve()
    assert sol.coordinates == (th1,) and set(sol.dependent) == {th2, th3}
    m, L1, L2, L3, d, g = (s.parameters[k] for k in ("m", "L1", "L2", "L3", "d", "g"))
    q1, q2, q3 = dynamicsymbols("q1 q2 q3")
    def rod(cx, cy, a, L):
        return m * (cx.diff(t) ** 2 + cy.diff(t) ** 2) / 2 + m * L**2 / 24 * a.diff(t) ** 2 - m * g * cy
    Lag = (rod(L1 / 2 * cos(q1), L1 / 2 * sin(q1), q1, L1)
           + rod(L1 * cos(q1) + L2 / 2 * cos(q2), L1 * sin(q1) + L2 / 2 * sin(q2), q2, L2)
           + rod(d + L3 / 2 * cos(q3), L3 / 2 * sin(q3), q3, L3))
    closure = [L1 * cos(q1) + L2 * cos(q2) - d - L3 * cos(q3), L1 * sin(q1) + L2 * sin(q2) - L3 * sin(q3)]
    LM = LagrangesMethod(Lag, [q1, q2, q3], hol_coneqs=closure)
    LM.form_lagranges_equations()
    rhs = LM.rhs()
    # compare at assembled states reached by the simulation
    res = simulate(s, 1.0)
    assert res.max_residual < 1e-9 and res.energy_drift < 1e-9
    vals = {m: 1, L1: 0.3, L2: 1.0, L3: 0.6, d: 0.8, g: 9.81}
    for t_ in (0.0, 0.4, 0.9):
        st = res.at(t_)
        on = {th1: st["theta1"], th2: st["theta2"], th3: st["theta3"], th1.diff(t): st["dot(theta1)"],
              th2.diff(t): st["dot(theta2)"], th3.diff(t): st["dot(theta3)"]}
        mine = float(sol.accelerations[th1].subs({k: v for k, v in on.items() if isinstance(k, sp.Derivative)})
                     .subs(on).subs(vals))
        ref = rhs[3].subs({q1.diff(t): on[th1.diff(t)], q2.diff(t): on[th2.diff(t)], q3.diff(t): on[th3.diff(t)]})
        ref = float(ref.subs({q1: on[th1], q2: on[th2], q3: on[th3]}).subs(vals))
        assert abs(mine - ref) < 1e-9 * max(1.0, abs(ref))


def test_collar_on_a_rough_rotating_rod():
    """A collar slides out along a rough rod turning at constant Ω in a horizontal plane: the rod's normal force
    is the Coriolis one, N = 2 m Ω ẋ, so m ẍ = m Ω² x − µ N while ẋ > 0 (friction against the rod's own
    motion, not against a fixed line)."""
    s = rk.System("rotating rod")
    m, Om, mu = s.parameter("m", "kg"), s.parameter("Omega", "rad/s"), s.parameter("mu")
    x = s.coordinate("x", "distance of the collar from the axis, along the rod", kind="length")
    R = s.frame("R", angle=Om * t, description="turns with the rod at the constant rate Omega")
    C = s.point("C", offset=x * R.x)
    b = s.body("collar", rk.shapes.PointMass(m), frame=s.inertial, at=C)
    s.contact("rod", b, s.line(s.origin, R.y, name="rod"), centre=C, friction=mu, unilateral=False,
              normal_name="N")
    sol = s.solve()
    reg = sol.regime_at({x.diff(t): 1.0, x: 1.0, m: 1.0, Om: 2.0, mu: 0.3})
    assert sp.simplify(reg.reactions["N"] - 2 * m * Om * x.diff(t)) == 0
    assert sp.simplify(reg.accelerations[x] - (Om**2 * x - 2 * mu * Om * x.diff(t))) == 0
