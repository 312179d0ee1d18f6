"""One rule for starting states: the coordinates are put onto the position constraints by Newton's method from
the rough values given, or the start is refused naming the constraint and its residual — in simulate, sweep
and solve alike.

Independent references: a rod end held on the line x = c: θ = asin(c/l) (closed form), and for c > l the
nearest the end can come leaves the gap c − l; a four-bar's coupler and rocker angles from the crank angle by
trigonometry (the intersection of two circles); energy conservation of the assembled four-bar's motion.
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from rigidkin.base.errors import InputError
from rigidkin.examples import build
from rigidkin.io.problem import parse_problem
from rigidkin.numeric import simulate
from rigidkin.numeric.starts import declared_start
from rigidkin.numeric.sweeps.sweep import plan, sweep

sys.path.insert(0, str(Path(__file__).parent))
from test_core_more import _four_bar  # noqa: E402

ROD = """
title = "Rod held on a line"
[parameters]
m = { unit = "kg", value = 1 }
l = { unit = "m", value = 1 }
c = { unit = "m", value = C }
g = { unit = "m/s^2", value = 9.81 }
[coordinates]
theta = { sense = "angle of the rod from the downward vertical", initial = 0.3, rate = 0 }
[frames]
R = { angle = "theta" }
[points]
B = { offset = "-l*R.y", body = "rod" }
G = { offset = "-l/2*R.y" }
Q = { offset = "c*Ex" }
[bodies]
rod = { shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }
[constraints]
O = { type = "pin", point = "O", body_a = "rod" }
B = { type = "contact", body = "rod", centre = "B", unilateral = false, \
      surface = { type = "line", point = "Q", normal = "-Ex" } }
[loads]
gravity = { type = "gravity", g = "g" }
"""


def rod(c: float):
    return parse_problem(ROD.replace("value = C", f"value = {c}"))[0]


def test_a_rod_end_on_a_line_is_assembled_onto_it():
    s = rod(0.5)
    r = simulate(s, 0.5)
    assert r.at(0.0)["theta"] == pytest.approx(math.asin(0.5), abs=1e-12)
    assert r.assembled == {"theta": (0.3, pytest.approx(math.asin(0.5), abs=1e-12))}
    assert declared_start(s)["theta"][1] == pytest.approx(math.asin(0.5), abs=1e-12)
    with pytest.warns(RuntimeWarning, match="theta = 0.4 was given"):
        r = simulate(s, 0.5, {"theta": 0.4})
    assert r.at(0.0)["theta"] == pytest.approx(math.asin(0.5), abs=1e-12)


def test_a_line_the_rod_cannot_reach_is_refused_with_its_residual():
    s = rod(1.6)
    for call in (lambda: simulate(s, 1.0), lambda: declared_start(s), lambda: plan(s, {"m": [1.0, 2.0]})):
        with pytest.raises(InputError, match=r"contact B keeps a residual of 0\.6 "):   # c − l: the closest reach
            call()


def _four_bar_by_trigonometry(th1, L1=0.3, L2=1.0, L3=0.6, d=0.8):
    """Both assemblies (θ2, θ3) of the loop: B on the circle of radius L2 about A and of radius L3 about D."""
    A, D = np.array([L1 * math.cos(th1), L1 * math.sin(th1)]), np.array([d, 0.0])
    r = float(np.linalg.norm(D - A))
    e = (D - A) / r
    a = (L2**2 - L3**2 + r**2) / (2 * r)
    h = math.sqrt(L2**2 - a**2)
    out = []
    for sgn in (1, -1):
        B = A + a * e + sgn * h * np.array([-e[1], e[0]])
        out.append((math.atan2(B[1] - A[1], B[0] - A[0]), math.atan2(B[1], B[0] - d)))
    return out


def _same_angle(a, b):
    return abs(math.remainder(a - b, 2 * math.pi)) < 1e-9


def test_a_four_bar_from_rough_angles_is_assembled():
    s = _four_bar()
    branches = _four_bar_by_trigonometry(1.2)
    r = simulate(s, 0.5)                                   # declared rough angles θ2 = 0.2, θ3 = 1.9
    st = r.at(0.0)
    assert st["theta1"] == 1.2                             # the independent coordinate stays
    assert any(_same_angle(st["theta2"], b2) and _same_angle(st["theta3"], b3) for b2, b3 in branches)
    assert r.max_residual < 1e-9 and r.energy_drift < 1e-9 and r.reached_end
    # rough values near the other assembly pick that one
    for b2, b3 in branches:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            r = simulate(s, 0.05, {"theta2": b2 + 0.05, "theta3": b3 - 0.04})
        st = r.at(0.0)
        assert _same_angle(st["theta2"], b2) and _same_angle(st["theta3"], b3)
        assert r.max_residual < 1e-9


def test_a_four_bar_sweep_assembles_every_run():
    s = _four_bar()
    _, _, Y = plan(s, {"theta1": [1.0, 1.2, 1.4]})
    for row, th1 in zip(Y, (1.0, 1.2, 1.4)):
        assert any(_same_angle(row[1], b2) and _same_angle(row[2], b3) for b2, b3 in _four_bar_by_trigonometry(th1))


def test_sweep_refuses_what_simulate_refuses():
    ladder = build("ladder")
    with pytest.raises(InputError, match="into its surface"):
        simulate(ladder, 0.5, initial_state={"theta": 0.3, "x": 0.1})
    with pytest.raises(InputError, match="run 1 .* puts contact A 0.49104 into its surface"):   # l sin 0.3 − 0.1
        sweep(ladder, {"theta": [0.3, 0.4]}, initial={"x": 0.1}, t_end=0.1)
    with pytest.raises(InputError, match="starts with contact A apart"):
        sweep(ladder, {"theta": [0.3, 0.4]}, initial={"x": 1.0}, t_end=0.1)
    res = sweep(ladder, {"theta": [0.3, 0.4]}, t_end=0.1)              # completed from the constraints: accepted
    assert np.allclose(res.y0[:, 1], 2 * np.sin([0.3, 0.4]))


def test_solve_refuses_a_declared_start_the_constraints_cannot_reach(tmp_path, capsys):
    from rigidkin.cli import main

    far, near = tmp_path / "far.toml", tmp_path / "near.toml"
    far.write_text(ROD.replace("value = C", "value = 1.6"))
    near.write_text(ROD.replace("value = C", "value = 0.5"))
    assert main(["solve", str(far), "--no-cache"]) == 2
    assert "contact B keeps a residual of 0.6" in capsys.readouterr().err
    assert main(["solve", str(near), "--no-cache"]) == 0
    assert "theta = 0.5235987756 (declared 0.3)" in capsys.readouterr().err


def test_a_sweeps_record_answers_only_starts_on_the_constraints():
    from rigidkin.numeric.sweeps import sweep_record

    ladder = build("ladder")
    res = sweep(ladder, {"theta": [0.3, 0.4]}, t_end=0.1, keep_record=True)
    if res.record is None:
        pytest.skip("no C compiler: no record is kept")
    rec = res.record
    assert len(rec["starts"]) == 2                           # the wall and the floor under the foot
    _, _, Y = sweep_record.plan(rec, {"theta": [0.3, 0.4]}, {}, {})
    assert np.allclose(Y[:, 1], 2 * np.sin([0.3, 0.4]))      # x = l sin θ: on the wall
    assert sweep_record.plan(rec, {"theta": [0.3, 0.4]}, {}, {"x": "0.1"}) is None    # the full route refuses


def test_a_declared_rate_the_rolling_constraint_overrules_is_said():
    """A disk rolling on an incline: ẋ = r θ̇ (r = 0.2 m).  Declared θ̇ = 5 and ẋ = 0: the start takes ẋ = 1 from
    the rolling constraint, and the result (and the command line) says which declared rate yielded."""
    from rigidkin.examples import HERE

    text = (HERE / "disk-spring-incline.toml").read_text(encoding="utf-8").replace(
        'kind = "length" }', 'kind = "length", initial = 0, rate = 0 }').replace("initial = 0, rate = 0 }\nx",
                                                                                 "initial = 0, rate = 5 }\nx")
    s = parse_problem(text)[0]
    r = simulate(s, 0.01)
    assert r.at(0.0)["dot(x)"] == pytest.approx(1.0, abs=1e-12)
    assert r.assembled == {"dot(x)": (0.0, pytest.approx(1.0, abs=1e-12))}
