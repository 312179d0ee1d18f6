"""Impact: a separated point reaches the surface again; impulse–momentum at the instant.

During the impact the configuration q does not change and every finite force is negligible; the
rates jump.  With M the mass matrix of the mode in which the contact is open (independent rates u)
and J, b the contact's constraint rows (normal speed v_n = J_n u + b_n, and for a rolling contact
the tangential slip speed too):

    M (u⁺ − u⁻) = Jᵀ Λ           (the impulse Λ acts along the constraint rows)
    J_n u⁺ + b_n = −e (J_n u⁻ + b_n)   (Newton's coefficient of restitution e)
    J_t u⁺ + b_t = 0              (rolling contact: no slip after the impact)

so Λ = (J M⁻¹ Jᵀ)⁻¹ (v_target − v⁻) and u⁺ = u⁻ + M⁻¹ Jᵀ Λ.  A smooth contact takes a normal
impulse only.  A Coulomb contact (planar) sticks if the tangential impulse that stops the slip is
within µ times the normal one; otherwise it slides through the impact with the tangential impulse
−σ µ Λ_n opposing the slip σ it arrived with (Λ_n from the restitution condition along the
direction J_nᵀ − σ µ J_tᵀ).  The dependent rates follow from the mode's rate relations; the
kinetic energy lost is reported.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from sympy.physics.vector import dynamicsymbols

from ..kinematics import linear_form
from ..model.constraints import ROLLING, Coulomb
from .modes import SLIP, STICK, Hybrid, mode_key
from .rhs import SimulationError, compile_functions

t = dynamicsymbols._t


@dataclass(frozen=True)
class ImpactOutcome:
    """The state just after an impact, the impulses (normal first) and the speeds along the normal."""

    y: np.ndarray
    impulses: dict
    approach_speed: float       # normal speed of the contact point before (< 0: approaching)
    separation_speed: float     # after (≥ 0)
    energy_change: float        # T⁺ − T⁻ (≤ 0 for e ≤ 1)


def _impact_functions(hybrid: Hybrid, mode: dict, contact: str):
    cache = hybrid.__dict__.setdefault("_impact_fns", {})
    key = (mode_key(mode), contact)
    if key not in cache:
        sol = hybrid.solution(mode)
        setup = sol.setup
        c = hybrid.contacts[contact]
        rough = c.friction == ROLLING or (isinstance(c.friction, Coulomb) and setup.kin.planar)
        rows = c.rows(setup.kin, STICK if rough else SLIP)
        rates = [q.diff(t) for q in sol.coordinates]
        A, b = linear_form([setup.scalar(r.velocity) for r in rows], rates)
        M = sol.regime(0).mass_matrix
        lay = hybrid.layout
        exprs = [lay.to_plain(e) for e in (*M, *A, *b)]
        fn = compile_functions(lay.arguments(), exprs)
        slots = [lay.coordinates.index(q) for q in sol.coordinates]
        cache[key] = (fn, len(rates), len(rows), slots, [str(r.reaction) for r in rows])
    return cache[key]


def impact(hybrid: Hybrid, mode: dict, contact: str, t_: float, y: np.ndarray, p, restitution: float,
           regime: int = 0) -> ImpactOutcome:
    """Rates just after ``contact`` (open in ``mode``) strikes its surface with restitution ``restitution``."""
    fn, n, m, slots, names = _impact_functions(hybrid, mode, contact)
    lay = hybrid.layout
    vals = np.asarray([float(v) for v in fn(t_, *y[:2 * lay.n], *p)])
    M = vals[:n * n].reshape(n, n)
    J = vals[n * n:n * n + m * n].reshape(m, n)
    b = vals[n * n + m * n:]
    u = np.array([y[lay.n + s] for s in slots])
    v_before = J @ u + b
    target = np.zeros(m)
    target[0] = -restitution * v_before[0]
    try:
        Minv_Jt = np.linalg.solve(M, J.T)
        Lam = np.linalg.solve(J @ Minv_Jt, target - v_before)
        u_after = u + Minv_Jt @ Lam
        c = hybrid.contacts[contact]
        if isinstance(c.friction, Coulomb) and m == 2:
            mu = hybrid._param_value(c.friction.mu, p)
            if abs(Lam[1]) > mu * abs(Lam[0]):            # cannot stop the slip: it slides through the impact
                sigma = 1.0 if v_before[1] > 0 else -1.0
                d = J[0] - sigma * mu * J[1]
                Minv_d = np.linalg.solve(M, d)
                lam_n = (target[0] - v_before[0]) / float(J[0] @ Minv_d)
                Lam = np.array([lam_n, -sigma * mu * lam_n])
                u_after = u + Minv_d * lam_n
    except np.linalg.LinAlgError:
        raise SimulationError(f"at t = {t_:.10g} the impact at {contact} cannot be resolved: the mass matrix "
                              "or the contact's constraint rows are singular here.", where=hybrid.system.name) from None
    y_after = np.array(y, dtype=float)
    for s, v in zip(slots, u_after):
        y_after[lay.n + s] = v
    y_after = hybrid.project_rates(mode, t_, y_after, p)
    model = hybrid.model(mode, regime)
    T0, _ = model.energy(t_, np.asarray(y, dtype=float), p)
    T1, _ = model.energy(t_, y_after, p)
    v_after = J @ u_after + b
    return ImpactOutcome(y_after, dict(zip(names, map(float, Lam))), float(v_before[0]), float(v_after[0]),
                         T1 - T0)
