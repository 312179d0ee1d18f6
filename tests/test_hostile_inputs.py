"""Hostile and mistaken inputs, class by class: each is refused (exit 2, one paragraph naming the field and
what to do) in under 2 s of CPU time and 500 MB of memory, checked by the harness; accepted inputs next to
them stay accepted (exit 0).

Classes: the structure of the TOML text (keys, tables, depth, line length), unit and quantity strings (our
grammar in front of pint), expression size and growth (exponents, nested functions, huge numbers,
accelerations in loads), physical values (positive masses and lengths, µ ≥ 0, real and finite after the
parameters' values are put in, dimensions of initial values), names (ASCII identifiers, no keywords, none of
the engine's own names, no look-alike letters), the same rules through the Python API, and hypothesis over
the fields of a problem file.
"""

from __future__ import annotations

import resource
import signal
import time
from contextlib import contextmanager

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import rigidkin as rk
from rigidkin.base.errors import InputError, ModelError, RigidkinError
from rigidkin.base.units import LENGTH, ONE, parse_quantity
from rigidkin.cli import main
from rigidkin.io.problem import parse_problem

CPU_LIMIT = 2.0                 # seconds of CPU time per case
MEMORY_LIMIT = 500 * 2**20      # bytes of growth of the peak resident set per case
HANG_LIMIT = 30                 # seconds of wall time before a case is stopped as hung

PENDULUM = '''\
title = "Pendulum"
[parameters]
m = { unit = "kg", value = 1 }
l = { unit = "m", value = 1 }
g = { unit = "m/s^2", value = 9.81 }
[coordinates]
theta = { sense = "from the downward vertical, counter-clockwise", initial = 0.1, rate = 0 }
[frames]
R = { angle = "theta", basis = ["er", "et", "ez"] }
[points]
G = { offset = "-l/2*R.y" }
[bodies]
rod = { shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }
[constraints]
O = { type = "pin", point = "O", body_a = "rod" }
[loads]
gravity = { type = "gravity", g = "g" }
'''

BLOCK = '''\
title = "Block on a rough floor"
[parameters]
m = { unit = "kg", value = 2 }
g = { unit = "m/s^2", value = 9.81 }
r = { unit = "m", value = 0.1 }
mu = { unit = "1", value = 0.3 }
k = { unit = "N/m", value = 10 }
[coordinates]
x = { sense = "along Ex from O", kind = "length", initial = 0, rate = 1 }
[points]
C = { offset = "x*Ex + r*Ey" }
[bodies]
disk = { shape = "disk", mass = "m", radius = "r", frame = "F", at = "C" }
[constraints]
floor = { type = "contact", body = "disk", surface = { type = "line", normal = "Ey" }, radius = "r", friction = "mu" }
[loads]
gravity = { type = "gravity", g = "g" }
spring = { type = "spring", point_a = "C", point_b = "O", stiffness = "k", natural_length = 0 }
'''


def sub(old: str, new: str, text: str = PENDULUM) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def add(section: str, line: str, text: str = PENDULUM) -> str:
    """Add a line at the end of a [section] of the text."""
    head = f"[{section}]\n"
    assert head in text, section
    return text.replace(head, head + line + "\n", 1)


@contextmanager
def bounded(name: str):
    """Run a case under the harness's bounds: CPU time, growth of peak memory, and a wall-clock stop."""
    def hung(signum, frame):
        raise TimeoutError(f"{name}: still running after {HANG_LIMIT} s")

    old = signal.signal(signal.SIGALRM, hung)
    signal.alarm(HANG_LIMIT)
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    cpu0 = time.process_time()
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    cpu = time.process_time() - cpu0
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 - rss0
    assert cpu < CPU_LIMIT, f"{name}: {cpu:.2f} s of CPU time (at most {CPU_LIMIT})"
    assert grown < MEMORY_LIMIT, f"{name}: peak memory grew by {grown / 2**20:.0f} MB (at most 500)"


@pytest.fixture(scope="module", autouse=True)
def warm():
    """Import what the command line imports lazily, so that the bounds measure the case itself."""
    from rigidkin.base.units import registry

    registry()
    parse_problem(PENDULUM, "warm.toml")
    parse_problem(BLOCK, "warm.toml")


def run_file(text, tmp_path, capsys, command="validate", name="problem.toml"):
    f = tmp_path / name
    f.write_bytes(text) if isinstance(text, bytes) else f.write_text(text, encoding="utf-8")
    with bounded(name):
        code = main([command, str(f)])
    out, err = capsys.readouterr()
    return code, out, err.strip(), f


# --- generated cases: (id, file text, expected exit code, words the message contains) -------------------------
def _structure_cases():
    dotted = PENDULUM + "[junk]\n" + "".join(f"k{i}.a.b = 1\n" for i in range(30_000))
    headers = PENDULUM + "".join(f"[x{i}]\n" for i in range(100_000))
    deep_headers = PENDULUM + "".join("[" + ".".join(f"t{j}" for j in range(i % 50 + 1)) + "]\n"
                                      for i in range(2_000))
    return [
        ("toml-30000-dotted-keys", dotted, 2, ["more than 2000 dotted keys"]),
        ("toml-100000-headers", headers, 2, ["more than 2000 table headers"]),
        ("toml-200kB-header", PENDULUM + "[" + "a." * 100_000 + "b]\n", 2, ["characters long (at most 10000)"]),
        ("toml-long-key-path", PENDULUM + "[" + ".".join(["a"] * 20) + "]\n", 2, ["more than 8 parts"]),
        ("toml-deep-headers", deep_headers, 2, ["more than 8 parts"]),
        ("toml-deep-inline", PENDULUM + "junk = " + "{ a = " * 40 + "1" + " }" * 40 + "\n", 2,
         ["nested more than 16 deep"]),
        ("toml-deep-arrays", PENDULUM + "junk = " + "[" * 200 + "]" * 200 + "\n", 2, ["nested more than 16 deep"]),
        ("toml-many-keys", PENDULUM + "[junk]\n" + "".join(f"k{i} = {i}\n" for i in range(12_000)), 2,
         ["more than 10000 keys"]),
        ("toml-many-inline-keys", PENDULUM + "junk = [" + ",\n".join("{ a = 1, b = 2 }" for _ in range(6_000))
         + "]\n", 2, ["more than 10000 keys"]),
        ("toml-long-statement", sub('title = "Pendulum"', 'title = "Pendulum"\nstatement = "' + "x" * 20_000 + '"'),
         2, ["line 2", "statement", "characters long"]),
        ("toml-header-of-spaces", PENDULUM + "[" + " " * 9_000 + "junk]\n", 2, ["junk", "unknown field"]),
        ("toml-array-line-of-spaces", PENDULUM + "junk = [\n" + ("  [ 1," + " " * 9_000 + "2 ],\n") * 50 + "]\n", 2,
         ["line 18, loads.junk"]),
        ("toml-keys-in-strings-do-not-count", sub('title = "Pendulum"', 'title = "Pendulum"\nstatement = """'
                                                  + "a.b.c = [[{" * 800 + '"""'), 0, []),
    ]


def _unit_cases():
    return [
        ("unit-less-than", sub('unit = "kg"', 'unit = "kg<m"'), 2, ["parameters.m.unit", "'<' is not allowed"]),
        ("unit-tilde", sub('unit = "kg"', 'unit = "~kg"'), 2, ["parameters.m.unit", "'~' is not allowed"]),
        ("unit-lambda", sub('unit = "kg"', 'unit = "lambda: kg"'), 2, ["parameters.m.unit", "':' is not allowed"]),
        ("unit-dunder", sub('unit = "kg"', 'unit = "__class__"'), 2, ["parameters.m.unit", "is not a unit"]),
        ("unit-tower", sub('unit = "kg"', 'unit = "kg^2^2"'), 2, ["parameters.m.unit", "towers"]),
        ("unit-huge-power", sub('unit = "kg"', 'unit = "kg**99999"'), 2, ["parameters.m.unit", "at most 12"]),
        ("unit-power-of-name", sub('unit = "kg"', 'unit = "kg**m"'), 2, ["parameters.m.unit", "whole number"]),
        ("unit-parentheses", sub('unit = "kg"', 'unit = "((((kg))))"'), 2, ["parameters.m.unit", "nested"]),
        ("unit-long-product", sub('unit = "kg"', 'unit = "' + "*".join(["m"] * 30) + '"'), 2,
         ["parameters.m.unit", "more than 12 unit names"]),
        ("unit-unknown", sub('unit = "kg"', 'unit = "blorp"'), 2, ["parameters.m.unit", "'blorp' is not a unit"]),
        ("unit-semicolon", sub('unit = "kg"', 'unit = "kg; import os"'), 2, ["parameters.m.unit", "';'"]),
        ("unit-empty-parentheses", sub('unit = "kg"', 'unit = "()"'), 2, ["parameters.m.unit"]),
        ("unit-percent", sub("value = 1 }", 'value = "50 %" }'), 2,
         ["parameters.m.value", "neither a number nor a quantity"]),
        ("unit-ok-compound", sub('unit = "m/s^2"', 'unit = "(kg*m)/(kg*s**2)"'), 0, []),
        ("value-tower", sub("value = 1 }", 'value = "9 kg^9^9^9" }'), 2, ["parameters.m.value", "towers"]),
        ("value-number-tower", sub("value = 1 }", 'value = "9^9^9^9 kg" }'), 2, ["parameters.m.value"]),
        ("value-less-than", sub("value = 1 }", 'value = "1 kg<2" }'), 2, ["parameters.m.value", "'<'"]),
        ("value-lambda", sub("value = 1 }", 'value = "1 lambda: 0" }'), 2, ["parameters.m.value"]),
        ("value-overflow", sub("value = 1 }", 'value = "1e999 kg" }'), 2, ["parameters.m.value", "not a finite"]),
        ("value-wrong-dimension", sub("value = 1 }", 'value = "2 m" }'), 2,
         ["parameters.m.value", "not in units of kg"]),
        ("value-ok-other-unit", sub("value = 1 }", 'value = "500 g" }'), 0, []),
        ("initial-angle-in-kg", sub("initial = 0.1", 'initial = "2 kg"'), 2,
         ["coordinates.theta.initial", "dimension M", "angle"]),
        ("initial-angle-in-m", sub("initial = 0.1", 'initial = "2 m"'), 2, ["coordinates.theta", "angle"]),
        ("rate-angle-in-m-per-s", sub("rate = 0", 'rate = "2 m/s"'), 2, ["coordinates.theta.rate", "dimension L"]),
        ("initial-ok-degrees", sub("initial = 0.1", 'initial = "10 deg", unit = "rad"'), 0, []),
        ("initial-length-in-degrees", sub('initial = 0, rate = 1', 'initial = "30 deg", rate = 1', BLOCK), 2,
         ["coordinates.x", "length"]),
        ("start-angle-in-kg", PENDULUM + '[[ask.question]]\nkind = "integral"\nstart = { theta = "3 kg" }\n', 2,
         ["ask.question[0].start.theta", "dimension M"]),
        ("start-rate-in-m", PENDULUM + '[[ask.question]]\nkind = "integral"\nstart = { "dot(theta)" = "3 m" }\n',
         2, ["ask.question[0].start", "dimension L"]),
        ("start-tower", PENDULUM + '[[ask.question]]\nkind = "integral"\nstart = { theta = "1 rad^9^9^9" }\n', 2,
         ["ask.question[0].start.theta", "towers"]),
        ("start-ok", PENDULUM + '[[ask.question]]\nkind = "integral"\nstart = { theta = "30 deg", '
                                '"dot(theta)" = "1 rad/s" }\n', 0, []),
    ]


def _expression_cases():
    force = '[loads]\ngravity = { type = "gravity", g = "g" }\npush = { type = "force", point = "G", vector = "{}" }'

    def load(vector):
        return sub('[loads]\ngravity = { type = "gravity", g = "g" }', force.replace("{}", vector))

    return [
        ("expr-3-to-100", load("3**100*Ex"), 2, ["loads.push.vector", "too large a number"]),
        ("expr-symbol-to-100", load("(theta + 1)**100*Ex"), 2, ["loads.push.vector", "at most 12"]),
        ("expr-symbol-to-minus-100", load("theta**-100*Ex"), 2, ["loads.push.vector", "at most 12"]),
        ("expr-combined-power", load("((theta + 1)**10)**10*Ex"), 2, ["loads.push.vector", "combined exponent"]),
        ("expr-exp-of-huge", load("exp(10**10)*Ex"), 2, ["loads.push.vector", "too large a number"]),
        ("expr-sin-exp-huge", load("sin(exp(10**7))*Ex"), 2, ["loads.push.vector", "too large"]),
        ("expr-nested-functions", load("sin(cos(sin(cos(sin(theta)))))*Ex"), 2,
         ["loads.push.vector", "nested more than 4 deep"]),
        ("expr-huge-literal", load("1e60*Ex"), 2, ["loads.push.vector", "too large"]),
        ("expr-huge-product", load("1e30*1e30*Ex"), 2, ["loads.push.vector", "too large"]),
        ("expr-ddot-in-load", load("m*ddot(theta)*Ex"), 2, ["loads.push.vector", "ddot(theta)", "acceleration"]),
        ("expr-ddot-in-offset", sub('offset = "-l/2*R.y"', 'offset = "-ddot(theta)*R.y"'), 2,
         ["points.G.offset", "acceleration"]),
        ("expr-acos-2-friction", sub('friction = "mu"', 'friction = "acos(2)"', BLOCK), 2,
         ["constraints.floor.friction", "complex"]),
        ("expr-log-negative", sub('stiffness = "k"', 'stiffness = "log(1 - 2*k)"', BLOCK), 2,
         ["loads.spring.stiffness", "complex"]),
        ("expr-log-zero", load("log(0)*Ex"), 2, ["loads.push.vector", "infinite or undefined"]),
        ("expr-dot-in-load-ok", load("-m*l*dot(theta)**2*R.x"), 0, []),      # a force (issue 26: dimensions)
        ("expr-ddot-in-question-ok", PENDULUM + '[[ask.question]]\nkind = "value"\nexpression = "ddot(theta)"\n'
                                                'at = { theta = 0.5 }\n', 0, []),
        ("expr-big-constant-ok", load("6.67*10**-11*m*g*Ex"), 0, []),
    ]


def _value_cases():
    return [
        ("negative-mass-expr", sub('mass = "m"', 'mass = "-m"'), 2, ["bodies.rod", "mass", "positive"]),
        ("zero-mass", sub('mass = "m"', "mass = 0"), 2, ["bodies.rod", "mass", "must be positive"]),
        ("negative-length-expr", sub('length = "l"', 'length = "-l"'), 2, ["bodies.rod", "length", "positive"]),
        ("zero-length-expr", sub('length = "l"', 'length = "l - l"'), 2, ["bodies.rod", "length", "positive"]),
        ("negative-length-after-values", sub('length = "l"', 'length = "l - 2"'), 2,
         ["bodies.rod", "length", "-1", "with the parameters' values"]),
        ("mass-not-real", sub('mass = "m"', 'mass = "m*sqrt(-1)"'), 2, ["bodies.rod.mass", "complex"]),
        ("negative-radius", sub('radius = "r", friction', 'radius = "-r", friction', BLOCK), 2,
         ["constraints.floor", "radius", "zero or positive"]),
        ("negative-disk-radius", sub('radius = "r", frame', 'radius = "-r", frame', BLOCK), 2,
         ["bodies.disk", "radius", "positive"]),
        ("negative-mu", sub('friction = "mu"', 'friction = "-mu"', BLOCK), 2,
         ["constraints.floor", "friction coefficient", "zero or positive"]),
        ("negative-mu-value", sub("value = 0.3 }", "value = -0.3, positive = false }", BLOCK), 2,
         ["constraints.floor", "friction coefficient", "-0.3"]),
        ("negative-stiffness", sub('stiffness = "k"', 'stiffness = "-k"', BLOCK), 2,
         ["loads.spring", "stiffness", "zero or positive"]),
        ("negative-natural-length", sub("natural_length = 0", "natural_length = -1", BLOCK), 2,
         ["loads.spring", "natural length"]),
        ("negative-g", sub('g = "g"', 'g = "-g"'), 2, ["loads.gravity", "gravitational acceleration"]),
        ("negative-positive-parameter", sub("value = 1 }", "value = -1 }"), 2,
         ["parameters.m", "positive parameter", "positive = false"]),
        ("zero-positive-parameter", sub("value = 9.81", "value = 0"), 2, ["parameters.g", "positive parameter"]),
        ("infinite-parameter", sub("value = 9.81", "value = inf"), 2, ["parameters.g.value", "not a finite"]),
        ("huge-parameter", sub("value = 9.81", "value = 1e300"), 2, ["parameters.g", "too large"]),
        ("negative-real-parameter-ok", sub("value = 9.81", "value = -9.81, positive = false"), 2,
         ["loads.gravity", "-9.81"]),
        ("negative-circle-radius", sub('surface = { type = "line", normal = "Ey" }',
                                       'surface = { type = "circle", radius = "-1", inside = true }', BLOCK), 2,
         ["constraints.floor", "radius", "positive"]),
        ("negative-plate-side", sub('shape = "slender_rod", mass = "m", length = "l", axis = "y"',
                                    'shape = "plate", mass = "m", a = "-l", b = "l"'), 2,
         ["bodies.rod", "a of the rectangular plate", "positive"]),
        ("question-set-negative-mass", PENDULUM + '[[ask.question]]\nkind = "equilibrium"\nset = { m = -2 }\n', 2,
         ["ask.question[0].set.m", "must be zero or positive"]),
        ("question-set-acos", PENDULUM + '[[ask.question]]\nkind = "equilibrium"\nset = { l = "acos(2)" }\n', 2,
         ["ask.question[0].set.l", "complex"]),
        ("question-set-wrong-unit", PENDULUM + '[[ask.question]]\nkind = "equilibrium"\nset = { l = "2 kg" }\n', 2,
         ["ask.question[0].set.l", "dimension M"]),
        ("block-ok", BLOCK, 0, []),
    ]


def _name_cases():
    def param(name):
        return add("parameters", f'{name} = {{ unit = "m" }}')

    return [
        ("name-q-theta", add("coordinates", 'q_theta = { sense = "s" }'), 2,
         ["coordinates.q_theta", "name rigidkin makes itself"]),
        ("name-u-theta", add("coordinates", 'u_theta = { sense = "s" }'), 2, ["coordinates.u_theta", "rigidkin"]),
        ("name-X0", param("X0"), 2, ["parameters.X0", "rigidkin makes itself"]),
        ("name-sigma", param("sigma_O"), 2, ["parameters.sigma_O", "rigidkin makes itself"]),
        ("name-Delta-t", param("Delta_t"), 2, ["parameters.Delta_t"]),
        ("name-reaction-hat", param("R_Ox_hat"), 2, ["parameters.R_Ox_hat", "from R_Ox"]),
        ("name-dot-end", param("theta_dot_end"), 2, ["parameters.theta_dot_end", "from theta"]),
        ("name-homoglyph-cyrillic", param('"m\u0430"'), 2, ["non-ASCII", "U+0430"]),
        ("name-homoglyph-greek-point", add("points", '"\u039f" = { offset = "l*R.x" }'), 2,
         ["non-ASCII", "U+039F"]),
        ("name-basis-homoglyph", sub('basis = ["er", "et", "ez"]', 'basis = ["\u0435r", "et", "ez"]'), 2,
         ["frames.R.basis[0]", "non-ASCII", "U+0435"]),
        ("name-fullwidth", param('"\uff4d"'), 2, ["non-ASCII"]),
        ("name-c-keyword", param("double"), 2, ["parameters.double", "C keyword"]),
        ("name-c-library", param("system"), 2, ["parameters.system", "C keyword or C library"]),
        ("name-python-keyword", param("lambda"), 2, ["parameters.lambda", "Python keyword"]),
        ("name-soft-keyword", param("match"), 2, ["parameters.match", "keyword"]),
        ("name-too-long", param("a" * 65), 2, ["65 characters long"]),
        ("name-body-with-space", sub("rod = { shape", '"the rod" = { shape').replace('body_a = "rod"',
                                                                                   'body_a = "the rod"'), 2,
         ["not a valid name for a body"]),
        ("name-load-with-comment", sub("gravity = { type", '"g*/x" = { type'), 2, ["not a valid name for a load"]),
        ("name-constraint-hyphen", sub('O = { type = "pin"', '"pin-O" = { type = "pin"'), 2,
         ["not a valid name for a constraint"]),
        ("problem-name-c-comment", sub('title = "Pendulum"', 'title = "Pendulum"\nname = "x */ int system(); /*"'),
         2, ["line 2, name", "not a valid problem name"]),
        ("problem-name-path", sub('title = "Pendulum"', 'title = "Pendulum"\nname = "../../etc/passwd"'), 2,
         ["not a valid problem name"]),
        ("problem-name-ok", sub('title = "Pendulum"', 'title = "Pendulum"\nname = "heavy-top_2"'), 0, []),
    ]


CASES = _structure_cases() + _unit_cases() + _expression_cases() + _value_cases() + _name_cases()


def test_cases_are_many_and_distinct():
    assert len(CASES) >= 100
    assert len({c[0] for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=lambda c: c[0])
def test_problem_file(case, tmp_path, capsys):
    name, text, expected, words = case
    code, out, err, f = run_file(text, tmp_path, capsys)
    assert code == expected, (name, err)
    if expected == 2:
        assert err.startswith("rigidkin: ") and "\n" not in err and "Traceback" not in err, err
        assert str(f) in err, err
        for w in words:
            assert w in err, (name, w, err)
    else:
        assert "valid" in out, out


def test_problem_name_from_file_name_is_made_safe(tmp_path, capsys):
    code, out, err, f = run_file(PENDULUM, tmp_path, capsys, name="my pendulum (v2).toml")
    assert code == 0, err
    from rigidkin.io.problem import load_problem

    system, spec = load_problem(f)
    assert spec.name == "my_pendulum__v2_" == system.name


def test_chain_of_30_frames_and_points_validates_fast(tmp_path, capsys):
    """A planar chain of 30 links, each frame turned from the last one: direction cosines stay short."""
    n = 30
    lines = ['title = "chain"', "[parameters]", 'l = { unit = "m", value = 1 }', 'm = { unit = "kg", value = 1 }',
             "[coordinates]"] + [f'q{i} = {{ sense = "angle of link {i} from link {i - 1}" }}' for i in range(n)]
    lines += ["[frames]"] + [f'A{i} = {{ parent = "{"F" if i == 0 else f"A{i - 1}"}", angle = "q{i}" }}'
                             for i in range(n)]
    lines += ["[points]"] + [f'P{i} = {{ from = "{"O" if i == 0 else f"P{i - 1}"}", offset = "l*A{i}.x" }}'
                             for i in range(n)]
    lines += ["[bodies]"] + [f'b{i} = {{ shape = "point_mass", mass = "m", frame = "A{i}", at = "P{i}" }}'
                             for i in range(n)]
    f = tmp_path / "chain.toml"
    f.write_text("\n".join(lines) + "\n")
    start = time.process_time()
    with bounded("chain"):
        code = main(["validate", str(f)])
    out, err = capsys.readouterr()
    assert code == 0, err
    assert "30 bodies, 30 coordinates" in out
    assert time.process_time() - start < CPU_LIMIT


def test_deep_chain_positions_are_right():
    """The closed-form direction cosines of a chain give the same positions as the links added one by one."""
    s = rk.System("chain")
    l = s.parameter("l", "m")
    qs = [s.coordinate(f"q{i}", "angle") for i in range(12)]
    parent, point, angle = s.inertial, s.origin, 0
    for i, q in enumerate(qs):
        parent = s.frame(f"A{i}", parent, angle=q)
        point = s.point(f"P{i}", point, l * parent.x)
        angle = angle + q
    values = {q: 0.1 * (i + 1) for i, q in enumerate(qs)}
    values[l] = 1.0
    r = point.position()
    x, y = float(r.dot(s.inertial.x).subs(values)), float(r.dot(s.inertial.y).subs(values))
    import math

    total, ex, ey = 0.0, 0.0, 0.0
    for i in range(12):
        total += 0.1 * (i + 1)
        ex, ey = ex + math.cos(total), ey + math.sin(total)
    assert abs(x - ex) < 1e-12 and abs(y - ey) < 1e-12


# --- the same rules through the Python API ---------------------------------------------------------------------
def _api_cases():
    def pendulum():
        s = rk.System("pendulum")
        m, l = s.parameter("m", "kg"), s.parameter("l", "m")
        th = s.coordinate("theta", "angle")
        R = s.frame("R", angle=th)
        G = s.point("G", offset=-l / 2 * R.y)
        return s, m, l, th, R, G

    def body(mass_of, length_of):
        s, m, l, th, R, G = pendulum()
        s.body("rod", rk.shapes.SlenderRod(mass_of(m), length_of(l), axis="y"), frame=R, at=G)

    def with_values(length):
        s = rk.System("p")
        m, l = s.parameter("m", "kg", value=1), s.parameter("l", "m", value=1)
        th = s.coordinate("theta", "angle")
        R = s.frame("R", angle=th)
        s.body("rod", rk.shapes.SlenderRod(m, length(l), axis="y"), frame=R, at=s.point("G", offset=l * R.y))

    def contact(radius=None, friction="smooth"):
        s, m, l, th, R, G = pendulum()
        rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
        s.contact("A", rod, s.line(s.origin, s.inertial.y), radius=radius if radius is not None else 0,
                  friction=friction)

    def spring(k):
        s, m, l, th, R, G = pendulum()
        s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
        s.spring("k", G, s.origin, k)

    def solve_negative():
        s, m, l, th, R, G = pendulum()
        s.pin("O", s.origin, s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G))
        s.solve(substitutions={m: -1})

    return [
        ("api-negative-mass", lambda: body(lambda m: -m, lambda l: l), ["mass", "positive"]),
        ("api-zero-length", lambda: body(lambda m: m, lambda l: 0), ["length", "positive"]),
        ("api-complex-length", lambda: body(lambda m: m, lambda l: l * sp.acos(2)), ["length", "real"]),
        ("api-length-after-values", lambda: with_values(lambda l: l - 3), ["length", "-2"]),
        ("api-negative-radius", lambda: contact(radius=-1), ["radius", "zero or positive"]),
        ("api-negative-mu", lambda: contact(friction=-0.2), ["friction coefficient", "zero or positive"]),
        ("api-mu-acos", lambda: contact(friction=sp.acos(2)), ["friction coefficient", "real"]),
        ("api-negative-stiffness", lambda: spring(-5), ["stiffness", "zero or positive"]),
        ("api-parameter-negative-value", lambda: rk.System("s").parameter("m", "kg", value=-1), ["positive"]),
        ("api-parameter-unit-tower", lambda: rk.System("s").parameter("m", "kg^9^9"), ["towers"]),
        ("api-parameter-unit-lambda", lambda: rk.System("s").parameter("m", "lambda: kg"), ["':'"]),
        ("api-initial-in-kg", lambda: rk.System("s").coordinate("theta", "angle", initial="2 kg"), ["dimension M"]),
        ("api-homoglyph-name", lambda: rk.System("s").parameter("\u0430", "kg"), ["non-ASCII"]),
        ("api-generated-name", lambda: rk.System("s").coordinate("q_theta", "angle"), ["rigidkin makes itself"]),
        ("api-c-keyword-name", lambda: rk.System("s").coordinate("int", "angle"), ["C keyword"]),
        ("api-solve-negative-substitution", solve_negative, ["value given for m", "zero or positive"]),
        ("api-string-expression", lambda: rk.System("s").gravity("9.81"), ["string"]),
    ]


@pytest.mark.parametrize("case", _api_cases(), ids=lambda c: c[0])
def test_python_api(case):
    name, build, words = case
    with bounded(name), pytest.raises(RigidkinError) as err:
        build()
    for w in words:
        assert w in str(err.value), (name, w, str(err.value))


# --- the quantity reader the command line uses --------------------------------------------------------------
@pytest.mark.parametrize("text, dimension, expected", [
    ("30 deg", ONE, 0.5235987755982988), ("2 ft", LENGTH, 0.6096), ("9.81", None, 9.81), ("-0.5 m", LENGTH, -0.5),
    ("1 rad/s", ONE / rk.units.TIME, 1.0), ("250 g", None, 0.25),
])
def test_parse_quantity_reads(text, dimension, expected):
    assert parse_quantity(text, where="--set x", dimension=dimension) == pytest.approx(expected)


@pytest.mark.parametrize("text", ["9^9^9^9 kg", "1 m<2", "~m", "lambda: 0", "1 kg**100", "1e999", "nan", "2 kg m s 5",
                                  "(((((m)))))", "1 " + "m*" * 40 + "m", "x" * 200, "1 m; import os", "1 __class__"])
def test_parse_quantity_refuses(text):
    with bounded(text[:20]), pytest.raises(InputError) as err:
        parse_quantity(text, where="--initial theta")
    assert str(err.value).startswith("--initial theta: ")


def test_parse_quantity_checks_the_dimension():
    with pytest.raises(InputError, match="angle"):
        parse_quantity("3 kg", where="--initial theta", dimension=ONE)


# --- hypothesis over the fields of a problem file ----------------------------------------------------------------
_TEXT = st.text(alphabet=st.characters(codec="utf-8", exclude_categories=("Cs",)), max_size=40)
_NUMBERS = st.one_of(st.integers(-10**50, 10**50), st.floats(allow_nan=True, allow_infinity=True))
_UNITS = st.one_of(_TEXT, st.sampled_from(["kg", "m", "s", "N/m", "m/s^2", "kg*m^2", "deg", "1/s", "kg^2^2",
                                           "m**99", "<", "(m", "m)", "m/", "*m", "lambda: m"]))
_EXPRS = st.one_of(_TEXT, _NUMBERS, st.sampled_from(["-m", "0", "m - 5", "acos(2)", "log(-m)", "sqrt(-l)", "1e60",
                                                     "3**100", "(l + 1)**50", "ddot(theta)", "exp(10**10)", "l/0",
                                                     "sin(cos(tan(exp(log(l)))))", "m*l", "2*l"]))
_FIELD = st.sampled_from([
    ('unit = "kg", value = 1', "unit = {}, value = 1", _UNITS),
    ('unit = "kg", value = 1', 'unit = "kg", value = {}', st.one_of(_NUMBERS, _TEXT)),
    ("initial = 0.1", "initial = {}", st.one_of(_NUMBERS, _TEXT)),
    ("rate = 0", "rate = {}", st.one_of(_NUMBERS, _TEXT)),
    ('mass = "m"', "mass = {}", _EXPRS),
    ('length = "l"', "length = {}", _EXPRS),
    ('angle = "theta"', "angle = {}", _EXPRS),
    ('g = "g"', "g = {}", _EXPRS),
    ('offset = "-l/2*R.y"', "offset = {}", _EXPRS),
    ('basis = ["er", "et", "ez"]', 'basis = [{}, "et", "ez"]', _TEXT),
])


def _toml(value) -> str:
    if isinstance(value, str):
        return '"' + value.encode("unicode_escape").decode("ascii").replace('"', '\\"') + '"'
    if isinstance(value, float) and value != value:
        return "nan"
    if isinstance(value, float) and value in (float("inf"), float("-inf")):
        return "inf" if value > 0 else "-inf"
    return repr(value)


@pytest.mark.slow
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(field=_FIELD, data=st.data())
def test_hypothesis_fields(field, data):
    old, template, values = field
    value = data.draw(values)
    text = sub(old, template.format(_toml(value)))
    with bounded(f"{template} {value!r}"[:60]):
        try:
            parse_problem(text, "fuzz.toml")
        except (InputError, ModelError, RigidkinError) as exc:
            message = str(exc)
            assert message.startswith("fuzz.toml") and "\n" not in message.strip(), message
