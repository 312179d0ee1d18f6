"""Values typed on the command line for a named quantity (``--initial theta=30 deg``, ``--at``, ``--param``,
``--stop-at theta=1.2``): read with their unit and checked against the dimension of what they name.

A coordinate that is an angle takes an angle (``0.5``, ``30 deg``), a length a length, a rate the
coordinate's dimension per second; a kilogram for an angle, NaN or an infinity is refused in one paragraph
naming the option.  A bare number is SI.  The values come back in SI, as numbers.
"""

from __future__ import annotations

import math

from ..base.errors import InputError
from ..base.units import MAX_MAGNITUDE, parse_quantity, unit_dimension
from ..io.load import value as plain_value

_KIND_UNIT = {"angle": "rad", "length": "m"}


def units_of(system) -> dict[str, str | None]:
    """The SI unit each name of ``system`` takes: coordinates and their rates (``dot(theta)``), parameters
    (their declared unit); None where the dimension is not known (any value is read as SI)."""
    out: dict[str, str | None] = {}
    for name, c in system.coordinate_info.items():
        unit = _KIND_UNIT.get(getattr(c, "kind", None))
        out[name] = unit
        out[f"dot({name})"] = f"{unit}/s" if unit else None
    for name, p in system.parameter_info.items():
        out.setdefault(name, p.unit or None)
    return out


def checked(text: str, unit: str | None, where: str) -> float:
    """``text`` in SI, refused unless it is finite and (with ``unit``) of ``unit``'s dimension."""
    try:
        v = float(text)                          # a bare number: SI, no unit registry loaded
    except (TypeError, ValueError):
        v = None
    if v is not None and math.isfinite(v) and abs(v) <= MAX_MAGNITUDE:
        return v
    if unit is None:
        return plain_value(text, where)      # any dimension: read as SI
    return parse_quantity(text, None, where, dimension=unit_dimension(unit, where))


def checked_values(pairs: dict, units: dict, what: str) -> dict:
    """``{name: text}`` from ``what`` (``--initial``) as ``{name: SI value}``; a name ``units`` does not know
    is passed on unchanged (the simulation names the coordinates it has)."""
    return {name: checked(text, units[name], f"{what} {name}") if name in units else text
            for name, text in pairs.items()}


def checked_events(items: list[str], units: dict, what: str) -> list[str]:
    """``--stop-at`` / ``--record`` events: ``NAME=VALUE`` has its value checked (and written in SI); a
    reaction's name (``N_A``) is passed on."""
    out = []
    for item in items:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep:
            out.append(item)
            continue
        if not text.strip():
            raise InputError(f"'{item}' has no value.", where=what, hint="Write NAME=VALUE, e.g. theta=1.2.")
        v = checked(text.strip(), units.get(name), f"{what} {name}")
        out.append(f"{name}={v!r}")
    return out
