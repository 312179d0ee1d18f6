"""Quantities with units inside the expressions of a problem file: ``radius = "10 cm"``, ``"l/2 + 5 cm"``.

A quantity is a number followed by a unit: ``5 cm``, ``2 ft``, ``500 g``, ``30 deg``, ``3 m^2``.  Inside
an expression the unit is one unit name (with an optional power); a compound unit goes in parentheses
right after the number (``"v0 + 2 (m/s)"``); a field that is one quantity alone takes any unit
(``g = "9.81 m/s^2"``).  Units are read by the unit grammar of :mod:`rigidkin.base.units` (pint).

Each quantity is read as a placeholder symbol of its unit's dimension, so the expression's dimension
can be checked (``"l/2 + 5 kg"`` is refused, and so is a mass in a length field), and is then replaced
by its exact value in SI units (``30 deg`` is π/6, ``2 ft`` is 381/625 m).  Nothing is evaluated by
Python: the rest of the text goes to the restricted parser of :mod:`rigidkin.io.expressions`.

>>> from rigidkin.io.expressions import default_scope
>>> text, literals = split("l/2 + 5 cm", default_scope().with_names({"l": sp.Symbol("l")}))
>>> text, [(q.text, q.si) for q in literals]
('l/2 + Q0  ', [('5 cm', 1/20)])
>>> unit_factor("deg")[0], unit_factor("ft")[0]
(pi/180, 381/1250)
"""

from __future__ import annotations

import keyword
import re
from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from ..base.errors import InputError
from ..base.units import Dimension, parse_quantity, registry, unit_dimension
from ..model.values import exact_decimal
from .expressions import _snippet
from .language import MAX_LENGTH

#: the most quantities with units in one expression
MAX_QUANTITIES = 100

_NUMBER = r"(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
#: a number not inside a name (x2) or another number, then optional spaces and what may be a unit
_START = re.compile(rf"(?<![\w.])(?P<num>{_NUMBER})(?P<gap>\s*)(?=[A-Za-z_µμ°Ω(])")
_NAME = re.compile(r"[A-Za-z_µμ°Ω][A-Za-z0-9_]*")
_POWER = re.compile(r"\s*(?:\^|\*\*)\s*-?\d+")
_WHOLE = re.compile(rf"\s*[-+]?\s*{_NUMBER}\s*[A-Za-z_µμ°Ω(].*", re.S)
_HINT = ("Write a quantity as a number and a unit: \"10 cm\", \"30 deg\", \"l/2 + 5 cm\"; inside an expression a "
         "compound unit goes in parentheses: \"v0 + 2 (m/s)\".")


@dataclass(frozen=True)
class Literal:
    """One quantity of an expression: its text, the placeholder standing for it, its dimension and SI value."""

    text: str
    symbol: sp.Symbol
    dimension: Dimension
    si: sp.Expr


@lru_cache(maxsize=256)
def unit_factor(unit: str) -> tuple[sp.Expr, Dimension]:
    """The exact SI value of one ``unit`` (``deg`` → π/180, ``ft`` → 381/1250) and its dimension."""
    dim = unit_dimension(unit)
    f = parse_quantity(f"1 {unit}")
    for guess in (sp.nsimplify(f, rational=True), sp.nsimplify(f / sp.pi.evalf(17), rational=True) * sp.pi):
        if len(str(guess)) <= 24 and abs(float(guess) - f) <= 1e-14 * abs(f):
            return guess, dim
    return exact_decimal(f"{f:.17g}"), dim


def _is_unit(name: str) -> bool:
    try:
        return bool(registry().parse_unit_name(name.replace("μ", "µ")))
    except Exception:          # pint: not a unit name
        return False


def _placeholders(taken):
    for a in "QZYXWVU":
        for b in "0123456789abcdefghijklmnopqrstuvwxyz":
            name = a + b
            if name not in taken and not keyword.iskeyword(name):
                yield name


def split(text, scope, where: str | None = None):
    """``text`` with each quantity replaced by a placeholder name of at most its length (columns kept), and
    the :class:`Literal` of each; ``(text, [])`` when it has none."""
    if not isinstance(text, str) or len(text) > MAX_LENGTH or not _START.search(text):
        return text, []                    # (the parser refuses a text too long)
    taken = set(scope.names) | set(scope.vectors) | set(scope.frames) | set(scope.functions) | {"dot", "ddot"}
    names = _placeholders(taken)
    whole = _WHOLE.fullmatch(text)
    out, literals, pos = [], [], 0
    for m in _START.finditer(text):
        if m.start() < pos or re.match(_NUMBER, text[m.start():]).end() != len(m.group("num")):
            continue                       # inside an earlier quantity, or 1e999 read as 1 and a unit 'e999'
        alone = whole and not text[:m.start()].strip("+- \t")
        end, unit = _unit_at(text, m.end(), where, text if alone else None, set(scope.names))
        if unit is None:
            continue
        literal = text[m.start():end]
        factor, dim = unit_factor(unit)
        name = next(names, None)
        if name is None or len(literals) >= MAX_QUANTITIES:
            raise InputError(f"the expression has more than {MAX_QUANTITIES} quantities with units.", where=where,
                             hint="Declare them as parameters with their units.")
        sym = sp.Symbol(name, real=True)
        literals.append(Literal(literal.strip(), sym, dim, exact_decimal(m.group("num")) * factor))
        out.append(text[pos:m.start()] + name.ljust(end - m.start()))
        pos = end
    out.append(text[pos:])
    return "".join(out), literals


def _unit_at(text: str, i: int, where, whole, declared) -> tuple[int, str | None]:
    """Where the unit starting at ``text[i]`` ends, and the unit's text (None: no unit here)."""
    rest = text[i:].strip()
    if whole is not None and not set(_NAME.findall(rest)[1:]) & declared:   # one quantity: any unit (3 m^2/l with
        # a parameter l is 3 m² over l, not over a litre)
        try:
            unit_dimension(rest, where)
            return len(text), rest
        except InputError:
            pass                           # not a unit alone: a quantity inside an expression
    if text[i] == "(":
        depth, j = 0, i
        while j < len(text):
            depth += {"(": 1, ")": -1}.get(text[j], 0)
            if depth == 0:
                break
            j += 1
        inner = text[i + 1:j]
        if not _NAME.match(inner.strip() or "0") or not _is_unit(_NAME.match(inner.strip()).group()):
            return i, None                   # 2 (l + 1): not a unit (the parser says what is wrong)
        unit_dimension(inner, where)
        return j + 1, inner
    m = _NAME.match(text, i)
    name = m.group()
    if not _is_unit(name):
        raise InputError(f"in the expression {text!r}: '{name}' follows a number but is not a unit.", where=where,
                         hint=_HINT + " A product is written with '*': \"2*l\".")
    end = m.end()
    p = _POWER.match(text, end)
    if p:
        end = p.end()
    after = re.match(r"\s*([*/])\s*([A-Za-z_µμ°Ω]\w*)", text[end:])
    if after and after.group(2) not in declared and _is_unit(after.group(2)):
        raise InputError(f"in the expression {text!r}: the unit after {text[i:end].strip()!r} goes on "
                         f"({after.group(1)}{after.group(2)}); a compound unit inside an expression goes in "
                         "parentheses.", where=where, hint=_HINT)
    return end, text[i:end].replace("**", "^")


def read(text, scope, where: str | None, parse):
    """``parse(rewritten, scope_with_placeholders, where)`` and the literals; errors shown on ``text``."""
    rewritten, literals = split(text, scope, where)
    if not literals:
        return parse(text, scope, where), []
    sc = scope.with_names({lit.symbol.name: lit.symbol for lit in literals})
    try:
        value = parse(rewritten, sc, where)
    except InputError as exc:
        message = exc.message.replace(_snippet(rewritten), _snippet(text))
        raise InputError(message, where=exc.where, hint=_HINT + " In a unit, a name declared in the file (m, g, l "
                         "...) after the first unit name is read as that name: write \"3 (kg*m^2)\".") from None
    return value, literals


def to_si(value, literals):
    """``value`` with each placeholder replaced by its quantity's exact SI value."""
    return value.subs({lit.symbol: lit.si for lit in literals}) if literals else value
