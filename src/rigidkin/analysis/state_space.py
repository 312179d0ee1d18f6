"""State-space form about an operating point: ẋ = A δx + B δu, y = C δx + D δu.

The state is x = (q, q̇) of the solution's independent coordinates and u the system's inputs
(:mod:`rigidkin.model.inputs`).  With the reaction-free equations M(q) q̈ = f(q, q̇, u, t):

    A = [[0, 1], [M⁻¹ ∂f/∂q, M⁻¹ ∂f/∂q̇]],   B = [[0], [M⁻¹ ∂f/∂u]]     at (q*, q̇*, u*),

exact when the operating point is a steady motion (q̈ = M⁻¹f = 0 there: an equilibrium, or uniform
rates of coordinates that f does not depend on); any other point is refused with its residual q̈.  The
check, the elimination of dependent coordinates and A, B are :mod:`rigidkin.analysis.linear`'s.
Outputs are coordinates (``"x"``), rates (``"dot(x)"``) and reactions (``"N_A"``): their rows of C and
D are the derivatives of their expressions at the operating point.  Everything is closed form
(sympy matrices in the parameters); :meth:`StateSpace.numeric` puts the parameters' values in.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import RigidkinError
from ..derive.kinematics import linear_form
from ..model.inputs import inputs_of
from ..model.speeds import require_rate_speeds
from .events import _num, numeric_values
from .integrals import single_regime
from .linear import _at, linearise_about, position_gaps

t = dynamicsymbols._t


@dataclass(frozen=True)
class StateSpace:
    """A, B, C, D (sympy matrices) with the names of the states, inputs and outputs, and the operating point."""

    A: sp.Matrix
    B: sp.Matrix
    C: sp.Matrix
    D: sp.Matrix
    states: tuple[str, ...]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    operating_point: dict
    values: dict = field(default_factory=dict, repr=False)    # the parameters' values (or probes) for numeric()

    def numeric(self, values: Mapping | None = None):
        """(A, B, C, D) as float arrays with the parameters' values (``values``: name or symbol → number)."""
        import numpy as np

        vals = dict(self.values)
        symbols = set().union(*(m.free_symbols for m in (self.A, self.B, self.C, self.D)))
        by_name = {str(s): s for s in symbols | set(vals)}
        for k, v in (values or {}).items():
            vals[by_name.get(str(k), k)] = float(v)
        free = symbols - set(vals)
        if free:
            raise RigidkinError(f"the parameters {', '.join(sorted(map(str, free)))} have no value.",
                                where="state_space numeric", hint="Give them: numeric({'m': 1.5, ...}).")

        def num(m):
            return np.array([[_num(m[i, j], vals) for j in range(m.cols)] for i in range(m.rows)], dtype=float)

        return num(self.A), num(self.B), num(self.C), num(self.D)


def _resolve(solution, at: Mapping) -> dict:
    """The operating point as {q: value, q̇: value} for the independent coordinates (rates default 0)."""
    system = solution.system
    by_name = {q.func.__name__: q for q in system.coordinates}
    point = {}
    for key, value in (at or {}).items():
        if isinstance(key, str):
            k = key.strip()
            if k.startswith("dot(") and k.endswith(")") and k[4:-1].strip() in by_name:
                sym = by_name[k[4:-1].strip()].diff(t)
            elif k in by_name:
                sym = by_name[k]
            else:
                raise RigidkinError(f"'{key}' is not a coordinate or a rate of {system.name}.", where="state_space",
                                    hint=f"Coordinates: {', '.join(by_name)}; rates are written dot(NAME).")
        else:
            sym = key
        point[sym] = sp.sympify(value)
    for q in solution.coordinates:
        point.setdefault(q, sp.Integer(0))
        point.setdefault(q.diff(t), sp.Integer(0))
    return point


def state_space(solution, at: Mapping, inputs: Mapping | None = None, outputs: Sequence[str] = (),
                tol: float = 1e-9) -> StateSpace:
    """The linear state-space model (A, B, C, D) of ``solution`` about the operating point ``at``.

    ``at`` maps coordinates (name or q(t)) and rates (``"dot(x)"`` or q̇) to values (rates default 0);
    ``inputs`` maps input names to their values u* there (default 0); ``outputs`` names coordinates,
    rates or reactions.  Refused unless the operating point is a steady motion (q̈ = 0 there); the
    check, the elimination of dependent coordinates and A, B are :func:`rigidkin.analysis.linear.linearise_about`'s
    (every coordinate kept as a state, ignorable ones included).
    """
    if not hasattr(solution, "regimes"):            # a System: solve it first
        solution = solution.solve()
    system = solution.system
    require_rate_speeds(system, "the state-space form")
    regime = single_regime(solution)
    declared = inputs_of(system)
    unknown = [k for k in (inputs or {}) if k not in declared]
    if unknown:
        raise RigidkinError(f"{', '.join(map(str, unknown))} is not an input of {system.name}.", where="state_space",
                            hint=f"Inputs: {', '.join(declared) or 'none (declare them with System.input)'}.")
    u_syms = [i.symbol for i in declared.values()]
    u_at = {declared[k].symbol: sp.sympify(v) for k, v in (inputs or {}).items()}
    for u in u_syms:
        u_at.setdefault(u, sp.Integer(0))
    point = {**_resolve(solution, at), **u_at}
    qs = list(solution.coordinates)
    us = [q.diff(t) for q in qs]
    M, f = regime.raw_mass_matrix, regime.raw_forcing
    fixed = {q for q in system.coordinates if any(sp.sympify(g).has(q) for _, g in position_gaps(solution))}
    hidden = [q for q in system.coordinates if q not in qs and q not in fixed and (M.has(q) or f.has(q))]
    if hidden:
        names = ", ".join(q.func.__name__ for q in hidden)
        raise RigidkinError(f"the equations of motion depend on {names}, which the constraints give only through "
                            "their rates (a nonholonomic constraint), so the state (q, q̇) of the independent "
                            "coordinates does not determine the motion.", where="state_space",
                            hint="Linearise in every coordinate and the independent speeds numerically "
                                 "(rigidkin.numeric.large.projected.ProjectedModel), or simulate.")
    values = {k: v for k, v in numeric_values(solution).items() if k in set(system.parameters.values())}
    lin = linearise_about(solution, point, inputs=u_syms, values=values, what="state_space", full_state=True)
    C, D, names = _outputs(solution, regime, outputs, qs, us, u_syms, lin)
    return StateSpace(lin.A, lin.B, C, D,
                      tuple(q.func.__name__ for q in qs) + tuple(f"dot({q.func.__name__})" for q in qs),
                      tuple(declared), names, dict(lin.point), dict(system.parameter_values()))


def _outputs(solution, regime, outputs, qs, us, u_syms, lin):
    """Rows of C and D: each output's derivatives at the point, dependent coordinates by the chain rule."""
    n, m = len(qs), len(u_syms)
    point = dict(lin.point)
    rows_c, rows_d, names = [], [], []
    dep_rates = {q.diff(t): sp.sympify(solution.rate_relations[q.diff(t)]) for q in lin.dependent}
    chain = {}
    for q in lin.dependent:             # ∂q_d/∂q_i: the coefficient of q̇_i in the rate relation
        A_, _ = linear_form([dep_rates[q.diff(t)]], us)
        chain[q] = [_at(A_[0, j], point) for j in range(n)]
    acc = {q.diff(t, 2): a for q, a in dict(regime.accelerations).items()}
    for name in outputs:
        key = str(name).strip()
        expr = None
        for i, q in enumerate(qs):
            if key == q.func.__name__:
                expr = q
            elif key == f"dot({q.func.__name__})":
                expr = us[i]
        if expr is None:
            reactions = regime.reactions
            if key not in dict(reactions):
                known = [q.func.__name__ for q in qs] + [str(r) for r in dict(reactions)]
                raise RigidkinError(f"'{name}' is not an independent coordinate, a rate or a reaction.",
                                    where="state_space outputs", hint=f"Outputs may be: {', '.join(known)} "
                                                                      "(rates: dot(NAME)).")
            expr = dict(reactions)[key]
        expr = sp.sympify(expr).xreplace(acc).xreplace(dep_rates)
        row = []
        for j, s in enumerate(qs + us):
            d = sp.diff(expr, s)
            if j < n:
                d = d + sum((sp.diff(expr, qd) * chain[qd][j] for qd in lin.dependent), sp.Integer(0))
            row.append(algebra.readable(_at(d, point)))
        rows_c.append(row)
        rows_d.append([algebra.readable(_at(sp.diff(expr, u), point)) for u in u_syms])
        names.append(key)
    C = sp.Matrix(rows_c) if rows_c else sp.zeros(0, 2 * n)
    D = sp.Matrix(rows_d) if rows_d and m else sp.zeros(len(rows_c), m)
    return C, D, tuple(names)
