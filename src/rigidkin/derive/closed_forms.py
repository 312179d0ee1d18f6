"""Closed forms where they are cheap, structure where they are not.

The accelerations q̈ = M⁻¹ f are written in closed form (and the reactions with them) only while their
size stays readable.  The size is predicted before anything is solved, from M and f as derived: by
Cramer's rule each q̈_i is a ratio of determinants, and a determinant of an n × n matrix with a fraction
d of its entries non-zero has about n!·dⁿ products of n entries, so

    predicted operations ≈ 2 · n! · dⁿ · (n · m̄ + f̄),

m̄ and f̄ the mean operation counts (``sympy.count_ops``, found by ``base.opcount``) of the non-zero
entries of M and of f. Above ``CLOSED_FORM_OPS`` the solution is given as structure: the equations of
motion M q̈ = f (their entries as derived), and the reactions in terms of q̈, which M q̈ = f gives as
exact numbers at any state (``Solution.reactions_at``; ``accelerations_at``). The choice depends on the
expressions alone — the same on every run, on any machine, however loaded. ``regime.accelerations``
still gives the closed form when a program asks for it; only what is printed and what the reactions are
written with follow the choice.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import sympy as sp

from ..base.opcount import count_ops

#: Above this predicted operation count the accelerations are given as M q̈ = f rather than solved.
#: (Every bundled example predicts at most ~650, a chain of three rods ~1900; a four-bar linkage ~3500,
#: a cart with three links ~6900, a ball on a turntable ~21000.)
CLOSED_FORM_OPS = 2500


@dataclass(frozen=True)
class FormChoice:
    """How a regime's accelerations and reactions are given: ``closed`` or as structure, and why."""

    closed: bool
    predicted: int
    dof: int

    @property
    def reason(self) -> str:
        if self.closed:
            return f"closed form (predicted size {self.predicted} operations, at most {CLOSED_FORM_OPS})"
        return (f"from M q̈ = f: the closed-form accelerations would have about {self.predicted} operations "
                f"(more than {CLOSED_FORM_OPS}), too large to read; exact numbers at any state from M and f")


def predicted_ops(M: sp.Matrix, f: sp.Matrix) -> int:
    """The predicted operation count of the closed-form solution of M x = f (see the module docstring)."""
    n = M.rows
    if n == 0:
        return 0
    if 2 * math.factorial(n) * (n + 1) > 100 * CLOSED_FORM_OPS:      # large whatever the entries
        return 2 * math.factorial(n) * (n + 1)
    entries = [e for e in M if e != 0]
    density = len(entries) / (n * n)
    memo: dict = {}             # the entries share subexpressions: each counted once (the counts are sympy's)
    m = sum(count_ops(e, memo) for e in entries) / max(1, len(entries)) + 1
    fm = sum(count_ops(e, memo) for e in f) / max(1, f.rows) + 1
    return int(round(2 * math.factorial(n) * density ** n * (n * m + fm)))


#: M and f are simplified for reading while their entries as derived have at most this many operations
#: in all (every bundled example has under 820; a four-bar linkage's 1800 take seconds to simplify and
#: stay unreadable).
READABLE_MF_OPS = 1000


def readable_size(M: sp.Matrix, f: sp.Matrix) -> bool:
    """Whether M and f as derived are small enough to be simplified for reading."""
    memo: dict = {}
    return sum(count_ops(e, memo) for e in (*M, *f) if e != 0) <= READABLE_MF_OPS


def choose(M_raw: sp.Matrix, f_raw: sp.Matrix) -> FormChoice:
    """Closed form or structure for M q̈ = f as derived: the same choice for the same expressions."""
    p = predicted_ops(M_raw, f_raw)
    return FormChoice(p <= CLOSED_FORM_OPS, p, M_raw.rows)


def mark(regime, choice: FormChoice) -> None:
    """Record the choice on the regime (read by the solution's printers through :func:`structured`)."""
    regime.__dict__["form"] = choice


def structured(regime) -> bool:
    """Whether the regime's accelerations are given as M q̈ = f (not in closed form), unless a program
    already asked for the closed form."""
    choice = regime.__dict__.get("form")
    acc = regime.accelerations
    computed = getattr(acc, "computed", True)
    return choice is not None and not choice.closed and not computed
