"""The terminal form of a solution, for people: the coordinates and their senses restated, one equation
per block in unicode math (θ̈, θ̇, µ), each reaction and answer named with what it is.  What a problem
file wrote (title, senses, descriptions) cannot drive the terminal: control characters and escape
sequences are shown as visible escapes (:func:`rigidkin.base.textsafe.terminal_safe`).
"""

from __future__ import annotations

from sympy.physics.vector import dynamicsymbols

from ..base.printing import text
from ..base.textsafe import terminal_safe
from ..base.units import shown_value
from ..derive import named as named_form
from ..derive.closed_forms import structured
from ..derive.derivation import derivation_of
from ..model.speeds import euler_norms

t = dynamicsymbols._t
_INDENT = "    "


def _along(vector) -> str:
    """', positive along −Ex' for a reaction's direction (empty when it cannot be written simply)."""
    try:
        words = text(vector)
    except (TypeError, ValueError):
        return ""
    return f", positive along {words}" if len(words) <= 40 else ""


def _directions(system, c) -> dict:
    """Reaction symbol → its direction vector for contacts and collars (planar problems)."""
    try:
        kin = derivation_of(system).kinematics()
        if not kin.planar:
            return {}
        if c.kind == "contact" and hasattr(c, "tangents"):
            out = {c.N: kin.simplify_vector(c.normal(kin))}
            if len(c.reactions()) > 1:
                out[c.F] = c.tangents(kin)[0]
            return out
        if c.kind == "collar":
            return {c.N: c._normals(kin)[0]}
    except Exception:          # a direction is a courtesy: never let it stop the report
        return {}
    return {}


def reaction_labels(system) -> dict[str, str]:
    """Reaction name → what it is (``"normal force of contact A, positive along Ex (wall)"``)."""
    out = {}
    for c in system.constraints.values():
        syms = c.reactions()
        dirs = _directions(system, c)
        for sym in syms:
            name = sym.name
            kind = c.kind
            if kind == "contact":
                what = "normal force" if sym == c.N else "friction force"
                label = f"{what} of contact {c.name}" + (_along(dirs[sym]) if sym in dirs else "")
            elif kind == "collar":
                what = "track normal force" if name.startswith(c.N.name) else "track reaction couple"
                label = f"{what} of collar {c.name}" + (_along(dirs[sym]) if sym in dirs else "")
            elif hasattr(c, "reaction_label"):        # e.g. a rope: the tension of each segment
                label = c.reaction_label(sym)
            elif kind == "pin" and name[-1:] in ("x", "y", "z"):
                frame = getattr(c, "basis_frame", None) or system.inertial
                label = f"pin reaction of {c.name} along {frame.basis['xyz'.index(name[-1])]}"
            else:
                label = f"reaction of {kind} {c.name}"
            if c.description:
                label += f" ({c.description})"
            out[name] = label
        if c.kind == "pin" and getattr(c, "axis", None):      # a 3D hinge: its torques about the other two axes
            frame_name, _, along = str(c.axis).partition(".")
            for comp in "xyz".replace(along[-1:], "") if along else "":
                label = f"hinge torque of {c.name} about {frame_name}.{comp} (the hinge turns about {c.axis})"
                out.setdefault(f"M_{c.name}{comp}", label + (f" ({c.description})" if c.description else ""))
    return out


def _coordinates(sol) -> list[str]:
    s = sol.system
    out = ["Coordinates"]
    # coordinates whose rates the speeds give (Euler parameters, angles with angular speeds): q̇ = W(q) u
    by_speeds = {q for g in getattr(s, "speed_groups", {}).values() for q in g.coordinates}
    for c in s.coordinate_info.values():
        role = "" if c.symbol in sol.coordinates else \
            "  [its rate from the speeds: q̇ = W(q) u]" if c.symbol in by_speeds else "  [dependent]"
        out.append(f"{_INDENT}{text(c.symbol)} ({c.kind}): {c.sense or c.description or 'no sense given'}{role}")
    if sol.relations:
        out.append(f"{_INDENT}while the constraints hold:")
        for q, e in sol.relations.items():
            out.append(f"{_INDENT * 2}{text(q)} = {text(e)}")
    definitions = getattr(s, "definitions", {})
    if definitions:
        out += ["", "Definitions"]
        for d in definitions.values():
            value = f" = {shown_value(d.value, d.unit, d.dimension)}" if d.value is not None else ""
            about = f"  ({d.description})" if d.description else ""
            out.append(f"{_INDENT}{text(d.quantity)} = {text(d.expression)}{value}{about}")
    return out


def _regime(sol, r, reactions, labels, eom=True) -> list[str]:
    out = []
    if eom and not sol.coordinates:
        out += ["Equations of motion", f"{_INDENT}none: no degree of freedom remains in this mode (at rest, or carried "
                "by the constraints); the reactions follow from statics", ""]
    elif eom:
        out += ["Equations of motion", ""]
        for frame, norm in euler_norms(sol.system):
            out += [f"{_INDENT}(written with the Euler parameters of {frame} normalised: {text(norm)} = 1)", ""]
        for i, e in enumerate(r.eom, start=1):
            out += [f"{_INDENT}({i})  {text(e)} = 0", ""]
        out.append("Accelerations")
        if structured(r):
            out.append(f"{_INDENT}{r.form.reason}: M q̈ = f are the equations above; the reactions below are in "
                       "terms of q̈")
            out += _named_lines(sol, r)
        else:
            for q, a in r.accelerations.items():
                out.append(f"{_INDENT}{text(q.diff(t, 2))} = {text(a)}")
        out.append("")
    shown = [k for k in (reactions if reactions is not None else r.reactions) if k in r.reactions]
    if shown:
        out += ["Reactions"]
        for k in shown:
            out.append(f"{_INDENT}{k}: {labels.get(k, 'reaction')}")
            out.append(f"{_INDENT * 2}{k} = {text(r.reactions[k])}")
    if getattr(r, "indeterminate", None):        # statically indeterminate (derive/indeterminate.py)
        out += ["", "Statically indeterminate"] + [f"{_INDENT}{line}" for line in r.indeterminate.lines()]
    if r.validity:
        out += ["" if shown else None, "Holds while"]
        out = [line for line in out if line is not None]
        named = {v: k for k, v in r.reactions.items()}
        for c in r.validity:
            rel = c.relation.replace(">=", "≥").replace("<=", "≤")
            if c.expr in named:
                out.append(f"{_INDENT}{named[c.expr]} {rel} 0   ({c.label})")
            else:
                out.append(f"{_INDENT}{c}")
    return out


def _named_lines(sol, r) -> list[str]:
    """M and f of a structured regime with named common sub-expressions (derive/named.py)."""
    out = [f"{_INDENT}{named_form.heading(sol.coordinates)}"]
    out += [f"{_INDENT * 2}{text(k)} = {text(v)}" for k, v in named_form.rows(named_form.of_regime(r, sol.system))]
    return out


def solution_text(sol, reactions=None, eom: bool = True) -> str:
    """A solution for a terminal; ``reactions`` limits the reactions shown (default: all); ``eom=False``
    leaves out the equations of motion and accelerations (a problem file's ``[ask] eom = false``)."""
    s = sol.system
    out = [s.title, f"(derived with {sol.method})", ""]
    out += _coordinates(sol)
    labels = reaction_labels(s)
    for i, r in enumerate(sol.regimes):
        out.append("")
        if len(sol.regimes) > 1:
            out += [f"Regime {i + 1} of {len(sol.regimes)}: while {r.describe()}", ""]
        out += _regime(sol, r, reactions, labels, eom)
    slips = [st for st in sol.trace.steps if st.title.startswith("Slip velocity and its direction at ")]
    if slips:                   # 3D sliding friction −µN û (model.friction3d): what û stands for
        out += ["", "Slip direction (while the slip speed |v_s| > 0; v_s = s1 t1 + s2 t2)"]
        out += [f"{_INDENT}{text(lhs)} = {text(rhs)}" for st in slips for lhs, rhs in st.equations]
    return terminal_safe("\n".join(out))


def answers_text(answers: dict, questions=()) -> str:
    """The answers, each under its name and description; a string value is the reason it is missing."""
    if not answers:
        return ""
    described = {q.name: q.fields.get("description", "") for q in questions}
    out = ["Answers"]
    for name, a in answers.items():
        head = f"{_INDENT}{name}" + (f" — {described[name]}" if described.get(name) else "")
        out.append(head)
        if isinstance(a, str):
            out.append(f"{_INDENT * 2}not answered: {a}")
            continue
        for line in a.text.splitlines():
            out.append(f"{_INDENT * 2}{line}")
        if a.tolerance is not None and not a.exact:
            out.append(f"{_INDENT * 2}(numerical, to within {a.tolerance:g})")
        if a.note:
            out.append(f"{_INDENT * 2}note: {a.note}")
    return terminal_safe("\n".join(out))


def problem_text(sol, spec=None, answers: dict | None = None, notes=()) -> str:
    """What ``rigidkin solve`` prints: the solution, the asked reactions, the answers and notes."""
    reactions = spec.reactions if spec is not None else None
    parts = [solution_text(sol, reactions, spec.eom if spec is not None else True).rstrip()]
    if answers:
        parts.append(answers_text(answers, spec.questions if spec is not None else ()))
    if notes:
        parts.append("Notes\n" + "\n".join(f"{_INDENT}{n}" for n in notes))
    if sol.warnings:
        parts.append("Warnings\n" + "\n".join(f"{_INDENT}{w}" for w in sol.warnings))
    return terminal_safe("\n\n".join(parts))
