"""Closed forms where they are cheap, structure where they are not (issue 31, derive/closed_forms.py).

Independent references: M q̈ = f as derived, solved numerically (numpy) at random states, for the
closed-form accelerations of the bundled examples; the balance equations themselves, solved numerically
(least squares over every scalar equation, reactions and q̈ together), for reactions written in terms of q̈.
"""

import random
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin import examples
from rigidkin.base import algebra
from rigidkin.derive import closed_forms
from rigidkin.derive.kinematics import linear_form
from rigidkin.report.text import problem_text

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import models  # noqa: E402

t = dynamicsymbols._t


def _states(sol, regime, n=3, seed=5):
    """Random numeric values of every coordinate, rate and parameter (symbols as sympy uses them)."""
    exprs = list(regime.raw_mass_matrix) + list(regime.raw_forcing)
    plain, back = algebra.plain_state(sp.Matrix(exprs))
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        vals = {s: rng.uniform(0.3, 1.2) for s in plain.free_symbols - {t}}
        out.append({back.get(s, s): v for s, v in vals.items()})
    return out


def _num(expr, values):
    plain, back = algebra.plain_state(sp.sympify(expr))
    fwd = {s: values[o] for s, o in back.items() if o in values}
    rest = {k: v for k, v in values.items() if k not in back.values()}
    vals = {k: sp.Float(v, 30) for k, v in {**fwd, **rest}.items()}
    return complex(sp.sympify(plain.xreplace(vals)).evalf(30)).real


@pytest.mark.parametrize("name", ["boulder-push", "collar-force", "collar-rod", "disk-in-track", "ladder",
                                  "sphere-on-sphere", "gyroscope", "paper-pull", "slip-to-roll"])
def test_closed_form_accelerations_equal_M_inverse_f(name):
    sol = examples.build(name).solve()
    for regime in sol.regimes:
        assert regime.form.closed
        coords = list(sol.coordinates)
        for st in _states(sol, regime):
            M = np.array([[_num(e, st) for e in regime.raw_mass_matrix.row(i)]
                          for i in range(regime.raw_mass_matrix.rows)])
            f = np.array([_num(e, st) for e in regime.raw_forcing])
            ref = np.linalg.solve(M, f)
            got = np.array([_num(regime.accelerations[q], st) for q in coords])
            assert np.allclose(got, ref, rtol=1e-12, atol=1e-12 * max(1.0, np.abs(ref).max()))


def test_a_cart_with_three_links_is_given_as_structure_and_its_reactions_in_terms_of_the_accelerations():
    s = models.cart_pendulum(3)
    sol = s.solve()
    r = sol.regimes[0]
    assert not r.form.closed and r.form.predicted > closed_forms.CLOSED_FORM_OPS
    assert closed_forms.choose(r.raw_mass_matrix, r.raw_forcing) == r.form        # the same choice every time
    out = problem_text(sol)
    assert "from M q̈ = f" in out and "too large to read" in out
    assert closed_forms.structured(r)               # printing did not build the closed form
    # the reactions, with q̈ from M q̈ = f, against the balance equations solved numerically
    accels = [q.diff(t, 2) for q in sol.coordinates]
    names = list(r.reactions)
    syms = sorted({x for e in sol.equations for x in e.expr.free_symbols if x.name in names}, key=str)
    A, b = linear_form([e.expr for e in sol.equations], accels + syms)
    for st in _states(sol, r, n=2, seed=11):
        M = np.array([[_num(e, st) for e in r.raw_mass_matrix.row(i)] for i in range(r.raw_mass_matrix.rows)])
        f = np.array([_num(e, st) for e in r.raw_forcing])
        qdd = dict(zip(accels, np.linalg.solve(M, f)))
        An = np.array([[_num(e, st) for e in A.row(i)] for i in range(A.rows)])
        bn = np.array([_num(e, st) for e in b])
        x, *_ = np.linalg.lstsq(An, -bn, rcond=None)
        assert np.allclose(x[:len(accels)], [qdd[a] for a in accels], rtol=1e-10)
        for k, sym in enumerate(syms):
            got = _num(r.reactions[sym.name].xreplace(qdd), st)
            assert abs(got - x[len(accels) + k]) <= 1e-9 * max(1.0, abs(x[len(accels) + k]))


def test_a_cylinder_in_a_rolling_shell_stays_in_closed_form():
    sol = models.cylinder_in_shell().solve()
    r = sol.regimes[0]
    assert r.form.closed and not closed_forms.structured(r)
    for st in _states(sol, r, n=2):
        M = np.array([[_num(e, st) for e in r.raw_mass_matrix.row(i)] for i in range(r.raw_mass_matrix.rows)])
        f = np.array([_num(e, st) for e in r.raw_forcing])
        ref = np.linalg.solve(M, f)
        got = np.array([_num(r.accelerations[q], st) for q in sol.coordinates])
        assert np.allclose(got, ref, rtol=1e-12)


def test_the_predicted_size_grows_with_the_entries_and_the_count():
    a, b = sp.symbols("a b")
    small = closed_forms.predicted_ops(sp.Matrix([[a, 0], [0, b]]), sp.Matrix([a, b]))
    dense = closed_forms.predicted_ops(sp.Matrix([[a, b], [b, a]]), sp.Matrix([a, b]))
    big = closed_forms.predicted_ops(sp.Matrix(3, 3, [sp.sin(a) * b + a] * 9), sp.Matrix([a, b, a]))
    assert small < dense < big
    assert closed_forms.predicted_ops(sp.zeros(0, 0), sp.zeros(0, 1)) == 0
