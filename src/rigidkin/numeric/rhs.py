"""The numerical right-hand side of one regime of one mode: dy/dt for y = (q, q̇) of every coordinate.

In a mode the independent accelerations q̈_i come from the Solution's regime; the dependent
coordinates follow the constraints: q̇_d from the reduction's rate relations and q̈_d from its
acceleration relations, with q̈_i put in.  Every coordinate is integrated, so the state can be
carried into any other mode.  Expressions become numeric functions through ``compile_functions``
(``sympy.cse`` then one ``lambdify``): that is the one place a faster backend plugs in.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..errors import RigidkinError
from .state import StateLayout

t = dynamicsymbols._t

#: Optional replacement of :func:`compile_functions`: ``backend(args, exprs) -> f(*args) -> sequence``.
_BACKEND: Callable | None = None


class SimulationError(RigidkinError):
    """The integration failed (a NaN or infinity, a step size that collapsed, a state no mode admits)."""


def use_backend(backend: Callable | None) -> None:
    """Use ``backend(args, exprs)`` instead of lambdify to make numeric functions (None: lambdify)."""
    global _BACKEND
    _BACKEND = backend


def compile_functions(args: Sequence[sp.Symbol], exprs: Sequence[sp.Expr]) -> Callable:
    """One numeric function of ``args`` returning the values of ``exprs`` (common subexpressions shared)."""
    exprs = [sp.sympify(e) for e in exprs]
    extra = set().union(*[e.free_symbols for e in exprs]) - set(args) if exprs else set()
    if extra:
        names = ", ".join(sorted(map(str, extra)))
        raise RigidkinError(f"the equations still contain {names}, which is neither a coordinate, a rate, "
                            "time nor a parameter, so they cannot be evaluated numerically.",
                            hint="Every quantity in a model must be a parameter, a coordinate or a function "
                                 "of time written with rigidkin.t.")
    if _BACKEND is not None:
        return _BACKEND(list(args), exprs)
    if not exprs:
        return lambda *a: ()
    return sp.lambdify(list(args), exprs, modules="numpy", cse=True)


def regime_rates(solution, regime_index: int, layout: StateLayout) -> tuple[list, list]:
    """(q̇ expressions, q̈ expressions) for every coordinate in layout order, in one regime of a mode."""
    reg = solution.regime(regime_index)
    red = solution.setup.reduction
    acc = {q.diff(t, 2): a for q, a in reg.accelerations.items()}
    qdot, udot = [], []
    for q in layout.coordinates:
        if q in reg.accelerations:
            qdot.append(q.diff(t))
            udot.append(reg.accelerations[q])
        else:
            qdot.append(red.rate_map[q.diff(t)])
            udot.append(sp.sympify(red.accel_map[q.diff(t, 2)]).xreplace(acc).xreplace(red.rate_map))
    return qdot, udot


class RHS:
    """dy/dt = f(t, y) with the parameters bound; y = (q, q̇, extra integrals such as work done).

    It refuses to return a NaN or an infinity: the failing time and state are reported instead.
    ``progress(t)`` is called now and then (for progress bars).
    """

    def __init__(self, function: Callable, layout: StateLayout, params: np.ndarray, n_extra: int = 0,
                 label: str = "", progress: Callable | None = None):
        self.function = function
        self.layout = layout
        self.params = tuple(float(v) for v in params)
        self.size = 2 * layout.n + n_extra
        self.label = label
        self.progress = progress
        self.calls = 0
        self._last_report = 0.0

    def __call__(self, t_: float, y: np.ndarray) -> np.ndarray:
        self.calls += 1
        with np.errstate(all="ignore"):
            dy = np.asarray(self.function(t_, *y[:2 * self.layout.n], *self.params), dtype=float)
        if not np.all(np.isfinite(dy)):
            state = ", ".join(f"{k} = {v:.6g}" for k, v in self.layout.as_dict(y).items())
            raise SimulationError(f"the equations of motion give a non-finite rate at t = {t_:.10g} "
                                  f"({state}).", where=self.label or "simulation",
                                  hint="The motion reached a singular configuration of the coordinates "
                                       "or of the mass matrix; check the model and the initial state.")
        if self.progress is not None:
            now = time.monotonic()
            if now - self._last_report > 0.1:
                self._last_report = now
                self.progress(t_)
        return dy


def make_rhs(system, mode: dict | None = None, regime: int = 0, params=None, layout: StateLayout | None = None,
             extra_rates: Sequence[sp.Expr] = (), progress: Callable | None = None) -> RHS:
    """The right-hand side rhs(t, y) of ``system`` in ``mode`` (regime ``regime``), parameters bound by value.

    y = (q_1 … q_n, q̇_1 … q̇_n[, extra…]); ``extra_rates`` are further integrands (e.g. the power of
    non-conservative loads).  This is the function a compiled backend replaces.
    """
    from .state import parameter_vector

    layout = layout or StateLayout.of(system)
    solution = system.solve(mode=dict(mode or {}))
    qdot, udot = regime_rates(solution, regime, layout)
    exprs = [layout.to_plain(e) for e in (*qdot, *udot, *extra_rates)]
    f = compile_functions(layout.arguments(), exprs)
    p = parameter_vector(system, layout, params)
    return RHS(f, layout, p, len(extra_rates), label=f"{system.name}", progress=progress)
