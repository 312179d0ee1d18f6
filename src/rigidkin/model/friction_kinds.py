"""The kinds of friction at a contact: smooth, rolling (no slip) or Coulomb friction with its coefficients.

A contact or a collar names its friction with one of these: ``"smooth"`` (no tangential force),
``"rolling"`` (no slip: the tangential reaction is whatever keeps the contact point at rest relative to the
surface) or :class:`Coulomb` (sticking while |F| ≤ µs N, sliding with µk N against the slip).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..base.errors import ModelError

SMOOTH = "smooth"
ROLLING = "rolling"


@dataclass(frozen=True)
class Coulomb:
    """Coulomb friction: kinetic coefficient ``mu`` (µk) and static coefficient ``mu_s`` (µs).

    A contact sticks while the friction it needs satisfies |F| ≤ µs N; while it slides the friction
    is µk N against the slip.  A single coefficient (``mu_s`` None) means both: ``Coulomb(0.3)``.
    """

    mu: sp.Expr
    mu_s: sp.Expr | None = None

    def __post_init__(self):
        if self.mu_s is not None and sp.sympify(self.mu_s) == sp.sympify(self.mu):
            object.__setattr__(self, "mu_s", None)
        a, b = sp.sympify(self.static), sp.sympify(self.mu)
        if a.is_number and b.is_number and bool(a < b):
            raise ModelError(f"the static coefficient of friction µs = {a} is smaller than the kinetic one "
                             f"µk = {b}; a contact that starts to slip would need less friction than it had.",
                             where="friction", hint="Give µs ≥ µk (a single µ means both).")

    @property
    def static(self) -> sp.Expr:
        """µs: sticking holds while |F| ≤ µs N."""
        return self.mu if self.mu_s is None else self.mu_s

    @property
    def kinetic(self) -> sp.Expr:
        """µk: the sliding friction is µk N against the slip."""
        return self.mu

    @property
    def two(self) -> bool:
        """Whether static and kinetic coefficients differ (µs given apart from µk)."""
        return self.mu_s is not None
