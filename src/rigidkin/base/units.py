"""Physical dimensions and unit conversion, on pint (no hand-written table of units).

A dimension is a ``Dimension``: exponents of mass, length and time (and of current, temperature,
amount and luminosity, which kinetics rarely needs).  Angles are dimensionless, as in SI.  pint
parses unit strings with its own tokenizer and evaluator; nothing here calls ``eval``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache

from .errors import InputError
from .unit_cache import staged

_BASES = ("mass", "length", "time", "current", "temperature", "substance", "luminosity")
_SYMBOLS = {"mass": "M", "length": "L", "time": "T", "current": "I", "temperature": "Θ",
            "substance": "N", "luminosity": "J"}


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:  # noqa: F821
    """The one unit registry rigidkin uses (pint imported here: it is slow to import and most commands
    run from the derivation cache never read a unit).

    pint looks for dask when it is imported (0.35 s where dask is installed, for sweeps on a cluster);
    rigidkin gives pint no dask arrays, so pint is imported as if dask were absent.  pint's parsed
    definitions are kept, signed, in the cache folder (:mod:`rigidkin.base.unit_cache`; 0.4 s less for
    the next command)."""
    import sys

    absent = "dask" not in sys.modules
    if absent:
        sys.modules["dask"] = None          # an ImportError for pint's probe only
    try:
        import pint
    finally:
        if absent and sys.modules.get("dask", 0) is None:
            del sys.modules["dask"]
    with staged() as folder:                # pint's definitions, verified under the per-user key (unit_cache)
        if folder is not None:
            try:
                return pint.UnitRegistry(cache_folder=folder)
            except Exception:               # a cache that cannot be used: parse the definitions afresh
                pass
    return pint.UnitRegistry()


@dataclass(frozen=True)
class Dimension:
    """Exponents of the SI base dimensions; ``Dimension()`` is dimensionless."""

    mass: float = 0
    length: float = 0
    time: float = 0
    current: float = 0
    temperature: float = 0
    substance: float = 0
    luminosity: float = 0

    def _vec(self):
        return tuple(getattr(self, b) for b in _BASES)

    @classmethod
    def _from(cls, vec) -> Dimension:
        return cls(*[_clean(v) for v in vec])

    def __mul__(self, other: Dimension) -> Dimension:
        return Dimension._from(a + b for a, b in zip(self._vec(), other._vec()))

    def __truediv__(self, other: Dimension) -> Dimension:
        return Dimension._from(a - b for a, b in zip(self._vec(), other._vec()))

    def __pow__(self, p: float) -> Dimension:
        return Dimension._from(a * p for a in self._vec())

    @property
    def is_dimensionless(self) -> bool:
        return all(v == 0 for v in self._vec())

    def __str__(self) -> str:
        parts = []
        for b, v in zip(_BASES, self._vec()):
            if v == 0:
                continue
            sym = _SYMBOLS[b]
            parts.append(sym if v == 1 else f"{sym}^{_fmt(v)}")
        return "·".join(parts) if parts else "1"


def _clean(v: float) -> float:
    r = round(v)
    return int(r) if abs(v - r) < 1e-12 else v


def _fmt(v: float) -> str:
    return str(int(v)) if float(v).is_integer() else f"{v:g}"


MASS = Dimension(mass=1)
LENGTH = Dimension(length=1)
TIME = Dimension(time=1)
ONE = Dimension()

#: Named dimensions accepted where a unit is not given.
NAMED = {
    "mass": MASS,
    "length": LENGTH,
    "time": TIME,
    "angle": ONE,
    "dimensionless": ONE,
    "acceleration": LENGTH / TIME**2,
    "velocity": LENGTH / TIME,
    "speed": LENGTH / TIME,
    "angular velocity": ONE / TIME,
    "force": MASS * LENGTH / TIME**2,
    "torque": MASS * LENGTH**2 / TIME**2,
    "moment": MASS * LENGTH**2 / TIME**2,
    "energy": MASS * LENGTH**2 / TIME**2,
    "impulse": MASS * LENGTH / TIME,
    "stiffness": MASS / TIME**2,
    "torsional stiffness": MASS * LENGTH**2 / TIME**2,
    "damping": MASS / TIME,
    "moment of inertia": MASS * LENGTH**2,
}


#: pint evaluates what it reads with Python numbers and its own tokenizer: a tower such as ``9^9^9`` or a
#: long product would never finish.  Unit and quantity strings are therefore read first by the small
#: grammar below, and pint sees only the text the grammar rebuilt from its tokens.
MAX_UNIT_TEXT = 100        # characters of a unit or quantity string
MAX_POWER = 12             # |n| in m^n
MAX_UNIT_PARENS = 3        # nested parentheses in a unit
MAX_UNIT_FACTORS = 12      # unit names in one unit expression
MAX_MAGNITUDE = 1e40       # |value| in SI units
_UNIT_HINT = "Write SI-style units such as kg, m, s, N, N/m, m/s^2, kg*m^2, rad, deg (powers: small integers)."
_QTY_HINT = ("Write a number, or a number and a unit such as '30 deg', '2 ft' or '9.81 m/s^2' (units: names, *, /, "
             "^ or ** with a small integer, parentheses).")
_TOKEN = re.compile(r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)|(?P<name>[A-Za-z_µμ°Ω][A-Za-z0-9_]*)"
                    r"|(?P<op>\*\*|\^|\*|/|\(|\)|-|\+))")


class _UnitText:
    """A unit or quantity string read token by token: ``[sign] [number] [unit]``, where a unit is
    names from pint's registry joined by ``*``, ``/`` or a space, ``^``/``**`` with a small integer and
    parentheses.  ``rebuilt`` is the same text from the accepted tokens only."""

    def __init__(self, text: str, where: str | None, quantity: bool):
        self.text, self.where, self.quantity = text, where, quantity
        self.tokens: list[tuple[str, str]] = []
        pos = 0
        stripped = text.rstrip()
        while pos < len(stripped):
            m = _TOKEN.match(stripped, pos)
            if not m or m.end() == pos:
                bad = stripped[pos:].lstrip()[:1]
                self.fail(f"the character {bad!r} is not allowed")
            kind = m.lastgroup
            self.tokens.append((kind, m.group(kind)))
            pos = m.end()
        self.i, self.out, self.names, self.parens = 0, [], 0, 0

    def fail(self, why: str):
        shown = self.text if len(self.text) <= 40 else self.text[:37] + "..."
        what = "quantity" if self.quantity else "unit"
        raise InputError(f"the {what} {shown!r} cannot be read: {why}.", where=self.where,
                         hint=_QTY_HINT if self.quantity else _UNIT_HINT)

    def peek(self) -> tuple[str, str]:
        return self.tokens[self.i] if self.i < len(self.tokens) else ("end", "")

    def take(self) -> tuple[str, str]:
        tok = self.peek()
        self.i += 1
        return tok

    def read(self) -> str:
        if self.quantity:
            if self.peek() in (("op", "-"), ("op", "+")):
                self.out.append(self.take()[1])
            if self.peek()[0] == "num":
                num = self.take()[1]
                if len(num) > 30:
                    self.fail("the number has more than 30 characters")
                self.out.append(num)
                if self.peek()[0] == "end":
                    return " ".join(self.out)
            elif self.out:
                self.fail("a sign must be followed by a number")
        if self.peek()[0] == "num" and self.peek()[1] == "1" and self.tokens[self.i + 1:self.i + 2] == [("op", "/")]:
            self.out.append(self.take()[1])          # 1/s
        if self.peek() == ("op", "/") and self.out:
            self.out.append(self.take()[1])          # 2 /s
        self.product()
        if self.peek()[0] != "end":
            self.fail(f"unexpected {self.peek()[1]!r}")
        return " ".join(self.out)

    def product(self) -> None:
        self.factor()
        while True:
            kind, tok = self.peek()
            if tok in ("*", "/"):
                self.out.append(self.take()[1])
                self.factor()
            elif kind == "name" or tok == "(":
                self.out.append("*")
                self.factor()
            else:
                return

    def factor(self) -> None:
        kind, tok = self.take()
        if tok == "(":
            self.parens += 1
            if self.parens > MAX_UNIT_PARENS:
                self.fail(f"parentheses are nested more than {MAX_UNIT_PARENS} deep")
            self.out.append("(")
            self.product()
            if self.take()[1] != ")":
                self.fail("a parenthesis is not closed")
            self.out.append(")")
            self.parens -= 1
        elif kind == "name":
            self.names += 1
            if self.names > MAX_UNIT_FACTORS:
                self.fail(f"it has more than {MAX_UNIT_FACTORS} unit names")
            name = "deg" if tok == "°" else tok.replace("μ", "µ")
            if len(name) > 40 or not registry().parse_unit_name(name):
                self.fail(f"'{tok}' is not a unit")
            self.out.append(name)
        else:
            self.fail(f"expected a unit name, not {tok!r}" if tok else "a unit name is missing")
        if self.peek()[1] in ("^", "**"):
            self.take()
            sign = self.take()[1] if self.peek()[1] in ("-", "+") else ""
            kind, tok = self.take()
            if kind != "num" or not tok.isdigit() or int(tok) > MAX_POWER:
                self.fail(f"a power must be a whole number of magnitude at most {MAX_POWER}")
            if self.peek()[1] in ("^", "**"):
                self.fail("powers of powers (towers) are not allowed")
            self.out.append(f"**{'-' if sign == '-' else ''}{tok}")


def _screen(text: str, where: str | None, quantity: bool = False) -> str:
    """The unit or quantity string ``text`` rebuilt from the tokens of the grammar (refused if it does not fit)."""
    if not isinstance(text, str):
        raise InputError(f"expected a {'quantity' if quantity else 'unit'} string, not {type(text).__name__}.",
                         where=where)
    if len(text) > MAX_UNIT_TEXT:
        raise InputError(f"the {'quantity' if quantity else 'unit'} string is {len(text)} characters long (at most "
                         f"{MAX_UNIT_TEXT}).", where=where, hint=_QTY_HINT if quantity else _UNIT_HINT)
    return _UnitText(text, where, quantity).read().replace(" **", "**")


def _shown(value) -> str:
    text = str(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _dimension(q, text: str, where: str | None) -> Dimension:
    if not hasattr(q, "dimensionality"):
        return ONE
    dims = {k.strip("[]"): v for k, v in dict(q.dimensionality).items()}
    unknown = set(dims) - set(_BASES)
    if unknown:
        raise InputError(f"'{text}' has dimensions {sorted(unknown)} that rigidkin does not know.", where=where,
                         hint=_UNIT_HINT)
    return Dimension(**{k: _clean(v) for k, v in dims.items()})


@lru_cache(maxsize=512)
def unit_dimension(unit: str, where: str | None = None) -> Dimension:
    """The dimension of a unit string such as ``"kg"``, ``"N/m"`` or ``"m/s^2"`` (read by the unit grammar)."""
    if unit is None or str(unit).strip() in ("", "1", "-"):
        return ONE
    rebuilt = _screen(unit, where)
    try:
        q = registry().parse_expression(rebuilt)
    except Exception as exc:  # pint raises many kinds; all mean "not a unit"
        raise InputError(f"'{unit}' is not a unit pint understands ({type(exc).__name__}).", where=where,
                         hint=_UNIT_HINT) from None
    return _dimension(q, unit, where)


def parse_quantity(value: float | int | str, unit: str | None = None, where: str | None = None,
                   dimension: Dimension | None = None) -> float:
    """The magnitude in SI base units of a quantity: the one reader of values with units.

    ``value`` is a number (in ``unit`` if given, else in SI) or a string read by the unit grammar:
    ``"9.81"``, ``"30 deg"``, ``"2 ft"``, ``"-0.5 m/s^2"``.  With ``unit`` a string value must have the
    unit's dimension; with ``dimension`` (an angle is ``ONE``, a length ``LENGTH`` ...) the value must
    have that dimension (a bare number is taken as already in it).  The result is finite; anything
    else is refused with an :class:`~rigidkin.base.errors.InputError` naming ``where``.  Command-line values
    (``--set m=2kg``, ``--initial theta=30deg``) are read here too.

    >>> parse_quantity("500 g"), parse_quantity(5, "cm"), parse_quantity("30 deg", dimension=ONE)
    (0.5, 0.05, 0.5235987755982988)
    >>> parse_quantity("2 kg", dimension=LENGTH)
    Traceback (most recent call last):
    ...
    rigidkin.base.errors.InputError: '2 kg' has dimension M, where length (L) is expected. Give a value in ...
    """
    reg = registry()
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        raise InputError(f"expected a number or a quantity string such as '30 deg', not {type(value).__name__}.",
                         where=where, hint=_QTY_HINT)
    if isinstance(value, str) and value.strip().lower().lstrip("+-") in ("nan", "inf", "infinity"):
        raise InputError(f"the quantity '{_shown(value)}' is not a finite number.", where=where,
                         hint="Give a finite value, e.g. 9.81 or '30 deg'.")
    unit_text = None if unit is None or str(unit).strip() in ("", "1", "-") else _screen(unit, where)
    target = None if unit_text is None else unit_dimension(unit, where)
    try:
        if isinstance(value, str):
            q = reg.Quantity(_screen(value, where, quantity=True))
            has_unit = not q.unitless
            if unit_text is not None:
                if has_unit and _dimension(q, value, where) != target:
                    raise InputError(f"'{_shown(value)}' is not in units of {unit} (dimension "
                                     f"{_dimension(q, value, where)} instead of {target}).", where=where,
                                     hint=f"Give the value in {unit} or an equivalent unit.")
                if not has_unit:
                    q = reg.Quantity(float(q.magnitude), reg.parse_expression(unit_text).units)
        else:
            q = reg.Quantity(float(value)) if unit_text is None else \
                reg.Quantity(float(value), reg.parse_expression(unit_text).units)
        if dimension is not None and (isinstance(value, str) and not q.unitless or unit_text is not None):
            got = _dimension(q, value, where)
            if got != dimension and not (got.is_dimensionless and dimension.is_dimensionless):
                given = f" {unit}" if unit_text and not isinstance(value, str) else ""
                raise InputError(f"'{_shown(value)}'{given} has "
                                 f"dimension {got}, where {_dimension_name(dimension)} is expected.", where=where,
                                 hint=f"Give a value in a unit of {_dimension_name(dimension)} (or a plain number in "
                                      "SI units).")
        mag = float(q.to_base_units().magnitude)
    except InputError:
        raise
    except Exception as exc:
        raise InputError(f"cannot read the quantity '{_shown(value)}' ({type(exc).__name__}).", where=where,
                         hint=_QTY_HINT) from None
    if not math.isfinite(mag):
        raise InputError(f"the quantity '{_shown(value)}' is not a finite number.", where=where,
                         hint="Give a finite value, e.g. 9.81 or '30 deg'.")
    if abs(mag) > MAX_MAGNITUDE:
        raise InputError(f"the quantity '{_shown(value)}' is too large ({mag:.3g} in SI units, at most "
                         f"{MAX_MAGNITUDE:.0e}).", where=where, hint="Give a value of a physical size in SI units.")
    return mag


def _dimension_name(dim: Dimension) -> str:
    for name, d in NAMED.items():
        if d == dim and name != "dimensionless":
            return f"{name} ({dim})"
    return str(dim)


def to_si(value: float | str, unit: str | None = None, where: str | None = None,
          dimension: Dimension | None = None) -> float:
    """Convert ``value`` (a number in ``unit``, or a string such as ``"30 deg"``) to SI base units
    (see :func:`parse_quantity`)."""
    return parse_quantity(value, unit, where, dimension)


# showing values ----------------------------------------------------------------------------------
_SI_NAMES = (("mass", "kg"), ("length", "m"), ("time", "s"), ("current", "A"), ("temperature", "K"),
             ("substance", "mol"), ("luminosity", "cd"))


def _declared(unit: str | None) -> str | None:
    """``unit`` when it names a unit; None for a plain number (``None``, ``""``, ``"1"``, ``"-"``)."""
    return None if unit is None or str(unit).strip() in ("", "1", "-") else str(unit).strip()


def si_unit(dimension: Dimension) -> str:
    """The SI unit of a dimension, written as a unit string rigidkin reads back: ``kg*m/s^2``, ``1/s``; ``""``
    for a dimensionless quantity."""
    up, down = [], []
    for base, name in _SI_NAMES:
        v = getattr(dimension, base)
        if v == 0:
            continue
        power = f"^{_fmt(abs(v))}" if abs(v) != 1 else ""
        (up if v > 0 else down).append(name + power)
    if not up and not down:
        return ""
    top = "*".join(up) or "1"
    if not down:
        return top
    return f"{top}/{down[0]}" if len(down) == 1 else f"{top}/({'*'.join(down)})"


def from_si(value: float | None, unit: str | None) -> float | None:
    """The magnitude in ``unit`` of a value held in SI base units: the inverse of :func:`parse_quantity`
    (``from_si(2.0, "cm")`` is 200, ``from_si(pi/6, "deg")`` is 30).  A plain number's unit (None, ``""``,
    ``"1"``) leaves the value as it is."""
    if value is None or _declared(unit) is None:
        return value
    units = _units_of(_declared(unit))
    reg = registry()
    base = reg.Quantity(1.0, units).to_base_units().units
    return float(reg.Quantity(value, base).to(units).magnitude)


@lru_cache(maxsize=256)
def _units_of(unit: str):
    return registry().parse_expression(_screen(unit, None)).units


def shown_unit(unit: str | None, dimension: Dimension) -> str:
    """The unit a value is shown in: the one it was declared in, else the SI unit of its dimension."""
    return _declared(unit) or si_unit(dimension)


def shown_value(value: float | None, unit: str | None, dimension: Dimension, digits: int = 6) -> str:
    """A value held in SI, as text in the unit it was declared in (``"200 cm"``) or, with no unit, in SI
    with the SI unit (``"2 m"``); ``"—"`` for no value."""
    if value is None:
        return "—"
    shown = _declared(unit)
    number = from_si(value, shown) if shown else value
    text = f"{number:.{digits}g}"
    u = shown or si_unit(dimension)
    return f"{text} {u}" if u else text
