"""Newton's coefficient of restitution e in a problem file (a part of the file reader's builder): of a
contact's impacts (``contact``, ``disk_contact``), or of the jerk with which a slack rope or cable
re-tightens (``rope``, ``cable``): the speed apart after is −e times the speed before.

e is a ratio of speeds: a pure number, constant (numbers and parameters), 0 ≤ e ≤ 1.
"""

from __future__ import annotations

import sympy as sp
from sympy.core.function import AppliedUndef

from ..base.dimensions import symbol_dimensions
from ..base.errors import InputError
from ..base.units import ONE
from ..model.dimension_checks import field_error

#: what e is of, by constraint type; and the two ends of its range in those words
_OF = {"contact": ("its impacts", "the contact closes on impact", "it bounces back at the speed it came"),
       "rope": ("its jerk as it re-tightens after going slack", "it jerks taut and stays taut",
                "it rebounds slack at the speed it came")}
_HINT = ("e is the ratio of the speed apart after to the speed before: a number in [0, 1] (0.3) or an expression of "
         "parameters with unit = \"1\".")


def restitution_value(builder, name: str, c, path: tuple):
    """The coefficient of restitution of constraint ``name`` (table ``c`` at ``path``), checked: a pure number,
    free of the coordinates and time, with every parameter in it given a value, in [0, 1]."""
    path = path + ("restitution",)
    where = builder.where(*path)
    kind = c.type.replace("_", " ")
    of, plastic, elastic = _OF["contact" if "contact" in c.type else "rope"]
    label = f"the coefficient of restitution of {kind} {name}"
    e = builder.scalar(c.restitution, path)
    dims = symbol_dimensions(builder.s)
    for n in getattr(builder, "unknown_dimensions", ()):
        dims.pop(builder.s.parameters[n], None)
    why = field_error(e, ONE, "a coefficient of restitution (a number)", label, dims)
    if why:
        raise InputError(why, where=where, hint=_HINT)
    value = sp.sympify(e.xreplace(builder.s.parameter_values()))
    coordinates = {str(f.func) for f in value.atoms(AppliedUndef)}        # q(t): its t is not a name of its own
    moving = sorted(coordinates | {str(s) for s in value.free_symbols if not (coordinates and str(s) == "t")})
    if moving:
        unset = [m for m in moving if m in builder.s.parameters]
        if unset:
            raise InputError(f"{label} needs the value of the parameter{'s' if len(unset) > 1 else ''} "
                             f"{', '.join(unset)}, which {'have' if len(unset) > 1 else 'has'} none.", where=where,
                             hint="Give the parameter a value (value = 0.5) or write e as a number.")
        raise InputError(f"{label} must be a constant, but '{c.restitution}' depends on {', '.join(moving)} (e of "
                         f"{of} is one number for the whole motion).", where=where, hint=_HINT)
    number = float(value)
    if not 0.0 <= number <= 1.0:
        raise InputError(f"{label} is {number:g}; it must lie in [0, 1] (e of {of}: 0, {plastic}; 1, {elastic}).",
                         where=where, hint=_HINT)
    return e


__all__ = ["restitution_value"]
