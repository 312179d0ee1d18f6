"""Rich display in Jupyter: System, Solution and simulation results show themselves as HTML (MathML) and LaTeX."""

from __future__ import annotations

import re
import xml.dom.minidom

import pytest
import sympy as sp

from rigidkin import examples
from rigidkin.numeric.simulate import simulate


def _maths(html: str) -> list:
    return [xml.dom.minidom.parseString(m) for m in re.findall(r"<math .*?</math>", html, flags=re.S)]


def test_system_shows_its_model():
    s = examples.build("collar-rod")
    html = s._repr_html_()
    for word in ("collar", "rod", "slender rod", "point mass", "track", "M_track", "R_Px", "gravity"):
        assert word in html
    assert len(_maths(html)) == len(s.parameter_info) + len(s.coordinate_info)
    tex = s._repr_latex_()
    assert tex.startswith("$\\displaystyle") and tex.endswith("$")
    assert r"\theta" in tex and "m_{1}" in tex


def test_solution_shows_equations_and_reactions():
    sol = examples.build("disk-in-track").solve()
    html = sol._repr_html_()
    maths = _maths(html)
    assert any(m.getElementsByTagName("mover") for m in maths)          # θ̈ with dots
    assert "Reactions as functions of the state" in html
    assert sol._repr_latex_().startswith("$")
    # the normal form shown is the solution's own
    th = examples.build("disk-in-track").coordinates[0]
    g, R, r = sp.symbols("g R r", positive=True)
    assert sp.simplify(sol.accelerations[th] - 2 * g * sp.sin(th) / (3 * (r - R))) == 0


@pytest.mark.slow
def test_simulation_result_shows_events_and_figures():
    s = examples.build("ladder")
    res = simulate(s, 1.0, initial_state={"theta": 0.4})
    html = res._repr_html_()
    assert "contact A opens" in html
    assert html.count("data:image/png;base64,") == 2                      # time histories, phase portrait
