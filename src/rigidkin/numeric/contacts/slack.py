"""A rope or cable that goes slack, moves free, and re-tightens with a jerk.

While taut a rope (:mod:`rigidkin.model.ropes`) or a cable (:class:`rigidkin.model.constraints.Cable`) has a
velocity row and a tension T ≥ 0.  When T reaches zero it goes *slack*: the mode names it ``open``, its row is
dropped and the bodies move free of it, while the simulation watches the rope's *gap*, the free length
available minus the straight distance between its stations:

* a cable: gap = ℓ − Σ|P_{k+1} − P_k|, with ℓ its declared length;
* a rope of one straight segment (between two points, or from a point to a drum it is wound on):
  gap = ℓ − L, with L the segment's length between its tangent points.  The rope stays wound on the
  drum as it was and turns with it (the wound turns do not slip on the drum, slack or taut), so the drum
  pays rope out or takes it in as it turns relative to the rope's direction: ℓ̇ = L̇ − v_row, the rate by
  which the rope's no-slip row and the tangent length differ (−r(φ̇ − ψ̇) for a drum of radius r turning
  by φ, ψ the rope's direction; 0 between two points).  The free length is ℓ = ℓ_s + that change, with ℓ_s
  = L where the rope goes slack.  So the gap's rate is −v_row in every mode: it stays closed exactly while
  the rope is taut, and opens only as the tension lets go.

A rope over pulleys (more than one segment) going slack still stops the simulation: which segment takes
up the slack depends on how its pulleys turn free, which the model does not follow.

When the gap closes the rope re-tightens (:mod:`.jerk`): an impulse along it, by impulse–momentum.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base.linear import linear_form
from ..result import Event
from ..rhs import SimulationError, compile_functions
from .jerk import jerk, restitution_of
from .slip3d import nudge
from .vocabulary import OPEN, ModeUnavailable

t = dynamicsymbols._t

#: a rope's watch for its gap closing (``Watch.kind``)
TIGHTENS = "tightens"


class CannotFollow(SimulationError):
    """A rope goes slack where the simulation cannot follow it (stop reason ``slack``)."""

    def __init__(self, message, *, where=None, hint=None):
        super().__init__(message, where=where, hint=hint)
        self.stop_reason = "slack"


def slack_gap(c, kin, coordinates):
    """(gap expression without its constant, why not): the watched gap of rope or cable ``c`` while slack, up
    to the constant fixed where it goes slack (a cable's gap is complete: its constant is 0 but for the drift
    of the taut integration); or (None, the reason it cannot be followed).

    A rope of one segment with signed radii a, b at its ends (0 at a point), turning angles φ_i, φ_j of the
    bodies there and ψ the direction angle of the segment's normal n: the rope moves with each drum's rim
    where it leaves it, so the free length changes by ℓ̇ = a(φ̇_i − ψ̇) − b(φ̇_j − ψ̇) (the turn of the drum
    relative to the rope's direction pays rope out or winds it in), and the gap is a φ_i − b φ_j + (b − a) ψ − L
    plus a constant.  ψ is measured from n in the reference configuration (its ±π cut opposite to it)."""
    if c.kind == "cable":
        return c.rows(kin, c.states[0])[0].gap, ""
    if len(c.stations) != 2:
        return None, (f"rope {c.name} runs over pulleys; which of its segments takes up the slack depends on how "
                      "the pulleys turn free, which the model does not follow")
    ez = kin.F.z
    e = c.segment(kin, 0)[0]
    n = e.cross(ez)                                       # e = Ez × n
    rates = [q.diff(t) for q in coordinates]
    out = -c.length(kin, 0)
    for st, sign in zip(c.stations, (1, -1)):
        if st.signed_radius == 0:
            continue
        A, b = linear_form([kin.omega_of(st.body).dot(ez)], rates)
        coef = [sp.sympify(x) for x in A]
        if not kin.is_zero(b[0]) or any(x.has(*coordinates, t, sp.Derivative) for x in coef):
            return None, (f"the angular velocity of {st.label}, the drum of rope {c.name}, is not the rate of an "
                          "angle of the coordinates, so the rope it pays out while slack is not followed")
        out += sign * st.signed_radius * sum((x * q for x, q in zip(coef, coordinates)), sp.Integer(0))
    a, b = c.stations[0].signed_radius, c.stations[1].signed_radius
    if a != b:
        nx, ny = kin.simplify_expr(n.dot(kin.F.x)), kin.simplify_expr(n.dot(kin.F.y))
        ref = {**kin.reference_values(), t: 0}
        try:
            rx, ry = float(nx.subs(ref)), float(ny.subs(ref))
        except (TypeError, ValueError):
            rx, ry = 1.0, 0.0
        if not (np.isfinite(rx) and np.isfinite(ry)) or rx * rx + ry * ry == 0.0:
            rx, ry = 1.0, 0.0
        out += (b - a) * sp.atan2(rx * ny - ry * nx, rx * nx + ry * ny)
    return out, ""


def with_offsets(model, free: dict):
    """``model`` with the constants ℓ_s − c·q_s of its slack ropes' gaps added to their watches."""
    idx = [(i, free.get(w.name, 0.0)) for i, w in enumerate(model.watches) if w.kind == TIGHTENS]
    if not idx:
        return model
    off = np.zeros(len(model.watches))
    for i, v in idx:
        off[i] = v
    return replace(model, offsets=off)


def _gap_functions(hyb, c):
    cache = hyb.__dict__.setdefault("_slack_fns", {})
    if c.name not in cache:
        kin = hyb.kin
        gap, why = slack_gap(c, kin, hyb.layout.coordinates)
        lay = hyb.layout
        if gap is not None and not (lay.to_plain(gap).free_symbols - set(lay.parameter_symbols)):
            cache[c.name] = (f"the coordinates keep {c.kind} {c.name} at its length (its gap cannot change), so "
                             "nothing moves differently while it is slack")
        elif gap is None:
            cache[c.name] = why
        else:
            length = c.length if c.kind == "cable" else c.length(kin, 0)
            cache[c.name] = compile_functions(lay.arguments(), [lay.to_plain(e) for e in (gap, length)])
    return cache[c.name]


def open_slack(hyb, mode: dict, name: str, t_, y, p, why: str = "reaches zero") -> float:
    """Let rope or cable ``name`` go slack at the state: its gap's constant kept in ``hyb.free_lengths`` (the
    gap is zero here); returns its free length, or CannotFollow where the model cannot follow it slack."""
    c = hyb.system.constraints[name]
    fns = _gap_functions(hyb, c)
    hint = "Until then the motion is exact; a slack rope needs the ends' motions as coordinates of their own."
    if isinstance(fns, str):
        raise CannotFollow(f"the tension of {name} {why}: it goes slack, and {fns}.", where=hyb.system.name,
                           hint=hint)
    try:
        hyb.solution({**mode, name: OPEN})
    except ModeUnavailable as exc:
        raise CannotFollow(f"the tension of {name} {why}: it goes slack, and the model cannot move without it "
                           f"({exc.message.split(': ', 1)[-1]})", where=hyb.system.name, hint=hint) from None
    gap, length = (float(v) for v in fns(t_, *y[:2 * hyb.layout.n], *p))
    hyb.free_lengths[name] = -gap          # ℓ_s − c·q_s: the gap is zero where it goes slack
    return length


def pushing(hyb, mode: dict, react: dict, tol: float) -> list[tuple[float, str, str]]:
    """(tension, its name, rope) for each taut rope or cable of ``mode`` whose tension would push (< −tol)."""
    out = []
    for c in hyb.system.constraints.values():
        if c.kind in ("rope", "cable") and mode.get(c.name) != OPEN:
            out += [(react[str(T)], str(T), c.name) for T in c.reactions() if react.get(str(T), 0.0) < -tol]
    return sorted(out)


def goes_slack(hyb, model, w, t_, y, p, forced: dict) -> tuple[dict, int, list, str]:
    """The mode, regime, notes and words after rope or cable ``w.name``'s tension reached zero: the rope
    open, its gap watched from zero (its constant kept in ``hyb.free_lengths``)."""
    c = hyb.system.constraints[w.name]
    length = open_slack(hyb, model.mode, c.name, t_, y, p)
    new_mode, k, nts = hyb.settle({**model.mode, c.name: OPEN}, t_, y, p, forced=forced)
    detail = (f"the tension {w.quantity} reaches zero: {c.kind} {c.name} goes slack and the motion goes on free "
              f"of it (free length {length:.6g}")
    if c.kind == "rope" and any(st.signed_radius != 0 for st in c.stations):
        detail += "; the rope stays wound on its drum and turns with it"
    return new_mode, k, nts, detail + ")"


def tightens(hyb, model, w, t_, y, p, e_of: dict, rest_speed: float, forced: dict):
    """The mode, regime, state, notes, words and numbers after slack rope ``w.name``'s gap closed: the jerk
    (:func:`.jerk.jerk`), then taut — or still slack where it rebounds (e > 0) or would have to push."""
    mode, name = dict(model.mode), w.name
    out = jerk(hyb, mode, name, t_, y, p, restitution_of(hyb, name, e_of))
    y = out["y"]
    y[2 * hyb.layout.n] += out["energy_change"]          # the work slot: the jerk's change of kinetic energy
    words = (f"the gap of {name} closes: its ends moved apart along it at {-out['gap_rate_before']:.6g} → "
             f"{-out['gap_rate_after']:.6g}, impulse {out['impulse_name']} = {out['impulse']:.6g}, kinetic energy "
             f"change {out['energy_change']:.6g} (dissipated {out['energy_dissipated']:.6g}"
             + (f", work of the moving end {out['work_of_moving_ends']:.6g}" if out["work_of_moving_ends"] else "")
             + ")")
    taut = {k: v for k, v in mode.items() if k != name}
    if out["gap_rate_after"] > rest_speed:              # e > 0: it leaves its length again
        new_mode, k, notes = hyb.settle(mode, t_, y, p, forced=forced)
        notes.insert(0, f"{name} rebounds slack (e = {out['restitution']:g})")
    else:
        new_mode, k, notes = hyb.settle(taut, t_, y, p, forced=forced)   # slack again where it would push
    out["state"] = "slack" if new_mode.get(name) == OPEN else "taut"
    return new_mode, k, y, notes, words, out


def rope_transition(hyb, model, w, t_, y, p, e_of: dict, rest_speed: float, forced: dict):
    """(mode, regime, state, Event) after a rope's or cable's tension reaches zero (``slack``) or its slack gap
    closes (``tightens``)."""
    lay = hyb.layout
    n = lay.n
    before = lay.as_dict(y)
    numbers, name = None, w.label
    if w.kind == TIGHTENS:
        new_mode, k, y, nts, detail, out = tightens(hyb, model, w, t_, y, p, e_of, rest_speed, forced)
        if out["impulse"] > 0:
            name = f"{w.label} (jerk), impulse {out['impulse_name']} = {out['impulse']:.6g}"
        numbers = {k_: v for k_, v in out.items() if k_ != "y"}
    else:
        new_mode, k, nts, detail = goes_slack(hyb, model, w, t_, y, p, forced)
    y = np.array(y, dtype=float)
    y[:2 * n] = hyb.project_rates(new_mode, t_, y[:2 * n], p)
    y = nudge(hyb, new_mode, t_, y, p)
    after = lay.as_dict(y)
    if numbers is not None:
        numbers["velocity_jump"] = {k_: float(after[k_] - before[k_]) for k_ in before if k_.startswith("dot(")}
    detail = "; ".join([detail, *nts])
    ev = Event(name, w.kind, w.name, t_, before, after, model.description, hyb.model(new_mode, k).description,
               detail, numbers)
    return new_mode, k, y, ev


__all__ = ["TIGHTENS", "CannotFollow", "goes_slack", "open_slack", "pushing", "rope_transition", "slack_gap",
           "tightens", "with_offsets"]
