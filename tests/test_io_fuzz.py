"""Fuzzing the expression parser and the problem-file reader with hypothesis (bounded, reproducible):
every input either gives a valid result or a RigidkinError — never another exception, never a hang."""

import math
import os
import random
import time

import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from sympy.physics.vector import ReferenceFrame, Vector, dynamicsymbols

from rigidkin.base.errors import RigidkinError
from rigidkin.examples import HERE
from rigidkin.io.expressions import default_scope, parse, parse_condition, parse_equation
from rigidkin.io.problem import build_problem, parse_problem

# CI: 150 reproducible examples per test; RIGIDKIN_FUZZ_EXAMPLES=5000 for a long random run.
_DEEP = os.environ.get("RIGIDKIN_FUZZ_EXAMPLES")
FUZZ = settings(max_examples=int(_DEEP or 150), deadline=None, derandomize=not _DEEP, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])

theta = dynamicsymbols("theta")
F, R = ReferenceFrame("F"), ReferenceFrame("R")
R.orient_axis(F, F.z, theta)
SCOPE = default_scope()
SCOPE.names.update(m=sp.Symbol("m", positive=True), l=sp.Symbol("l", positive=True), theta=theta)
SCOPE.coordinates["theta"] = theta
SCOPE.add_frame("F", ("Ex", "Ey", "Ez"), (F.x, F.y, F.z))
SCOPE.add_frame("R", ("er", "et", "ez"), (R.x, R.y, R.z))

ALPHABET = "ml theta R F Ex er dot ddot sin sqrt atan2 pi t _ . , ( ) [ ] { } : ' \" = < > + - * / ** % ^ 0 1 9 e j"
TOKENS = ["m", "l", "theta", "pi", "t", "R.x", "F.y", "er", "Ex", "2", "0", "0.5", "1e300", "9", "dot(theta)",
          "ddot(theta)", "__class__", "lambda", "x", "nan", "1j", "'s'"]


def _finite(value) -> bool:
    if isinstance(value, Vector):
        return all(_finite(sp.sympify(c)) for measure, _ in value.args for c in measure)
    return not value.has(sp.nan, sp.zoo, sp.oo, -sp.oo)


def _parse_all(text):
    start = time.process_time()
    for fn, kw in ((parse, {"want": "any"}), (parse_equation, {}), (parse_condition, {})):
        try:
            value = fn(text, SCOPE, "fuzz", **kw)
        except RigidkinError:
            continue
        assert isinstance(value, sp.Basic | Vector)
        assert _finite(value) if isinstance(value, Vector | sp.Expr) else True
    assert time.process_time() - start < 2.0


@FUZZ
@given(st.lists(st.sampled_from(ALPHABET.split() + [" "]), max_size=30).map("".join))
def test_parser_token_soup(text):
    _parse_all(text)


@FUZZ
@given(st.text(max_size=60))
def test_parser_any_text(text):
    _parse_all(text)


def expressions():
    leaf = st.sampled_from(TOKENS)
    return st.recursive(
        leaf,
        lambda inner: st.one_of(
            st.tuples(inner, st.sampled_from(["+", "-", "*", "/", "**"]), inner).map(lambda x: f"({x[0]}{x[1]}{x[2]})"),
            st.tuples(st.sampled_from(["sin", "cos", "sqrt", "exp", "log", "abs", "sign", "atan", "acos"]), inner)
            .map(lambda x: f"{x[0]}({x[1]})"),
            inner.map(lambda x: f"-{x}"),
            st.tuples(inner, inner).map(lambda x: f"atan2({x[0]}, {x[1]})"),
        ),
        max_leaves=12)


@FUZZ
@given(expressions())
def test_parser_structured(text):
    _parse_all(text)
    _parse_all(f"{text} = 0")
    _parse_all(f"{text} > m")


# problem files ---------------------------------------------------------------------------------------------
KEYS = ["title", "statement", "parameters", "coordinates", "frames", "points", "bodies", "constraints", "loads",
        "ask", "question", "m", "theta", "R", "G", "rod", "O", "unit", "value", "sense", "kind", "initial", "angle",
        "parent", "basis", "from", "offset", "body", "shape", "mass", "length", "axis", "frame", "at", "type",
        "point", "body_a", "surface", "normal", "radius", "friction", "g", "when", "start", "mode", "set", "reaction"]
VALUES = ["m", "theta", "R", "G", "rod", "O", "F", "kg", "m/s^2", "slender_rod", "disk", "pin", "contact", "line",
          "gravity", "event", "N = 0", "-l/2*R.y", "x*Ex", "30 deg", "smooth", "rolling", "open", "y", "__import__"]

toml_values = st.recursive(
    st.one_of(st.sampled_from(VALUES), st.integers(-5, 5), st.floats(allow_nan=True, allow_infinity=True),
              st.booleans(), st.text(max_size=8)),
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.dictionaries(st.sampled_from(KEYS), inner, max_size=4)),
    max_leaves=20)


@FUZZ
@given(st.dictionaries(st.sampled_from(KEYS), toml_values, max_size=8))
def test_schema_random_tables(data):
    try:
        system, spec = build_problem(data, "", "fuzz.toml")
    except RigidkinError as exc:
        assert str(exc).startswith("fuzz.toml")
        return
    assert system.title == data["title"]


SOURCES = {name: (HERE / f"{name}.toml").read_text() for name in ("ladder", "slip-to-roll", "boulder-push")}


@FUZZ
@given(st.sampled_from(sorted(SOURCES)), st.integers(0, 2**32 - 1), st.integers(1, 4))
def test_problem_file_mutations(name, seed, count):
    """A bundled file with a few random edits: a valid problem or a RigidkinError that names the file."""
    rng = random.Random(seed)
    text = SOURCES[name]
    pieces = ["=", "\"", "[", "]", "{", "}", ",", "\n", "__class__", "lambda: 0", "9**9**9", "nan", "inf", "-",
              "R.y", "theta", "rod", "0", "1e999", "dot(", "x", "[[ask.question]]\nkind = \"event\"\n"]
    for _ in range(count):
        i = rng.randrange(len(text) + 1)
        op = rng.random()
        if op < 0.4:
            j = min(len(text), i + rng.randint(1, 12))
            text = text[:i] + text[j:]
        elif op < 0.8:
            text = text[:i] + rng.choice(pieces) + text[i:]
        else:
            lines = text.splitlines(keepends=True)
            k = rng.randrange(len(lines))
            lines.insert(k, lines[rng.randrange(len(lines))])
            text = "".join(lines)
    start = time.process_time()
    try:
        system, spec = parse_problem(text, f"{name}.toml")
    except RigidkinError as exc:
        assert str(exc).startswith(f"{name}.toml")
    else:
        assert system.bodies and spec.title
        for p in system.parameter_info.values():
            assert p.value is None or math.isfinite(p.value)
    assert time.process_time() - start < 2.0
