"""Figures of a simulation: phase portrait with events, the animation (HTML5 player and GIF), the report section."""

from __future__ import annotations

import io
import re

import numpy as np
import pytest
from PIL import Image

from rigidkin import examples
from rigidkin.numeric.simulate import simulate
from rigidkin.report import build_document, render
from rigidkin.report.animate import animate
from rigidkin.report.blocks import Animation, Figure, Table
from rigidkin.report.plots import phase_portrait


@pytest.fixture(scope="module")
def ladder_run():
    """The ladder released at θ0 = 0.3 leaves the wall when cos θ = (2/3) cos θ0 (card ladder (b))."""
    system = examples.build("ladder")
    return system, simulate(system, 1.2, initial_state={"theta": 0.3, "dot(theta)": 0.0})


def test_phase_portrait_marks_the_event_where_the_card_says(ladder_run):
    system, res = ladder_run
    opens = res.events_of("opens")
    assert len(opens) == 1
    assert np.cos(opens[0].state["theta"]) == pytest.approx(2 / 3 * np.cos(0.3), abs=1e-8)
    fig = phase_portrait(res)
    ax = fig.axes[0]
    markers = [ln for ln in ax.lines if ln.get_marker() == "D"]      # one per event (then the top hits the floor)
    assert len(markers) == len(res.events)
    marker = markers[0]
    assert marker.get_xdata()[0] == pytest.approx(opens[0].state["theta"])
    assert marker.get_ydata()[0] == pytest.approx(opens[0].state["dot(theta)"])
    # the curves are the histories, one line per mode
    curves = [ln for ln in ax.lines if ln.get_marker() in ("None", "", None)]
    assert len(curves) == len(res.segments) == 3      # against the wall, free of it, lying on the floor
    assert np.concatenate([c.get_xdata() for c in curves]) == pytest.approx(res["theta"])


def test_animation_player_and_gif(ladder_run):
    system, res = ladder_run
    anim = animate(system, res, frames=12)
    try:
        assert len(anim.times) == 12 and anim.times[-1] == pytest.approx(res.t_final)
        player = anim.to_jshtml()
        assert len(re.findall(r"data:image/png;base64,", player)) == 12
        assert "http" not in player.replace("http://www.w3.org", "")
        assert "<link" not in player
        gif = anim.gif_bytes()
        img = Image.open(io.BytesIO(gif))
        assert gif[:6] == b"GIF89a" and img.n_frames >= 10   # Pillow may merge identical frames
        assert anim.speed == pytest.approx(1.2 / 2.0)       # a motion shorter than 2 s is played over 2 s
    finally:
        anim.close()


def test_animation_frames_follow_the_simulation(ladder_run):
    """The rod drawn in the last frame lies from B = (x, 0) to A = B + l (−sin θ, cos θ) of the final state."""
    system, res = ladder_run
    anim = animate(system, res, frames=3)
    try:
        assert anim.to_jshtml().count("data:image/png;base64,") == 3
        anim.animation._draw_frame(2)     # the last frame again, to read what it drew
        ax = anim.figure.axes[0]
        rod = [ln for ln in ax.lines if ln.get_linewidth() == 7][0]
        xs, ys = rod.get_xdata(), rod.get_ydata()
        fin = res.final_state
        th, x = fin["theta"], fin["x"]
        np.testing.assert_allclose(sorted(zip(xs, ys)), sorted([(x, 0.0), (x - 2 * np.sin(th), 2 * np.cos(th))]),
                                   atol=1e-7)
    finally:
        anim.close()


def test_report_simulation_section(ladder_run):
    system, res = ladder_run
    doc = build_document(system.solve(), simulation=res, checks=False, gif=True, frames=6)
    blocks = doc.section("simulation").blocks
    events = [b for b in blocks if isinstance(b, Table)][0]
    assert events.rows[0][2] == res.events[0].name
    keys = [b.key for b in blocks if isinstance(b, (Figure, Animation))]
    assert keys == ["time-histories", "phase-portrait", "motion"]
    anim = [b for b in blocks if isinstance(b, Animation)][0]
    assert anim.gif[:6] == b"GIF89a"
    page = render(doc, "html")
    assert 'id="animation-motion"' in page and "fa-play" not in page
