"""Generalised speeds and quaternion orientation (issue 18, items 1–2): 3D motion with no singular
configuration.

* The kinematic equations ė = ½ Q(e) w are checked against sympy's own quaternion kinematics, and the
  angular speeds of an Euler-angle frame against its angular velocity.
* A sleeping top started exactly upright — nutation zero, where 3-1-3 angles are singular (their mass
  matrix is, checked below) — stays upright above the threshold I3²ω3² > 4 I1 m g l and falls below it
  (Goldstein §5.7; the threshold is computed from the parameters, not written in).
* A tumbling box with three distinct principal moments, for 100 s, passes within 1° of the singular
  configuration of every one of the twelve Euler sequences (a body axis along a space axis), and its
  energy ½ ωᵀĪω, |H̄| and the vector H̄ in space keep their values to 1e-10 — computed here from the
  state by hand, not by the library.
* The Whipple bicycle with the rear frame's angular-velocity components as speeds (in place of the
  yaw, roll and pitch rates) still has the eigenvalues of Meijaard et al. (2007), Table 2, to 1e-10.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp
from sympy.physics.vector import ReferenceFrame, dynamicsymbols

import rigidkin as rk
from rigidkin.model.speeds import quaternion_from_axis_angle, quaternion_matrix, speeds_of
from rigidkin.numeric.large.projected import ProjectedModel

t = dynamicsymbols._t


def dcm(e):
    """Rows: the body axes b1, b2, b3 in the inertial basis, for the rotation by e/|e| (written out here)."""
    e0, e1, e2, e3 = np.asarray(e, dtype=float) / np.linalg.norm(e)
    return np.array([[e0**2 + e1**2 - e2**2 - e3**2, 2 * (e1 * e2 + e0 * e3), 2 * (e1 * e3 - e0 * e2)],
                     [2 * (e1 * e2 - e0 * e3), e0**2 - e1**2 + e2**2 - e3**2, 2 * (e2 * e3 + e0 * e1)],
                     [2 * (e1 * e3 + e0 * e2), 2 * (e2 * e3 - e0 * e1), e0**2 - e1**2 - e2**2 + e3**2]])


# kinematic equations -------------------------------------------------------------------------------
def test_quaternion_rates_give_the_body_angular_velocity():
    """sympy orients a frame by e and finds ω from ė; with ė = ½ Q(e) w that ω is w (|e| = 1), and
    d|e|²/dt = 2 eᵀ ė = eᵀ Q(e) w = 0 for any e."""
    N, B = ReferenceFrame("N"), ReferenceFrame("B")
    e = dynamicsymbols("e0:4")
    w = sp.symbols("w1:4")
    B.orient_quaternion(N, e)
    rates = quaternion_matrix(e) * sp.Matrix(w) / 2
    omega = B.ang_vel_in(N).xreplace({ei.diff(t): r for ei, r in zip(e, rates)})
    unit = {e[0]: sp.sqrt(1 - e[1]**2 - e[2]**2 - e[3]**2)}
    for k, b in enumerate((B.x, B.y, B.z)):
        assert sp.simplify(omega.dot(b).xreplace(unit) - w[k]) == 0
    assert sp.expand(sp.Matrix(e).T * quaternion_matrix(e)) == sp.zeros(1, 3)


def test_frame_by_quaternion_and_its_speeds():
    s = rk.System("body")
    B = s.frame("B", quaternion=("e0", "e1", "e2", "e3"), initial=(2, 0, 0, 2), rates=(0, 0, 1))
    e = s.coordinates[:4]
    info = list(s.coordinate_info.values())
    assert [c.initial for c in info[:4]] == pytest.approx([2**-0.5, 0, 0, 2**-0.5])
    ke = speeds_of(s)
    assert ke.configuration == e and len(ke.speeds) == 3 and not ke.trivial
    # the quasi-coordinates π with π̇ = w: what the symbolic core integrates; they locate nothing
    assert [c.name for c in info[4:]] == ["w_bx_int", "w_by_int", "w_bz_int"]
    assert [c.rate for c in info[4:]] == [0, 0, 1]
    assert [p.diff(t) for p in s.coordinates[4:]] == list(ke.speeds)
    assert B.ref.ang_vel_in(s.inertial.ref) == sum((w * b for w, b in zip(ke.speeds, (B.x, B.y, B.z))),
                                                   sp.S.Zero * B.x)
    assert ke.W().shape == (4, 3)
    # a quarter turn about Ez: b1 = Ey, whatever |e| (the rotation of e/|e|)
    b1 = B.x.express(s.inertial.ref).to_matrix(s.inertial.ref).xreplace(dict(zip(e, (2, 0, 0, 2))))
    assert list(sp.simplify(b1)) == [0, 1, 0]
    with pytest.raises(rk.ModelError, match="zero"):
        s.frame("C", quaternion=True, initial=(0, 0, 0, 0))
    with pytest.raises(rk.ModelError, match="four"):
        s.frame("D", quaternion=("a", "b", "c"))
    with pytest.raises(rk.ModelError, match="not both"):
        s.frame("E", quaternion=True, sequence="313", angles=e[1:])


def test_angular_speeds_of_an_euler_sequence_invert_its_kinematics():
    """Kane's choice on request for 3-1-3 angles: ω·bᵢ with q̇ = W(q) w substituted is wᵢ again, and W
    is singular only at the sequence's own singularity (θ = 0)."""
    s = rk.System("euler")
    q = [s.coordinate(n) for n in ("psi", "theta", "phi")]
    B = s.frame("B", sequence="313", angles=q, speeds=("w1", "w2", "w3"))
    ke = speeds_of(s)
    w = ke.speeds
    omega = ke.substitute(B.ref.ang_vel_in(s.inertial.ref))
    for k, b in enumerate((B.x, B.y, B.z)):
        assert sp.simplify(omega.dot(b) - w[k]) == 0
    assert sp.simplify(ke.W().det() * sp.sin(q[1])) != 0


# the sleeping top ------------------------------------------------------------------------------------
def _top():
    s = rk.System("top")
    m, g = s.parameter("m", "kg", value=0.1), s.parameter("g", "m/s^2", value=9.81)
    l = s.parameter("l", "m", value=0.03)
    I1 = s.parameter("I1", "kg*m^2", "transverse moment about the tip", value=1.2e-4)
    I3 = s.parameter("I3", "kg*m^2", "axial moment", value=4e-5)
    B = s.frame("B", quaternion=("e0", "e1", "e2", "e3"), basis=("b1", "b2", "b3"))
    top = s.body("top", rk.shapes.Inertia(m, I1 - m * l**2, I1 - m * l**2, I3), frame=B,
                 at=s.point("G", offset=l * B.z))
    s.pin("O", s.origin, top)
    s.gravity(g, -s.inertial.z)
    return s


@pytest.fixture(scope="module")
def top():
    return ProjectedModel(_top())


@pytest.mark.parametrize("ratio, sleeps", [pytest.param(1.6, True, marks=pytest.mark.slow), (0.64, False)])
def test_sleeping_top_started_upright(top, ratio, sleeps):
    """Exactly upright (e = 1, nutation zero) with a transverse rate of 1 mrad/s: above the threshold the
    axis stays within 1e-3 rad of the vertical for 2 s; below it the top falls (tilt > 1 rad).  Energy
    and the vertical angular momentum H·Ez (gravity has no moment about Ez) hold to 1e-8."""
    v = {str(k): val for k, val in top.values.items()}
    m, g, l, I1, I3 = (v[k] for k in ("m", "g", "l", "I1", "I3"))
    critical = 2 * np.sqrt(I1 * m * g * l) / I3          # I3² ω3² = 4 I1 m g l
    y0 = np.array([1.0, 0, 0, 0, 1e-3, 0, ratio * critical])
    assert top.independent == tuple(dynamicsymbols("w_b1 w_b2 w_b3", real=True))
    sol = solve_ivp(top.rhs(), (0, 2), y0, method="DOP853", rtol=1e-10, atol=1e-12, dense_output=True)
    assert sol.status == 0
    ys = sol.sol(np.linspace(0, 2, 2001))
    R = [dcm(y[:4]) for y in ys.T]
    tilt = np.array([np.arccos(np.clip(Rk[2, 2], -1, 1)) for Rk in R])
    Io = np.diag([I1, I1, I3])
    energy = [0.5 * y[4:] @ Io @ y[4:] + m * g * l * Rk[2, 2] for y, Rk in zip(ys.T, R)]
    Hz = [(Rk.T @ (Io @ y[4:]))[2] for y, Rk in zip(ys.T, R)]
    assert np.ptp(energy) < 1e-8 * abs(energy[0]) and np.ptp(Hz) < 1e-8 * abs(Hz[0])
    assert np.abs(np.sum(ys[:4] ** 2, axis=0) - 1).max() < 1e-8
    if sleeps:
        assert tilt.max() < 1e-3
    else:
        assert tilt.max() > 1.0


def test_euler_angles_are_singular_where_the_top_sleeps():
    """The same top in 3-1-3 angles: its mass matrix in (ψ̇, θ̇, φ̇) is singular at θ = 0."""
    from rigidkin.examples import heavy_top

    pm = ProjectedModel(heavy_top.build("313"))
    assert abs(np.linalg.det(pm.mass_matrix([0.3, 0.0, 0.2], [1.0, 0.0, 1.0]))) < 1e-25
    assert abs(np.linalg.det(pm.mass_matrix([0.3, 0.5, 0.2], [1.0, 0.0, 1.0]))) > 1e-14


# the tumbling box --------------------------------------------------------------------------------------
A, B_, C = 0.3, 0.2, 0.1


def _box(rates=None):
    s = rk.System("box")
    m = s.parameter("m", "kg", value=1.0)
    a, b, c = (s.parameter(n, "m", value=v) for n, v in (("a", A), ("b", B_), ("c", C)))
    F = s.frame("B", quaternion=("e0", "e1", "e2", "e3"), rates=rates)
    s.body("box", rk.shapes.Box(m, a, b, c), frame=F, at=s.point("G", offset=0))
    return s


def _tumble(t_end):
    """The box spinning at w = (3, 2, 1) rad/s in its own axes, turned so that H̄ points along (1, 1, 1)."""
    pm = ProjectedModel(_box())
    I = np.array([B_**2 + C**2, A**2 + C**2, A**2 + B_**2]) / 12
    w0 = np.array([3.0, 2.0, 1.0])
    h = I * w0 / np.linalg.norm(I * w0)
    n = np.ones(3) / np.sqrt(3)
    e0 = quaternion_from_axis_angle(np.cross(h, n), np.arccos(h @ n))
    y0 = np.concatenate([e0, w0])
    sol = solve_ivp(pm.rhs(), (0, t_end), y0, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    assert sol.status == 0
    ys = sol.sol(np.linspace(0, t_end, int(400 * t_end) + 1))
    R = np.array([dcm(y[:4]) for y in ys.T])
    H = np.array([Rk.T @ (I * y[4:]) for y, Rk in zip(ys.T, R)])
    T = np.array([0.5 * y[4:] @ (I * y[4:]) for y in ys.T])
    return ys, R, H, T


def _conserved(ys, H, T):
    assert np.abs(T - T[0]).max() < 1e-10 * T[0]
    Hn = np.linalg.norm(H, axis=1)
    assert np.abs(Hn - Hn[0]).max() < 1e-10 * Hn[0]
    assert np.abs(H - H[0]).max() < 1e-10 * Hn[0]                    # H̄ fixed in space
    assert np.abs(np.sum(ys[:4] ** 2, axis=0) - 1).max() < 1e-9


def test_tumbling_box_short():
    ys, _, H, T = _tumble(10.0)
    _conserved(ys, H, T)


@pytest.mark.slow
def test_tumbling_box_through_every_euler_singularity():
    """100 s: every body axis bₖ comes within 1° of every space axis Eᵢ (|bₖ·Eᵢ| = 1 is the singular
    configuration of the sequences i-j-k and, for k = i, i-j-i: all twelve), and T, |H̄|, H̄ hold."""
    ys, R, H, T = _tumble(100.0)
    closest = np.degrees(np.arccos(np.clip(np.abs(R).max(axis=0), -1, 1)))
    assert closest.max() < 1.0, closest
    _conserved(ys, H, T)


# closed-form linearisations are written in q̇: refused, not silently wrong, for other speeds ------------
def _euler_top(speeds, sequence="313"):
    s = rk.System("top")
    m, g, l = (s.parameter(n, u, n, value=v) for n, u, v in (("m", "kg", 0.1), ("g", "m/s^2", 9.81),
                                                                ("l", "m", 0.03)))
    I1, I3 = (s.parameter(n, "kg*m^2", n, value=v) for n, v in (("I1", 1.2e-4), ("I3", 4e-5)))
    q = [s.coordinate(n, initial=v) for n, v in (("psi", 0.0), ("theta", 0.5), ("phi", 0.0))]
    B = s.frame("B", sequence=sequence, angles=q, speeds=speeds)
    G = s.point("G", offset=l * B.z)
    top = s.body("top", rk.shapes.Inertia(m, I1 - m * l**2, I1 - m * l**2, I3), frame=B, at=G)
    s.pin("O", s.origin, top)
    s.gravity(g, -s.inertial.z)
    return s, q


@pytest.mark.slow
def test_closed_form_linearisations_refuse_speeds_that_are_not_rates():
    from rigidkin.analysis import equilibrium, steady

    s, (psi, theta, phi) = _euler_top(("w1", "w2", "w3"))
    sol = s.solve()
    for call in (lambda: equilibrium.equilibria(sol), lambda: equilibrium.linearise(sol, {theta: 0}),
                 lambda: steady.linearise(sol, {theta: 0.5}, check=False)):
        with pytest.raises(rk.RigidkinError, match="w1, w2, w3, which are not coordinate rates"):
            call()
    # the same top in q̇ (a 1-2-3 sequence, regular where the axis hangs down: turned by π about Ex)
    # swings about the hanging state with ω² = m g l / I1 in both directions
    s, (a, b, c) = _euler_top(None, "123")
    sol = s.solve()
    hanging = equilibrium.linearise(sol, {a: sp.pi, b: 0, c: 0})
    assert "stable" in hanging.stability
    w2 = sorted(abs(complex(e).imag) ** 2 for e in hanging.eigenvalues if abs(complex(e)) > 1e-9)
    assert w2 and np.isclose(w2[-1], 0.1 * 9.81 * 0.03 / 1.2e-4, rtol=1e-9)


# the bicycle with generalised speeds -------------------------------------------------------------------
@pytest.mark.slow
def test_bicycle_eigenvalues_with_angular_speeds():
    from test_bicycle import TABLE2, _expected, _sorted

    from rigidkin.examples import bicycle

    s = bicycle.build()
    phi, delta, thR, x, y, psi, thB, thF = s.coordinates
    wx, wy, wz = s.angular_speeds("B", ("wx", "wy", "wz"), coordinates=(psi, phi, thB))
    model = ProjectedModel(s, independent=(wx, delta, thR))
    assert model.independent == (wx, delta, thR) and len(model.speeds) == 8
    q = model.configuration([0.0] * 8)
    rR = bicycle.BENCHMARK["rR"]
    for v in TABLE2:
        A_ = model.state_matrix(q, [0.0, 0.0, -v / rR], (phi, delta), (wx, delta))
        np.testing.assert_allclose(_sorted(np.linalg.eigvals(A_)), _expected(v), rtol=0, atol=1e-10)


# the whole chain from a problem file: solve (EOM in ẇ), check, simulate (q, u) -------------------------------
TOP_FILE = """
title = "Sleeping top"
[parameters]
m = { unit = "kg", value = 0.1 }
g = { unit = "m/s^2", value = 9.81 }
l = { unit = "m", value = "3 cm" }
I1 = { unit = "kg*m^2", value = 1.2e-4, description = "transverse moment about the tip" }
I3 = { unit = "kg*m^2", value = 4e-5 }
[frames.B]
quaternion = ["e0", "e1", "e2", "e3"]                 # Euler parameters, scalar first; they start at (1, 0, 0, 0)
speeds = ["w1", "w2", "w3"]                           # angular-velocity components along b1, b2, b3
rates = ["1 mrad/s", 0, 150]                          # their initial values
basis = ["b1", "b2", "b3"]
[points]
G = { offset = "l*b3" }
[bodies]
top = { shape = "inertia", mass = "m", Ixx = "I1 - m*l**2", Iyy = "I1 - m*l**2", Izz = "I3", frame = "B", at = "G" }
[constraints]
O = { type = "pin", point = "O", body_a = "top" }
[loads]
gravity = { type = "gravity", g = "g", direction = "-Ez" }
"""


@pytest.mark.slow
def test_sleeping_top_file_solve_and_simulate(tmp_path):
    """From the file: Euler's equations in ẇ (against the closed form with the gravity moment
    m g l (b2·Ez) about b1, written here), the kinematic equations ė = ½ Q(e) w in the trace, every
    law that applies agreeing, and the simulation in (q, u) from upright: the top sleeps at 150 rad/s."""
    from rigidkin.io.problem import load_problem
    from rigidkin.numeric import simulate

    path = tmp_path / "top.toml"
    path.write_text(TOP_FILE)
    s, _ = load_problem(path)
    sol = s.solve()
    e = s.coordinates[:4]
    w = speeds_of(s).speeds
    from rigidkin.report.text import solution_text

    listed = [line for line in solution_text(sol).splitlines() if "Euler parameter" in line and "(other)" in line]
    assert len(listed) == 4 and all(line.endswith("[its rate from the speeds: q̇ = W(q) u]") for line in listed)
    # the printed equations are Euler's, on |e| = 1 (M and f, which the code evaluates, hold for any e)
    P_ = {str(k): v for k, v in s.parameters.items()}
    m_, g_, l_, I1_, I3_ = (P_[k] for k in ("m", "g", "l", "I1", "I3"))
    e0, e1, e2, e3 = e
    w1, w2, w3 = w
    euler1 = I1_ * w1.diff(t) + (I3_ - I1_) * w2 * w3 - 2 * m_ * g_ * l_ * (e0 * e1 + e2 * e3)
    assert sp.expand(sol.eom[0] - euler1) == 0 or sp.expand(sol.eom[0] + euler1) == 0, sol.eom[0]
    assert "normalised: e₀² + e₁² + e₂² + e₃² = 1" in solution_text(sol)
    P = {str(k): v for k, v in s.parameters.items()}
    rng = np.random.default_rng(3)
    ev = rng.normal(size=4)
    ev /= np.linalg.norm(ev)
    wv = rng.normal(size=3)
    vals = {**dict(zip(e, ev)), **dict(zip(w, wv)), **{P[k]: v for k, v in
                                                      dict(m=0.1, g=9.81, l=0.03, I1=1.2e-4, I3=4e-5).items()}}
    acc = {str(k): float(sp.sympify(v).xreplace(vals)) for k, v in sol.accelerations.items()}
    R = dcm(ev)
    mgl, I1, I3 = 0.1 * 9.81 * 0.03, 1.2e-4, 4e-5
    assert acc["w1_int(t)"] == pytest.approx(((I1 - I3) * wv[1] * wv[2] + mgl * R[1, 2]) / I1, rel=1e-12)
    assert acc["w2_int(t)"] == pytest.approx(((I3 - I1) * wv[0] * wv[2] - mgl * R[0, 2]) / I1, rel=1e-12)
    assert acc["w3_int(t)"] == 0
    steps = [s_ for s_ in sol.trace.steps if "Kinematic differential equations" in s_.title]
    assert steps and "W" in str(steps[0].equations)
    assert all(v.status in ("agrees", "does not apply") for v in sol.check().verdicts)
    res = simulate(s, 1.0, rtol=1e-10, atol=1e-12)
    assert res.reached_end
    ys = np.asarray(res.y).T
    lay = res.layout
    E = ys[[lay.index(n) for n in ("e0", "e1", "e2", "e3")]]
    assert lay.index("w3") == lay.index("dot(w3_int)")
    tilt = np.arccos(np.clip(1 - 2 * (E[1] ** 2 + E[2] ** 2) / np.sum(E**2, axis=0), -1, 1))
    assert tilt.max() < 1e-3
    assert np.abs(np.sum(E**2, axis=0) - 1).max() < 1e-8
    assert abs(res.energy_drift) < 1e-8


@pytest.mark.slow
def test_first_integrals_of_the_free_box():
    """The answers that apply: T, the components of H about O along Ex, Ey, Ez and |H_O|² are first
    integrals of the torque-free box in its speeds, with the values at the start computed by hand."""
    from rigidkin.analysis.integrals import first_integrals

    s = _box(rates=(3.0, 2.0, 1.0))
    found = {fi.name: fi for fi in first_integrals(s.solve())}
    vals = {v: x for v, x in zip(s.parameters.values(), (1.0, A, B_, C))}
    I = np.array([B_**2 + C**2, A**2 + C**2, A**2 + B_**2]) / 12
    w0 = np.array([3.0, 2.0, 1.0])
    assert float(found["energy"].value.xreplace(vals)) == pytest.approx(0.5 * w0 @ (I * w0), rel=1e-14)
    for k, axis in enumerate(("Ex", "Ey", "Ez")):
        assert float(found[f"angular momentum about O along {axis}"].value.xreplace(vals)) == \
            pytest.approx(I[k] * w0[k], rel=1e-14)
    assert float(found["|H_O|²"].value.xreplace(vals)) == pytest.approx(np.sum((I * w0) ** 2), rel=1e-14)


@pytest.mark.parametrize("old, new, field", [
    ('speeds = ["w1", "w2", "w3"]', 'speeds = ["w1", "w2", "g"]', "frames.B.speeds[2]"),
    ('quaternion = ["e0", "e1", "e2", "e3"]', 'quaternion = ["e0", "e1", "e2"]', "frames.B.quaternion"),
    ('rates = ["1 mrad/s", 0, 150]', 'rates = ["1 m", 0, 150]', "frames.B.rates[0]"),
    ('rates = ["1 mrad/s", 0, 150]', 'rates = ["1 mrad/s", 0, 150]\nangle = "0"', "frames.B.angle"),
    ('rates = ["1 mrad/s", 0, 150]', 'initial = [0, 0, 0, 0]', "frames.B"),
])
def test_bad_quaternion_frames_in_files(tmp_path, old, new, field):
    """Each mistake: one paragraph naming the file, the line and the field (validate exits 2)."""
    from rigidkin.cli import main

    assert old in TOP_FILE
    path = tmp_path / "top.toml"
    path.write_text(TOP_FILE.replace(old, new))
    with pytest.raises(rk.RigidkinError) as info:
        from rigidkin.io.problem import load_problem

        load_problem(path)
    msg = str(info.value)
    assert "top.toml, line" in msg and field in msg and "\n" not in msg.strip()
    assert main(["validate", str(path)]) == 2


def test_loads_read_the_speeds_by_name(tmp_path):
    """A file's loads may use a frame's speeds (a spin damper −c w3 b3): the top's spin then decays as
    ẇ3 = −c w3 / I3.  Their rates, accelerations, are refused in a load with one paragraph."""
    from rigidkin.base.errors import InputError
    from rigidkin.io.problem import load_problem

    damped = TOP_FILE.replace('I3 = { unit = "kg*m^2", value = 4e-5 }',
                              'I3 = { unit = "kg*m^2", value = 4e-5 }\nc = { unit = "N*m*s", value = 1e-6 }')
    damped += 'spin_damper = { type = "torque", body = "top", vector = "-c*w3*b3" }\n'
    path = tmp_path / "damped.toml"
    path.write_text(damped)
    s, _ = load_problem(path)
    sol = s.solve()
    w3 = speeds_of(s).speeds[2]
    c, I3 = s.parameters["c"], s.parameters["I3"]
    acc = {str(k): v for k, v in sol.accelerations.items()}
    assert sp.simplify(acc["w3_int(t)"] + c * w3 / I3) == 0, acc
    path.write_text(damped.replace("-c*w3*b3", "-c*dot(w3)*b3"))
    with pytest.raises(InputError, match=r"dot\(w3\), the rate of the speed w3, is an acceleration"):
        load_problem(path)
