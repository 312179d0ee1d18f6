"""Which renderer draws which object in which form: where :func:`rigidkin.base.display.render` lands.

The display methods of the lower layers' objects (a System's and a SimulationResult's Jupyter views, a
Solution's text and Jupyter views) come here through ``base.display``; the renderers are the terminal form
(:mod:`rigidkin.report.text`) and the compact Jupyter views (:mod:`rigidkin.report.jupyter`).
"""

from __future__ import annotations

from ..derive.solution import Solution
from ..model.system import System
from ..numeric.result import SimulationResult
from .jupyter import result_html, solution_html, system_html, system_latex
from .text import solution_text

#: (class, form) → renderer.
VIEWS = {
    (System, "html"): system_html,
    (System, "latex"): system_latex,
    (Solution, "text"): solution_text,
    (Solution, "html"): solution_html,
    (SimulationResult, "html"): result_html,
}


def render(obj, form: str) -> str:
    for cls in type(obj).__mro__:
        if (cls, form) in VIEWS:
            return VIEWS[(cls, form)](obj)
    raise TypeError(f"no {form} view of a {type(obj).__name__}")
