"""Contacts and friction as one complementarity problem, checked against closed forms and hand
impulse–momentum (never against the engine's own output)."""

import math

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.io.problem import parse_problem
from rigidkin.numeric import simulate

G = 9.81


def incline(beta, mu_s, mu_k=None, m=2.0):
    """A block (a point mass) on a rough incline: x down the slope, y off it (so the contact can open)."""
    s = rk.System("block-on-incline")
    m_ = s.parameter("m", "kg", value=m)
    g = s.parameter("g", "m/s^2", value=G)
    b = s.parameter("beta", "rad", value=beta)
    ms = s.parameter("mu_s", "", value=mu_s)
    mk = s.parameter("mu_k", "", value=mu_s if mu_k is None else mu_k)
    x = s.coordinate("x", "distance of the block down the slope", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "distance of the block off the slope", kind="length", initial=0, rate=0)
    I = s.frame("I", angle=-b, basis=("es", "en", "ez"))
    G_ = s.point("G", offset=x * I.es + y * I.en)
    blk = s.body("block", rk.shapes.PointMass(m_), frame=I, at=G_)
    s.contact("ground", blk, s.line(s.origin, I.en), centre=G_, friction={"static": ms, "kinetic": mk},
              normal_name="N", friction_name="F")
    s.gravity(g)
    return s


INCLINE_TOML = """
title = "Block on a rough incline"
[parameters]
m = { unit = "kg", value = 2 }
g = { unit = "m/s^2", value = 9.81 }
beta = { unit = "rad", value = "30 deg" }
mu_s = { unit = "", value = 0.6 }
mu_k = { unit = "", value = 0.4 }
[coordinates]
x = { sense = "distance of the block down the slope", kind = "length", initial = 0, rate = 0 }
y = { sense = "distance of the block off the slope", kind = "length", initial = 0, rate = 0 }
[frames]
I = { angle = "-beta", basis = ["es", "en", "ez"] }
[points]
G = { offset = "x*es + y*en" }
[bodies]
block = { shape = "point_mass", mass = "m", frame = "I", at = "G" }
[constraints.ground]
type = "contact"
body = "block"
surface = { type = "line", point = "O", normal = "en" }
friction = { static = "mu_s", kinetic = "mu_k" }
normal_name = "N"
friction_name = "F"
[loads]
gravity = { type = "gravity", g = "g" }
"""


# (a) a mode with no degree of freedom is an ordinary mode ------------------------------------------
def test_sticking_block_is_a_mode_at_rest_with_reactions_from_statics():
    s = incline(0.4, 0.6, 0.4)
    sol = s.solve(mode={"ground": "stick"})
    assert sol.coordinates == ()                          # no degree of freedom: q̇ = 0, q̈ = 0
    m, beta = 2.0, 0.4
    vals = {"m": m, "g": G, "beta": beta, "mu_s": 0.6, "mu_k": 0.4}
    subs = {sym: vals[str(sym)] for sym in sol.reactions["N"].free_symbols | sol.reactions["F"].free_symbols}
    # statics across and along the slope: N = m g cos β, F = m g sin β (F positive up the slope, along −es)
    assert float(sol.reactions["N"].subs(subs)) == pytest.approx(m * G * math.cos(beta), rel=1e-14)
    assert float(sol.reactions["F"].subs(subs)) == pytest.approx(m * G * math.sin(beta), rel=1e-14)
    # validity: sticking holds while |F| ≤ µs N (the static coefficient, not the kinetic one)
    conds = [c for c in sol.regimes[0].validity if "within" in c.label]
    assert conds and all("µs" in c.label for c in conds)
    assert all(c.expr.has(s.parameter_info["mu_s"].symbol) and not c.expr.has(s.parameter_info["mu_k"].symbol)
               for c in conds)


# (b) static and kinetic friction: the block released from rest -------------------------------------
@pytest.mark.parametrize("beta,mu_s,mu_k", [(0.4, 0.6, 0.4), (math.radians(30), 0.6, 0.4), (0.5, 0.9, 0.2)])
def test_block_released_on_incline_stays_when_tan_beta_within_mu_s(beta, mu_s, mu_k):
    assert math.tan(beta) <= mu_s
    res = simulate(incline(beta, mu_s, mu_k), 1.5)
    assert res.reached_end and res.stop_reason == "completed"
    assert res.segments[0].mode == {"ground": "stick"} and not res.events
    assert np.max(np.abs(res["x"])) == 0.0 and np.max(np.abs(res["dot(x)"])) == 0.0
    assert np.allclose(res["N"], 2.0 * G * math.cos(beta), rtol=1e-13)


def test_block_stays_exactly_at_the_limit_tan_beta_equal_to_mu_s():
    beta = 0.5
    res = simulate(incline(beta, math.tan(beta), 0.3), 2.0)
    assert res.reached_end and not res.events
    assert res.segments[0].mode == {"ground": "stick"}
    assert np.max(np.abs(res["x"])) == 0.0


@pytest.mark.parametrize("beta,mu_s,mu_k", [(math.radians(30), 0.5, 0.4), (0.7, 0.6, 0.1), (0.5, 0.5, 0.5)])
def test_block_released_on_incline_slides_with_kinetic_friction(beta, mu_s, mu_k):
    assert math.tan(beta) > mu_s
    res = simulate(incline(beta, mu_s, mu_k), 1.0)
    assert res.reached_end and not res.events
    assert res.segments[0].mode == {"ground": "slip"}
    a = G * (math.sin(beta) - mu_k * math.cos(beta))       # the closed form
    t = res.t
    assert np.max(np.abs(res["x"] - a * t**2 / 2)) < 1e-10
    assert np.max(np.abs(res["dot(x)"] - a * t)) < 1e-10


def test_static_and_kinetic_friction_in_a_problem_file():
    system, _ = parse_problem(INCLINE_TOML, "incline.toml")
    fr = system.constraints["ground"].friction
    assert str(fr.static) == "mu_s" and str(fr.kinetic) == "mu_k"
    stays = simulate(system, 1.0)                          # tan 30° = 0.577 ≤ µs = 0.6
    assert stays.reached_end and np.max(np.abs(stays["x"])) == 0.0
    slides = simulate(system, 1.0, params={"mu_s": 0.55})  # tan 30° > µs: slides with µk = 0.4
    a = G * (0.5 - 0.4 * math.cos(math.radians(30)))
    assert slides["x"][-1] == pytest.approx(a / 2, rel=1e-10)


def test_a_single_mu_keeps_meaning_both_and_mu_s_below_mu_k_is_refused():
    fr = rk.Coulomb(0.3)
    assert fr.static == fr.kinetic == 0.3
    with pytest.raises(rk.ModelError, match="µs"):
        rk.Coulomb(0.3, 0.2)
    bad = INCLINE_TOML.replace('friction = { static = "mu_s", kinetic = "mu_k" }', 'friction = { static = 0.2, '
                               'kinetic = 0.4 }')
    with pytest.raises(rk.RigidkinError, match="static coefficient"):
        parse_problem(bad, "incline.toml")
