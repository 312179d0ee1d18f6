"""The numeric state of a system: every coordinate and every rate, and the parameters' values.

One set of coordinates serves every mode, so a simulation state is always (q_1 … q_n, q̇_1 … q̇_n)
in the order the coordinates were declared.  ``StateLayout`` names the slots (``theta``,
``dot(theta)``) and maps sympy coordinates, rates and parameters to plain symbols for code
generation.  ``parameter_vector`` binds the parameters by value: the system's own values,
overridden by the caller's (numbers are SI; strings carry a unit, ``"30 deg"``).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.errors import InputError
from ..base.units import to_si

t = dynamicsymbols._t

_DOT = re.compile(r"^\s*dot\(\s*([A-Za-z_]\w*)\s*\)\s*$")


def rate_name(name: str) -> str:
    """The name of a coordinate's rate in states, tables and the command line: ``dot(theta)``."""
    return f"dot({name})"


@dataclass(frozen=True)
class StateLayout:
    """Names and plain symbols of the state vector y = (q, q̇) and of the parameter vector p."""

    names: tuple[str, ...]             # coordinate names, in declaration order
    coordinates: tuple                  # q(t)
    parameters: tuple[str, ...]         # parameter names, in declaration order
    parameter_symbols: tuple
    speeds: tuple[str, ...] = ()       # per coordinate: the speed its rate is (a quasi-coordinate's w), or ""

    @classmethod
    def of(cls, system) -> StateLayout:
        info = system.coordinate_info
        params = system.parameter_info
        return cls(tuple(info), tuple(c.symbol for c in info.values()), tuple(params),
                   tuple(p.symbol for p in params.values()),
                   tuple(c.extra.get("speed", "") if c.extra else "" for c in info.values()))

    @property
    def n(self) -> int:
        return len(self.names)

    @property
    def labels(self) -> tuple[str, ...]:
        """``theta, x, dot(theta), dot(x)``: the names of the 2n state slots (a speed by its own name)."""
        sp_ = self.speeds or ("",) * self.n
        return self.names + tuple(w or rate_name(n) for n, w in zip(self.names, sp_))

    def plain_symbols(self) -> tuple[list, list]:
        """Plain symbols for q and q̇ (``q_theta``, ``u_theta``), in layout order."""
        q = [sp.Symbol(f"q_{n}", real=True) for n in self.names]
        u = [sp.Symbol(f"u_{n}", real=True) for n in self.names]
        return q, u

    def to_plain(self, expr):
        """Replace q(t), q̇(t) by the plain symbols (q̈ must not remain)."""
        q, u = self.plain_symbols()
        m = {c.diff(t): ui for c, ui in zip(self.coordinates, u)}
        m.update(dict(zip(self.coordinates, q)))
        return sp.sympify(expr).xreplace(m)

    def arguments(self) -> list:
        """The argument list of every generated function: t, q…, q̇…, parameters…."""
        q, u = self.plain_symbols()
        return [t, *q, *u, *self.parameter_symbols]

    def index(self, name: str) -> int:
        """Slot of ``theta`` or ``dot(theta)`` in y."""
        if self.speeds and name.strip() and name.strip() in self.speeds:
            return self.n + self.speeds.index(name.strip())          # a speed w: the rate of its quasi-coordinate
        m = _DOT.match(name)
        base = m.group(1) if m else name.strip()
        if base not in self.names:
            raise InputError(f"'{name}' is not a coordinate or a rate of this system.",
                             hint=f"Coordinates: {', '.join(self.names)}; rates are written dot(NAME).")
        i = self.names.index(base)
        return i + self.n if m else i

    def as_dict(self, y) -> dict[str, float]:
        return {k: float(v) for k, v in zip(self.labels, y[:2 * self.n])}


def quantity(value, unit: str | None, where: str) -> float:
    """A number (SI) or a string with a unit (``"30 deg"``, ``"2 cm"``; a bare number is SI) → float."""
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return to_si(value, unit or None, where)
    if isinstance(value, sp.Basic):
        if not value.is_number:
            raise InputError(f"{value} is not a number.", where=where)
        value = float(value)
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{value!r} is not a number.", where=where,
                         hint="Give a number (SI units) or a string with a unit such as '30 deg'.") from None
    return v


def _key_name(key) -> str:
    return key if isinstance(key, str) else str(key)


def parameter_vector(system, layout: StateLayout, overrides: Mapping | None = None) -> np.ndarray:
    """Values of all parameters in layout order: the system's values, then ``overrides`` (name or symbol)."""
    info = system.parameter_info
    vals = {name: p.value for name, p in info.items()}
    for key, value in (overrides or {}).items():
        name = _key_name(key)
        if name not in info:
            raise InputError(f"'{name}' is not a parameter of {system.name}.", where="parameters",
                             hint=f"Parameters: {', '.join(info) or 'none'}.")
        vals[name] = quantity(value, info[name].unit, f"parameter {name}")
    missing = [n for n in layout.parameters if vals.get(n) is None]
    if missing:
        raise InputError(f"the parameters {', '.join(missing)} have no value.", where=system.name,
                         hint="Give them values (simulate(..., params={...}) or --set NAME=VALUE).")
    bad = [n for n in layout.parameters if not np.isfinite(vals[n])]
    if bad:
        raise InputError(f"the parameters {', '.join(bad)} are not finite numbers.", where=system.name)
    return np.array([float(vals[n]) for n in layout.parameters], dtype=float)


def initial_values(system, layout: StateLayout, given: Mapping | None = None) -> tuple[dict, dict]:
    """The initial coordinates and rates the user fixed: (index → value given explicitly, index → declared).

    ``given`` maps ``theta`` / ``dot(theta)`` (or q(t) / q̇(t)) to numbers or strings with units.
    Slots neither given nor declared are left to the constraints (or zero).
    """
    explicit = {}
    for key, value in (given or {}).items():
        if isinstance(key, sp.Derivative):
            name = rate_name(key.expr.func.__name__)
        elif isinstance(key, sp.core.function.AppliedUndef):
            name = key.func.__name__
        else:
            name = str(key)
        i = layout.index(name)
        explicit[i] = quantity(value, None, f"initial {name}")
        if not np.isfinite(explicit[i]):
            raise InputError(f"the initial value of {name} is not a finite number.", where=f"initial {name}")
    declared = {}
    for i, c in enumerate(system.coordinate_info.values()):
        if c.initial is not None:
            declared[i] = float(c.initial)
        if c.rate is not None:
            declared[i + layout.n] = float(c.rate)
    return explicit, declared
