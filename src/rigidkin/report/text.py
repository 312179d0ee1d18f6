"""The terminal form of a solution: coordinates and senses restated, one equation per block."""

from __future__ import annotations

from sympy.physics.vector import dynamicsymbols

from ..printing import text

t = dynamicsymbols._t


def solution_text(sol) -> str:
    s = sol.system
    out = [f"{s.title} — {sol.method}"]
    out.append("Coordinates:")
    for c in s.coordinate_info.values():
        role = "" if c.symbol in sol.coordinates else " (dependent)"
        out.append(f"  {text(c.symbol)}{role}: {c.sense or c.description}")
    if sol.relations:
        out.append("Constraint relations:")
        for q, e in sol.relations.items():
            out.append(f"  {text(q)} = {text(e)}")
    for i, r in enumerate(sol.regimes):
        if len(sol.regimes) > 1:
            out.append(f"Regime {i + 1}: while {r.describe()}")
        out.append("Equations of motion:")
        for e in r.eom:
            out.append(f"  {text(e)} = 0")
        out.append("Accelerations:")
        for q, a in r.accelerations.items():
            out.append(f"  {text(q.diff(t, 2))} = {text(a)}")
        if r.reactions:
            out.append("Reactions:")
            for k, v in r.reactions.items():
                out.append(f"  {k} = {text(v)}")
        if r.validity:
            out.append("Holds while:")
            for c in r.validity:
                out.append(f"  {c}")
    return "\n".join(out)
