"""The derivation trace: the steps a law takes, recorded as it computes them.

Each ``Step`` names its section of the method (frames, kinematics, inertia, free-body diagram,
balance laws, solving), what was computed, the equations (left side, right side: sympy expressions
or vectors), and why.  Renderers (text, Markdown, LaTeX, HTML) read the trace; they never write
derivation text of their own.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

SECTIONS = (
    "Frames and coordinates",
    "Kinematics",
    "Inertia and momentum",
    "Free-body diagram",
    "Balance laws",
    "Solving",
    "Answers",
    "Checks",
)


class LazyEquations(Sequence):
    """Equations of a step computed when first read (simplifying for a reader costs time the solve
    does not need; a report reads them, a sweep never does)."""

    def __init__(self, compute):
        self._compute, self._items = compute, None

    def _get(self) -> tuple:
        if self._items is None:
            self._items = tuple(self._compute())
            self._compute = None
        return self._items

    def __getitem__(self, i):
        return self._get()[i]

    def __len__(self) -> int:
        return len(self._get())

    def __repr__(self) -> str:
        return repr(self._get())            # printed: what a reader asks for is the equations, so they are made


@dataclass(frozen=True)
class Step:
    """One step of a derivation: ``equations`` is a tuple of (lhs, rhs) pairs."""

    section: str
    title: str
    equations: tuple = ()
    why: str = ""
    law: str = ""


@dataclass
class Trace:
    """An ordered record of steps; ``add`` is called by the code that does the computing."""

    steps: list[Step] = field(default_factory=list)
    law: str = ""

    def add(self, section: str, title: str, equations=(), why: str = "") -> None:
        """Record a step; ``equations`` is a sequence of (lhs, rhs) or a LazyEquations."""
        if section not in SECTIONS:
            raise ValueError(f"unknown trace section {section!r}")
        eqs = equations if isinstance(equations, LazyEquations) else tuple(equations)
        self.steps.append(Step(section, title, eqs, why, self.law))

    def section(self, name: str) -> list[Step]:
        return [s for s in self.steps if s.section == name]

    def extend(self, other: Trace) -> None:
        self.steps.extend(other.steps)

    def __len__(self) -> int:
        return len(self.steps)
