"""A question's ``start`` (or ``at``) follows the one rule for starting states: assembled onto the position
constraints by Newton's method, or refused naming the constraint and its residual.

Independent references: a rod end held on the line x = c: θ = asin(c/l) (closed form), and for c > l the
nearest the end can come leaves the gap c − l; the ladder released from rest at θ0 leaves the wall where
cos θ = (2/3) cos θ0 (energy and the wall's push by hand).
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin.analysis.answers import answer
from rigidkin.analysis.questions import Question
from rigidkin.base.errors import InputError
from rigidkin.io.load import load_system
from rigidkin.io.problem import parse_problem

sys.path.insert(0, str(Path(__file__).parent))
from test_start_assembly import ROD  # noqa: E402

t = dynamicsymbols._t
QUESTION = """
[[ask.question]]
kind = "value"
name = "angle"
expression = "theta"
at = { theta = 0.3 }
"""


def test_a_question_start_off_the_line_is_assembled_onto_it():
    s, spec = parse_problem(ROD.replace("value = C", "value = 0.5") + QUESTION)
    with pytest.warns(RuntimeWarning, match=r"theta = 0.5235987756 \(given 0.3\)"):
        a = answer(s, spec.questions[0])
    c, l_ = s.parameters["c"], s.parameters["l"]
    assert sp.simplify(a.value - sp.asin(c / l_)) == 0                 # the closed form, not a float
    assert float(a.value.subs({c: 0.5, l_: 1})) == pytest.approx(math.asin(0.5), abs=1e-14)


def test_a_question_start_the_constraints_cannot_reach_is_refused():
    s, spec = parse_problem(ROD.replace("value = C", "value = 0.5") + QUESTION)
    q = spec.questions[0]
    far = Question(q.kind, q.name, {**q.fields, "set": {s.parameters["c"]: sp.Rational(8, 5)}}, q.where)
    with pytest.raises(InputError, match=r"contact B keeps a residual of 0\.6 ") as exc:   # c − l
        answer(s, far)
    assert "ask.question[0], at" in str(exc.value)


def _leaves_wall(system, spec, start):
    q = spec.questions[1]
    return answer(system, Question(q.kind, q.name, {**q.fields, "start": start}, q.where))


def test_ladder_question_start_with_the_foot_off_the_wall():
    system, spec = load_system("ladder")
    th, x = (c.symbol for c in system.coordinate_info.values())
    th0 = sp.Rational(3, 10)
    with warnings.catch_warnings():
        warnings.simplefilter("error")                        # on the constraints: no warning, kept exact
        exact = _leaves_wall(system, spec, {th: th0, th.diff(t): 0})
    with pytest.warns(RuntimeWarning, match=r"x = 0.5910404133 \(given 0.1\)"):     # l sin θ0 with l = 2
        moved = _leaves_wall(system, spec, {th: th0, x: sp.Rational(1, 10), th.diff(t): 0})
    for a in (exact, moved):
        angle = float(a.details["configuration"][th])
        assert math.cos(angle) == pytest.approx(2 / 3 * math.cos(0.3), rel=1e-12)


def test_ladder_question_start_inside_the_wall_is_moved_out_by_the_cli(tmp_path, capsys):
    from rigidkin.cli import main
    from rigidkin.examples import HERE

    text = (HERE / "ladder.toml").read_text().replace('start = { theta = 0, "dot(theta)" = 0 }\n\n[[ask',
                                                      'start = { theta = 0, "dot(theta)" = 0 }\n\n[[ask', 1)
    text = text.replace('when = "N_A = 0"\nstart = { theta = 0, "dot(theta)" = 0 }',
                        'when = "N_A = 0"\nstart = { theta = 0.3, x = 0.1, "dot(theta)" = 0 }')
    path = tmp_path / "ladder.toml"
    path.write_text(text)
    assert main(["solve", str(path), "--no-cache"]) == 0
    out, err = capsys.readouterr()
    assert "x = 0.5910404133 (given 0.1)" in err and "ask.question[1], start" in err
    assert "acos(2·cos(3/10)/3)" in out or "acos(2*cos(3/10)/3)" in out
