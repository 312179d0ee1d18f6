"""The report as a document: a solution laid out in sections of blocks (:mod:`rigidkin.report.blocks`).

``build_document`` lays a solution out in the order of the method: the problem, its parameters and
coordinates, then the derivation trace section by section (frames and coordinates, kinematics,
inertia and momentum, free-body diagram, balance laws, solving), the answers, the cross-checks and
the simulation.  The derivation text is the trace's own (what the laws recorded as they computed);
this module only arranges it and adds the tables and figures.
"""

from __future__ import annotations

import re

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.printing import text as plain_text
from ..base.trace import SECTIONS
from ..base.units import ONE, from_si, shown_unit, si_unit
from ..derive import named
from ..derive.closed_forms import structured
from ..model.speeds import euler_norms
from .blocks import Document, Equations, Figure, Math, Paragraph, Section, Step, Table

t = dynamicsymbols._t


def slug(title: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", title.lower()).strip("-")


#: Sections of every report, in order: (key, title).
REPORT_SECTIONS = (("problem", "Problem"), ("inputs", "Parameters and coordinates")) + tuple(
    (slug(s), s) for s in SECTIONS if s not in ("Answers", "Checks")) + (
    ("answers", "Answers"), ("checks", "Checks"), ("simulation", "Simulation"))


# building -------------------------------------------------------------------------------------------
def _value(v, unit: str = "") -> str:
    if v is None:
        return "—"
    return f"{v:.6g}" + (f" {unit}" if unit else "")


def _unit_of(info) -> str:
    """The unit a coordinate's values are shown in (they are held in SI): rad for an angle, else the SI unit of
    its dimension."""
    dim = getattr(info, "dimension", ONE)
    if getattr(info, "kind", "") == "angle" and dim.is_dimensionless:
        return "rad"
    return si_unit(dim)


def inputs_tables(system, solution=None) -> list[Table]:
    """The parameters (symbol, meaning, unit, value) and coordinates (symbol, sense, kind, unit, initial state)."""
    prows = []
    for p in system.parameter_info.values():
        prows.append((Math(p.symbol), p.description or "", p.shown_unit or "—", _value(p.value_in_unit)))
    independent = set(solution.coordinates) if solution is not None else set(system.coordinates)
    crows = []
    for c in system.coordinate_info.values():
        role = "independent" if c.symbol in independent else "dependent"
        unit = _unit_of(c)
        rate_unit = f"{unit}/s" if unit else "1/s"
        crows.append((Math(c.symbol), c.sense or c.description or "", c.kind, unit or "—", role,
                      _value(c.initial, unit), _value(c.rate, rate_unit)))
    tables = [Table(("Parameter", "Meaning", "Unit", "Value"), tuple(prows), "Parameters")]
    definitions = getattr(system, "definitions", {})
    if definitions:              # derived quantities (System.define): each with its definition
        drows = tuple((Math(sp.Eq(d.quantity.symbol, d.expression, evaluate=False)), d.description or "",
                       shown_unit(d.unit, d.dimension) or "—", _value(from_si(d.value, d.unit)))
                      for d in definitions.values())
        tables.append(Table(("Definition", "Meaning", "Unit", "Value"), drows, "Derived quantities"))
    return tables + [Table(("Coordinate", "Sense", "Kind", "Unit", "Role", "Initial value", "Initial rate"),
                           tuple(crows), "Generalised coordinates")]


def _step(s) -> Step:
    return Step(s.title, tuple(Math(eq) for eq in s.equations), s.why, s.law)


def answers_blocks(solution) -> list:
    """The equations of motion, accelerations, reactions and their conditions, regime by regime."""
    out = []
    if solution.relations:
        out.append(Paragraph("Constraint relations (the dependent coordinates):"))
        out.append(Equations(tuple(Math((q, e)) for q, e in solution.relations.items())))
    if solution.rate_relations:
        out.append(Paragraph("Dependent rates:"))
        out.append(Equations(tuple(Math((q, e)) for q, e in solution.rate_relations.items())))
    several = len(solution.regimes) > 1
    for i, r in enumerate(solution.regimes):
        if several:
            out.append(Paragraph(f"Regime {i + 1}, while its condition holds ("
                                 + (", ".join(c.label for c in r.conditions) or "always") + "):"))
            out.append(Equations(tuple(Math(c.expr, c.relation) for c in r.conditions)))
        norms = euler_norms(solution.system)
        out.append(Paragraph("Equations of motion (each = 0 in mass-matrix form"
                             + "".join(f"; the Euler parameters of {frame} normalised, {plain_text(n)} = 1"
                                       for frame, n in norms) + "):"))
        out.append(Equations(tuple(Math((e, sp.Integer(0))) for e in r.eom)))
        if structured(r):
            out.append(Paragraph(f"Accelerations: {r.form.reason}. " + named.heading(solution.coordinates)))
            out.append(Equations(tuple(Math((k, v)) for k, v in named.rows(named.of_regime(r, solution.system)))))
        else:
            out.append(Paragraph("In normal form:"))
            out.append(Equations(tuple(Math((q.diff(t, 2), a)) for q, a in r.accelerations.items())))
        if r.reactions:
            out.append(Paragraph("Reactions as functions of the state:"))
            out.append(Equations(tuple(Math((sp.Symbol(k), v)) for k, v in r.reactions.items())))
        if r.validity:
            out.append(Paragraph("The solution holds while: " + "; ".join(c.label for c in r.validity) + "."))
            out.append(Equations(tuple(Math(c.expr, c.relation) for c in r.validity)))
    return out


def answer_blocks(answers) -> list:
    """Answers to the problem's questions: name → ``rigidkin.analysis`` Answer, or the reason it has none."""
    if not answers:
        return []
    items = answers.items() if isinstance(answers, dict) else ((a.question.name, a) for a in answers)
    rows = []
    for name, a in items:
        if isinstance(a, str):
            rows.append((name, "", "not answered", "", a))
            continue
        value = a.value
        cell = Math(value) if isinstance(value, sp.Basic) and not isinstance(value, sp.Tuple) else a.text
        note = a.note or ("exact" if a.exact else f"numerical (tolerance {a.tolerance:g})" if a.tolerance else "")
        rows.append((name, a.question.kind, cell, a.text if isinstance(cell, Math) else "", note))
    return [Table(("Question", "Kind", "Answer", "Reading", "Note"), tuple(rows), "Answers to the questions asked")]


def check_blocks(solution) -> list:
    """The cross-check of the solution by other laws (``Solution.check()``), when it is available."""
    check = getattr(solution, "check", None)
    if check is None:
        return [Paragraph("No cross-check is available in this installation (Solution.check).")]
    try:
        result = check()
    except Exception as exc:  # a law that does not apply must not stop the report; say what happened
        return [Paragraph(f"The cross-check could not be run: {exc}")]
    return check_table(result)


def check_table(result) -> list:
    """Blocks from a cross-check report (``rigidkin.derive.laws.crosscheck.CheckReport``): the law × equation
    verdicts and how each was decided, the disagreements with both forms, the dimensions of every equation."""
    verdicts = getattr(result, "verdicts", None)
    if verdicts is None:
        return [Paragraph(str(result))]
    reference = getattr(result, "reference", "the reference law")
    ok = getattr(result, "ok", None)
    out = [Paragraph(f"Every other law that applies, against {reference}"
                     + (": all agree." if ok else ": DISAGREEMENT FOUND." if ok is False else "."))]
    if verdicts:
        out.append(Table(("Law", "Equation", "Result", "How decided"),
                         tuple((v.law, v.equation, v.status, v.how) for v in verdicts),
                         "Cross-check: the equations of motion by every law"))
    else:
        out.append(Paragraph("No other law applies to this model."))
    for v in verdicts:
        if getattr(v, "status", "") == "disagrees" and v.ours is not None and v.reference is not None:
            out.append(Paragraph(f"{v.law} disagrees on {v.equation}: {v.law} (first), {reference} (second)."))
            out.append(Equations((Math(v.ours), Math(v.reference))))
    dims = getattr(result, "dimensions", ())
    if dims:
        rows = tuple((d.label, str(d.dimension) if d.consistent else "—",
                      "consistent" if d.consistent else str(d)) for d in dims)
        good = sum(1 for d in dims if d.consistent)
        out.append(Table(("Equation", "Dimension of every term", "Verdict"), rows,
                         f"Dimensions: {good} of {len(dims)} equations consistent"))
    for e in getattr(result, "expectations", ()):
        out.append(Paragraph(e.describe()))
    for note in getattr(result, "notes", ()):
        out.append(Paragraph(str(note)))
    return out


def build_document(solution, simulation=None, answers=None, figures: bool = True, animation: bool = True,
                   checks: bool = True, values=None, gif: bool = False, frames: int = 80,
                   parameters=None) -> Document:
    """The report of ``solution`` (and of a simulation result, if given) as a Document.

    ``answers`` are the answers to the problem's questions (name → Answer, or the reason there is none);
    ``figures`` draws the free-body diagrams (and, with a simulation, its plots); ``animation`` adds an
    animation of the simulated motion (``frames`` frames; with ``gif`` also as a GIF); ``checks`` runs
    the cross-check; ``values`` is the configuration the free-body diagrams are drawn in (default: the
    initial values); ``parameters`` overrides parameter values in the figures (name → number).
    """
    system = solution.system
    sections = {key: Section(key, title) for key, title in REPORT_SECTIONS}
    prob = sections["problem"]
    prob.blocks.append(Paragraph(system.statement or "(no statement given)"))
    states = ", ".join(f"{k}: {v}" for k, v in solution.states.items())
    prob.blocks.append(Paragraph(f"Derived with the {solution.method} law" + (f"; contacts: {states}." if states
                                                                             else ".")))
    sections["inputs"].blocks.extend(inputs_tables(system, solution))
    for s in solution.trace.steps:
        key = slug(s.section)
        if key in sections:
            sections[key].blocks.append(_step(s))
    if figures and system.bodies:
        from .fbd import free_body_diagram

        fbd = free_body_diagram(solution, values=values, parameters=parameters)
        try:
            shown = ", ".join(f"{plain_text(k)} = {v:.4g}" for k, v in fbd.configuration.items() if k != t)
            note = f" Parameters drawn at 1 (no value given): {', '.join(fbd.assumed)}." if fbd.assumed else ""
            sections["free-body-diagram"].blocks.insert(0, Figure(
                "fbd", fbd.png(), f"Free-body diagrams at {shown}. Applied loads start at their point; reactions "
                                  f"(unknowns) end at it, in the sense their symbol is positive.{note}",
                "free-body diagrams"))
        finally:
            fbd.close()
    ans = sections["answers"]
    ans.blocks.extend(answer_blocks(answers))
    ans.blocks.extend(answers_blocks(solution))
    for s in solution.trace.section("Answers"):
        ans.blocks.append(_step(s))
    chk = sections["checks"]
    for s in solution.trace.section("Checks"):
        chk.blocks.append(_step(s))
    if checks:
        chk.blocks.extend(check_blocks(solution))
    sim = sections["simulation"]
    if simulation is None:
        sim.blocks.append(Paragraph("No simulation was asked for (rigidkin report ... --simulate T)."))
    else:
        from .plots import simulation_blocks

        sim.blocks.extend(simulation_blocks(simulation, solution, figures=figures, animation=animation, gif=gif,
                                            frames=frames))
    for sec in sections.values():
        if not sec.blocks:
            sec.blocks.append(Paragraph("Nothing was recorded in this section for this model and law."))
    return Document(system.title, f"{system.name} — {solution.method}", list(sections.values()))
