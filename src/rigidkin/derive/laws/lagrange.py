"""Lagrange's equations by ``sympy.physics.mechanics.LagrangesMethod``, built from the same model.

L = T − U with T from the bodies (``RigidBody``) and U from the conservative loads' potentials; the
other loads enter as generalised forces through the velocities of the points where they act.  All the
coordinates of the system are kept; the constraints that relate them are passed as holonomic
constraints (a gap whose rate is the constraint's velocity row) or non-holonomic ones, so the
multipliers λ and the dependent accelerations come out of the mechanics tools, not out of rigidkin's
reduction.  The result is the normal form q̈_i = f_i(q, q̇) of the independent coordinates.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.mechanics import LagrangesMethod, Lagrangian
from sympy.physics.vector import dynamicsymbols

from ...base.printing import text
from ...base.trace import LazyEquations
from ..mode import ModeSetup
from .mechanics_model import build
from .methods import NotApplicable
from .newton_euler import BalanceEquation

t = dynamicsymbols._t

METHOD = "lagrange"


def equations(setup: ModeSetup) -> list[BalanceEquation]:
    """q̈_i = f_i for each independent coordinate, from LagrangesMethod with multipliers."""
    if getattr(setup.system, "speed_groups", None):
        raise NotApplicable("Lagrange's equations hold for coordinates, and this system's speeds are angular-velocity "
                            "components (quasi-coordinates, model/speeds.py), which are no coordinate's rate.",
                            where=setup.system.name, hint="Newton–Euler and the laws about a point apply.")
    kin, tr = setup.kin, setup.trace
    model = build(setup, "potential", METHOD)
    qs = list(setup.system.coordinates)
    L = Lagrangian(model.frame, *model.bodies) - model.potential if model.bodies else -model.potential
    tr.add("Balance laws", "Lagrangian", LazyEquations(lambda: [(sp.Symbol("L"), kin.simplify_expr(L))]),
           "L = T − U over all the coordinates " + ", ".join(text(q) for q in qs) + " (none eliminated).")
    if model.holonomic or model.nonholonomic:
        tr.add("Balance laws", "Constraints for Lagrange's equations",
               [(g, 0) for g in model.holonomic] + [(v, 0) for v in model.nonholonomic],
               "holonomic constraints (gaps) and rate constraints, each with a multiplier λ.")
    LM = LagrangesMethod(L, qs, forcelist=model.loads or None, frame=model.frame,
                         hol_coneqs=model.holonomic or None, nonhol_coneqs=model.nonholonomic or None)
    eom = LM.form_lagranges_equations()
    tr.add("Balance laws", "Lagrange's equations", [(e, 0) for e in eom],
           "d/dt(∂L/∂q̇) − ∂L/∂q = Q_q + Σ λ a_q for every coordinate (sympy.physics.mechanics.LagrangesMethod).")
    n = len(qs)
    out = []
    tidy = _tidy(setup)
    if not (model.holonomic or model.nonholonomic):
        # no constraint relates the rates: the equations themselves, M q̈ = f, one per coordinate
        for q, e in zip(qs, eom):
            e = tidy(setup.scalar(e))
            lhs, rhs = split(e, [c.diff(t, 2) for c in qs])
            out.append(BalanceEquation(f"Lagrange's equation for {text(q)}", "system", METHOD, lhs, rhs))
        return out
    rhs = LM.rhs()
    for q in setup.reduction.independent:
        a = rhs[n + qs.index(q)]
        a = tidy(setup.scalar(a))
        out.append(BalanceEquation(f"Lagrange's equations solved for {text(q.diff(t, 2))}", "system", METHOD,
                                   a, q.diff(t, 2)))
        tr.add("Balance laws", f"Acceleration {text(q.diff(t, 2))} from Lagrange's equations",
               LazyEquations(lambda q=q, a=a: [(q.diff(t, 2), kin.simplify_expr(a))]),
               "Lagrange's equations and the differentiated constraints solved for the accelerations and "
               "multipliers, at a state that satisfies the constraints.")
    return out


def _tidy(setup: ModeSetup):
    """Simplification of a law's equations as they are formed: for up to two degrees of freedom (their
    accelerations are compared symbolically where small); above, the equations are compared numerically
    from M and f as derived, and simplified for reading only when the trace is read."""
    if len(setup.reduction.independent) <= 2:
        return setup.kin.simplify_expr
    return lambda e: e


def split(e, accels) -> tuple:
    """``e = 0`` as (other terms, inertia terms): the terms with an acceleration go to the right side."""
    e = sp.expand(e)
    inertia = sp.Add(*[a for a in sp.Add.make_args(e) if a.has(*accels)])
    return sp.factor_terms(inertia - e), sp.factor_terms(inertia)
