"""Kane's equations by ``sympy.physics.mechanics.KanesMethod``, built from the same model.

Generalised speeds u_j = q̇_j for every coordinate; the speeds of the coordinates that the mode makes
dependent are declared ``u_dependent`` and the constraint rows that relate the rates are handed to
KanesMethod as velocity constraints, so the elimination of the dependent speeds (and the partial
velocities that make workless reactions drop out) is done by the mechanics tools.  Every load,
gravity and springs included, enters as a force or torque.  The result is the normal form
q̈_i = f_i(q, q̇) of the independent coordinates.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.mechanics import KanesMethod
from sympy.physics.vector import dynamicsymbols

from ..mode import ModeSetup
from ..printing import text
from .mechanics_model import build
from .newton_euler import BalanceEquation

t = dynamicsymbols._t

METHOD = "kane"


def equations(setup: ModeSetup) -> list[BalanceEquation]:
    """q̇_i = u_i, and u̇_i from Kane's equations F_r + F_r* = 0 for the independent speeds."""
    kin, tr = setup.kin, setup.trace
    model = build(setup, "forces", METHOD)
    qs = list(setup.system.coordinates)
    us = [dynamicsymbols(f"u_{q.func.__name__}") for q in qs]
    to_u = {q.diff(t): u for q, u in zip(qs, us)}
    back = {u: q.diff(t) for q, u in zip(qs, us)}
    ind = set(setup.reduction.independent)
    u_ind = [u for q, u in zip(qs, us) if q in ind]
    u_dep = [u for q, u in zip(qs, us) if q not in ind]
    vc = [sp.sympify(r.velocity).xreplace(to_u) for r in model.rows]
    if len(vc) != len(u_dep):
        vc = vc[:len(u_dep)] if len(vc) > len(u_dep) else vc
    kd = [q.diff(t) - u for q, u in zip(qs, us)]
    tr.add("Balance laws", "Generalised speeds", [(q.diff(t), u) for q, u in zip(qs, us)],
           "one speed per coordinate; " + (f"dependent speeds {', '.join(map(text, u_dep))} are fixed by the "
                                           "velocity constraints." if u_dep else "all independent."))
    if vc:
        tr.add("Balance laws", "Velocity constraints", [(v, 0) for v in vc],
               "handed to KanesMethod, which eliminates the dependent speeds.")
    KM = KanesMethod(model.frame, q_ind=qs, u_ind=u_ind, kd_eqs=kd, u_dependent=u_dep or None,
                     velocity_constraints=vc or None)
    fr, frstar = KM.kanes_equations(model.bodies, model.loads)
    tr.add("Balance laws", "Kane's equations", [(e, 0) for e in (fr + frstar)],
           "F_r + F_r* = 0 for each independent generalised speed (sympy.physics.mechanics.KanesMethod).")
    n = len(qs)
    out = []
    if not u_dep:
        # no dependent speed: Kane's equations themselves, M(q) q̈ = f(q, q̇), one per speed
        from .lagrange import split

        udot = {u.diff(t): q.diff(t, 2) for q, u in zip(qs, us)}
        accels = [q.diff(t, 2) for q in qs]
        for q, e in zip(qs, fr + frstar):
            e = kin.simplify_expr(setup.scalar(sp.sympify(e).xreplace(udot).xreplace(back)))
            lhs, rhs = split(-e, accels)
            out.append(BalanceEquation(f"Kane's equation for the speed of {text(q)}", "system", METHOD, lhs, rhs))
        return out
    rhs = KM.rhs()
    order = list(KM.u)
    for q, u in zip(qs, us):
        if q not in ind:
            continue
        a = rhs[n + order.index(u)].xreplace(back)
        a = kin.simplify_expr(setup.scalar(a))
        out.append(BalanceEquation(f"Kane's equations solved for {text(q.diff(t, 2))}", "system", METHOD,
                                   a, q.diff(t, 2)))
        tr.add("Balance laws", f"Acceleration {text(q.diff(t, 2))} from Kane's equations", [(q.diff(t, 2), a)],
               "mass matrix and forcing of KanesMethod solved for the independent speed rates.")
    return out
