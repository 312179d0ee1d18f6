"""A blank worksheet for a problem: the steps of the method, and one answer step per quantity each question
asks, saying what is asked in words and symbol, with its SI unit.

``rigidkin grade --template PROBLEM`` prints it; a student fills in the claims.
"""

from __future__ import annotations

import json

from ..io.locate import resolve_problem
from .answers import held, quantities
from .engine import reference

_METHOD = (("kinematics", "the velocity or acceleration of a point, or ω, α of a body: 'a_G = ...'"),
           ("fbd", "every load on one body with its point: '-m*g*Ey at G; N*Ex at A'"),
           ("balance", "a balance law (law = force | moment | energy, direction or point): 'lhs = rhs'"),
           ("eom", "an equation of motion, free of the reactions"))


def asked_lines(ref, question: str) -> list[str]:
    """What a question asks, one line per quantity it asks (the rest it states are listed after)."""
    qs = quantities(ref, question)
    out = []
    for q in qs:
        unit = f", in {q.unit}" if q.unit else ""
        verb = "asks" if q.asked and not held(ref, q) else "also states"
        out.append(f"{verb} {q.describe()}{unit}; quantity = {json.dumps(q.names[0] if q.names else q.symbol)}")
    return out


def template(problem: str, folder=None) -> str:
    """The worksheet text (TOML) for ``problem`` (a bundled name or a problem file)."""
    how, found = resolve_problem(problem, folder)
    ref = reference(problem if how == "example" else str(found))
    title = getattr(ref.spec, "title", "") or problem
    lines = [f"# Worksheet on {title}", f"problem = {json.dumps(problem)}", 'student = ""', ""]
    if len(ref.regimes()) > 1:
        lines += ["# the sliding direction is fixed by the motion; an instructor may state it as a condition on",
                  "# a slip speed, motion = \"... > 0\", one of: "
                  + "; ".join(" ".join(r.describe().split()) for r in ref.regimes()), ""]
    for kind, what in _METHOD:
        lines += [f"# {what}", "[[step]]", f"kind = \"{kind}\"", "claim = \"\"", ""]
    for q in ref.spec_questions():
        desc = q.fields.get("description") or q.name
        lines.append(f"# question '{q.name}': {desc}")
        asked = asked_lines(ref, q.name)
        for a in asked:
            lines.append(f"#   {a}")
        lines += ["[[step]]", "kind = \"answer\"", f"question = {json.dumps(q.name)}"]
        wanted = [a for a in asked if a.startswith("asks")] or asked[:1]
        wanted += [a for a in asked if "natural frequency" in a and a not in wanted]
        for k, a in enumerate(wanted or [""]):
            if k:
                lines += ["[[step]]", "kind = \"answer\"", f"question = {json.dumps(q.name)}"]
            if a:
                lines.append(a.split("; ")[-1])
            lines += ["claim = \"\"", ""]
    return "\n".join(lines)
