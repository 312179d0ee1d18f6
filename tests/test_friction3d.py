"""Sliding friction in 3D (issue 18, item 3): a billiard ball struck with spin on a rough table, against the
closed form, and the slip direction in `solve`.

Closed form (sphere of radius r, I = 2/5 m r², on a horizontal plane, Coulomb µ): with v_s the slip velocity of
the contact point, dv̄/dt = −µ g û and dω/dt = (5 µ g / 2r) Ez × û, so dv_s/dt = −(7/2) µ g û: the slip direction
û is constant, |v_s| falls linearly and vanishes at t = 2|v_s0|/(7 µ g); the centre moves on the parabola
r̄ = r̄0 + v̄0 t − µ g û t²/2, and rolls on at v̄0 − (2/7) v_s0.  The spin about the vertical stays constant.
"""

import numpy as np
import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.numeric import simulate
from rigidkin.numeric.state import StateLayout

M, R, G, MU = 0.17, 0.028575, 9.81, 0.2
SPEEDS = ("wx", "wy", "wz")


def billiard() -> rk.System:
    """A billiard ball: orientation by a quaternion, ω by its body components (no singular configuration)."""
    s = rk.System("billiard")
    m = s.parameter("m", "kg", "mass of the ball", value=M)
    r = s.parameter("r", "m", "radius of the ball", value=R)
    g = s.parameter("g", "m/s^2", value=G)
    mu = s.parameter("mu", "1", "coefficient of friction ball-cloth", value=MU)
    F = s.inertial
    x = s.coordinate("x", "centre along Ex", kind="length")
    y = s.coordinate("y", "centre along Ey", kind="length")
    z = s.coordinate("z", "height of the centre", kind="length", initial=R)
    B = s.frame("B", quaternion=True, speeds=SPEEDS, initial=(0.9, 0.1, -0.3, 0.2))
    C = s.point("C", offset=x * F.x + y * F.y + z * F.z)
    ball = s.body("ball", rk.shapes.SolidSphere(m, r), frame=B, at=C)
    s.contact("P", ball, s.plane(s.origin, F.z, name="table"), centre=C, radius=r, friction=mu, normal_name="N")
    s.gravity(g, -F.z)
    return s


def _speed_label(name: str, labels) -> str:
    """The state slot of a body angular speed (named ``w`` or, in older layouts, ``dot(w_int)``)."""
    return name if name in labels else f"dot({name}_int)"


def _omega(st) -> np.ndarray:
    """ω in the ground's basis from the quaternion and the body components, written independently of the library."""
    e = np.array([st[f"B_e{i}"] for i in range(4)])
    e0, e1, e2, e3 = e / np.linalg.norm(e)
    rows = np.array([[e0**2 + e1**2 - e2**2 - e3**2, 2 * (e1 * e2 + e0 * e3), 2 * (e1 * e3 - e0 * e2)],
                     [2 * (e1 * e2 - e0 * e3), e0**2 - e1**2 + e2**2 - e3**2, 2 * (e2 * e3 + e0 * e1)],
                     [2 * (e1 * e3 + e0 * e2), 2 * (e2 * e3 - e0 * e1), e0**2 - e1**2 - e2**2 + e3**2]])
    return rows.T @ np.array([st[_speed_label(w, st)] for w in SPEEDS])


@pytest.fixture(scope="module")
def system():
    return billiard()


# (v̄0, ω0 in the ground's basis): side spin (the slip oblique to the cue: a curved path), top spin, back spin
CASES = {
    "side spin": ((0.3, 1.0), (-10.0, 8.0, 5.0)),
    "top spin": ((0.0, 1.2), (-90.0, 0.0, 0.0)),
    "back spin": ((0.0, 1.2), (70.0, 0.0, 30.0)),
}


@pytest.mark.slow
@pytest.mark.parametrize("case", list(CASES))
def test_billiard_ball_path_until_rolling(system, case):
    (vx, vy), w0 = CASES[case]
    v0, w0 = np.array([vx, vy, 0.0]), np.array(w0)
    vs0 = v0 + np.cross(w0, [0.0, 0.0, -R])
    u = vs0 / np.linalg.norm(vs0)
    t_roll = 2 * np.linalg.norm(vs0) / (7 * MU * G)
    e = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
    quat = {f"B_e{i}": e[i] for i in range(4)}
    labels = StateLayout.of(system).labels
    to_ground = np.array([_omega({**quat, **{_speed_label(w, labels): float(k == j) for j, w in enumerate(SPEEDS)}})
                          for k in range(3)]).T           # body components of ω → ground components
    body = np.linalg.solve(to_ground, w0)
    initial = {"x": 0.0, "y": 0.0, "dot(x)": vx, "dot(y)": vy,
               **{_speed_label(w, labels): c for w, c in zip(SPEEDS, body)}}
    res = simulate(system, 2.5 * t_roll, initial)
    assert res.reached_end
    sticks = [e for e in res.events if e.kind == "sticks"]
    # the motion's events; "reverses": the slip direction written relative to a tangent once |v_s| < 1 mm/s
    assert [e.name for e in res.events if e.kind != "reverses"] == ["contact P sticks (rolling begins)"]
    assert len(res.events) == 2 and "passes 0.001 m/s" in res.events[0].detail
    assert abs(sticks[0].t - t_roll) < 1e-8 * t_roll

    def closed(t):
        tt = min(t, t_roll)
        pos, vel = v0 * tt - MU * G * u * tt**2 / 2, v0 - MU * G * u * tt
        return pos + vel * max(0.0, t - t_roll), vel

    for t in np.linspace(0.0, 2.5 * t_roll, 11):
        st = res.at(t)
        pos, vel = closed(t)
        assert np.allclose([st["x"], st["y"]], pos[:2], rtol=0, atol=1e-8 * np.linalg.norm(v0) * t_roll)
        assert np.allclose([st["dot(x)"], st["dot(y)"]], vel[:2], rtol=0, atol=1e-8 * np.linalg.norm(v0))
        w = _omega(st)
        assert abs(w[2] - w0[2]) < 1e-8 * np.linalg.norm(w0)           # the spin about the vertical stays
        if t == 0.0:
            assert np.allclose(w, w0, atol=1e-12 * np.linalg.norm(w0))
        if t > t_roll:                                                    # rolling: no slip
            assert np.linalg.norm(vel + np.cross(w, [0.0, 0.0, -R])) < 1e-8 * np.linalg.norm(v0)
    final = v0 - 2 / 7 * vs0
    assert np.allclose(res.at(2.5 * t_roll)["dot(x)"], final[0], atol=1e-8)
    assert np.allclose(res.at(2.5 * t_roll)["dot(y)"], final[1], atol=1e-8)
    # energy falls only by the friction work, E − E0 = W
    assert abs(res["E"][-1] - res["E"][0] - res["W"][-1]) < 1e-8 * res["E"][0]
    assert abs(res["W"][-1] + MU * M * G * np.linalg.norm(vs0) * t_roll / 2) < 1e-8 * res["E"][0]


@pytest.mark.slow
def test_billiard_ball_equations_with_the_slip_direction(system):
    """`solve` of the slipping mode: friction −µ N û with û the unit vector of the slip velocity (û_P1, û_P2),
    one regime; N = m g; the trace states v_s and û."""
    sol = system.solve(mode={"P": "slip"}, integrate=False)
    assert len(sol.regimes) == 1
    u1, u2 = sp.symbols("û_P1 û_P2", real=True)
    m, g, mu = (system.parameters[n] for n in ("m", "g", "mu"))
    x, y = (system.coordinate_info[n].symbol for n in ("x", "y"))
    t = rk.t
    assert sp.simplify(sol.accelerations[x] + mu * g * u1) == 0
    assert sp.simplify(sol.accelerations[y] + mu * g * u2) == 0
    assert sp.simplify(sol.reactions["N"] - m * g) == 0
    steps = [st for st in sol.trace.steps if st.title == "Slip velocity and its direction at P"]
    assert len(steps) == 1
    eqs = dict(steps[0].equations)
    s1, s2 = sp.symbols("s_P1 s_P2", real=True)
    assert sp.simplify(eqs[u1] - s1 / sp.sqrt(s1**2 + s2**2)) == 0
    # the slip velocity along t1, t2 (Ex, Ey): ẋ − r ω_y and ẏ + r ω_x
    assert eqs[s1].has(x.diff(t)) and eqs[s2].has(y.diff(t))
    from rigidkin.report.text import solution_text

    shown = solution_text(sol)
    rolling = system.solve(mode={"P": "stick"}, integrate=False)       # rolling: within the friction cone
    cone = [c for c in rolling.regime(0).validity if "within the cone" in c.label]
    # the quaternion ball's rolling regime is given structured (M q̈ = f): its condition is written in the
    # accelerations ẇ, which are zero for the free rolling ball (q̈ = M⁻¹ f)
    acc = {k.diff(t).diff(t): v for k, v in dict(rolling.regime(0).accelerations).items()}
    assert all(sp.simplify(v) == 0 for v in acc.values())
    assert len(cone) == 1
    assert sp.simplify(cone[0].expr.subs({sp.Symbol("N"): m * g}).xreplace(acc) - (mu * m * g) ** 2) == 0
    assert "Slip direction (while the slip speed |v_s| > 0" in shown and "û_P1 = s_P1/" in shown


@pytest.mark.slow
def test_rolling_ball_pulled_starts_to_slip_in_the_pull_direction():
    """A ball at rest pulled at its centre by P = k t p̂ (p̂ oblique in the plane): it rolls with friction 2P/7
    until that reaches µ m g, at t* = 7 µ m g/(2k), then slips along p̂: m dv̄/dt = k t − µ m g."""
    s = billiard()
    k, p_hat = 2.0, np.array([0.6, 0.8, 0.0])
    F = s.inertial
    s.force("pull", "C", k * rk.t * (0.6 * F.x + 0.8 * F.y), body=s.bodies["ball"])
    t_star = 7 * MU * M * G / (2 * k)
    res = simulate(s, 1.5 * t_star, {"x": 0.0, "y": 0.0})
    assert res.reached_end
    assert [e.kind for e in res.events if e.kind != "reverses"] == ["slips"]
    assert abs(res.events[0].t - t_star) < 1e-9
    assert res.segments[0].mode == {"P": "stick"} and res.segments[1].mode == {"P": "slip"}
    for t in (0.5 * t_star, t_star, 1.2 * t_star, 1.5 * t_star):
        speed = 5 * k * min(t, t_star) ** 2 / (14 * M)
        if t > t_star:
            speed += k * (t**2 - t_star**2) / (2 * M) - MU * G * (t - t_star)
        st = res.at(t)
        assert np.allclose([st["dot(x)"], st["dot(y)"]], speed * p_hat[:2], rtol=0, atol=1e-7)


# The tippe top: a sphere (radius R, centre C) whose mass centre G lies a below C on its symmetry axis e3, on a
# rough plane (Coulomb µ), spun fast about the vertical through G with e3 tilted by 0.1 rad.  With
# 1 − a/R < I3/I1 < 1 + a/R it turns over onto its stem: G rises above C.  Energy is lost only by the friction
# work ∫ F·v_s dt = −µ ∫ N |v_s| dt (the normal force does no work: C stays at height R).
TOP = {"m": 0.015, "R": 0.025, "a": 0.3 * 0.025, "I1": 131 / 350 * 0.015 * 0.025**2,
       "I3": 2 / 5 * 0.015 * 0.025**2, "mu": 0.3, "g": 9.81}
TILT, TURN, SPIN = 0.1, 0.7, 155.0
T_TOP = 1.6       # inverted by about 1.3 s; then it rolls on its ball (the slip dies out near 1.35 s)


def _quat_mul(p, q):
    p0, p1, p2, p3 = p
    q0, q1, q2, q3 = q
    return np.array([p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3, p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
                     p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1, p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0])


def _rows(e) -> np.ndarray:
    """Rows: the body axes in the ground's basis, for the quaternion e (normalised here)."""
    e0, e1, e2, e3 = np.asarray(e) / np.linalg.norm(e)
    return np.array([[e0**2 + e1**2 - e2**2 - e3**2, 2 * (e1 * e2 + e0 * e3), 2 * (e1 * e3 - e0 * e2)],
                     [2 * (e1 * e2 - e0 * e3), e0**2 - e1**2 + e2**2 - e3**2, 2 * (e2 * e3 + e0 * e1)],
                     [2 * (e1 * e3 + e0 * e2), 2 * (e2 * e3 - e0 * e1), e0**2 - e1**2 - e2**2 + e3**2]])


# tilted about Ex, turned about the body's own axis (every Euler parameter nonzero)
Q_TOP = _quat_mul([np.cos(TILT / 2), np.sin(TILT / 2), 0, 0], [np.cos(TURN / 2), 0, 0, np.sin(TURN / 2)])


def tippe_top() -> rk.System:
    s = rk.System("tippe-top")
    p = {k: s.parameter(k, u, value=TOP[k]) for k, u in
         (("m", "kg"), ("R", "m"), ("a", "m"), ("I1", "kg*m^2"), ("I3", "kg*m^2"), ("mu", "1"), ("g", "m/s^2"))}
    F = s.inertial
    x = s.coordinate("x", "centre C along Ex", kind="length")
    y = s.coordinate("y", "centre C along Ey", kind="length")
    z = s.coordinate("z", "height of C", kind="length", initial=TOP["R"])
    B = s.frame("B", quaternion=True, speeds=("w1", "w2", "w3"), initial=tuple(Q_TOP),
                rates=tuple(_rows(Q_TOP) @ [0.0, 0.0, SPIN]))
    C = s.point("C", offset=x * F.x + y * F.y + z * F.z)
    G = s.point("G", from_=C, offset=-p["a"] * B.z)
    top = s.body("top", rk.shapes.Inertia(p["m"], p["I1"], p["I1"], p["I3"]), frame=B, at=G)
    s.contact("P", top, s.plane(s.origin, F.z, name="table"), centre=C, radius=p["R"], friction=p["mu"],
              normal_name="N")
    s.gravity(p["g"], -F.z)
    return s


@pytest.mark.slow
def test_tippe_top_inverts_losing_energy_only_by_friction_work():
    s = tippe_top()
    vc = np.cross([0.0, 0.0, SPIN], TOP["a"] * _rows(Q_TOP)[2])    # G at rest: v_C = ω × (C − G)
    res = simulate(s, T_TOP, {"x": 0.0, "y": 0.0, "dot(x)": vc[0], "dot(y)": vc[1]}, n_points=8001)
    assert res.reached_end
    # it slips until it has turned over, then the slip dies out and it rolls on (no slip: no more friction work)
    assert [e.kind for e in res.events if e.kind != "reverses"] == ["sticks"]
    t_roll = next(e.t for e in res.events if e.kind == "sticks")
    assert 1.3 < t_roll < 1.45 and res.reached_end
    rise = []
    speed = []
    for row in res.y:
        st = dict(zip(res.layout.labels, row))
        axes = _rows([st[f"B_e{i}"] for i in range(4)])
        rise.append(-TOP["a"] * axes[2, 2])                           # z_G − z_C = −a e3·Ez
        w = axes.T @ [st[_speed_label(n, st)] for n in ("w1", "w2", "w3")]
        vs = np.array([st["dot(x)"], st["dot(y)"], 0.0]) + np.cross(w, [0.0, 0.0, -TOP["R"]])
        speed.append(np.linalg.norm(vs))
    rise, speed = np.array(rise), np.array(speed)
    assert rise[0] < -0.99 * TOP["a"] and rise[-1] > 0.9 * TOP["a"]     # G below C, then above: inverted
    rolling = res.t > t_roll + 1e-9
    assert np.max(speed[rolling]) < 1e-9 * np.max(speed)                # rolling: the contact point at rest
    assert np.ptp(res["W"][rolling]) < 1e-12 * res["E"][0]              # and friction does no more work
    E, W = res["E"], res["W"]
    assert np.max(np.abs(E - E[0] - W)) < 1e-8 * E[0]                 # E(t) − E(0) = ∫ F·v_s dt
    assert W[-1] < -0.05 * E[0] and np.all(np.diff(W) <= 1e-12 * E[0])
    # the same work from the histories, independently: −µ ∫ N |v_s| dt (Simpson)
    from scipy.integrate import simpson

    work = simpson(-TOP["mu"] * res["N"] * np.array(speed), x=res.t)
    assert abs(work - W[-1]) < 1e-4 * abs(W[-1])


@pytest.mark.slow
def test_rolling_eliminates_the_centres_rates_not_the_body_speeds():
    """Rolling on a ball: the no-slip rows are the identity in the centre's rates at every state, but singular in
    two body angular speeds wherever the third body axis is horizontal (the tippe top stalled there, spinning
    inverted): the translations are the dependent rates."""
    sol = tippe_top().solve(mode={"P": "stick"})
    assert [q.func.__name__ for q in sol.dependent[:3]] == ["x", "y", "z"]
    assert not any(q.func.__name__.endswith("_int") for q in sol.dependent)
