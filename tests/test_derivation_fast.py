"""The fast derivation path: one-pass linear forms, vector algebra on components, machine-arithmetic
evaluation, and the readable forms made only when read — each against the slow way it replaces."""

from __future__ import annotations

import random

import sympy as sp
from sympy.physics.vector import ReferenceFrame, dynamicsymbols

from rigidkin import examples
from rigidkin.base import algebra, vectorops
from rigidkin.base.linear import _split_by_diff, linear_form
from rigidkin.derive.mode import setup_mode

t = dynamicsymbols._t


def test_linear_form_matches_derivatives():
    q1, q2 = dynamicsymbols("q1 q2")
    a, b, m = sp.symbols("a b m", positive=True)
    R = sp.Symbol("R")
    u = [q1.diff(t, 2), q2.diff(t, 2), R]
    exprs = [m * (a * sp.cos(q1) * u[0] + b * u[1] * sp.sin(q2) + q1.diff(t) ** 2) - R * sp.sin(q1) + 3,
             (u[0] + u[1]) * (a + b) * sp.cos(q2 - q1) - m * R,
             sp.sin(q1) * q2.diff(t)]
    A, c = linear_form(exprs, u)
    for i, e in enumerate(exprs):
        coeffs, rest = _split_by_diff(e, u)
        for j in range(len(u)):
            assert sp.simplify(A[i, j] - coeffs.get(j, 0)) == 0
        assert sp.simplify(c[i] - rest) == 0
    # an unknown inside a function: still its derivative (not visibly linear, handled by differentiation)
    A2, _ = linear_form([sp.exp(R) + R * a], [R])
    assert sp.simplify(A2[0, 0] - (sp.exp(R) + a)) == 0


def test_vectorops_give_sympys_expressions():
    q, p = dynamicsymbols("q p")
    N = ReferenceFrame("N")
    A = N.orientnew("A", "Axis", (q, N.z))
    B = A.orientnew("B", "Axis", (p, A.x))
    r = 2 * B.y + q * A.x + N.z
    w = B.ang_vel_in(N)
    assert vectorops.cross(w, r).args == w.cross(r).args
    assert vectorops.cross(r, w).args == r.cross(w).args
    assert vectorops.dt(r, N).args == r.dt(N).args
    assert vectorops.dt(r.dt(N), N).args == r.dt(N).dt(N).args
    assert list(vectorops.in_frame(r, N)) == [r.dot(N.x), r.dot(N.y), r.dot(N.z)]
    assert sp.simplify(vectorops.dot_vectors(r, w) - r.dot(w)) == 0


def test_machine_evaluation_agrees_with_evalf():
    q = dynamicsymbols("q")
    x, y = sp.symbols("x y", positive=True)
    exprs = [sp.sin(q) ** 2 * x + sp.sqrt(x + y) / y, sp.atan2(y, x) * sp.exp(q.diff(t)), sp.Abs(q - 2) ** 3]
    vals = algebra.state_point(exprs, random.Random(3), 0.4)
    got = algebra.evaluate(exprs, vals)
    subs = {k: sp.Float(v) for k, v in vals.items()}
    plain, back = algebra.plain_state(sp.Matrix(exprs))
    want = [complex(e.xreplace({s: subs[f] for s, f in back.items()}).xreplace(subs).evalf()) for e in plain]
    assert all(abs(g - w) < 1e-12 * max(1, abs(w)) for g, w in zip(got, want))
    assert algebra.evaluate([1 / x], {x: 0.0})[0] != algebra.evaluate([1 / x], {x: 0.0})[0]    # nan
    assert algebra.is_zero(sp.sin(q) ** 2 + sp.cos(q) ** 2 - 1)
    assert not algebra.is_zero(sp.sin(q) ** 2 - sp.cos(q) ** 2)


def test_readable_forms_made_when_read_and_equal_to_raw():
    system = examples.build("heavy-top")
    sol = system.solve()
    regime = sol.regimes[0]
    assert "_mass_matrix" in regime.__dict__ and not hasattr(regime.__dict__["_mass_matrix"], "shape")
    assert not sol.reactions.computed
    M, f = sol.mass_matrix, sol.forcing                  # readable, made now
    assert hasattr(regime.__dict__["_mass_matrix"], "shape")
    diff = list(M - regime.raw_mass_matrix) + list(f - regime.raw_forcing)
    assert all(algebra.is_zero(d) for d in diff)
    assert sol.reactions["R_Oz"] != 0 and sol.reactions.computed
    assert len(sol.eom) == 3


def test_projected_rows_workless_reactions_cancel():
    """The reaction-free rows (partial velocities once per frame) give the Newton–Euler accelerations."""
    system = examples.build("sphere-on-sphere")
    sol = system.solve()
    setup = setup_mode(system)
    th = setup.reduction.independent[0]
    rows = sol.regimes[0]
    acc = sol.accelerations[th]
    resid = rows.raw_mass_matrix[0, 0] * acc - rows.raw_forcing[0]
    assert algebra.is_zero(resid)


def test_time_derivatives_match_diff():
    q, p = dynamicsymbols("q p")
    a = sp.Symbol("a", positive=True)
    shared = sp.sin(q) * sp.cos(p) ** 2 * a
    exprs = [shared + q.diff(t) * sp.sqrt(a + sp.sin(q)), sp.exp(q) * t * shared, (a * q + p) ** 3 / (1 + shared),
             sp.atan2(sp.sin(q), p), a]
    for e, d in zip(exprs, algebra.time_derivatives(exprs)):
        assert algebra.is_zero(d - e.diff(t))
