"""Units and dimensions of a problem file, checked while it is read (a part of the file reader's builder).

Every command that derives (``solve``, ``check``, ``simulate``, ``report``, ``sweep``, ...) reads its file
through the builder, so each gets these checks before anything is derived:

* a parameter declared with neither ``unit`` nor ``dimension`` is a warning (its dimension is not known,
  so the expressions it enters cannot be checked); ``unit = "1"`` (or ``""``, or ``dimension =
  "dimensionless"``) declares a pure number;
* every equation and condition of a question (``when = "N_A = 0"``) must have terms of one dimension;
* every field of a load, point, body, constraint and frame must have its dimension (a force's vector is
  a force, a spring's stiffness a force per length, an offset a length ...): a force written in N/m is an
  error naming the load, the field and the term (:mod:`rigidkin.model.dimension_checks`);
* a quantity with a unit in an expression field (``radius = "10 cm"``, ``offset = "(l/2 + 5 cm)*ey"``,
  :mod:`rigidkin.io.quantity_literals`) is checked as it is read, with its unit, against the field's
  dimension (``field_dimension``), and then put in SI units.
"""

from __future__ import annotations

import warnings

import sympy as sp

from ..base.dimensions import FORCE, TORQUE, DimensionMismatch, UnknownDimension, dimension_of, symbol_dimensions
from ..base.errors import InputError
from ..base.printing import text
from ..base.units import LENGTH, MASS, ONE, TIME, Dimension, unit_dimension
from ..model.dimension_checks import field_error, input_dimension_errors
from . import quantity_literals

_LENGTH, _ANGLE, _NUMBER, _DIRECTION = ("a length", LENGTH), ("an angle", ONE), ("a number", ONE), ("a direction", ONE)
#: The dimension of each expression field of a file's loads, by type (quantities with units are checked
#: against it while the file is read).
LOAD_FILE_FIELDS: dict[str, dict[str, tuple[str, Dimension]]] = {
    "gravity": {"g": ("an acceleration", LENGTH / TIME**2), "direction": _DIRECTION},
    "force": {"vector": ("a force", FORCE)},
    "torque": {"vector": ("a torque", TORQUE)},
    "impulse": {"vector": ("an impulse (force × time)", FORCE * TIME)},
    "spring": {"stiffness": ("a stiffness (force per length)", FORCE / LENGTH), "natural_length": _LENGTH},
    "torsional_spring": {"stiffness": ("a torsional stiffness (torque per radian)", TORQUE), "angle": _ANGLE,
                         "natural_angle": _ANGLE, "axis": _DIRECTION},
    "rotational_spring": {"stiffness": ("a torsional stiffness (torque per radian)", TORQUE), "angle": _ANGLE,
                          "natural_angle": _ANGLE, "axis": _DIRECTION},
    "rotational_damper": {"coefficient": ("a rotational damping (torque × time)", TORQUE * TIME),
                          "axis": _DIRECTION},
    "damper": {"law": ("a force (a law in the speed v)", FORCE), "along": _DIRECTION},
    "friction": {"mu": ("a friction coefficient (a number)", ONE), "normal_force": ("a force", FORCE),
                 "radius": _LENGTH, "normal": _DIRECTION},
}
_BODY_FIELDS = {"mass": ("a mass", MASS), "centre": _LENGTH,
                **{k: ("a moment of inertia", MASS * LENGTH**2) for k in ("Ixx", "Iyy", "Izz", "Ixy", "Iyz", "Izx")}}
_CONSTRAINT_FILE_FIELDS = {"radius": _LENGTH, "length": _LENGTH, "restitution": ("a coefficient of restitution "
                           "(a number)", ONE), "friction": ("a friction coefficient (a number)", ONE), "mu":
                           ("a friction coefficient (a number)", ONE), "half_angle": _ANGLE, "toward": _DIRECTION,
                           "axis": _DIRECTION, "along": _DIRECTION, "direction": _DIRECTION, "normal": _DIRECTION}


class UnitsAndDimensions:
    """Builder steps for units (mixed into the file reader's builder)."""

    def field_dimension(self, path) -> tuple[str, Dimension] | None:
        """What the expression field at ``path`` is and its dimension (None where it has none of its own)."""
        table, name = path[0], path[1] if len(path) > 1 else None
        field = path[2] if len(path) > 2 else None
        if table == "bodies":
            return _BODY_FIELDS.get(field) or (_LENGTH if field in ("length", "radius", "inner_radius", "a", "b",
                                                                   "c") else None)
        if table == "points":
            return _LENGTH if field == "offset" else None
        if table == "frames":
            return _ANGLE if field in ("angle", "angles") else _DIRECTION if field == "axis" else None
        if table == "constraints":
            leaf = next((p for p in reversed(path[2:]) if isinstance(p, str) and p not in ("static", "kinetic")), None)
            return _CONSTRAINT_FILE_FIELDS.get(leaf)
        if table == "loads":
            kind = getattr(self.spec.loads.get(name), "type", None)
            return LOAD_FILE_FIELDS.get(kind, {}).get(field)
        if table == "inputs" and field == "history":
            unit = self.spec.inputs[name].unit
            return ("the input's unit", unit_dimension(unit)) if unit else None
        return None

    def parsed(self, value, path, scope, parse, dimension=None):
        """``value`` parsed, its quantities with units (``"l/2 + 5 cm"``) checked against the field's dimension
        (or ``dimension``) and put in SI units."""
        expr, literals = quantity_literals.read(value, scope or self.scope, self.where(*path), parse)
        if literals:
            self.check_quantities(expr, literals, path, dimension)
        return quantity_literals.to_si(expr, literals)

    def no_quantities(self, value, path) -> None:
        """Refuse a quantity with a unit in a definition (it would lose its unit: a definition's dimension
        follows from its parameters)."""
        if quantity_literals.split(value, self.scope, self.where(*path))[1]:
            raise InputError("a definition is an expression of the parameters; a quantity with a unit in it would "
                             "lose its dimension (the definition's dimension follows from its parameters).",
                             where=self.where(*path), hint="Declare the quantity as a parameter (d = { unit = "
                             "\"cm\", value = 5 }) and use its name in the definition.")

    def check_quantities(self, value, literals, path, dimension=None) -> None:
        """Refuse an expression with quantities (``"l/2 + 5 kg"``) whose terms cannot be added, or whose
        dimension is not the field's (a mass given for a radius), naming the field."""
        dims = symbol_dimensions(self.s)
        for n in getattr(self, "unknown_dimensions", ()):
            dims.pop(self.s.parameters[n], None)
        dims.update({lit.symbol: lit.dimension for lit in literals})
        if isinstance(value, sp.core.relational.Relational):       # an equation or condition: its sides agree
            value, dimension, path_dim = value.lhs - value.rhs, None, None
        else:
            path_dim = self.field_dimension(path)
        expected = ("a quantity", dimension) if dimension is not None else path_dim
        label = f"the field '{'.'.join(str(p) for p in path)}'"
        if expected is None:
            why = field_error(value, ONE, "", label, dims, consistent_only=True)
        else:
            why = field_error(value, expected[1], expected[0], label, dims)
        self.quantity_fields = getattr(self, "quantity_fields", set()) | {tuple(path[:3])}
        if why:
            for lit in literals:
                why = why.replace(text(lit.symbol), lit.text)
            shown = ", ".join(lit.text for lit in literals)
            raise InputError(f"{why} (quantities given: {shown})", where=self.where(*path),
                             hint="Give the quantity in a unit of the field's dimension (a length in m, cm, ft; "
                                  "an angle in deg or rad; a mass in kg, g, lb), or check the expression.")

    def unit_warning(self, name, p, path) -> None:
        """Warn about a parameter with no unit and no dimension; remember it as of unknown dimension."""
        if p.unit is not None or p.dimension is not None:
            return
        self.unknown_dimensions = getattr(self, "unknown_dimensions", set()) | {name}
        message = (f"{self.where(*path)}: the parameter '{name}' has no unit, so its dimension is not known and the "
                   "dimensions of the expressions it enters are not checked. Give it a unit (unit = \"N/m\"), or "
                   "unit = \"1\" for a pure number.")
        self.reading_warnings = (*getattr(self, "reading_warnings", ()), message)
        warnings.warn(message, UserWarning, stacklevel=2)

    def check_dimensions(self) -> None:
        """Refuse the first field of the model whose quantity has the wrong dimension, at its place in the file."""
        unknown = [self.s.parameters[n] for n in getattr(self, "unknown_dimensions", ())]
        checked = getattr(self, "quantity_fields", set())     # checked as read, with their quantities' units
        for err in input_dimension_errors(self.s, unknown):
            if (err.table, err.name, err.field) in checked:
                continue
            table = getattr(self.spec, err.table, {}) or {}
            where = self.where(err.table, err.name, err.field) if err.name in table else None
            raise err.error(where, InputError)

    def check_question_dimensions(self, questions) -> None:
        """Refuse an equation or condition of a question whose terms cannot be added (``"theta = l"``)."""
        dims = symbol_dimensions(self.s)
        for name in getattr(self, "unknown_dimensions", ()):
            dims.pop(self.s.parameters[name], None)
        for q in questions:
            for key, value in q.fields.items():
                for rel in value if isinstance(value, list | tuple) else (value,):
                    if not isinstance(rel, sp.core.relational.Relational):
                        continue
                    terms = [a for a in sp.Add.make_args(rel.lhs - rel.rhs) if a.free_symbols]  # numbers: SI
                    try:
                        dimension_of(sp.Add(*terms, evaluate=False) if len(terms) > 1 else sp.Add(*terms), dims)
                    except UnknownDimension:
                        continue
                    except DimensionMismatch as exc:
                        raise InputError(f"'{key}' of question {q.name} is not dimensionally consistent: "
                                         f"{exc.message}", where=q.where or None,
                                         hint="Check the units of the parameters in these terms, or the "
                                              "expression.") from None
