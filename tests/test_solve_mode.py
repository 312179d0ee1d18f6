"""`rigidkin solve --mode CONTACT=STATE`: a block at rest on a rough incline, reactions from statics.

By hand (free-body diagram of the block, at rest): N = m g cos β, F = m g sin β (F positive up the slope),
and it stays while tan β ≤ µs.
"""

import json
import math

import sympy as sp

from rigidkin.cli import main

INCLINE = """
title = "Block on a rough incline"
[parameters]
m = { unit = "kg", value = 2 }
g = { unit = "m/s^2", value = 9.81 }
beta = { unit = "rad", value = 0.4 }
mu_s = { unit = "1", value = 0.6 }
mu_k = { unit = "1", value = 0.4 }
[coordinates]
x = { kind = "length", sense = "down the incline from the start", initial = 0 }
y = { kind = "length", sense = "off the slope", initial = 0 }
[frames]
I = { angle = "-beta", basis = ["es", "en", "ez"] }
[points]
G = { offset = "x*I.es + y*I.en" }
[bodies]
block = { shape = "point_mass", mass = "m", frame = "I", at = "G" }
[constraints.ground]
type = "contact"
body = "block"
surface = { type = "line", point = "O", normal = "I.en" }
centre = "G"
friction = { static = "mu_s", kinetic = "mu_k" }
normal_name = "N"
friction_name = "F"
[loads]
gravity = { type = "gravity", g = "g" }
"""


def test_solve_at_rest_gives_the_reactions_of_statics(tmp_path, capsys):
    f = tmp_path / "incline.toml"
    f.write_text(INCLINE)
    assert main(["solve", str(f), "--mode", "ground=stick", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    reactions = data["regimes"][0]["reactions"]
    m, g, beta = sp.symbols("m g beta", positive=True)
    values = {m: 2, g: 9.81, beta: 0.4}
    N = float(sp.parse_expr(reactions["N"], {"m": m, "g": g, "beta": beta}).subs(values))
    F = float(sp.parse_expr(reactions["F"], {"m": m, "g": g, "beta": beta}).subs(values))
    assert math.isclose(N, 2 * 9.81 * math.cos(0.4), rel_tol=1e-12)
    assert math.isclose(F, 2 * 9.81 * math.sin(0.4), rel_tol=1e-12)


def test_solve_at_rest_text_says_no_degree_of_freedom(tmp_path, capsys):
    f = tmp_path / "incline.toml"
    f.write_text(INCLINE)
    assert main(["solve", str(f), "--mode", "ground=stick"]) == 0
    out = capsys.readouterr().out
    assert "no degree of freedom remains" in out
    assert "µ_s" in out or "mu_s" in out           # the sticking condition |F| ≤ µs N is listed


def test_solve_mode_refuses_unknown_contacts_and_states(tmp_path, capsys):
    f = tmp_path / "incline.toml"
    f.write_text(INCLINE)
    assert main(["solve", str(f), "--mode", "wall=stick"]) == 2
    assert "not a constraint" in capsys.readouterr().err
    assert main(["solve", str(f), "--mode", "ground=glue"]) == 2
    assert main(["solve", str(f), "--mode", "ground"]) == 2


def test_check_at_rest_says_nothing_was_compared(tmp_path, capsys):
    f = tmp_path / "incline.toml"
    f.write_text(INCLINE)
    assert main(["check", str(f), "--mode", "ground=stick"]) == 0
    out = capsys.readouterr().out
    assert "No law was compared" in out and "All agree." not in out
