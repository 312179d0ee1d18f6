"""Generated code (rigidkin.numeric.compiled.codegen): values against closed forms, KanesMethod and momentum balance."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from helpers import benchmark_models

import rigidkin as rk
from rigidkin.examples import chain
from rigidkin.numeric.compiled import codegen

G = 9.81


pytestmark = pytest.mark.usefixtures("code_cache")      # conftest: compiled once per session


def _ladder_closed_form(theta, dtheta, l):
    dd = 3 * G / (2 * l) * math.sin(theta)
    ddx = l * (math.cos(theta) * dd - math.sin(theta) * dtheta ** 2)
    return np.array([dtheta, l * math.cos(theta) * dtheta, dd, ddx])


@pytest.mark.parametrize("backend", ["c", "numpy"])
def test_ladder_rhs_equals_closed_form(ladder, backend):
    if backend == "c" and not codegen.c_available():
        pytest.skip("no C compiler")
    f = codegen.fast_rhs(ladder, backend=backend)
    rng = np.random.default_rng(1)
    for _ in range(20):
        th, dth = rng.uniform(0.05, 1.4), rng.uniform(-2, 2)
        y = np.array([th, 2 * math.sin(th), dth, 2 * math.cos(th) * dth])
        np.testing.assert_allclose(f(0.0, y), _ladder_closed_form(th, dth, 2.0), rtol=1e-12, atol=1e-12)


def test_ladder_reactions_equal_newton_closed_form(ladder):
    """N_A = m ẍ_G and N_B = m g + m ÿ_G with the closed-form accelerations of the mass centre."""
    m = codegen.compile_model(ladder)
    p = np.array([10.0, 2.0, G])
    names = m.kernel.output_names
    for th, dth in [(0.3, 0.0), (0.7, 1.1), (1.0, 2.0)]:
        dd = 3 * G / 4 * math.sin(th)
        ax = 1.0 * (math.cos(th) * dd - math.sin(th) * dth ** 2)      # x_G = (l/2) sin θ
        ay = -1.0 * (math.sin(th) * dd + math.cos(th) * dth ** 2)     # y_G = (l/2) cos θ
        out = m.outputs(0.0, [th, 2 * math.sin(th), dth, 2 * math.cos(th) * dth], p)
        assert out[names.index("N_A")] == pytest.approx(10 * ax, rel=1e-12, abs=1e-12)
        assert out[names.index("N_B")] == pytest.approx(10 * G + 10 * ay, rel=1e-12)


def test_implicit_equals_explicit_for_the_ladder(ladder):
    ex = codegen.compile_model(ladder, form="explicit")
    im = codegen.compile_model(ladder, form="implicit")
    assert ex.kernel.form == "explicit" and im.kernel.form == "implicit"
    p = np.array([10.0, 2.0, G])
    for th, dth in [(0.2, 0.4), (0.9, -1.3)]:
        y = [th, 2 * math.sin(th), dth, 2 * math.cos(th) * dth]
        np.testing.assert_allclose(im.rhs(0.0, y, p), ex.rhs(0.0, y, p), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(im.outputs(0.0, y, p), ex.outputs(0.0, y, p), rtol=1e-11, atol=1e-11)


def kane_chain(n: int):
    """The same n-rod chain with sympy.physics.mechanics KanesMethod (absolute angles; the benchmarks'
    model): (M, f, q, u, syms)."""
    km, q, u, syms = benchmark_models().kane_chain(n)
    return km.mass_matrix, km.forcing, q, u, syms


@pytest.mark.slow
@pytest.mark.parametrize("form", ["implicit", "auto"])
def test_chain_matches_kanes_method(form):
    """The implicit and mass-matrix kernels (LU in C) give KanesMethod's accelerations M⁻¹ f for a chain."""
    n = 3
    s = chain.build(n)
    model = codegen.compile_model(s, form=form)
    assert model.kernel.form == {"implicit": "implicit", "auto": "mass-matrix"}[form]
    M, f, q, u, (m, l, g) = kane_chain(n)
    Mf = sp.lambdify([*q, *u, m, l, g], [M, f])
    rng = np.random.default_rng(3)
    for _ in range(5):
        qs, us = rng.uniform(-1, 1, n), rng.uniform(-2, 2, n)
        pm, pl = 1.3, 0.7
        Mn, fn = (np.array(a, dtype=float) for a in Mf(*qs, *us, pm, pl, G))
        acc = np.linalg.solve(Mn, fn.ravel())
        dy = model.rhs(0.0, np.r_[qs, us], [pm, pl, G])
        np.testing.assert_allclose(dy[:n], us, rtol=1e-13)
        np.testing.assert_allclose(dy[n:], acc, rtol=1e-9, atol=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("form", ["implicit", "mass-matrix"])
def test_chain_pin_reaction_equals_momentum_balance(form):
    """At rest, the fixed pin carries R_O = Σ m a_G + n m g Ey (Euler's 1st law for the whole chain)."""
    n = 4 if form == "implicit" else 3
    model = codegen.compile_model(chain.build(n), form=form)
    rng = np.random.default_rng(5)
    th = rng.uniform(-0.8, 0.8, n)
    p = np.array([2.0, 0.5, G])
    dy = model.rhs(0.0, np.r_[th, np.zeros(n)], p)
    dd = dy[n:]
    ax = ay = 0.0
    for i in range(n):       # at rest: a_G = Σ_{j<i} l θ̈_j (cos, sin) + l/2 θ̈_i (cos, sin)
        ax += sum(p[1] * dd[j] * math.cos(th[j]) for j in range(i)) + p[1] / 2 * dd[i] * math.cos(th[i])
        ay += sum(p[1] * dd[j] * math.sin(th[j]) for j in range(i)) + p[1] / 2 * dd[i] * math.sin(th[i])
    out = model.outputs(0.0, np.r_[th, np.zeros(n)], p)
    names = model.kernel.output_names
    assert out[names.index("R_P0x")] == pytest.approx(p[0] * ax, rel=1e-10, abs=1e-10)
    assert out[names.index("R_P0y")] == pytest.approx(p[0] * ay + n * p[0] * G, rel=1e-10)


def test_code_is_cached_on_disk_by_model_hash(ladder, tmp_path, monkeypatch):
    if not codegen.c_available():
        pytest.skip("no C compiler")
    monkeypatch.setenv("RIGIDKIN_CACHE", str(tmp_path / "cache"))
    k = codegen.kernel(ladder)
    codegen._LOADED.clear()
    codegen.CompiledModel(k, "c")
    libs = sorted((tmp_path / "cache").glob("rk_*.so"))
    assert len(libs) == 1
    stamp = libs[0].stat().st_mtime_ns
    codegen._LOADED.clear()
    codegen.CompiledModel(k, "c")                       # a new process would find the same file
    assert sorted((tmp_path / "cache").glob("rk_*.so")) == libs and libs[0].stat().st_mtime_ns == stamp
    assert not list(Path(__file__).parents[1].glob("rk_*.so"))
    # a different model (another mode) has another hash
    k2 = codegen.kernel(ladder, mode={"A": "open"})
    assert k2.key() != k.key()


def test_default_cache_dir_is_in_the_users_cache(monkeypatch):
    monkeypatch.delenv("RIGIDKIN_CACHE", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", "/some/where")
    assert codegen.cache_dir() == Path("/some/where/rigidkin")


def test_numpy_fallback_without_compiler(ladder, monkeypatch):
    monkeypatch.setattr(codegen, "compiler", lambda: None)
    k = codegen.kernel(ladder, mode={"A": "open"})
    model = codegen.CompiledModel(k, "auto")
    assert model.backend == "numpy"
    with pytest.raises(codegen.CodegenError, match="no C compiler"):
        codegen.CompiledModel(k, "c")
    # the open ladder (wall gone): θ and x free; at rest the floor reaction balances part of the weight
    y = [0.5, 1.0, 0.0, 0.0]
    dy = model.rhs(0.0, y, [10.0, 2.0, G])
    # free rod on a smooth floor from rest: ẍ_G = 0 and x_B = x_G + (l/2) sin θ, so ẍ_B = (l/2) cos θ θ̈;
    # θ̈ = 6 g sinθ / (l (1 + 3 sin²θ))
    th = 0.5
    dd = 6 * G * math.sin(th) / (2.0 * (1 + 3 * math.sin(th) ** 2))
    assert dy[2] == pytest.approx(dd, rel=1e-12)
    assert dy[3] == pytest.approx(1.0 * math.cos(th) * dd, rel=1e-12)


def test_backend_for_the_simulator_matches_lambdify():
    x, y, p = sp.symbols("x y p")
    t = rk.t
    exprs = [sp.sin(x) * y ** 3 + p, sp.sqrt(x * x + y * y) / p, t * x]
    f = codegen.c_backend([t, x, y, p], exprs)
    g = sp.lambdify([t, x, y, p], exprs)
    for vals in [(0.1, 0.3, -1.2, 2.0), (2.0, -0.7, 0.5, 0.25)]:
        np.testing.assert_allclose(f(*vals), g(*vals), rtol=1e-14)


def test_bad_names_are_clear_errors(ladder):
    with pytest.raises(codegen.CodegenError, match="unknown form"):
        codegen.kernel(ladder, form="fast")
    with pytest.raises(codegen.CodegenError, match="unknown backend"):
        codegen.compile_model(ladder, backend="fortran")
    with pytest.raises(codegen.CodegenError, match="regime 3 does not exist"):
        codegen.kernel(rk.examples.build("boulder-push"), regime=3, form="implicit")
    with pytest.raises(rk.RigidkinError):
        chain.build(0)


def test_c_source_uses_products_for_small_powers(ladder):
    src = codegen.c_source(codegen.kernel(ladder))
    assert "pow(" not in src and "rk_eval_rhs" in src
    assert os.environ["RIGIDKIN_CACHE"]


@pytest.mark.slow
@pytest.mark.skipif(not codegen.c_available(), reason="no C compiler")
def test_simulator_with_the_c_backend_gives_the_same_motion():
    """rigidkin.numeric.rhs.use_backend(codegen.c_backend): the simulator's functions in C, same events."""
    from rigidkin.numeric import rhs, simulate

    th0 = 0.2
    runs = {}
    try:
        for backend in (None, codegen.c_backend):
            rhs.use_backend(backend)
            res = simulate(rk.examples.build("ladder"), 1.5, initial_state={"theta": th0})
            ev = next(e for e in res.events if e.contact == "A")
            runs[backend] = (ev.t, ev.state["theta"], res.final_state)
    finally:
        rhs.use_backend(None)
    (t_a, th_a, end_a), (t_b, th_b, end_b) = runs.values()
    assert th_b == pytest.approx(math.acos(2 / 3 * math.cos(th0)), abs=1e-10)
    assert t_b == pytest.approx(t_a, abs=1e-10)
    for k in end_a:
        assert end_b[k] == pytest.approx(end_a[k], abs=1e-8)
