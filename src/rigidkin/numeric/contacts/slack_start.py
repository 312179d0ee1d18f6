"""A start with a rope or cable already slack (``mode={"string": "open"}``, ``--mode string=open``).

The mode of a start names contacts (``open``, ``slip``, ``stick``) and ropes or cables: ``open`` or ``slack``
starts it slack (its row dropped, the bodies free of it, its gap watched: :mod:`.slack`), ``taut`` or
``closed`` starts it taut (the automatic start, which still lets it go slack where its tension would push).

The free length of a rope that starts slack:

* a cable has its declared length ℓ; the gap ℓ − Σ|P_{k+1} − P_k| at the start must be ≥ 0 (a start with its
  ends farther apart than ℓ is refused);
* a rope of one segment (a string from a point to a drum: a yo-yo) has no declared length: it starts slack with
  the free length it has at the start, the distance between its ends there (a gap of 0, slack).  The drum pays
  rope out or winds it in as it turns relative to the rope (:func:`.slack.slack_gap`), so a yo-yo thrown up
  with a spin that does not match the string flies free and jerks taut where the gap closes.
"""

from __future__ import annotations

from ...base.errors import InputError
from .slack import _gap_functions
from .vocabulary import OPEN, SLIP, STICK, ModeUnavailable

#: the words of a start state of a rope or cable
SLACK_WORDS, TAUT_WORDS = ("open", "slack"), ("taut", "closed")


def start_modes(hyb, mode) -> tuple[dict, list[str]]:
    """(the candidate mode of the start, the ropes and cables that start slack) from the user's ``mode``."""
    system = hyb.system
    cand = hyb.default_mode()
    ropes = {n: c for n, c in system.constraints.items() if getattr(c, "kind", "") in ("rope", "cable")}
    slack = []
    for name, st in (mode or {}).items():
        if name in ropes:
            if st not in SLACK_WORDS + TAUT_WORDS:
                raise InputError(f"the start state '{st}' of {ropes[name].kind} {name} is not open (slack) or taut "
                                 "(closed).", where=f"mode of {name}")
            if st in SLACK_WORDS:
                slack.append(name)
            continue
        if name not in hyb.contacts:
            raise InputError(f"'{name}' is not a contact, rope or cable of {system.name}.", where="mode",
                             hint=f"Contacts, ropes and cables: {', '.join([*hyb.contacts, *ropes]) or 'none'}.")
        if st not in (OPEN, SLIP, STICK):
            raise InputError(f"contact state '{st}' is not open, slip or stick.", where=f"mode of {name}")
        cand[name] = st
    for name in slack:
        c = ropes[name]
        fns = _gap_functions(hyb, c)
        why = fns if isinstance(fns, str) else ""
        if not why:
            try:
                hyb.solution({**cand, **{n: OPEN for n in slack}})
            except ModeUnavailable as exc:
                why = f"the model cannot move without it ({exc.message.split(': ', 1)[-1]})"
        if why:
            raise InputError(f"{c.kind} {name} cannot start slack: {why}.", where=f"mode of {name}",
                             hint="Start it taut, or give the ends' motions coordinates of their own.")
        cand[name] = OPEN
    return cand, slack


def start_slack(hyb, slack, t0, y, p, where: str) -> dict:
    """Fix the free lengths of the ropes and cables that start slack at the state ``y`` (see the module
    docstring; kept in ``hyb.free_lengths``), refusing a cable whose ends are farther apart than its length.
    Returns the modes' entries {name: open}."""
    n = hyb.layout.n
    for name in slack:
        c = hyb.system.constraints[name]
        gap, length = (float(v) for v in _gap_functions(hyb, c)(t0, *y[:2 * n], *p))
        if c.kind != "cable":
            hyb.free_lengths[name] = -gap          # ℓ = the distance at the start: the gap starts at zero
            continue
        if gap < -1e-9 * max(1.0, abs(length)):
            raise InputError(f"cable {name} cannot start slack: at the start its ends are {length - gap:.6g} apart "
                             f"along it, longer than its length {length:.6g} (gap ℓ − L = {gap:.6g} < 0).",
                             where=where, hint="Start the bodies within the cable's length, or start it taut.")
        hyb.free_lengths[name] = 0.0               # a cable's gap is complete: ℓ − L
    return {name: OPEN for name in slack}


__all__ = ["SLACK_WORDS", "TAUT_WORDS", "start_modes", "start_slack"]
