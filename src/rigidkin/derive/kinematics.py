"""Kinematics in the inertial frame F, and the elimination of dependent rates by the constraints.

``Kinematics`` gives the position, velocity and acceleration of every point, the angular velocity
and acceleration of every frame (sympy's ``Vector.dt`` applies the transport theorem
F d/dt r = B d/dt r + ω × r to every component expressed in a rotating basis), and the velocity of
the material point of a body at any location (the rigid-body relation v_P = v_G + ω × r_GP).

``reduce_constraints`` takes the constraint rows active in a mode, separates those already built
into the chosen coordinates from those that relate the rates, chooses the dependent coordinates
(the last declared, unless told otherwise), solves for their rates and accelerations, and
integrates the relations that are holonomic (a gap that vanishes, or an exact rate relation such as
r φ̇ = (R − r) θ̇, which gives φ = (R − r) θ / r).
"""

from __future__ import annotations

import random
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base import algebra, vectorops
from ..base.errors import ConstraintError
from ..base.linear import linear_form
from ..base.trace import Trace
from ..model.speeds import is_quasi, speeds_of
from .indeterminate import rest_configuration, split_redundant
from .prescribed import refuse_driven_against_ground

if TYPE_CHECKING:
    import numpy as np

t = dynamicsymbols._t


def _dyadic_component(u: Vector, D, w: Vector):
    """u · D · w for a dyadic D: Σ c (u · a)(b · w) over its terms c a b (the value of ``u.dot(D).dot(w)``,
    each unit vector resolved through the direction cosines once rather than through Vector arithmetic)."""
    return sp.Add(*[c * vectorops.dot_vectors(u, a) * vectorops.dot_vectors(b, w) for c, a, b in D.args])


class Kinematics:
    """Positions, velocities and accelerations of a system's points and frames in the inertial frame."""

    def __init__(self, system):
        self.system = system
        self.F = system.inertial
        self._pos: dict = {}
        self._vel: dict = {}
        self._acc: dict = {}
        self._rates: dict = {}          # expression → its time derivative, shared by every d/dt taken here
        self._simp: dict = {}
        self.assumptions: list[str] = []
        self.planar = self._detect_planar()

    # planar detection -----------------------------------------------------------------------------
    def _detect_planar(self) -> bool:
        s, z = self.system, self.F.z
        for fr in s.frames.values():
            if fr.parent is None:
                continue
            if fr.sequence is not None or fr.axis is None or \
                    not self.is_zero_vector(vectorops.cross(fr.axis, fr.parent.z)):
                return False
        for p in s.points.values():
            if p.parent is not None and not algebra.is_zero(p.offset.dot(z)):
                return False
        for b in s.bodies.values():
            I = b.inertia
            if not (algebra.is_zero(_dyadic_component(z, I, self.F.x)) and
                    algebra.is_zero(_dyadic_component(z, I, self.F.y))):
                return False
        for ld in s.loads.values():
            for attr in ("vector", "direction", "along", "normal", "axis"):
                v = getattr(ld, attr, None)
                if isinstance(v, Vector):
                    if ld.kind in ("torque", "torsional spring", "rotational spring", "rotational damper"):
                        if not (algebra.is_zero(v.dot(self.F.x)) and algebra.is_zero(v.dot(self.F.y))):
                            return False
                    elif not algebra.is_zero(v.dot(z)):
                        return False
        for c in s.constraints.values():
            surf = getattr(c, "surface", None)
            if surf is not None and getattr(surf, "normal", None) is not None and \
                    not algebra.is_zero(surf.normal.dot(z)):
                return False
            along = getattr(c, "along", None)
            if along is not None and not algebra.is_zero(along.dot(z)):
                return False
        return True

    # simplification -------------------------------------------------------------------------------
    def simplify_expr(self, e):
        e = sp.sympify(e)
        key = e
        if key not in self._simp:
            self._simp[key] = algebra.readable(e)
        return self._simp[key]

    def simplify_vector(self, v: Vector) -> Vector:
        if v == Vector(0):
            return v
        return Vector([(m.applyfunc(self.simplify_expr), fr) for m, fr in v.args])

    def is_zero(self, e) -> bool:
        return algebra.is_zero(e)

    def is_zero_vector(self, v: Vector) -> bool:
        if v == Vector(0):
            return True
        return all(algebra.is_zero(c) for c in vectorops.in_frame(v, self.F.ref))

    def reference_values(self) -> dict:
        """Parameters at their values (or 1) and coordinates at their initial values (or 0)."""
        vals = {p.symbol: (p.value if p.value is not None else 1.0) for p in self.system.parameter_info.values()}
        for c in self.system.coordinate_info.values():
            vals[c.symbol] = c.initial if c.initial is not None else 0.0
        return vals

    def magnitude(self, v: Vector) -> sp.Expr:
        """|v| = sqrt(v·v), simplified; |expr| resolved by its sign at the reference configuration."""
        sq = sp.factor(sp.trigsimp(sp.expand(v.dot(v))))
        mag = sp.sqrt(sq)
        if mag.has(sp.Abs):
            ref = self.reference_values()
            repl = {}
            for a in mag.atoms(sp.Abs):
                try:
                    val = float(a.args[0].subs(ref))
                except (TypeError, ValueError):
                    continue
                if val > 0:
                    repl[a] = a.args[0]
                elif val < 0:
                    repl[a] = -a.args[0]
                else:
                    continue
                note = f"|{a.args[0]}| = {repl[a]} (its sign in the reference configuration)"
                if note not in self.assumptions:
                    self.assumptions.append(note)
            mag = mag.xreplace(repl)
        return mag

    def tangent_basis(self, n: Vector) -> list[Vector]:
        """Two unit vectors that complete ``n`` to a right-handed basis (n, t1, t2) → t1, t2."""
        # prefer the frame nearest the bodies that is not a body's own frame (a heading frame turns the
        # no-slip rows into their short, familiar form), then the inertial frame
        body_frames = {b.frame.name for b in self.system.bodies.values()}
        frames = [f for f in reversed(list(self.system.frames.values())) if f.name not in body_frames]
        for fr in frames:
            axes = (fr.x, fr.y, fr.z)
            for i, a in enumerate(axes):
                for sgn in (1, -1):
                    if self.is_zero_vector(n - sgn * a):
                        return [sgn * axes[(i + 1) % 3], axes[(i + 2) % 3]]
        helper = self.F.z if not self.is_zero_vector(n.cross(self.F.z)) else self.F.x
        t1 = n.cross(helper)
        t1 = self.simplify_vector(t1 / self.magnitude(t1))
        return [t1, self.simplify_vector(n.cross(t1))]

    # points and frames ----------------------------------------------------------------------------
    def position(self, point) -> Vector:
        if point not in self._pos:
            self._pos[point] = point.position()
        return self._pos[point]

    def velocity(self, point) -> Vector:
        """v_P = F d/dt r_OP (transport theorem for components in rotating bases)."""
        if point not in self._vel:
            self._vel[point] = vectorops.dt(self.position(point), self.F.ref, self._rates)
        return self._vel[point]

    def acceleration(self, point) -> Vector:
        if point not in self._acc:
            self._acc[point] = vectorops.dt(self.velocity(point), self.F.ref, self._rates)
        return self._acc[point]

    def omega(self, frame) -> Vector:
        """F ω B: angular velocity of a frame in the inertial frame."""
        return frame.ref.ang_vel_in(self.F.ref)

    def alpha(self, frame) -> Vector:
        """F α B = F d/dt (F ω B) (what ``ang_acc_in`` forms, differentiated in one pass)."""
        return vectorops.dt(self.omega(frame), self.F.ref, self._rates)

    def omega_of(self, body) -> Vector:
        return Vector(0) if body is None else self.omega(body.frame)

    def material_velocity(self, body, location: Vector) -> Vector:
        """Velocity of the material point of ``body`` at ``location``: v_G + ω × (r − r_G)."""
        if body is None:
            return Vector(0)
        G = body.centre
        return self.velocity(G) + vectorops.cross(self.omega_of(body), location - self.position(G))

    def material_acceleration(self, body, location: Vector) -> Vector:
        """a_P = a_G + α × r_GP + ω × (ω × r_GP) for the material point of ``body`` at ``location``."""
        if body is None:
            return Vector(0)
        G = body.centre
        r = location - self.position(G)
        w = self.omega_of(body)
        cross = vectorops.cross
        return self.acceleration(G) + cross(self.alpha(body.frame), r) + cross(w, cross(w, r))


# ---------------------------------------------------------------------------------------------------
@dataclass
class Reduction:
    """Independent and dependent coordinates of a mode, with the maps that eliminate the dependent ones."""

    independent: tuple
    dependent: tuple
    rate_map: dict = field(default_factory=dict)       # q̇_d → expr(q, q̇_i)
    accel_map: dict = field(default_factory=dict)      # q̈_d → expr(q, q̇_i, q̈_i)
    coord_map: dict = field(default_factory=dict)      # q_d → expr(q_i) where integrated
    rate_integrated: frozenset = frozenset()           # the q_d of coord_map found by integrating rate relations
    built_in: tuple = ()                               # rows satisfied identically by the coordinates
    relating: tuple = ()                               # rows that relate the rates
    redundant: tuple = ()                              # no-slip rows that repeat the others (indeterminate)
    relations: tuple = ()                              # (lhs, rhs, why) for the trace

    def reduce(self, expr):
        """Express in the independent coordinates: q̈_d, q̇_d eliminated (q_d kept)."""
        m = {**self.accel_map, **self.rate_map}
        return algebra.substitute(expr, m) if m else expr

    def to_independent(self, expr):
        """Also replace the integrated dependent coordinates q_d by functions of q_i."""
        expr = self.reduce(expr)
        return algebra.substitute(expr, self.coord_map) if self.coord_map else expr

    @property
    def dof(self) -> int:
        return len(self.independent)


def _rates(coords):
    return [q.diff(t) for q in coords]


def _numeric_matrix(M: sp.Matrix, rng: random.Random) -> np.ndarray:
    import numpy as np  # here: a derivation read from the cache needs no numpy

    plain, _ = algebra.plain_state(M)
    vals = algebra.random_point(plain.free_symbols - {t}, rng)
    vals[t] = sp.Float(0.37)
    return np.array(plain.xreplace(vals).evalf(), dtype=complex)


def solve_square(A: sp.Matrix, b: sp.Matrix, simplify=algebra.readable, seed: int = 7) -> sp.Matrix:
    """Solve A x = b for a square nonsingular A by Gaussian elimination with numeric pivoting.

    Pivots are chosen by their magnitude at a random numeric point, so a pivot is never an
    expression that is zero without looking like it.
    """
    n = A.rows
    A = A.as_mutable()
    b = b.as_mutable()
    num = _numeric_matrix(A, random.Random(seed))
    perm = list(range(n))
    for k in range(n):
        piv = max(range(k, n), key=lambda i: abs(num[i, k]))
        if abs(num[piv, k]) < 1e-12:
            raise ZeroDivisionError("singular")
        if piv != k:
            A.row_swap(k, piv)
            b.row_swap(k, piv)
            num[[k, piv]] = num[[piv, k]]
            perm[k], perm[piv] = perm[piv], perm[k]
        for i in range(k + 1, n):
            if A[i, k] == 0:
                continue
            f = A[i, k] / A[k, k]
            num_f = num[i, k] / num[k, k]
            for j in range(k, n):
                A[i, j] = sp.cancel(A[i, j] - f * A[k, j]) if j > k else sp.Integer(0)
                num[i, j] = num[i, j] - num_f * num[k, j]
            b[i] = b[i] - f * b[k]
    x = [sp.Integer(0)] * n
    for i in reversed(range(n)):
        acc = b[i] - sum((A[i, j] * x[j] for j in range(i + 1, n)), sp.Integer(0))
        x[i] = simplify(acc / A[i, i])
    return sp.Matrix(x)


def reduce_constraints(system, kin: Kinematics, rows, independent=None, trace: Trace | None = None) -> Reduction:
    """Split constraint rows into built-in and rate-relating; eliminate dependent rates; integrate."""
    import numpy as np

    ke = speeds_of(system)
    coords = [q for q in system.coordinates if q not in ke.replaced]    # Euler parameters: q̇ = W(q) u
    built, relating, exprs = [], [], []
    for row in rows:
        v = kin.simplify_expr(ke.substitute(row.velocity))
        if algebra.is_zero(v):
            built.append(row)
        else:
            relating.append(row)
            exprs.append(v)
    if trace is not None:
        for row in built:
            trace.add("Kinematics", f"{row.label}: built into the coordinates", [(row.velocity, 0)],
                      f"the constraint {row.constraint} holds for every value of the coordinates "
                      "as they were chosen, so it relates no rates; it still brings its reaction "
                      f"{row.reaction}.")
    if not relating:
        return _kinematic_equations(Reduction(tuple(coords), (), built_in=tuple(built)), ke, kin, trace)
    rates = _rates(coords)
    A, b = linear_form(exprs, rates)
    accels = [algebra.plain_state(q.diff(t, 2))[0] for q in coords]      # the symbols plain_state gives q̈
    if any(algebra.plain_state(e)[0].has(*accels) for e in exprs):
        raise ConstraintError("a constraint row involves accelerations.", where=relating[0].constraint)
    rng = random.Random(11)
    numA = _numeric_matrix(A, rng)
    refuse_driven_against_ground(relating, exprs, numA)
    rank = np.linalg.matrix_rank(numA, tol=1e-9)
    redundant = []
    if rank < len(relating):            # the rows that add nothing: no-slip rows where they can be
        keep, redundant = split_redundant(relating, numA, A, b)
    if redundant and all(r.kind == "tangential" for r in redundant):
        # held from slipping twice (two rolling supports): the motion is determined, the friction split is not
        relating, exprs, A, b, numA = ([relating[i] for i in keep], [exprs[i] for i in keep],
                                       A.extract(keep, list(range(A.cols))), b.extract(keep, [0]), numA[keep])
    elif redundant:
        names = ", ".join(f"'{r.label}'" for r in redundant)
        raise ConstraintError(
            f"the model is over-constrained: the constraint rows {names} repeat what the other constraints "
            "already impose, so their reactions cannot be determined (statically indeterminate).",
            where=", ".join(sorted({r.constraint for r in redundant})),
            hint=f"{len(coords)} coordinates with {rank} independent constraint rows leave "
                 f"{len(coords) - rank} degrees of freedom; remove the redundant constraint or make it open.")
    if rank > len(coords):
        raise ConstraintError(
            f"the constraints {', '.join(sorted({r.constraint for r in relating}))} fix all "
            f"{len(coords)} coordinates: no degree of freedom remains (the system is a structure).",
            hint="Add a coordinate, or remove or open a constraint.")
    # choose dependent coordinates
    if independent is not None:
        indep = [q for q in coords if q in set(independent)]
        dep_idx = [i for i, q in enumerate(coords) if q not in set(independent)]
        if len(dep_idx) != rank or np.linalg.matrix_rank(numA[:, dep_idx], tol=1e-9) < rank:
            raise ConstraintError(
                f"the coordinates {', '.join(str(q.func.__name__) for q in indep)} cannot all be independent: "
                f"the constraints leave {len(coords) - rank} degrees of freedom and must determine the rest.",
                hint="Choose as many independent coordinates as there are degrees of freedom.")
    else:
        dep_idx = []
        # quasi-coordinates (angular speeds' integrals) last: a contact's rows in a body's angular speeds have
        # coefficients that vanish as it turns (rolling on the body's components w2, w3 is singular wherever b1
        # is horizontal), while the rows in the translations of its centre are the identity at every state
        quasi = [i for i in range(len(coords)) if is_quasi(system, coords[i])]
        order = [i for i in reversed(range(len(coords))) if i not in quasi] + quasi[::-1]
        for i in order:
            trial = dep_idx + [i]
            if np.linalg.matrix_rank(numA[:, trial], tol=1e-9) == len(trial):
                dep_idx = trial
            if len(dep_idx) == rank:
                break
        dep_idx.sort()
    dep = [coords[i] for i in dep_idx]
    ind = [q for i, q in enumerate(coords) if i not in dep_idx]
    ind_idx = [i for i in range(len(coords)) if i not in dep_idx]
    Ad = A[:, dep_idx]
    rhs = -(A[:, ind_idx] * sp.Matrix([rates[i] for i in ind_idx]) + b) if ind_idx else -b   # 0 DOF: at rest
    # square subsystem: choose rows (rank == len(relating) here)
    sol = solve_square(Ad, rhs)
    rate_map = {q.diff(t): sol[k] for k, q in enumerate(dep)}
    accel_map = {}
    for q in dep:
        d = ke.substitute(sp.diff(rate_map[q.diff(t)], t)).xreplace(rate_map)
        accel_map[q.diff(t, 2)] = kin.simplify_expr(d)
    relations = []
    for q in dep:
        relations.append((q.diff(t), rate_map[q.diff(t)],
                          "solved from the constraints " + ", ".join(r.label for r in relating)))
    red = Reduction(tuple(ind), tuple(dep), rate_map, accel_map, {}, built_in=tuple(built), relating=tuple(relating),
                    redundant=tuple(redundant))
    _integrate(system, kin, red, relating, trace)
    if red.redundant and not red.independent:       # at rest on repeated supports: where the gaps put it
        red.coord_map = {**red.coord_map, **rest_configuration(system, kin, dep, list(built) + relating, trace)}
    red.relations = tuple(relations)
    if trace is not None:
        for row in relating:
            trace.add("Kinematics", f"{row.label}: relates the rates", [(row.velocity, 0)],
                      f"the constraint {row.constraint} is not built into the coordinates.")
        trace.add("Kinematics", "Dependent rates eliminated",
                  [(lhs, rhs) for lhs, rhs, _ in relations] + [(k, v) for k, v in accel_map.items()],
                  f"{len(dep)} constraint row(s) relate the rates; the coordinates "
                  f"{', '.join(q.func.__name__ for q in dep)} are eliminated in favour of "
                  f"{', '.join(q.func.__name__ for q in ind)} ({len(ind)} degree(s) of freedom).")
        if red.coord_map:
            trace.add("Kinematics", "Holonomic relations integrated",
                      list(red.coord_map.items()),
                      "each relation is integrable: a gap that vanishes, or an exact rate relation "
                      "integrated from the initial configuration.")
    return _kinematic_equations(red, ke, kin, trace)


def _kinematic_equations(red: Reduction, ke, kin: Kinematics, trace) -> Reduction:
    """Add the kinematic differential equations q̇ = W(q) u of the coordinates whose rates are not their
    speeds (Euler parameters; Euler angles with angular speeds) to the reduction's rate and acceleration
    maps: those coordinates follow their speeds as dependent rates follow the constraints."""
    if not ke.qdot:
        return red
    rate = {k: sp.sympify(v).xreplace(red.rate_map) for k, v in ke.qdot.items()}
    full = {**red.rate_map, **rate}
    accel = {}
    for k, v in rate.items():
        d = ke.substitute(sp.diff(v, t)).xreplace(red.accel_map).xreplace(full)
        accel[k.expr.diff(t, 2)] = kin.simplify_expr(d)
    red.rate_map = {**red.rate_map, **rate}
    red.accel_map = {**red.accel_map, **accel}
    red.dependent = tuple(red.dependent) + tuple(k.expr for k in rate)
    red.relations = tuple(red.relations) + tuple((k, v, "kinematic differential equation") for k, v in rate.items())
    if trace is not None:
        for g in ke.groups:
            what = (f"the Euler parameters of {g.frame.name} follow ė = ½ Q(e) w, which keeps |e| constant"
                    if g.kind == "quaternion" else
                    f"the angles of {g.frame.name} follow from its angular-velocity components")
            trace.add("Kinematics", f"Kinematic differential equations of {g.frame.name}: q̇ = W(q) u",
                      [(q.diff(t), rate[q.diff(t)]) for q in g.coordinates] + [(sp.Symbol("W"), g.W)],
                      f"the speeds {', '.join(n for n in g.names)} are the components of the angular velocity "
                      f"of {g.frame.name} along its own basis (Kane's choice); {what}.")
    return red


def _integrate(system, kin, red: Reduction, relating, trace):
    """Fill ``red.coord_map`` with q_d = f(q_i) where the relations are holonomic and solvable."""
    dep = list(red.dependent)
    # (a) gaps that vanish and are linear in the dependent coordinates
    gaps = [r.gap for r in relating if r.gap is not None]
    solved = {}
    if gaps:
        plain = {q: sp.Dummy(q.func.__name__) for q in dep}
        eqs = [sp.sympify(g).xreplace(plain) for g in gaps]
        cand = [plain[q] for q in dep if any(e.has(plain[q]) for e in eqs)]
        linear = cand and all(sp.Poly(e, *cand).total_degree() <= 1 for e in eqs
                              if e.has(*cand) and e.is_polynomial(*cand))
        if linear and all(e.is_polynomial(*cand) for e in eqs if e.has(*cand)):
            try:
                res = sp.solve(eqs, cand, dict=True)
            except NotImplementedError:
                res = []
            if len(res) == 1:
                back = {v: k for k, v in plain.items()}
                for d, val in res[0].items():
                    if not val.has(*plain.values()):
                        solved[back[d]] = kin.simplify_expr(val.xreplace(back))
    # (b) exact rate relations q̇_d = Σ B_j(q_i) q̇_j
    from_rates = set()
    ind = list(red.independent)
    for q in dep:
        if q in solved or not ind:       # at rest (no degree of freedom): q_d stays where the state has it
            continue
        rhs = red.rate_map[q.diff(t)].xreplace({**{k.diff(t): 0 for k in solved}, **solved})
        rhs = kin.simplify_expr(rhs)
        if not algebra.functions_of_time(rhs) <= set(ind) or algebra.plain_state(rhs)[0].has(t):
            continue
        A, b = linear_form([rhs], [k.diff(t) for k in ind])
        if not algebra.is_zero(b[0]) or A.has(q):
            continue
        coeffs = list(A)
        plain = {k: sp.Dummy(k.func.__name__) for k in ind}
        cp = [sp.sympify(c).xreplace(plain) for c in coeffs]
        if any(c.has(t) for c in cp):
            continue
        P = [plain[k] for k in ind]
        exact = all(sp.simplify(sp.diff(cp[i], P[j]) - sp.diff(cp[j], P[i])) == 0
                    for i in range(len(P)) for j in range(i + 1, len(P)))
        if not exact:
            continue
        try:
            pot = sp.Integer(0)
            for i, Pi in enumerate(P):
                pot += sp.integrate(sp.simplify(cp[i] - sp.diff(pot, Pi)), Pi)
        except (NotImplementedError, ValueError):
            continue
        if pot.has(sp.Integral):
            continue
        back = {v: k for k, v in plain.items()}
        pot_t = pot.xreplace(back)
        q0 = system.coordinate_of(q).initial
        const = sp.Integer(0)
        if q0 is not None:
            const = sp.nsimplify(q0) - pot_t.xreplace(_initial(system, ind))
        solved[q] = kin.simplify_expr(pot_t + const)
        from_rates.add(q)
    red.coord_map = solved
    red.rate_integrated = frozenset(from_rates)


def _initial(system, coords) -> dict:
    out = {}
    for q in coords:
        c = system.coordinate_of(q)
        out[q] = sp.Integer(0) if c.initial is None else sp.nsimplify(c.initial)
    return out
