"""Issue 26, point 8: dimensions are checked by every command that derives, before it derives.

A force written in N/m (and every other field of the wrong dimension) is an error naming its load, field
and term, raised by ``solve`` (and ``simulate``, ``report``, ...), not only by ``check``; a parameter with no
unit is a warning unless declared dimensionless (``unit = "1"``, ``unit = ""``, ``dimension =
"dimensionless"``).  References: the dimensions of the units worked out by hand (N/m = kg/s², N = kg·m/s²),
and every bundled card, whose units are right, passes the check.
"""

from __future__ import annotations

import tomllib
import warnings
from pathlib import Path

import pytest
import sympy as sp

import rigidkin as rk
from rigidkin import examples
from rigidkin.base.errors import InputError, ModelError
from rigidkin.cli import main
from rigidkin.io.problem import build_problem, load_problem
from rigidkin.model.dimension_checks import check_input_dimensions, input_dimension_errors

BASE = """
title = "Pendulum pushed"
[parameters]
m = {{ unit = "kg", value = 1 }}
l = {{ unit = "m", value = 2 }}
g = {{ unit = "m/s^2", value = 9.81 }}
{extra}
[coordinates]
theta = {{ sense = "angle from the downward vertical, counter-clockwise", initial = 0.2 }}
[frames]
R = {{ angle = "theta" }}
[points]
G = {{ offset = "{offset}" }}
[bodies]
rod = {{ shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }}
[constraints]
O = {{ type = "pin", point = "O", body_a = "rod" }}
[loads]
gravity = {{ type = "gravity", g = "g" }}
{loads}
"""


SPRING = 'spring = { type = "spring", point_a = "G", point_b = "O", body_a = "rod", stiffness = "k" }'


def _text(extra="", loads="", offset="-l/2*R.y"):
    return BASE.format(extra=extra, loads=loads, offset=offset)


def _build(**kw):
    text = _text(**kw)
    return build_problem(tomllib.loads(text), text, "pushed.toml")


@pytest.mark.parametrize("extra, loads, field, term, got", [
    # a force in N/m: dimension kg/s² (N/m = kg·m/s² / m), named with its term
    ('F = { unit = "N/m", value = 3 }', 'push = { type = "force", point = "G", vector = "F*Ex" }',
     "loads.push.vector", "the term F", "M·T^-2 (kg/s^2)"),
    # one term of a sum in N/m: the sum is inconsistent, both terms named
    ('F = { unit = "N/m", value = 3 }', 'push = { type = "force", point = "G", vector = "m*g*Ex + F*Ey" }',
     "loads.push.vector", "F", "M·T^-2"),
    # a spring's stiffness in N (kg·m/s²) where N/m (kg/s²) is expected
    ('k = { unit = "N", value = 10 }', SPRING,
     "loads.spring.stiffness", "the term k", "M·L·T^-2 (kg*m/s^2)"),
    # a torque in N (a force)
    ('T0 = { unit = "N", value = 1 }', 'drive = { type = "torque", body = "rod", vector = "T0*Ez" }',
     "loads.drive.vector", "the term T₀", "M·L·T^-2"),
])
def test_a_load_of_the_wrong_dimension_is_an_error(extra, loads, field, term, got):
    with pytest.raises(InputError) as err:
        _build(extra=extra, loads=loads)
    msg = str(err.value)
    assert field in msg and term in msg and got in msg, msg


def test_an_offset_in_kilograms_is_an_error():
    with pytest.raises(InputError) as err:
        _build(offset="-m*R.y")
    assert "points.G.offset" in str(err.value) and "M (kg)" in str(err.value) and "a length" in str(err.value)


def test_right_units_pass_with_numbers_in_si():
    """Consistent loads pass; a bare number stands for a value in SI (0.1 m added to l/2)."""
    system, _ = _build(extra='F = { unit = "N", value = 3 }\nk = { unit = "N/cm", value = 2 }',
                       loads='push = { type = "force", point = "G", vector = "F*Ex - m*g*Ey" }\n'
                             + SPRING,
                       offset="-(l/2 + 0.1)*R.y")
    assert input_dimension_errors(system) == []


def test_every_bundled_card_passes():
    folder = Path(examples.__file__).parent
    cards = sorted(folder.glob("*.toml"))
    assert len(cards) >= 10
    for card in cards:
        system, _ = load_problem(card)
        assert input_dimension_errors(system) == [], card.name


def test_solve_and_simulate_refuse_a_force_in_newtons_per_metre(tmp_path, capsys):
    path = tmp_path / "pushed.toml"
    path.write_text(_text('F = { unit = "N/m", value = 3 }', 'push = { type = "force", point = "G", vector = "F*Ex" }'))
    for argv in (["solve", str(path)], ["simulate", str(path), "--t-end", "0.1"], ["check", str(path)]):
        assert main(argv + ["--no-cache"]) == 2, argv
        err = capsys.readouterr().err
        assert "loads.push.vector" in err and "the term F" in err and "Traceback" not in err


def test_a_parameter_without_unit_is_a_warning_unless_dimensionless():
    with pytest.warns(UserWarning, match="parameter 'c' has no unit"):
        system, _ = _build(extra="c = { value = 2 }",
                           loads='push = { type = "force", point = "G", vector = "c*Ex" }')   # not checked: unknown
    assert input_dimension_errors(system, [system.parameters["c"]]) == []
    for declared in ('c = { unit = "1", value = 2 }', 'c = { unit = "", value = 2 }',
                     'c = { dimension = "dimensionless", value = 2 }'):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            _build(extra=declared, loads='push = { type = "force", point = "G", vector = "c*m*g*Ex" }')
    # declared dimensionless, a number cannot be a force
    with pytest.raises(InputError, match="loads.push.vector"):
        _build(extra='c = { unit = "1", value = 2 }', loads='push = { type = "force", point = "G", vector = "c*Ex" }')


def test_python_api_can_check_its_model():
    s = rk.System("api")
    m, l, k = s.parameter("m", "kg"), s.parameter("l", "m"), s.parameter("k", "N/m")
    th = s.coordinate("theta")
    R = s.frame("R", angle=th)
    G = s.point("G", offset=-l / 2 * R.y)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
    s.pin("O", s.origin, rod)
    s.force("push", G, k * R.x, body=rod)
    errors = input_dimension_errors(s)
    assert [(e.table, e.name, e.field) for e in errors] == [("loads", "push", "vector")]
    with pytest.raises(ModelError, match="the term k"):
        check_input_dimensions(s)
    assert sp.Symbol("k", positive=True) == k


def test_the_warning_is_said_again_from_the_derivation_cache(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("RIGIDKIN_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("RIGIDKIN_NO_CACHE", raising=False)
    warnings.simplefilter("always")     # each command is a process of its own: every warning is shown
    path = tmp_path / "pushed.toml"
    path.write_text(_text("c = { value = 2 }", 'push = { type = "force", point = "G", vector = "c*m*g*Ex" }'))
    for _ in range(2):               # the second solve reads the derivation cache: the file is not read again
        assert main(["solve", str(path)]) == 0
        assert "parameter 'c' has no unit" in capsys.readouterr().err
    assert main(["simulate", str(path), "--t-end", "0.05"]) == 0
    assert "parameter 'c' has no unit" in capsys.readouterr().err


def test_a_question_whose_terms_cannot_be_added_is_an_error(tmp_path, capsys):
    """The ladder card asking when N_A = m·l (a force against kg·m) is refused, naming both terms."""
    src = Path(examples.__file__).parent / "ladder.toml"
    text = src.read_text()
    assert 'when = "N_A = 0"' in text
    with pytest.raises(InputError) as err:
        build_problem(tomllib.loads(text.replace('when = "N_A = 0"', 'when = "N_A = m*l"')), text, "ladder.toml")
    msg = str(err.value)
    assert "leaves_wall" in msg and "l·m has dimension M·L" in msg and "N_A has M·L·T^-2" in msg, msg
    build_problem(tomllib.loads(text.replace('when = "N_A = 0"', 'when = "N_A = m*g/2"')), text, "ladder.toml")


@pytest.mark.parametrize("old, new, field", [
    ('centre = "O", radius = "R"', 'centre = "O", radius = "m"', "constraints"),  # the track's radius in kg
    ('radius = "r"\n', 'radius = "r*m"\n', "constraints"),             # the contact radius in kg·m
    ('disk = { shape = "disk", mass = "m", radius = "r"', 'disk = { shape = "disk", mass = "m*r", radius = "r"',
     "bodies.disk.mass"),
])
def test_the_disk_in_track_card_with_a_wrong_unit(old, new, field):
    src = Path(examples.__file__).parent / "disk-in-track.toml"
    text = src.read_text()
    assert old in text
    bad = text.replace(old, new, 1)
    with pytest.raises(InputError) as err:
        build_problem(tomllib.loads(bad), bad, "disk-in-track.toml")
    assert field in str(err.value) and "has dimension" in str(err.value)
