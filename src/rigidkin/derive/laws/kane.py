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

from ...base.printing import text
from ...base.trace import LazyEquations
from ..mode import ModeSetup
from .lagrange import _tidy, split
from .mechanics_model import build
from .methods import NotApplicable
from .newton_euler import BalanceEquation

t = dynamicsymbols._t

METHOD = "kane"


def _auxiliary(setup: ModeSetup, model) -> list:
    """(auxiliary speed, reaction): each reaction in evidence gets a speed of its body along the reaction."""
    out = []
    N = model.frame
    for r, row in model.evidence:
        app = row.applications[0]
        direction = app.vector / r
        ua = dynamicsymbols(f"ua_{r.name}")
        for p, body in model.points:
            if body is app.body:
                p.set_vel(N, p.vel(N) + ua * direction)
        out.append((ua, r))
    return out


def equations(setup: ModeSetup) -> list[BalanceEquation]:
    """q̇_i = u_i, and u̇_i from Kane's equations F_r + F_r* = 0 for the independent speeds."""
    if getattr(setup.system, "speed_groups", None):
        raise NotApplicable("the adapter to sympy's KanesMethod takes u = q̇, and this system's speeds are "
                            "angular-velocity components (q̇ = W(q) u, model/speeds.py).", where=setup.system.name,
                            hint="Newton–Euler resolved along the body axes gives Kane's equations in those speeds.")
    if not setup.reduction.independent:     # at rest: no speed is free, so no Kane's equation (statics)
        return []
    kin, tr = setup.kin, setup.trace
    model = build(setup, "forces", METHOD, evidence=True)
    qs = list(setup.system.coordinates)
    us = [dynamicsymbols(f"u_{q.func.__name__}") for q in qs]
    aux = _auxiliary(setup, model)
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
    if aux and u_dep:
        raise NotApplicable("a load depends on a reaction and the mode has dependent speeds; bringing the reaction "
                            "into evidence is not supported together with velocity constraints here.",
                            where=setup.system.name, hint="Euler's laws (newton-euler) handle it.")
    KM = KanesMethod(model.frame, q_ind=qs, u_ind=u_ind, kd_eqs=kd, u_dependent=u_dep or None,
                     velocity_constraints=vc or None, u_auxiliary=[ua for ua, _ in aux] or None)
    fr, frstar = KM.kanes_equations(model.bodies, model.loads)
    tr.add("Balance laws", "Kane's equations", [(e, 0) for e in (fr + frstar)],
           "F_r + F_r* = 0 for each independent generalised speed (sympy.physics.mechanics.KanesMethod).")
    solved_r = {}
    if aux:
        eqs = [sp.sympify(e) for e in KM.auxiliary_eqs]
        tr.add("Balance laws", "Auxiliary equations", [(e, 0) for e in eqs],
               "an auxiliary speed along each reaction that a load depends on ("
               + ", ".join(str(r) for _, r in aux) + "): its F_r + F_r* = 0 brings the reaction into evidence.")
        sol = sp.solve(eqs, [r for _, r in aux], dict=True)
        if len(sol) != 1:
            raise NotApplicable("the auxiliary equations do not determine the reactions in evidence.",
                                where=setup.system.name)
        solved_r = sol[0]
    n = len(qs)
    out = []
    tidy = _tidy(setup)
    if not u_dep:
        # no dependent speed: Kane's equations themselves, M(q) q̈ = f(q, q̇), one per speed
        udot = {u.diff(t): q.diff(t, 2) for q, u in zip(qs, us)}
        accels = [q.diff(t, 2) for q in qs]
        for q, e in zip(qs, fr + frstar):
            e = sp.sympify(e).xreplace(solved_r)
            e = tidy(setup.scalar(e.xreplace(udot).xreplace(back)))
            lhs, rhs = split(-e, accels)
            out.append(BalanceEquation(f"Kane's equation for the speed of {text(q)}", "system", METHOD, lhs, rhs))
        return out
    rhs = KM.rhs()
    order = list(KM.u)
    for q, u in zip(qs, us):
        if q not in ind:
            continue
        a = rhs[n + order.index(u)].xreplace(back)
        a = tidy(setup.scalar(a))
        out.append(BalanceEquation(f"Kane's equations solved for {text(q.diff(t, 2))}", "system", METHOD,
                                   a, q.diff(t, 2)))
        tr.add("Balance laws", f"Acceleration {text(q.diff(t, 2))} from Kane's equations",
               LazyEquations(lambda q=q, a=a: [(q.diff(t, 2), kin.simplify_expr(a))]),
               "mass matrix and forcing of KanesMethod solved for the independent speed rates.")
    return out
