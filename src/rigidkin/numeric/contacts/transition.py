"""What happens at an event: the mode, regime and state after a watched quantity reaches zero.

A contact opens (the state carries over), an impact resolves by one impulse problem over every
contact closed or closing (``impact``), slipping turns into sticking if the friction needed is within
µs N, sticking turns into slipping in the direction the friction saturates (with the contacts it holds),
a friction direction reverses; a rope goes slack (free motion until its gap closes and it jerks taut:
``slack``) or a profile's arc ends (its edge takes the contact: ``arc_handover``).
Each returns the Event to record; the simulator then checks the choice against the contact problem
over every touching contact (``contact_modes.confirm``).
"""

from __future__ import annotations

import numpy as np

from ...model.constraints import SMOOTH, Coulomb
from ..result import Event
from ..rhs import SimulationError
from .arc_handover import ARC_KINDS, arc_transition
from .impact import impact, impact_numbers, mode_after
from .modes import Hybrid
from .slack import TIGHTENS, rope_transition
from .slip3d import SLOW, SPEED, contact_of, nudge, start_direction
from .vocabulary import OPEN, SLIP, STICK, ModeUnavailable


def transition(hyb: Hybrid, model, w, t_, y, p, e_of, rest_speed):
    """The mode, regime and state after watch ``w`` reached zero at (t_, y); and the Event to record."""
    lay = hyb.layout
    n = lay.n
    mode = dict(model.mode)
    before = lay.as_dict(y)
    detail = ""
    if w.kind == "opens":
        cand = {**mode, w.name: OPEN}
        forced = _current_signs(hyb, model, without=(w.name,))
        try:
            new_mode, k, nts = hyb.settle(cand, t_, y, p, forced=forced)
        except ModeUnavailable as exc:
            c = hyb.contacts[w.name]
            raise ModeUnavailable(f"the model has no coordinate that lets {w.name} leave its surface: with {w.name} "
                                  f"open, {exc.message.split(': ', 1)[-1]}", where=hyb.system.name,
                                  hint=f"Its normal reaction {c.N} reaches zero here. To follow the motion "
                                       f"beyond, add a coordinate that lets {w.name} separate (such as the "
                                       "distance of the body from the surface).") from None
        detail = f"the normal reaction of {w.name} reaches zero; the contact opens"
    elif w.kind == "impact":
        out = impact(hyb, mode, w.name, t_, y, p, e_of, model.regime_index)
        y = np.array(y, dtype=float)
        y[:2 * n] = out.y[:2 * n]
        y[2 * n] += out.energy_change
        detail = (f"impact at {w.name}"
                  + (f" (with {', '.join(c_ for c_ in out.contacts if c_ != w.name)})" if len(out.contacts) > 1
                     else "")
                  + f": normal speed {out.approach_speed:.6g} → {out.separation_speed:.6g}, "
                  + ", ".join(f"impulse {k_} = {v:.6g}" for k_, v in out.impulses.items())
                  + f", kinetic energy change {out.energy_change:.6g}"
                  + ("; Newton's law with friction would create energy here, so the impact is plastic (e = 0)"
                     if out.plastic else "")
                  + (f"; the impulse problem has {out.solutions} solutions (the first in the fixed order is "
                     "taken)" if out.solutions > 1 else "")
                  + (f"; {', '.join(out.held)} kept closed by the coordinates: its impulses from every body's "
                     "impulse–momentum equations" if out.held else "")
                  + (f"; {', '.join(out.indeterminate)} not determined by the impact (how they split between the "
                     "contacts is a choice: the smallest that fit)" if out.indeterminate else ""))
        cand, forced_after, nts0 = mode_after(hyb, mode, out, rest_speed)
        forced = _current_signs(hyb, model, without=out.contacts)
        forced.update(forced_after)
        new_mode, k, nts = hyb.settle(cand, t_, y, p, forced=forced)
        nts = nts0 + nts
        if out.separation_speed > rest_speed:
            nts.insert(0, "the body bounces off")
    elif w.kind == "sticks":
        cand = {**mode, w.name: STICK}
        forced = _current_signs(hyb, model, without=(w.name,))
        try:
            new_mode, k, nts = hyb.settle(cand, t_, y, p, forced=forced)
        except ModeUnavailable as exc:           # the model cannot stick here: can it slip on?
            try:
                new_mode, k, nts = mode, hyb.regime_at(mode, t_, y, p, forced), []
            except SimulationError:
                raise ModeUnavailable(f"neither slip direction at {w.name} is consistent (so friction holds it), "
                                      f"and the model cannot stick there: {exc.message.split(': ', 1)[-1]}",
                                      where=hyb.system.name,
                                      hint="The body comes to rest relative to the surface; to go on, the "
                                           "model needs a coordinate that still moves while it sticks.") from None
        if new_mode.get(w.name) == STICK:
            detail = f"the slip speed at {w.name} reaches zero and the friction needed is within µN: it sticks"
        else:
            detail = f"the slip speed at {w.name} reaches zero but sticking needs more than µN: it slips on"
    elif w.kind == "slips":
        cand = {**mode, w.name: SLIP}
        if w.slip_sign == 0:        # 3D: the slip starts against the friction the cone no longer holds
            forced = {**_current_signs(hyb, model), **start_direction(hyb, cand, w.name, t_, y, p,
                                                                      model.reactions(t_, y, p))}
        else:
            forced = {**_current_signs(hyb, model), w.name: w.slip_sign}
        for h in getattr(model.solution.setup, "held", ()):     # held with it: the group slips together
            cand[h], forced[h] = SLIP, w.slip_sign
        new_mode, k, nts = hyb.settle(cand, t_, y, p, forced=forced)
        detail = (f"the friction needed at {w.name} reaches µN; it slips with slip speed "
                  f"{'positive' if w.slip_sign > 0 else 'negative'}" if w.slip_sign else
                  f"the friction needed at {w.name} reaches the friction cone µN; it slips against it")
    elif w.kind in ("slack", TIGHTENS):   # a rope's tension reaches zero, or its slack gap closes (.slack)
        return rope_transition(hyb, model, w, t_, y, p, e_of, rest_speed, _current_signs(hyb, model))
    elif w.kind in ARC_KINDS:      # a profile's arc ends, comes back or strikes (model.profiles, arc_handover)
        return arc_transition(hyb, model, w, t_, y, p, e_of, rest_speed, transition, _current_signs)
    else:  # "reverses"
        turned = contact_of(w.name)     # a 3D slip direction past a diagonal: the other tangent is the reference
        forced = _current_signs(hyb, model, without=(w.name,) + ((turned,) if turned else ()))
        k = hyb.regime_at(mode, t_, y, p, forced)
        new_mode, nts = mode, []
        if turned and w.name.endswith(SPEED):
            detail = (f"the slip speed at {turned} passes {SLOW:g} m/s: its friction direction is written "
                      + ("relative to a reference tangent" if w.direction < 0 else "as v_s/|v_s| again")
                      + " (the motion does not change)")
        elif turned:
            detail = (f"the slip direction at {turned} turns past a diagonal of its tangent basis; its friction "
                      "direction is written relative to the other tangent (the motion does not change)")
        else:
            detail = f"{w.label}: the friction direction follows the new sign"
    y = np.array(y, dtype=float)
    y[:2 * n] = hyb.project_rates(new_mode, t_, y[:2 * n], p)
    y = nudge(hyb, new_mode, t_, y, p)        # a 3D slip that starts here (slip3d)
    after_model = hyb.model(new_mode, k)
    if nts:
        detail = "; ".join([detail, *nts]) if detail else "; ".join(nts)
    name = w.label
    if w.kind == "sticks" and new_mode.get(w.name) == STICK:
        c = hyb.contacts[w.name]
        name = f"contact {w.name} sticks" + (" (rolling begins)" if c.radius != 0 else "")
    elif w.kind == "sticks":
        name = f"contact {w.name} slip reverses"
    ev = Event(name, w.kind, w.name, t_, before, lay.as_dict(y), model.description, after_model.description,
               detail, impact_numbers(out, before, lay.as_dict(y)) if w.kind == "impact" else None)
    return new_mode, k, y, ev


def _current_signs(hyb: Hybrid, model, without=()) -> dict:
    """The friction directions of the regime in force (load → σ), kept through other contacts' changes;
    the contacts in ``without`` (those the event changes) are left to be decided anew."""
    out = {}
    sol = model.solution
    for sc in sol.setup.sign_choices:
        if sc.symbol in model.regime.signs:
            out[sc.load] = int(model.regime.signs[sc.symbol])
    # a contact whose friction is smooth or that sticks has no direction to keep
    return {k: v for k, v in out.items() if k not in without
            and (k not in hyb.contacts or (isinstance(hyb.contacts[k].friction, Coulomb)
                                         and hyb.contacts[k].friction != SMOOTH))}
