"""Choosing the consistent mode and regime at a state: normal reactions that push, friction within µs N
where a contact sticks, slip directions the motion keeps.

``settle`` starts from a candidate mode and repairs it one contact at a time (a contact whose normal
reaction would pull opens; a sticking contact that needs more than µs N slips in the direction the
friction saturates); ``regime_at`` picks the friction directions whose conditions hold, at a zero the
ones the motion leaves it consistently with.  ``held_alternative`` turns an over-constrained sticking
mode (a rod at rest on two rough supports) into the same motion with the friction carried jointly.
"""

from __future__ import annotations

import numpy as np

from ...model.constraints import ROLLING, Coulomb
from ..rhs import SimulationError
from .mode_model import ModeModel, _Only
from .slack import open_slack, pushing
from .slip3d import friction_needed, slip_speed, start_direction
from .vocabulary import OPEN, SLIP, STICK, ModeUnavailable, describe_mode, mode_key


def regime_at(hyb, mode: dict, t_, y, p, forced: dict | None = None, zero_tol: float = 1e-9) -> int:
    """The regime whose conditions hold at the state; at a zero, the one whose motion leaves it consistently.

    ``forced`` maps a sign choice's load name to the sign σ it must have (a slip that begins).
    """
    sol = hyb.solution(mode)
    if len(sol.regimes) == 1:
        return 0
    forced = forced or {}
    zero = zero_tol * max(1.0, float(np.max(np.abs(y[:2 * hyb.layout.n]))))
    choices = sol.setup.sign_choices
    candidates = []
    for k, reg in enumerate(sol.regimes):
        if any(sc.load in forced and sc.symbol in reg.signs and reg.signs[sc.symbol] != forced[sc.load]
               for sc in choices):
            continue
        model = hyb.model(mode, k)
        free = [(wi, rel) for wi, rel in model.conditions if model.watches[wi].name not in forced]
        held = ModeModel.condition_holds(_Only(model, free), t_, y, p, zero)
        if held is None:
            held = ModeModel.leaves_zero_consistently(_Only(model, free), t_, y, p, zero)
        if held:
            candidates.append(k)
    if not candidates:
        raise SimulationError(f"at t = {t_:.10g} no friction direction of the mode "
                              f"({describe_mode(hyb.system, mode)}) is consistent with the motion.",
                              where=hyb.system.name,
                              hint="The friction would have to stick where the model cannot stick "
                                   "(a friction load or a collar), or the friction law has no solution here.")
    return candidates[0]

def settle(hyb, mode: dict, t_, y, p, forced: dict | None = None, zero_tol: float = 1e-9,
           force_tol: float = 1e-9) -> tuple[dict, int, list[str]]:
    """The consistent (mode, regime) at a state, starting from the candidate ``mode``.

    Closed Coulomb contacts whose slip speed is zero are tried sticking; a sticking contact that
    needs more friction than µN slips in the direction the friction saturates; a unilateral
    contact whose normal reaction would pull opens, a rope or cable whose tension would push goes slack.
    Contacts and ropes are never closed here (an impact or a jerk does that).  Returns (mode, regime, notes).
    """
    mode, forced, notes = dict(mode), dict(forced or {}), []
    for name, c in hyb.contacts.items():      # a rolling contact held by others rolls again on its own
        if mode[name] == SLIP and c.friction == ROLLING:
            mode[name] = STICK
    scale = max(1.0, float(np.max(np.abs(y[:2 * hyb.layout.n]))))
    for name, c in hyb.contacts.items():
        if mode[name] != OPEN and isinstance(c.friction, Coulomb) and name not in forced:
            s = hyb.contact_state(name, t_, y, p)[2] if hyb.kin.planar else slip_speed(hyb, name, t_, y, p)
            if s is not None and abs(s) <= zero_tol * scale:
                mode[name] = STICK
            elif s is not None:
                mode[name] = SLIP
    seen = set()
    for _ in range(4 * len(hyb.contacts) + 4):
        key = (mode_key(mode), tuple(sorted(forced.items())))
        if key in seen:
            break
        seen.add(key)
        try:
            sol = hyb.solution(mode)
        except ModeUnavailable:
            alt = held_alternative(hyb, mode)
            if alt is None:
                raise
            mode = alt
            sol = hyb.solution(mode)
            notes.append("statically indeterminate: the friction at " + ", ".join(held_contacts(hyb, mode, sol))
                         + " cannot be told apart from the other sticking contacts'; they carry it together")
        held = tuple(h for h in held_contacts(hyb, mode, sol) if isinstance(hyb.contacts[h].friction, Coulomb))
        k = hyb.regime_at(mode, t_, y, p, forced, zero_tol)
        model = hyb.model(mode, k)
        react = model.reactions(t_, y, p)
        fscale = max(1.0, max((abs(v) for v in react.values()), default=1.0))
        changed = False
        # a unilateral contact that would pull opens (the most negative first)
        pulling = [(react[str(c.N)], n) for n, c in hyb.contacts.items()
                   if mode[n] != OPEN and c.unilateral and str(c.N) in react
                   and react[str(c.N)] < -force_tol * fscale]
        if pulling:
            _, n = min(pulling)
            mode[n] = OPEN
            forced.pop(n, None)
            notes.append(f"{n} opens: its normal reaction would pull ({react[str(hyb.contacts[n].N)]:.4g})")
            continue
        pushes = pushing(hyb, mode, react, force_tol * fscale)      # a rope that would push goes slack (.slack)
        if pushes:
            tension, tname, n = pushes[0]
            open_slack(hyb, mode, n, t_, y, p, f"would push ({tname} = {tension:.4g})")
            mode[n] = OPEN
            notes.append(f"{n} goes slack: its tension would push ({tname} = {tension:.4g})")
            continue
        # the friction of held contacts is carried by the sticking ones: their limits add up
        spare = sum(float(hyb._param_value(hyb.contacts[h].friction.static, p))
                    * abs(react.get(str(hyb.contacts[h].N), 0.0)) for h in held)
        for n, c in hyb.contacts.items():
            if mode[n] != STICK or not isinstance(c.friction, Coulomb):
                continue
            N, F = react.get(str(c.N), 0.0), react.get(str(c.F), 0.0)
            if not hyb.kin.planar:
                F = friction_needed(c, react) or 0.0
            mu = float(hyb._param_value(c.friction.static, p))
            if abs(F) > mu * abs(N) + spare + force_tol * fscale:
                if not hyb.kin.planar:
                    mode[n] = SLIP
                    forced.update(start_direction(hyb, mode, n, t_, y, p, react))
                    notes.append(f"{n} slips: sticking needs |F| = {abs(F):.4g} > µN = {mu * abs(N):.4g}")
                    changed = True
                    break
                mode[n] = SLIP
                forced[n] = -1 if F > 0 else 1
                notes.append(f"{n} slips: sticking needs |F| = {abs(F):.4g} > µN = {mu * abs(N):.4g}")
                changed = True
                break
        if changed:
            continue
        return mode, k, notes
    raise SimulationError(f"at t = {t_:.10g} no contact mode is consistent with the state "
                          f"(tried up to {describe_mode(hyb.system, mode)}).", where=hyb.system.name,
                          hint="Sticking and slipping are both inconsistent here (a Painlevé-type paradox), "
                               "or the contacts keep opening and closing.")

def held_alternative(hyb, mode: dict) -> dict | None:
    """A sticking mode that is over-constrained (a rod at rest on two rough supports, a block on two
    rolling corners): the same motion with a later sticking contact named ``slip``, held by the others
    (its friction carried jointly with theirs: the sum is determined, the split is not)."""
    sticking = [n for n in hyb.contacts if mode[n] == STICK
                and (isinstance(hyb.contacts[n].friction, Coulomb) or hyb.contacts[n].friction == ROLLING)]
    for n in reversed(sticking):
        trial = {**mode, n: SLIP}
        try:
            sol = hyb.solution(trial)
        except ModeUnavailable:
            continue
        if n in held_contacts(hyb, trial, sol):
            return trial
    return None


def held_contacts(hyb, mode: dict, sol) -> tuple[str, ...]:
    """The contacts of ``mode`` whose friction the sticking ones carry: Coulomb contacts the derivation
    found held, and rolling contacts named ``slip`` whose slip speed the other constraints keep at zero."""
    out = list(getattr(sol.setup, "held", ()))
    red = sol.setup.reduction
    for n, c in hyb.contacts.items():
        if (mode.get(n) == SLIP and c.friction == ROLLING and n not in out and hyb.kin.planar
                and hyb.kin.is_zero(red.to_independent(c.slip_velocity(hyb.kin)))):
            out.append(n)
    return tuple(out)
