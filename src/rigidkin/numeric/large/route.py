"""Past the symbolic limit: large trees of pinned bodies simulated with the articulated-body algorithm.

The symbolic route derives the mass matrix and forcing of every mode in closed form; for a chain of
n rods that is n² trigonometric entries, and past a few tens of degrees of freedom the derivation
and the generated code take minutes.  A system with more than :data:`SYMBOLIC_LIMIT` degrees of
freedom that is a tree of pinned bodies with no contacts (``tree.read_tree``) is simulated instead
with the equations of motion evaluated numerically at each step by the articulated-body algorithm
(``articulated.ArticulatedModel``: recursive Newton–Euler in O(n)); the result says so in its
``route`` and in the description of its one segment.  Anything else keeps the symbolic route.
"""

from __future__ import annotations

import numpy as np

from ...derive.derivation import derivation_of
from ..result import Segment, build_result
from ..rhs import RHS, SimulationError
from ..state import StateLayout, initial_values, parameter_vector
from .articulated import ArticulatedModel
from .tree import NotATree

#: above this many degrees of freedom a tree of pinned bodies is simulated numerically (ABA)
SYMBOLIC_LIMIT = 12


def numeric_route(system, limit: int | None = None) -> ArticulatedModel | None:
    """The articulated model of ``system`` when it is above the symbolic limit and a tree of pinned
    bodies (kept with the system), otherwise None (the symbolic route)."""
    limit = SYMBOLIC_LIMIT if limit is None else limit
    n = len(system.coordinate_info)
    if n <= limit:
        return None
    return derivation_of(system).articulated(lambda: _articulated(system, n, limit))


def _articulated(system, n: int, limit: int) -> ArticulatedModel | None:
    """The articulated model of ``system`` with the route it takes, None when it is not a tree of pinned bodies."""
    try:
        model = ArticulatedModel(system)
    except NotATree:
        return None
    model.route = (f"{system.title or system.name}: {n} degrees of freedom, above the symbolic limit of "
                   f"{limit}; equations of motion evaluated numerically (articulated-body algorithm, "
                   "recursive Newton–Euler, O(n) per step)")
    return model


class _Monitor:
    """What ``build_result`` reads of a segment's model: pin reactions, T and U at the samples."""

    def __init__(self, model: ArticulatedModel):
        self.model = model
        self.conservative = model.conservative

    def evaluate(self, times, ys, p) -> dict:
        m = self.model
        reactions = {k: np.empty(len(times)) for k in m.reaction_names}
        T, U = np.empty(len(times)), np.empty(len(times))
        for j, tt in enumerate(times):
            r, T[j], U[j] = m.sample(float(tt), ys[:, j], p)
            for k, v in r.items():
                reactions[k][j] = v
        return {"reactions": reactions, "residuals": {}, "T": T, "U": U, "frictions": {}}


def simulate_tree(system, model: ArticulatedModel, t_span: tuple[float, float], initial_state=None, params=None, *,
                  method: str = "DOP853", rtol: float = 1e-11, atol: float = 1e-13, max_step: float | None = None,
                  n_points: int = 1001, energy_tol: float = 1e-6, residual_tol: float = 1e-6, progress=None):
    """Simulate a tree of pinned bodies (no contacts, no events) with the articulated-body algorithm.

    Same arguments and result as :func:`rigidkin.numeric.simulate`; the initial state is the declared
    one with ``initial_state`` on top (every coordinate is independent in a tree).
    """
    t0, t1 = t_span
    lay: StateLayout = model.layout
    n = lay.n
    p = parameter_vector(system, lay, params)
    model.numbers(p)                              # NotATree here: the caller keeps the symbolic route
    explicit, declared = initial_values(system, lay, initial_state)
    y = np.zeros(2 * n + 1)
    for i, v in {**declared, **explicit}.items():
        y[i] = v
    max_step = (t1 - t0) / 100 if max_step is None else float(max_step)
    rhs = RHS(model.rates, lay, p, label=system.name, progress=(lambda tt: progress(tt, t1)) if progress else None)
    from scipy.integrate import solve_ivp  # here: importing the route (and simulate) stays quick

    try:
        sol = solve_ivp(rhs, (t0, t1), y, method=method, rtol=rtol, atol=atol, dense_output=True, max_step=max_step)
    except (ValueError, ZeroDivisionError, FloatingPointError) as exc:
        raise SimulationError(f"the integration failed: {exc}.", where=system.name) from None
    if sol.status == -1:
        raise SimulationError(f"the integration failed at t = {sol.t[-1]:.10g} ({sol.message}).", where=system.name,
                              hint="The motion may reach a singular configuration; try method='Radau' or looser "
                                   "tolerances.")
    if progress is not None:
        progress(float(sol.t[-1]), t1)
    seg = Segment(t0, float(sol.t[-1]), {}, 0, model.route, 0, sol.sol, _Monitor(model), p, rhs.calls)
    result = build_result(system, lay, [seg], [], "completed", f"reached t = {t1:g}", n_points=n_points,
                          energy_tol=energy_tol, residual_tol=residual_tol)
    result.route = model.route
    return result
