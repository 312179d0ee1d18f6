"""Quantities with units in every expression field of a problem file and in the time options of the command line.

Each value is checked against its SI value worked by hand (1 ft = 0.3048 m exactly, 1 in = 0.0254 m, 1 lb =
0.45359237 kg, 30° = π/6); a quantity of the wrong dimension is refused with the field's place in the file."""

import argparse
from pathlib import Path

import pytest
import sympy as sp

from rigidkin.base.errors import InputError
from rigidkin.commands.options import end_time, start_time, timeout
from rigidkin.io.problem import parse_problem

LADDER = (Path(__file__).parents[1] / "examples" / "ladder.toml").read_text()


def build(old, new):
    assert old in LADDER
    return parse_problem(LADDER.replace(old, new, 1), "units.toml")[0]


@pytest.mark.parametrize("old,new,get,si", [
    ('length = "l"', 'length = "2 ft"', lambda s: s.bodies["rod"].shape.length, sp.Rational(6096, 10000)),
    ('length = "l"', 'length = "10 cm"', lambda s: s.bodies["rod"].shape.length, sp.Rational(1, 10)),
    ('mass = "m"', 'mass = "500 g"', lambda s: s.bodies["rod"].shape.mass, sp.Rational(1, 2)),
    ('mass = "m"', 'mass = "3 lb"', lambda s: s.bodies["rod"].shape.mass, 3 * sp.Rational(45359237, 10**8)),
    ('g = "g"', 'g = "32.2 ft/s^2"', lambda s: s.loads["gravity"].g, sp.Rational(322, 10) * sp.Rational(3048, 10**4)),
    ('g = "g"', 'g = "981 cm/s^2"', lambda s: s.loads["gravity"].g, sp.Rational(981, 100)),
])
def test_a_quantity_alone_is_its_si_value(old, new, get, si):
    assert sp.simplify(get(build(old, new)) - si) == 0


def test_a_quantity_inside_an_expression():
    s = build('offset = "l/2*ey"', 'offset = "(l/2 + 5 cm)*ey + 1 in*ex"')
    R = s.frames["R"]
    l = s.parameters["l"]
    expected = (l / 2 + sp.Rational(5, 100)) * R.y + sp.Rational(254, 10**4) * R.x
    assert (s.points["G"].offset - expected).simplify() == 0 * R.x


def test_an_angle_in_degrees_is_exact():
    s = build('angle = "theta"', 'angle = "theta + 30 deg"')
    theta = s.coordinates[0] if isinstance(s.coordinates, list | tuple) else next(iter(s.coordinates.values()))
    assert sp.simplify(s.frames["R"].angle - (theta + sp.pi / 6)) == 0


def test_a_quantity_times_a_time_is_checked_with_its_unit():
    """0.5 m/s times t is a length: accepted in an offset (the later check of the model does not see the unit)."""
    s = build('offset = "l/2*ey"', 'offset = "(l/2 + 0.5 (m/s)*t)*ey"')
    l, t = s.parameters["l"], sp.Symbol("t")
    comp = s.points["G"].offset.dot(s.frames["R"].y)
    assert sp.simplify(comp.subs({l: 2}).subs({c: t for c in comp.free_symbols if c.name == "t"}) - (1 + t / 2)) == 0


@pytest.mark.parametrize("old,new,field,words", [
    ('mass = "m"', 'mass = "500 cm"', "bodies.rod.mass", "a mass"),
    ('length = "l"', 'length = "2 kg"', "bodies.rod.length", "a length"),
    ('g = "g"', 'g = "9.81 m/s"', "loads.gravity.g", "an acceleration"),
    ('offset = "l/2*ey"', 'offset = "(l/2 + 5 kg)*ey"', "points.G.offset", "5 kg"),
    ('angle = "theta"', 'angle = "theta + 30 cm"', "frames.R.angle", "30 cm"),
])
def test_a_wrong_dimension_is_refused_naming_the_field(old, new, field, words):
    with pytest.raises(InputError) as err:
        build(old, new)
    text = str(err.value)
    assert field in text and words in text


@pytest.mark.parametrize("new,words", [
    ('offset = "(l/2 + 5 cm/s)*ey"', "parentheses"),
    ('offset = "(l/2 + 5 foo)*ey"', "'foo' follows a number but is not a unit"),
])
def test_an_unreadable_quantity_is_refused_clearly(new, words):
    with pytest.raises(InputError) as err:
        build('offset = "l/2*ey"', new)
    assert words in str(err.value) and "points.G.offset" in str(err.value)


def test_constraint_and_load_fields_take_units():
    text = '''
title = "disk on a spring"
[parameters]
m = { unit = "kg", value = 2 }
[coordinates]
x = { sense = "along Ex", kind = "length" }
phi = { sense = "turn" }
[frames]
D = { angle = "phi" }
[points]
C = { from = "O", offset = "x*Ex + 10 cm*Ey", body = "disk" }
[bodies.disk]
shape = "disk"
mass = "m"
radius = "10 cm"
frame = "D"
at = "C"
[constraints.floor]
type = "contact"
body = "disk"
surface = { type = "line", point = "O", normal = "Ey" }
centre = "C"
radius = "100 mm"
friction = "rolling"
[loads.g]
type = "gravity"
g = "9.81 m/s^2"
[loads.spring]
type = "spring"
point_a = "C"
body_a = "disk"
point_b = "O"
stiffness = "2 N/cm"
natural_length = "1 ft"
'''
    s = parse_problem(text, "disk.toml")[0]
    assert s.constraints["floor"].radius == sp.Rational(1, 10)
    assert s.loads["spring"].stiffness == 200                       # 2 N/cm = 200 N/m
    assert s.loads["spring"].natural_length == sp.Rational(3048, 10**4)
    with pytest.raises(InputError) as err:
        parse_problem(text.replace('stiffness = "2 N/cm"', 'stiffness = "2 N"'), "disk.toml")
    assert "loads.spring.stiffness" in str(err.value) and "stiffness" in str(err.value)
    with pytest.raises(InputError) as err:
        parse_problem(text.replace('radius = "100 mm"', 'radius = "100 s"'), "disk.toml")
    assert "constraints.floor.radius" in str(err.value)


@pytest.mark.parametrize("fn,text,si", [(end_time, "500 ms", 0.5), (end_time, "2 min", 120.0), (end_time, "3", 3.0),
                                        (timeout, "10 min", 600.0), (start_time, "-2 ms", -0.002)])
def test_time_options_take_units(fn, text, si):
    assert fn(text) == pytest.approx(si, rel=1e-15)


@pytest.mark.parametrize("text", ["5 m", "2 kg", "abc", "nan"])
def test_a_time_option_refuses_what_is_not_a_time(text):
    with pytest.raises(argparse.ArgumentTypeError) as err:
        end_time(text)
    assert repr(text) in str(err.value)


def test_question_equations_take_units():
    """An event 'theta = 30 deg' is theta = π/6; a length for the angle is refused naming the question."""
    old = 'when = "N_A = 0"'
    _, spec = parse_problem(LADDER.replace(old, 'when = "theta = 30 deg"'), "units.toml")
    (when,) = [q.fields["when"] for q in spec.questions if "when" in q.fields]
    assert sp.simplify(when.rhs - sp.pi / 6) == 0 and when.lhs.func.__name__ == "theta"
    with pytest.raises(InputError) as err:
        parse_problem(LADDER.replace(old, 'when = "N_A = 2 kg"'), "units.toml")
    assert "ask.question[1].when" in str(err.value) and "2 kg" in str(err.value)


def test_a_quantity_in_a_definition_is_refused_clearly():
    text = LADDER.replace("[coordinates]", '[definitions]\na = { value = "l/2 + 5 cm", unit = "m" }\n[coordinates]')
    with pytest.raises(InputError) as err:
        parse_problem(text, "units.toml")
    assert "definitions.a.value" in str(err.value) and "parameter" in str(err.value)


def test_a_bare_number_in_an_inner_sum_is_in_si_units():
    """(l/2 + 0.1)·cos θ: the 0.1 is 0.1 m, as a bare number at the top of a field is; 5 kg there is refused."""
    s = build('offset = "l/2*ey"', 'offset = "(l/2 + 0.1)*cos(theta)*ey"')
    assert s.points["G"].offset != 0
    with pytest.raises(InputError) as err:
        build('offset = "l/2*ey"', 'offset = "(l/2 + 5 kg)*cos(theta)*ey"')
    assert "points.G.offset" in str(err.value) and "5 kg" in str(err.value)


def test_an_expression_with_too_many_quantities_is_refused():
    many = "+".join(["1cm"] * 150)                       # 599 characters: within the parser's 1000
    with pytest.raises(InputError) as err:
        build('length = "l"', f'length = "{many}"')
    assert "bodies.rod.length" in str(err.value) and "more than 100 quantities" in str(err.value)


def test_simulate_takes_an_end_time_with_a_unit(capsys):
    """--t-end "300 ms" ends where --t-end 0.3 does; --t-end "3 m" is refused as not a time (status 2)."""
    import json

    from rigidkin.cli import main

    finals = []
    for t_end in ("300 ms", "0.3"):
        assert main(["simulate", "ladder", "--t-end", t_end, "--json", "--points", "5", "--initial", "theta=0.3"]) == 0
        finals.append(json.loads(capsys.readouterr().out)["final_state"])
    assert finals[0] == finals[1]
    assert main(["simulate", "ladder", "--t-end", "3 m"]) == 2
    assert "is not a time" in capsys.readouterr().err
