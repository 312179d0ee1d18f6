"""Display: how the objects of the lower layers show themselves — the one door up to ``report/``.

A :class:`~rigidkin.model.system.System` (``model/``), a :class:`~rigidkin.derive.solution.Solution`
(``derive/``) and a :class:`~rigidkin.numeric.result.SimulationResult` (``numeric/``) are described below
``report/``, which draws them.  Their display methods (``str``, Jupyter's ``_repr_html_`` and
``_repr_latex_``) call :func:`render`, the only place where a lower layer reaches ``report/``
(:mod:`rigidkin.report.views` says which renderer draws which object in which form).  As with sympy's
``Printable``, the object asks and the printer answers; the object knows nothing of the printer.
"""

from __future__ import annotations


def render(obj, form: str) -> str:
    """``obj`` drawn in ``form`` (``"text"``, ``"html"`` or ``"latex"``) by the renderer report/ names."""
    from ..report.views import render as view  # the door up (tests/test_layers.py: DOORS)

    return view(obj, form)
