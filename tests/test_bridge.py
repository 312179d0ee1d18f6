"""The bridge to sympy.physics.mechanics, PyDy, scipy and pandas (issue 33, point 8).

References: KanesMethod built by hand for a rod pendulum and a double pendulum (mass matrix and forcing
term for term); scipy's solve_ivp on ``Solution.rhs()`` against rigidkin's own simulation; the result's
own histories for ``to_pandas`` and the drawn lines.
"""

from __future__ import annotations

import sys

import matplotlib
import numpy as np
import pytest
import sympy as sp
import sympy.physics.mechanics as me
from scipy.integrate import solve_ivp

import rigidkin as rk
from rigidkin.base.errors import InputError
from rigidkin.numeric.simulate import simulate

matplotlib.use("Agg")
t = rk.t


def pendulum(n: int) -> rk.System:
    """n uniform rods (mass m, length l) in a chain, absolute angles from the downward vertical, pinned."""
    s = rk.System(f"pendulum{n}")
    m, l = s.parameter("m", "kg", value=1.2), s.parameter("l", "m", value=0.8)
    g = s.parameter("g", "m/s^2", value=9.81)
    top, above = s.origin, None
    for i in range(1, n + 1):
        th = s.coordinate(f"theta{i}", "from the downward vertical, counter-clockwise", initial=0.4 * i, rate=0.1)
        R = s.frame(f"R{i}", angle=th)
        G = s.point(f"G{i}", top, -l / 2 * R.y)
        rod = s.body(f"rod{i}", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
        s.pin(f"P{i - 1}", top, rod, above)
        top, above = s.point(f"P{i}", top, -l * R.y, body=rod), rod
    s.gravity(g)
    return s


def kanes_method(n: int):
    """The same chain with sympy.physics.mechanics alone: KanesMethod with u_i = q̇_i."""
    m, l, g = sp.symbols("m l g")
    q = me.dynamicsymbols(f"theta1:{n + 1}")
    u = me.dynamicsymbols(f"u1:{n + 1}")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    top, bodies, loads = O, [], []
    for i in range(n):
        R = N.orientnew(f"R{i}", "Axis", [q[i], N.z])
        R.set_ang_vel(N, u[i] * N.z)
        G = top.locatenew(f"G{i}", -l / 2 * R.y)
        G.v2pt_theory(top, N, R)
        bodies.append(me.RigidBody(f"rod{i}", G, R, m, (me.inertia(R, m * l**2 / 12, 0, m * l**2 / 12), G)))
        loads.append((G, -m * g * N.y))
        nxt = top.locatenew(f"P{i}", -l * R.y)
        nxt.v2pt_theory(top, N, R)
        top = nxt
    km = me.KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=[qi.diff(t) - ui for qi, ui in zip(q, u)])
    km.kanes_equations(bodies, loads)
    return km, q, u


@pytest.fixture(scope="module")
def single():
    s = pendulum(1)
    return s, s.solve()


@pytest.fixture(scope="module")
def double():
    s = pendulum(2)
    return s, s.solve()


# results by key, by name, by sympy's own symbol -------------------------------------------------------
def test_accelerations_by_key_name_and_dynamicsymbol(single):
    s, sol = single
    th = s.coordinates[0]
    ours = sol.accelerations[th]
    assert ours.has(sp.sin(th))
    assert sol.accelerations["theta1"] == ours
    assert sol.accelerations[me.dynamicsymbols("theta1")] == ours
    assert me.dynamicsymbols("theta1") != th              # sympy's own symbol is another object: found by name
    assert "theta1" in sol.accelerations and "theta9" not in sol.accelerations
    with pytest.raises(KeyError, match="no entry for 'theta9'; the entries are 'theta1'"):
        sol.accelerations["theta9"]
    assert sol.accelerations.by_name() == {"theta1": ours}


def test_reactions_by_name_and_symbol(single):
    s, sol = single
    names = list(sol.reactions)
    assert names and all(isinstance(k, str) for k in names)
    for k in names:
        assert sol.reactions[sp.Symbol(k)] == sol.reactions[k]
        assert sol.reactions[sp.Symbol(k, real=True)] == sol.reactions[k]
    assert sol.regime(0).reactions["R_P0y"] == sol.reactions["R_P0y"]
    with pytest.raises(KeyError, match="reactions: no entry for 'N'"):
        sol.reactions["N"]


def test_rate_relations_by_dot_name():
    from rigidkin import examples

    sol = examples.build("disk-in-track").solve()
    (qd,) = list(sol.rate_relations)
    name = qd.expr.func.__name__
    assert sol.rate_relations[f"dot({name})"] == sol.rate_relations[qd]
    assert sol.rate_relations[me.dynamicsymbols(name).diff(t)] == sol.rate_relations[qd]
    assert sol.relations[name] == sol.relations[qd.expr]


# substitutions ---------------------------------------------------------------------------------------
def test_subs_accepts_names_and_sympy_symbols(single):
    s, sol = single
    th = s.coordinates[0]
    m, l, g = (s.parameters[k] for k in "mlg")
    a = sol.accelerations[th]
    expected = a.xreplace({th: sp.Float(0.5), g: 10, l: 2})
    assert sp.simplify(sol.subs(a, {me.dynamicsymbols("theta1"): 0.5, sp.Symbol("g"): 10, "l": 2}) - expected) == 0
    assert sp.simplify(sol.subs(a, {"theta1": 0.5, g: 10, l: 2}) - expected) == 0
    # an expression written with sympy's own symbols means the same quantities
    user = -3 * sp.Symbol("g") * sp.sin(me.dynamicsymbols("theta1")) / (2 * sp.Symbol("l"))
    assert sp.simplify(sol.subs(user, {}) - a) == 0
    rate = sol.subs(th.diff(t) ** 2 + th, {me.dynamicsymbols("theta1").diff(t): 2, "theta1": 1})
    assert rate == 5
    with pytest.raises(InputError, match=r"phi\(t\) in the values is no coordinate, rate or parameter"):
        sol.subs(a, {me.dynamicsymbols("phi"): 1})


def test_reactions_at_with_sympy_symbols(single):
    s, sol = single
    th = s.coordinates[0]
    ours = sol.reactions_at({th: 0.3, th.diff(t): 1.5})
    theirs = sol.reactions_at({me.dynamicsymbols("theta1"): 0.3, "dot(theta1)": 1.5})
    assert ours == pytest.approx(theirs, rel=1e-14)
    # by hand: the rod's centre on a circle of radius l/2; R_y − m g = m (l/2)(θ̈ sin θ + θ̇² cos θ)
    m, l, g = 1.2, 0.8, 9.81
    acc = -3 * g * np.sin(0.3) / (2 * l)
    assert ours["R_P0y"] == pytest.approx(m * g + m * l / 2 * (acc * np.sin(0.3) + 1.5**2 * np.cos(0.3)), rel=1e-12)
    with pytest.raises(InputError, match="no coordinate, rate or parameter"):
        sol.reactions_at({"theta2": 0.3})


# sympy.physics.mechanics ---------------------------------------------------------------------------
@pytest.mark.parametrize("n", [1, 2])
def test_to_sympy_equals_kanes_method(n, single, double):
    s, sol = single if n == 1 else double
    km, q, u = kanes_method(n)
    form = sol.to_sympy()
    assert list(form.q) == list(q)                       # sympy's own dynamicsymbols, by the same names
    to_ours = dict(zip(u, form.u))
    M = km.mass_matrix.xreplace(to_ours)
    f = km.forcing.xreplace({**{ui.diff(t): v.diff(t) for ui, v in to_ours.items()}, **to_ours})
    assert sp.simplify(form.mass_matrix - M) == sp.zeros(n, n)
    assert sp.simplify(form.forcing - f) == sp.zeros(n, 1)
    Mf = km.mass_matrix_full.xreplace(to_ours)
    ff = km.forcing_full.xreplace(to_ours)
    assert sp.simplify(form.mass_matrix_full - Mf) == sp.zeros(2 * n, 2 * n)
    assert sp.simplify(form.forcing_full - ff) == sp.zeros(2 * n, 1)
    kd = {k: v.xreplace(to_ours) for k, v in km.kindiffdict().items()}
    assert kd == {qi.diff(t): v for qi, v in zip(form.q, form.qdot)}
    assert list(form.kdes) == [qi.diff(t) - v for qi, v in zip(form.q, form.u)]


def test_to_sympy_keeps_assumptions_when_asked(single):
    s, sol = single
    form = sol.to_sympy(assumptions=True)
    assert form.q == s.coordinates
    assert form.mass_matrix.free_symbols >= {s.parameters["m"], s.parameters["l"]}


def test_sympy_system_gives_kanes_equations(double):
    s, sol = double
    ms = sol.to_sympy_system()
    ms.validate_system()
    ms.form_eoms()
    form = sol.to_sympy(assumptions=True)
    assert list(ms.q) == list(s.coordinates) and list(ms.u) == list(form.u)
    assert sp.simplify(ms.mass_matrix - form.mass_matrix) == sp.zeros(2, 2)
    assert sp.simplify(ms.forcing - form.forcing) == sp.zeros(2, 1)
    # and the hand-built KanesMethod of the same chain, in sympy's plain symbols
    km, q, u = kanes_method(2)
    plain = sol.to_sympy()
    assert sp.simplify(plain.mass_matrix - km.mass_matrix.xreplace(dict(zip(u, plain.u)))) == sp.zeros(2, 2)


def test_sympy_system_with_a_rolling_constraint():
    """The disk rolling in a track: φ's speed dependent, eliminated by KanesMethod from the velocity constraint."""
    from rigidkin import examples

    sol = examples.build("disk-in-track").solve()
    ms = sol.to_sympy_system()
    ms.form_eoms()
    assert len(ms.u_dep) == 1
    th = sol.coordinates[0]
    back = {u: q.diff(t) for q, u in zip(ms.q, ms.u)}
    rhs = ms.rhs()
    a = rhs[len(ms.q) + list(ms.u).index(sol.to_sympy(assumptions=True).u[0])].xreplace(back)
    assert sp.simplify(a - sol.accelerations[th]) == 0
    form = sol.to_sympy()
    assert [q.func.__name__ for q in form.q] == ["theta"]          # φ follows from θ (the integrated relation)


# scipy ---------------------------------------------------------------------------------------------
def test_rhs_with_solve_ivp_matches_simulate(double):
    s, sol = double
    rhs = sol.rhs()
    assert rhs.states == ("theta1", "theta2", "dot(theta1)", "dot(theta2)")
    assert rhs.parameters == ("m", "l", "g")
    res = simulate(s, 1.5, rtol=1e-11, atol=1e-12)
    out = solve_ivp(rhs, (0, 1.5), rhs.initial, args=(rhs.values,), t_eval=res.t, rtol=1e-11, atol=1e-12,
                    method="DOP853")
    for i, name in enumerate(rhs.states):
        assert np.max(np.abs(out.y[i] - res[name])) < 1e-7, name
    from scipy.integrate import odeint

    ys = odeint(rhs.for_odeint(), rhs.initial, res.t, args=(rhs.values,), rtol=1e-11, atol=1e-12)
    assert np.max(np.abs(ys[:, 0] - res["theta1"])) < 1e-7
    # other parameters: a longer rod swings more slowly (the ratio of the small-angle frequencies)
    y0 = np.array([0.01, 0.0, 0.0, 0.0])
    a1 = rhs(0.0, y0, [1.2, 0.8, 9.81])[2]
    a2 = rhs(0.0, y0, [1.2, 3.2, 9.81])[2]
    assert a1 / a2 == pytest.approx(4.0, rel=1e-12)
    with pytest.raises(InputError, match="takes 3 parameters"):
        rhs(0.0, y0, [1.0])


# pandas and plots ----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def run(single):
    s, _ = single
    return simulate(s, 1.0, n_points=101)


def test_to_pandas_holds_the_histories(run):
    pytest.importorskip("pandas")
    df = run.to_pandas()
    assert df.index.name == "t"
    np.testing.assert_array_equal(df.index.to_numpy(), run.t)
    for k, v in run.columns().items():
        if k != "t":
            np.testing.assert_array_equal(df[k].to_numpy(), v)
    assert set(df["mode"]) == {s.description for s in run.segments}


def test_to_pandas_without_pandas_says_so(run, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match="to_pandas\\(\\) needs pandas, which is not installed"):
        run.to_pandas()


def test_plot_into_axes_chosen_quantities(run, single, tmp_path):
    import matplotlib.pyplot as plt

    s, _ = single
    th = s.coordinates[0]
    fig, ax = plt.subplots()
    try:
        back = run.plot(ax=ax, quantities=["theta1", th.diff(t), me.dynamicsymbols("theta1"), "E"])
        assert back is fig
        lines = ax.get_lines()
        assert [ln.get_label() for ln in lines if not ln.get_label().startswith("_")] == [
            "theta1 [rad]", "dtheta1/dt [rad/s]", "theta1 [rad]", "energy: E [J]"]
        np.testing.assert_array_equal(lines[0].get_ydata(), run["theta1"])
        np.testing.assert_array_equal(lines[1].get_ydata(), run["dot(theta1)"])
        np.testing.assert_array_equal(lines[3].get_ydata(), run["E"])
    finally:
        plt.close(fig)
    fig2 = run.plot(tmp_path / "r.png", quantities=["R_P0x", "R_P0y"])
    assert (tmp_path / "r.png").stat().st_size > 1000 and fig2.axes[0].get_ylabel() == "[N or N·m]"
    with pytest.raises(InputError, match="'psi' is no history of this simulation"):
        run.plot(quantities=["psi"])


def test_sweep_to_pandas_holds_the_table(monkeypatch):
    pytest.importorskip("pandas")
    from rigidkin import examples
    from rigidkin.numeric.sweeps.sweep import sweep

    runs = sweep(examples.build("ladder"), {"theta": (0.2, 1.0, 3)}, stop_at="N_A")
    df = runs.to_pandas()
    cols = runs.columns()
    assert df.index.name == "run" and list(df.index) == [0, 1, 2]
    assert list(df.columns) == [k for k in cols if k != "run"]
    for k, v in cols.items():
        if k != "run":
            assert [str(a) for a in df[k]] == [str(b) for b in v], k
    # the ladder leaves the wall where cos θ = (2/3) cos θ0 (card ladder (b)), each run from rest
    th0, th = df["theta"].to_numpy(), df["N_A: theta"].to_numpy()
    np.testing.assert_allclose(np.cos(th), 2 / 3 * np.cos(th0), atol=1e-6)
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match="needs pandas"):
        runs.to_pandas()


def test_histories_by_symbol(run, single):
    s, _ = single
    th = s.coordinates[0]
    np.testing.assert_array_equal(run[th], run["theta1"])
    np.testing.assert_array_equal(run[me.dynamicsymbols("theta1")], run["theta1"])
    np.testing.assert_array_equal(run[me.dynamicsymbols("theta1").diff(t)], run["dot(theta1)"])
    np.testing.assert_array_equal(run[sp.Symbol("R_P0y")], run["R_P0y"])
    np.testing.assert_array_equal(run.q[th], run.y[:, 0])
    np.testing.assert_array_equal(run.rates[th.diff(t)], run.y[:, 1])
    with pytest.raises(KeyError, match="coordinates: no entry for 'psi'"):
        run.q["psi"]


def test_regimes_are_picked_for_sympy_and_scipy():
    """A disk sliding on an incline (slip-to-roll): sliding friction µN makes two regimes; by hand, sliding
    forward, ẍ = g (sin β − µ cos β) and φ̈ = 2 µ g cos β / r (r µ m g cos β = ½ m r² φ̈)."""
    from rigidkin import examples
    from rigidkin.base.errors import RegimeError

    s = examples.build("slip-to-roll")
    sol = s.solve()
    with pytest.raises(RegimeError, match="2 regimes"):
        sol.to_sympy()
    with pytest.raises(RegimeError, match="2 regimes"):
        sol.rhs()
    forward = next(i for i, r in enumerate(sol.regimes) if r.conditions[0].relation == ">")
    # regime_at by names and by sympy's own symbols: ẋ − r φ̇ = 1 > 0 is sliding forward
    assert sol.regime_at({"dot(x)": 1.0, me.dynamicsymbols("phi").diff(t): 0.0}) is sol.regimes[forward]
    assert sol.regime_at({"dot(x)": -1.0, "dot(phi)": 0.0}) is sol.regimes[1 - forward]
    rhs = sol.rhs(regime=forward)
    assert rhs.states == ("x", "phi", "dot(x)", "dot(phi)")
    vals = dict(zip(rhs.parameters, rhs.values))
    g, mu, beta, r = vals["g"], vals["mu"], vals["beta"], vals["r"]
    dy = rhs(0.0, [0.0, 0.0, 1.0, 0.0])                      # ẋ = 1 > r φ̇ = 0: sliding forward
    assert dy[:2] == pytest.approx([1.0, 0.0])
    assert dy[2] == pytest.approx(g * (np.sin(beta) - mu * np.cos(beta)), rel=1e-12)
    assert dy[3] == pytest.approx(2 * mu * g * np.cos(beta) / r, rel=1e-12)
    form = sol.to_sympy(regime=forward)
    a = [sp.sympify(e).subs(dict(zip(sp.symbols("m r beta g mu d"), rhs.values))) for e in form.rhs()[2:]]
    assert [float(v) for v in a] == pytest.approx(list(dy[2:]), rel=1e-12)
