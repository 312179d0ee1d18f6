"""The contact complementarity problem at a state: every touching contact decided together.

A contact *touches* when it is closed, or open with zero gap and zero normal speed (resting on its
surface).  For each touching contact the conditions of Signorini and Coulomb must hold together:

* normal: either closed with N ≥ 0, or open with the gap's acceleration ≥ 0 — never both N < 0
  and a gap that would shrink;
* tangential (Coulomb): either sticking with |F| ≤ µs N, or slipping with friction µk N against the
  slip, the slip growing in the direction σ chosen where it starts from zero.

A candidate mode (a state for every touching contact) is checked with the mode's own equations at
the state; a quantity that is zero there is judged a short step along the candidate's own motion
later (the side it leaves zero to).  :func:`decide` tries the candidates in a fixed order — the
proposed mode first, then every combination in declaration order, per contact ``stick`` before
``slip +`` before ``slip −`` before ``open`` — so the same state gives the same mode.  Sticking is
preferred wherever it is consistent (static friction holds while it can).  With no consistent
candidate, or with consistent candidates that disagree on which contacts are closed, the contact
problem has no solution or several (Painlevé's paradox): :class:`ContactParadox` says so, with the
critical coefficient of friction where one sliding contact makes the normal force change sign.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from ...model.constraints import ROLLING, SMOOTH, Coulomb
from ..rhs import SimulationError
from .mode_model import look_ahead
from .settle import held_alternative
from .slip3d import friction_needed, slip_speed
from .vocabulary import OPEN, SLIP, STICK, ModeUnavailable, describe_mode


class ContactParadox(SimulationError):
    """The contact problem has no solution, or several, at a state (Painlevé's paradox)."""

    def __init__(self, message, *, where=None, hint=None, stop_reason="no-consistent-mode"):
        super().__init__(message, where=where, hint=hint)
        self.stop_reason = stop_reason


@dataclass
class Decision:
    """The mode chosen, its regime, the slip directions it starts with, and every consistent mode found."""

    mode: dict
    regime: int
    forced: dict
    notes: list = field(default_factory=list)
    solutions: list = field(default_factory=list)


def touching(hyb, mode: dict, t_, y, p, zero: float) -> list[str]:
    """Contacts closed in ``mode``, and open ones resting on their surface (zero gap, zero normal speed)."""
    out = []
    for name in hyb.contacts:
        if mode[name] != OPEN:
            out.append(name)
            continue
        gap, vn, _ = hyb.contact_state(name, t_, y, p)
        if abs(gap) <= zero and abs(vn) <= zero:
            out.append(name)
    return out


def _options(hyb, name: str, t_, y, p, zero: float) -> list[tuple[str, int]]:
    """(state, slip sign) a touching contact may take, in the fixed order of preference."""
    c = hyb.contacts[name]
    opened = [(OPEN, 0)] if c.unilateral else []
    if c.friction == ROLLING:
        return [(STICK, 0), *opened]
    if c.friction == SMOOTH or not isinstance(c.friction, Coulomb):
        return [(SLIP, 0), *opened]
    if not hyb.kin.planar:          # 3D: slipping in the direction of the slip velocity, or sticking
        if slip_speed(hyb, name, t_, y, p) > zero:
            return [(SLIP, 0), *opened]
        return [(STICK, 0), *opened]
    _, _, s = hyb.contact_state(name, t_, y, p)
    if s is not None and abs(s) > zero:
        return [(SLIP, 1 if s > 0 else -1), *opened]
    return [(STICK, 0), (SLIP, 1), (SLIP, -1), *opened]


def check(hyb, mode: dict, forced: dict, names, t_, y, p, zero: float, force_tol: float = 1e-9):
    """(consistent?, regime, mode actually used, reason) of a candidate at the state."""
    try:
        sol = hyb.solution(mode)
    except ModeUnavailable as exc:
        alt = held_alternative(hyb, mode) if any(v == STICK for v in mode.values()) else None
        if alt is None:
            return False, None, mode, exc.message
        mode, sol = alt, hyb.solution(alt)
    try:
        k = hyb.regime_at(mode, t_, y, p, forced)
    except SimulationError as exc:
        return False, None, mode, exc.message
    model = hyb.model(mode, k)
    n2 = 2 * hyb.layout.n
    y = np.asarray(y, dtype=float)
    react = model.reactions(t_, y, p)
    f = model.rates(t_, y, p)[:n2]
    h, y2 = look_ahead(t_, y, f)
    react2 = model.reactions(t_ + h, y2, p)
    fscale = max(1.0, max((abs(v) for v in react.values()), default=1.0))
    scale = max(1.0, float(np.max(np.abs(y[:n2]))))
    held = tuple(getattr(sol.setup, "held", ()))
    spare = sum(float(hyb._param_value(hyb.contacts[h_].friction.static, p))
                * abs(react.get(str(hyb.contacts[h_].N), 0.0)) for h_ in held)
    for name in names:
        c, st = hyb.contacts[name], mode[name]
        if st != OPEN and c.unilateral and str(c.N) in react:
            N, pull = react[str(c.N)], -force_tol * fscale
            if pull > N or (abs(N) <= force_tol * fscale and react2[str(c.N)] < -1e-12 * fscale):
                return False, k, mode, f"the normal reaction at {name} would pull ({N:.4g})"
        if st == OPEN:
            _, vn2, _ = hyb.contact_state(name, t_ + h, y2, p)
            if vn2 < -1e-12 * scale:
                return False, k, mode, f"{name} would move into its surface (its gap's acceleration is negative)"
        F3 = friction_needed(c, react) if st == STICK and not hyb.kin.planar else None
        if st == STICK and isinstance(c.friction, Coulomb) and (str(c.F) in react or F3 is not None):
            N, F = abs(react.get(str(c.N), 0.0)), (react[str(c.F)] if F3 is None else F3)
            mu = float(hyb._param_value(c.friction.static, p))
            if abs(F) > mu * N + spare + force_tol * fscale:
                return False, k, mode, f"sticking at {name} needs |F| = {abs(F):.4g} > µs N = {mu * N:.4g}"
        if st == SLIP and name in forced and isinstance(c.friction, Coulomb):
            _, _, s0 = hyb.contact_state(name, t_, y, p)
            if s0 is not None and abs(s0) <= zero:
                _, _, s2 = hyb.contact_state(name, t_ + h, y2, p)
                if forced[name] * s2 < -1e-12 * scale:
                    return False, k, mode, f"the slip at {name} would not grow in the direction of its friction"
    return True, k, mode, ""


def decide(hyb, t_, y, p, proposal: dict | None = None, forced: dict | None = None, zero_tol: float = 1e-9,
           every: bool = False, keep: dict | None = None) -> Decision:
    """The consistent mode at a state (see the module docstring); ``every``: look for all solutions; ``keep``:
    states of constraints other than contacts that every candidate keeps (a slack rope)."""
    forced = dict(forced or {})
    base = {**(proposal or hyb.default_mode(t_, y, p)), **(keep or {})}
    scale = max(1.0, float(np.max(np.abs(np.asarray(y)[:2 * hyb.layout.n]))))
    zero = zero_tol * scale
    names = touching(hyb, base, t_, y, p, zero)
    candidates = []
    if proposal is not None:
        candidates.append((dict(proposal), dict(forced)))
    for combo in itertools.product(*[_options(hyb, n, t_, y, p, zero) for n in names]):
        mode = dict(base)
        fr = {k_: v for k_, v in forced.items() if k_ not in names}
        for n, (st, sg) in zip(names, combo):
            mode[n] = st
            if sg:
                fr[n] = sg
        candidates.append((mode, fr))
    found, reasons, seen = [], [], set()
    for mode, fr in candidates:
        key = (tuple(sorted(mode.items())), tuple(sorted(fr.items())))
        if key in seen:
            continue
        seen.add(key)
        ok, k, used, why = check(hyb, mode, fr, names, t_, y, p, zero)
        if ok:
            found.append(Decision(used, k, fr))
            if not every:
                break
        else:
            reasons.append(f"{describe_mode(hyb.system, mode)}: {why}")
    if not found:
        crit = critical_mu(hyb, base, names, t_, y, p)
        raise ContactParadox(
            f"at t = {t_:.10g} the contact problem has no solution: no combination of closed, open, sticking and "
            f"slipping contacts is consistent ({'; '.join(reasons)})." + (f" {crit}" if crit else ""),
            where=hyb.system.name,
            hint="Painlevé's paradox: with this much friction a sliding contact would need a pulling normal force. "
                 "Coulomb's law and rigid bodies have no answer here (an impact without collision, or compliance).")
    first = found[0]
    closed = {n: first.mode[n] != OPEN for n in names}
    other = [d for d in found[1:] if any((d.mode[n] != OPEN) != closed[n] for n in names)]
    if other:
        crit = critical_mu(hyb, base, names, t_, y, p)
        raise ContactParadox(
            f"at t = {t_:.10g} the contact problem has {1 + len(other)} solutions that disagree on which contacts "
            f"stay closed: {describe_mode(hyb.system, first.mode)}; "
            + "; ".join(describe_mode(hyb.system, d.mode) for d in other) + "." + (f" {crit}" if crit else ""),
            where=hyb.system.name, stop_reason="ambiguous",
            hint="Painlevé's paradox (non-uniqueness): rigid bodies with Coulomb friction do not say which one "
                 "happens; the simulation does not guess.")
    first.solutions = [d.mode for d in found]
    return first


def critical_mu(hyb, mode: dict, names, t_, y, p) -> str:
    """For a contact sliding with a coefficient given by a parameter: the µ at which its normal force would
    change sign through infinity (1/N is linear in µ), stated as the condition for a solution."""
    lay = hyb.layout
    for name in names:
        c = hyb.contacts[name]
        if not isinstance(c.friction, Coulomb) or not hyb.kin.planar:
            continue
        mu = sp.sympify(c.friction.kinetic)
        if mu not in lay.parameter_symbols:
            continue
        _, _, s = hyb.contact_state(name, t_, y, p)
        if s is None or s == 0:
            continue
        trial = {**mode, name: SLIP}
        try:
            i = lay.parameter_symbols.index(mu)
            inv = []
            for val in (0.0, float(p[i])):
                pp = np.array(p, dtype=float)
                pp[i] = val
                k = hyb.regime_at(trial, t_, y, pp, {name: 1 if s > 0 else -1})
                inv.append(1.0 / hyb.model(trial, k).reactions(t_, y, pp)[str(c.N)])
        except (ModeUnavailable, SimulationError, ZeroDivisionError, KeyError):
            continue
        if inv[1] == inv[0] or p[i] == 0:
            continue
        star = -inv[0] * float(p[i]) / (inv[1] - inv[0])
        if star > 0:
            return (f"The critical coefficient of friction at {name} is µ* = {star:.6g} here: sliding with the contact "
                    f"closed, its normal force changes sign through infinity at µ*, and the contact problem has "
                    f"exactly one solution for µ < µ* (with µ = {float(p[i]):.6g} the normal force N would be "
                    f"{1.0 / inv[1]:.4g}).")
    return ""


def confirm(hyb, model, t_, y, p) -> tuple[dict, int, str]:
    """After an event: the mode the transition chose, checked as a whole against the contact problem over
    every touching contact; if it fails, the first consistent candidate in the fixed order (or
    :class:`ContactParadox`).  Returns (mode, regime, a note when the choice changed)."""
    mode, k = dict(model.mode), model.regime_index
    scale = max(1.0, float(np.max(np.abs(np.asarray(y)[:2 * hyb.layout.n]))))
    zero = 1e-9 * scale
    names = touching(hyb, mode, t_, y, p, zero)
    forced = {}
    for sc in model.solution.setup.sign_choices:
        if sc.load in hyb.contacts and sc.symbol in model.regime.signs:
            forced[sc.load] = int(model.regime.signs[sc.symbol])
    ok, _, _, why = check(hyb, mode, forced, names, t_, y, p, zero)
    if ok:
        return mode, k, ""
    dec = decide(hyb, t_, y, p, None, {k_: v for k_, v in forced.items() if k_ not in names},
                 keep={k_: v for k_, v in mode.items() if k_ not in hyb.contacts})
    return dec.mode, dec.regime, (f"the contact problem over {', '.join(names)} rejects "
                                  f"{describe_mode(hyb.system, mode)} ({why}); {describe_mode(hyb.system, dec.mode)}")
