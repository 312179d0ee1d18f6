"""Equations of motion of a large constrained system, projected on the independent rates and evaluated numerically.

The joint symbolic solve of ``System.solve`` (every acceleration and reaction at once, dependent
rates eliminated in closed form) is what a person checks on paper, but for a system such as the
Whipple bicycle — four bodies, two rolling wheels, a holonomic constraint with no closed form — the
closed forms grow beyond any use.  The same laws are evaluated here numerically instead:

* every body's Euler's laws, F = m ā and M̄ = dH̄/dt with H̄ = Ī·ω, written for all coordinates:
  with u = q̇, v̄ = Jv u, ω = Jω u, ā = Jv q̈ + ā0, dH̄/dt = JH q̈ + h0;
* the generalised mass matrix and forcing of all coordinates, Mf = Σ m JvᵀJv + JωᵀJH and
  ff = Q − Σ (m Jvᵀ ā0 + Jωᵀ h0), Q the generalised active forces (the reactions are workless and
  drop out — which is checked, not assumed);
* the constraint rows A(q) q̇ + b = 0 that relate the rates: at a state, the dependent rates are
  u_d = −A_d⁻¹ (A_i u_i + b), the accelerations satisfy A q̈ + c0 = 0, and with the matrix of
  independent partial rates T = [I; −A_d⁻¹ A_i] the equations projected on the independent rates are
  (Tᵀ Mf T) u̇_i = Tᵀ (ff − Mf q̈p)   (Kane's equations; Maggi's form).

Only small symbolic pieces are built (partial velocities, remainder accelerations, constraint rows
and their derivatives); ``sympy.lambdify`` with common-subexpression elimination turns them into one
numeric function (numpy for simulation, mpmath for high-precision linearisation).  Holonomic
constraints among the rows (a gap that must stay zero, e.g. the front wheel touching the ground)
fix their dependent coordinates at any configuration by Newton's method.
"""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import mpmath
import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from .. import algebra
from ..errors import ConstraintError, ModelError, RigidkinError
from ..kinematics import Kinematics, linear_form

t = dynamicsymbols._t


@dataclass(frozen=True)
class Linearisation:
    """M δq̈ + C δq̇ + K δq = 0 about a motion, for the independent coordinates (rows) and the chosen
    perturbed coordinates (columns of K); ``M`` and ``C`` are square in the independent rates."""

    coordinates: tuple      # independent coordinates (rows of M, C, K; columns of M, C)
    perturbed: tuple        # the coordinates the columns of K refer to
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray

    def state_matrix(self, rates: Sequence | None = None) -> np.ndarray:
        """A of d/dt (δq_perturbed, δu_rates) = A (...), over the perturbed coordinates and ``rates``
        (the indices of the independent rates kept; default: those of the perturbed coordinates)."""
        idx = [self.coordinates.index(q) for q in self.perturbed]
        rates = idx if rates is None else list(rates)
        Minv = np.linalg.inv(self.M[np.ix_(rates, rates)])
        Kp = self.K[np.ix_(rates, range(len(self.perturbed)))]
        Cp = self.C[np.ix_(rates, rates)]
        n, k = len(self.perturbed), len(rates)
        A = np.zeros((n + k, n + k))
        for i, q in enumerate(self.perturbed):
            A[i, n + rates.index(self.coordinates.index(q))] = 1.0
        A[n:, :n] = -Minv @ Kp
        A[n:, n:] = -Minv @ Cp
        return A


class ProjectedModel:
    """Numeric equations of motion of ``system`` projected on its independent rates.

    ``independent`` lists the coordinates to keep (default: the first declared, as many as the
    degrees of freedom); ``mode`` maps contact names to states as in ``System.solve`` (sliding
    friction is not supported: its normal force does work).  Parameters take their declared values
    unless ``values`` (symbol or name → number) overrides them.
    """

    def __init__(self, system, independent: Sequence | None = None, mode: Mapping | None = None,
                 values: Mapping | None = None):
        self.system = system
        self.kin = kin = Kinematics(system)
        self.coordinates = tuple(system.coordinates)
        qs = list(self.coordinates)
        n = len(qs)
        self.rates = tuple(q.diff(t) for q in qs)
        accels = [q.diff(t, 2) for q in qs]
        # constraint rows -----------------------------------------------------------------------
        rows = []
        loads = list(system.loads.values())
        for name, c in system.constraints.items():
            st = (mode or {}).get(name) or c.default_state(kin)
            rows.extend(c.rows(kin, st))
            extra = c.loads(kin, st)
            if extra:
                raise ModelError("sliding friction makes its normal reaction do work, so the reactions cannot be "
                                 "projected out.", where=f"constraint {name}",
                                 hint="Use a rolling (stick) or smooth mode, or System.solve for this system.")
        relating = [r for r in rows if not algebra.is_zero(r.velocity)]
        self.rows = tuple(relating)
        if relating:
            A, b = linear_form([r.velocity for r in relating], list(self.rates))
        else:
            A, b = sp.zeros(0, n), sp.zeros(0, 1)
        # A q̈ + c0 = 0: the rows' time derivatives with the accelerations set to zero
        zero_acc = {a: 0 for a in accels}
        c0 = sp.Matrix([sp.diff(r.velocity, t).xreplace(zero_acc) for r in relating]) if relating \
            else sp.zeros(0, 1)
        gaps = [sp.sympify(r.gap) for r in relating if r.gap is not None and not algebra.is_zero(r.gap)]
        # independent coordinates --------------------------------------------------------------------
        self._plain = {**{u: sp.Symbol(f"_u{i}", real=True) for i, u in enumerate(self.rates)},
                       **{q: sp.Symbol(f"_q{i}", real=True) for i, q in enumerate(qs)}}
        self.parameters = tuple(system.parameters.values())
        self._args = [sp.Symbol("_t", real=True)] + [self._plain[q] for q in qs] + \
                     [self._plain[u] for u in self.rates] + list(self.parameters)
        rng = random.Random(5)
        ref = {s: rng.uniform(0.2, 0.6) for s in self._args}
        Anum = np.array(self._sym(A).xreplace(ref).evalf(), dtype=float) if relating else np.zeros((0, n))
        rank = np.linalg.matrix_rank(Anum, tol=1e-9) if relating else 0
        if rank < len(relating):
            raise ConstraintError(f"{len(relating) - rank} of the constraint rows repeat the others.",
                                  where=system.name, hint="Remove the redundant constraint.")
        if independent is None:
            dep_idx: list[int] = []
            for i in reversed(range(n)):
                trial = dep_idx + [i]
                if np.linalg.matrix_rank(Anum[:, trial], tol=1e-9) == len(trial):
                    dep_idx = trial
                if len(dep_idx) == rank:
                    break
            dep_idx.sort()
        else:
            keep = set(independent)
            dep_idx = [i for i, q in enumerate(qs) if q not in keep]
            if len(dep_idx) != rank or (rank and np.linalg.matrix_rank(Anum[:, dep_idx], tol=1e-9) < rank):
                raise ConstraintError("the constraints cannot determine the rates of "
                                      + ", ".join(qs[i].func.__name__ for i in dep_idx) + ".", where=system.name,
                                      hint=f"Choose {n - rank} independent coordinates.")
        self.dependent_index = tuple(dep_idx)
        self.independent_index = tuple(i for i in range(n) if i not in dep_idx)
        self.independent = tuple(qs[i] for i in self.independent_index)
        self.dependent = tuple(qs[i] for i in dep_idx)
        # bodies: partial velocities, remainder accelerations; active forces ------------------------
        Fr = kin.F.ref
        pieces: list[sp.Matrix] = []
        self._bodies = []
        self._partials_cache: dict = {}
        for body in system.bodies.values():
            if body.is_massless:
                raise ModelError("a massless body has no inertia to project; fold it into its neighbours.",
                                 where=f"body {body.name}")
            G = body.centre
            w = kin.omega_of(body)
            pv, pw = self._body_partials(body)
            I = body.inertia
            a0 = algebra.substitute(kin.acceleration(G), zero_acc)
            h0 = I.dot(algebra.substitute(kin.alpha(body.frame), zero_acc)) + w.cross(I.dot(w))
            Jv = sp.Matrix.hstack(*[_vec(p, Fr) for p in pv])
            Jw = sp.Matrix.hstack(*[_vec(p, Fr) for p in pw])
            JH = sp.Matrix.hstack(*[_vec(I.dot(p), Fr) for p in pw])
            self._bodies.append((body.name, len(pieces)))
            pieces += [body.mass * sp.ones(1, 1), Jv, _vec(a0, Fr), Jw, JH, _vec(h0, Fr)]
        Q = sp.zeros(n, 1)
        for ld in loads:
            for app in ld.applications(kin):
                Q += self._generalised(app)
        reaction_apps = [app for r in rows for app in r.applications]
        per: dict = {}
        for app in reaction_apps:
            unit = algebra.substitute(app.vector, {app.reaction: 1})
            per[app.reaction] = per.get(app.reaction, sp.zeros(n, 1)) + self._generalised(app, unit)
        self._reaction_syms = list(per)
        self._reaction_cols = self._sym(sp.Matrix.hstack(*per.values())) if per else None
        self._n_gaps = len(gaps)
        self._n_rows = len(relating)
        gq = sp.Matrix(gaps) if gaps else sp.zeros(1, 1)
        # empty blocks travel as one zero row (lambdify has no empty matrices); _raw drops them again
        pieces += [Q, A if relating else sp.zeros(1, n), b if relating else sp.zeros(1, 1),
                   c0 if relating else sp.zeros(1, 1), gq, gq.jacobian(qs) if gaps else sp.zeros(1, n)]
        self._pieces = [self._sym(P) for P in pieces]
        extra = set().union(*[P.free_symbols for P in self._pieces]) - set(self._args)
        if extra:
            raise RigidkinError(f"the equations contain {', '.join(sorted(map(str, extra)))}, which is neither a "
                                "coordinate, a rate, time nor a parameter.", where=system.name)
        self._fn = {}
        self.values = self._values(values)
        self._checked = False

    # symbolic helpers ---------------------------------------------------------------------------
    def _sym(self, M) -> sp.Matrix:
        """q(t), q̇ → plain symbols; t → _t (one pass: xreplace meets q̇ before the q inside it)."""
        return sp.Matrix(M).xreplace({**self._plain, t: self._args[0]})

    def _body_partials(self, body) -> tuple[list, list]:
        """Partial velocities of the mass centre and partial angular velocities of ``body``."""
        key = ("body", body.name)
        if key not in self._partials_cache:
            self._partials_cache[key] = (self._partial(self.kin.velocity(body.centre)),
                                         self._partial(self.kin.omega_of(body)))
        return self._partials_cache[key]

    def _partial(self, vel) -> list:
        """Partial velocities ∂vel/∂q̇_j (vectors, differentiated component by component in their frames)."""
        Fr = self.kin.F.ref
        return [vel.diff(u, Fr, var_in_dcm=False) if vel != 0 else vel for u in self.rates]

    def _generalised(self, app, vector=None) -> sp.Matrix:
        """Generalised force of one application: ∂v_P/∂q̇_j · F (or ∂ω/∂q̇_j · T for a torque)."""
        kin = self.kin
        if app.is_torque:
            key = ("ω", app.body.name)

            def make():
                return self._body_partials(app.body)[1]
        else:
            loc = app.location if app.location is not None else kin.position(app.point)
            key = (app.body.name, app.point.name if app.location is None else id(app.location))

            def make():
                # v_P = v_G + ω × (r_P − r_G): ∂v_P/∂q̇ = ∂v_G/∂q̇ + ∂ω/∂q̇ × (r_P − r_G), r_P free of rates
                pv, pw = self._body_partials(app.body)
                r = loc - kin.position(app.body.centre)
                return [a + b.cross(r) if b != 0 else a for a, b in zip(pv, pw)]
        if key not in self._partials_cache:
            self._partials_cache[key] = make()
        vec = app.vector if vector is None else vector
        return sp.Matrix([p.dot(vec) if p != 0 else 0 for p in self._partials_cache[key]])

    def _values(self, values) -> dict:
        vals = dict(self.system.parameter_values())
        for k, v in (values or {}).items():
            sym = self.system.parameters[k] if isinstance(k, str) else k
            vals[sym] = v
        missing = [p for p in self.parameters if p not in vals]
        if missing:
            raise ModelError(f"the parameters {', '.join(map(str, missing))} have no values.", where=self.system.name,
                             hint="Declare value= for each parameter or pass values={name: number}.")
        return vals

    def _function(self, kind: str, level: str = "all"):
        """The pieces as one numeric function: "numpy" (lambdify with CSE), "mpmath" (any precision) or
        "c" (compiled by rigidkin.numeric.codegen; numpy where no C compiler is found).  ``level="q"``:
        only the configuration-level pieces (constraint matrix, gaps), cheaper where rates are not needed."""
        key = (kind, level)
        if key not in self._fn:
            pieces = list(self._pieces) if level == "all" else [self._pieces[i] for i in (-5, -4, -2, -1)]
            if kind == "c":
                from .codegen import c_backend

                shapes = [P.shape for P in pieces]
                flat_fn = c_backend(self._args, [e for P in pieces for e in P])

                def unpack(*a):
                    flat, out, k = np.asarray(flat_fn(*a), dtype=float).ravel(), [], 0
                    for r, c in shapes:
                        out.append(flat[k:k + r * c].reshape(r, c))
                        k += r * c
                    return out

                self._fn[key] = unpack
            else:
                self._fn[key] = sp.lambdify(self._args, pieces, modules="mpmath" if kind == "mpmath" else "numpy",
                                            cse=True)
        return self._fn[key]

    # evaluation ---------------------------------------------------------------------------------
    def _param_vector(self, kind, values=None):
        vals = self.values if values is None else self._values(values)
        if kind == "mpmath":
            return [v if isinstance(v, mpmath.mpf) else mpmath.mpf(sp.Float(sp.sympify(v), mpmath.mp.dps + 5))
                    for v in (vals[p] for p in self.parameters)]
        return [float(vals[p]) for p in self.parameters]

    def _raw_q(self, kind, t_, q, p):
        """(A, b, gaps, their Jacobian) at the configuration q (None where there are none)."""
        out = list(self._function(kind, "q")(t_, *q, *([0] * len(self.coordinates)), *p))
        if kind != "mpmath":
            out = [np.array(o, dtype=float) for o in out]
        A, b = (out[0], out[1]) if self._n_rows else (None, None)
        g, J = (out[2], out[3]) if self._n_gaps else (None, None)
        return A, b, g, J

    def _raw(self, kind, t_, q, u, p):
        if not self._checked:
            self._checked = True          # (the check itself evaluates the pieces)
            try:
                self._check_workless()
            except ModelError:
                self._checked = False
                raise
        out = list(self._function(kind)(t_, *q, *u, *p))
        if kind != "mpmath":
            out = [np.array(o, dtype=float) for o in out]
        if not self._n_rows:
            out[-5] = out[-4] = out[-3] = None
        if not self._n_gaps:
            out[-2] = out[-1] = None
        return out

    def rates_of(self, q, ui, t_: float = 0.0, kind: str = "numpy", values=None):
        """All rates q̇ at the configuration ``q`` (all coordinates) for independent rates ``ui``."""
        p = self._param_vector(kind, values)
        return self._rates(kind, t_, q, ui, p)

    def _rates(self, kind, t_, q, ui, p):
        n = len(self.coordinates)
        A, b, _, _ = self._raw_q(kind, t_, q, p)
        return _full_rates(kind, A, b, ui, self.independent_index, self.dependent_index, n)

    def accelerations(self, q, ui, t_: float = 0.0, kind: str = "numpy", values=None):
        """(q̇ of every coordinate, u̇ of the independent rates) at the state (q, u_i)."""
        p = self._param_vector(kind, values)
        u = self._rates(kind, t_, q, ui, p)
        out = self._raw(kind, t_, q, list(u), p)
        return u, _project(kind, out, self._bodies, len(self.coordinates), self.independent_index,
                           self.dependent_index)[0]

    def mass_matrix(self, q, ui, t_: float = 0.0, kind: str = "numpy", values=None):
        """The projected mass matrix Tᵀ Mf T at (q, u_i)."""
        p = self._param_vector(kind, values)
        u = self._rates(kind, t_, q, ui, p)
        out = self._raw(kind, t_, q, list(u), p)
        return _project(kind, out, self._bodies, len(self.coordinates), self.independent_index,
                        self.dependent_index)[1]

    def gaps(self, q, t_: float = 0.0, kind: str = "numpy", values=None):
        """The holonomic constraint gaps (zero on the constraint) and their Jacobian in q."""
        p = self._param_vector(kind, values)
        _, _, g, J = self._raw_q(kind, t_, q, p)
        return g, J

    def rhs(self, values=None, backend: str = "numpy"):
        """f(t, y) for y = (q of every coordinate, u_i): dy/dt = (q̇, u̇_i), for scipy's solve_ivp.

        ``backend``: "numpy" (lambdify with CSE) or "c" (generated C, rigidkin.numeric.codegen)."""
        if backend not in ("numpy", "c"):
            raise ModelError(f"unknown backend {backend!r}.", where="rhs", hint="Use 'numpy' or 'c'.")
        p = self._param_vector("numpy", values)
        n = len(self.coordinates)

        def f(t_, y):
            u = self._rates(backend, t_, y[:n], y[n:], p)
            out = self._raw(backend, t_, y[:n], list(u), p)
            ud = _project(backend, out, self._bodies, n, self.independent_index, self.dependent_index)[0]
            return np.concatenate([u, ud])

        return f

    # configuration --------------------------------------------------------------------------------
    def holonomic_coordinates(self) -> tuple:
        """The dependent coordinates that the gaps fix (one per gap), found from the gaps' Jacobian."""
        if not self._n_gaps:
            return ()
        rng = random.Random(2)
        q = [rng.uniform(0.1, 0.3) for _ in self.coordinates]
        _, J = self.gaps(q)
        J = np.atleast_2d(J)
        chosen: list[int] = []
        for i in reversed(self.dependent_index):
            trial = chosen + [i]
            if np.linalg.matrix_rank(J[:, trial], tol=1e-9) == len(trial):
                chosen = trial
            if len(chosen) == self._n_gaps:
                break
        if len(chosen) < self._n_gaps:
            raise ConstraintError("the holonomic constraints do not fix any set of dependent coordinates.",
                                  where=self.system.name)
        return tuple(sorted(chosen))

    def configuration(self, q, kind: str = "numpy", values=None, tol=None, max_iter: int = 50):
        """``q`` with the holonomic dependent coordinates corrected (Newton) so that every gap vanishes."""
        idx = self.holonomic_coordinates()
        if not idx:
            return list(q)
        q = list(q)
        tol = tol if tol is not None else (1e-14 if kind != "mpmath" else mpmath.mpf(10) ** (-mpmath.mp.dps + 5))
        for _ in range(max_iter):
            g, J = self.gaps(q, kind=kind, values=values)
            if kind == "mpmath":
                Jd = mpmath.matrix([[J[r, c] for c in idx] for r in range(len(idx))])
                dq = mpmath.lu_solve(Jd, g)
                step = max(abs(x) for x in dq)
                for k, i in enumerate(idx):
                    q[i] -= dq[k]
            else:
                J = np.atleast_2d(J)
                dq = np.linalg.solve(J[:, idx], np.ravel(g))
                step = float(np.abs(dq).max())
                for k, i in enumerate(idx):
                    q[i] = q[i] - dq[k]
            if step < tol:
                return q
        raise RigidkinError("Newton's method did not close the holonomic constraints.", where=self.system.name,
                            hint="Start from a configuration closer to one the constraints allow.")

    # checks -------------------------------------------------------------------------------------
    def _check_workless(self) -> None:
        """Every reaction's generalised force, projected on the independent rates, must vanish (checked
        at two random states before the first numeric result is given)."""
        rng = random.Random(9)
        n = len(self.coordinates)
        for _ in range(2):
            q = [rng.uniform(-0.3, 0.3) for _ in range(n)]
            ui = [rng.uniform(-1, 1) for _ in self.independent_index]
            p = self._param_vector("numpy")
            try:
                q = self.configuration(q)
                u = self._rates("numpy", 0.0, q, ui, p)
            except (RigidkinError, np.linalg.LinAlgError):
                continue
            out = self._raw("numpy", 0.0, q, list(u), p)
            Tm = _partials("numpy", out[-5], self.independent_index, self.dependent_index, n)
            if self._reaction_cols is None:
                return
            cols = np.array(sp.lambdify(self._args, self._reaction_cols, modules="numpy", cse=True)(0.0, *q, *u, *p),
                            dtype=float)
            for j, sym in enumerate(self._reaction_syms):
                col = cols[:, j]
                proj = Tm.T @ col
                if np.abs(proj).max() > 1e-8 * max(1.0, np.abs(col).max()):
                    raise ModelError(f"the reaction {sym} does work on the independent motions, so it cannot be "
                                     "projected out.", where=self.system.name,
                                     hint="Use System.solve, which keeps the reactions as unknowns.")
            return

    # linearisation --------------------------------------------------------------------------------
    def linearise(self, q, ui, perturb: Sequence, values=None, dps: int = 40, step: float = 1e-15) -> Linearisation:
        """M δq̈ + C δq̇ + K δq = 0 about the state (q, u_i), with the columns of K for ``perturb``.

        Derivatives by central differences in ``dps``-digit arithmetic (mpmath): with the step
        1e-15 their error is below 1e-25, far below double precision.  The holonomic dependent
        coordinates follow each perturbation (Newton); the others keep their values.
        """
        pert = list(perturb)
        bad = [q_ for q_ in pert if q_ not in self.independent]
        if bad:
            names = ", ".join(q_.func.__name__ for q_ in self.independent)
            raise ModelError(f"{', '.join(q_.func.__name__ for q_ in bad)} are not independent coordinates.",
                             where="linearise", hint=f"Independent: {names}.")
        with mpmath.workdps(dps):
            h = mpmath.mpf(step)
            q0 = self.configuration([mpmath.mpf(sp.Float(sp.sympify(x), dps + 5)) for x in q], kind="mpmath",
                                    values=values)
            u0 = [mpmath.mpf(sp.Float(sp.sympify(x), dps + 5)) for x in ui]
            M = self.mass_matrix(q0, u0, kind="mpmath", values=values)
            k = len(u0)

            def acc(qq, uu):
                return self.accelerations(qq, uu, kind="mpmath", values=values)[1]

            dK = []
            for qv in pert:
                i = self.coordinates.index(qv)
                qp, qm = list(q0), list(q0)
                qp[i] += h
                qm[i] -= h
                qp = self.configuration(qp, kind="mpmath", values=values)
                qm = self.configuration(qm, kind="mpmath", values=values)
                ap, am = acc(qp, u0), acc(qm, u0)
                dK.append([(ap[r] - am[r]) / (2 * h) for r in range(k)])
            dC = []
            for j in range(k):
                up, um = list(u0), list(u0)
                up[j] += h
                um[j] -= h
                ap, am = acc(q0, up), acc(q0, um)
                dC.append([(ap[r] - am[r]) / (2 * h) for r in range(k)])
            Dk = mpmath.matrix([[dK[c][r] for c in range(len(pert))] for r in range(k)]) if pert else None
            Dc = mpmath.matrix([[dC[c][r] for c in range(k)] for r in range(k)])
            Kmat = -(M * Dk) if pert else mpmath.matrix(k, 0)
            Cmat = -(M * Dc)
            tonp = lambda X: np.array([[float(X[r, c]) for c in range(X.cols)] for r in range(X.rows)])  # noqa: E731
            return Linearisation(self.independent, tuple(pert), tonp(M), tonp(Cmat),
                                 tonp(Kmat) if pert else np.zeros((k, 0)))


# numeric assembly ----------------------------------------------------------------------------------
def _vec(v, frame) -> sp.Matrix:
    return sp.zeros(3, 1) if v == 0 else v.to_matrix(frame)


def _solve(kind, A, b):
    if kind == "mpmath":
        return mpmath.lu_solve(A, b)
    return np.linalg.solve(A, b)


def _cols(kind, A, idx):
    if kind == "mpmath":
        return mpmath.matrix([[A[r, c] for c in idx] for r in range(A.rows)])
    return A[:, list(idx)]


def _full_rates(kind, A, b, ui, ind, dep, n):
    u = [0] * n if kind == "mpmath" else np.zeros(n)
    for k, i in enumerate(ind):
        u[i] = ui[k]
    if dep:
        Ai, Ad = _cols(kind, A, ind), _cols(kind, A, dep)
        if kind == "mpmath":
            rhs = -(Ai * mpmath.matrix(list(ui)) + b)
        else:
            rhs = -(Ai @ np.asarray(ui, dtype=float) + np.ravel(b))
        ud = _solve(kind, Ad, rhs)
        for k, i in enumerate(dep):
            u[i] = ud[k]
    return u


def _partials(kind, A, ind, dep, n):
    """T (n × k): the rates of all coordinates per unit independent rate."""
    k = len(ind)
    if kind == "mpmath":
        T = mpmath.matrix(n, k)
        for c, i in enumerate(ind):
            T[i, c] = 1
        if dep:
            X = mpmath.inverse(_cols(kind, A, dep)) * (-_cols(kind, A, ind))
            for r, i in enumerate(dep):
                for c in range(k):
                    T[i, c] = X[r, c]
        return T
    T = np.zeros((n, k))
    T[list(ind), range(k)] = 1.0
    if dep:
        T[list(dep), :] = np.linalg.solve(A[:, list(dep)], -A[:, list(ind)])
    return T


def _project(kind, out, bodies, n, ind, dep):
    """(u̇_i, projected mass matrix) from the evaluated pieces."""
    Q, A, _b, c0 = out[-6], out[-5], out[-4], out[-3]
    if kind == "mpmath":
        Mf = mpmath.matrix(n, n)
        ff = mpmath.matrix(Q) if Q is not None else mpmath.matrix(n, 1)
        for _, s in bodies:
            m, Jv, a0, Jw, JH, h0 = out[s:s + 6]
            m = m[0, 0]
            Mf += m * (Jv.T * Jv) + Jw.T * JH
            ff -= m * (Jv.T * a0) + Jw.T * h0
    else:
        Mf = np.zeros((n, n))
        ff = np.ravel(Q).astype(float).copy()
        for _, s in bodies:
            m, Jv, a0, Jw, JH, h0 = out[s:s + 6]
            m = float(np.ravel(m)[0])
            Mf += m * (Jv.T @ Jv) + Jw.T @ JH
            ff -= m * (Jv.T @ np.ravel(a0)) + Jw.T @ np.ravel(h0)
    T = _partials(kind, A, ind, dep, n)
    if dep:
        # particular accelerations: independent part zero, dependent part from A q̈ + c0 = 0
        if kind == "mpmath":
            xd = mpmath.lu_solve(_cols(kind, A, dep), -c0)
            qp = mpmath.matrix(n, 1)
            for r, i in enumerate(dep):
                qp[i] = xd[r]
        else:
            xd = np.linalg.solve(A[:, list(dep)], -np.ravel(c0))
            qp = np.zeros(n)
            qp[list(dep)] = xd
    else:
        qp = mpmath.matrix(n, 1) if kind == "mpmath" else np.zeros(n)
    if kind == "mpmath":
        Mr = T.T * Mf * T
        fr = T.T * (ff - Mf * qp)
        return mpmath.lu_solve(Mr, fr), Mr
    Mr = T.T @ Mf @ T
    fr = T.T @ (ff - Mf @ qp)
    return np.linalg.solve(Mr, fr), Mr
