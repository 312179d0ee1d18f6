"""A solution handed to sympy.physics.mechanics, PyDy and scipy.

``Solution.to_sympy()`` gives the equations of motion in the form ``KanesMethod`` gives them: the
coordinates q, the generalised speeds u (u_i = q̇_i of the independent coordinates), the kinematic
differential equations q̇ − u = 0, the mass matrix M and forcing f of M u̇ = f, and the full forms
``mass_matrix_full`` · d/dt[q; u] = ``forcing_full``.  The rows are Kane's equations with u = q̇ (each
body's balance projected on its partial velocities), so they are KanesMethod's own, term for term.
By default every symbol is written as a sympy user writes it — ``dynamicsymbols('theta')``,
``symbols('m')``, without rigidkin's assumptions (real, positive) — so the user's symbols match.

``Solution.rhs()`` is the numeric right-hand side ``rhs(t, y, p)`` with y = [q, u] and p the parameters,
in the orders it lists (``states``, ``parameters``): what scipy's ``solve_ivp`` and PyDy's ODE
integration take.  ``Solution.subs`` puts values in by name or by sympy's own symbols.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.physics.vector import dynamicsymbols

from ..base.errors import InputError, RigidkinError
from ..model.definitions import expand
from .keyed import as_ours, to_ours

t = dynamicsymbols._t


class Bridge:
    """The methods of a Solution that hand it to sympy, PyDy and scipy."""

    def subs(self, expr, values: Mapping):
        """``expr`` with ``values`` put in; keys by name (``'theta'``, ``'dot(theta)'``, ``'m'``), rigidkin's
        symbols or sympy's own ``dynamicsymbols`` / ``symbols`` (the same quantity by name).  A key that is
        no coordinate, rate or parameter is an InputError (never a substitution that silently does nothing)."""
        vals = to_ours(self.system, values)
        e = as_ours(self.system, expr)
        derivs = {k: sp.sympify(v) for k, v in vals.items() if isinstance(k, sp.Derivative)}
        rest = {k: sp.sympify(v) for k, v in vals.items() if not isinstance(k, sp.Derivative)}
        # the accelerations first, then the rates, then the coordinates (q̇ contains q)
        for order in (2, 1):
            e = e.xreplace({k: v for k, v in derivs.items() if len(k.variables) == order})
        return e.xreplace(rest)

    def to_sympy(self, regime: int | None = None, assumptions: bool = False) -> KaneForm:
        """M, f, q, u and the kinematic equations as KanesMethod gives them (a :class:`KaneForm`).

        ``regime``: which regime (needed when there are several); ``assumptions=True`` keeps rigidkin's
        symbols (real coordinates, positive parameters) instead of sympy's plain ones."""
        return kane_form(self, regime, assumptions)

    def to_sympy_system(self, regime: int | None = None):
        """The model as a ``sympy.physics.mechanics.System`` (bodies, loads, q, u, kdes, velocity constraints),
        in rigidkin's symbols; ``form_eoms()`` gives KanesMethod's equations of it."""
        return mechanics_system(self, regime)

    def rhs(self, regime: int | None = None) -> NumericRHS:
        """The numeric right-hand side ``rhs(t, y, p)`` for scipy's ``solve_ivp`` and PyDy (a :class:`NumericRHS`)."""
        return numeric_rhs(self, regime)


@dataclass(frozen=True)
class KaneForm:
    """The equations of motion as ``sympy.physics.mechanics.KanesMethod`` gives them.

    ``q`` (coordinates), ``u`` (speeds, u_i = q̇_i), ``kdes`` (q̇ − u, each = 0), ``mass_matrix`` and
    ``forcing`` (M u̇ = f), ``mass_matrix_full`` and ``forcing_full`` (for d/dt [q; u]); ``symbols`` maps
    each of rigidkin's symbols to the one used here.
    """

    q: tuple
    u: tuple
    kdes: tuple
    mass_matrix: sp.Matrix
    forcing: sp.Matrix
    qdot: tuple                  # q̇ in terms of u (q̇_i = u_i; a dependent coordinate's rate relation)
    symbols: Mapping

    @property
    def mass_matrix_full(self) -> sp.Matrix:
        n = len(self.q)
        return sp.diag(sp.eye(n), self.mass_matrix)

    @property
    def forcing_full(self) -> sp.Matrix:
        return sp.Matrix([*self.qdot, *self.forcing])

    @property
    def state(self) -> list:
        """[q, u]: the state of ``mass_matrix_full`` and of ``Solution.rhs()``."""
        return [*self.q, *self.u]

    def rhs(self) -> sp.Matrix:
        """d/dt [q; u] = M_full⁻¹ f_full (KanesMethod.rhs())."""
        return sp.Matrix([*self.qdot, *self.mass_matrix.LUsolve(self.forcing)])


def _plain_speeds(solution) -> None:
    """Refuse a system whose speeds are angular-velocity components (q̇ = W(q) w): here u = q̇."""
    if getattr(solution.system, "speed_groups", None):
        raise RigidkinError("this system's speeds are angular-velocity components (q̇ = W(q) w), not u = q̇; the "
                            "KanesMethod form and rhs(t, y, p) here take u = q̇.", where=solution.system.name,
                            hint="rigidkin.numeric.rhs.make_rhs(system) gives dy/dt for y = (q, q̇) of such a system.")


def _pick(solution, regime):
    return solution._one() if regime is None else solution.regime(regime)


def _integrated(solution) -> tuple[list, list]:
    """(independent coordinates, dependent ones with no position relation: integrated from their rates)."""
    ind = list(solution.coordinates)
    dep = [q for q in solution.dependent if q not in solution.relations]
    return ind, dep


def _plain(expr_syms) -> dict:
    """rigidkin's symbols (with assumptions) → sympy's plain ones of the same name."""
    out = {}
    for a in expr_syms:
        if isinstance(a, AppliedUndef) and a.args == (t,):
            plain = dynamicsymbols(a.func.__name__)
            if plain != a:
                out[a] = plain
        elif isinstance(a, sp.Symbol) and a != t and not isinstance(a, sp.Dummy):
            plain = sp.Symbol(a.name)
            if plain != a:
                out[a] = plain
    return out


def kane_form(solution, regime: int | None = None, assumptions: bool = False) -> KaneForm:
    """The KanesMethod form of one regime of ``solution`` (see the module's docstring)."""
    reg = _pick(solution, regime)
    _plain_speeds(solution)
    ind, dep = _integrated(solution)
    us = [dynamicsymbols(f"u_{q.func.__name__}", real=True) for q in ind]
    to_u = {q.diff(t): u for q, u in zip(ind, us)}
    to_u.update({q.diff(t, 2): u.diff(t) for q, u in zip(ind, us)})
    rel = dict(solution.relations)

    def in_u(e):
        e = sp.sympify(e).xreplace(rel)
        return e.xreplace({k: v for k, v in to_u.items() if len(k.variables) == 2}).xreplace(to_u)

    M = reg.mass_matrix.applyfunc(in_u)
    f = reg.forcing.applyfunc(in_u)
    qdot = [*us, *(in_u(solution.rate_relations[q.diff(t)]) for q in dep)]
    qs = [*ind, *dep]
    kdes = [q.diff(t) - v for q, v in zip(qs, qdot)]
    every = set()
    for e in (*M, *f, *qdot, *qs, *us):
        every |= sp.sympify(e).atoms(AppliedUndef, sp.Symbol)
    for p in solution.system.parameter_info.values():
        every.add(p.symbol)
    sub = {} if assumptions else _plain(every)
    if sub:                      # the derivatives first: d(θ)/dt of the real θ becomes d(θ)/dt of the plain θ
        def plain(e):
            e = sp.sympify(e)
            return e.xreplace({d: d.xreplace(sub) for d in e.atoms(sp.Derivative)}).xreplace(sub)
        M, f = M.applyfunc(plain), f.applyfunc(plain)
        qs, us, qdot, kdes = ([plain(e) for e in seq] for seq in (qs, us, qdot, kdes))
    return KaneForm(tuple(qs), tuple(us), tuple(kdes), M, f, tuple(qdot), dict(sub))


def mechanics_system(solution, regime: int | None = None):
    """A ``sympy.physics.mechanics.System`` of the solution's model in its mode: every coordinate, the speeds
    u_i = q̇_i (dependent ones where the mode's constraint rows relate the rates, handed over as velocity
    constraints), each body as a RigidBody, each load (gravity and springs included) as a force or torque.
    The bodies and loads are those of the Kane cross-check (laws/mechanics_model.py); a load that depends on a
    reaction (Coulomb friction set by a normal force) is refused, as KanesMethod eliminates the reactions."""
    from sympy.physics.mechanics import Force, Point, Torque
    from sympy.physics.mechanics import System as MechanicsSystem

    from .laws.mechanics_model import build

    reg = _pick(solution, regime)
    setup = solution.setup
    _plain_speeds(solution)
    model = build(setup, "forces", "to_sympy_system")
    signs = dict(reg.signs)
    qs = list(solution.system.coordinates)
    us = [dynamicsymbols(f"u_{q.func.__name__}", real=True) for q in qs]
    ind = set(solution.coordinates)
    to_u = {q.diff(t): u for q, u in zip(qs, us)}
    N = model.frame
    O = Point("O")
    O.set_vel(N, 0)
    ms = MechanicsSystem(N, O)
    ms.add_coordinates(*qs)
    ms.add_speeds(*[u for q, u in zip(qs, us) if q in ind])
    dep = [u for q, u in zip(qs, us) if q not in ind]
    if dep:
        ms.add_speeds(*dep, independent=False)
        vc = [sp.sympify(r.velocity).xreplace(signs).xreplace(to_u) for r in model.rows][:len(dep)]
        ms.add_nonholonomic_constraints(*vc)
    ms.add_kdes(*[q.diff(t) - u for q, u in zip(qs, us)])
    ms.add_bodies(*model.bodies)
    ms.add_loads(*[(Torque if not isinstance(where, Point) else Force)(where, vec.subs(signs) if signs else vec)
                   for where, vec in model.loads])
    return ms


@dataclass
class NumericRHS:
    """``rhs(t, y, p)`` → dy/dt for y = [q, u] (``states``) and p (``parameters``; ``p`` defaults to ``values``).

    ``rhs.values`` holds the parameters' declared values (SI) in that order; ``rhs.initial`` the declared
    initial state.  ``solve_ivp(rhs, (0, 2), rhs.initial, args=(rhs.values,))`` integrates it.
    """

    states: tuple
    parameters: tuple
    values: object
    initial: object
    _f: object
    _n: int

    def __call__(self, t_, y, p=None):
        import numpy as np

        p = self.values if p is None else p
        if len(p) != len(self.parameters):
            raise InputError(f"rhs(t, y, p) takes {len(self.parameters)} parameters "
                             f"({', '.join(self.parameters)}), not {len(p)}.", where="Solution.rhs()")
        qdot, M, f = self._f(float(t_), *np.asarray(y, dtype=float), *np.asarray(p, dtype=float))
        n = self._n
        udot = np.linalg.solve(np.atleast_2d(np.asarray(M, dtype=float)).reshape(n, n),
                               np.asarray(f, dtype=float).reshape(n)) if n else np.zeros(0)
        return np.concatenate([np.asarray(qdot, dtype=float).reshape(-1), udot])

    def for_odeint(self):
        """The same right-hand side in the argument order of scipy's ``odeint`` and PyDy's generated ODE
        functions, ``f(y, t, p)``."""
        return lambda y, t_, p=None: self(t_, y, p)


def numeric_rhs(solution, regime: int | None = None) -> NumericRHS:
    """The numeric right-hand side of one regime (see :class:`NumericRHS`)."""
    import numpy as np

    form = kane_form(solution, regime, assumptions=True)
    system = solution.system
    info = system.parameter_info
    qs = [sp.Symbol(f"_q{i}") for i in range(len(form.q))]
    us = [sp.Symbol(f"_u{i}") for i in range(len(form.u))]
    ps = [sp.Symbol(f"_p{i}") for i in range(len(info))]
    rep = {**dict(zip(form.q, qs)), **dict(zip(form.u, us)), **dict(zip((p.symbol for p in info.values()), ps))}

    def plain(e):
        e = sp.sympify(expand(sp.sympify(e)))
        return e.xreplace({d: d.xreplace(rep) for d in e.atoms(sp.Derivative)}).xreplace(rep)

    exprs = [sp.Matrix([plain(e) for e in form.qdot]), form.mass_matrix.applyfunc(plain),
             form.forcing.applyfunc(plain)]
    left = set().union(*(e.free_symbols for e in exprs)) - {t, *qs, *us, *ps}
    left |= set().union(*(e.atoms(AppliedUndef, sp.Derivative) for e in exprs))
    if left:
        raise RigidkinError(f"the equations of motion contain {', '.join(sorted(map(str, left)))}, which is neither "
                            "a coordinate, a speed, time nor a parameter: rhs(t, y, p) cannot evaluate them.",
                            where=system.name, hint="Inputs u(t) are simulated by rigidkin's simulate(..., inputs=).")
    f = sp.lambdify([t, *qs, *us, *ps], exprs, "numpy", cse=True)
    names = [q.func.__name__ for q in form.q]
    states = (*names, *(f"dot({n})" for n in names[:len(form.u)]))
    values = np.array([np.nan if p.value is None else float(p.value) for p in info.values()])
    coords = system.coordinate_info
    start = [coords[n].initial or 0.0 for n in names] + [coords[n].rate or 0.0 for n in names[:len(form.u)]]
    return NumericRHS(states, tuple(info), values, np.array(start, dtype=float), f, len(form.u))
