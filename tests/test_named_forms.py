"""M and f with named common sub-expressions (derive/named.py), where a regime is given as M q̈ = f.

Independent reference: the regime's own M and f.  The sub-expressions as printed (the JSON strings, read
back by sympy's parser) are put into M and f in order and compared with M and f at random rational
states — exactly where sympy's numbers allow it, else to 60 digits; the text output shows the same rows.
"""

import random
import sys
from pathlib import Path

import pytest
import sympy as sp

from rigidkin.base import algebra
from rigidkin.derive import named
from rigidkin.derive.closed_forms import structured
from rigidkin.io.results import regime_data
from rigidkin.report.text import problem_text

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import models  # noqa: E402


def _plain_by_name(expr):
    """The expression with q(t), q̇ ... as plain symbols, every symbol keyed by its name (so that what
    the parser reads back and what was derived meet whatever assumptions each symbol carries)."""
    plain, _ = algebra.plain_state(sp.sympify(expr))
    return plain.xreplace({s: sp.Symbol(s.name) for s in plain.free_symbols})


def _read(text):
    return _plain_by_name(sp.parse_expr(text))


def _equal_at(a, b, values) -> bool:
    """a = b at ``values`` (names and state): exactly, or to 60 digits where sympy leaves sin(3/7) symbolic."""
    va, vb = a.xreplace(values), b.xreplace(values)
    if va == vb:
        return True
    return abs(sp.N(va - vb, 60)) <= sp.Float(10) ** -50 * max(1, abs(sp.N(vb, 60)))


@pytest.fixture(scope="module", params=[pytest.param("four_bar", marks=pytest.mark.slow), "cart_pendulum"])
def structured_regime(request):
    system = getattr(models, request.param)()
    sol = system.solve()
    (regime,) = sol.regimes
    assert structured(regime)
    return sol, regime


def test_printed_subexpressions_give_M_and_f_exactly(structured_regime):
    sol, regime = structured_regime
    data = regime_data(regime, sol.system)["named"]
    assert data is not None and data["subexpressions"]
    names = [(sp.Symbol(d["name"]), _read(d["expression"])) for d in data["subexpressions"]]
    M_named = sp.Matrix([[_read(x) for x in row] for row in data["mass_matrix"]])
    f_named = sp.Matrix([_read(x) for x in data["forcing"]])
    M = regime.mass_matrix.applyfunc(_plain_by_name)
    f = regime.forcing.applyfunc(_plain_by_name)
    assert M_named.shape == M.shape and f_named.shape == f.shape
    free = set().union(*[e.free_symbols for e in (*M, *f)])
    rng = random.Random(11)
    for _ in range(3):
        values = {s: sp.Rational(rng.randint(3, 40), rng.randint(7, 23)) for s in free}
        # the definitions evaluated in order, each from the state and the names before it
        at = dict(values)
        for s, e in names:
            assert not (e.free_symbols - set(at)), f"{s} uses a name defined after it"
            at[s] = e.xreplace(at)
        for got, want in zip((*M_named, *f_named), (*M, *f)):
            assert _equal_at(got, want, at)


def test_substituted_back_symbolically_is_M_and_f(structured_regime):
    sol, regime = structured_regime
    M, f = named.of_regime(regime, sol.system).substituted()
    rng = random.Random(5)
    for got, want in zip((*M, *f), (*regime.mass_matrix, *regime.forcing)):
        got, want = _plain_by_name(got), _plain_by_name(want)
        values = {s: sp.Rational(rng.randint(3, 40), rng.randint(7, 23)) for s in got.free_symbols | want.free_symbols}
        assert _equal_at(got, want, values)


def test_the_text_output_shows_the_named_rows(structured_regime):
    sol, regime = structured_regime
    out = problem_text(sol)
    assert "named common sub-expressions" in out and "exact at any state" in out
    rows = named.rows(named.of_regime(regime, sol.system))
    assert any(str(k).startswith("M_") for k, _ in rows) and any(str(k).startswith("f_") for k, _ in rows)
    from rigidkin.base.printing import text

    for k, v in rows:
        assert f"{text(k)} = {text(v)}" in out


def test_names_avoid_the_models_symbols():
    # the cart has a coordinate x: its names use another letter
    sol = models.cart_pendulum().solve()
    form = named.of_regime(sol.regimes[0], sol.system)
    assert form.names and not str(form.names[0][0]).startswith("x")
