"""The words of hybrid motion: the state of a contact in a mode, and a mode told in words.

A *mode* gives every contact a state: ``open`` (apart, no reaction), ``slip`` (touching and sliding, the
friction µk N against the slip, or smooth) or ``stick`` (touching without sliding: sticking, or rolling
for a contact with a radius).  A mode is keyed by its sorted (contact, state) pairs; a mode the model
cannot derive (no coordinate lets a contact open) is :class:`ModeUnavailable`.  Shared by the modes'
derivation (:mod:`.modes`), the choice of a consistent mode (:mod:`.settle`, :mod:`.contact_modes`),
3D slip (:mod:`.slip3d`), impacts and transitions.
"""

from __future__ import annotations

from ...base.errors import RigidkinError
from ...model.constraints import ROLLING, SMOOTH

OPEN, SLIP, STICK = "open", "slip", "stick"


class ModeUnavailable(RigidkinError):
    """A mode the motion needs cannot be derived from the model (e.g. no coordinate lets a contact open)."""


def mode_key(mode: dict) -> tuple:
    return tuple(sorted(mode.items()))


def describe_mode(system, mode: dict, held=()) -> str:
    """``A open, B closed (smooth)``: the contacts' states in words.

    A contact named ``slip`` whose friction the sticking ones carry (``held``: a rod at rest on two rough
    supports; a rolling contact is named ``slip`` only so) does not slip: it is told as sticking (rolling)
    with its friction shared."""
    words = []
    ropes = {n: STICK for n, c in system.constraints.items() if getattr(c, "kind", "") in ("rope", "cable")}
    for name, st in sorted({**ropes, **mode}.items()):      # a rope is in a mode only while slack: else taut
        c = system.constraints.get(name)
        if c is None or (st == OPEN and getattr(c, "edge_of", None)):
            continue            # an edge at the end of an arc (model.arc_edges) is told only while it touches
        if getattr(c, "kind", "") in ("rope", "cable"):
            words.append(f"{name} slack" if st == OPEN else f"{name} taut")
        elif st == OPEN:
            words.append(f"{name} open")
        elif st == STICK:
            words.append(f"{name} rolling" if c.radius != 0 else f"{name} sticking")
        elif c.friction == SMOOTH:
            words.append(f"{name} closed")
        elif name in held or c.friction == ROLLING:
            words.append(f"{name} {'rolling' if c.radius != 0 else 'sticking'} (friction shared)")
        else:
            words.append(f"{name} slipping")
    return ", ".join(words) or "no contacts"
