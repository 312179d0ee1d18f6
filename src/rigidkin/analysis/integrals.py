"""First integrals: the energy integral of a conservative one-degree-of-freedom motion.

For one independent coordinate q the reaction-free equation of motion has the form
M(q) q̈ + ½ M′(q) q̇² = Q(q) exactly when the system is conservative (no damping, no sliding friction,
no moving surfaces): then d/dt(½ M q̇²) = Q(q) q̇ and

    ½ M(q) q̇² − ½ M(q0) q̇0² = ∫_{q0}^{q} Q(s) ds,

which gives q̇² as a function of q.  The generalised mass M and force Q come from the solution's mass
matrix and forcing; the check that the q̇-dependent part of the forcing is −½ M′ q̇² is what decides
that the integral exists (a non-conservative system gets a clear error, not a wrong integral).

A system driven by a law of t (a driven body, a prescribed coordinate, a frame turned at Ω) is answered
only for that law, and said so: where its equations are free of t (a rod on a shaft turned at constant Ω)
the same integral is the Jacobi integral h = Σ q̇ ∂L/∂q̇ − L (T₂ − T₀ + U), not the conservation of
T + U, which changes by the work of the drive; where they depend on t there is none.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import RigidkinError
from ..derive.laws.energy import kinetic_energy, potential_energy
from ..model.drives import driving_laws, driving_note
from .linear import position_gaps, present
from .states import at_state, full_state

t = dynamicsymbols._t


#: sympy's simplify gets this many seconds, and only expressions up to this many operations.
SIMPLIFY_SECONDS = 4.0
SIMPLIFY_OPS = 600


def bounded_simplify(expr) -> sp.Expr:
    """``simplify`` within a time and size budget (its randomised factoring can run for minutes), then
    the bounded simplification for reading; the expression as it is when the budget runs out."""
    e = sp.sympify(expr)
    if sp.count_ops(e) <= SIMPLIFY_OPS:
        try:
            with algebra.time_limit(SIMPLIFY_SECONDS):
                e = sp.simplify(e)
        except TimeoutError:
            e = sp.sympify(expr)
    return algebra.readable(e)


@dataclass(frozen=True)
class EnergyIntegral:
    """q̇² = ``rate_squared`` (a function of q) along the motion that starts at (q0, q̇0)."""

    coordinate: sp.Expr
    rate_squared: sp.Expr
    mass: sp.Expr            # generalised mass M(q)
    force: sp.Expr           # generalised force Q(q)
    start: tuple             # (q0, q̇0)
    branch: dict = field(default_factory=dict)   # dependent coordinates as functions of q along the motion
    name: str = "energy integral"                # "Jacobi integral" for a system driven by a law of t
    note: str = ""                               # when it holds: only for the given driving law

    @property
    def equation(self) -> tuple:
        return (self.coordinate.diff(t) ** 2, self.rate_squared)


def single_regime(solution):
    if len(solution.regimes) != 1:
        raise RigidkinError(f"this needs one regime, and the solution has {len(solution.regimes)} (one per sense of "
                            "sliding, where friction slides).",
                            hint="Ask with the sliding contact's mode set to 'stick' (or 'open').")
    return solution.regimes[0]


def start_values(solution, start: dict | None) -> tuple:
    """(q0, q̇0) of the single independent coordinate, from ``start`` or the declared initial state."""
    (q,) = solution.coordinates
    start = dict(start or {})
    info = solution.system.coordinate_of(q)
    q0 = start.get(q, info.initial if info.initial is not None else 0)
    u0 = start.get(q.diff(t), info.rate if info.rate is not None else 0)
    return exact_number(q0), exact_number(u0)


def exact_number(v):
    """A start value as an exact number: 0.3 → 3/10 (so that answers stay exact), else as given."""
    if isinstance(v, float | sp.Float):
        return sp.nsimplify(v, rational=True)
    return sp.sympify(v)


def energy_integral(solution, start: dict | None = None) -> EnergyIntegral:
    """The energy integral q̇²(q) of a conservative 1-DOF solution, from ``start`` (default: initial state)."""
    if len(solution.coordinates) != 1:
        raise RigidkinError(f"the closed-form energy integral here is for one degree of freedom; this solution "
                            f"has {len(solution.coordinates)}.", hint="Use the energy law (T + U) instead.")
    regime = single_regime(solution)
    (q,) = solution.coordinates
    u = q.diff(t)
    branch = explicit_branch(solution, regime, start)
    M = bounded_simplify(regime.mass_matrix[0, 0].xreplace(branch))
    f = regime.forcing[0].xreplace(branch)
    Q = f.xreplace({u: 0})
    gyro = sp.expand(f - Q)
    s = sp.Dummy("s")
    expected = -sp.diff(M.xreplace({q: s}), s).xreplace({s: q}) * u**2 / 2
    laws = driving_laws(solution.system)
    if f.has(t) and algebra.plain_state(f)[0].has(t):
        why = f" (the driving law {'; '.join(laws)})" if laws else ""
        raise RigidkinError(f"the forcing depends explicitly on time{why}, so energy is not conserved and there is "
                            "no energy integral.", hint="Moving surfaces, driving laws and time-varying loads do "
                                                        "work; simulate instead (its energy balance counts that work).")
    if not algebra.is_zero(gyro - expected):
        raise RigidkinError("the system is not conservative (its rate-dependent forces are not those of a "
                            "kinetic energy ½M(q)q̇²: damping or sliding friction does work), so there is "
                            "no energy integral.", hint="Simulate it instead.")
    q0, u0 = start_values(solution, start)
    work = sp.integrate(Q.xreplace({q: s}), (s, q0, q))
    rate_sq = (M.xreplace({q: q0}) * u0**2 + 2 * work) / M
    rate_sq = algebra.readable(sp.simplify(rate_sq))
    if laws:            # the equations are free of t: the Jacobi integral for this driving law
        return EnergyIntegral(q, rate_sq, M, Q, (q0, u0), branch, "Jacobi integral",
                              driving_note(solution.system) + "; this is the Jacobi integral ½M q̇² − ∫Q dq, "
                              "constant while the driving law holds")
    return EnergyIntegral(q, rate_sq, M, Q, (q0, u0), branch)


def explicit_branch(solution, regime, start: dict | None) -> dict:
    """The dependent coordinates that M and f still contain, as functions of the independent one: the
    position constraints solved in closed form, the branch the start lies on (a pendulum in x and y:
    y = −sqrt(l² − x²) when it starts below the pivot).  Empty when there are none."""
    extra = [d for d in solution.dependent if d in present([regime.mass_matrix[0, 0], regime.forcing[0]])]
    if not extra:
        return {}
    (q,) = solution.coordinates
    plain = {d: sp.Dummy(d.func.__name__, real=True) for d in extra}
    eqs = [g.xreplace(plain) for _, g in position_gaps(solution) if g.has(*extra)]
    try:
        with algebra.time_limit(SIMPLIFY_SECONDS):
            sols = sp.solve(eqs, list(plain.values()), dict=True)
    except (NotImplementedError, TimeoutError):
        sols = []
    state = full_state(solution.system, dict(start or {}))
    values = {p.symbol: p.value for p in solution.system.parameter_info.values() if p.value is not None}
    back = {v: k for k, v in plain.items()}
    for sol in sols:
        if set(sol) != set(plain.values()):
            continue
        branch = {back[k]: v for k, v in sol.items()}
        ok = True
        for d, v in branch.items():
            try:
                have = complex(at_state(v, state).xreplace({k: sp.Float(x) for k, x in values.items()}).evalf())
                want = complex(sp.sympify(state[d]).xreplace({k: sp.Float(x) for k, x in values.items()}).evalf())
            except TypeError:
                ok = False
                break
            ok &= abs(have - want) <= 1e-9 * max(1.0, abs(want))
        if ok:
            return branch
    raise RigidkinError("the equations contain the dependent coordinates "
                        f"{', '.join(d.func.__name__ for d in extra)}, and no closed-form solution of the position "
                        "constraints passes through the start, so there is no closed-form energy integral.",
                        hint="Check that the start satisfies the constraints, or simulate.")


def along_motion(solution, expr, integral: EnergyIntegral) -> sp.Expr:
    """``expr`` (of q, q̇, q̈) along the motion: q̈ from the EOM, q̇² from the integral."""
    (q,) = solution.coordinates
    u = q.diff(t)
    regime = single_regime(solution)
    e = sp.sympify(expr).xreplace({q.diff(t, 2): regime.accelerations[q]})
    if integral.branch:
        e = e.xreplace(dict(solution.rate_relations)).xreplace(integral.branch)
    e = sp.expand(e)
    plain, _ = algebra.plain_state(e)
    e = e.xreplace({u: sp.Symbol("_u")})
    us = sp.Symbol("_u")
    if e.has(us):
        poly = sp.Poly(e, us) if e.is_polynomial(us) else None
        if poly is None or any(k[0] % 2 for k in poly.monoms() if poly.coeff_monomial(k) != 0):
            # odd powers: q̇ = ±sqrt(q̇²); the sign is the direction of motion
            raise RigidkinError("the expression depends on the sign of the rate, not only on its square.",
                                hint="Give the direction of motion.")
        e = e.xreplace({us: sp.sqrt(integral.rate_squared)})
    return bounded_simplify(e)


@dataclass(frozen=True)
class FirstIntegral:
    """A quantity constant along every motion of the mode: ``expression`` = ``value`` (at ``start``)."""

    name: str
    expression: sp.Expr
    value: sp.Expr | None
    why: str


def _rate_along(solution, regime, expr) -> sp.Expr:
    """d/dt of an expression of the state, with the accelerations of the solution substituted."""
    d = solution.setup.reduction.reduce(sp.diff(expr, t))      # dependent rates (ė = W(q)u) eliminated
    for qd2, acc in regime.accelerations.items():
        d = d.xreplace({qd2.diff(t, 2): acc})
    return d


def first_integrals(solution, start: dict | None = None) -> list[FirstIntegral]:
    """Energy (when conserved) and the generalised momentum of each cyclic coordinate.

    Each candidate is kept only if its rate along the motion (accelerations substituted) vanishes
    identically, so a dissipative system simply has no energy integral in the list.
    """
    regime = single_regime(solution)
    setup = solution.setup
    state = full_state(solution.system, dict(start or {}))
    out = []
    T, U = kinetic_energy(setup), potential_energy(setup)
    E = algebra.readable(T + U)
    note = driving_note(solution.system)
    if algebra.is_zero(_rate_along(solution, regime, E)):
        out.append(FirstIntegral("energy", E, algebra.readable(at_state(E, state)),
                                 "T + U is constant: no non-conservative load does work in this mode"
                                 + (f"; {note}" if note else "")))
    elif note:
        out += _jacobi(solution, regime, setup, T, U, state, note)
    M = regime.mass_matrix
    for j, q in enumerate(solution.coordinates):
        p = algebra.readable(sum((M[j, k] * qk.diff(t) for k, qk in enumerate(solution.coordinates)),
                                 sp.Integer(0)))
        if p == 0 or not algebra.is_zero(_rate_along(solution, regime, p)):
            continue
        out.append(FirstIntegral(f"momentum conjugate to {q.func.__name__}", p, algebra.readable(at_state(p, state)),
                                 f"{q.func.__name__} is cyclic: it appears neither in the kinetic energy nor in "
                                 "the generalised forces"))
    if getattr(solution.system, "speed_groups", None):
        out += _angular_momentum(solution, regime, state)
    return out


def _jacobi(solution, regime, setup, T, U, state, note) -> list[FirstIntegral]:
    """The Jacobi integral h = Σ q̇ ∂L/∂q̇ − L of a driven system whose Lagrangian is free of t (a frame turned at
    constant Ω): kept only if its rate along the motion vanishes."""
    L = setup.scalar(T - U)
    if algebra.plain_state(sp.sympify(L))[0].has(t):
        return []
    us = [q.diff(t) for q in solution.coordinates]
    h = algebra.readable(sum((u * sp.diff(L, u) for u in us), sp.Integer(0)) - L)
    if h == 0 or not algebra.is_zero(_rate_along(solution, regime, h)):
        return []
    return [FirstIntegral("Jacobi integral", h, algebra.readable(at_state(h, state)),
                          f"h = Σ q̇ ∂L/∂q̇ − L is constant: L = T − U is free of t; {note}")]


def _angular_momentum(solution, regime, state) -> list[FirstIntegral]:
    """The angular momentum about O, H_O = Σ (Ī·ω + r_G × m v_G), of a 3D system with angular speeds: its
    components along the inertial axes and |H_O|², each kept only if its rate along the motion vanishes."""
    from sympy.physics.vector import Vector

    setup = solution.setup
    kin = setup.kin
    F = kin.F
    H = Vector(0)
    for b in solution.system.bodies.values():
        if b.is_massless:
            continue
        G = b.centre
        H += b.inertia.dot(kin.omega_of(b)) + kin.position(G).cross(b.mass * kin.velocity(G))
    H = setup.vector(H)
    comps = [algebra.readable(setup.scalar(H.dot(e))) for e in (F.x, F.y, F.z)]
    out = []
    for c, name in zip(comps, F.basis):
        if c != 0 and algebra.is_zero(_rate_along(solution, regime, c)):
            out.append(FirstIntegral(f"angular momentum about O along {name}", c, algebra.readable(at_state(c, state)),
                                     f"the loads have no moment about O along {name}"))
    mag = sum((c**2 for c in comps), sp.Integer(0))
    if mag != 0 and algebra.is_zero(_rate_along(solution, regime, mag)):
        out.append(FirstIntegral("|H_O|²", mag, algebra.readable(at_state(mag, state)),
                                 "the magnitude of the angular momentum about O is constant"))
    return out
