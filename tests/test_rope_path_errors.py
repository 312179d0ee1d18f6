"""A rope path entry with a wrong pulley table is reported at its own field, not as "not a string"."""

from __future__ import annotations

import pytest
import sympy as sp

from rigidkin.base.errors import InputError
from rigidkin.io.problem import parse_problem

ATWOOD_FILE = """
title = "Atwood machine with a massive pulley"
[parameters]
m1 = { unit = "kg", value = 3 }
m2 = { unit = "kg", value = 1 }
M = { unit = "kg", value = 2 }
R = { unit = "m", value = 0.1 }
g = { unit = "m/s^2", value = 9.81 }
[coordinates]
y1 = { sense = "depth of block 1 below the axle", kind = "length", initial = 1, rate = 0 }
y2 = { sense = "depth of block 2 below the axle", kind = "length", initial = 1 }
phi = { sense = "pulley rotation, counter-clockwise" }
[frames]
P = { angle = "phi" }
[points]
A = { offset = "-R*Ex - y1*Ey" }
B = { offset = "R*Ex - y2*Ey" }
[bodies]
pulley = { shape = "disk", mass = "M", radius = "R", frame = "P", at = "O" }
block1 = { shape = "point_mass", mass = "m1", frame = "F", at = "A" }
block2 = { shape = "point_mass", mass = "m2", frame = "F", at = "B" }
[constraints]
axle = { type = "pin", point = "O", body_a = "pulley" }
rope = { type = "rope", path = ["A", { pulley = "pulley", radius = "R", sense = "cw" }, "B"], tensions = ["T1", "T2"] }
[loads]
gravity = { type = "gravity", g = "g" }
"""
ROPE_LINE = 1 + next(i for i, line in enumerate(ATWOOD_FILE.splitlines()) if line.startswith("rope ="))


def _error(text: str) -> str:
    with pytest.raises(InputError) as info:
        parse_problem(text, "atwood.toml")
    message = str(info.value)
    assert "\n" not in message and "Traceback" not in message
    return message


@pytest.mark.parametrize("word", ["anticlockwise", "left", "CW"])
def test_misspelt_sense_names_the_field_and_the_words(word):
    message = _error(ATWOOD_FILE.replace('sense = "cw" }', f'sense = "{word}" }}'))
    assert f"atwood.toml, line {ROPE_LINE}" in message
    assert "constraints.rope.path[1].sense" in message
    assert '"cw"' in message and '"ccw"' in message and repr(word) in message
    assert "valid string" not in message and "got dict" not in message


def test_other_pulley_table_errors_are_at_their_own_field():
    message = _error(ATWOOD_FILE.replace('radius = "R", sense', 'rdius = "R", sense'))
    assert "constraints.rope.path[1].radius" in message and "missing" in message
    message = _error(ATWOOD_FILE.replace('{ pulley = "pulley"', '{ body = "pulley"'))
    assert "constraints.rope.path[1].pulley" in message and "missing" in message
    message = _error(ATWOOD_FILE.replace('"B"], tensions', '3], tensions'))
    assert "constraints.rope.path[2]" in message and "point name" in message and "pulley table" in message


def test_a_correct_file_still_loads():
    """Atwood machine with a disk pulley, by hand (Newton for each block, Euler for the pulley, no slip):
    ÿ1 = (m1 − m2) g/(m1 + m2 + M/2)."""
    system, _ = parse_problem(ATWOOD_FILE, "atwood.toml")
    sol = system.solve()
    m1, m2, M, g = (system.parameters[n] for n in ("m1", "m2", "M", "g"))
    y1 = system.coordinates[0]
    assert sp.simplify(sol.accelerations[y1] - (m1 - m2) * g / (m1 + m2 + M / 2)) == 0
