"""Numbers from a solution at one state: reactions and accelerations.

The closed forms are evaluated first (compiled once per regime).  Where one of them is not finite — a
0/0 left in a closed form at a special configuration — or its denominator has lost its digits, the
balance equations themselves are solved numerically at that state (they are linear in q̈ and the
reactions, and of full column rank), so the value is always the finite one the physics gives.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import RigidkinError
from .kinematics import linear_form

t = dynamicsymbols._t

_CACHE: dict = {}


def full_state(solution, state: Mapping, values: Mapping | None = None) -> tuple[dict, dict]:
    """(every coordinate and rate, parameter values): dependent ones from the relations."""
    params = {p.symbol: float(p.value) for p in solution.system.parameter_info.values() if p.value is not None}
    for k, v in (values or {}).items():
        params[k] = float(v)
    out = {k: float(v) for k, v in state.items()}
    num = {**params, t: out.get(t, 0.0)}        # the instant, where a law of t drives the motion

    def at(expr):
        e = sp.sympify(expr)
        rates = {k: sp.Float(v) for k, v in out.items() if isinstance(k, sp.Derivative)}
        coords = {k: sp.Float(v) for k, v in out.items() if not isinstance(k, sp.Derivative)}
        e = e.xreplace(rates).xreplace(coords).xreplace({k: sp.Float(v) for k, v in num.items()})
        return complex(e.evalf()).real

    for q, rel in solution.relations.items():
        if q not in out:
            out[q] = at(rel)
    for u, rel in solution.rate_relations.items():
        if u not in out:
            out[u] = at(rel)
    return out, params


def _compiled(solution, regime):
    key = (id(solution), id(regime))
    hit = _CACHE.get(key)
    if hit is not None and hit[0] is regime:
        return hit[1]
    names = list(regime.reactions)
    closed = sp.Matrix([regime.reactions[n] for n in names]) if names else sp.Matrix([])
    accels = [q.diff(t, 2) for q in solution.coordinates]
    present = {s for e in solution.equations for s in e.expr.free_symbols}
    equations = solution.equations
    if names and not any(s.name in names for s in present):
        # Lagrange's and Kane's equations have no reactions: they come from Euler's laws, same mode
        equations = solution.system.solve(mode=dict(solution.states)).equations
        present = {s for e in equations for s in e.expr.free_symbols}
    loose = set(getattr(regime.indeterminate, "reactions", ()))   # statically indeterminate: unknowns too
    react_syms = sorted((s for s in present if s.name in names or s.name in loose), key=str)
    exprs = [e.expr.xreplace(dict(regime.signs)) for e in equations]
    A, b = linear_form(exprs, accels + react_syms)
    plain, back = algebra.plain_state(closed if names else sp.Matrix([0]))
    pA, backA = algebra.plain_state(A.row_join(b))
    back = {**back, **backA}
    syms = sorted((plain.free_symbols | pA.free_symbols) - {t}, key=str)
    f_closed = sp.lambdify([t] + syms, plain, "numpy")
    f_lin = sp.lambdify([t] + syms, pA, "numpy")
    out = (names, react_syms, syms, back, f_closed, f_lin, len(accels))
    if len(_CACHE) > 200:
        _CACHE.clear()
    _CACHE[key] = (regime, out)
    return out


def _arguments(syms, back, state, params):
    args = []
    for s in syms:
        orig = back.get(s, s)
        if orig in state:
            args.append(state[orig])
        elif s in params:
            args.append(params[s])
        else:
            raise RigidkinError(f"a value for {orig} is needed to evaluate the reactions.",
                                hint="Give every independent coordinate and rate, and a value for every parameter.")
    return args


def reactions_at(solution, state: Mapping, values: Mapping | None = None, regime=None) -> dict[str, float]:
    """Every reaction (name → number) at ``state`` ({q: value, q̇: value}, and the instant t where a law of t
    drives the motion: default 0); parameters from ``values`` or their declared values.  Finite wherever the
    physics is: a closed form that gives 0/0 there is replaced by the numeric solution of the balance
    equations at that state.
    """
    full, params = full_state(solution, state, values)
    if regime is None:
        regime = solution.regimes[0] if len(solution.regimes) == 1 else \
            solution.regime_at({**full, **params})
    names, react_syms, syms, back, f_closed, f_lin, n_acc = _compiled(solution, regime)
    if not names:
        return {}
    if any(isinstance(back.get(s), sp.Derivative) and back[s].derivative_count == 2 for s in syms):
        full.update(accelerations_at(solution, full, params, regime))   # reactions written with q̈
    args = _arguments(syms, back, full, params)
    with np.errstate(all="ignore"):
        closed = np.array(f_closed(float(full.get(t, 0.0)), *args), dtype=complex).ravel()
    if np.all(np.isfinite(closed)) and np.all(np.abs(closed.imag) <= 1e-9 * np.maximum(1, np.abs(closed.real))):
        values_closed = closed.real
        numeric = _numeric(f_lin, full.get(t, 0.0), args, names, react_syms, n_acc, regime.indeterminate)
        if numeric is None:
            return dict(zip(names, map(float, values_closed)))
        scale = max(1.0, float(np.abs(numeric).max()))
        if np.abs(values_closed - numeric).max() <= 1e-6 * scale:
            return dict(zip(names, map(float, values_closed)))
        return dict(zip(names, map(float, numeric)))      # the closed form lost its digits here
    numeric = _numeric(f_lin, full.get(t, 0.0), args, names, react_syms, n_acc, regime.indeterminate)
    if numeric is None:
        raise RigidkinError("the reactions are not determined at this state (the balance equations are "
                            "singular there).")
    return dict(zip(names, map(float, numeric)))


def _numeric(f_lin, time, args, names, react_syms, n_acc, loose=None):
    """The reactions from the balance equations solved numerically (None where they are singular; with
    statically indeterminate reactions ``loose``, the least-norm solution: the determinate ones are the same in
    every solution)."""
    with np.errstate(all="ignore"):
        Ab = np.array(f_lin(float(time), *args), dtype=float)
    if not np.all(np.isfinite(Ab)):
        return None
    A, b = Ab[:, :-1], -Ab[:, -1]
    if np.linalg.matrix_rank(A) < A.shape[1] and not loose:
        return None
    x, *_ = np.linalg.lstsq(A, b, rcond=None)
    by_name = {str(s): x[n_acc + i] for i, s in enumerate(react_syms)}
    return np.array([by_name.get(n, 0.0) for n in names], dtype=float)


def accelerations_at(solution, state: Mapping, values: Mapping | None = None, regime=None) -> dict:
    """q̈ (as {q̈: number}) at ``state`` from M q̈ = f solved numerically."""
    full, params = full_state(solution, state, values)
    if regime is None:
        regime = solution.regimes[0] if len(solution.regimes) == 1 else \
            solution.regime_at({**full, **params})
    key = ("acc", id(solution), id(regime))
    hit = _CACHE.get(key)
    if hit is None or hit[0] is not regime:
        plain, back = algebra.plain_state(regime.mass_matrix.row_join(regime.forcing))
        syms = sorted(plain.free_symbols - {t}, key=str)
        hit = (regime, (syms, back, sp.lambdify([t] + syms, plain, "numpy")))
        _CACHE[key] = hit
    syms, back, fn = hit[1]
    with np.errstate(all="ignore"):
        Mf = np.array(fn(float(full.get(t, 0.0)), *_arguments(syms, back, full, params)), dtype=float)
    n = Mf.shape[0]
    if n == 0:
        return {}
    x = np.linalg.solve(Mf[:, :n], Mf[:, n])
    return {q.diff(t, 2): float(v) for q, v in zip(solution.coordinates, x)}
