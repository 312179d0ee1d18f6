"""A body at rest on two supports that both hold it from slipping (rolling, or Coulomb friction all sticking):
an ordinary zero-DOF mode whose determinate reactions are solved and whose indeterminate ones are named.

References: hand statics (moment balance about each support: N_A = m g b/(a + b) for supports at a and b from
the mass centre; force balance along the floor: F_A + F_C = the applied tangential load), d'Alembert for a block
carried on an accelerating cart, and the simulation's reactions at rest (an independent path: the simulator
carries the friction of one contact by the other, numerically).
"""

import json
from importlib import resources

import jsonschema
import numpy as np
import pytest
import sympy as sp

import rigidkin as rk
from rigidkin.cli import main
from rigidkin.numeric import simulate

G = 9.81


def block(la=0.2, lb=0.2, h=0.6, m=2.0, friction="rolling", push=None):
    """A block of height h on two lower corners A (la behind its centre) and C (lb ahead), on a floor; ``push``
    = (P, d): a horizontal force P along Ex at height d above the floor, on the back face ((c, d, True): c t)."""
    s = rk.System("block-on-two-supports")
    m_, g = s.parameter("m", "kg", value=m), s.parameter("g", "m/s^2", value=G)
    la_, lb_, h_ = s.parameter("a", "m", value=la), s.parameter("b", "m", value=lb), s.parameter("h", "m", value=h)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=h / 2, rate=0)
    th = s.coordinate("theta", "tilt, counter-clockwise", initial=0, rate=0)
    B = s.frame("B", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    box = s.body("box", rk.shapes.RectangularPlate(m_, la_ + lb_, h_), frame=B, at=Gp)
    A = s.point("A", Gp, -la_ * B.x - h_ / 2 * B.y, body=box)
    C = s.point("C", Gp, lb_ * B.x - h_ / 2 * B.y, body=box)
    floor = s.line(s.origin, s.inertial.y)
    if friction != "rolling":
        friction = s.parameter("mu", "", value=friction)
    s.contact("A", box, floor, centre=A, friction=friction, normal_name="N_A", friction_name="F_A")
    s.contact("C", box, floor, centre=C, friction=friction, normal_name="N_C", friction_name="F_C")
    if push is not None:                                # (P, d) or (c, d, True): P = c t
        ramp = len(push) > 2 and push[2]
        P_ = s.parameter("c", "N/s", value=push[0]) if ramp else s.parameter("P", "N", value=push[0])
        d_ = s.parameter("d", "m", value=push[1])
        Q = s.point("Q", Gp, -la_ * B.x + (d_ - h_ / 2) * B.y, body=box)
        s.force("push", Q, (P_ * rk.t if ramp else P_) * s.inertial.x)
    s.gravity(g)
    return s


def values(s):
    return {p.symbol: p.value for p in s.parameter_info.values()}


def number(expr, s):
    return float(sp.sympify(expr).subs(values(s)))


@pytest.mark.parametrize("la, lb", [(0.2, 0.2), (0.15, 0.35)])
def test_rolling_block_on_two_corners_is_statics_with_the_friction_split_named(la, lb):
    s = block(la, lb)
    sol = s.solve()                                    # both corners rolling: the default mode
    assert sol.coordinates == ()                       # at rest, flat: where the two closed gaps put it
    assert {q.func.__name__: str(v) for q, v in sol.relations.items()} == {"theta": "0", "y": "h/2"}
    r = sol.regimes[0]
    m = 2.0
    # moment balance about C: N_A (a + b) = m g b; about A: N_C (a + b) = m g a
    assert number(r.reactions["N_A"], s) == pytest.approx(m * G * lb / (la + lb), rel=1e-12)
    assert number(r.reactions["N_C"], s) == pytest.approx(m * G * la / (la + lb), rel=1e-12)
    assert r.indeterminate.reactions == ("F_A", "F_C")
    assert "F_A" not in r.reactions and "F_C" not in r.reactions
    FA, FC = sp.Symbol("F_A", real=True), sp.Symbol("F_C", real=True)
    assert [(sp.simplify(c - (FA + FC)), v) for c, v in r.indeterminate.combinations] == [(0, 0)]
    assert any("rolling" in line for line in r.indeterminate.friction)


@pytest.mark.parametrize("la, lb", [(0.2, 0.2), pytest.param(0.15, 0.35, marks=pytest.mark.slow)])
def test_rolling_block_reactions_match_the_simulation_at_rest(la, lb):
    s = block(la, lb)
    r = s.solve().regimes[0]
    res = simulate(s, 0.05, n_points=6)
    assert res.stop_reason == "completed"
    assert np.allclose(res["N_A"], number(r.reactions["N_A"], s), rtol=1e-9)
    assert np.allclose(res["N_C"], number(r.reactions["N_C"], s), rtol=1e-9)
    assert res.segments[0].mode == {"A": "stick", "C": "slip"}     # the simulator lets A carry both frictions:
    assert np.allclose(res["F_A"], 0.0, atol=1e-9)                  # F_A + F_C, the sum the balance laws fix


def test_all_sticking_statics_with_a_push_gives_the_sum_and_the_slip_threshold():
    mu, P, d, la, lb, m = 0.4, 3.0, 0.45, 0.25, 0.25, 2.0
    s = block(la, lb, friction=mu, push=(P, d))
    sol = s.solve(mode={"A": "stick", "C": "stick"})
    r = sol.regimes[0]
    at = sol.reactions_at({})                  # numbers: the closed form checked against the balance equations
    assert at == pytest.approx({"N_A": (m * G * lb - P * d) / (la + lb), "N_C": (m * G * la + P * d) / (la + lb)})
    # moments about C and about A (the push at height d, the weight at the middle)
    assert number(r.reactions["N_A"], s) == pytest.approx((m * G * lb - P * d) / (la + lb), rel=1e-12)
    assert number(r.reactions["N_C"], s) == pytest.approx((m * G * la + P * d) / (la + lb), rel=1e-12)
    assert r.indeterminate.reactions == ("F_A", "F_C")
    (combo, value), = r.indeterminate.combinations
    FA, FC = sp.Symbol("F_A", real=True), sp.Symbol("F_C", real=True)
    assert sp.simplify(combo - (FA + FC)) == 0                # friction positive along −Ex: F_A + F_C = P
    assert number(value, s) == pytest.approx(P, rel=1e-12)
    # a split within µN at each corner exists iff |P| ≤ µ (N_A + N_C) = µ m g
    split = [c for c in r.validity if "split" in c.label]
    assert len(split) == 2
    margins = sorted(number(c.expr, s) for c in split)
    assert margins == pytest.approx(sorted([mu * m * G - P, mu * m * G + P]), rel=1e-12)


def test_held_mode_takes_the_friction_limits_of_both_contacts():
    # A sticks and carries the friction of C, which slips nowhere (the simulator's mode at rest): F_A = P and
    # the limit is µ (N_A + N_C) = µ m g, not µ N_A
    mu, P, d, m = 0.4, 3.0, 0.45, 2.0
    s = block(0.15, 0.35, friction=mu, push=(P, d))
    sol = s.solve(mode={"A": "stick", "C": "slip"})
    r = sol.regimes[0]
    assert {q.func.__name__: str(v) for q, v in sol.relations.items()} == {"theta": "0", "y": "h/2"}
    assert number(r.reactions["N_A"], s) == pytest.approx((m * G * 0.35 - P * d) / 0.5, rel=1e-12)
    assert number(r.reactions["F_A"], s) == pytest.approx(P, rel=1e-12)
    limits = [c for c in r.validity if "friction" in c.label]
    assert all("carries that of C" in c.label for c in limits) and len(limits) == 2
    assert sorted(number(c.expr, s) for c in limits) == pytest.approx([mu * m * G - P, mu * m * G + P], rel=1e-12)


@pytest.mark.slow
def test_push_threshold_agrees_with_the_simulation_slipping():
    # P = c t: statics holds while a split within µN exists, c t ≤ µ m g; the simulation slips then
    mu, c, d, m = 0.3, 2.0, 0.4, 2.0
    s = block(0.25, 0.25, friction=mu, push=(c, d, True))
    r = s.solve(mode={"A": "stick", "C": "stick"}).regimes[0]
    margin = min((cd.expr for cd in r.validity if "split" in cd.label), key=lambda e: number(e.subs(rk.t, 1), s))
    t_star, = [float(root) for root in sp.solve(sp.sympify(margin).subs(values(s)), rk.t)]
    assert t_star == pytest.approx(mu * m * G / c, rel=1e-12)
    res = simulate(s, t_star + 0.02, max_events=3)
    assert res.events[0].kind == "slips" and res.events[0].t == pytest.approx(t_star, abs=1e-9)


def test_block_on_an_accelerating_cart_by_dalembert():
    """A cart (x only, on two smooth wheels) pushed by P carries a block rolling on two corners: one degree of
    freedom, ẍ = P/(M + m); the block's corners share the friction −m ẍ (sum only), and its normal forces
    shift to the back: N_A, N_C = m g/2 ± h m ẍ/(2 b) (moments about the block's centre)."""
    M, m, P, b, h, w, hc = 5.0, 1.5, 4.0, 0.4, 0.3, 0.5, 0.2
    s = rk.System("cart-and-block")
    M_, m_ = s.parameter("M", "kg", value=M), s.parameter("m", "kg", value=m)
    g, P_ = s.parameter("g", "m/s^2", value=G), s.parameter("P", "N", value=P)
    b_, h_ = s.parameter("b", "m", value=b), s.parameter("h", "m", value=h)
    w_, hc_ = s.parameter("w", "m", value=w), s.parameter("hc", "m", value=hc)
    F = s.inertial
    x1 = s.coordinate("x1", "cart along Ex", kind="length", initial=0, rate=0)
    x2 = s.coordinate("x2", "block along Ex", kind="length", initial=0, rate=0)
    y2 = s.coordinate("y2", "block height", kind="length", initial=hc / 2 + h / 2, rate=0)
    th = s.coordinate("theta", "block tilt", initial=0, rate=0)
    C1 = s.point("C1", s.origin, x1 * F.x)
    cart = s.body("cart", rk.shapes.RectangularPlate(M_, 2 * w_, hc_), frame=F, at=C1)
    W1 = s.point("W1", C1, -w_ * F.x - hc_ / 2 * F.y, body=cart)
    W2 = s.point("W2", C1, w_ * F.x - hc_ / 2 * F.y, body=cart)
    floor = s.line(s.point("O1", s.origin, -hc_ / 2 * F.y), F.y, name="floor")
    s.contact("W1", cart, floor, centre=W1, normal_name="N_1")
    s.contact("W2", cart, floor, centre=W2, normal_name="N_2")
    B = s.frame("B", angle=th)
    G2 = s.point("G2", s.origin, x2 * F.x + y2 * F.y)
    blk = s.body("block", rk.shapes.RectangularPlate(m_, b_, h_), frame=B, at=G2)
    A = s.point("A", G2, -b_ / 2 * B.x - h_ / 2 * B.y, body=blk)
    C = s.point("C", G2, b_ / 2 * B.x - h_ / 2 * B.y, body=blk)
    top = s.line(s.point("T", C1, hc_ / 2 * F.y, body=cart), F.y, body=cart, name="top")
    s.contact("A", blk, top, centre=A, friction="rolling", normal_name="N_A", friction_name="F_A")
    s.contact("C", blk, top, centre=C, friction="rolling", normal_name="N_C", friction_name="F_C")
    s.force("push", C1, P_ * F.x)
    s.gravity(g)
    sol = s.solve()
    assert [q.func.__name__ for q in sol.coordinates] == ["x1"]
    r = sol.regimes[0]
    a = P / (M + m)
    assert number(r.accelerations["x1"], s) == pytest.approx(a, rel=1e-12)
    assert number(r.reactions["N_A"], s) == pytest.approx(m * G / 2 + h * m * a / (2 * b), rel=1e-12)
    assert number(r.reactions["N_C"], s) == pytest.approx(m * G / 2 - h * m * a / (2 * b), rel=1e-12)
    assert r.indeterminate.reactions == ("F_A", "F_C")
    (combo, value), = r.indeterminate.combinations
    assert number(value, s) == pytest.approx(-m * a, rel=1e-12)     # friction on the block along −Ex
    assert {"N_1", "N_2"} <= set(r.reactions)


@pytest.mark.slow
def test_solve_command_states_it_in_text_and_json(tmp_path, capsys):
    f = tmp_path / "block.toml"
    f.write_text(BLOCK_TOML)
    assert main(["solve", str(f), "--no-cache"]) == 0
    out = capsys.readouterr().out
    assert "Statically indeterminate" in out and "F_A and F_C individually" in out and "F_A + F_C = 0" in out
    assert "N_A = g·lb·m/(la + lb)" in out
    assert main(["solve", str(f), "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    jsonschema.validate(data, json.loads(resources.files("rigidkin.io").joinpath("results.schema.json").read_text()))
    ind = data["indeterminate"]
    assert ind["reactions"] == ["F_A", "F_C"] and ind["combinations"] == [{"expression": "F_A + F_C", "value": "0"}]
    assert set(data["reactions"]) == {"N_A", "N_C"}
    assert main(["solve", str(f), "--format", "markdown"]) == 0
    assert "Statically indeterminate" in capsys.readouterr().out


@pytest.mark.parametrize("method", ["lagrange", "kane"])
def test_every_law_at_rest_gives_the_same_statics(method):
    # no degree of freedom: Lagrange's and Kane's methods have no equation; the reactions come from Euler's laws
    s = block(0.15, 0.35)
    r = s.solve(method=method).regimes[0]
    assert r.eom == () and number(r.reactions["N_A"], s) == pytest.approx(2.0 * G * 0.35 / 0.5, rel=1e-12)
    assert r.indeterminate.reactions == ("F_A", "F_C")


@pytest.mark.slow
def test_a_question_for_an_indeterminate_reaction_says_so(tmp_path, capsys):
    f = tmp_path / "block.toml"
    f.write_text(BLOCK_TOML + '\n[[ask.question]]\nkind = "reaction"\nname = "front"\nreaction = "N_C"\n'
                 '\n[[ask.question]]\nkind = "reaction"\nname = "grip"\nreaction = "F_A"\n')
    assert main(["solve", str(f), "--no-cache"]) == 1          # one question not answered
    out = " ".join(capsys.readouterr().out.split())
    assert "N_C = g·la·m/(la + lb)" in out
    assert "F_A is statically indeterminate in this mode: the balance laws determine only F_A + F_C = 0" in out


def test_two_supports_moving_at_different_speeds_are_refused():
    """Both corners rolling on belts that run at different speeds: no motion satisfies both."""
    s = rk.System("two-belts")
    m_, g = s.parameter("m", "kg", value=1.0), s.parameter("g", "m/s^2", value=G)
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=0.1, rate=0)
    th = s.coordinate("theta", "tilt", initial=0, rate=0)
    B = s.frame("B", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    box = s.body("box", rk.shapes.RectangularPlate(m_, 0.4, 0.2), frame=B, at=Gp)
    A = s.point("A", Gp, -0.2 * B.x - 0.1 * B.y, body=box)
    C = s.point("C", Gp, 0.2 * B.x - 0.1 * B.y, body=box)
    belt1 = s.line(s.point("S1", s.origin, 1 * rk.t * s.inertial.x), s.inertial.y, name="belt1")
    belt2 = s.line(s.point("S2", s.origin, 2 * rk.t * s.inertial.x), s.inertial.y, name="belt2")
    s.contact("A", box, belt1, centre=A, friction="rolling")
    s.contact("C", box, belt2, centre=C, friction="rolling")
    s.gravity(g)
    with pytest.raises(rk.ConstraintError, match="different speed") as err:
        s.solve()
    assert "contact C: no slip" in str(err.value)


BLOCK_TOML = """
title = "Block on two rolling supports"
[parameters]
m = { unit = "kg", value = 2 }
g = { unit = "m/s^2", value = 9.81 }
la = { unit = "m", value = 0.3 }
lb = { unit = "m", value = 0.5 }
h = { unit = "m", value = 0.4 }
[coordinates]
x = { sense = "centre along Ex", kind = "length", initial = 0, rate = 0 }
y = { sense = "centre height", kind = "length", initial = 0.2, rate = 0 }
theta = { sense = "tilt", initial = 0, rate = 0 }
[frames]
B = { angle = "theta", basis = ["ex", "ey", "ez"] }
[points]
G = { from = "O", offset = "x*Ex + y*Ey" }
A = { from = "G", offset = "-la*ex - h/2*ey", body = "box" }
C = { from = "G", offset = "lb*ex - h/2*ey", body = "box" }
[bodies.box]
shape = "rectangular_plate"
mass = "m"
a = "la+lb"
b = "h"
frame = "B"
at = "G"
[constraints.A]
type = "contact"
body = "box"
surface = { type = "line", point = "O", normal = "Ey", name = "floor" }
centre = "A"
friction = "rolling"
normal_name = "N_A"
friction_name = "F_A"
[constraints.C]
type = "contact"
body = "box"
surface = { type = "line", point = "O", normal = "Ey", name = "floor" }
centre = "C"
friction = "rolling"
normal_name = "N_C"
friction_name = "F_C"
[loads.gravity]
type = "gravity"
g = "g"
"""
