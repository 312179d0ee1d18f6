"""Linearisation about an operating point: an equilibrium (rates zero) or a steady motion (rates constant).

The reaction-free equations M(q) q̈ = f(q, q̇, u) are linearised about a state x* at which every
acceleration vanishes (checked first: the residual q̈* is computed and a state where it is not zero is
refused with it, never linearised):

    M δq̈ + C δq̇ + K δq = B_u δu,   M = M(x*), C = −∂f/∂q̇, K = −∂f/∂q, B_u = ∂f/∂u at x*

(∂M/∂q q̈* drops out because q̈* = 0).  Dependent coordinates that the equations still contain (a
pendulum written in x and y with its length as a constraint) are eliminated by the chain rule:
∂q_d/∂q_i is the coefficient of q̇_i in the rate relation q̇_d = B(q) q̇_i, exact for a position
constraint, and q_d takes the value the position constraint gives at the point — as sympy's
Linearizer does with its configuration constraints.  Coordinates in neither M nor f (the heading and
spin of a rolling coin) are *ignorable*: their rates are states, they are not.  The first-order
state is (δq of the other coordinates, δq̇ of all): d/dt x = A x + B u.  ``inputs`` (symbols or
functions of t in the forcing) give B; the outputs' C and D are left to the caller.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import InputError, RigidkinError
from ..base.printing import text
from ..derive.kinematics import linear_form
from ..model.inputs import input_symbols
from ..model.speeds import require_rate_speeds

t = dynamicsymbols._t

#: sympy gets this many seconds for a closed form (dependent coordinates, critical values).
SOLVE_SECONDS = 8.0
#: a residual below this, relative to the size of its terms, vanishes at the parameters' values.
REL_TOL = 1e-9


@dataclass(frozen=True)
class SteadyMotion:
    """The linearisation of a solution about a steady motion or an equilibrium ``point``."""

    point: Mapping              # coordinates and rates → values (dependent ones included)
    coordinates: tuple          # all independent coordinates of the solution
    ignorable: tuple            # coordinates absent from M and f (their rates are states)
    states: tuple               # δq of the non-ignorable coordinates, then δq̇ of all
    M: sp.Matrix
    C: sp.Matrix
    K: sp.Matrix
    A: sp.Matrix                # first-order state matrix: d(states)/dt = A states + B inputs
    B: sp.Matrix = field(default_factory=lambda: sp.zeros(0, 0))
    inputs: tuple = ()
    dependent: tuple = ()       # dependent coordinates eliminated (their values are in ``point``)
    residual: Mapping = field(default_factory=dict)    # q̈ at the point: zero
    notes: tuple = ()
    values: Mapping = field(default_factory=dict)      # the parameters' values (symbol → number)

    def characteristic_polynomial(self, lam: sp.Symbol | None = None) -> sp.Expr:
        """det(λ I − A), expanded in λ."""
        lam = lam if lam is not None else sp.Symbol("lambda")
        n = self.A.shape[0]
        return sp.expand((lam * sp.eye(n) - self.A).det(method="berkowitz"))

    def numeric_A(self, values: Mapping | None = None) -> np.ndarray:
        """A with the parameters replaced by ``values`` (symbol → number; default their declared values)."""
        vals = {**self.values, **dict(values or {})}
        Anum = self.A.xreplace({k: sp.Float(v) for k, v in vals.items()})
        if Anum.free_symbols:
            raise RigidkinError("the linearisation still contains "
                                f"{', '.join(sorted(map(str, Anum.free_symbols)))}, which have no values.",
                                where="linearisation", hint="Pass values={symbol: number}.")
        return np.array(Anum.evalf(), dtype=float)

    def eigenvalues(self, values: Mapping | None = None) -> np.ndarray:
        """Eigenvalues of the first-order system, with ``values`` for the parameters."""
        return np.linalg.eigvals(self.numeric_A(values))

    def stability(self, values: Mapping | None = None, tol: float = 1e-9) -> str:
        """"unstable" if an eigenvalue has a positive real part, else "asymptotically stable" or "marginal"."""
        re = self.eigenvalues(values).real
        scale = max(1.0, float(np.abs(re).max()))
        if re.max() > tol * scale:
            return "unstable"
        if re.max() < -tol * scale:
            return "asymptotically stable"
        return "marginal (no growing mode in the linearisation)"

    def critical_condition(self, lam: sp.Symbol | None = None) -> sp.Expr:
        """The lowest non-vanishing coefficient of det(λ I − A) (its λᵏ factor of neutral modes removed):
        an eigenvalue crosses zero where it vanishes."""
        lam = lam if lam is not None else sp.Dummy("lambda")
        coeffs = sp.Poly(self.characteristic_polynomial(lam), lam).all_coeffs()[::-1]
        for c in coeffs:
            if not algebra.is_zero(c):
                return sp.factor(algebra.readable(c))
        return sp.Integer(0)

    def critical_values(self, parameter: sp.Symbol, values: Mapping | None = None) -> tuple:
        """The values of ``parameter`` (a spin rate, a speed) at which an eigenvalue crosses zero: closed
        forms where sympy finds them, else numeric roots (Floats) with the other parameters' values."""
        cond = self.critical_condition()
        if not cond.has(parameter):
            return ()
        vals = {k: v for k, v in {**self.values, **dict(values or {})}.items() if k != parameter}
        try:
            with algebra.time_limit(SOLVE_SECONDS):
                roots = sp.solve(cond, parameter)
        except (NotImplementedError, TimeoutError):
            roots = None
        if roots is not None:
            out = []
            for r in roots:
                r = algebra.readable(r)
                v = complex(r.xreplace({k: sp.Float(x) for k, x in vals.items()}).evalf())
                if abs(v.imag) <= 1e-12 * max(1.0, abs(v.real)):
                    out.append(r)
            return tuple(out)
        return _numeric_roots(cond, parameter, vals)


def _numeric_roots(cond, p, vals) -> tuple:
    """Sign changes of ``cond`` in ``p`` over ±[1e-6, 1e6] (log grid), each refined by bisection."""
    from scipy.optimize import brentq

    fn = sp.lambdify(p, cond.xreplace({k: sp.Float(v) for k, v in vals.items()}), "mpmath")

    def g(x):
        return float(sp.re(fn(x)))

    grid = np.logspace(-6, 6, 481)
    out = []
    for sign in ((1,) if p.is_positive else (-1, 1)):
        xs = sign * grid
        ys = [g(x) for x in xs]
        for a, b, fa, fb in zip(xs, xs[1:], ys, ys[1:]):
            if math.isfinite(fa) and math.isfinite(fb) and fa * fb < 0:
                out.append(sp.Float(brentq(g, a, b, xtol=1e-14, rtol=1e-13)))
    return tuple(sorted(out))


# the operating point --------------------------------------------------------------------------------
def single_regime(solution, what: str, keep_inputs: Sequence = ()):
    """The one regime of ``solution`` with its M and f (rate speeds required); inputs u(t) other than
    ``keep_inputs`` are held at zero (an equilibrium of the unforced system)."""
    require_rate_speeds(solution.system, what)
    if len(solution.regimes) != 1:
        raise RigidkinError(f"the solution has {len(solution.regimes)} regimes; {what} is taken in one.",
                            where=what, hint="Solve with the contacts' mode given (at rest relative to a "
                                             "surface a sliding contact sticks: mode 'stick').")
    regime = solution.regimes[0]
    M, f = regime.mass_matrix, regime.forcing
    rel = dict(solution.relations)
    if rel:
        M, f = (algebra.substitute(X, rel) for X in (M, f))
    M, f = sp.Matrix(M), sp.Matrix(f)
    held = {u: sp.Integer(0) for u in input_symbols(solution.system) if u not in set(keep_inputs)}
    if held:                    # inputs u(t) not asked for are held at u* = 0
        M, f = M.xreplace(held), f.xreplace(held)
    return regime, M, f


def present(exprs) -> set:
    """The coordinates the expressions depend on — by the derivative, tested at random states, so a
    coordinate that appears but cancels (an unsimplified spin angle) counts as absent."""
    found = set()
    for e in exprs:
        plain, back = algebra.plain_state(sp.sympify(e))
        for sym in plain.free_symbols:
            q = back.get(sym)
            if q is None or isinstance(q, sp.Derivative) or q in found:
                continue
            if not algebra.is_zero(sp.diff(plain, sym)):
                found.add(q)
    return found


def explicit_time(expr) -> bool:
    """True when ``expr`` depends on t other than through the coordinates (a driving law)."""
    return algebra.plain_state(sp.sympify(expr))[0].has(t)


def position_gaps(solution) -> list:
    """(label, gap) of the position constraints that relate the coordinates."""
    return [(r.label, sp.sympify(r.gap)) for r in solution.setup.reduction.relating if r.gap is not None]


def _name(q) -> str:
    return q.func.__name__ if isinstance(q, sp.Function) else str(q)


def dependent_coordinates(solution, extra: Sequence, known: Mapping, values: Mapping) -> list[dict]:
    """Every assignment of the dependent coordinates ``extra`` that the position constraints give at the
    configuration ``known`` (closed form where sympy finds one, else Newton's method from their initial
    values); real at the parameters' values.  Refused when the constraints do not fix them (a velocity
    constraint: a non-holonomic coordinate is a state of its own)."""
    rest = {q.diff(t): 0 for q in known}
    gaps = [(lab, g.xreplace(rest).xreplace(dict(known))) for lab, g in position_gaps(solution)]
    plain = {q: sp.Dummy(_name(q), real=True) for q in extra}
    eqs = [(lab, g.xreplace(plain)) for lab, g in gaps]
    eqs = [(lab, g) for lab, g in eqs if g.has(*plain.values())]
    unknowns = list(plain.values())
    if eqs:
        J = sp.Matrix([g for _, g in eqs]).jacobian(unknowns)
        rng_vals = {s: sp.Float(0.37 + 0.11 * i) for i, s in enumerate(sorted(J.free_symbols, key=str))}
        Jn = np.array(J.xreplace(rng_vals).evalf(), dtype=complex)
        rank = np.linalg.matrix_rank(Jn, tol=1e-9)
    else:
        rank = 0
    if rank < len(extra):
        raise RigidkinError("the equations of motion contain the dependent coordinates "
                            f"{', '.join(_name(q) for q in extra)}, which no position constraint fixes "
                            "(a velocity constraint relates only their rates).", where="linearisation",
                            hint="Choose them as independent coordinates (solve(independent=[...])), or "
                                 "linearise numerically with rigidkin.numeric.large.projected.")
    sols = None
    try:
        with algebra.time_limit(SOLVE_SECONDS):
            sols = sp.solve([g for _, g in eqs], unknowns, dict=True)
    except (NotImplementedError, TimeoutError):
        sols = None
    back = {v: k for k, v in plain.items()}
    out = []
    if sols:
        for s in sols:
            if set(s) != set(unknowns):
                continue
            conf = {back[k]: algebra.readable(v) for k, v in s.items()}
            if all(_is_real(v, values) for v in conf.values()):
                out.append(conf)
        return out
    # numeric: Newton's method from the declared initial values
    x0 = []
    for q in extra:
        try:
            c = solution.system.coordinate_of(q)
            x0.append(float(c.initial) if c.initial is not None else 0.1)
        except (KeyError, TypeError):
            x0.append(0.1)
    num = [g.xreplace({k: sp.Float(v) for k, v in values.items()}) for _, g in eqs]
    try:
        root = sp.nsolve(num[:len(unknowns)] if len(num) > len(unknowns) else num, unknowns, x0, prec=30)
    except (ValueError, ZeroDivisionError, TypeError) as exc:
        raise RigidkinError("the position constraints cannot be solved for "
                            f"{', '.join(_name(q) for q in extra)} at this configuration ({exc}).",
                            where="linearisation", hint="Give their values in the operating point.") from None
    return [{back[u]: sp.Float(root[i], 15) for i, u in enumerate(unknowns)}]


def _is_real(v, values) -> bool:
    try:
        z = complex(sp.sympify(v).xreplace({k: sp.Float(x) for k, x in values.items()}).evalf())
    except TypeError:
        return True                 # a symbol without a value: real for the values that make it so
    return abs(z.imag) <= 1e-9 * max(1.0, abs(z.real))


def _numeric(expr, values) -> complex | None:
    """``expr`` as a number with ``values`` (30 digits), None when a symbol has no value."""
    e = sp.sympify(expr).xreplace({k: sp.Float(v, 30) for k, v in values.items()})
    plain, _ = algebra.plain_state(e)
    if plain.free_symbols:
        return None
    return complex(plain.evalf(30))


def _scale(expr, values) -> float:
    terms = sp.Add.make_args(sp.expand(sp.sympify(expr)))
    s = 0.0
    for term in terms:
        v = _numeric(term, values)
        s += abs(v) if v is not None else 0.0
    return max(s, 1.0)


def check_vanishes(residual: Mapping, values: Mapping, what: str, where: str) -> list[str]:
    """Back-substitution: each residual must vanish identically, or at the parameters' values to
    ``REL_TOL`` of the size of its terms (then a note says so); otherwise the answer is refused with it."""
    notes = []
    bad = {}
    for k, r in residual.items():
        if algebra.is_zero(r):
            continue
        v = _numeric(r, values)
        if v is not None and abs(v) <= REL_TOL * _scale(r, values):
            notes.append(f"{what} holds at the parameters' values ({k} = {abs(v):.2g} there), not for all values")
            continue
        bad[k] = (r, v)
    if bad:
        parts = [f"{k} = {text(r)}" + (f" ≈ {v.real:.6g}" if v is not None and abs(v.imag) < 1e-12 else "")
                 for k, (r, v) in bad.items()]
        raise RigidkinError(f"{what} fails its back-substitution: " + "; ".join(parts) + ".", where=where,
                            hint="Choose a state where it holds (an equilibrium: every generalised force "
                                 "vanishes at rest; a steady motion: every acceleration vanishes).")
    return notes


def _point(solution, at: Mapping, rest: bool, kept: Sequence, what: str) -> dict:
    point = {}
    for k, v in at.items():
        point[k] = sp.sympify(v)
    qs = list(solution.coordinates)
    if rest:
        moving = {k: v for k, v in point.items() if isinstance(k, sp.Derivative) and not algebra.is_zero(v)}
        if moving:
            raise InputError("an equilibrium is a state of rest, but rates are given: "
                             + ", ".join(f"{text(k)} = {text(v)}" for k, v in moving.items()) + ".", where=what,
                             hint="Linearise about a steady motion with rigidkin.analysis.steady.linearise.")
        for q in qs:
            point[q.diff(t)] = sp.Integer(0)
    missing = [q for q in qs if q.diff(t) not in point]
    if missing:
        raise InputError("a steady motion needs the rate of every independent coordinate; missing: "
                         + ", ".join(f"d{_name(q)}/dt" for q in missing) + ".", where=what)
    unset = [q for q in kept if q not in point]
    if unset:
        raise InputError("the operating point must give the value of every coordinate that is not ignorable; "
                         f"missing: {', '.join(_name(q) for q in unset)}.", where=what)
    return point


def residual_at(M, f, point, n: int) -> sp.Matrix:
    """q̈ at ``point`` (M⁻¹ f; the generalised forces f themselves above four degrees of freedom)."""
    fp = f.xreplace({k: v for k, v in point.items() if isinstance(k, sp.Derivative)}).xreplace(
        {k: v for k, v in point.items() if not isinstance(k, sp.Derivative)})
    if n > 4:
        return fp.applyfunc(algebra.readable)
    Mp = M.xreplace({k: v for k, v in point.items() if not isinstance(k, sp.Derivative)})
    return Mp.LUsolve(fp).applyfunc(algebra.readable)


def linearise_about(solution, at: Mapping, rest: bool = False, inputs: Sequence = (), check: bool = True,
                    values: Mapping | None = None, what: str = "steady motion",
                    full_state: bool = False) -> SteadyMotion:
    """Linearise ``solution`` about the operating point ``at`` (see the module's docstring).

    ``rest``: an equilibrium (every rate zero; only coordinates given).  ``inputs``: symbols or functions
    of t in the forcing, whose columns form B (their operating values from ``at``, else as they are).
    ``values``: the parameters' numbers for the back-substitution and the eigenvalues (default: declared).
    ``full_state``: keep ignorable coordinates as states too (the state (q, q̇) of a control model).
    """
    regime, M, f = single_regime(solution, f"{what}'s linearisation", keep_inputs=inputs)
    vals = {p.symbol: p.value for p in solution.system.parameter_info.values() if p.value is not None}
    vals.update(dict(values or {}))
    qs = list(solution.coordinates)
    us = [q.diff(t) for q in qs]
    found = present(list(M) + list(f))
    extra = [q for q in solution.dependent if q in found and not isinstance(q, sp.Derivative)]
    ignorable = () if full_state else tuple(q for q in qs if q not in found)
    kept = [q for q in qs if q not in ignorable]
    point = _point(solution, at, rest, kept, what)
    notes = []
    # dependent coordinates: their values from the position constraints (given ones are checked)
    known = {q: point[q] for q in qs if q in point}
    given = {q: point[q] for q in extra if q in point}
    if extra:
        sols = dependent_coordinates(solution, [q for q in extra if q not in given], known, vals) \
            if len(given) < len(extra) else [{}]
        if not sols:
            raise RigidkinError("the position constraints have no real solution for "
                                f"{', '.join(_name(q) for q in extra)} at this configuration.", where=what)
        if len(sols) > 1:
            raise InputError("the position constraints leave several configurations here: "
                             + " or ".join(", ".join(f"{_name(k)} = {text(v)}" for k, v in s.items())
                                           for s in sols) + ".", where=what,
                             hint="Give the value of the dependent coordinate in the operating point.")
        point.update(sols[0])
    _check_constraints(solution, point, vals, what)
    # dependent rates at the point, and ∂q_d/∂q_i from the rate relations
    D = sp.zeros(len(extra), len(qs))
    for i, q in enumerate(extra):
        rel = sp.sympify(solution.rate_relations[q.diff(t)])
        A_, _ = linear_form([rel], us)
        for j in range(len(qs)):
            D[i, j] = _at(A_[0, j], point)
        point.setdefault(q.diff(t), algebra.readable(_at(rel, point)))
    for q in ignorable:
        point.setdefault(q, sp.Integer(0))       # absent from M and f: any value will do
    # back-substitution: the accelerations vanish at the point
    input_values = {u: point.get(u, u) for u in inputs}
    Mi = M.xreplace(input_values)
    fi = f.xreplace(input_values)
    res = residual_at(Mi, fi, point, len(qs))
    residual = {f"{_name(q)}''": r for q, r in zip(qs, res)}
    kind = "this equilibrium" if rest else "this steady motion"
    timed = explicit_time(fi)
    if check:
        try:
            notes += check_vanishes(residual, vals, kind, what)
        except RigidkinError as exc:
            if timed:
                exc.message += (" The equations of motion depend on t explicitly (a driving law), so no state "
                                "is at rest for all t.")
            raise
    # Jacobians through plain symbols (rates first: they are Derivative objects containing q)
    pu = {u: sp.Dummy(f"u_{_name(q)}") for q, u in zip(qs, us)}
    pq = {q: sp.Dummy(_name(q)) for q in list(qs) + list(extra)}
    pin = {u: sp.Dummy(f"in_{i}") for i, u in enumerate(inputs)}
    fp = f.xreplace(pin).xreplace(pu).xreplace(pq)
    pp = {**{pu[u]: point[u] for u in us}, **{pq[q]: point[q] for q in pq},
          **{pin[u]: input_values[u] for u in inputs}}
    Mv = M.xreplace(input_values).xreplace(pu).xreplace(pq).xreplace(pp)
    C = (-fp.jacobian([pu[u] for u in us])).xreplace(pp)
    Kq = (-fp.jacobian([pq[q] for q in qs])).xreplace(pp)
    if extra:
        Kq = Kq + (-fp.jacobian([pq[q] for q in extra])).xreplace(pp) * D
    Bu = fp.jacobian([pin[u] for u in inputs]).xreplace(pp) if inputs else sp.zeros(len(qs), 0)
    K = Kq[:, [qs.index(q) for q in kept]] if kept else sp.zeros(len(qs), 0)
    Mv, C, K, Bu = (X.applyfunc(algebra.readable) for X in (Mv, C, K, Bu))
    if any(explicit_time(x) for X in (Mv, C, K, Bu) for x in X):
        raise RigidkinError(f"{kind} is not a state of the same linear system for all t: its linearised "
                            "equations depend on t explicitly (a driving law).", where=what,
                            hint="Write the coordinates relative to the driven frame where the driving is a "
                                 "steady rotation, or simulate.")
    n, k = len(qs), len(kept)
    Minv = Mv.inv()
    select = sp.zeros(k, n)
    for i, q in enumerate(kept):
        select[i, qs.index(q)] = 1
    A = sp.BlockMatrix([[sp.zeros(k, k), select], [-Minv * K, -Minv * C]]).as_explicit().applyfunc(algebra.readable)
    B = sp.Matrix.vstack(sp.zeros(k, len(inputs)), Minv * Bu).applyfunc(algebra.readable) if inputs \
        else sp.zeros(k + n, 0)
    states = tuple(kept) + tuple(us)
    return SteadyMotion(dict(point), tuple(qs), ignorable, states, Mv, C, K, A, B, tuple(inputs), tuple(extra),
                        residual, tuple(notes), vals)


def _at(expr, point):
    e = sp.sympify(expr)
    return e.xreplace({k: v for k, v in point.items() if isinstance(k, sp.Derivative)}).xreplace(
        {k: v for k, v in point.items() if not isinstance(k, sp.Derivative)})


def _check_constraints(solution, point, vals, what) -> None:
    """The position constraints hold at the point (those whose coordinates it gives)."""
    res = {}
    for lab, g in position_gaps(solution):
        e = _at(g, point)
        if algebra.functions_of_time(e):
            continue
        res[lab] = algebra.readable(e)
    if res:
        check_vanishes(res, vals, "the operating point's position constraints", what)
