"""State-space form about an operating point: ẋ = A δx + B δu, y = C δx + D δu.

The state is x = (q, q̇) of the solution's independent coordinates and u the system's inputs
(:mod:`rigidkin.model.inputs`).  With the reaction-free equations M(q) q̈ = f(q, q̇, u, t):

    A = [[0, 1], [M⁻¹ ∂f/∂q, M⁻¹ ∂f/∂q̇]],   B = [[0], [M⁻¹ ∂f/∂u]]     at (q*, q̇*, u*),

exact when the operating point is a steady motion (q̈ = M⁻¹f = 0 there: an equilibrium, or uniform
rates of coordinates that f does not depend on); any other point is refused with its residual q̈.
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
from ..model.inputs import inputs_of
from ..model.speeds import require_rate_speeds
from .events import _num, numeric_values
from .integrals import single_regime

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
    rates or reactions.  Refused unless the operating point is a steady motion (q̈ = 0 there).
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
    hidden = [q for q in system.coordinates if q not in qs and (M.has(q) or f.has(q))]
    if hidden:
        names = ", ".join(q.func.__name__ for q in hidden)
        raise RigidkinError(f"the equations of motion depend on {names}, which the constraints give only through "
                            "their rates (a nonholonomic constraint), so the state (q, q̇) of the independent "
                            "coordinates does not determine the motion.", where="state_space",
                            hint="Linearise in every coordinate and the independent speeds numerically "
                                 "(rigidkin.numeric.large.projected.ProjectedModel), or simulate.")
    Mo = M.xreplace(point).applyfunc(algebra.readable)
    fo = f.xreplace(point)
    values = numeric_values(solution)
    # a steady motion: M⁻¹ f vanishes at the operating point
    residual = [algebra.readable(e) for e in Mo.LUsolve(fo)]
    bad = [(q, r) for q, r in zip(qs, residual) if r != 0 and abs(_num(r, values)) > tol]
    if bad:
        what = "; ".join(f"{q.func.__name__}'' = {r}" for q, r in bad)
        raise RigidkinError(f"the operating point is not a steady motion: the accelerations do not vanish there "
                            f"({what}).", where="state_space",
                            hint="Linearise about an equilibrium (or a steady motion): choose the coordinates, rates "
                                 "and input values that make every acceleration zero.")
    n = len(qs)
    Kq = f.jacobian(qs).xreplace(point)
    Ku = f.jacobian(us).xreplace(point)
    Fu = f.jacobian(u_syms).xreplace(point) if u_syms else sp.zeros(n, 0)
    lower_q = Mo.LUsolve(Kq).applyfunc(algebra.readable)
    lower_u = Mo.LUsolve(Ku).applyfunc(algebra.readable)
    A = sp.zeros(2 * n, 2 * n)
    A[:n, n:] = sp.eye(n)
    A[n:, :n] = lower_q
    A[n:, n:] = lower_u
    B = sp.zeros(2 * n, len(u_syms))
    if u_syms:
        B[n:, :] = Mo.LUsolve(Fu).applyfunc(algebra.readable)
    C, D, names = _outputs(solution, regime, outputs, qs, us, u_syms, point)
    ss = StateSpace(A, B, C, D, tuple(q.func.__name__ for q in qs) + tuple(f"dot({q.func.__name__})" for q in qs),
                    tuple(declared), names, point, dict(system.parameter_values()))
    return ss


def _outputs(solution, regime, outputs, qs, us, u_syms, point):
    n, m = len(qs), len(u_syms)
    rows_c, rows_d, names = [], [], []
    state = qs + us
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
        expr = sp.sympify(expr)
        acc = {q.diff(t, 2): a for q, a in dict(regime.accelerations).items()}
        expr = expr.xreplace(acc)
        rows_c.append([algebra.readable(sp.diff(expr, s).xreplace(point)) for s in state])
        rows_d.append([algebra.readable(sp.diff(expr, u).xreplace(point)) for u in u_syms])
        names.append(key)
    C = sp.Matrix(rows_c) if rows_c else sp.zeros(0, 2 * n)
    D = sp.Matrix(rows_d) if rows_d and m else sp.zeros(len(rows_c), m)
    return C, D, tuple(names)
