"""Issue 26, point 7: decimals are read as the exact rationals they denote, so exact input gives exact output.

References: sympy's exact rationals, the pendulum's θ̈ = -3 g sin θ/(2 l) (a slender rod pinned at one end),
and the ladder card's answers in /work/shared/problems/ladder.md (θ̈ = 3 g sin θ/(2 l); it leaves the wall at
θ = arccos(2/3)).
"""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest
import sympy as sp

from rigidkin import examples
from rigidkin.cli import main
from rigidkin.io.expressions import default_scope, parse_scalar
from rigidkin.io.problem import build_problem
from rigidkin.model.system import System
from rigidkin.model.values import _expr, exact_decimal

PENDULUM = """
title = "Pendulum"
[parameters]
m = {{ unit = "kg", value = 1 }}
l = {{ unit = "m", value = 2 }}
g = {{ unit = "m/s^2", value = 9.81 }}
[coordinates]
theta = {{ sense = "angle from the downward vertical, counter-clockwise" }}
[frames]
R = {{ angle = "theta" }}
[points]
G = {{ offset = "{offset}" }}
[bodies]
rod = {{ shape = "slender_rod", mass = "m", length = "{length}", axis = "y", frame = "R", at = "G" }}
[constraints]
O = {{ type = "pin", point = "O", body_a = "rod" }}
[loads]
gravity = {{ type = "gravity", g = "{g}" }}
"""


def _solve(offset="-l/2*R.y", length="l", g="g"):
    text = PENDULUM.format(offset=offset, length=length, g=g)
    system, _ = build_problem(tomllib.loads(text), text, "pendulum.toml")
    return system, system.solve()


def _floats(*exprs) -> list:
    return [f for e in exprs for f in sp.sympify(e).atoms(sp.Float)]


def test_literals_are_exact():
    scope = default_scope()
    assert parse_scalar("0.1", scope) == sp.Rational(1, 10)
    assert parse_scalar("0.1 + 0.2", scope) == sp.Rational(3, 10)         # not 0.30000000000000004
    assert parse_scalar("2.5e-3", scope) == sp.Rational(1, 400)
    assert parse_scalar("1e3", scope) == 1000 and parse_scalar("1_000.5", scope) == sp.Rational(2001, 2)
    assert parse_scalar(0.3, scope) == sp.Rational(3, 10)                # a TOML float: as it is written
    # the decimal as written, not its nearest binary float
    assert parse_scalar("3.14159265358979323846", scope) == sp.Rational(314159265358979323846, 10**20)
    assert parse_scalar("1e-60", scope).is_Float                          # too many digits exactly: a float


def test_decimal_sum_of_gravity_is_gravity():
    """g = 0.1*g + 0.9*g is exactly g: the same EOM as g, and θ̈ = -3 g sin θ/(2 l) with no float in it."""
    _, ref = _solve()
    system, sol = _solve(g="0.1*g + 0.9*g")
    th = sol.coordinates[0]
    g, l = sp.symbols("g l", positive=True)
    acc = sol.accelerations[th]
    assert sp.simplify(acc - (-3 * g * sp.sin(th) / (2 * l))) == 0
    assert acc == ref.accelerations[th]
    assert not _floats(acc, *sol.eom, *sol.reactions.values())


def test_decimal_offsets_give_no_floats():
    """"-0.5*l*R.y" and "1.0*l" are l/2 and l: the same reactions as the exact file, term by term."""
    _, ref = _solve()
    _, sol = _solve(offset="-0.5*l*R.y", length="1.0*l")
    assert not _floats(*sol.eom, *sol.accelerations.values(), *sol.reactions.values())
    for name, r in ref.reactions.items():
        assert sp.simplify(sol.reactions[name] - r) == 0


def test_ladder_card_with_decimals(tmp_path, capsys):
    """The ladder written with 0.5*l and 1.0*l still answers exactly: θ̈ = 3 g sin θ/(2 l), θ = acos(2/3)."""
    src = Path(examples.__file__).parent / "ladder.toml"
    text = src.read_text().replace('offset = "l/2*ey"', 'offset = "0.5*l*ey"').replace(
        'offset = "l*ey"', 'offset = "1.0*l*ey"')
    assert "0.5*l*ey" in text and "1.0*l*ey" in text
    path = tmp_path / "ladder.toml"
    path.write_text(text)
    assert main(["solve", str(path), "--no-cache", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    th, g, l = sp.Function("theta")(sp.Symbol("t")), sp.Symbol("g"), sp.Symbol("l")
    local = {"theta": sp.Function("theta"), "t": sp.Symbol("t"), "g": g, "l": l}
    acc = sp.parse_expr(data["accelerations"]["theta"], local_dict=local)
    assert sp.simplify(acc - 3 * g * sp.sin(th) / (2 * l)) == 0 and not acc.atoms(sp.Float)
    assert sp.parse_expr(data["answers"]["leaves_wall"]) == sp.acos(sp.Rational(2, 3))


def test_python_api_floats():
    """A bare float given to the API is its decimal, exactly; a sympy expression built in Python is kept."""
    assert _expr(0.3) == sp.Rational(3, 10) and _expr(2) == 2
    assert exact_decimal(0.1) == sp.Rational(1, 10) and exact_decimal("0.25") == sp.Rational(1, 4)
    assert _expr(float("inf")) == sp.oo                   # refused later, as before, by the value checks
    l = sp.Symbol("l", positive=True)
    assert _expr(0.5 * l).atoms(sp.Float)                 # the user's sympy float stays (documented choice)
    s = System("api")
    m = s.parameter("m", "kg", value=0.5)
    assert s.parameter_info["m"].value == pytest.approx(0.5)   # numeric values stay numbers in SI
    assert isinstance(m, sp.Symbol)
