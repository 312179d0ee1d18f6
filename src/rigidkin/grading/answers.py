"""Grading an answer against the quantity the question asks, in the unit the student gives.

An answer of the engine may hold several quantities: an event's configuration (every coordinate) and
its rates, an equilibrium's position, natural frequency and stability, the rates after an impulse.
Each is a :class:`Quantity` with its symbol, words, kind and dimension.  A step names the one it answers
(``quantity = "phi"``, or a claim ``"phi = acos(10/17)"``); a step that names none answers the
question's *asked* quantities (an event: where it happens, any coordinate of that configuration; an
equilibrium: the position), and its dimension picks among them (``sqrt(K/m)`` is a frequency).
A number with a unit is checked dimensionally (``0.8411 kg`` is no angle); a bare number is read in SI
(radians for an angle), and one that is right only in degrees is refused as ambiguous.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..analysis.answers import numeric_values_from
from ..base.dimensions import dimension_of, symbol_dimensions
from ..base.errors import InputError, RigidkinError
from ..base.printing import text
from ..base.units import ONE, TIME, parse_quantity, unit_dimension
from ..io.expressions import parse_scalar
from . import space
from .claims import Unreadable
from .engine import Reference
from .verdicts import CORRECT, INCORRECT, StepResult
from .worksheet import Step

t = dynamicsymbols._t
ANSWER_RTOL = 5e-3
_NUM_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z°/^*0-9. ]*?)\s*$")
_FREQ = ("omega_n", "frequency", "natural_frequency", "wn")
_STAB = ("stability", "stable")


@dataclass
class Quantity:
    """One quantity an answer states."""

    symbol: str                 # as printed (φ, φ̇, ω_n, N)
    names: tuple                # what a worksheet may call it (phi, dot(phi), frequency ...)
    value: object               # a sympy expression, or a word (stability)
    kind: str                   # position | rate | frequency | stability | time | reaction | value
    dimension: object = None
    words: str = ""
    asked: bool = True          # part of what the question asks when a step names no quantity
    coordinate: object = None   # the coordinate q(t) of a position

    def describe(self) -> str:
        return f"{self.symbol} ({self.words})" if self.words else self.symbol

    @property
    def unit(self) -> str:
        """The SI unit the quantity is given in."""
        if self.dimension is None:
            return ""
        if self.dimension == ONE:
            return "rad" if self.kind == "position" else ("rad/s" if self.kind == "frequency" else "")
        if self.dimension == ONE / TIME:
            return "rad/s"
        return _si(self.dimension)


def quantities(ref: Reference, question: str) -> list[Quantity]:
    """The quantities the engine's answer to ``question`` states (empty when it could not answer)."""
    key = ("quantities", question)
    if key in ref._rows:
        return ref._rows[key]
    a = ref.answers().get(question)
    out: list[Quantity] = []
    if a is not None and not isinstance(a, Exception) and a.value is not None:
        out = answer_quantities(ref.system, a, ref.setup)
    ref._rows[key] = out
    return out


def _coord(system, q):
    for c in system.coordinate_info.values():
        if c.symbol == q:
            return c
    return None


def _position(system, q, v, asked=True) -> Quantity:
    c = _coord(system, q)
    name = c.name if c else text(q)
    return Quantity(text(q), (name,), sp.sympify(v), "position", c.dimension if c else None,
                    c.sense if c else "", asked, q)


def _rate(system, d, v, asked) -> Quantity:
    c = _coord(system, d.expr)
    name = c.name if c else text(d.expr)
    dim = (c.dimension / TIME) if c else None
    return Quantity(text(d), (f"dot({name})", f"{name}_dot", f"d{name}"), sp.sympify(v), "rate", dim,
                    f"the rate of {c.sense}" if c and c.sense else "", asked)


def answer_quantities(system, a, setup=None) -> list[Quantity]:
    """Every quantity an Answer states, with its symbol, words, kind and dimension."""
    kind, v, det = a.question.kind, a.value, a.details or {}
    out = []

    def dim(e):
        return _dim(system, setup, e)

    if v is None:
        return out
    if kind == "event":
        for q, x in (det.get("configuration") or {}).items():
            out.append(_position(system, q, x))
        for d, x in (det.get("end_state") or {}).items():
            if isinstance(d, sp.Derivative):
                out.append(_rate(system, d, x, False))
        if det.get("time") is not None:
            out.append(Quantity("t", ("t", "time"), sp.sympify(det["time"]), "time", TIME, "the time", False))
    elif kind == "extreme":
        c = system.coordinate_info.get(str(a.question.fields.get("coordinate")))
        out.append(_position(system, c.symbol, v) if c is not None else
                   Quantity("value", (), sp.sympify(v), "value", dim(v)))
    elif kind == "equilibrium":
        for k, e in enumerate(v):
            tag = f" of equilibrium {k + 1}" if len(v) > 1 else ""
            for q, x in (e.configuration or {}).items():
                out.append(_position(system, q, x))
            for i, w in enumerate(e.natural_frequencies or ()):
                out.append(Quantity(f"ω_n{i + 1}" if len(e.natural_frequencies) > 1 else "ω_n",
                                    tuple(_FREQ) + (f"omega_n{i + 1}",), sp.sympify(w), "frequency", ONE / TIME,
                                    "the natural frequency" + tag, False))
            out.append(Quantity("stability", tuple(_STAB), str(e.stability), "stability", None, "the stability" + tag,
                                False))
    elif kind == "phases":
        for ph in det.get("phases") or ():
            if not ph.happens:
                continue
            if ph.duration is not None:
                out.append(Quantity(f"Δt({ph.name})", (f"duration_{ph.name}", f"t_{ph.name}"), sp.sympify(ph.duration),
                                    "time", TIME, f"the duration of the phase '{ph.name}'", True))
                for d, x in ph.end_state.items():
                    if isinstance(d, sp.Derivative):
                        r = _rate(system, d, x, True)
                        r.symbol, r.names = f"{r.symbol}({ph.name})", tuple(f"{n}_{ph.name}" for n in r.names)
                        r.words = f"{r.words or r.symbol} at the end of the phase '{ph.name}'"
                        out.append(r)
    elif isinstance(v, dict):
        for d, x in v.items():
            if isinstance(d, sp.Derivative):
                out.append(_rate(system, d, x, True))
            elif isinstance(x, sp.Basic | int | float):
                out.append(Quantity(text(d), (str(d),), sp.sympify(x), "value", None, "", True))
    elif kind == "reaction" and isinstance(v, sp.Basic):
        r = str(a.question.fields.get("reaction", "reaction"))
        out.append(Quantity(r, (r,), v, "reaction", dim(v), "the reaction", True))
    elif isinstance(v, sp.Eq):
        out.append(Quantity(text(v.lhs), (str(v.lhs),), v.rhs, "value", dim(v.rhs), "", True))
    elif isinstance(v, sp.Basic):
        head = a.text.split(" = ")[0] if " = " in a.text else a.question.name
        out.append(Quantity(head, (head,), v, "value", dim(v), "", True))
    elif kind == "integral":
        for k, e in enumerate(v):
            x = getattr(e, "value", None) if not isinstance(e, sp.Basic) else None
            if isinstance(x, sp.Basic):
                out.append(Quantity(f"integral {k + 1}", (f"integral{k + 1}",), x, "value", dim(x), "", True))
    return out


def _dim(system, setup, expr):
    try:
        return dimension_of(expr, symbol_dimensions(system, setup))
    except (RigidkinError, TypeError, ValueError):
        return None


# grading -------------------------------------------------------------------------------------------------
def grade_answer(ref: Reference, st: Step) -> StepResult:
    res = StepResult(st.index, st.kind, INCORRECT)
    a = ref.answers().get(st.question)
    if isinstance(a, Exception) or a is None:
        res.feedback = [f"the engine could not answer '{st.question}' itself ({a}), so the answer is not graded"]
        return res
    res.expected = a.text
    qs = quantities(ref, st.question)
    res.asks = "; ".join(f"{q.describe()}" + (f", in {q.unit}" if q.unit else "") for q in qs
                         if q.asked and not held(ref, q))
    if not qs:
        res.feedback = [f"the answer to '{st.question}' is not a value that can be compared ({a.text})"]
        return res
    claim_text, named = _split_name(st)
    chosen = _named(qs, named, st) if named else None
    if chosen is not None and chosen[0].kind == "stability":
        return _grade_stability(res, chosen, claim_text)
    value, unit_dim, bare = _read(ref, claim_text, st)
    params = numeric_values_from(ref.system)
    rtol = st.tolerance or ANSWER_RTOL
    pool = chosen if chosen is not None else [q for q in qs if q.kind != "stability"]
    if chosen is None:
        # a coordinate the mode holds fixed (ρ = R + r while in contact) says nothing about where: not asked
        asked = [q for q in pool if q.asked and not held(ref, q)] or [q for q in pool if q.asked]
        dim = unit_dim if unit_dim is not None else (None if bare else _dim(ref.system, ref.setup, value))
        fit = [q for q in pool if dim is not None and q.dimension is not None and q.dimension == dim]
        pool = [q for q in fit if q in asked] or fit or asked
    target = pool[0]
    # dimension: a unit or an expression of another kind of quantity is wrong whatever its number
    got = unit_dim if unit_dim is not None else (None if bare else _dim(ref.system, ref.setup, value))
    if got is not None and target.dimension is not None and got != target.dimension and \
            all(q.dimension != got for q in pool):
        what = ", ".join(f"{q.symbol}: {q.dimension}" for q in pool[:4])
        res.feedback = [f"unit: {claim_text.strip()} has dimension {got}, which no quantity the question asks has "
                        f"({what}; an angle is dimensionless: rad or deg)"]
        res.differences.append((claim_text.strip(), _shown(target, params)))
        return res
    for q in pool:
        if _same(ref, value, q.value, params, rtol):
            res.verdict = CORRECT
            if len(qs) > 1 and chosen is None:
                res.feedback = [f"read as {q.describe()}"]
            return res
    res.feedback = [_cause(ref, value, pool, qs, params, rtol, bare, claim_text)]
    res.differences.append((claim_text.strip(), _shown(target, params)))
    return res


def held(ref, q: Quantity) -> bool:
    """A position whose coordinate is constant in the mode (fixed by a constraint)."""
    if q.kind != "position" or q.coordinate is None:
        return False
    try:
        e = ref.scalar(q.coordinate)
    except (RigidkinError, TypeError, ValueError):
        return False
    return not any(f.has(t) for f in sp.sympify(e).atoms(sp.Function)) and not e.has(t)


def _split_name(st: Step) -> tuple[str, str | None]:
    """The claim's value and the quantity it names (``quantity`` field, or ``NAME = value``)."""
    claim = st.claim if isinstance(st.claim, str) else "; ".join(st.claim)
    if st.quantity:
        return claim, st.quantity.strip()
    m = re.match(r"^\s*([A-Za-z][A-Za-z0-9_]*(?:\([A-Za-z][A-Za-z0-9_]*\))?)\s*=(?!=)(.*)$", claim)
    if m:
        return m.group(2), m.group(1)
    return claim, None


def _named(qs, name: str, st: Step) -> list[Quantity]:
    key = name.replace(" ", "").lower()
    hit = [q for q in qs if key in {n.lower() for n in q.names} or key == q.symbol.lower()]
    if not hit:
        known = ", ".join(dict.fromkeys(q.names[0] if q.names else q.symbol for q in qs))
        raise Unreadable(f"unreadable: the question '{st.question}' states no quantity '{name[:40]}' "
                         f"(it states: {known})")
    return hit


def _read(ref, claim: str, st: Step):
    """(value, the dimension of its unit or None, a bare number?)."""
    m = _NUM_UNIT.match(claim)
    if m and m.group(2).strip():
        unit = m.group(2).strip().replace("°", "deg")
        try:
            dim = unit_dimension(unit, st.where)
            mag = parse_quantity(f"{m.group(1)} {unit}", None, st.where)
        except InputError as exc:
            raise Unreadable(f"unreadable value: {exc.message}") from None
        return sp.Float(mag), dim, False
    try:
        v = parse_scalar(claim, ref.scope, st.where)
    except InputError as exc:
        raise Unreadable(f"unreadable value: {exc.message}") from None
    return v, None, not (v.free_symbols - {t})


def _same(ref, value, target, params, rtol) -> bool:
    target = sp.sympify(target)
    if sp.sympify(value).free_symbols - {t}:
        d = space.to_plain(value - target)
        vals = ref.sampler.evaluate([d, space.to_plain(target)])
        return bool(space.vanishes(vals[:, :1], np.abs(vals)))
    cv, v = _num(target, params), _num(value, params)
    return cv is not None and v is not None and math.isclose(v, cv, rel_tol=rtol, abs_tol=rtol * 1e-3)


def _cause(ref, value, pool, qs, params, rtol, bare, claim) -> str:
    v = _num(value, params)
    for q in pool:
        cv = _num(q.value, params)
        if v is None or cv is None:
            continue
        if math.isclose(v, -cv, rel_tol=rtol) and cv != 0:
            return f"sign: the value has the wrong sign ({_shown(q, params)})"
        if bare and q.dimension == ONE and q.kind == "position" and math.isclose(v, math.degrees(cv), rel_tol=rtol):
            raise Unreadable(f"ambiguous: {claim.strip()} is {q.symbol} in degrees, but a bare number is read in "
                             f"radians (SI); write it with its unit ('{claim.strip()} deg')")
    for q in qs:
        if q in pool or q.kind == "stability":
            continue
        if _same(ref, value, q.value, params, rtol):
            return f"wrong quantity: this is {q.describe()}, but the question asks {_asked(pool, params)}"
    return f"the answer is {_asked(pool, params)}"


def _asked(pool, params) -> str:
    shown = "; ".join(_shown(q, params) for q in pool[:4])
    return shown + (" (any one of them)" if len(pool) > 1 else "")


def _grade_stability(res, chosen, claim) -> StepResult:
    said = claim.strip().lower()
    for q in chosen:
        truth = str(q.value).lower()
        if said and (truth.startswith(said) or said.split()[0] == truth.split()[0]):
            res.verdict = CORRECT
            return res
    res.feedback = [f"the equilibrium is {chosen[0].value}"]
    return res


def _shown(q: Quantity, params) -> str:
    if q.kind == "stability":
        return str(q.value)
    v = _num(q.value, params)
    s = f"{q.symbol} = {text(q.value)}"
    if v is not None and not sp.sympify(q.value).is_Integer:
        s += f" ≈ {v:.6g}"
        if q.kind == "position" and q.dimension == ONE:
            s += f" ({math.degrees(v):.4g}°)"
    return s


def _num(expr, params) -> float | None:
    try:
        v = complex(sp.sympify(expr).xreplace(params).evalf())
    except (TypeError, ValueError):
        return None
    if abs(v.imag) > 1e-9 * max(1.0, abs(v.real)) or not math.isfinite(v.real):
        return None
    return v.real


def _si(dim) -> str:
    parts = []
    for name, sym in (("mass", "kg"), ("length", "m"), ("time", "s")):
        e = getattr(dim, name)
        if e:
            parts.append(sym if e == 1 else f"{sym}^{e:g}")
    return "·".join(parts)
