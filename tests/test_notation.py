"""Notation of rates and accents: dots over the symbol's letter in text, MathML and LaTeX.

Text: ``theta1`` → θ̇₁ (not ṫheta1), ``x_B`` → ẍ_B, ``phi2`` → φ̇₂, and ``dot(xA)`` where a name has no one
letter to carry the dot.  MathML: the dot is an over-script on the letter (inside a subscript's base),
not stretchy; ``e_hat`` and ``x_bar`` print with a hat and a bar.  How a browser draws them is tested
in pixels in tests/test_report_browser.py.
"""

from __future__ import annotations

import unicodedata
from xml.dom.minidom import parseString

import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin.base.printing import dotted, greek, text
from rigidkin.report.notation import latex, mathml

t = dynamicsymbols._t


@pytest.mark.parametrize("name, plain, one, two", [
    ("theta", "θ", "θ̇", "θ̈"),
    ("theta1", "θ₁", "θ̇₁", "θ̈₁"),
    ("phi2", "φ₂", "φ̇₂", "φ̈₂"),
    ("x_B", "x_B", "ẋ_B", "ẍ_B"),
    ("theta_1", "θ_1", "θ̇_1", "θ̈_1"),
    ("omega_rod", "ω_rod", "ω̇_rod", "ω̈_rod"),
    ("x2", "x₂", "ẋ₂", "ẍ₂"),
    ("θ1", "θ₁", "θ̇₁", "θ̈₁"),
    ("xA", "xA", "dot(xA)", "ddot(xA)"),
])
def test_text_dots_sit_over_the_letter(name, plain, one, two):
    q = dynamicsymbols(name)
    assert greek(name) == plain
    assert text(q) == plain
    assert _nfd(text(q.diff(t))) == _nfd(one) == _nfd(dotted(name, 1))
    assert _nfd(text(q.diff(t, 2))) == _nfd(two) == _nfd(dotted(name, 2))
    assert text(q.diff(t, 3)) == plain + "⁽³⁾"
    # the combining dots follow the first letter, never a later one (not ṫheta1)
    for s in (text(q.diff(t)), text(q.diff(t, 2))):
        marks = [i for i, ch in enumerate(_nfd(s)) if ch in "\u0307\u0308"]
        assert marks in ([], [1]), s


def test_state_rate_keys_read_with_dots():
    """An event's state in a report's table: dot(theta) = 2.16 reads θ̇ = 2.16."""
    assert _nfd(greek("dot(theta)")) == _nfd("θ̇") and _nfd(greek("dot(theta1)")) == _nfd("θ̇₁")
    assert _nfd(greek("ddot(x_B)")) == _nfd("ẍ_B") and greek("dot(xA)") == "dot(xA)"


def _nfd(s: str) -> str:
    return unicodedata.normalize("NFD", s)


def test_text_equation_reads_with_dots():
    th1 = dynamicsymbols("theta1")
    assert _nfd(text((th1.diff(t, 2), -sp.Symbol("g") * sp.sin(th1) / sp.Symbol("l")))) == _nfd("θ̈₁ = -g·sin(θ₁)/l")


def _dom(m: str):
    return parseString(m).documentElement


def _over(m: str):
    movers = _dom(m).getElementsByTagName("mover")
    assert len(movers) == 1, m
    base, mark = [c for c in movers[0].childNodes if c.nodeType == c.ELEMENT_NODE]
    return movers[0], base, mark


@pytest.mark.parametrize("order, char", [(1, "\u02d9"), (2, "\u00a8")])
def test_mathml_dot_is_an_overscript_on_the_letter(order, char):
    th, th1 = dynamicsymbols("theta theta1")
    mover, base, mark = _over(mathml(th.diff(t, order)))
    assert base.tagName == "mi" and base.firstChild.data == "θ"
    assert mark.tagName == "mo" and mark.firstChild.data == char
    assert mark.getAttribute("stretchy") == "false"
    assert "math-depth" in mark.getAttribute("style")            # the letter's size, not a script's
    # θ̇₁: the dot on θ, inside the subscript's base, the index after
    dom = _dom(mathml(th1.diff(t, order)))
    msub = dom.getElementsByTagName("msub")[0]
    first, index = [c for c in msub.childNodes if c.nodeType == c.ELEMENT_NODE]
    assert first.tagName == "mover" and index.firstChild.data == "1"


@pytest.mark.parametrize("name, base, char, tex", [
    ("e_hat", "e", "^", r"\hat{e}"), ("x_bar", "x", "\u00af", r"\bar{x}"), ("F_hat", "F", "^", r"\hat{F}"),
])
def test_hat_and_bar_names(name, base, char, tex):
    _, b, mark = _over(mathml(sp.Symbol(name)))
    assert b.firstChild.data == base and mark.firstChild.data == char
    assert mark.getAttribute("stretchy") == "false"
    assert latex(sp.Symbol(name)) == tex
    assert "hat" not in mathml(sp.Symbol(name)) and "bar" not in mathml(sp.Symbol(name))
