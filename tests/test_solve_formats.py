"""``rigidkin solve --format latex|markdown`` say everything the text says.

The ladder (closed forms by hand: θ̈ = 3 g sin θ / (2 l); it leaves the wall at θ = acos(2/3)): every heading of
the text form is a heading of the LaTeX and the Markdown; both give the acceleration (sympy's own LaTeX of the
closed form), the "holds while" conditions, and the answers' numbers.
"""

from __future__ import annotations

import contextlib
import io
import math
import re

import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin.base.printing import latex
from rigidkin.cli import main
from rigidkin.commands.solve_formats import tex_words


@pytest.fixture(scope="module")
def ladder(tmp_path_factory) -> dict[str, str]:
    """``rigidkin solve ladder`` in the three forms (derived once: a cache of its own)."""
    out = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.delenv("RIGIDKIN_NO_CACHE", raising=False)
        mp.setenv("RIGIDKIN_CACHE", str(tmp_path_factory.mktemp("cache")))
        for fmt in ("text", "latex", "markdown"):
            buf = io.StringIO()
            with contextlib.redirect_stdout(buf):
                assert main(["solve", "ladder", "--format", fmt]) == 0
            out[fmt] = buf.getvalue()
    return out


def test_every_heading_of_the_text_is_in_latex_and_markdown(ladder):
    headings = [h for h in ladder["text"].splitlines()[3:] if h and not h.startswith(" ") and not h.startswith("(")]
    expected = {"Coordinates", "Equations of motion", "Accelerations", "Reactions", "Holds while", "Answers"}
    assert expected <= set(headings)
    for h in headings:
        assert rf"\paragraph{{{h}}}" in ladder["latex"], h
        assert f"## {h}" in ladder["markdown"], h


def test_acceleration_conditions_and_numbers(ladder):
    g, l = sp.symbols("g l", positive=True)
    theta = dynamicsymbols("theta")
    closed = latex((theta.diff(dynamicsymbols._t, 2), 3 * g * sp.sin(theta) / (2 * l)))
    number = f"{math.acos(2 / 3):.10g}"                       # where the ladder leaves the wall
    for fmt in ("latex", "markdown"):
        out = ladder[fmt]
        assert closed in out, fmt
        assert r"N_{A} \geq 0" in out and r"N_{B} \geq 0" in out, fmt
        assert number in out and "leaves" in out, fmt
        assert "2.214723459" in out, fmt                     # θ̇ there: sqrt(g/l), g = 9.81, l = 2
    assert abs(math.sqrt(9.81 / 2) - 2.214723459) < 1e-9


def test_latex_has_no_character_a_tex_engine_cannot_read(ladder):
    assert ladder["latex"].isascii()
    assert tex_words("θ̇ = 0, µ ≥ 0") == r"$\dot{\theta}$ = 0, $\mu$ $\geq$ 0"
    assert re.search(r"\\textbf\{leaves\\_wall", ladder["latex"])


def test_regimes_and_their_conditions_in_markdown(capsys):
    """The boulder pushed along rough ground: two regimes (sliding forward, backward), each with its condition."""
    assert main(["solve", "boulder-push", "--no-answers", "--format", "markdown"]) == 0
    out = capsys.readouterr().out
    assert "## Regime 1 of 2" in out and "## Regime 2 of 2" in out
    assert "## Accelerations (regime 1 of 2)" in out and "## Accelerations (regime 2 of 2)" in out
    assert re.search(r"\\dot\{x\} > 0", out) and re.search(r"\\dot\{x\} < 0", out)
