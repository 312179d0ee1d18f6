"""Impact: a contact reaches its surface; one impulse problem over every contact closed or closing.

During the impact the configuration q does not change and every finite force is negligible; the
rates jump.  Every contact that touches its surface at that instant takes part: the one that
strikes, any other that strikes at the same instant (a rod falling flat onto two supports), and
every unilateral contact already closed (a rod's foot on a rough floor when its other end lands):
each may take a normal impulse and, if rough, a friction impulse.  They are solved together
(:func:`contact_lcp.impulse_problem`) in the rates of the mode in which all of them are open,
with Newton's law of restitution on each contact's normal velocity (v_n⁺ = −e v_n⁻ where it takes
an impulse) and Coulomb's law for the friction impulse (sticking within µs Λ_n, else sliding with
µk Λ_n against the slip it leaves with).  The kinetic energy after the impact is checked never to
exceed the energy before; where Newton's law with friction would create energy the impact is
resolved as plastic (e = 0) and the event says so.  A contact the model cannot open (no
coordinate lets it separate: a ladder's foot on the floor) is *held*: it keeps its constraint, and its
normal and friction impulses come from every body's unreduced impulse–momentum equations
(``derive.laws.impulse.unreduced_equations``), as its reaction does in ``solve``.  In 3D a rough
contact's friction impulse lies in Coulomb's cone (``contact_lcp``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from sympy.physics.vector import dynamicsymbols

from ...derive.kinematics import linear_form
from ...derive.laws.impulse import unreduced_equations
from ...model.constraints import ROLLING, SMOOTH, Coulomb
from ..rhs import SimulationError, compile_functions
from .contact_lcp import ContactRows, NoImpulseSolution, impulse_problem
from .modes import Hybrid
from .vocabulary import OPEN, SLIP, STICK, ModeUnavailable, describe_mode, mode_key

t = dynamicsymbols._t


@dataclass(frozen=True)
class ImpactOutcome:
    """The state just after an impact, the impulses (normal first) and the speeds along the normal."""

    y: np.ndarray
    impulses: dict
    approach_speed: float       # normal speed of the striking contact point before (< 0: approaching)
    separation_speed: float     # after (≥ 0)
    energy_change: float        # T⁺ − T⁻ (≤ 0, checked)
    contacts: tuple = ()        # every contact that took part
    normal_after: dict = field(default_factory=dict)    # v_n⁺ per contact
    slip_after: dict = field(default_factory=dict)      # v_t⁺ per rough contact
    states: dict = field(default_factory=dict)          # stick / slide± / inactive per contact
    plastic: bool = False       # Newton's law would have created energy: resolved with e = 0
    solutions: int = 1          # how many solutions the impulse problem has (1: unique)
    indeterminate: tuple = ()   # impulses the impact does not determine (how they split is a choice)
    held: tuple = ()            # contacts the coordinates keep closed (impulses from every body's equations)
    impulse_names: tuple = ()   # (normal, tangential or None, further...) reaction names per contact


def _rough(c, planar: bool) -> bool:
    return c.friction == ROLLING or isinstance(c.friction, Coulomb)


def _impact_mode(hybrid: Hybrid, mode: dict, taking_part: list[str]):
    """The mode in which the contacts taking part are open, where the model can open them: a contact
    whose normal the coordinates keep (a ladder's foot on the floor) stays closed and is *held*."""
    trial = {**mode, **{n: OPEN for n in taking_part}}
    try:
        hybrid.solution(trial)
        return trial, list(taking_part)
    except ModeUnavailable:
        pass
    trial = {**mode, **{n: OPEN for n in taking_part if mode[n] == OPEN}}
    hybrid.solution(trial)                  # ModeUnavailable propagates with the model's reason
    for n in taking_part:                   # in declaration order: open each one the model can open
        if trial[n] != OPEN:
            try:
                hybrid.solution({**trial, n: OPEN})
                trial = {**trial, n: OPEN}
            except ModeUnavailable:
                pass
    return trial, list(taking_part)


def _functions(hybrid: Hybrid, imode: dict, names: tuple):
    cache = hybrid.__dict__.setdefault("_impact_fns", {})
    key = (mode_key(imode), names)
    if key not in cache:
        sol = hybrid.solution(imode)
        setup = sol.setup
        rates = [q.diff(t) for q in sol.coordinates]
        exprs, shape, contact_rows = [], [], []
        for name in names:
            c = hybrid.contacts[name]
            rows = c.rows(setup.kin, STICK if _rough(c, setup.kin.planar) else SLIP)
            A, b = linear_form([setup.scalar(r.velocity) for r in rows], rates)
            exprs.extend([*A, *b])
            shape.append((len(rows), str(rows[0].reaction), str(rows[1].reaction) if len(rows) > 1 else None,
                          tuple(str(r.reaction) for r in rows[2:])))
            contact_rows.append(rows)
        M = sol.regime(0).mass_matrix
        held = [n for n in names if imode[n] != OPEN]
        unreduced = None
        if held:             # the held contacts' impulses: from every body's impulse–momentum equations
            E, R, C, rlabels = unreduced_equations(setup, rates, set(names), contact_rows)
            unreduced = (E.shape, R.shape, [len(r) for r in contact_rows], rlabels)
            exprs.extend([*E, *R, *C])
        lay = hybrid.layout
        fn = compile_functions(lay.arguments(), [lay.to_plain(e) for e in (*M, *exprs)])
        slots = [lay.coordinates.index(q) for q in sol.coordinates]
        cache[key] = (fn, len(rates), shape, slots, unreduced)
    return cache[key]


def impact(hybrid: Hybrid, mode: dict, contact: str, t_: float, y: np.ndarray, p, restitution: dict,
           regime: int = 0, gap_tol: float = 1e-9) -> ImpactOutcome:
    """Rates just after ``contact`` (open in ``mode``) strikes its surface; ``restitution``: e per contact."""
    lay = hybrid.layout
    y = np.asarray(y, dtype=float)
    scale = max(1.0, float(np.max(np.abs(y[:2 * lay.n]))))
    taking_part = []
    for name, c in hybrid.contacts.items():
        if name == contact or (mode[name] != OPEN and c.unilateral):
            taking_part.append(name)
        elif mode[name] == OPEN:
            gap, vn, _ = hybrid.contact_state(name, t_, y, p)
            if abs(gap) <= gap_tol * scale and vn < 0:
                taking_part.append(name)           # strikes at the same instant
    imode, names = _impact_mode(hybrid, mode, taking_part)
    fn, n, shape, slots, unreduced = _functions(hybrid, imode, tuple(names))
    vals = np.asarray([float(v) for v in fn(t_, *y[:2 * lay.n], *p)])
    M = vals[:n * n].reshape(n, n)
    k = n * n
    blocks = []
    for m, *_ in shape:
        blocks.append((vals[k:k + m * n].reshape(m, n), vals[k + m * n:k + m * n + m]))
        k += m * n + m
    momentum = bilateral = None
    cols = [None] * len(names)
    if unreduced is not None:
        (ke, _), (_, mr), sizes, rlabels = unreduced
        momentum = vals[k:k + ke * n].reshape(ke, n)
        k += ke * n
        bilateral = (vals[k:k + ke * mr].reshape(ke, mr), rlabels)
        k += ke * mr
        C = vals[k:k + ke * sum(sizes)].reshape(ke, sum(sizes))
        j = 0
        for i, m in enumerate(sizes):
            cols[i] = [C[:, j + r] for r in range(m)]
            j += m
    rows = []
    for i, (name, (m, nn, ft, more), (A, b)) in enumerate(zip(names, shape, blocks)):
        c = hybrid.contacts[name]
        mu_s = mu_k = 0.0
        if isinstance(c.friction, Coulomb) and m > 1:
            mu_s, mu_k = hybrid._param_value(c.friction.static, p), hybrid._param_value(c.friction.kinetic, p)
        col = cols[i] or [None, None]
        rows.append(ContactRows(name, A[0], float(b[0]), A[1] if m > 1 else None, float(b[1]) if m > 1 else 0.0,
                                mu_s, mu_k, c.friction == ROLLING, float(restitution.get(name, 0.0)),
                                tuple((A[r], float(b[r])) for r in range(2, m)),
                                col[0], col[1] if m > 1 else None, tuple(col[2:]), imode[name] != OPEN,
                                (nn, ft, *more)))
    u0 = np.array([y[lay.n + s] for s in slots])
    model = hybrid.model(imode, 0)
    T0, _ = model.energy(t_, y, p)

    def solve(plastic: bool):
        try:
            res = impulse_problem(M, u0, rows, plastic=plastic, momentum=momentum, bilateral=bilateral)
        except NoImpulseSolution:
            raise SimulationError(f"at t = {t_:.10g} no impulses at {', '.join(names)} satisfy Newton's law of "
                                  "restitution and Coulomb's law for impulses together (an impact paradox).",
                                  where=hybrid.system.name,
                                  hint="The friction coefficient may be too large for this configuration.") from None
        except np.linalg.LinAlgError:
            raise SimulationError(f"at t = {t_:.10g} the impact at {', '.join(names)} cannot be resolved: the "
                                  "mass matrix is singular here.", where=hybrid.system.name) from None
        y1 = np.array(y, dtype=float)
        for s, v in zip(slots, res.u):
            y1[lay.n + s] = v
        y1 = hybrid.project_rates(imode, t_, y1, p)
        return res, y1, model.energy(t_, y1, p)[0] - T0

    res, y_after, dT = solve(False)
    plastic = False
    if dT > 1e-12 * max(1.0, abs(T0)) and any(r.restitution > 0 for r in rows):
        res, y_after, dT = solve(True)          # Newton's law with friction would create energy
        plastic = True
    if dT > 1e-12 * max(1.0, abs(T0)):
        raise SimulationError(f"at t = {t_:.10g} the impact at {', '.join(names)} would increase the kinetic "
                              f"energy by {dT:.3g}; it is not resolved.", where=hybrid.system.name)
    impulses = {}
    for name, (_m, nn, ft, more) in zip(names, shape):
        impulses[nn] = res.normal[name]
        if ft is not None:
            impulses[ft] = res.tangential[name]
        for k_, v in zip(more, res.further.get(name, ())):
            impulses[k_] = v
    gap, vn0, _ = hybrid.contact_state(contact, t_, y, p)
    return ImpactOutcome(y_after, impulses, float(vn0), float(res.normal_after[contact]), float(dT),
                         tuple(names), dict(res.normal_after), dict(res.slip_after), dict(res.states), plastic,
                         res.count, res.indeterminate, tuple(n_ for n_ in names if imode[n_] != OPEN),
                         tuple((nn, ft, *more) for _m, nn, ft, more in shape))


def impact_numbers(out: ImpactOutcome, before: dict, after: dict) -> dict:
    """An impact as plain numbers (for JSON): per contact its normal and tangential impulse, its state
    and its normal speed after; the jump of every rate; the change of kinetic energy."""
    per = {}
    for c, (nn, ft, *more) in zip(out.contacts, out.impulse_names):
        d = {"state": out.states.get(c, ""), "normal_impulse": float(out.impulses.get(nn, 0.0)),
             "normal_impulse_name": nn, "tangential_impulse": float(out.impulses.get(ft, 0.0)) if ft else 0.0,
             "normal_speed_after": float(out.normal_after.get(c, 0.0))}
        if ft is not None:
            d["tangential_impulse_name"] = ft
        if more:            # 3D: the friction impulse along each tangent of the contact's basis
            d["tangential_impulses"] = [float(out.impulses.get(k, 0.0)) for k in (ft, *more)]
        if c in out.slip_after:
            d["slip_speed_after"] = float(out.slip_after[c])
        per[c] = d
    return {"contacts": per,
            "velocity_jump": {k: float(after[k] - before[k]) for k in before if k.startswith("dot(")},
            "energy_change": float(out.energy_change), "approach_speed": float(out.approach_speed),
            "separation_speed": float(out.separation_speed), "plastic": bool(out.plastic),
            "solutions": int(out.solutions), "indeterminate": list(out.indeterminate), "held": list(out.held)}


def mode_after(hybrid: Hybrid, mode: dict, out: ImpactOutcome, rest_speed: float) -> tuple[dict, dict, list[str]]:
    """The candidate mode after an impact and the slip directions it starts with: a contact that leaves
    faster than ``rest_speed`` is open, the others closed (sticking where they leave without slip)."""
    cand, forced, notes = dict(mode), {}, []
    for name in out.contacts:
        c = hybrid.contacts[name]
        if out.normal_after[name] > rest_speed:
            cand[name] = OPEN
            if mode[name] != OPEN:
                notes.append(f"{name} leaves its surface")
            continue
        if c.friction == ROLLING:
            cand[name] = STICK
        elif c.friction == SMOOTH or not isinstance(c.friction, Coulomb) or name not in out.slip_after:
            cand[name] = SLIP
        elif out.states.get(name) == "stick":
            cand[name] = STICK
        else:
            cand[name] = SLIP
            if hybrid.kin.planar:       # in 3D the slip direction is taken from the state (slip3d)
                forced[name] = 1 if out.slip_after[name] > 0 else -1
    return cand, forced, notes


__all__ = ["ImpactOutcome", "impact", "mode_after", "describe_mode"]
