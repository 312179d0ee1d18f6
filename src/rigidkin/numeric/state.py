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


@dataclass(frozen=True)
class PositionConstraints:
    """The position-level constraints g(t, q, p) = 0 of a mode that a starting state must satisfy: the gaps of
    its bilateral rows (pins, collars, bilateral contacts, loop closures), with their names and the slots of the
    coordinates Newton's method may move (the dependent ones)."""

    labels: tuple[str, ...]
    function: object             # (t, q…, q̇…, p…) → the gaps, in the order of ``labels``
    free: tuple[int, ...]        # coordinate slots that assembly may move

    def residuals(self, t_, y, p, n: int) -> np.ndarray:
        if not self.labels:
            return np.zeros(0)
        return np.asarray(self.function(t_, *np.asarray(y, dtype=float)[:2 * n], *p), dtype=float).ravel()


def assembly_tolerance(y, n: int) -> float:
    """How far from zero a position constraint may be at an assembled start (relative to the coordinates)."""
    return 1e-9 * max(1.0, float(np.max(np.abs(np.asarray(y, dtype=float)[:n]))) if n else 1.0)


def assemble(cons: PositionConstraints, layout: StateLayout, t_, y, p, where: str) -> np.ndarray:
    """The starting state put onto the position constraints by Newton's method from the values given.

    The coordinates in ``cons.free`` (the dependent ones: given, declared or rough) are corrected by a
    Gauss–Newton iteration (scipy's least_squares, exact in the limit) until every gap is within
    :func:`assembly_tolerance`; the independent coordinates stay as given.  A start that cannot be
    assembled is refused (InputError) naming the constraint with the largest residual and its value.
    """
    n = layout.n
    y = np.array(y, dtype=float)
    r0 = cons.residuals(t_, y, p, n)
    if not len(r0):
        return y
    tol = assembly_tolerance(y, n)
    if np.all(np.isfinite(r0)) and np.max(np.abs(r0)) <= tol:
        return y
    free = list(cons.free)
    best = y
    if free and np.all(np.isfinite(r0)):
        from scipy.optimize import least_squares  # here: the state module stays light

        def resid(z):
            yy = y.copy()
            yy[free] = z
            r = cons.residuals(t_, yy, p, n)
            return np.where(np.isfinite(r), r, 1e6)

        for method in ("lm", "trf"):
            if method == "lm" and len(r0) < len(free):
                continue
            try:
                out = least_squares(resid, y[free], method=method, xtol=1e-15, ftol=1e-15, gtol=1e-15,
                                    max_nfev=200 * (len(free) + 1))
            except ValueError:
                continue
            cand = y.copy()
            cand[free] = out.x
            if np.max(np.abs(cons.residuals(t_, cand, p, n))) < np.max(np.abs(cons.residuals(t_, best, p, n))):
                best = cand
            if np.max(np.abs(cons.residuals(t_, best, p, n))) <= assembly_tolerance(best, n):
                return best
    r = cons.residuals(t_, best, p, n)
    r = np.where(np.isfinite(r), r, np.inf)
    i = int(np.argmax(np.abs(r)))
    moved = ", ".join(layout.names[s] for s in free) or "none (every coordinate involved is independent)"
    raise InputError(f"the starting state cannot be assembled onto the position constraints: {cons.labels[i]} "
                     f"keeps a residual of {abs(r[i]):.4g} (it is {abs(r0[i]):.4g} at the values given) after "
                     f"Newton's method from the values given, moving {moved}.", where=where,
                     hint="Give starting values of the coordinates near a configuration the constraints allow "
                          "(and check that the constraint can hold at all: a point held on a line it cannot "
                          "reach has no configuration).")


def assembled_changes(layout: StateLayout, given: Mapping, y) -> dict[str, tuple[float, float]]:
    """The coordinates the assembly moved: name → (value given or declared, assembled value)."""
    out = {}
    for i, v in given.items():
        if i < layout.n and abs(float(y[i]) - float(v)) > 1e-9 * max(1.0, abs(float(v))):
            out[layout.names[i]] = (float(v), float(y[i]))
    return out
