"""The kernel: the numeric content of one regime of one mode, from which code is generated.

A :class:`Kernel` holds the equations of a regime in plain symbols of the state layout (t, q…, q̇…,
parameters…): the unknowns X (the independent accelerations q̈_i and the reactions), given either
explicitly (X = b, the Solution's solved expressions) or implicitly (A·X = b, the balance equations
before the symbolic solve, solved numerically by LU at every call); the rates dy/dt = (q̇, q̈) of every
coordinate (dependent ones through the constraints' rate and acceleration relations) and named outputs
(the reactions and any event function).  Its :meth:`Kernel.key` hashes that content: the cache key of the
code generated from it (:mod:`rigidkin.numeric.compiled.csource`, :mod:`rigidkin.numeric.compiled.codegen`).
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from dataclasses import dataclass, field

import sympy as sp

from ...base.errors import RigidkinError
from ...model.definitions import expand
from ..state import StateLayout

#: Version of the generated code: part of every cache key.
CODE_VERSION = "3"


class CodegenError(RigidkinError):
    """Code could not be generated or compiled for a model."""


@dataclass(frozen=True, eq=False)
class Kernel:
    """The numeric content of one regime of one mode (plain symbols; see the module docstring)."""

    layout: StateLayout
    unknowns: tuple[sp.Symbol, ...]        # X: q̈_i (named ddot(q)) then reactions
    unknown_names: tuple[str, ...]
    A: sp.Matrix | None                    # None: explicit (X = b)
    b: tuple[sp.Expr, ...]
    rates: tuple[sp.Expr, ...]             # dy/dt, 2n expressions of args and X
    outputs: tuple[sp.Expr, ...]           # of args and X
    output_names: tuple[str, ...]
    label: str = ""
    M: sp.Matrix | None = None             # mass-matrix form of the rates: M·q̈_i = f (reactions from A, b)
    f: tuple[sp.Expr, ...] = ()
    _cache: dict = field(default_factory=dict, repr=False)

    @property
    def args(self) -> list:
        if "args" not in self._cache:
            self._cache["args"] = self.layout.arguments()
        return self._cache["args"]

    @property
    def form(self) -> str:
        return "explicit" if self.A is None else ("mass-matrix" if self.M is not None else "implicit")

    @property
    def ny(self) -> int:
        return len(self.args) - 1 - self.np_

    @property
    def np_(self) -> int:
        return len(self.layout.parameter_symbols)

    def with_outputs(self, names: Sequence[str], exprs: Sequence[sp.Expr]) -> Kernel:
        """The same kernel with further named outputs (expressions of the state and parameters)."""
        exprs = [self.layout.to_plain(sp.sympify(e)) for e in exprs]
        check_free(self, exprs)
        return Kernel(self.layout, self.unknowns, self.unknown_names, self.A, self.b, self.rates,
                      self.outputs + tuple(exprs), self.output_names + tuple(names), self.label, self.M, self.f)

    def key(self) -> str:
        """A hash of the model's numeric content (the cache key of its generated code)."""
        if "key" not in self._cache:
            h = hashlib.sha256(CODE_VERSION.encode())
            for part in (self.args, self.unknowns, self.A, self.b, self.rates, self.outputs, self.M, self.f):
                h.update(sp.srepr(part).encode())
            self._cache["key"] = h.hexdigest()[:24]
        return self._cache["key"]

    def output_index(self, name: str) -> int:
        try:
            return self.output_names.index(name)
        except ValueError:
            raise CodegenError(f"'{name}' is not an output of this model.", where=self.label,
                               hint=f"Outputs: {', '.join(self.output_names) or 'none'}.") from None


def check_free(kernel: Kernel, exprs) -> None:
    """Refuse expressions holding a quantity that is neither a coordinate, a rate, time, a parameter nor an
    unknown of ``kernel`` (derived quantities count by their definitions)."""
    allowed = set(kernel.args) | set(kernel.unknowns)
    extra = set().union(*[expand(sp.sympify(e)).free_symbols for e in exprs]) - allowed if exprs else set()
    if extra:
        raise CodegenError(f"the expressions contain {', '.join(sorted(map(str, extra)))}, which is neither a "
                           "coordinate, a rate, time nor a parameter, so no code can be generated for them.",
                           where=kernel.label,
                           hint="Every quantity in a model must be a parameter, a coordinate or a function of time.")
