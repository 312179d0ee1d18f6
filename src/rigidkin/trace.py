"""The derivation trace: the steps a law takes, recorded as it computes them.

Each ``Step`` names its section of the method (frames, kinematics, inertia, free-body diagram,
balance laws, solving), what was computed, the equations (left side, right side: sympy expressions
or vectors), and why.  Renderers (text, Markdown, LaTeX, HTML) read the trace; they never write
derivation text of their own.
"""

from __future__ import annotations

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
        if section not in SECTIONS:
            raise ValueError(f"unknown trace section {section!r}")
        self.steps.append(Step(section, title, tuple(equations), why, self.law))

    def section(self, name: str) -> list[Step]:
        return [s for s in self.steps if s.section == name]

    def extend(self, other: Trace) -> None:
        self.steps.extend(other.steps)

    def __len__(self) -> int:
        return len(self.steps)
