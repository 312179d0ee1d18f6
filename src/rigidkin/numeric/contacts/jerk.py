"""A slack rope or cable that re-tightens: the jerk, by impulse–momentum.

When a slack rope's gap closes (:mod:`.slack`) the ends move apart along it at the speed v⁻ (the rate of
its row, v_row = L̇ − ℓ̇); an inextensible rope stops that with an impulse Λ ≥ 0 along itself (it can only
pull), in the rates u of the slack mode with M their mass matrix:

    M (u⁺ − u⁻) = Jᵀ Λ,   g⁺ = −e g⁻,   Λ ≥ 0,

where g = J u + b = −v_row is the gap's rate (the rope's row as a contact's normal row: the tension's power
is −T v_row) and e the rope's coefficient of restitution (0 by default: it jerks taut and stays so;
``System.restitution``).  It is the impulse problem of an impact (:func:`contact_lcp.impulse_problem`) with
one smooth row.  The kinetic energy the jerk dissipates is ½ Λ (1 − e)(−g⁻) ≥ 0; where an end moves by a
law (a hand, b ≠ 0) that end does the work −Λ b too, so the kinetic energy may grow by that much.
"""

from __future__ import annotations

import numpy as np
from sympy.physics.vector import dynamicsymbols

from ...base.linear import linear_form
from ...model.constraints import Coulomb
from ..rhs import SimulationError, compile_functions
from .contact_lcp import ContactRows, impulse_problem
from .vocabulary import OPEN, SLIP

t = dynamicsymbols._t


def _functions(hyb, mode: dict, name: str):
    cache = hyb.__dict__.setdefault("_jerk_fns", {})
    key = (tuple(sorted(mode.items())), name)
    if key not in cache:
        c = hyb.system.constraints[name]
        sol = hyb.solution(mode)
        setup = sol.setup
        rates = [q.diff(t) for q in sol.coordinates]
        row = c.rows(setup.kin, c.states[0])[0]
        A, b = linear_form([-setup.scalar(row.velocity)], rates)        # the gap's rate g = J u + b
        M = sol.regime(0).mass_matrix
        lay = hyb.layout
        fn = compile_functions(lay.arguments(), [lay.to_plain(e) for e in (*M, *A, *b)])
        cache[key] = (fn, len(rates), [lay.coordinates.index(q) for q in sol.coordinates], str(row.reaction))
    return cache[key]


def restitution_of(hyb, name: str, e_of: dict) -> float:
    """The rope's coefficient of restitution: given to the simulation, else declared (System.restitution), else 0."""
    return float(e_of.get(name, hyb.system.restitutions.get(name, 0.0)))


def jerk(hyb, mode: dict, name: str, t_: float, y: np.ndarray, p, e: float) -> dict:
    """The state just after slack rope ``name`` (open in ``mode``) re-tightens, and the jerk's numbers."""
    closed = [n for n, c in hyb.contacts.items() if mode[n] != OPEN
              and (c.unilateral or (mode[n] == SLIP and isinstance(c.friction, Coulomb)))]
    if closed:
        err = SimulationError(f"{name} re-tightens while {', '.join(closed)} touches its surface: a jerk together "
                              "with contact impulses is not modelled.", where=hyb.system.name,
                              hint="Until then the motion is exact.")
        err.stop_reason = "jerk-with-contacts"
        raise err
    lay = hyb.layout
    fn, n, slots, tension = _functions(hyb, mode, name)
    vals = np.asarray([float(v) for v in fn(t_, *y[:2 * lay.n], *p)])
    M, J, b = vals[:n * n].reshape(n, n), vals[n * n:n * n + n], float(vals[-1])
    u0 = np.array([y[lay.n + s] for s in slots])
    try:
        res = impulse_problem(M, u0, [ContactRows(name, J, b, restitution=e, labels=(tension,))])
    except np.linalg.LinAlgError:
        raise SimulationError(f"at t = {t_:.10g} the jerk of {name} cannot be resolved: the mass matrix is "
                              "singular here.", where=hyb.system.name) from None
    y1 = np.array(y, dtype=float)
    for s, v in zip(slots, res.u):
        y1[lay.n + s] = v
    y1[:2 * lay.n] = hyb.project_rates(mode, t_, y1[:2 * lay.n], p)
    model = hyb.model(mode, 0)
    dT = model.energy(t_, y1, p)[0] - model.energy(t_, y, p)[0]
    impulse = float(res.normal[name])
    g0, g1 = float(J @ u0 + b), float(res.normal_after[name])
    lost = -0.5 * impulse * (g1 + g0)            # ½ Λ (1 − e)(−g⁻) ≥ 0
    work = -impulse * b                          # of an end that moves by a law
    scale = max(1.0, abs(model.energy(t_, y, p)[0]))
    if lost < -1e-9 * scale or dT > work + 1e-9 * scale:
        raise SimulationError(f"at t = {t_:.10g} the jerk of {name} would create kinetic energy "
                              f"({dT:.3g} with {work:.3g} done by the moving ends); it is not resolved.",
                              where=hyb.system.name)
    return {"y": y1, "impulse": impulse, "impulse_name": tension, "gap_rate_before": g0, "gap_rate_after": g1,
            "energy_change": float(dT), "energy_dissipated": float(lost), "work_of_moving_ends": float(work),
            "restitution": float(e)}


__all__ = ["jerk", "restitution_of"]
