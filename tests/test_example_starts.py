"""Every bundled example's own start shows its motion: ``rigidkin report NAME --simulate 3`` from the
declared initial state moves something visibly (a coordinate changes by at least 0.2 rad or 0.2 m in 3 s)
— not a rod balanced 1e-6 rad off upright.  The cards' questions set their own starts."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import rigidkin.examples as examples
from rigidkin.numeric.simulate import simulate

ALL = sorted(p.stem for p in Path(examples.__file__).parent.glob("*.toml"))
QUICK = ["ladder", "sphere-on-sphere", "rod-impulse"]          # the starts that were 1e-6 or at rest


def _largest_change(name: str) -> tuple[float, dict]:
    s = examples.build(name)
    r = simulate(s, 3.0, n_points=120)
    spans = {c: float(np.ptp(r[c])) for c in s.coordinate_info}
    return max(spans.values()), spans


@pytest.mark.parametrize("name", QUICK)
def test_default_start_shows_the_motion(name):
    largest, spans = _largest_change(name)
    assert largest >= 0.2, spans


@pytest.mark.slow
@pytest.mark.parametrize("name", [n for n in ALL if n not in QUICK])
def test_every_bundled_start_shows_the_motion(name):
    largest, spans = _largest_change(name)
    assert largest >= 0.2, spans


def test_ladder_start_leaves_the_wall_as_the_card_says():
    """From the file's start θ0 = 0.3 at rest the rod leaves the wall where cos θ = (2/3) cos θ0 (card (b),
    the general release angle), and hits the floor with its upper end within the 3 s a report shows."""
    s = examples.build("ladder")
    th0 = s.coordinate_info["theta"].initial
    assert th0 == pytest.approx(0.3)
    r = simulate(s, 3.0)
    names = [e.name for e in r.events]
    assert names[0] == "contact A opens", names
    assert abs(r.events[0].state["theta"] - np.arccos(2 / 3 * np.cos(th0))) < 1e-8
    assert any(e.kind == "impact" for e in r.events), names
