"""A state of the system for the answers: every coordinate and rate, and expressions evaluated at it.

Shared by the energy integrals, the events and the phases (a module of its own, so that none of them
needs to import another for it).
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import dynamicsymbols

t = dynamicsymbols._t


def full_state(system, start: dict) -> dict:
    """Every coordinate and rate: given values, else the declared initial values, else 0."""
    out = {}
    for c in system.coordinate_info.values():
        q, u = c.symbol, c.symbol.diff(t)
        q0 = start.get(q, c.initial if c.initial is not None else 0)
        u0 = start.get(u, c.rate if c.rate is not None else 0)
        out[q] = _exact(q0)
        out[u] = _exact(u0)
    return out


def _exact(v):
    """0.3 → 3/10 (answers stay exact); anything else as given."""
    return sp.nsimplify(v, rational=True) if isinstance(v, float | sp.Float) else sp.sympify(v)


def at_state(expr, state: dict):
    """``expr`` with the rates and then the coordinates of ``state`` put in."""
    e = sp.sympify(expr)
    rates = {k: v for k, v in state.items() if isinstance(k, sp.Derivative)}
    coords = {k: v for k, v in state.items() if not isinstance(k, sp.Derivative)}
    return e.xreplace(rates).xreplace(coords)


def state_from_names(system, named: dict) -> dict:
    """A simulator's state ({"theta": 0.3, "dot(theta)": 1.2}) as {θ: 0.3, θ̇: 1.2} (sympy numbers)."""
    out = {}
    for c in system.coordinate_info.values():
        if c.name in named:
            out[c.symbol] = sp.Float(named[c.name])
        if f"dot({c.name})" in named:
            out[c.symbol.diff(t)] = sp.Float(named[f"dot({c.name})"])
    return out
