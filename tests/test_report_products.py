"""Products in a report are written as an engineer writes them: the mass first (m g, m l², never g m).

Checked on MathML and LaTeX of products, fractions and negatives; the factors shown are the same as sympy's
own print of the product (only their order changes), and products without a mass are left as sympy orders them.
"""

from __future__ import annotations

import html
import re

import pytest
import sympy as sp

from rigidkin.report.notation import latex, mathml
from rigidkin.report.products import is_mass, masses_first

g, m, l, th, M, mu, m1, r = sp.symbols("g m l theta M mu m1 r")


def _mi(expr) -> list[str]:
    return [html.unescape(x) for x in re.findall(r"<m[in]>([^<]+)</m[in]>", mathml(expr))]


def _tokens(tex: str) -> list[str]:
    return sorted(re.findall(r"\\[a-z]+|[A-Za-z]|\d+", tex))


@pytest.mark.parametrize(("expr", "mi", "tex"), [
    (-g * m, ["m", "g"], "- m g"),
    (m * l**2 / 3, ["m", "l", "2", "3"], r"\frac{m l^{2}}{3}"),
    (-3 * g * m * sp.sin(th) / 4, ["3", "m", "g", "sin", "θ", "4"], r"- \frac{3 m g \sin{\left(\theta \right)}}{4}"),
    (2 * g * M * mu, ["2", "M", "g", "μ"], r"2 M g \mu"),
    (g * m1 * r, ["m", "1", "g", "r"], None),                 # m₁ g r (m1: m with the subscript 1)
])
def test_the_mass_leads_its_product(expr, mi, tex):
    assert _mi(expr) == mi
    if tex is not None:
        assert latex(expr) == tex
    # the same factors as sympy's own LaTeX of the product, in another order
    assert _tokens(latex(expr)) == _tokens(sp.latex(expr))


def test_products_without_a_mass_keep_sympys_order():
    assert masses_first(g * l) is None and latex(g * l / 2) == r"\frac{g l}{2}"
    assert masses_first(m * sp.Symbol("x")) is None is masses_first(m + g)        # sympy already puts m first
    assert is_mass(sp.Symbol("m_A")) and is_mass(m1**2) and not is_mass(mu) and not is_mass(sp.Symbol("mass"))
