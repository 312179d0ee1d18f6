"""The problem file's ``[ask]``: the equations of motion, the reactions and one table per question kind
(eom, reaction, integral, event, extreme, threshold, equilibrium, impulse, interval, phases, value), chosen
by ``kind``."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from .schema_base import Expr, Name, Quantity, State, Strict


class QuestionBase(Strict):
    name: str | None = None
    description: str = ""
    mode: dict[Name, str] | None = None
    set: State | None = None
    after: str | None = None


class PhaseSpec(Strict):
    name: str | None = None
    mode: dict[Name, str] = {}
    set: State = {}
    until: str | None = None


class EomQ(QuestionBase):
    kind: Literal["eom"]


class ReactionQ(QuestionBase):
    kind: Literal["reaction"]
    reaction: Name
    start: State | None = None


class IntegralQ(QuestionBase):
    kind: Literal["integral"]
    start: State | None = None


class EventQ(QuestionBase):
    kind: Literal["event"]
    when: str
    start: State | None = None


class ExtremeQ(QuestionBase):
    kind: Literal["extreme"]
    coordinate: Name
    start: State | None = None


class ThresholdQ(QuestionBase):
    kind: Literal["threshold"]
    holds: str
    start: State | None = None
    over: list[Quantity] | None = Field(default=None, min_length=2, max_length=2)
    expression: Expr | None = None


class EquilibriumQ(QuestionBase):
    kind: Literal["equilibrium"]


class ImpulseQ(QuestionBase):
    kind: Literal["impulse"]
    start: State | None = None


class IntervalQ(QuestionBase):
    kind: Literal["interval"]
    duration: Expr | None = None
    until: str | None = None
    start: State | None = None
    regime: str | None = None


class PhasesQ(QuestionBase):
    kind: Literal["phases"]
    start: State | None = None
    phase: list[PhaseSpec] = Field(min_length=1)


class ValueQ(QuestionBase):
    kind: Literal["value"]
    expression: Expr
    at: State | None = None


QUESTION_MODELS = (EomQ, ReactionQ, IntegralQ, EventQ, ExtremeQ, ThresholdQ, EquilibriumQ, ImpulseQ, IntervalQ,
                   PhasesQ, ValueQ)
QuestionSpec = Annotated[EomQ | ReactionQ | IntegralQ | EventQ | ExtremeQ | ThresholdQ | EquilibriumQ | ImpulseQ
                         | IntervalQ | PhasesQ | ValueQ, Field(discriminator="kind")]


class AskSpec(Strict):
    eom: bool = True
    reactions: list[Name] | None = None
    question: list[QuestionSpec] = []
