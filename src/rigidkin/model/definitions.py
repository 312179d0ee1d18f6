"""Derived quantities: a name for an expression of the parameters (a = √(R² − l²)).

``System.define("a", sp.sqrt(R**2 - l**2), unit="m")`` returns a :class:`Defined` quantity that takes
part in every expression like a parameter and prints as its name (``a``), so the equations of motion
read as the user wrote them; the definition is listed with the results.  It *means* its definition:

* for the algebra it is a quantity of its own (its free symbol is itself: random states give it a
  value of its own, as to a parameter), so identities are checked without its definition;
* numbers put in for the parameters (``xreplace({R: 1.0, l: 0.6})``) turn it into the number of its
  definition; ``evalf`` and the code printers (``lambdify``, C) print the definition when it is not
  an argument, and :func:`expand` replaces every defined quantity by its definition (generated code
  holds only sympy's own classes, so the generated-code checks expand first);
* its dimension is that of its definition (checked against ``unit`` when one is given);
* it is real, and positive when its value with the parameters' values is (checked when defined).

A definition is a constant of the problem: it may use parameters and earlier definitions, not the
coordinates or time.
"""

from __future__ import annotations

import cmath
from dataclasses import dataclass

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.core.symbol import Str
from sympy.physics.vector import dynamicsymbols

from ..base.dimensions import DimensionMismatch, dimension_of, symbol_dimensions
from ..base.errors import ModelError
from ..base.units import Dimension, unit_dimension
from .checks import numeric_value

t = dynamicsymbols._t


class Defined(sp.Function):
    """A derived quantity: prints as its name, means its definition (args: name, definition, sign).

    A Function application (not a Symbol) so that ``lambdify`` puts a variable in its place when it is
    one of the arguments, and prints its definition when it is not.
    """

    is_commutative = True
    is_Defined = True

    @classmethod
    def eval(cls, name, definition, sign):
        if isinstance(definition, sp.Expr) and not definition.free_symbols and definition.has(sp.Float):
            return definition            # numbers were put in for the parameters: it is that number
        return None

    def __new__(cls, name, definition, sign="real"):
        name = name if isinstance(name, Str) else Str(str(name))
        sign = sign if isinstance(sign, Str) else Str(str(sign))
        return super().__new__(cls, name, sp.sympify(definition), sign)

    @property
    def name(self) -> str:
        return self.args[0].name

    @property
    def definition(self) -> sp.Expr:
        return self.args[1]

    @property
    def symbol(self) -> sp.Symbol:
        """A plain symbol of the same name (for printing)."""
        return sp.Symbol(self.name, positive=True) if self.args[2].name == "positive" else sp.Symbol(self.name,
                                                                                                    real=True)

    @property
    def free_symbols(self) -> set:
        return {self}            # for the algebra (random states) it is a quantity of its own

    @property
    def is_number(self) -> bool:
        return self.definition.is_number

    # assumptions ---------------------------------------------------------------------------------------
    def _eval_is_extended_real(self):
        return True

    def _eval_is_finite(self):
        return True

    def _eval_is_extended_positive(self):
        return True if self.args[2].name == "positive" else self.definition.is_extended_positive

    def _eval_is_zero(self):
        return False if self.args[2].name == "positive" else self.definition.is_zero

    # calculus and numbers -----------------------------------------------------------------------------
    def _eval_derivative(self, s):
        return self.definition.diff(s)

    def _eval_evalf(self, prec):
        return expand(self.definition)._eval_evalf(prec)

    def _eval_nseries(self, x, n, logx, cdir=0):
        return expand(self.definition)._eval_nseries(x, n, logx, cdir)

    # printing: the name for people, the definition for code --------------------------------------------
    def _sympystr(self, printer, **kwargs):
        return printer._print(self.symbol, **kwargs)

    def _latex(self, printer, exp=None, **kwargs):
        out = printer._print(self.symbol)
        return out if exp is None else f"{out}^{{{exp}}}"

    def _pretty(self, printer, **kwargs):
        return printer._print(self.symbol, **kwargs)

    def _mathml_presentation(self, printer, **kwargs):
        return printer._print(self.symbol, **kwargs)

    def _mathml_content(self, printer, **kwargs):
        return printer._print(self.symbol, **kwargs)

    def _code(self, printer, **kwargs):
        return printer._print(expand(self.definition), **kwargs)

    _pythoncode = _mpmathcode = _lambdacode = _numpycode = _ccode = _code


def expand(expr):
    """``expr`` with every defined quantity replaced by its definition (nested ones too); also vectors."""
    from sympy.physics.vector import Vector

    if isinstance(expr, Vector):
        return Vector([(sp.Matrix([expand(c) for c in m]), f) for m, f in expr.args]) if expr.args else expr
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(expand)
    if not isinstance(expr, sp.Basic):
        return expr
    for _ in range(50):
        found = expr.atoms(Defined)
        if not found:
            return expr
        expr = expr.xreplace({d: d.definition for d in found})
    raise ModelError("the definitions refer to each other without end.", where="definitions")


@dataclass(frozen=True, eq=False)
class Definition:
    """A derived quantity as declared: ``quantity`` (what expressions hold), its expression and meaning."""

    name: str
    quantity: Defined
    expression: sp.Expr
    unit: str
    dimension: Dimension
    description: str = ""
    value: float | None = None


def define(system, name: str, expression, unit: str | None = None, description: str = "",
           where: str | None = None) -> Definition:
    """Check ``expression`` (constant, dimensionally consistent, real at the parameters' values) and
    return the Definition of ``name``; its ``quantity`` is positive when its value is."""
    where = where or f"definition {name}"
    expr = sp.sympify(expression)
    moving = expr.atoms(AppliedUndef) | ({t} & expr.free_symbols)
    if moving:
        raise ModelError(f"the definition of {name} depends on the motion ({', '.join(map(str, moving)) or 't'}); "
                         "a definition is a constant of the problem.", where=where,
                         hint="Use parameters and earlier definitions only; write expressions of the coordinates "
                              "where they are used.")
    params = set(system.parameters.values())
    unknown = [s for s in expand(expr).free_symbols if s not in params]
    if unknown:
        raise ModelError(f"the definition of {name} uses {', '.join(sorted(map(str, unknown)))}, which "
                         f"{'is' if len(unknown) == 1 else 'are'} not a parameter or an earlier definition.",
                         where=where, hint="Declare the parameters first (and definitions in the order they use "
                                           "each other).")
    try:
        dim = dimension_of(expr, symbol_dimensions(system))
    except DimensionMismatch as exc:
        raise ModelError(f"the definition of {name} is not dimensionally consistent: {exc.message}",
                         where=where) from None
    if unit not in (None, ""):
        want = unit_dimension(unit, where)
        if want != dim:
            raise ModelError(f"the definition of {name} has dimension {dim}, but its unit {unit!r} is {want}.",
                             where=where, hint="Check the expression or the unit.")
    value, sign = _value(system, expr, name, where), "real"
    if value is not None and value > 0 or value is None and expand(expr).is_positive:
        sign = "positive"
    return Definition(name, Defined(name, expr, sign), expr, unit or "", dim, description, value)


def _value(system, expr, name: str, where: str) -> float | None:
    """The value with the parameters' values, checked real and finite (None when some have none)."""

    vals = system.parameter_values()
    full = expand(expr)
    if not full.free_symbols <= set(vals):
        return None
    v = numeric_value(full.xreplace({k: sp.Float(x) for k, x in vals.items()}))
    if v is None:
        v = complex(full.xreplace(vals).evalf())
    if not (cmath.isfinite(v)) or abs(v.imag) > 1e-12 * max(1.0, abs(v.real)):
        shown = ", ".join(f"{s} = {vals[s]:g}" for s in sorted(full.free_symbols, key=str))
        raise ModelError(f"{name} = {expr} is not a real, finite number with the parameters' values ({shown}).",
                         where=where, hint="Check the parameters' values (a square root of a negative number, "
                                           "acos beyond ±1) or the definition.")
    return v.real
