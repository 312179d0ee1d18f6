"""The yo-yo: a disk falling from a string tied to the ceiling, wound on its drum of radius r.

Its fall is checked against the closed form ÿ = g/(1 + R²/(2r²)) (moments about the string's contact
point: m g r = (m R²/2 + m r²) ÿ/r), and its animation's frames against the geometry by hand: the
string runs straight down from the ceiling point A = (0, 0) to the drum's left side (0, −y), and a
ceiling is drawn across it at A."""

from __future__ import annotations

import matplotlib.colors as mc
import numpy as np
import pytest

from rigidkin.io.problem import parse_problem
from rigidkin.numeric.simulate import simulate

YOYO_FILE = """
title = "Yo-yo falling from its string"
[parameters]
m = { unit = "kg", value = 0.1 }
R = { unit = "m", value = "3 cm" }
r = { unit = "m", value = "5 mm" }
g = { unit = "m/s^2", value = 9.81 }
[coordinates]
y = { sense = "depth of the yo-yo's centre below the ceiling point A", kind = "length", initial = "20 cm", rate = 0 }
phi = { sense = "turn of the yo-yo, counter-clockwise" }
[frames]
Y = { angle = "phi" }
[points]
A = { offset = 0, description = "where the string is tied to the ceiling" }
C = { offset = "r*Ex - y*Ey" }
[bodies]
yoyo = { shape = "disk", mass = "m", radius = "R", frame = "Y", at = "C" }
[constraints]
string = { type = "rope", path = ["A", { pulley = "yoyo", radius = "r", sense = "ccw" }], tensions = ["T"] }
[loads]
gravity = { type = "gravity", g = "g" }
"""
T_END = 0.3


@pytest.fixture(scope="module")
def run():
    system, _ = parse_problem(YOYO_FILE, "yoyo.toml")
    return system, simulate(system, T_END)


def test_the_yoyo_falls_as_the_closed_form(run):
    _, res = run
    a = 9.81 / (1 + 0.03**2 / (2 * 0.005**2))
    assert res.final_state["y"] == pytest.approx(0.2 + a * T_END**2 / 2, rel=1e-9)


def test_the_animation_draws_the_string_and_the_ceiling(run):
    from rigidkin.report.animate import animate
    from rigidkin.report.drawing import ROPE, SURFACE

    system, res = run
    anim = animate(system, res, frames=3)
    try:
        for i in (0, 2):
            anim.animation._draw_frame(i)
            ax = anim.figure.axes[0]
            y = res.at(float(anim.times[i]))["y"]
            string = [ln.get_xydata() for ln in ax.lines if mc.same_color(ln.get_color(), ROPE)]
            assert len(string) == 1
            np.testing.assert_allclose(string[0], [[0, 0], [0, -y]], atol=1e-9)     # A down to the drum's side
            ceiling = [ln.get_xydata() for ln in ax.lines if mc.same_color(ln.get_color(), SURFACE)]
            assert len(ceiling) == 1
            (x0, y0), (x1, y1) = ceiling[0]
            assert y0 == pytest.approx(0, abs=1e-12) and y1 == pytest.approx(0, abs=1e-12)   # across the string
            assert x0 == pytest.approx(-x1) and abs(x0) > 0                                  # centred on A
    finally:
        anim.animation._draw_was_started = True
        anim.close()
