"""Issue 26, point 9: every value is shown in the unit it was declared in (or in SI with the SI unit).

A parameter declared ``unit = "cm", value = 200`` is 2 m inside (values are held in SI); every view of it —
the Parameter's repr, the report's table, the notebook view (HTML and LaTeX), the solve text's definitions
and the JSON — shows 200 cm, or 2 with the SI unit m.  The conversions are checked against hand values.
"""

from __future__ import annotations

import json
import math
import re

import pytest

from rigidkin.base.units import LENGTH, ONE, TIME, Dimension, from_si, parse_quantity, shown_value, si_unit
from rigidkin.cli import main
from rigidkin.io.problem import build_problem
from rigidkin.model.system import System

PENDULUM = """
title = "Pendulum in centimetres"
[parameters]
m = { unit = "kg", value = 1 }
l = { unit = "cm", value = 200, description = "length of the rod" }
g = { unit = "m/s^2", value = 9.81 }
c = { unit = "N*m*s", value = 0.5 }
tilt = { unit = "deg", value = 30 }
[definitions]
a = { value = "l/4", unit = "cm", description = "a quarter of the rod" }
[coordinates]
theta = { sense = "angle from the downward vertical, counter-clockwise", initial = "10 deg" }
[frames]
R = { angle = "theta" }
[points]
G = { offset = "-l/2*R.y" }
[bodies]
rod = { shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }
[constraints]
O = { type = "pin", point = "O", body_a = "rod" }
[loads]
gravity = { type = "gravity", g = "g" }
"""


@pytest.fixture(scope="module")
def pendulum():
    import tomllib

    return build_problem(tomllib.loads(PENDULUM), PENDULUM, "cm.toml")


def test_conversions_by_hand():
    assert from_si(2.0, "cm") == pytest.approx(200)
    assert from_si(0.3048, "ft") == pytest.approx(1)               # 1 ft = 0.3048 m exactly
    assert from_si(math.pi / 6, "deg") == pytest.approx(30)
    assert from_si(1.0, "km/h") == pytest.approx(3.6)               # 1 m/s = 3.6 km/h
    assert from_si(1000.0, "g") == pytest.approx(1e6)                # 1000 kg in grams
    assert from_si(9.81, "m/s^2") == pytest.approx(9.81)
    assert from_si(0.7, "") == 0.7 and from_si(0.7, "1") == 0.7 and from_si(None, "cm") is None
    for value, unit in ((200, "cm"), (3, "ft"), (45, "deg"), (12, "N/mm"), (2.5, "lbf")):
        assert from_si(parse_quantity(value, unit), unit) == pytest.approx(value)   # the inverse of reading
    assert si_unit(LENGTH) == "m" and si_unit(ONE) == "" and si_unit(ONE / TIME) == "1/s"
    assert si_unit(Dimension(mass=1, length=1, time=-2)) == "kg*m/s^2"
    assert si_unit(Dimension(mass=1, time=-1, current=-1)) == "kg/(s*A)"
    assert shown_value(2.0, "cm", LENGTH) == "200 cm" and shown_value(2.0, None, LENGTH) == "2 m"
    assert shown_value(0.25, "", ONE) == "0.25" and shown_value(None, "cm", LENGTH) == "—"


def test_parameter_keeps_si_and_shows_its_unit(pendulum):
    system, _ = pendulum
    p = system.parameter_info["l"]
    assert p.value == pytest.approx(2.0)                               # held in SI
    assert p.value_in_unit == pytest.approx(200) and p.shown_value == "200 cm"
    assert "l = 200 cm" in repr(p) and "= 2 " not in repr(p)
    tilt = system.parameter_info["tilt"]
    assert tilt.value == pytest.approx(math.pi / 6) and tilt.shown_value == "30 deg"
    s = System("api")
    s.parameter("L", "mm", value=1500)
    assert s.parameter_info["L"].value == pytest.approx(1.5) and s.parameter_info["L"].shown_value == "1500 mm"
    s.parameter("k", dimension="stiffness", value=40)
    assert s.parameter_info["k"].shown_value == "40 kg/s^2"          # no unit: SI with the SI unit


def _row(html: str, name: str) -> str:
    rows = re.findall(r"<tr>.*?</tr>", html, flags=re.S)
    return next(r for r in rows if f"<mi>{name}</mi>" in r)


def test_notebook_view(pendulum):
    system, _ = pendulum
    row = _row(system._repr_html_(), "l")
    cells = re.findall(r"<td>(.*?)</td>", row, flags=re.S)
    assert "cm" in cells and "200" in cells and "2" not in cells
    tex = system._repr_latex_()
    assert "200 cm" in tex and "(2 cm)" not in tex and "30 deg" in tex


def test_report_table(tmp_path, capsys):
    path = tmp_path / "cm.toml"
    path.write_text(PENDULUM)
    out = tmp_path / "r.md"
    assert main(["report", str(path), "--no-cache", "-o", str(out)]) == 0
    md = out.read_text()
    assert re.search(r"\| \$l\$ \| length of the rod \| cm \| 200 \|", md), md[:2000]
    assert re.search(r"\| \$\\theta\$ .*\| rad \|", md)
    assert re.search(r"a quarter of the rod \| cm \| 50 \|", md)          # a definition: l/4 = 50 cm


def test_solve_text_and_json(tmp_path, capsys):
    path = tmp_path / "cm.toml"
    path.write_text(PENDULUM)
    assert main(["solve", str(path), "--no-cache"]) == 0
    text = capsys.readouterr().out
    assert "= 50 cm" in text and "0.5 cm" not in text                   # the definition a = l/4
    assert main(["solve", str(path), "--no-cache", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    p = data["parameters"]["l"]
    assert p["unit"] == "cm" and p["value_in_unit"] == pytest.approx(200)
    assert p["value"] == pytest.approx(2.0) and p["si_unit"] == "m"    # value stays SI, with its SI unit
    d = data["definitions"]["a"]
    assert d["value"] == pytest.approx(0.5) and d["value_in_unit"] == pytest.approx(50) and d["si_unit"] == "m"


def test_a_coordinate_number_is_in_its_unit():
    """unit = "cm", initial = 5 is 5 cm (0.05 m) and rate = 10 is 10 cm/s, as a parameter's value is in its unit;
    a quantity keeps its own unit, and with no unit a number is in SI."""
    import tomllib

    text = PENDULUM.replace('[coordinates]\n', '[coordinates]\n'
                            'x = { sense = "along Ex", kind = "length", unit = "cm", initial = 5, rate = 10 }\n'
                            'y = { sense = "along Ey", kind = "length", unit = "cm", initial = "3 mm" }\n'
                            'z = { sense = "along Ez", kind = "length", initial = 0.5 }\n'
                            'phi = { sense = "about Ez", unit = "deg", initial = 90 }\n')
    system, _ = build_problem(tomllib.loads(text), text, "cm.toml")
    info = system.coordinate_info
    assert info["x"].initial == pytest.approx(0.05) and info["x"].rate == pytest.approx(0.1)
    assert info["y"].initial == pytest.approx(0.003) and info["z"].initial == pytest.approx(0.5)
    assert info["phi"].initial == pytest.approx(math.pi / 2)
