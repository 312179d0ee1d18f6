"""Printing for people: unicode text (θ̈, θ̇, µ) for a terminal and LaTeX for documents and Jupyter.

Coordinates print by name without ``(t)``, their rates with dots above (one dot per derivative up
to two, then a superscript order), Greek names as Greek letters.
"""

from __future__ import annotations

import re

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols, vlatex
from sympy.printing.str import StrPrinter

t = dynamicsymbols._t

GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "zeta": "ζ", "eta": "η",
    "theta": "θ", "iota": "ι", "kappa": "κ", "lambda": "λ", "lamda": "λ", "mu": "µ", "nu": "ν", "xi": "ξ",
    "omicron": "ο", "pi": "π", "rho": "ρ", "sigma": "σ", "tau": "τ", "upsilon": "υ", "phi": "φ", "chi": "χ",
    "psi": "ψ", "omega": "ω", "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π",
    "Sigma": "Σ", "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω",
}
_SUP = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
_DOTS = {1: "\u0307", 2: "\u0308"}


_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
_RATE_KEY = re.compile(r"(d?)dot\((\w+)\)")         # a state's rate: dot(theta), ddot(x)
_INDEXED = re.compile(r"([^\W\d_]+?)(\d+)")       # a letter or a Greek name, then its index: theta1, x2


def _letter_index(head: str) -> tuple[str, str]:
    """(letter, index) of a symbol's head: ``theta1`` → (theta, 1), ``x`` → (x, ""); ("", "") for a word (``xA``)."""
    if head in GREEK or (len(head) == 1 and head.isalpha()):
        return head, ""
    m = _INDEXED.fullmatch(head)
    if m and (m.group(1) in GREEK or len(m.group(1)) == 1):
        return m.group(1), m.group(2)
    return "", ""


def greek(name: str) -> str:
    """``theta_1`` → ``θ_1``; ``theta1`` → ``θ₁``; ``m2`` → ``m₂``; ``F_hat`` → ``F̂``; a state's rate
    ``dot(theta)`` → ``θ̇``."""
    rate = _RATE_KEY.fullmatch(name)
    if rate:
        return dotted(rate.group(2), 1 + len(rate.group(1)))
    head, sep, tail = name.partition("_")
    if tail == "hat":
        return greek(head) + "\u0302"
    letter, index = _letter_index(head)
    if index:
        return GREEK.get(letter, letter) + index.translate(_SUB) + sep + tail
    return GREEK.get(head, head) + sep + tail


def dotted(name: str, order: int) -> str:
    """A coordinate's rate with its dots over the symbol's letter: ``theta`` → θ̇, ``theta1`` → θ̇₁,
    ``x_B`` → ẍ_B (order 2), ``phi2`` → φ̇₂, ``y1`` → ẏ₁; ``dot(xA)`` / ``ddot(xA)`` where the name has no one letter
    to carry them."""
    head, sep, tail = name.partition("_")
    letter, index = _letter_index(head)
    if not letter:
        return f"{'d' * (order - 1)}dot({greek(name)})"
    return GREEK.get(letter, letter) + _DOTS[order] + index.translate(_SUB) + sep + tail


class TextPrinter(StrPrinter):
    """sympy's str printer with dynamics notation."""

    def _print_Symbol(self, expr):
        return greek(expr.name)

    _print_Dummy = _print_Symbol

    def _print_Function(self, expr):
        if isinstance(expr.func, sp.core.function.UndefinedFunction) and expr.args == (t,):
            return greek(expr.func.__name__)
        return super()._print_Function(expr)

    def _print_Float(self, expr):
        """A number found numerically, to 10 significant digits (1.28483152, not 1.28483151989612)."""
        s = format(float(expr), ".10g")
        return s if any(c in s for c in ".en") else s + ".0"

    def _print_Derivative(self, expr):
        f = expr.expr
        if isinstance(f, sp.Function) and isinstance(f.func, sp.core.function.UndefinedFunction) \
                and f.args == (t,) and all(v == t for v, _ in expr.variable_count):
            order = sum(c for _, c in expr.variable_count)
            if order in _DOTS:
                return dotted(f.func.__name__, order)
            return f"{greek(f.func.__name__)}⁽{str(order).translate(_SUP)}⁾"
        return super()._print_Derivative(expr)


_PRINTER = TextPrinter({"order": "none"})


def text(expr) -> str:
    """Unicode text of an expression, a vector, or an equation (lhs, rhs)."""
    if isinstance(expr, tuple) and len(expr) == 2:
        return f"{text(expr[0])} = {text(expr[1])}"
    if isinstance(expr, Vector):
        return text_vector(expr)
    if isinstance(expr, sp.Eq):
        return f"{text(expr.lhs)} = {text(expr.rhs)}"
    if isinstance(expr, sp.MatrixBase):
        return "[" + ", ".join(text(e) for e in expr) + "]"
    s = _PRINTER.doprint(sp.sympify(expr))
    s = re.sub(r"\*\*(-?\d+)", lambda m: m.group(1).translate(_SUP), s)
    s = s.replace("**", "^").replace("*", "·")
    return s


def text_vector(v: Vector) -> str:
    """A vector as a sum of components times named basis vectors (in the frames it is written in)."""
    if v == Vector(0):
        return "0"
    terms = []
    for measure, frame in v.args:
        for comp, name in zip(measure, frame.str_vecs):
            comp = sp.sympify(comp)
            if comp == 0:
                continue
            c = text(comp)
            if comp == 1:
                terms.append(name)
            elif comp == -1:
                terms.append("-" + name)
            elif comp.is_Add:
                terms.append(f"({c}) {name}")
            else:
                terms.append(f"{c} {name}")
    return " + ".join(terms).replace("+ -", "- ") if terms else "0"


def latex(expr) -> str:
    """LaTeX (with θ̇ as \\dot{\\theta}) of an expression, vector, or equation (lhs, rhs)."""
    if isinstance(expr, tuple) and len(expr) == 2:
        return f"{latex(expr[0])} = {latex(expr[1])}"
    if isinstance(expr, sp.Eq):
        return f"{latex(expr.lhs)} = {latex(expr.rhs)}"
    return vlatex(expr)
