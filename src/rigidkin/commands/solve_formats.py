"""``rigidkin solve --format latex|markdown``: everything the text form says, as LaTeX or Markdown.

The same sections as the terminal (:func:`rigidkin.report.text.problem_text`): coordinates with their senses
and the constraints' relations, definitions, for each regime its conditions, the equations of motion, the
accelerations, the reactions (each with what it is) and the conditions it holds while, the slip direction
of 3D friction, the answers with their exact values *and* numbers (time and state of an event), notes and
warnings.  Both are built from one list of sections, so that neither can say less than the other.
"""

from __future__ import annotations

import re
import unicodedata

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.plaintext import to_ascii
from ..base.printing import latex
from ..base.textsafe import markdown_text
from ..derive import named as named_form
from ..derive.closed_forms import structured
from ..io.results import answer_data
from ..model.speeds import euler_norms
from ..report.notation import latex_text
from ..report.text import reaction_labels

t = dynamicsymbols._t
_REL = {">": ">", "<": "<", ">=": r"\geq", "<=": r"\leq"}


# one list of sections: (heading, entries); an entry is ("text", words), ("math", tex) or ("item", words, tex)
def _condition(c) -> str:
    return f"{latex(c.expr)} {_REL[c.relation]} 0"


def _coordinates(sol) -> list:
    s = sol.system
    by_speeds = {q for g in getattr(s, "speed_groups", {}).values() for q in g.coordinates}
    out = []
    for c in s.coordinate_info.values():
        role = "" if c.symbol in sol.coordinates else \
            " (its rate from the speeds: q̇ = W(q) u)" if c.symbol in by_speeds else " (dependent)"
        out.append(("item", f"({c.kind}): {c.sense or c.description or 'no sense given'}{role}", latex(c.symbol)))
    if sol.relations:
        out.append(("text", "while the constraints hold:"))
        out += [("math", f"{latex(q)} = {latex(e)}") for q, e in sol.relations.items()]
    return out


def _definitions(s) -> list:
    out = []
    for d in getattr(s, "definitions", {}).values():
        value = f" = {d.value:.6g}" + (f" {d.unit}" if d.unit else "") if d.value is not None else ""
        out.append(("item", f"{value}  {d.description or ''}".strip(),
                    f"{latex(d.quantity)} = {latex(d.expression)}"))
    return out


def _regime(sol, r, shown, labels, eom) -> list:
    out = []
    if eom and not sol.coordinates:
        out.append(("Equations of motion", [("text", "none: no degree of freedom remains in this mode; the "
                                                     "reactions follow from statics")]))
    elif eom:
        entries = [("text", f"(written with the Euler parameters of {frame} normalised)") for frame, _ in
                   euler_norms(sol.system)]
        entries += [("math", f"{latex(norm)} = 1") for _, norm in euler_norms(sol.system)]
        entries += [("math", f"{latex(e)} = 0") for e in r.eom]
        out.append(("Equations of motion", entries))
        if structured(r):
            acc = [("text", f"{r.form.reason}; the reactions are in terms of q̈"),
                   ("text", named_form.heading(sol.coordinates))]
            form = named_form.of_regime(r, sol.system)
            acc += [("math", f"{latex(k)} = {latex(v)}") for k, v in named_form.rows(form)]
        else:
            acc = [("math", f"{latex(q.diff(t, 2))} = {latex(a)}") for q, a in r.accelerations.items()]
        out.append(("Accelerations", acc))
    names = [k for k in (shown if shown is not None else r.reactions) if k in r.reactions]
    if names:
        out.append(("Reactions", [("item", labels.get(k, "reaction"), f"{latex(sp.Symbol(k))} = "
                                                                      f"{latex(r.reactions[k])}") for k in names]))
    if getattr(r, "indeterminate", None):                  # statically indeterminate (derive/indeterminate.py)
        ind = r.indeterminate
        out.append(("Statically indeterminate", [("text", ind.lines()[0])]
                    + [("math", f"{latex(c)} = {latex(v)}") for c, v in ind.combinations]
                    + [("text", note) for note in ind.friction]))
    if r.validity:
        named = {v: k for k, v in r.reactions.items()}         # N_A ≥ 0 rather than its expression
        out.append(("Holds while", [("item", c.label, f"{latex(sp.Symbol(named[c.expr]))} {_REL[c.relation]} 0"
                                     if c.expr in named else _condition(c)) for c in r.validity]))
    return out


def _answer(name, a, description, values) -> list:
    out = [("name", f"{name}" + (f" — {description}" if description else ""))]
    if isinstance(a, str):
        return out + [("text", f"not answered: {a}")]
    out += [("text", line) for line in a.text.splitlines()]
    data = answer_data(a, values)
    value = data.get("value") or {}
    if isinstance(a.value, sp.Basic) and not isinstance(a.value, sp.Eq | sp.Symbol):
        number = value.get("numeric")
        out.append(("item", f"≈ {number:.10g}" if number is not None else "", latex(a.value)))
    if data.get("time") is not None:
        out.append(("item", f"at t = {data['time']:.10g} s", ""))
    for key, q in (data.get("state") or {}).items():
        if q.get("numeric") is not None:
            out.append(("item", f"{key} = {q['numeric']:.10g}", ""))
    if a.tolerance is not None and not a.exact:
        out.append(("text", f"(numerical, to within {a.tolerance:g})"))
    if a.note:
        out.append(("text", f"note: {a.note}"))
    return out


def sections(sol, spec=None, answers: dict | None = None, notes=()) -> tuple[str, str, list]:
    """(title, subtitle, [(heading, entries)]) of a solution: what ``rigidkin solve`` prints, as data."""
    s = sol.system
    shown = spec.reactions if spec is not None else None
    eom = spec.eom if spec is not None else True
    out = [("Coordinates", _coordinates(sol))]
    if _definitions(s):
        out.append(("Definitions", _definitions(s)))
    labels = reaction_labels(s)
    for i, r in enumerate(sol.regimes):
        parts = _regime(sol, r, shown, labels, eom)
        if len(sol.regimes) > 1:
            head = f"Regime {i + 1} of {len(sol.regimes)}"
            out.append((head, [("item", c.label, _condition(c)) for c in r.conditions] or [("text", "always")]))
            parts = [(f"{h} ({head.lower()})", e) for h, e in parts]
        out += parts
    slips = [st for st in sol.trace.steps if st.title.startswith("Slip velocity and its direction at ")]
    if slips:
        out.append(("Slip direction (while the slip speed |v_s| > 0)",
                    [("math", f"{latex(lhs)} = {latex(rhs)}") for st in slips for lhs, rhs in st.equations]))
    if answers:
        described = {q.name: q.fields.get("description", "") for q in (spec.questions if spec is not None else ())}
        values = s.parameter_values()
        out.append(("Answers", [e for n, a in answers.items() for e in _answer(n, a, described.get(n), values)]))
    if notes:
        out.append(("Notes", [("text", n) for n in notes]))
    if sol.warnings:
        out.append(("Warnings", [("text", w) for w in sol.warnings]))
    return s.title, f"derived with {sol.method}", out


# LaTeX ------------------------------------------------------------------------------------------------------
_MATH_LETTER = re.compile(r"([A-Za-z][\u0307\u0308]|[\u0370-\u03ffµ][\u0307\u0308]?)")


def _greek_tex(letter: str) -> str:
    base, marks = letter[0], letter[1:]
    tex = sp.latex(sp.Symbol(to_ascii(base))) if not base.isascii() else base
    return {"\u0307": rf"\dot{{{tex}}}", "\u0308": rf"\ddot{{{tex}}}"}.get(marks, tex)


def tex_words(words: str) -> str:
    """Words for TeX with their Greek letters and dotted rates as math (θ̇ → ``$\\dot{\\theta}$``), the rest
    escaped (:func:`rigidkin.report.notation.latex_text`)."""
    parts = _MATH_LETTER.split(unicodedata.normalize("NFD", str(words)))
    return "".join(f"${_greek_tex(p)}$" if i % 2 else latex_text(p) for i, p in enumerate(parts))


def to_latex(sol, spec=None, answers=None, notes=()) -> str:
    """A LaTeX fragment (amsmath) of everything ``rigidkin solve`` prints."""
    title, subtitle, body = sections(sol, spec, answers, notes)
    out = [rf"\section*{{{tex_words(title)}}}", rf"\emph{{({tex_words(subtitle)})}}"]
    for heading, entries in body:
        out.append(rf"\paragraph{{{tex_words(heading)}}}")
        for e in entries:
            if e[0] == "math":
                out.append(rf"\[ {e[1]} \]")
            elif e[0] == "text":
                out.append(tex_words(e[1]) + r"\par")
            elif e[0] == "name":
                out.append(rf"\textbf{{{tex_words(e[1])}}}\par")
            else:
                math = f"${e[2]}$" if e[2] else ""
                out.append(f"{math} {tex_words(e[1])}".strip() + r"\par")
    return "\n".join(out)


# Markdown ---------------------------------------------------------------------------------------------------
def to_markdown(sol, spec=None, answers=None, notes=()) -> str:
    """Markdown (math as ``$…$`` and ``$$…$$``) of everything ``rigidkin solve`` prints."""
    title, subtitle, body = sections(sol, spec, answers, notes)
    out = [f"# {markdown_text(title)}", f"*({markdown_text(subtitle)})*"]
    for heading, entries in body:
        out.append(f"## {markdown_text(heading)}")
        blocks: list[str] = []
        for e in entries:
            if e[0] == "math":
                blocks.append(f"$$\n{e[1]}\n$$")
            elif e[0] == "text":
                blocks.append(markdown_text(e[1]))
            elif e[0] == "name":
                blocks.append(f"**{markdown_text(e[1])}**")
            else:                           # consecutive items make one list
                item = "- " + " ".join(x for x in (f"${e[2]}$" if e[2] else "", markdown_text(e[1])) if x)
                if blocks and blocks[-1].startswith("- "):
                    blocks[-1] += "\n" + item
                else:
                    blocks.append(item)
        out.append("\n\n".join(blocks))
    return "\n\n".join(out) + "\n"
