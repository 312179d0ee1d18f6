"""The numerical right-hand side of one regime of one mode: dy/dt for y = (q, q̇) of every coordinate.

In a mode the independent accelerations q̈_i come from the Solution's regime; the dependent
coordinates follow the constraints: q̇_d from the reduction's rate relations and q̈_d from its
acceleration relations, with q̈_i put in.  Every coordinate is integrated, so the state can be
carried into any other mode.  Expressions become numeric functions through ``compile_functions``
(``sympy.cse`` then one ``lambdify``, on our own argument names: no user text in the code it writes):
that is the one place a faster backend plugs in.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.errors import RigidkinError
from ..derive.kinematics import linear_form
from ..model.definitions import expand
from ..model.speeds import STABILISATION, quaternion_groups
from .compiled.codesafe import safe_lambdify
from .inputs import ACTIVE as INPUTS
from .state import StateLayout, parameter_vector

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

    exprs = [expand(sp.sympify(e)) for e in exprs]
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
    return safe_lambdify(list(args), exprs, where="simulation")      # our own names only in the code


def _is_ready(mapping) -> bool:
    """True when a Solution mapping holds its expressions already (not a LazyMap still to compute)."""
    return getattr(mapping, "computed", True)


class RegimeFunctions:
    """The numeric content of one regime of one mode, in three stages.

    1. the independent accelerations q̈_i: the Solution's expressions when it has them, otherwise
       M q̈_i = f solved numerically (large systems whose symbolic solve is left lazy);
    2. the reactions: the Solution's expressions when it has them, otherwise the balance equations
       (linear in q̈_i and the reactions) solved numerically with q̈_i known (least squares: the
       extra equations are consistent);
    3. the rates of every coordinate (q̇_d and q̈_d from the reduction's relations) and any further
       ``quantities`` — expressions of the state, the parameters, q̈_i and the reaction symbols.

    ``evaluate(t, y, p)`` returns (dy/dt for (q, q̇), reactions, quantities).
    """

    def __init__(self, solution, regime_index: int, layout: StateLayout, quantities: Sequence[sp.Expr] = ()):

        reg = solution.regime(regime_index)
        red = solution.setup.reduction
        lay = self.layout = layout
        self.independent = list(solution.coordinates)
        self.slots = [lay.coordinates.index(q) for q in self.independent]
        accels = [q.diff(t, 2) for q in self.independent]
        acc_syms = [sp.Symbol(f"_acc_{q.func.__name__}", real=True) for q in self.independent]
        to_acc = dict(zip(accels, acc_syms))
        reactions = [r for r in solution.setup.reactions]
        present = set().union(*[e.expr.free_symbols for e in solution.equations]) if solution.equations else set()
        self.reaction_symbols = [r for r in reactions if r in present]
        self.zero_reactions = [str(r) for r in reactions if r not in present]
        self.reaction_names = [str(r) for r in self.reaction_symbols] + self.zero_reactions
        base = lay.arguments()
        n_t = 1 + 2 * lay.n
        args_acc = base[:n_t] + acc_syms + base[n_t:]
        # stage 1
        self.explicit_acc = _is_ready(reg.accelerations)
        if self.explicit_acc:
            self._acc = compile_functions(base, [lay.to_plain(reg.accelerations[q]) for q in self.independent])
        else:
            M, f = reg.mass_matrix, reg.forcing
            self._acc = compile_functions(base, [lay.to_plain(e) for e in (*M, *f)])
        # stage 2
        self.explicit_react = _is_ready(reg.reactions)
        nI, nR = len(acc_syms), len(self.reaction_symbols)
        if self.explicit_react:
            self._react = compile_functions(base, [lay.to_plain(reg.reactions[str(r)])
                                                   for r in self.reaction_symbols])
        else:
            signs = dict(reg.signs)
            exprs = [e.expr.xreplace(signs) for e in solution.equations]
            A, b = linear_form(exprs, accels + self.reaction_symbols)
            Aa, Ar = A[:, :nI], A[:, nI:]
            rhs = -(b + Aa * sp.Matrix(acc_syms)) if nI else -b
            self._rows = A.rows
            self._react = compile_functions(args_acc, [lay.to_plain(e) for e in (*Ar, *rhs)])
        # stage 3
        qdot, udot = [], []
        # Euler parameters: ė = ½Q(e)w + k(1 − |e|²)e holds |e| at 1 (the frame turns by e/|e|: no physical change)
        euler = {e: g.coordinates for g in quaternion_groups(solution.system) for e in g.coordinates}
        for q in lay.coordinates:
            if q in self.independent:
                qdot.append(q.diff(t))
                udot.append(to_acc[q.diff(t, 2)])
            else:
                qdot.append(red.rate_map[q.diff(t)] + (STABILISATION * (1 - sum(e**2 for e in euler[q])) * q
                                                       if q in euler else 0))
                udot.append(sp.sympify(red.accel_map[q.diff(t, 2)]).xreplace(to_acc).xreplace(red.rate_map))
        args_all = base[:n_t] + acc_syms + self.reaction_symbols + base[n_t:]
        self.n_quantities = len(quantities)
        self._rest = compile_functions(args_all, [lay.to_plain(e) for e in (*qdot, *udot, *quantities)])
        self._nI, self._nR = nI, nR
        self._key, self._val = None, None

    def evaluate(self, t_: float, y: np.ndarray, p) -> tuple[np.ndarray, dict, np.ndarray]:
        """(dy/dt of (q, q̇), reactions by name, quantities) at one state; the last call is remembered."""
        lay = self.layout
        bind = INPUTS.get()                   # the inputs u(t) of the simulation in progress (numeric/inputs.py)
        if bind is not None:
            p = bind(t_, y, p)
        st = tuple(float(v) for v in y[:2 * lay.n])
        key = (float(t_), st, tuple(p))
        if key == self._key:
            return self._val
        nI, nR = self._nI, self._nR
        with np.errstate(all="ignore"):
            a = np.asarray(self._acc(t_, *st, *p), dtype=float)
            if not self.explicit_acc:
                M, f = a[:nI * nI].reshape(nI, nI), a[nI * nI:]
                try:
                    a = np.linalg.solve(M, f)
                except np.linalg.LinAlgError:
                    a = np.full(nI, np.nan)
            if nR:
                r = np.asarray(self._react(t_, *st, *a, *p) if not self.explicit_react
                               else self._react(t_, *st, *p), dtype=float)
                if not self.explicit_react:
                    Ar, rhs = r[:self._rows * nR].reshape(self._rows, nR), r[self._rows * nR:]
                    r = np.linalg.lstsq(Ar, rhs, rcond=None)[0] if np.all(np.isfinite(Ar)) else np.full(nR, np.nan)
            else:
                r = np.zeros(0)
            rest = np.asarray(self._rest(t_, *st, *a, *r, *p), dtype=float)
        reactions = dict(zip(self.reaction_names, [*map(float, r), *([0.0] * len(self.zero_reactions))]))
        out = (rest[:2 * lay.n], reactions, rest[2 * lay.n:])
        self._key, self._val = key, out
        return out


class RHS:
    """dy/dt = f(t, y) with the parameters bound; y = (q, q̇, then extra integrals such as work done).

    ``rates(t, y, p)`` gives the whole derivative.  It refuses to return a NaN or an infinity: the
    failing time and state are reported instead.  ``progress(t)`` is called now and then.
    """

    def __init__(self, rates: Callable, layout: StateLayout, params: np.ndarray, label: str = "",
                 progress: Callable | None = None):
        self.rates = rates
        self.layout = layout
        self.params = tuple(float(v) for v in params)
        self.label = label
        self.progress = progress
        self.calls = 0
        self._last_report = 0.0

    def __call__(self, t_: float, y: np.ndarray) -> np.ndarray:
        self.calls += 1
        with np.errstate(all="ignore"):
            try:
                dy = np.asarray(self.rates(t_, y, self.params), dtype=float)
            except (OverflowError, ZeroDivisionError):     # a load such as θ⁻¹⁰⁰ out of range: reported below
                dy = np.full(np.shape(y), np.nan)
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

    y = (q_1 … q_n, q̇_1 … q̇_n[, extra…]); ``extra_rates`` are further integrands (expressions of the
    state, parameters and reaction symbols).  Its numeric functions come from :func:`compile_functions`.
    """

    layout = layout or StateLayout.of(system)
    fns = RegimeFunctions(system.solve(mode=dict(mode or {})), regime, layout, extra_rates)
    p = parameter_vector(system, layout, params)

    def rates(t_, y, p_):
        dy, _, extra = fns.evaluate(t_, y, p_)
        return np.concatenate([dy, extra]) if len(extra) else dy

    return RHS(rates, layout, p, label=f"{system.name}", progress=progress)
