"""A Solution from equations of motion that are already free of reactions (energy, Lagrange, Kane).

Such a law gives as many equations as there are independent coordinates, linear in the independent
accelerations q̈_i.  They are solved for q̈_i regime by regime (the sign choices of sliding friction);
the reactions, which these laws eliminate, and the regime and validity conditions come from Euler's
laws for the same mode (the trace says so).
"""

from __future__ import annotations

from types import MappingProxyType

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base import algebra
from ...base.errors import ConstraintError, ModelError
from ...base.linear import solve_linear
from ...base.printing import text
from ...base.trace import LazyEquations, Trace
from ..kinematics import linear_form
from ..mode import ModeSetup
from ..regime import Deferred
from ..solution import LazyMap, Regime, Solution, repeatable
from .compare import ops_above

t = dynamicsymbols._t


def eom_row(expr: sp.Expr, accels) -> sp.Expr:
    """An equation of motion ``= 0`` tidied for reading: constant factors dropped, first q̈ positive."""
    e = algebra.strip_factors(sp.sympify(expr))
    e = sp.collect(sp.expand(e), accels, func=sp.factor_terms) if not ops_above(e, 199) else e
    return algebra.leading_sign(e, accels) * e


def _value(x):
    return x.compute() if isinstance(x, Deferred) else x


def _readable_later(M_raw, f_raw, exprs, accels, kin):
    """(M, f, equations of motion) simplified for reading when first read (each computed once)."""
    box: dict = {}

    def get(name):
        if not box:
            repeatable()
            box["M"] = M_raw.applyfunc(kin.simplify_expr)
            box["f"] = f_raw.applyfunc(kin.simplify_expr)
            box["eom"] = tuple(eom_row(e, accels) if not ops_above(e, 399) else e for e in exprs)
        return box[name]

    return Deferred(lambda: get("M")), Deferred(lambda: get("f")), Deferred(lambda: get("eom"))


def _accelerations(M, f, coords, kin, method, where):
    """q̈ = M⁻¹ f: at once for up to two coordinates, else when first asked (a LazyMap)."""
    def solve():
        M_, f_ = _value(M), _value(f)
        try:
            return dict(zip(coords, solve_linear(M_, f_, simplify=kin.simplify_expr, symmetric=True)))
        except ZeroDivisionError:
            raise ConstraintError(f"the equations of {method} are singular in the accelerations.",
                                  where=where) from None

    return MappingProxyType(solve()) if len(coords) <= 2 else LazyMap(solve)


def solution_from_rows(setup: ModeSetup, equations, method: str, trace: Trace, reference: Solution) -> Solution:
    """Solve reaction-free rows for q̈_i in each regime of ``reference`` (Euler's laws, same mode)."""
    repeatable()
    red, kin = setup.reduction, setup.kin
    accels = [q.diff(t, 2) for q in red.independent]
    if len(equations) != len(accels):
        raise ConstraintError(f"{method} gives {len(equations)} equations for {len(accels)} accelerations.",
                              where=setup.system.name)
    reactions = set(setup.reactions)
    for eq in equations:
        bad = [r for r in reactions if eq.expr.has(r)]
        if bad:
            raise ModelError(f"{eq.label} still involves the reaction(s) {', '.join(map(str, bad))}.",
                             where=setup.system.name, hint="This law must eliminate the reactions.")
    regimes = []
    for ref in reference.regimes:
        exprs = [eq.expr.xreplace(dict(ref.signs)) for eq in equations]
        left = {sc.symbol for sc in setup.sign_choices if any(e.has(sc.symbol) for e in exprs)}
        if left:
            raise ModelError(f"{method}: the sign(s) {', '.join(map(str, left))} are not fixed by a regime.",
                             where=setup.system.name)
        A, b = linear_form(exprs, accels)
        if len(accels) <= 2:
            M = A.applyfunc(kin.simplify_expr)
            f = (-b).applyfunc(kin.simplify_expr)
            eom = tuple(eom_row(e, accels) if not ops_above(e, 399) else e for e in exprs)
        else:     # compared numerically from M and f as derived: the readable forms are made when read
            M, f, eom = _readable_later(A, -b, exprs, accels, kin)
        acc = _accelerations(M, f, red.independent, kin, method, setup.system.name)
        if isinstance(acc, LazyMap):
            trace.add("Solving", "Mass matrix and forcing",
                      LazyEquations(lambda M=M, f=f: [(sp.Symbol("M"), _value(M)), (sp.Symbol("f"), _value(f))]),
                      f"the equations of {method} as M q̈ = f" + (f" while {ref.describe()}" if ref.conditions
                                                                  else "") + "; solved for q̈ when asked.")
        else:
            trace.add("Solving", "Accelerations", [(q.diff(t, 2), a) for q, a in acc.items()],
                      f"solved from the {len(exprs)} equation(s) of {method}"
                      + (f" while {ref.describe()}" if ref.conditions else "") + ".")
        trace.add("Solving", "Reactions (from Euler's laws)", [],
                  f"{method} eliminates the reactions; they follow from Euler's laws with these accelerations.")
        regimes.append(Regime(ref.conditions, Deferred(lambda ref=ref: ref.validity), ref.signs, eom, acc,
                              ref.reactions, M, f,
                              raw_mass_matrix=A, raw_forcing=-b, indeterminate=ref.indeterminate))
    trace.add("Solving", "Equations of motion", LazyEquations(lambda: [(e, 0) for r in regimes for e in r.eom]),
              f"the equations of {method}, free of reactions: " + "; ".join(text(e) for e in accels) + ".")
    return Solution(setup.system, method, MappingProxyType(dict(setup.states)), tuple(red.independent),
                    tuple(red.dependent), MappingProxyType(dict(red.coord_map)),
                    MappingProxyType({k: setup.scalar(v) for k, v in red.rate_map.items()}),
                    tuple(regimes), tuple(equations), trace, setup)
