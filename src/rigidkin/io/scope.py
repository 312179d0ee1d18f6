"""What names mean in an expression of the problem-file language (:mod:`rigidkin.io.expressions`).

A :class:`Scope` maps the names an expression may use to sympy objects: parameters, coordinates (and
which of them ``dot``/``ddot`` accept), generalised speeds, frames and their basis vectors, extra
functions, and how high a time derivative may be written where the expression is read.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

t = dynamicsymbols._t


@dataclass
class Scope:
    """What names mean in an expression.

    ``names``: scalar names (parameter symbols, coordinates q(t), reaction symbols ...);
    ``coordinates``: the names ``dot()``/``ddot()`` accept; ``frames``: frame name → {axis or basis
    name → unit vector}; ``vectors``: basis names usable alone; ``ambiguous``: basis names that several
    frames share (name → frames); ``functions``: extra functions, name → handler(arguments, node, parser).
    """

    names: dict[str, sp.Basic] = field(default_factory=dict)
    coordinates: dict[str, sp.Basic] = field(default_factory=dict)
    frames: dict[str, dict[str, Vector]] = field(default_factory=dict)
    vectors: dict[str, Vector] = field(default_factory=dict)
    ambiguous: dict[str, list[str]] = field(default_factory=dict)
    functions: dict[str, Callable] = field(default_factory=dict)
    #: generalised speeds that are no coordinate's rate (body angular speeds): ``dot(w)`` is ẇ, an acceleration
    speeds: dict[str, sp.Basic] = field(default_factory=dict)
    #: the highest time derivative ``dot``/``ddot`` may write (2: accelerations; 1: rates only, as in loads)
    max_derivative: int = 2

    def with_names(self, extra: Mapping[str, sp.Basic]) -> Scope:
        """A copy of this scope with more scalar names (e.g. reaction names, the damper speed v)."""
        return replace(self, names={**self.names, **extra})

    def with_functions(self, extra: Mapping[str, Callable]) -> Scope:
        return replace(self, functions={**self.functions, **extra})

    def with_max_derivative(self, order: int) -> Scope:
        """A copy of this scope in which ``dot``/``ddot`` may write derivatives up to ``order``."""
        return replace(self, max_derivative=order)

    def add_speeds(self, names, speeds) -> None:
        """Make the speeds known by name (w), with ``dot(w)`` their rate."""
        for n, w in zip(names, speeds):
            self.names[n] = w
            self.speeds[n] = w

    def add_frame(self, name: str, basis: tuple[str, str, str], unit_vectors: tuple[Vector, Vector, Vector]):
        """Make ``name.x/.y/.z`` and ``name.<basis>`` known, and each basis name alone when unambiguous."""
        axes = dict(zip(("x", "y", "z"), unit_vectors))
        axes.update(zip(basis, unit_vectors))
        self.frames[name] = axes
        for b, v in zip(basis, unit_vectors):
            owners = self.ambiguous.get(b) or [f for f, ax in self.frames.items() if f != name and b in ax
                                               and b in self.vectors and ax[b] is self.vectors[b]]
            if owners:
                self.ambiguous[b] = [*owners, name]
                self.vectors.pop(b, None)
            else:
                self.vectors[b] = v


def default_scope() -> Scope:
    """A scope with only ``t`` and ``pi``."""
    return Scope(names={"t": t, "pi": sp.pi})
