"""The dimensions of a model's inputs, checked before anything is derived.

Every load, point, body, constraint and frame has a quantity of a known dimension in each of its
fields: a force's vector is a force, a spring's stiffness a force per length, a point's offset a
length, a body's mass a mass, a frame's angle a number.  ``input_dimension_errors`` checks each field
with the dimensional analysis of :mod:`rigidkin.base.dimensions` (every term of every sum) and says,
for a field that disagrees, which term has which dimension where which one is expected: a force
written in N/m is refused before a derivation carries it into every equation of motion.

A parameter whose dimension is not known (declared with no unit in a problem file) is left out: the
fields it enters are not checked (the file reader warns about it).  A bare number (``radius = 0.05``, the
``0.1`` of ``"l/2 + 0.1"``) stands for a quantity in SI units of the field's dimension.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector

from ..base.dimensions import FORCE, TORQUE, DimensionMismatch, UnknownDimension, dimension_of, symbol_dimensions
from ..base.errors import ModelError
from ..base.printing import text
from ..base.units import LENGTH, MASS, ONE, TIME, Dimension, si_unit
from .loads import V as damper_speed

#: The dimension of each field of each kind of load (the field names of the model and of the file).
LOAD_FIELDS: dict[str, dict[str, tuple[str, Dimension]]] = {
    "Gravity": {"g": ("an acceleration", LENGTH / TIME**2)},
    "Force": {"vector": ("a force", FORCE)},
    "Torque": {"vector": ("a torque", TORQUE)},
    "Spring": {"stiffness": ("a stiffness (force per length)", FORCE / LENGTH),
               "natural_length": ("a length", LENGTH)},
    "TorsionalSpring": {"stiffness": ("a torsional stiffness (torque per radian)", TORQUE),
                        "angle": ("an angle (a number)", ONE), "natural_angle": ("an angle (a number)", ONE)},
    "RotationalDamper": {"coefficient": ("a rotational damping coefficient (torque per rad/s)", TORQUE * TIME)},
    "Damper": {"law": ("a force (a law in the speed v)", FORCE)},
    "SlidingFriction": {"mu": ("a friction coefficient (a number)", ONE), "normal_force": ("a force", FORCE),
                        "radius": ("a length", LENGTH)},
    "Impulse": {"vector": ("an impulse (force × time)", FORCE * TIME)},
}
_SHAPE_FIELDS = {"mass": ("a mass", MASS), "length": ("a length", LENGTH), "radius": ("a length", LENGTH),
                 "inner_radius": ("a length", LENGTH), "a": ("a length", LENGTH), "b": ("a length", LENGTH),
                 "c": ("a length", LENGTH)}
_CONSTRAINT_FIELDS = {"radius": ("a length", LENGTH), "length": ("a length", LENGTH)}


@dataclass(frozen=True)
class DimensionError:
    """A field whose quantity has the wrong dimension: ``table`` (loads, points, bodies, constraints, frames),
    ``name`` of the object, ``field``, and the message naming the term."""

    table: str
    name: str
    field: str
    message: str

    def error(self, where: str | None = None, kind=ModelError):
        return kind(self.message, where=where or f"{self.table}.{self.name}.{self.field}",
                    hint="Check the units of the parameters in this term (a parameter's unit is in "
                         "[parameters]), or the expression.")


def _components(value) -> list:
    if isinstance(value, Vector):
        return [c for measure, _frame in value.args for c in measure]
    return [value]


def _shown(d: Dimension) -> str:
    unit = si_unit(d)
    return f"{d} ({unit})" if unit else "1 (a number)"


def _without_bare_numbers(expr):
    """``expr`` with the bare numbers of its sums left out: a number added to a quantity is in SI units of the
    quantity's dimension (``(l + 0.1)*sin(theta)``: 0.1 m)."""
    expr = sp.sympify(expr)
    if not expr.args or not expr.free_symbols:
        return expr
    if expr.is_Add:
        kept = [_without_bare_numbers(a) for a in expr.args if a.free_symbols]
        return sp.Add(*kept) if kept else expr
    return expr.func(*[_without_bare_numbers(a) for a in expr.args])


def field_error(value, want: Dimension, what: str, label: str, dims: dict, consistent_only: bool = False) -> str | None:
    """Why ``value`` (a scalar or a vector) is not of dimension ``want``, naming the term; None when it is
    (or when a quantity of unknown dimension enters it).  ``consistent_only``: only whether its terms can be
    added (a field with no dimension of its own)."""
    if value is None or callable(value) and not isinstance(value, sp.Basic | Vector):
        return None
    for comp in _components(value):
        comp = _without_bare_numbers(comp)
        comp = sp.Add(*[a for a in sp.Add.make_args(comp) if a.free_symbols])   # a bare number: in SI
        if comp == 0:
            continue
        try:
            got = dimension_of(comp, dims)
        except UnknownDimension:
            continue
        except DimensionMismatch as exc:
            return f"{label} is not dimensionally consistent: {exc.message}"
        if consistent_only:
            continue
        if got != want and not (got.is_dimensionless and want.is_dimensionless):
            term = sp.Add.make_args(comp)[0] if comp.is_Add else comp
            return (f"{label} has dimension {_shown(got)}, where {what} {_shown(want)} is expected: the term "
                    f"{text(term)}.")
    return None


def input_dimension_errors(system, unknown=()) -> list[DimensionError]:
    """The fields of ``system``'s loads, points, bodies, constraints and frames whose dimensions are wrong.

    ``unknown``: the parameters (symbols) whose dimension is not known; fields they enter are not checked."""
    dims = symbol_dimensions(system)
    for s in unknown:
        dims.pop(s, None)
    dims[damper_speed] = LENGTH / TIME
    out = []

    def check(table, name, field, value, what, want, label):
        why = field_error(value, want, what, label, dims)
        if why:
            out.append(DimensionError(table, name, field, why))

    for name, ld in system.loads.items():
        kind = "TorsionalSpring" if type(ld).__name__ == "RotationalSpring" else type(ld).__name__
        for field, (what, want) in LOAD_FIELDS.get(kind, {}).items():
            check("loads", name, field, getattr(ld, field, None), what, want, f"the {field} of load {name}")
    for name, p in system.points.items():
        check("points", name, "offset", p.offset, "a length", LENGTH, f"the offset of point {name}")
    for name, b in system.bodies.items():
        for field, (what, want) in _SHAPE_FIELDS.items():
            value = getattr(b.shape, field, None)
            if isinstance(value, sp.Basic | int | float):
                check("bodies", name, field, value, what, want, f"the {field} of body {name}")
    for name, c in system.constraints.items():
        for field, (what, want) in _CONSTRAINT_FIELDS.items():
            value = getattr(c, field, None)
            if isinstance(value, sp.Basic):
                check("constraints", name, field, value, what, want, f"the {field} of constraint {name}")
        surface_radius = getattr(getattr(c, "surface", None), "radius", None)
        if isinstance(surface_radius, sp.Basic):
            check("constraints", name, "surface", surface_radius, "a length", LENGTH,
                  f"the radius of the surface of constraint {name}")
        for station in getattr(c, "stations", ()) or ():
            value = getattr(station, "signed_radius", None)
            if isinstance(value, sp.Basic):
                check("constraints", name, "path", value, "a length", LENGTH, f"a pulley radius of rope {name}")
            if isinstance(getattr(station, "mu", None), sp.Basic):
                check("constraints", name, "path", station.mu, "a friction coefficient (a number)", ONE,
                      f"a friction coefficient of rope {name}")
        friction = getattr(c, "friction", None)
        for field in ("mu", "mu_s"):
            value = getattr(friction, field, None)
            if isinstance(value, sp.Basic):
                check("constraints", name, "friction", value, "a friction coefficient (a number)", ONE,
                      f"the friction coefficient of constraint {name}")
    for name, f in system.frames.items():
        value = getattr(f, "angle", None)
        if isinstance(value, sp.Basic):
            check("frames", name, "angle", value, "an angle (a number)", ONE, f"the angle of frame {name}")
    return out


def check_input_dimensions(system, unknown=()) -> None:
    """Raise a :class:`~rigidkin.base.errors.ModelError` for the first field of ``system`` of the wrong dimension."""
    errors = input_dimension_errors(system, unknown)
    if errors:
        raise errors[0].error()
