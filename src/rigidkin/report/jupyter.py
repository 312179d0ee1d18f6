"""Rich display in Jupyter: HTML and LaTeX views of a System, a Solution and a simulation result.

These are compact views: what the object *is* (a system's parameters, coordinates, bodies,
constraints and loads; a solution's equations of motion and reactions; a simulation's modes and
events with its figures).  The whole derivation is ``rigidkin.report.build_document`` /
``write_report``; sliders that re-simulate are :func:`explore` (:mod:`rigidkin.report.widgets`).

Every formula is presentation MathML, which browsers draw themselves (Chromium, Firefox, Safari): a
notebook's output reads the same in JupyterLab, in Notebook, in VS Code and in a notebook exported to
HTML and opened offline (nbconvert's page loads MathJax from the network; nothing here needs it).  The
formula's TeX travels with it as the ``alttext`` of its ``<math>`` element (to copy, or for a reader that
prefers it); ``text/latex`` bundles (``_repr_latex_``) stay TeX.  The fragment is marked for MathJax to
leave alone (a ``$`` in a description stays a dollar sign), and it holds no script.
"""

from __future__ import annotations

import re

from sympy.physics.vector import dynamicsymbols

from ..base.textsafe import html_text
from .blocks import Math, Paragraph, Table
from .document import answers_blocks, inputs_tables
from .html import _math as _mathml
from .html import block_html as _report_block
from .notation import latex, latex_condition
from .widgets import explore as _explore

t = dynamicsymbols._t

#: MathJax's classes (2: classic Notebook; 3: JupyterLab, Notebook 7): leave this fragment alone.
IGNORE = "tex2jax_ignore mathjax_ignore"

STYLE = ("<style>.rigidkin table{border-collapse:collapse;margin:.4em 0}.rigidkin th,.rigidkin td{border:1px "
         "solid #ccc;padding:.2em .5em;text-align:left;vertical-align:top}.rigidkin caption{text-align:left;"
         "font-weight:bold}.rigidkin .step{margin:.4em 0}.rigidkin .why{font-style:italic;color:#444}"
         ".rigidkin .eqs{overflow-x:auto}.rigidkin .law{font-size:smaller;font-weight:normal;margin-left:.6em}"
         ".rigidkin math[display=block]{margin:.3em 0}</style>")


def _esc(s: str) -> str:
    return html_text(s)


def tex(m: Math) -> str:
    """The TeX of a formula (no delimiters): rates with dots, ``\\dot{\\theta}``, ``\\ddot{\\theta}``."""
    return latex_condition(m.obj, m.relation) if m.relation is not None else latex(m.obj)


def _math(m: Math, display: bool) -> str:
    """A formula as MathML (drawn by the browser, no MathJax), its TeX as the ``alttext``."""
    return _mathml(m, display).replace("<math ", f'<math alttext="{html_text(tex(m))}" ', 1)


def block_html(b) -> str:
    """One block of a document as an HTML fragment for a notebook (MathML, the report's layout)."""
    return _report_block(b, _math, heading="h4", anchors=False)


def fragment(title: str, blocks) -> str:
    body = "\n".join(block_html(b) for b in blocks)
    return f'{STYLE}<div class="rigidkin {IGNORE}"><h3>{_esc(title)}</h3>{body}</div>'


def model_tables(system) -> list:
    """Bodies, constraints and loads of a system, one row each."""
    bodies = tuple((b.name, b.shape.kind, ", ".join(f"{k} = {v}" for k, v in b.shape.dimensions.items()),
                    b.frame.name, b.reference.name) for b in system.bodies.values())
    cons = tuple((c.name, c.kind, ", ".join(str(r) for r in c.reactions()), c.description)
                 for c in system.constraints.values())
    loads = tuple((ld.name, ld.kind, ld.description) for ld in system.loads.values())
    return [Table(("Body", "Shape", "Dimensions", "Frame", "Placed at"), bodies, "Bodies"),
            Table(("Constraint", "Kind", "Reactions", "Description"), cons, "Constraints"),
            Table(("Load", "Kind", "Description"), loads, "Loads")]


def system_html(system) -> str:
    blocks = [Paragraph(system.statement)] if system.statement else []
    return fragment(system.title, blocks + inputs_tables(system) + model_tables(system))


def _mathjax_text(s: str) -> str:
    """Text for ``\\text{...}`` in a notebook (MathJax): TeX's specials escaped, Unicode kept as it is."""
    s = "".join(ch for ch in str(s) if ch == " " or ch.isprintable())
    s = re.sub(r"([#$%&_{}])", r"\\\1", s.replace("\\", "\0"))
    return s.replace("\0", r"\backslash ").replace("^", r"\hat{}").replace("~", r"\sim ")


def _no_markup(s: str) -> str:
    """No ``<`` or ``>`` in a LaTeX display (the classic notebook inserts it as HTML): look-alikes instead."""
    return s.replace("<", "\u2039").replace(">", "\u203a")


def system_latex(system) -> str:
    """Coordinates (with their senses) and parameters, one per row, for ``System._repr_latex_``."""
    rows = [rf"{latex(c.symbol)} & \text{{{_mathjax_text(c.sense or c.description or c.kind)}}}"
            for c in system.coordinate_info.values()]
    rows += [rf"{latex(p.symbol)} & \text{{{_mathjax_text(p.description or '')}"
             + (f" ({_mathjax_text(p.shown_value)})" if p.value is not None else "") + "}"
             for p in system.parameter_info.values()]
    head = rf"\text{{{_mathjax_text(system.title)}}} & "
    return _no_markup("$\\displaystyle \\begin{array}{ll}" + " \\\\ ".join([head, *rows]) + "\\end{array}$")


def solution_html(solution) -> str:
    return fragment(f"{solution.system.title} — {solution.method}", answers_blocks(solution))


def result_html(result, figures: bool = True) -> str:
    """A simulation result: summary, modes, events and (with ``figures``) its time histories and phase portrait."""
    from .plots import simulation_blocks

    return fragment(f"{result.title}: simulation", simulation_blocks(result, None, figures=figures, animation=False))


def explore(obj, **kwargs):
    """Sliders for the parameters that re-simulate and redraw (see :func:`rigidkin.report.widgets.explore`)."""

    return _explore(obj, **kwargs)
