"""The verdict on each step of a hand derivation, and the report of a whole worksheet.

A step is ``correct``, ``incorrect`` or ``unreadable`` (the parser could not read the claim), with
feedback naming the cause; a wrong step that follows from the student's own earlier wrong steps (their
accelerations, diagrams or balance equations, kept in :class:`Carried`) is a *carried error*.
"""

from __future__ import annotations

from dataclasses import dataclass, field

CORRECT, INCORRECT, UNREADABLE = "correct", "incorrect", "unreadable"


@dataclass
class StepResult:
    index: int
    kind: str
    verdict: str
    feedback: list[str] = field(default_factory=list)
    claim: str = ""                     # the student's claim as written
    expected: str = ""                  # the engine's form of the step, for the report
    carried_from: tuple[int, ...] = ()  # earlier steps this (wrong) step follows from
    differences: list[tuple[str, str]] = field(default_factory=list)   # (student's, engine's) per difference
    asks: str = ""                      # an answer step: what its question asks, in words and symbol


@dataclass
class GradeReport:
    problem: str
    title: str
    student: str
    steps: list[StepResult]

    @property
    def correct(self) -> int:
        return sum(1 for s in self.steps if s.verdict == CORRECT)

    @property
    def score(self) -> float:
        return round(self.correct / len(self.steps), 4) if self.steps else 0.0

    @property
    def ok(self) -> bool:
        return all(s.verdict == CORRECT for s in self.steps)


@dataclass
class Carried:
    """What the student's earlier wrong steps said, for grading later steps against them."""

    accel: dict = field(default_factory=dict)      # body → (step, vector a_G)
    alpha: dict = field(default_factory=dict)      # body → (step, vector α)
    loads: dict = field(default_factory=dict)      # body → (step, [(vector, location | None)])
    balances: list = field(default_factory=list)   # (step, expr = 0, the engine's nearest equation)
    cache: dict = field(default_factory=dict)      # the student's modified equations, per set of steps
