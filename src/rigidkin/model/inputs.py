"""Inputs: named forces, torques or other quantities that are given functions of time, u(t).

An input (a motor torque, a control force; sympy's "specified") is declared with its unit and sense
and used in loads like a parameter: ``F = s.input("F", "N", "force on the cart, positive along Ex")``,
then ``s.force("push", C, F*s.inertial.x)``.  In the equations it prints as F(t).  It has no value
of its own: a simulation is given each input as an expression of t, a table of samples or a
function of (t, state) (``simulate(..., inputs={"F": ...})``), and the state-space form
(``rigidkin.analysis.state_space``) gives B = ∂ẋ/∂u and D = ∂y/∂u.

Symbolically an input is a real Symbol (a subclass that prints as ``F(t)``): loads are never
differentiated in time by the balance laws, so the equations of motion hold for any history u(t).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.core.function import AppliedUndef

from ..base.errors import ModelError
from ..base.units import ONE, Dimension
from .quantities import Parameter, declared_dimension
from .values import _expr


class InputSymbol(sp.Symbol):
    """The symbol of an input: a real Symbol that prints as ``name(t)``."""

    def _sympystr(self, printer):
        return f"{printer._print_Symbol(self)}(t)"

    def _latex(self, printer):
        return rf"{printer._print_Symbol(self)}{{\left(t \right)}}"

    def _pretty(self, printer):
        from sympy.printing.pretty.stringpict import prettyForm

        return prettyForm(f"{printer._print_Symbol(self)}(t)")


@dataclass(frozen=True, eq=False)
class Input:
    """A named input u(t): ``symbol``, ``unit``, its physical ``dimension`` and ``description`` (with the sense)."""

    name: str
    symbol: InputSymbol
    unit: str = ""
    dimension: Dimension = ONE
    description: str = ""
    history: sp.Expr | None = None        # u(t) a simulation uses when it is given none (an expression of t)

    def __repr__(self) -> str:
        return f"Input({self.name}(t) [{self.unit or self.dimension}]: {self.description})"


def inputs_of(system) -> dict[str, Input]:
    """Input name → :class:`Input` of ``system`` (in declaration order; empty when it has none)."""
    return dict(getattr(system, "_inputs", None) or {})


def input_symbols(system) -> set:
    return {i.symbol for i in inputs_of(system).values()}


class InputMethods:
    """``System.input`` (mixed into System)."""

    def input(self, name: str, unit: str | None = None, description: str = "", dimension: str | None = None,
              history=None):
        """Declare an input u(t) (a given function of time: a motor torque, a control force); returns its symbol.

        ``description`` says what it is and its positive sense ("force on the cart, positive along Ex").
        Use it in loads like a parameter; give its history to ``simulate(..., inputs=...)``, or here as
        ``history`` (an expression of t and the parameters: the default of every simulation).
        """
        where = f"input {name}"
        dim = declared_dimension(unit, dimension, where, "N, N*m ...")
        hist = None if history is None else _expr(history, where)
        if hist is not None and hist.atoms(AppliedUndef):
            raise ModelError(f"the history {hist} of an input is an expression of t and the parameters only.",
                             where=where, hint="Give feedback laws to simulate(..., inputs={name: function}).")
        self._claim(name, "input")
        sym = InputSymbol(name, real=True)
        desc = description or "input"
        # the numeric layer binds it like a parameter: a slot in the parameter vector, set at each time
        self._parameters[name] = Parameter(name, sym, f"input: {desc}", unit or "", dim, None)
        if getattr(self, "_inputs", None) is None:
            self._inputs = {}
        self._inputs[name] = Input(name, sym, unit or "", dim, desc, hist)
        return sym

    @property
    def inputs(self) -> dict[str, Input]:
        """Input name → :class:`rigidkin.model.inputs.Input`."""
        return inputs_of(self)
