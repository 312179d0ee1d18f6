"""base.opcount.count_ops against sympy.count_ops itself: the same integer on every expression."""

import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin.base.opcount import count_ops
from rigidkin.examples import chain

a, b, c = sp.symbols("a b c")
q = dynamicsymbols("q")

CRAFTED = [
    0, 1, -1, sp.Rational(-1, 3), sp.Rational(2, 5), a, -a, a + b, a - b, -a - b, -a + b, -a - b + c,
    2 * a, -2 * a, a / b, -a / b, 2 / a, -2 / a, a / 3, -a / (3 * b), a**2, a**-1, a**-2, (a + b)**-1,
    sp.sqrt(a), 1 / sp.sqrt(a + b), sp.exp(a), sp.exp(-a), sp.E, sp.E**2, sp.sin(a) * sp.cos(b) / (1 + a**2),
    sp.Max(a, b), sp.Min(a, b, c), q.diff(), q.diff(dynamicsymbols._t, 2) * sp.sin(q) - q.diff()**2,
    sp.Derivative(sp.Function("F")(a), a), sp.Integral(a, (a, 0, 1)), a**b, a**(-b), sp.exp(a - b) / (a - c),
    (a - b) * (b - c) / ((a + c) * (c - a)), -sp.pi * a / 7 + sp.I * b,
]


@pytest.mark.parametrize("expr", CRAFTED, ids=range(len(CRAFTED)))
def test_crafted_expressions(expr):
    for e in (expr, -sp.sympify(expr), 1 / (sp.sympify(expr) + a), sp.sympify(expr) * b - 3):
        assert count_ops(e) == sp.count_ops(e)


def test_chain_mass_matrix_and_forcing_with_a_shared_memo():
    r = chain.build(4).solve().regimes[0]
    entries = [*r.raw_mass_matrix, *r.raw_forcing]
    memo: dict = {}
    counted = [count_ops(e, memo) for e in entries]
    assert counted == [sp.count_ops(e) for e in entries]
    assert sum(counted) > 100                      # real expressions, not zeros
    assert count_ops(sp.Eq(a, b)) == sp.count_ops(sp.Eq(a, b))      # not an expression: sympy's own count
