"""Which friction regime a worksheet is graded in.

A contact with sliding friction gives one set of equations per sliding direction (a *regime*).  The
motion fixes the regime: what the worksheet states (``motion = "dot(x) - r*dot(phi) > 0"``), the start of
the question a step names, or the problem's own declared start (released from rest: the slip that
starts).  In that regime an equation or diagram valid only in another regime is wrong, and its one cause
is the friction's direction.  Where nothing fixes it (a problem with no stated motion), the first step
that tells the regimes apart is the student's choice, stated, and every later step is held to it.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..analysis.answers import selects
from ..base.errors import InputError, RigidkinError
from ..base.printing import text
from ..io.expressions import parse_condition
from .claims import Unreadable, read

CAUSE = "friction drawn along the motion"


def _d(reg) -> str:
    return " ".join(reg.describe().split())


@dataclass
class RegimeChoice:
    """The regime the grading uses: fixed by the motion, chosen by the student (step), or still open."""

    regimes: list
    fixed: object = None          # a Regime fixed by the stated motion
    why: str = ""                 # what fixed it, in words
    chosen: object = None         # the student's choice where the problem leaves it open
    chosen_at: int = 0            # the step that chose it

    @property
    def open(self) -> bool:
        return len(self.regimes) > 1 and self.fixed is None

    def for_step(self, stated=None):
        """The regimes a step may be graded in, in order (the fixed or chosen one, else all)."""
        if stated is not None:
            return [stated]
        if self.fixed is not None:
            return [self.fixed]
        if self.chosen is not None:
            return [self.chosen]
        return list(self.regimes)

    def wrong_regime(self, other) -> str:
        """The cause of a step valid only in ``other``."""
        target = self.fixed or self.chosen
        if self.fixed is not None:
            return (f"{CAUSE}: this holds only when {_d(other)}, but {self.why} gives "
                    f"{_d(target)}; sliding friction opposes the slip")
        return (f"{CAUSE}: this holds only when {_d(other)}, but your step {self.chosen_at} took "
                f"{_d(target)}; keep one sliding direction throughout (sliding friction opposes the slip)")

    def scoped(self, question: str | None, ref) -> RegimeChoice:
        """This choice, or the one the start of the step's question fixes."""
        stated = regime_of_question(ref, question)
        if stated is None or stated is self.fixed:
            return self
        return RegimeChoice(self.regimes, stated, f"the start of '{question}'")

    def holds_in(self, reg, index: int) -> None:
        """A step valid in ``reg`` only: where the regime is open, it is the student's choice from now on."""
        if self.open and self.chosen is None:
            self.chosen, self.chosen_at = reg, index

    def note(self) -> str:
        if self.fixed is not None:
            return f"graded with the motion {_d(self.fixed)}, fixed by {self.why}"
        if self.chosen is not None:
            return (f"the problem leaves the sliding direction open: graded with your choice in step "
                    f"{self.chosen_at}, {_d(self.chosen)}")
        return ""


def regime_choice(ref, ws) -> RegimeChoice:
    """The regime the motion fixes for this worksheet (cached per problem and statement)."""
    regimes = ref.regimes()
    rc = RegimeChoice(regimes)
    if len(regimes) < 2:
        return rc
    if ws.motion:
        rc.fixed = _by_condition(ref, ws.motion, ws.motion_where)
        rc.why = f"the stated motion {ws.motion}"
        return rc
    found = []                        # every motion the problem states or a question asks
    got = _by_start(ref, {})
    if got is not None and _declares_start(ref):
        found.append((got, "the problem's start (" + _start_text(ref) + ")"))
    for q in ref.spec_questions():
        reg = regime_of_question(ref, q.name)
        if reg is not None:
            found.append((reg, f"the start of the question '{q.name}'"))
    phase = _by_phases(ref)
    if phase is not None:
        found.append(phase)
    if found and len({id(r) for r, _ in found}) == 1:
        rc.fixed, rc.why = found[0]
    return rc                         # motions that disagree: each step by its question, else the student's


def _by_phases(ref):
    """The regime of the sliding phases the problem's questions ask (each in the problem's own mode, started
    where the phase before it ended); one regime for all of them, else None."""
    found = []
    for q in ref.spec_questions():
        if q.kind != "phases":
            continue
        a = ref.answers().get(q.name)
        results = (getattr(a, "details", None) or {}).get("phases") if not isinstance(a, Exception) else None
        for spec, res in zip(q.fields.get("phase") or [], results or []):
            if spec.get("mode") or spec.get("set") or not res.happens:
                continue
            reg = next((r for r in ref.regimes() if r.describe() == res.regime), None)
            if reg is not None:
                rates = ", ".join(f"{text(k)} = {text(v)}" for k, v in res.start_state.items()
                                  if hasattr(k, "variables"))
                found.append((reg, f"the phase '{res.name}' of '{q.name}' (it starts with {rates})"))
    regs = {id(r) for r, _ in found}
    return found[0] if len(regs) == 1 else None


def regime_of_question(ref, question: str | None):
    """The regime at the start of the question a step names (None: no start there, or not decided)."""
    if not question or len(ref.regimes()) < 2:
        return None
    q = next((q for q in ref.spec_questions() if q.name == question), None)
    start = dict((q.fields.get("start") or q.fields.get("at") or {}) if q is not None else {})
    return _by_start(ref, start) if start else None


def _by_start(ref, start: dict):
    try:
        return ref.solution.regime_at(start)
    except (RigidkinError, TypeError, ValueError, ZeroDivisionError):
        return None


def _declares_start(ref) -> bool:
    return any(c.initial is not None or c.rate is not None for c in ref.system.coordinate_info.values())


def _start_text(ref) -> str:
    parts = []
    for c in ref.system.coordinate_info.values():
        if c.rate is not None:
            parts.append(f"dot({c.name}) = {c.rate:g}")
    moving = [p for p in parts if not p.endswith("= 0")]
    return "released from rest: the slip that starts" if parts and not moving else "its initial rates " + \
        ", ".join(parts)


def _by_condition(ref, motion: str, where: str):
    """The regime a condition on the rates selects (``dot(x) - r*dot(phi) > 0``)."""
    try:
        rel = read("motion", parse_condition, motion, ref.scope, where)
    except Unreadable as exc:                  # the worksheet's own field: bad input, not a step's verdict
        raise InputError(f"the motion cannot be read ({exc}).", where=where,
                         hint="Write a condition on a slip speed, e.g. motion = \"dot(x) - r*dot(phi) > 0\".") from None
    q = ref.setup.scalar(rel.lhs - rel.rhs)
    sign = 1 if rel.rel_op in (">", ">=") else -1
    for r in ref.regimes():
        if r.conditions and selects(r, q, sign):
            return r
    raise InputError(f"the motion {text(rel)} does not select one sliding regime of the problem.", where=where,
                     hint="Regimes: " + "; ".join(r.describe() for r in ref.regimes()) + ". Write the condition "
                          "of one, e.g. its slip speed > 0.")
