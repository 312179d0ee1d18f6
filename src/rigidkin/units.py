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

import pint

from .errors import InputError

_BASES = ("mass", "length", "time", "current", "temperature", "substance", "luminosity")
_SYMBOLS = {"mass": "M", "length": "L", "time": "T", "current": "I", "temperature": "Θ",
            "substance": "N", "luminosity": "J"}


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    """The one unit registry rigidkin uses."""
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


#: pint evaluates powers with Python numbers: a tower such as ``9^9^9`` would never finish.
_MAX_UNIT_TEXT = 100
_POWER = re.compile(r"(\^|\*\*)")
_SMALL_EXPONENT = re.compile(r"\s*[-+]?\d{1,2}(\.\d{1,3})?(?![\d.])(?!\s*(\^|\*\*))")


def _screen(text: str, where: str | None) -> None:
    """Refuse unit and quantity strings that pint could not read in bounded time (long ones, power towers)."""
    bad = None
    if len(text) > _MAX_UNIT_TEXT:
        bad = f"is {len(text)} characters long (at most {_MAX_UNIT_TEXT})"
    else:
        for m in _POWER.finditer(text):
            if not _SMALL_EXPONENT.match(text, m.end()):
                bad = "has a power whose exponent is not a small number (at most two digits, no towers)"
                break
    if bad:
        raise InputError(f"the unit or quantity '{text[:40]}{'...' if len(text) > 40 else ''}' {bad}.", where=where,
                         hint="Write SI-style units such as kg, m, s, N, N/m, m/s^2, rad, deg.")


@lru_cache(maxsize=512)
def unit_dimension(unit: str, where: str | None = None) -> Dimension:
    """The dimension of a unit string such as ``"kg"``, ``"N/m"`` or ``"m/s^2"``."""
    if unit is None or str(unit).strip() in ("", "1", "-"):
        return ONE
    _screen(str(unit), where)
    try:
        q = registry().parse_expression(str(unit))
    except Exception as exc:  # pint raises many kinds; all mean "not a unit"
        raise InputError(f"'{unit}' is not a unit pint understands ({exc}).", where=where,
                         hint="Write SI-style units such as kg, m, s, N, N/m, m/s^2, rad, deg.") from None
    if not hasattr(q, "dimensionality"):
        return ONE
    dims = {k.strip("[]"): v for k, v in dict(q.dimensionality).items()}
    unknown = set(dims) - set(_BASES)
    if unknown:
        raise InputError(f"'{unit}' has dimensions {sorted(unknown)} that rigidkin does not know.",
                         where=where)
    return Dimension(**{k: _clean(v) for k, v in dims.items()})


def to_si(value: float | str, unit: str | None = None, where: str | None = None) -> float:
    """Convert ``value`` (a number in ``unit``, or a string such as ``"30 deg"``) to SI base units."""
    reg = registry()
    for text in (value, unit):
        if isinstance(text, str):
            _screen(text, where)
    try:
        if isinstance(value, str):
            q = reg.Quantity(value)
        else:
            q = reg.Quantity(float(value), unit or "")
        if unit and isinstance(value, str):
            target = reg.parse_expression(unit)
            if q.dimensionality != getattr(target, "dimensionality", {}):
                raise InputError(f"'{value}' is not in units of {unit} (dimension "
                                 f"{q.dimensionality} instead of {target.dimensionality}).", where=where)
        mag = float(q.to_base_units().magnitude)
    except InputError:
        raise
    except Exception as exc:
        raise InputError(f"cannot read the quantity '{value}' ({exc}).", where=where,
                         hint="Write a number, or a number and a unit such as '30 deg' or '2 ft'.") from None
    if not math.isfinite(mag):
        raise InputError(f"the quantity '{value}' is not a finite number.", where=where,
                         hint="Give a finite value, e.g. 9.81 or '30 deg'.")
    return mag
