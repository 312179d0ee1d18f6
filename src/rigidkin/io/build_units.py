"""Units and dimensions of a problem file, checked while it is read (a part of the file reader's builder).

Every command that derives (``solve``, ``check``, ``simulate``, ``report``, ``sweep``, ...) reads its file
through the builder, so each gets these checks before anything is derived:

* a parameter declared with neither ``unit`` nor ``dimension`` is a warning (its dimension is not known,
  so the expressions it enters cannot be checked); ``unit = "1"`` (or ``""``, or ``dimension =
  "dimensionless"``) declares a pure number;
* every equation and condition of a question (``when = "N_A = 0"``) must have terms of one dimension;
* every field of a load, point, body, constraint and frame must have its dimension (a force's vector is
  a force, a spring's stiffness a force per length, an offset a length ...): a force written in N/m is an
  error naming the load, the field and the term (:mod:`rigidkin.model.dimension_checks`).
"""

from __future__ import annotations

import warnings

import sympy as sp

from ..base.dimensions import DimensionMismatch, UnknownDimension, dimension_of, symbol_dimensions
from ..base.errors import InputError
from ..model.dimension_checks import input_dimension_errors


class UnitsAndDimensions:
    """Builder steps for units (mixed into the file reader's builder)."""

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
        for err in input_dimension_errors(self.s, unknown):
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
