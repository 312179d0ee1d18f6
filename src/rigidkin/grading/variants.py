"""Problem sets: variants of a problem with changed parameter values, their answer keys, Moodle XML.

Each variant is the problem file with new values (drawn from ``--vary NAME=LOW:HIGH`` ranges, rounded
to three significant figures, reproducibly from the seed), built and solved afresh: its answers come
from its own solve.  Where the original problem has an exact answer, the exact answer evaluated at the
variant's values must agree with the variant's own solve — the key is checked by two routes, and a
variant whose two routes disagree is refused.  Keys are numbers with a relative tolerance.

Every question of the problem is kept: one whose answer gives no number is named in ``left_out`` with
why.  The exports (Moodle XML, PrairieLearn question folders) are in :mod:`rigidkin.grading.exports`.
"""

from __future__ import annotations

import copy
import math
import random
from dataclasses import dataclass, field
from pathlib import Path

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from .. import examples
from ..analysis.answers import answer, numeric_values_from
from ..base.errors import InputError, RigidkinError
from ..base.printing import text
from ..base.textsafe import is_identifier
from ..base.units import LENGTH, TIME, to_si
from ..io.problem import build_problem, read_toml
from .answers import answer_quantities

t = dynamicsymbols._t

MAX_COUNT = 200
DEFAULT_RTOL = 0.01


@dataclass
class KeyEntry:
    question: str
    label: str           # what the number is (θ, θ̇ just after ...)
    value: float
    tolerance: float     # absolute, for the platform
    exact: str = ""      # the closed form, where there is one
    symbol: str = ""     # the quantity asked: its symbol, words, SI unit and kind
    words: str = ""
    unit: str = ""
    kind: str = ""
    at: str = ""         # where a function of the state is evaluated (" at the start (θ = 0.3)")


@dataclass
class Variant:
    index: int
    values: dict                       # parameter name → value in its declared unit
    units: dict
    keys: list[KeyEntry] = field(default_factory=list)
    fixed: dict = field(default_factory=dict)      # the parameters kept, in their declared units
    notes: list[str] = field(default_factory=list)
    left_out: list = field(default_factory=list)    # (question, why) for each question without a key


@dataclass
class ProblemSet:
    problem: str
    title: str
    statement: str
    questions: dict                    # name → description
    variants: list[Variant]


def parse_vary(items) -> dict:
    """``NAME=LOW:HIGH`` (numbers in the parameter's declared unit, or quantities such as ``10 deg``)."""
    out = {}
    for it in items:
        name, sep, rng = it.partition("=")
        low, sep2, high = rng.partition(":")
        name = name.strip()
        if not sep or not sep2 or not is_identifier(name):
            raise InputError(f"--vary '{it[:60]}' is not NAME=LOW:HIGH.", where="--vary",
                             hint="For example --vary m=1:5 --vary l=0.5:2.")
        out[name] = (low.strip(), high.strip())
    return out


def _round3(v: float) -> float:
    if v == 0 or not math.isfinite(v):
        return v
    return round(v, 2 - int(math.floor(math.log10(abs(v)))))


def _in_unit(text_value: str, unit: str, where: str) -> float:
    """A number in the parameter's declared unit, from a number or a quantity."""
    si = to_si(text_value, None, where) if any(c.isalpha() for c in text_value) else None
    if si is None:
        try:
            v = float(text_value)
        except ValueError:
            raise InputError(f"'{text_value[:40]}' is not a number.", where=where) from None
        if not math.isfinite(v):
            raise InputError(f"'{text_value[:40]}' is not a finite number.", where=where)
        return v
    return si / to_si(1.0, unit or None, where)


def make_set(problem: str, count: int, seed: int, vary: dict, rtol: float = DEFAULT_RTOL) -> ProblemSet:
    """``count`` variants of ``problem`` (a bundled name or a problem file) with checked answer keys."""

    if not 1 <= count <= MAX_COUNT:
        raise InputError(f"--count {count} is out of range (1 to {MAX_COUNT}).", where="--count")
    path = Path(problem)
    if path.suffix != ".toml":
        if problem not in examples.names() or not (examples.HERE / f"{problem}.toml").exists():
            raise InputError(f"'{problem}' is neither a problem file nor a bundled example with a problem file.",
                             hint=f"Bundled examples: {', '.join(examples.names())}.")
        path = examples.HERE / f"{problem}.toml"
    text_, data = read_toml(path)
    base_system, base_spec = build_problem(data, text_, path)
    if not base_spec.questions:
        raise InputError("the problem asks no question ([[ask.question]]), so there is nothing to answer.",
                         where=str(path), hint="Add the questions a student should answer.")
    params = data.get("parameters", {})
    ranges = {}
    for name, (lo, hi) in vary.items():
        if name not in params or name not in base_system.parameter_info:
            raise InputError(f"the problem has no parameter named '{name}'.", where="--vary",
                             hint=f"Parameters: {', '.join(base_system.parameter_info)}.")
        unit = base_system.parameter_info[name].unit
        a, b = _in_unit(lo, unit, f"--vary {name}"), _in_unit(hi, unit, f"--vary {name}")
        if not a < b:
            raise InputError(f"--vary {name}: LOW must be below HIGH.", where="--vary")
        if base_system.parameter_info[name].symbol.is_positive and a <= 0:
            raise InputError(f"--vary {name}: {name} is positive, so LOW must be above 0.", where="--vary")
        ranges[name] = (a, b)
    if not vary:          # every parameter with a value, ±20 %, except accelerations (gravity)
        for name, p in base_system.parameter_info.items():
            if p.value is not None and p.value != 0 and p.dimension != LENGTH / TIME**2:
                v = p.value / to_si(1.0, p.unit or None, name)
                ranges[name] = (0.8 * v, 1.2 * v) if v > 0 else (1.2 * v, 0.8 * v)

    base_answers, context = {}, {}
    for q in base_spec.questions:
        try:
            a = answer(base_system, q, context)
        except RigidkinError:
            continue
        base_answers[q.name] = a
        context[q.name] = a
    out = []
    for k in range(count):
        rng = random.Random(f"{seed}:{k}")
        values = {n: _round3(rng.uniform(a, b)) for n, (a, b) in sorted(ranges.items())}
        vdata = copy.deepcopy(data)
        for n, v in values.items():
            entry = vdata["parameters"][n]
            if isinstance(entry, dict):
                entry["value"] = v
            else:
                vdata["parameters"][n] = {"value": v}
        system, spec = build_problem(vdata, text_, path)
        info = base_system.parameter_info
        var = Variant(k + 1, values, {n: p.unit for n, p in info.items()})
        var.fixed = {n: p.value / to_si(1.0, p.unit or None, n) for n, p in info.items()
                     if n not in values and p.value is not None}
        _keys(var, system, spec, base_answers, rtol)
        out.append(var)
    return ProblemSet(str(problem), base_spec.title, base_spec.statement,
                      {q.name: q.fields.get("description") or q.name for q in base_spec.questions}, out)


def _labelled(system, a) -> list:
    """(label, value, quantity) for each number-like quantity of an answer (stability is not a number)."""
    out = []
    for q in answer_quantities(system, a):
        if q.kind == "stability":
            continue
        out.append((q.symbol + (f" — {q.words}" if q.words else ""), q.value, q))
    return out


def _at_start(system, expr):
    """A function of the state evaluated at the problem's declared start (None: no start declared, or the
    value still depends on the state)."""
    sub = {}
    for c in system.coordinate_info.values():
        if c.initial is None and c.rate is None:
            continue                   # not declared (a dependent coordinate): the value must not need it
        sub[c.symbol.diff(t)] = c.rate if c.rate is not None else 0
        sub[c.symbol] = c.initial if c.initial is not None else 0
    e = sp.sympify(expr).xreplace({k: v for k, v in sub.items() if isinstance(k, sp.Derivative)}).xreplace(sub)
    if not sub or e.atoms(sp.Derivative) or any(f.has(t) for f in e.atoms(sp.Function)):
        return None, ""
    shown = ", ".join(f"{text(k)} = {v:g}" for k, v in sub.items() if k in sp.sympify(expr).atoms(sp.Function,
                                                                                                    sp.Derivative))
    return e, shown


def _keys(var: Variant, system, spec, base_answers, rtol) -> None:
    """Every question's numbers from the variant's own solve; one that gives none is left out, with why."""
    values = numeric_values_from(system)
    held = _held(system)
    context = {}
    for q in spec.questions:
        try:
            a = answer(system, q, context)
        except RigidkinError as exc:
            var.left_out.append((q.name, f"not answered ({exc.message})"))
            continue
        context[q.name] = a
        base = {lab: x for lab, x, _ in _labelled(system, base_answers[q.name])} if q.name in base_answers else {}
        got = 0
        state_bound = []
        for label, expr, qty in _labelled(system, a):
            fixed = _held_by(qty, held)
            if fixed is not None:              # ρ = R + r while in contact: not a question
                note = f"{q.name}: {qty.symbol} is not asked ({fixed})"
                if note not in var.notes:
                    var.notes.append(note)
                continue
            num = _number(expr, values)
            where = ""
            if num is None:
                at, shown = _at_start(system, expr)
                num = _number(at, values) if at is not None else None
                if num is None:
                    state_bound.append(label)
                    continue
                where = (f" at {shown} along the motion of the question ({text(a.details['integral'])})"
                         if (a.details or {}).get("integral") is not None else f" at the start ({shown})")
            tol = max(rtol * abs(num), (a.tolerance or 0.0), 1e-12)
            exact = base.get(label)
            if exact is not None and base_answers[q.name].exact:
                check = _number(exact if not where else _at_start(system, exact)[0], values)
                if check is None or not math.isclose(check, num, rel_tol=max(rtol / 10, 1e-6), abs_tol=1e-9):
                    raise RigidkinError(f"variant {var.index}: the answer {label} of '{q.name}' is {num:.6g} by the "
                                        f"variant's own solve but {check} from the exact answer {text(exact)}; the "
                                        "key is refused.", hint="Narrow the --vary ranges (a regime may change).")
            var.keys.append(KeyEntry(q.name, label + where, num, tol, text(exact) if exact is not None else "",
                                     qty.symbol, qty.words, qty.unit, qty.kind, where))
            got += 1
        if not got:
            why = (f"its answer ({', '.join(state_bound)}) is a function of the state, not a number, and the problem "
                   "declares no start to evaluate it at") if state_bound else "its answer holds no number"
            var.left_out.append((q.name, why))


def _held(system) -> dict:
    """Coordinate name → (its value, the constraints that fix it), for each coordinate the constraints of the
    problem's mode fix (the distance of centres ρ = R + r of a sphere rolling on a sphere, by the contact):
    what no student is asked to find."""
    try:
        setup = system.solve().setup
    except RigidkinError:
        return {}
    out = {}
    for c in system.coordinate_info.values():
        try:
            e = sp.sympify(setup.scalar(c.symbol))
        except (RigidkinError, TypeError, ValueError):
            continue
        if not e.has(t):
            rate = c.symbol.diff(t)
            by = sorted({r.constraint for r in setup.rows if sp.sympify(r.velocity).has(rate)
                         or (r.gap is not None and sp.sympify(r.gap).has(c.symbol))})
            out[c.name] = (e, by)
    return out


def _held_by(qty, held: dict) -> str | None:
    """``ρ = R + r, fixed by the constraint P`` (``ρ̇ = 0`` for its rate) when the quantity is a coordinate, or
    its rate, that the constraints fix."""
    if qty.kind not in ("position", "rate"):
        return None
    for name, (value, by) in held.items():
        which = (f"the constraint{'s' if len(by) > 1 else ''} {', '.join(by)}" if by else "the constraints")
        if qty.kind == "position" and qty.coordinate is not None and getattr(qty.coordinate.func, "__name__",
                                                                              None) == name:
            return f"{qty.symbol} = {text(value)}, fixed by {which}"
        if qty.kind == "rate" and f"dot({name})" in qty.names:
            return f"{qty.symbol} = 0, fixed by {which}"
    return None


def _number(expr, values) -> float | None:
    try:
        v = complex(sp.sympify(expr).xreplace(values).evalf())
    except (TypeError, ValueError):
        return None
    if abs(v.imag) > 1e-9 * max(1.0, abs(v.real)) or not math.isfinite(v.real):
        return None
    return v.real


# output -------------------------------------------------------------------------------------------
def as_data(ps: ProblemSet) -> dict:
    return {"problem": ps.problem, "title": ps.title,
            "variants": [{"index": v.index, "parameters": {n: {"value": x, "unit": v.units[n]}
                                                           for n, x in v.values.items()},
                          "kept": {n: {"value": x, "unit": v.units[n]} for n, x in v.fixed.items()},
                          "answers": [{"question": k.question, "quantity": k.label, "value": k.value,
                                       "tolerance": k.tolerance, "exact": k.exact} for k in v.keys],
                          "notes": v.notes,
                          "left_out": [{"question": q, "why": w} for q, w in v.left_out]} for v in ps.variants],
            "left_out": [{"question": q, "why": w} for q, w in left_out(ps)]}


def as_text(ps: ProblemSet) -> str:
    lines = [f"{ps.title}: {len(ps.variants)} variants"]
    for v in ps.variants:
        vals = ", ".join(f"{n} = {x:g} {v.units[n]}".rstrip() for n, x in v.values.items())
        lines.append(f"Variant {v.index}: {vals}")
        for k in v.keys:
            lines.append(f"    {k.question}: {k.label} = {k.value:.6g} ± {k.tolerance:.2g}")
        for n in v.notes:
            lines.append(f"    {n}")
    for q, why in left_out(ps):
        lines.append(f"Left out of every variant: {q}: {why}")
    return "\n".join(lines)


def left_out(ps: ProblemSet) -> list:
    """(question, why) for each question that has no key in some variant (the first reason given)."""
    out = {}
    for v in ps.variants:
        for q, why in v.left_out:
            out.setdefault(q, why)
    return list(out.items())

