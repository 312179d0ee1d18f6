"""The events of a profile that is an arc: its end hands the contact to an edge, the edge hands it back.

* ``arc`` — the contact point reaches the end of the arc (margin m = 0, falling).  The arc's geometry ends
  there: the contact opens, and the edge at that end (``<contact>_edge1`` or ``_edge2``,
  :mod:`rigidkin.model.arc_edges`) takes it.  At that instant the edge *is* the contact point, so its
  velocity is the material velocity of the contact point: normal speed zero (the arc was closed), slip
  speed the arc's.  The edge closes with that slip (sticking where it rolled, sliding on where it slid,
  in the contact's friction law) and the consistent mode follows (``settle``: it may open at once, and the
  body leaves the surface).  Were the edge's approach speed not zero (an arc contact that was not closed
  does not come here), it would be an impact, solved as any other.  Without edges (3D, a curved surface,
  an arc declared by hand) the simulation stops here (reason ``arc-end``), as it does where the model has
  no coordinate that lets the body leave its arc.
* ``arc-back`` — the body rocks back on the edge until the arc's end reaches the surface again (m rising
  through zero with the edge touching): there the arc touches at its end, where the edge is, with the
  edge's velocity; the arc contact closes and the edge opens (the consistent mode follows).
* ``arc-impact`` — an open arc (no edge touching) or an edge strikes the surface: an impact of that
  contact (``impact``), the edges taking their arc contact's coefficient of restitution.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...model.constraints import ROLLING, SMOOTH, Coulomb
from ..result import Event
from ..rhs import SimulationError
from .arc_support import end_values, parent_of
from .vocabulary import OPEN, SLIP, STICK, ModeUnavailable

ARC_KINDS = ("arc", "arc-back", "arc-impact")


def arc_transition(hyb, model, w, t_, y, p, e_of, rest_speed, transition, current_signs):
    """(mode, regime, state, Event) after an arc event ``w`` at (t_, y); ``transition`` solves an impact,
    ``current_signs(hyb, model, without)`` gives the friction directions kept through the event."""
    if w.kind == "arc-impact":
        parents = parent_of(hyb)
        e_full = {**e_of, **{e: e_of.get(a, 0.0) for e, a in parents.items()}}
        name = w.name
        if name in hyb.edges and end_values(hyb, name, t_, y, p)[0] < 0:   # the arc's end: the edge there strikes
            name = min(hyb.edges[name], key=lambda e: abs(hyb.contact_state(e, t_, y, p)[0]))
        w2 = replace(w, kind="impact", name=name, label=f"impact at {name}", quantity=f"gap of {name}")
        return transition(hyb, model, w2, t_, y, p, e_full, rest_speed)
    if w.kind == "arc":
        return _hand_over(hyb, model, w, t_, y, p, e_of, rest_speed, transition, current_signs)
    return _hand_back(hyb, model, w, t_, y, p, current_signs)


def _closing(hyb, name, slip, zero) -> tuple[str, int]:
    """(state, slip sign) a contact takes as it closes with slip speed ``slip``: its friction law."""
    c = hyb.contacts[name]
    if c.friction == ROLLING:
        return STICK, 0
    if c.friction == SMOOTH or not isinstance(c.friction, Coulomb) or slip is None:
        return SLIP, 0
    if abs(slip) <= zero:
        return STICK, 0
    return SLIP, (1 if slip > 0 else -1)


def _stop(hyb, name, why: str, hint: str):
    exc = SimulationError(f"the contact point of {name} reaches the end of its profile's arc: {why}",
                          where=hyb.system.name, hint=hint)
    exc.stop_reason = "arc-end"
    return exc


def _hand_over(hyb, model, w, t_, y, p, e_of, rest_speed, transition, current_signs):
    name, mode = w.name, dict(model.mode)
    if name not in hyb.edges:
        raise _stop(hyb, name, "the edge meets the surface, and the model has no contact there.",
                    "To follow the motion beyond, model the edge (or flat face) as a contact of its own (edges are "
                    "added by themselves for a half shape's curved face in planar motion on a straight surface).")
    scale = max(1.0, float(np.max(np.abs(y[:2 * hyb.layout.n]))))
    zero = 1e-9 * scale
    states = {e: hyb.contact_state(e, t_, y, p) for e in hyb.edges[name]}
    edge = min(states, key=lambda e: abs(states[e][0]))
    gap, vn, slip = states[edge]
    before = hyb.layout.as_dict(y)
    head = (f"the contact point of {name} reaches the end of its arc (its arc margin is zero): the arc ends there "
            f"and {name} opens; the edge {edge} takes the contact with normal speed {vn:.6g}"
            + (f" and slip speed {slip:.6g}" if slip is not None else ""))
    try:
        hyb.solution({**mode, name: OPEN})
    except ModeUnavailable as exc:
        raise _stop(hyb, name, f"the edge {edge} would take the contact there, but the model has no coordinate "
                               f"that lets {hyb.contacts[name].body.name} leave its arc (with {name} open, "
                               f"{exc.message.split(': ', 1)[-1].rstrip('.')}).",
                    f"Give {hyb.contacts[name].body.name} the coordinates of a free body in the plane (the height "
                    "of its flat-face centre too), so that it can rock on the edge and land on its flat "
                    "face.") from None
    if vn < -max(rest_speed, zero):           # the edge strikes: an impact (not reached from a closed arc)
        opened = {**mode, name: OPEN}
        w2 = replace(w, kind="arc-impact", name=edge, label=f"impact at {edge}", quantity=f"gap of {edge}")
        k0 = hyb.regime_at(opened, t_, y, p)
        new_mode, k, y2, ev = arc_transition(hyb, hyb.model(opened, k0), w2, t_, y, p, e_of, rest_speed, transition,
                                             current_signs)
        return new_mode, k, y2, replace(ev, name=f"the arc of {name} ends: the edge {edge} strikes the surface",
                                        mode_before=model.description, detail=f"{head}; {ev.detail}")
    st, sign = _closing(hyb, edge, slip, zero)
    forced = current_signs(hyb, model, without=(name, edge))
    if sign:
        forced[edge] = sign
    new_mode, k, nts = hyb.settle({**mode, name: OPEN, edge: st}, t_, y, p, forced=forced)
    return _finish(hyb, model, w, t_, y, p, new_mode, k, [head, *nts], before,
                   f"the arc of {name} ends: the edge {edge} takes the contact")


def _hand_back(hyb, model, w, t_, y, p, current_signs):
    name, mode = w.name, dict(model.mode)
    scale = max(1.0, float(np.max(np.abs(y[:2 * hyb.layout.n]))))
    zero = 1e-9 * scale
    before = hyb.layout.as_dict(y)
    edges = [e for e in hyb.edges[name] if mode[e] != OPEN]
    slip = hyb.contact_state(name, t_, y, p)[2]
    vn = hyb.contact_state(edges[0], t_, y, p)[1] if edges else 0.0     # the arc's end is where the edge is
    if abs(end_values(hyb, name, t_, y, p)[2]) > zero:        # the arc's end comes back above the surface
        k = hyb.regime_at(mode, t_, y, p, current_signs(hyb, model))
        return _finish(hyb, model, w, t_, y, p, mode, k, [f"the arc of {name} comes back clear of the surface"],
                       before, w.label)
    st, sign = _closing(hyb, name, slip, zero)
    forced = current_signs(hyb, model, without=(name, *edges))
    if sign:
        forced[name] = sign
    new_mode, k, nts = hyb.settle({**mode, name: st, **{e: OPEN for e in edges}}, t_, y, p, forced=forced)
    head = (f"rocking back on {', '.join(edges)}, the end of the arc of {name} reaches the surface where the edge "
            f"is (its arc margin is zero): {name} closes with normal speed {vn:.6g}"
            + (f" and slip speed {slip:.6g}" if slip is not None else "") + f", and {', '.join(edges)} opens")
    return _finish(hyb, model, w, t_, y, p, new_mode, k, [head, *nts], before,
                   f"the edge {', '.join(edges)} hands the contact back to the arc of {name}")


def _finish(hyb, model, w, t_, y, p, new_mode, k, notes, before, name):
    n = hyb.layout.n
    y = np.array(y, dtype=float)
    y[:2 * n] = hyb.project_rates(new_mode, t_, y[:2 * n], p)
    after = hyb.model(new_mode, k)
    ev = Event(name, w.kind, w.name, t_, before, hyb.layout.as_dict(y), model.description, after.description,
               "; ".join(notes))
    return new_mode, k, y, ev
