"""Equations of motion of a large constrained system, projected on the independent rates and evaluated numerically.

The joint symbolic solve of ``System.solve`` (every acceleration and reaction at once, dependent
rates eliminated in closed form) is what a person checks on paper, but for a system such as the
Whipple bicycle — four bodies, two rolling wheels, a holonomic constraint with no closed form — the
closed forms grow beyond any use.  The same laws are evaluated here numerically instead:

* every body's Euler's laws, F = m ā and M̄ = dH̄/dt with H̄ = Ī·ω, written for all speeds u: the
  rates q̇ where nothing else is said, a body's angular-velocity components where its frame is
  oriented by a quaternion or asks for them (``rigidkin.model.speeds``; q̇ = W(q) u), so that
  v̄ = Jv u, ω = Jω u, ā = Jv u̇ + ā0, dH̄/dt = JH u̇ + h0;
* the generalised mass matrix and forcing of all coordinates, Mf = Σ m JvᵀJv + JωᵀJH and
  ff = Q − Σ (m Jvᵀ ā0 + Jωᵀ h0), Q the generalised active forces (the reactions are workless and
  drop out — which is checked, not assumed);
* the constraint rows A(q) u + b = 0 that relate the speeds: at a state, the dependent speeds are
  u_d = −A_d⁻¹ (A_i u_i + b), the accelerations satisfy A u̇ + c0 = 0, and with the matrix of
  independent partial rates T = [I; −A_d⁻¹ A_i] the equations projected on the independent speeds are
  (Tᵀ Mf T) u̇_i = Tᵀ (ff − Mf u̇p)   (Kane's equations; Maggi's form);
* the state is (q, u_i) and the coordinates follow the kinematic equations q̇ = W(q) u; Euler
  parameters are pulled back to |e| = 1 by the stabilisation term k (1 − |e|²) e, which changes no
  rotation (the frame turns by e/|e|).

Only small symbolic pieces are built (partial velocities, remainder accelerations, constraint rows
and their derivatives); ``sympy.lambdify`` with common-subexpression elimination turns them into one
numeric function (numpy for simulation, mpmath for high-precision linearisation).  Holonomic
constraints among the rows (a gap that must stay zero, e.g. the front wheel touching the ground)
fix their dependent coordinates at any configuration by Newton's method (:mod:`rigidkin.numeric.large.closure`).
"""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence

import mpmath
import numpy as np
import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ...base import algebra, vectorops
from ...base.errors import ConstraintError, ModelError, RigidkinError
from ...derive.kinematics import Kinematics, linear_form
from ...model.speeds import STABILISATION, speeds_of
from ..compiled.codegen import c_backend
from .closure import configuration, holonomic_coordinates
from .linearise import linearise, state_matrix
from .projected_assembly import _full_rates, _partials, _project, _vec

t = dynamicsymbols._t


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
        self.kinematic = ke = speeds_of(system)
        self.coordinates = tuple(ke.configuration)
        qs = list(self.coordinates)
        self.speeds = tuple(ke.speeds)
        nu = len(self.speeds)
        self.rates = self.speeds
        accels = [u.diff(t) for u in self.speeds]
        self._ke = ke.substitute
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
        velocities = [self._ke(r.velocity) for r in relating]
        if relating:
            A, b = linear_form(velocities, list(self.speeds))
        else:
            A, b = sp.zeros(0, nu), sp.zeros(0, 1)
        # A u̇ + c0 = 0: the rows' time derivatives (q̇ = W u again) with the speeds' rates set to zero
        zero_acc = {a: 0 for a in accels}
        # (rows linear in the speeds: d/dt (A u + b) with u̇ = 0 is Ȧ u + ḃ, no product rule through u)
        dA = algebra.time_derivatives(list(A) + list(b)) if relating else []   # shared subtrees once
        c0 = sp.Matrix([self._ke(sum((dA[i * A.cols + j] * u for j, u in enumerate(self.speeds) if A[i, j] != 0),
                                     dA[A.rows * A.cols + i])) for i in range(A.rows)]) \
            if relating else sp.zeros(0, 1)
        if relating and algebra.atoms_of(c0, sp.Derivative) & set(accels):    # A or b holding a speed
            c0 = c0.xreplace(zero_acc)
        gaps = [sp.sympify(r.gap) for r in relating if r.gap is not None and not algebra.is_zero(r.gap)]
        # independent speeds -------------------------------------------------------------------------
        self._plain = {**{u: sp.Symbol(f"_u{i}", real=True) for i, u in enumerate(self.speeds)},
                       **{q: sp.Symbol(f"_q{i}", real=True) for i, q in enumerate(qs)}}
        self.parameters = tuple(system.parameters.values())
        self._args = [sp.Symbol("_t", real=True)] + [self._plain[q] for q in qs] + \
                     [self._plain[u] for u in self.speeds] + list(self.parameters)
        rng = random.Random(5)
        ref = {s: rng.uniform(0.2, 0.6) for s in self._args}
        Anum = np.array(algebra.evaluate(list(self._sym(A)), ref), dtype=complex).real.reshape(A.shape) \
            if relating else np.zeros((0, nu))
        rank = np.linalg.matrix_rank(Anum, tol=1e-9) if relating else 0
        if rank < len(relating):
            raise ConstraintError(f"{len(relating) - rank} of the constraint rows repeat the others.",
                                  where=system.name, hint="Remove the redundant constraint.")
        # a speed is named by its coordinate where it is that coordinate's rate
        self._speed_names = tuple(u.expr if isinstance(u, sp.Derivative) else u for u in self.speeds)
        if independent is None:
            dep_idx: list[int] = []
            for i in reversed(range(nu)):
                trial = dep_idx + [i]
                if np.linalg.matrix_rank(Anum[:, trial], tol=1e-9) == len(trial):
                    dep_idx = trial
                if len(dep_idx) == rank:
                    break
            dep_idx.sort()
        else:
            keep = set(independent)
            unknown = [k for k in keep if k not in self._speed_names]
            if unknown:
                raise ModelError(f"{', '.join(map(str, unknown))} name no speed of the model.", where=system.name,
                                 hint="Speeds: " + ", ".join(map(str, self._speed_names)) + ".")
            dep_idx = [i for i, q in enumerate(self._speed_names) if q not in keep]
            if len(dep_idx) != rank or (rank and np.linalg.matrix_rank(Anum[:, dep_idx], tol=1e-9) < rank):
                raise ConstraintError("the constraints cannot determine the speeds "
                                      + ", ".join(str(self._speed_names[i]) for i in dep_idx) + ".",
                                      where=system.name, hint=f"Choose {nu - rank} independent speeds.")
        self.dependent_index = tuple(dep_idx)
        self.independent_index = tuple(i for i in range(nu) if i not in dep_idx)
        self.independent = tuple(self._speed_names[i] for i in self.independent_index)
        self.dependent = tuple(self._speed_names[i] for i in dep_idx)
        n = nu
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
            pv, pw = self._body_partials(body)
            a0 = algebra.substitute(self._ke(kin.acceleration(G)), zero_acc)
            Jv = sp.Matrix.hstack(*[_vec(p, Fr) for p in pv])
            # the rotational pieces in the body's own basis, where its central inertia Ī is constant:
            # ω, α and the partial angular velocities are resolved once, H̄ = Ī ω by a constant matrix
            Bf = body.frame.ref
            Ib = body.inertia.to_matrix(Bf)
            w = _vec(self._ke(kin.omega_of(body)), Bf)
            alpha0 = _vec(algebra.substitute(self._ke(kin.alpha(body.frame)), zero_acc), Bf)
            Jw = sp.Matrix.hstack(*[_vec(p, Bf) for p in pw])
            h0 = Ib * alpha0 + w.cross(Ib * w)
            self._bodies.append((body.name, len(pieces)))
            pieces += [body.mass * sp.ones(1, 1), Jv, _vec(a0, Fr), Jw, Ib * Jw, h0]
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
                   c0 if relating else sp.zeros(1, 1), gq]
        self._pieces = [self._sym(P) for P in pieces]
        # ∂gap/∂q on the plain symbols (sympy differentiates a symbol far faster than a function of time)
        self._pieces.append(self._pieces[-1].jacobian([self._plain[q] for q in qs]) if gaps
                            else sp.zeros(1, len(qs)))
        extra = algebra.atoms_of([e for P in self._pieces for e in P], sp.Symbol) - set(self._args)
        if extra:
            raise RigidkinError(f"the equations contain {', '.join(sorted(map(str, extra)))}, which is neither a "
                                "coordinate, a rate, time nor a parameter.", where=system.name)
        self._fn = {}
        self.values = self._values(values)
        self._checked = False

    # symbolic helpers ---------------------------------------------------------------------------
    def _sym(self, M) -> sp.Matrix:
        """q(t), q̇ → plain symbols; t → _t, as ``xreplace`` does (q̇ met before the q inside it), with one memo
        for every entry of every matrix: the pieces share most of their subexpressions."""
        memo = self.__dict__.setdefault("_sym_memo", {})
        M = sp.Matrix(M)
        if not (M.rows and M.cols):
            return M
        return sp.Matrix(M.rows, M.cols, algebra.xreplace_shared(list(M), {**self._plain, t: self._args[0]}, memo))

    def _body_partials(self, body) -> tuple[list, list]:
        """Partial velocities of the mass centre and partial angular velocities of ``body``."""
        key = ("body", body.name)
        if key not in self._partials_cache:
            self._partials_cache[key] = (self._partial(self._ke(self.kin.velocity(body.centre))),
                                         self._partial(self._ke(self.kin.omega_of(body))))
        return self._partials_cache[key]

    def _partial(self, vel) -> list:
        """Partial velocities ∂vel/∂u_j (vectors, differentiated component by component in their frames)."""
        if vel == 0:
            return [vel for _ in self.speeds]
        # the coefficients of the speeds, read in one pass per frame term (vel is linear in them)
        cols = [(linear_form(list(m), list(self.speeds))[0], fr) for m, fr in vel.args]
        return [Vector([(A.col(j), fr) for A, fr in cols]) for j in range(len(self.speeds))]

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
                return [a + vectorops.cross(b, r) if b != 0 else a for a, b in zip(pv, pw)]
        if key not in self._partials_cache:
            self._partials_cache[key] = make()
        vec = app.vector if vector is None else vector
        return sp.Matrix([vectorops.dot_vectors(p, vec) if p != 0 else 0 for p in self._partials_cache[key]])

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
        "c" (compiled by rigidkin.numeric.compiled.codegen; numpy where no C compiler is found).  ``level="q"``:
        only the configuration-level pieces (constraint matrix, gaps), cheaper where rates are not needed."""
        key = (kind, level)
        if key not in self._fn:
            pieces = list(self._pieces) if level == "all" else [self._pieces[i] for i in (-5, -4, -2, -1)]
            if kind == "c":
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
        out = list(self._function(kind, "q")(t_, *q, *([0] * len(self.speeds)), *p))
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
        """All speeds u at the configuration ``q`` (all coordinates) for independent speeds ``ui`` (the
        rates q̇ where the speeds are the rates; :meth:`coordinate_rates` gives q̇ = W(q) u)."""
        p = self._param_vector(kind, values)
        return self._rates(kind, t_, q, ui, p)

    def _rates(self, kind, t_, q, ui, p):
        n = len(self.speeds)
        if not self._n_rows:                  # no constraint relates the speeds: u = u_i
            return list(ui) if kind == "mpmath" else np.asarray(ui, dtype=float)
        A, b, _, _ = self._raw_q(kind, t_, q, p)
        return _full_rates(kind, A, b, ui, self.independent_index, self.dependent_index, n)

    def accelerations(self, q, ui, t_: float = 0.0, kind: str = "numpy", values=None):
        """(every speed u, u̇ of the independent speeds) at the state (q, u_i)."""
        p = self._param_vector(kind, values)
        u = self._rates(kind, t_, q, ui, p)
        out = self._raw(kind, t_, q, list(u), p)
        return u, _project(kind, out, self._bodies, len(self.speeds), self.independent_index,
                           self.dependent_index)[0]

    def mass_matrix(self, q, ui, t_: float = 0.0, kind: str = "numpy", values=None):
        """The projected mass matrix Tᵀ Mf T at (q, u_i)."""
        p = self._param_vector(kind, values)
        u = self._rates(kind, t_, q, ui, p)
        out = self._raw(kind, t_, q, list(u), p)
        return _project(kind, out, self._bodies, len(self.speeds), self.independent_index,
                        self.dependent_index)[1]

    def gaps(self, q, t_: float = 0.0, kind: str = "numpy", values=None):
        """The holonomic constraint gaps (zero on the constraint) and their Jacobian in q."""
        p = self._param_vector(kind, values)
        _, _, g, J = self._raw_q(kind, t_, q, p)
        return g, J

    def coordinate_rates(self, q, u, t_: float = 0.0, kind: str = "numpy", values=None):
        """q̇ = W(q) u of every coordinate, for every speed ``u`` (no stabilisation term)."""
        p = self._param_vector(kind, values)
        return self._qdot(kind, t_, q, u, p)

    def _qdot(self, kind, t_, q, u, p):
        key = (kind, "qdot")
        if key not in self._fn:
            exprs = self._sym(sp.Matrix(self.kinematic.rate_expressions()))
            self._fn[key] = sp.lambdify(self._args, exprs, modules="mpmath" if kind == "mpmath" else "numpy",
                                        cse=True)
        out = self._fn[key](t_, *q, *u, *p)
        if kind == "mpmath":
            return [out[i] for i in range(len(self.coordinates))]
        return np.ravel(np.array(out, dtype=float))

    def quaternion_slots(self) -> tuple:
        """For each frame oriented by Euler parameters, the slots of (e0, e1, e2, e3) in q."""
        return tuple(tuple(self.coordinates.index(e) for e in g.coordinates)
                     for g in self.kinematic.groups if g.kind == "quaternion")

    def rhs(self, values=None, backend: str = "numpy", stabilise: bool = True):
        """f(t, y) for y = (q of every coordinate, u_i): dy/dt = (W(q) u, u̇_i), for scipy's solve_ivp.

        ``backend``: "numpy" (lambdify with CSE) or "c" (generated C, rigidkin.numeric.compiled.codegen).
        ``stabilise``: Euler parameters get ė += k (1 − |e|²) e (k = ``model.speeds.STABILISATION`` times
        the largest |u|, at least 1/s), which holds |e| at 1 without changing the rotation."""
        if backend not in ("numpy", "c"):
            raise ModelError(f"unknown backend {backend!r}.", where="rhs", hint="Use 'numpy' or 'c'.")
        p = self._param_vector("numpy", values)
        n = len(self.coordinates)
        slots = [list(s) for s in self.quaternion_slots()] if stabilise else []

        fused = self._fused() if not self._n_rows and backend == "numpy" else None

        def f(t_, y):
            if fused is not None:                 # no constraint row: M(q) u̇ = f(q, u) and q̇ = W(q) u at once
                self._raw("numpy", t_, y[:n], list(y[n:]), p) if not self._checked else None
                out = fused(t_, *y[:n], *y[n:], *p)
                ud = np.linalg.solve(np.array(out[0], dtype=float), np.ravel(np.array(out[1], dtype=float)))
                qd = np.ravel(np.array(out[2], dtype=float))
                for sl in slots:
                    e = y[sl]
                    k = STABILISATION * max(1.0, float(np.max(np.abs(y[n:]))))
                    qd[sl] = qd[sl] + k * (1.0 - float(e @ e)) * e
                return np.concatenate([qd, ud])
            u = self._rates(backend, t_, y[:n], y[n:], p)
            out = self._raw(backend, t_, y[:n], list(u), p)
            ud = _project(backend, out, self._bodies, len(self.speeds), self.independent_index,
                          self.dependent_index)[0]
            qd = self._qdot("numpy", t_, y[:n], u, p) if not self.kinematic.trivial else np.asarray(u, dtype=float)
            if slots:
                k = STABILISATION * max(1.0, float(np.max(np.abs(u))) if len(u) else 1.0)
                for sl in slots:
                    e = y[sl]
                    qd[sl] = qd[sl] + k * (1.0 - float(e @ e)) * e
            return np.concatenate([qd, ud])

        return f

    def _fused(self):
        """One numeric function (t, q, u, p) → (M, f, q̇) for a model without constraint rows, where the
        speeds are all independent: M = Σ m JvᵀJv + JωᵀJH, f = Q − Σ (m Jvᵀā0 + Jωᵀh0), q̇ = W(q) u."""
        if ("fused",) not in self._fn:
            nu = len(self.speeds)
            M, f = sp.zeros(nu, nu), sp.Matrix(self._pieces[-6])
            for _, s in self._bodies:
                m, Jv, a0, Jw, JH, h0 = self._pieces[s:s + 6]
                M += m[0, 0] * (Jv.T * Jv) + Jw.T * JH
                f -= m[0, 0] * (Jv.T * a0) + Jw.T * h0
            qd = self._sym(sp.Matrix(self.kinematic.rate_expressions()))
            self._fn[("fused",)] = sp.lambdify(self._args, [M, f, qd], modules="numpy", cse=True)
        return self._fn[("fused",)]

    def state_matrix(self, q, ui, coordinates: Sequence, speeds: Sequence, values=None, dps: int = 40,
                     step: float = 1e-15) -> np.ndarray:
        """A of d/dt (δq, δu) = A (δq, δu) about (q, u_i): see :func:`rigidkin.numeric.large.linearise.state_matrix`."""

        return state_matrix(self, q, ui, coordinates, speeds, values, dps, step)

    # configuration --------------------------------------------------------------------------------
    def holonomic_coordinates(self) -> tuple:
        """The dependent coordinates the gaps fix: see :func:`rigidkin.numeric.large.closure.holonomic_coordinates`."""
        return holonomic_coordinates(self)

    def configuration(self, q, kind: str = "numpy", values=None, tol=None, max_iter: int = 50):
        """``q`` with every gap closed (Newton): see :func:`rigidkin.numeric.large.closure.configuration`."""
        return configuration(self, q, kind, values, tol, max_iter)

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
            Tm = _partials("numpy", out[-5], self.independent_index, self.dependent_index, len(self.speeds))
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
    def linearise(self, q, ui, perturb: Sequence, values=None, dps: int = 40, step: float = 1e-15):
        """M δq̈ + C δq̇ + K δq = 0 about (q, u_i): see :func:`rigidkin.numeric.large.linearise.linearise`."""

        return linearise(self, q, ui, perturb, values, dps, step)
