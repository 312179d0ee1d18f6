"""Mathematics for documents: presentation MathML (HTML pages) and LaTeX (Markdown, TeX, Jupyter).

Both printers write the notation of engineering dynamics: coordinates without ``(t)``, rates with
dots above (θ̇, θ̈), Greek names as Greek letters, and vectors and dyadics as sums of components
times the *user's* basis vectors (``l/2 ey + x Ex``, ``m l²/12 ex⊗ex``).  Presentation MathML is
rendered natively by current browsers, so an HTML page needs no script and no network.

A trace step may name a quantity by a label (``weight_of_rod``, ``normal_reaction_N_A``); such
names print as words followed by the symbol (weight of rod, normal reaction N_A).
"""

from __future__ import annotations

import html.entities
import re
import unicodedata
from xml.dom.minidom import Element

import sympy as sp
from sympy.physics.vector import Dyadic, Vector, dynamicsymbols
from sympy.physics.vector.printing import VectorLatexPrinter
from sympy.printing.mathml import MathMLPresentationPrinter
from sympy.printing.precedence import PRECEDENCE

from ..base.printing import GREEK
from ..base.textsafe import tex_text
from .products import masses_first

t = dynamicsymbols._t

_GREEK_UNICODE = set(GREEK.values())
_LATEX_GREEK = {v: "\\" + ("mu" if k == "mu" else "lambda" if k == "lamda" else k) for k, v in GREEK.items()}
_LATEX_GREEK["µ"] = r"\mu"
_DOT_CHARS = {1: "\u02d9", 2: "\u00a8"}
#: Name suffixes that put an accent over the symbol (``e_hat`` → ê, ``x_bar`` → x̄), as MathML marks.
ACCENT_SUFFIXES = {"hat": "^", "bar": "\u00af"}
_RELATIONS = {">": ">", "<": "<", ">=": "≥", "<=": "≤", "=": "="}
_LATEX_RELATIONS = {">": ">", "<": "<", ">=": r"\geq", "<=": r"\leq", "=": "="}


# names -------------------------------------------------------------------------------------------
def _is_word(part: str) -> bool:
    """A word of a label (``weight``, ``of``, ``(no-slip)``), not a symbol's name or index."""
    if part in GREEK or part in _GREEK_UNICODE:
        return False
    if not part.isidentifier():
        return True
    return len(part) >= 2 and part.isalpha() and part.islower()


def split_label(name: str) -> tuple[str, str]:
    """``normal_reaction_N_A`` → (``normal reaction``, ``N_A``); ``N_A`` → (``""``, ``N_A``).

    Only a name whose first part is a word of three letters or more is a label.
    """
    parts = name.split("_")
    if len(parts) < 2 or not (_is_word(parts[0]) and len(parts[0]) >= 3):
        return "", name
    words, rest = [], []
    for i, p in enumerate(parts):
        if _is_word(p):
            words.append(p)
        else:
            rest = parts[i:]
            break
    # words after the symbol ("sliding friction P on disk") stay words
    tail_words = []
    while len(rest) > 1 and _is_word(rest[-1]):
        tail_words.insert(0, rest.pop())
    text = " ".join(words)
    symbol = "_".join(rest)
    if tail_words:
        symbol = symbol + "\0" + " ".join(tail_words)
    return text, symbol


def basis_parts(name: str) -> tuple[str, str]:
    """A basis vector's name as (head, subscript): ``Ex`` → (E, x); ``er_in`` → (e, r,in); ``eθ`` → (e, θ)."""
    head, tail = name[0], name[1:]
    pieces = [p for p in tail.split("_") if p]
    pieces = [GREEK.get(p, p) for p in pieces]
    return head, ",".join(pieces)


def _vector_terms(v: Vector):
    """(component, frame, index) for each nonzero term of a vector, in the frames it is written in."""
    out = []
    for measure, frame in v.args:
        for i in range(3):
            comp = sp.sympify(measure[i])
            if comp != 0:
                out.append((comp, frame, i))
    return out


def _basis_index(v: Vector):
    measure, frame = v.args[0]
    for i in range(3):
        if measure[i] != 0:
            return frame, i
    raise ValueError("not a basis vector")


def _dyadic_terms(d: Dyadic):
    out = []
    for coeff, a, b in d.args:
        coeff = sp.sympify(coeff)
        if coeff == 0:
            continue
        (fa, ia), (fb, ib) = _basis_index(a), _basis_index(b)
        ca, cb = sp.sympify(a.args[0][0][ia]), sp.sympify(b.args[0][0][ib])
        out.append((coeff * ca * cb, (fa, ia), (fb, ib)))
    return out


def _is_rate(e) -> bool:
    """A time derivative of a coordinate q(t) (printed with dots, so never parenthesised)."""
    if not isinstance(e, sp.Derivative):
        return False
    f = e.expr
    return isinstance(f, sp.Function) and isinstance(f.func, sp.core.function.UndefinedFunction) \
        and f.args == (t,) and all(v == t for v, _ in e.variable_count)


def _basis_name(frame, i) -> str:
    names = getattr(frame, "str_vecs", None)
    return names[i] if names else f"{frame.name.lower()}{'xyz'[i]}"


# MathML --------------------------------------------------------------------------------------------
_BARE_AMPERSAND = re.compile(r"&(?![A-Za-z][A-Za-z0-9]*;|#[0-9]+;|#[xX][0-9A-Fa-f]+;)")


def _xml_text(data) -> str:
    """Text for a MathML element: ``<`` and ``>`` always escaped, ``&`` unless it starts a character
    reference (sympy writes ``&InvisibleTimes;`` as text), so no name can open an element."""
    return _BARE_AMPERSAND.sub("&amp;", str(data)).replace("<", "&lt;").replace(">", "&gt;")


class MathMLPrinter(MathMLPresentationPrinter):
    """sympy's presentation MathML with dynamics notation, basis names and labels."""

    def __init__(self, settings=None):
        super().__init__({"mat_delim": "(", **(settings or {})})
        raw = self.dom.createTextNode         # sympy's: writes its text unescaped (for its own entities)
        self.dom.createTextNode = lambda data: raw(_xml_text(data))

    def _el(self, tag: str, *children, text: str | None = None, **attrs) -> Element:
        e = self.dom.createElement(tag)
        for k, v in attrs.items():
            e.setAttribute(k.rstrip("_").replace("_", "-"), v)
        if text is not None:
            e.appendChild(self.dom.createTextNode(text))
        for c in children:
            e.appendChild(c)
        return e

    def accent(self, base: Element, mark: str) -> Element:
        """``mark`` drawn above ``base`` — above a subscripted symbol's letter, not its subscript (θ̇₁).

        Laid out as an over-script at the letter's own size (``math-depth: add(0)``), not as a MathML
        accent: an accent sits on the letter's top and merges into a tall letter (θ̇ drawn as θ), an
        over-script keeps the math font's gap.  The mark is not stretchy: Chromium draws a stretchy
        bar at no width.  Tested in pixels in tests/test_report_browser.py.
        """
        if base.tagName in ("msub", "msubsup") and base.firstChild is not None:
            letter = base.firstChild
            base.replaceChild(self.accent(letter.cloneNode(True), mark), letter)
            return base
        return self._el("mover", base, self._el("mo", text=mark, stretchy="false", style="math-depth:add(0)"),
                        accent="false")

    def _name(self, name: str) -> Element:
        head, sep, suffix = name.rpartition("_")
        if sep and head and suffix in ACCENT_SUFFIXES:
            return self.accent(self._name(head), ACCENT_SUFFIXES[suffix])
        text, symbol = split_label(name)
        words_after = ""
        if "\0" in symbol:
            symbol, words_after = symbol.split("\0")
        if not text:
            return super()._print_Symbol(sp.Symbol(symbol))
        kids = [self._el("mtext", text=text + ("\u00a0" if symbol else ""))]
        if symbol:
            kids.append(super()._print_Symbol(sp.Symbol(symbol)))
        if words_after:
            kids.append(self._el("mtext", text="\u00a0" + words_after))
        return self._el("mrow", *kids)

    def _print_Symbol(self, sym, style="plain"):
        return self._name(sym.name)

    _print_Dummy = _print_Symbol

    def _print_Function(self, e):
        if isinstance(e.func, sp.core.function.UndefinedFunction) and e.args == (t,):
            return self._name(e.func.__name__)
        return super()._print_Function(e)

    def parenthesize(self, item, level, strict=False):
        if _is_rate(item):
            return self._print(item)
        return super().parenthesize(item, level, strict)

    def _print_Derivative(self, e):
        f = e.expr
        if _is_rate(e):
            order = sum(c for _, c in e.variable_count)
            base = self._name(f.func.__name__)
            if order in _DOT_CHARS:
                return self.accent(base, _DOT_CHARS[order])
            return self._el("msup", base, self._el("mrow", self._el("mo", text="("), self._el("mn", text=str(order)),
                                                    self._el("mo", text=")")))
        return super()._print_Derivative(e)

    def basis(self, frame, i) -> Element:
        head, sub = basis_parts(_basis_name(frame, i))
        mi = self._el("mi", text=head, mathvariant="normal", style="font-weight:bold")
        if not sub:
            return mi
        return self._el("msub", mi, self._el("mi", text=sub))

    def _term(self, comp, basis: Element, first: bool, kids: list) -> None:
        neg = comp.could_extract_minus_sign()
        if neg:
            comp = -comp
        if not first or neg:
            kids.append(self._el("mo", text="\u2212" if neg else "+"))
        if comp != 1:
            c = self._print(comp)
            if comp.is_Add:
                c = self._el("mrow", self._el("mo", text="("), c, self._el("mo", text=")"))
            kids.append(c)
            kids.append(self._el("mo", text="\u2062"))
        kids.append(basis)

    def _print_Vector(self, v):
        terms = _vector_terms(v)
        if not terms:
            return self._el("mn", text="0")
        kids = []
        for k, (comp, frame, i) in enumerate(terms):
            self._term(comp, self.basis(frame, i), k == 0, kids)
        return self._el("mrow", *kids)

    def _print_Dyadic(self, d):
        terms = _dyadic_terms(d)
        if not terms:
            return self._el("mn", text="0")
        kids = []
        for k, (comp, a, b) in enumerate(terms):
            outer = self._el("mrow", self.basis(*a), self._el("mo", text="\u2297"), self.basis(*b))
            self._term(comp, outer, k == 0, kids)
        return self._el("mrow", *kids)

    def _print_Mul(self, expr):
        """m g, m l² (report.products): the masses first, factors joined by invisible times."""
        ordered = masses_first(expr)
        if ordered is None:
            return super()._print_Mul(expr)
        coeff, factors = ordered
        kids = [self._el("mo", text="\u2212")] if coeff < 0 else []
        if abs(coeff) != 1:
            kids += [self._print(abs(coeff)), self._el("mo", text="\u2062")]
        for k, f in enumerate(factors):
            kids += ([self._el("mo", text="\u2062")] if k else []) + [self.parenthesize(f, PRECEDENCE["Mul"])]
        return self._el("mrow", *kids)

    def _print_Relational(self, e):
        op = {"==": "=", ">=": "≥", "<=": "≤"}.get(e.rel_op, e.rel_op)
        return self._el("mrow", self._print(e.lhs), self._el("mo", text=op), self._print(e.rhs))

    def _print_Sign(self, e):
        return self._el("mrow", self._el("mi", text="sgn"), self._el("mo", text="("), self._print(e.args[0]),
                        self._el("mo", text=")"))


_MATHML = MathMLPrinter()


_FUNCTION_AFTER_PRODUCT = re.compile(r"(<mo>(?:&InvisibleTimes;|\u2062)</mo>)(<mrow><mi>[a-z]{2,}</mi>)")


_NAMED_ENTITY = re.compile(r"&([A-Za-z][A-Za-z0-9]*);")


def _numeric_entity(m) -> str:
    name = m.group(1)
    if name in ("amp", "lt", "gt", "quot", "apos"):
        return m.group(0)
    ch = html.entities.html5.get(name + ";")
    return "".join(f"&#x{ord(c):x};" for c in ch) if ch else m.group(0)


def _polish(s: str) -> str:
    """A true minus sign, a thin space between a factor and a function name (l cos θ), and numeric
    character references for sympy's named entities (&InvisibleTimes;), so the markup is also XML."""
    s = s.replace("<mo>-</mo>", "<mo>\u2212</mo>")
    s = _FUNCTION_AFTER_PRODUCT.sub(r'\1<mspace width="0.17em"></mspace>\2', s)
    return _NAMED_ENTITY.sub(_numeric_entity, s)


def _mathml_inner(obj) -> str:
    if isinstance(obj, str):
        return f"<mtext>{_escape(obj)}</mtext>"
    if isinstance(obj, Vector):
        return _polish(_MATHML._print_Vector(obj).toxml())
    if isinstance(obj, Dyadic):
        return _polish(_MATHML._print_Dyadic(obj).toxml())
    return _polish(_MATHML.doprint(sp.sympify(obj)))


def _escape(s: str) -> str:
    return s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def mathml(obj, display: bool = False) -> str:
    """A ``<math>`` element for an expression, vector, dyadic, or an equation ``(lhs, rhs)``."""
    if isinstance(obj, tuple) and len(obj) == 2:
        inner = f"<mrow>{_mathml_inner(obj[0])}<mo>=</mo>{_mathml_inner(obj[1])}</mrow>"
    else:
        inner = _mathml_inner(obj)
    attrs = ' display="block"' if display else ""
    return f'<math xmlns="http://www.w3.org/1998/Math/MathML"{attrs}>{inner}</math>'


def mathml_condition(expr, relation: str) -> str:
    """``expr relation 0`` as MathML (a regime's or a validity condition)."""
    inner = f"<mrow>{_mathml_inner(expr)}<mo>{_escape(_RELATIONS[relation])}</mo><mn>0</mn></mrow>"
    return f'<math xmlns="http://www.w3.org/1998/Math/MathML">{inner}</math>'


# LaTeX ---------------------------------------------------------------------------------------------
def _latex_name_piece(s: str) -> str:
    return "".join(_LATEX_GREEK.get(ch, ch) for ch in s)


_PLAIN_NAME = re.compile(r"\w+")


def _plain(name: str) -> bool:
    """A name sympy's LaTeX printer may print itself: letters (any script), digits and ``_`` only."""
    return _PLAIN_NAME.fullmatch(name) is not None


class LatexPrinter(VectorLatexPrinter):
    """sympy's vector LaTeX printer (dots for rates) with the user's basis names and labels.

    A name that is not plain (:func:`_plain`) is never handed to sympy, which would copy it into the
    LaTeX as it is (``\\input``, ``\\write18``): it is shown as escaped text instead.
    """

    def _symbol(self, name: str) -> str:
        return super()._print_Symbol(sp.Symbol(name)) if _plain(name) else rf"\text{{{_latex_text(name)}}}"

    def _print_Symbol(self, expr, style="plain"):
        head, sep, suffix = expr.name.rpartition("_")
        if sep and head and suffix in ACCENT_SUFFIXES:
            return rf"\{suffix}{{{self._print_Symbol(sp.Symbol(head))}}}"
        text, symbol = split_label(expr.name)
        if not text:
            return self._symbol(expr.name)
        after = ""
        if "\0" in symbol:
            symbol, after = symbol.split("\0")
        out = rf"\text{{{_latex_text(text)}}}"
        if symbol:
            out += r"\ " + self._symbol(symbol)
        if after:
            out += rf"\ \text{{{_latex_text(after)}}}"
        return out

    _print_Dummy = _print_Symbol

    def _print_Function(self, expr, exp=None):
        if isinstance(expr.func, sp.core.function.UndefinedFunction) and not _plain(expr.func.__name__):
            name = rf"\text{{{_latex_text(expr.func.__name__)}}}"
            if expr.args != (t,):
                name += r"\left(" + ", ".join(self._print(a) for a in expr.args) + r"\right)"
            return f"{name}^{{{exp}}}" if exp else name
        return super()._print_Function(expr, exp)

    def _print_Derivative(self, der_expr):
        f = der_expr.expr
        if _is_rate(der_expr) and not _plain(f.func.__name__):
            order = sum(c for _, c in der_expr.variable_count)
            name = rf"\text{{{_latex_text(f.func.__name__)}}}"
            return {1: rf"\dot{{{name}}}", 2: rf"\ddot{{{name}}}"}.get(order, rf"{name}^{{({order})}}")
        return super()._print_Derivative(der_expr)

    def basis(self, frame, i) -> str:
        name = _basis_name(frame, i)
        if not _plain(name):
            return rf"\mathbf{{\text{{{_latex_text(name)}}}}}"
        head, sub = basis_parts(name)
        sub = ",".join(_latex_name_piece(p) if p in _LATEX_GREEK or len(p) == 1 else rf"\mathrm{{{p}}}"
                       for p in sub.split(",")) if sub else ""
        return rf"\mathbf{{{head}}}_{{{sub}}}" if sub else rf"\mathbf{{{head}}}"

    def _terms(self, items) -> str:
        out = []
        for k, (comp, basis) in enumerate(items):
            neg = comp.could_extract_minus_sign()
            if neg:
                comp = -comp
            sign = "- " if neg else ("+ " if k else "")
            if comp == 1:
                out.append(f"{sign}{basis}")
            else:
                c = self._print(comp)
                if comp.is_Add:
                    c = rf"\left({c}\right)"
                out.append(f"{sign}{c}\\,{basis}")
        return " ".join(out) if out else "0"

    def _print_Mul(self, expr):
        """m g, m l² (report.products): the masses first."""
        numer, denom = sp.fraction(expr)
        if denom != 1 and masses_first(-numer if numer.could_extract_minus_sign() else numer) is not None:
            if expr.could_extract_minus_sign():
                return "- " + self._print(-expr)
            return rf"\frac{{{self._print(numer)}}}{{{self._print(denom)}}}"
        ordered = masses_first(expr)
        if ordered is None:
            return super()._print_Mul(expr)
        coeff, factors = ordered
        head = ("- " if coeff < 0 else "") + (f"{self._print(abs(coeff))} " if abs(coeff) != 1 else "")
        return head + " ".join(self.parenthesize(f, PRECEDENCE["Mul"]) for f in factors)

    def _print_Vector(self, v):
        return self._terms([(c, self.basis(f, i)) for c, f, i in _vector_terms(v)])

    def _print_Dyadic(self, d):
        return self._terms([(c, rf"{self.basis(*a)}\otimes {self.basis(*b)}") for c, a, b in _dyadic_terms(d)])


_LATEX = LatexPrinter()


def _latex_text(s: str) -> str:
    """Text for ``\\text{...}``: every character with a meaning to TeX escaped, Greek letters as math."""
    s = tex_text(s)
    for ch, cmd in _LATEX_GREEK.items():
        s = s.replace(ch, f"${cmd}$")
    return s


def latex_text(s: str) -> str:
    """Plain text (a title, a reason) for a TeX document: TeX's specials escaped, Unicode made TeX (ASCII out)."""
    s = _latex_text(s)
    repl = {"≥": r"$\geq$", "≤": r"$\leq$", "×": r"$\times$", "·": r"$\cdot$", "−": "-", "→": r"$\to$",
            "⊗": r"$\otimes$", "°": r"$^\circ$", "≈": r"$\approx$",
            "\u0307": "", "\u0308": "", "\u0302": "", "–": "--", "—": "---", "…": r"\ldots{}"}
    for k, v in repl.items():
        s = s.replace(k, v)
    # a run of superscripts (Ω⁴, s⁻¹) or subscripts (y₁₂) as one TeX script: NFKD would print Ω⁴ as Ω4
    s = _SUPERSCRIPTS.sub(lambda mt: "$^{" + mt.group(0).translate(_SCRIPT_DIGITS) + "}$", s)
    s = _SUBSCRIPTS.sub(lambda mt: "$_{" + mt.group(0).translate(_SCRIPT_DIGITS) + "}$", s)
    return _ascii(s)


_SUPERSCRIPTS = re.compile("[⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻]+")
_SUBSCRIPTS = re.compile("[₀₁₂₃₄₅₆₇₈₉₊₋]+")
_SCRIPT_DIGITS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻₀₁₂₃₄₅₆₇₈₉₊₋", "0123456789+-0123456789+-")


def _ascii(s: str) -> str:
    """Accents dropped and any other non-ASCII character shown as '?', so that any TeX engine reads it."""
    s = unicodedata.normalize("NFKD", s)
    return "".join(ch if ord(ch) < 128 else "?" for ch in s if not unicodedata.combining(ch))


def _latex_unicode(s: str) -> str:
    """Greek letters that came into math as Unicode (a symbol named ``ω_rod``) as TeX commands."""
    for ch, cmd in _LATEX_GREEK.items():
        s = s.replace(ch, "{" + cmd + "}")
    return _ascii(s)


def latex(obj) -> str:
    """LaTeX (no delimiters) of an expression, vector, dyadic, or an equation ``(lhs, rhs)``."""
    if isinstance(obj, tuple) and len(obj) == 2:
        return f"{latex(obj[0])} = {latex(obj[1])}"
    if isinstance(obj, str):
        return rf"\text{{{latex_text(obj)}}}"
    if isinstance(obj, Vector):
        return _latex_unicode(_LATEX._print_Vector(obj))
    if isinstance(obj, Dyadic):
        return _latex_unicode(_LATEX._print_Dyadic(obj))
    return _latex_unicode(_LATEX.doprint(sp.sympify(obj)))


def latex_condition(expr, relation: str) -> str:
    return f"{latex(expr)} {_LATEX_RELATIONS[relation]} 0"
