"""``rigidkin draw``: the geometry and free-body diagrams of a problem, also of one that cannot be solved.

The Atwood machine of test_vocabulary_ropes with the rope wrapped the wrong way (``ccw``) gives balance laws
that contradict each other: ``solve`` refuses it (and says to draw it), ``draw`` draws it.  The ropes drawn
are checked against the tangent points by hand: wrapped clockwise over a pulley of radius R at O, the rope
leaves it at (−R, 0) and (R, 0) and hangs straight down to A = (−R, −y1) and B = (R, −y2); wrapped the other
way its two straight parts cross.
"""

from __future__ import annotations

import contextlib
import io
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from test_vocabulary_ropes import ATWOOD_FILE

from rigidkin.cli import main
from rigidkin.io.problem import parse_problem
from rigidkin.report.drawing import _rope_segments
from rigidkin.report.geometry import Geometry

WRONG = ATWOOD_FILE.replace('sense = "cw"', 'sense = "ccw"')


def _run(argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


def _crosses(p, q, r, s) -> bool:
    """Whether the segments p–q and r–s cross (orientation test)."""
    def side(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    return side(p, q, r) != side(p, q, s) and side(r, s, p) != side(r, s, q)


def test_ropes_drawn_at_their_tangent_points():
    system, _ = parse_problem(ATWOOD_FILE, "atwood.toml")
    geom = Geometry(system)
    (s1, s2) = _rope_segments(geom, system.constraints["rope"], geom.configuration())
    assert np.allclose(s1, [[-0.1, -1.0], [-0.1, 0.0]], atol=1e-12)
    assert np.allclose(s2, [[0.1, 0.0], [0.1, -1.0]], atol=1e-12)
    assert not _crosses(*s1, *s2)
    wrong, _ = parse_problem(WRONG, "atwood.toml")
    geom = Geometry(wrong)
    (w1, w2) = _rope_segments(geom, wrong.constraints["rope"], geom.configuration())
    assert _crosses(*w1, *w2)                          # the wrong wrap is seen: the rope crosses itself


def test_a_file_whose_laws_contradict_is_refused_by_solve_and_drawn(tmp_path):
    f = tmp_path / "atwood.toml"
    f.write_text(WRONG)
    code, _, err = _run(["solve", str(f), "--no-cache"])
    assert code == 2 and "contradict" in err and "rigidkin draw" in err
    code, out, err = _run(["draw", str(f), "-o", str(tmp_path / "atwood.svg")])
    assert code == 0, err
    for name in ("atwood.svg", "atwood-fbd.svg"):
        assert f"wrote {tmp_path / name}" in out
        root = ET.parse(tmp_path / name).getroot()
        assert root.tag.endswith("svg") and (tmp_path / name).stat().st_size > 5000


@pytest.mark.parametrize(("argv", "words"), [
    (["draw", "ladder", "-o", "x.txt"], "no known format"),
    (["draw", "ladder", "--at", "phi=1"], "names no coordinate"),
])
def test_bad_options_are_one_paragraph(argv, words, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = _run(argv)
    assert code == 2 and words in err and "Traceback" not in err


def test_the_animation_draws_the_rope():
    """The animation's frames draw the rope (two straight parts and the arc on the pulley), where it was drawn
    with the bodies only before; the rope's ends are on the blocks, so no ceiling is drawn for it."""
    import matplotlib.colors as mc

    from rigidkin.numeric.simulate import simulate
    from rigidkin.report.animate import animate
    from rigidkin.report.drawing import ROPE

    system, _ = parse_problem(ATWOOD_FILE, "atwood.toml")
    anim = animate(system, simulate(system, 0.2), frames=3)
    anim.animation._draw_frame(1)
    ax = anim.figure.axes[0]
    rope = [ln for ln in ax.lines if mc.same_color(ln.get_color(), ROPE)]
    assert len(rope) == 2
    ends = sorted(tuple(np.round(ln.get_xydata()[0], 9)) for ln in rope)
    assert [e[0] for e in ends] == pytest.approx([-0.1, 0.1])          # straight down from the rim at x = ∓R
    assert any(mc.same_color(p.get_edgecolor(), ROPE) for p in ax.patches)  # the arc over the pulley
    anim.animation._draw_was_started = True          # drawn by hand here: no "deleted without rendering" warning
    anim.close()
