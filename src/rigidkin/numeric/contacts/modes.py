"""Hybrid modes: the state of every contact, what ends a mode, and which mode follows.

A mode is the state of every contact (``open``, ``slip``, ``stick``); within a mode a regime is the
direction of every sliding friction.  ``ModeModel`` holds the numeric functions of one regime: the
right-hand side, the reactions, and the *watches* — quantities whose zero ends the regime:

* a unilateral normal reaction N reaching zero (the contact opens);
* the gap of an open contact reaching zero (an impact);
* the slip speed of a slipping contact reaching zero (it may stick: rolling begins);
* the friction a sticking contact needs reaching ±µN (it starts to slip, in the direction in
  which the friction saturates);
* a regime condition of another sign choice reaching zero (the friction direction reverses).

``Hybrid`` derives each mode once (``system.solve(mode=...)``, cached by the system), and chooses the
mode and regime that are consistent at a state (``settle``): normal reactions that push, friction
within µN where it sticks, slip directions whose slip-speed rate has the slip's sign.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base import algebra
from ...base.errors import ModelError
from ...base.printing import text as show
from ...derive.derivation import derivation_of
from ...derive.laws.energy import kinetic_energy, nonconservative_power, potential_energy
from ...derive.laws.newton_euler import body_balances
from ...derive.mode import setup_mode
from ...model.constraints import ROLLING, SMOOTH, Contact, Coulomb
from ...model.inputs import input_symbols
from ..rhs import RegimeFunctions, compile_functions
from ..state import PositionConstraints, StateLayout, assemble
from .arc_support import arc_gap, arc_watches, dormant, extended, leaving_end, off_arc, parent_of
from .mode_model import ModeModel, Watch
from .settle import held_alternative, regime_at, settle
from .slack import TIGHTENS, slack_gap, with_offsets
from .slip3d import expand
from .vocabulary import OPEN, SLIP, STICK, ModeUnavailable, describe_mode, mode_key

t = dynamicsymbols._t


class Hybrid:
    """The modes of one system: derived once each, with their numeric functions and transitions."""

    def __init__(self, system, layout: StateLayout | None = None):
        self.layout = layout or StateLayout.of(system)
        self.system, self.edges = extended(system)     # the edges at the ends of half shapes' arcs (arc_support)
        self.base = system
        self.contacts = {n: c for n, c in self.system.constraints.items() if isinstance(c, Contact)}
        self._solutions: dict = {}
        self._models: dict = {}
        self._contact_fns: dict = {}
        self._rate_fns: dict = {}
        self._relation_fns: dict = {}
        self._depends: dict = {}
        self._kin = None
        self.free_lengths: dict = {}    # slack rope → the constant of its gap (set where it goes slack: .slack)

    # derivation ------------------------------------------------------------------------------
    def solution(self, mode: dict):
        """The Solution of ``mode`` (every contact named), or ModeUnavailable with the model's reason."""
        key = mode_key(mode)
        if key not in self._solutions:
            try:              # 3D slip: the direction relative to a reference tangent (slip3d.expand)
                system, mode_ = self._system_for(mode)
                sol = system.solve(mode=mode_, integrate=False)
                if sol.regimes[0].indeterminate:        # two supports holding a body: settle's held alternative
                    raise ModelError("statically indeterminate: " + ", ".join(sol.regimes[0].indeterminate.reactions)
                                     + " are not separated by the balance laws.")
                self._solutions[key] = expand(sol)
            except ModelError as exc:   # ConstraintError included
                self._solutions[key] = ModeUnavailable(
                    f"the mode ({describe_mode(self.system, mode)}) cannot be derived from the model: "
                    f"{exc.message}", where=self.system.name, hint=exc.hint)
        sol = self._solutions[key]
        if isinstance(sol, Exception):
            raise sol
        return sol

    def _system_for(self, mode: dict):
        """The system a mode is derived on: the one given while every edge is open (its own derivations,
        kept between runs), else the one with the edges."""
        if not self.edges:
            return self.system, dict(mode)
        if all(mode.get(e) == OPEN for es in self.edges.values() for e in es):
            return self.base, {n: s for n, s in mode.items() if n in self.base.constraints}
        return self.system, dict(mode)

    def derivable(self, mode: dict) -> dict:
        """``mode``, or where it is over-constrained (two supports that both hold a body from slipping) the same
        motion with the friction carried jointly (``settle.held_alternative``)."""
        try:
            self.solution(mode)
        except ModeUnavailable:
            return held_alternative(self, mode) or mode
        return mode

    @property
    def kin(self):
        if self._kin is None:
            self._kin = derivation_of(self.system).kinematics()
        return self._kin

    def default_mode(self, t_=None, y=None, p=None) -> dict:
        """Every contact closed: rolling contacts stick, the others slip (friction decides later).  The edges at
        the ends of arcs are open; given a state, an arc that does not touch there is open (arc_support)."""
        edges = {e for es in self.edges.values() for e in es}     # an edge touches only where its arc ends
        out = {n: (OPEN if n in edges else STICK if c.friction == ROLLING else SLIP) for n, c in self.contacts.items()}
        return out if y is None else {**out, **off_arc(self, t_, y, p)}

    def model(self, mode: dict, regime_index: int) -> ModeModel:
        key = (mode_key(mode), regime_index)
        if key not in self._models:
            self._models[key] = self._build(dict(mode), regime_index)
        return with_offsets(self._models[key], self.free_lengths)

    def _build(self, mode: dict, k: int) -> ModeModel:
        sol = self.solution(mode)
        reg = sol.regime(k)
        setup = sol.setup
        kin = setup.kin
        lay = self.layout
        signs = dict(reg.signs)
        present = set().union(*[e.expr.free_symbols for e in sol.equations]) if sol.equations else set()
        zero_r = {r: sp.Integer(0) for r in setup.reactions if r not in present}

        def R(sym):         # a reaction as a symbol the numeric functions fill in (0 if absent)
            return zero_r.get(sym, sym)

        # energy and the power of non-conservative loads and reactions

        T, U = kinetic_energy(setup), potential_energy(setup)
        powers = nonconservative_power(setup)
        P = sum((pw.power for pw in powers), sp.Integer(0)).xreplace(signs).xreplace(zero_r)
        conservative = all(pw.power == 0 for pw in powers)
        # watches
        watches, wexprs = [], []
        parents = parent_of(self)

        def watch(w, e):
            e = sp.sympify(e).xreplace(zero_r)
            plain = lay.to_plain(e)
            if not (plain.free_symbols - set(lay.parameter_symbols)):
                return None          # a constant never crosses zero
            watches.append(w)
            wexprs.append(e)
            return len(watches) - 1

        for name, c in self.contacts.items():
            for dom, what, why in (c.domain(kin) if hasattr(c, "domain") else ()):    # the geometry's validity
                watch(Watch("domain", name, what, -1, quantity=show(dom), detail=why), dom)
            st = mode[name]
            if st == OPEN and name in self.edges:       # an arc with edges (arc_support)
                arc_watches(self, mode, name, kin, watch, Watch)
                continue
            if st == OPEN and not dormant(self, mode, name):
                kind = "arc-impact" if name in parents else "impact"      # an edge: its arc's restitution
                watch(Watch(kind, name, f"impact at {name}", -1, quantity=f"gap of {name}"), c.gap(kin))
            if st == OPEN:
                continue
            if c.unilateral:
                watch(Watch("opens", name, f"contact {name} opens", -1, quantity=str(c.N)), R(c.N))
            if getattr(c, "arc", None) is not None:        # a profile that is an arc (model.profiles)
                watch(Watch("arc", name, f"contact {name} reaches the end of its arc", -1,
                            quantity=f"arc margin of {name}"), c.arc.margin(c, kin))
            if st == STICK and isinstance(c.friction, Coulomb):
                mu, N = c.friction.static, R(c.N)       # sticking holds while |F| ≤ µs N
                if kin.planar:
                    F = R(c.F)
                    # contacts held by this one carry their friction with it: their limits add up
                    spare = sum((self.contacts[h].friction.static * R(self.contacts[h].N)
                                 for h in getattr(setup, "held", ())), sp.Integer(0))
                    watch(Watch("slips", name, f"contact {name} starts to slip", -1, -1, f"µ{c.N} − {c.F}"),
                          mu * N + spare - F)
                    watch(Watch("slips", name, f"contact {name} starts to slip", -1, +1, f"µ{c.N} + {c.F}"),
                          mu * N + spare + F)
                else:
                    Fs = [R(r) for r in setup.reactions if str(r).startswith(str(c.F))]
                    watch(Watch("slips", name, f"contact {name} starts to slip", -1, quantity="friction cone"),
                          mu**2 * N**2 - sum((f**2 for f in Fs), sp.Integer(0)))
        for c in self.system.constraints.values():      # ropes and cables can only pull (model.ropes)
            if c.kind in ("rope", "cable") and mode.get(c.name) == OPEN:       # slack: its gap closing (.slack)
                gap, _ = slack_gap(c, kin, lay.coordinates)
                if gap is not None:
                    watch(Watch(TIGHTENS, c.name, f"{c.kind} {c.name} re-tightens", -1,
                                quantity=f"gap of {c.kind} {c.name}"), gap)
            elif c.kind in ("rope", "cable"):
                for tension in c.reactions():
                    watch(Watch("slack", c.name, f"{c.kind} {c.name} goes slack ({tension} = 0)", -1,
                                quantity=str(tension)), R(tension))
        conditions = []
        for sc in setup.sign_choices:
            if sc.symbol not in signs:
                continue
            sgn = int(signs[sc.symbol])
            q = (setup.scalar(sc.quantity) if sc.rate_based else R(sc.quantity)).xreplace(signs)
            kind = "sticks" if (sc.load in self.contacts and sc.rate_based
                                and isinstance(self.contacts[sc.load].friction, Coulomb)) else "reverses"
            label = f"contact {sc.load} stops slipping" if kind == "sticks" else f"{sc.label} changes sign"
            wi = watch(Watch(kind, sc.load, label, -1 if sgn > 0 else +1, quantity=show(kin.simplify_expr(q))), q)
            if wi is not None:
                conditions.append((wi, ">" if sgn > 0 else "<"))
        # constraint residuals: the gaps of the closed rows (position level)
        residual_names, rexprs = [], []
        for row in setup.rows:
            if row.gap is not None and row.gap != 0:
                residual_names.append(row.label.replace(": normal velocity", "").replace(": velocity along",
                                                                                           " along"))
                rexprs.append(row.gap)
        # friction forces along the contact tangent (stick: the reaction; slip: −µ N σ), and the limits µN
        friction_names, fexprs = [], []
        for name, c in self.contacts.items():
            if mode[name] == SLIP and isinstance(c.friction, Coulomb):
                sc = next((s_ for s_ in setup.sign_choices if s_.load == name and s_.rate_based), None)
                if sc is not None and sc.symbol in signs:
                    friction_names.append(str(c.F))
                    fexprs.append(-c.friction.mu * R(c.N) * signs[sc.symbol])
        for name, c in self.contacts.items():
            if isinstance(c.friction, Coulomb) and not (name in parents and mode[name] == OPEN):
                friction_names.append(f"mu*{c.N}")
                mu = c.friction.static if mode[name] == STICK else c.friction.kinetic
                fexprs.append(mu * R(c.N) if mode[name] != OPEN else sp.Integer(0))
        fns = RegimeFunctions(sol, k, lay, [P, *wexprs, *rexprs, T, U, *fexprs])
        model = ModeModel(self.system, mode, k, sol, lay, fns, watches, conditions, residual_names,
                          friction_names, conservative, self._steady(sol, reg, wexprs))
        model.steady = model.steady | _vanishing(model)       # identically zero reactions: no watch
        return model

    def _steady(self, sol, reg, wexprs) -> frozenset:
        """Watches that cannot cross zero in this regime, so they are no events even where they sit exactly
        at their limit (the tie rule: at the limit the state in force stays):

        * in a mode at rest (no degree of freedom) the state does not change, so a watch without explicit
          time (a load growing with t) keeps its value (tan β = µs: the block stays);
        * in any mode, a watch that with the regime's reactions depends on neither the state nor the time
          is a constant (a cylinder rolling down an incline at µs = tan β / 3 exactly: µN − F = 0 throughout,
          which rounding would otherwise cross back and forth)."""
        moving = bool(sol.coordinates) or any(self.layout.to_plain(v) != 0 for v in sol.rate_relations.values())
        react = {sp.Symbol(k, real=True): v for k, v in reg.reactions.items()}
        params = set(self.layout.parameter_symbols)
        out = set()
        for i, e in enumerate(wexprs):
            full = self.layout.to_plain(sp.sympify(e).xreplace(react))
            if full.has(t, *input_symbols(self.system)):      # an input u(t) varies too
                continue
            if not moving or not (full.free_symbols - params):
                out.add(i)
        return frozenset(out)

    # contact quantities in the full state ----------------------------------------------------------
    def contact_functions(self, name: str):
        """(gap(q), normal speed(q, q̇), slip speed(q, q̇) or None) of a contact, in every coordinate."""
        if name not in self._contact_fns:
            c = self.contacts[name]
            kin = self.kin
            exprs = list(arc_gap(c, kin)) if name in self.edges else [c.gap(kin), c.rows(kin, SLIP)[0].velocity]
            if kin.planar and c.friction != SMOOTH:
                exprs.append(c.slip_velocity(kin))
            f = compile_functions(self.layout.arguments(), [self.layout.to_plain(e) for e in exprs])
            self._contact_fns[name] = (f, len(exprs))
        return self._contact_fns[name]

    def contact_state(self, name: str, t_, y, p) -> tuple[float, float, float | None]:
        f, n = self.contact_functions(name)
        vals = [float(v) for v in f(t_, *y[:2 * self.layout.n], *p)]
        if name in self.edges and leaving_end(self, name, t_, y, p):      # the arc's end, leaving: the edge's
            vals[0] = abs(vals[0]) + float(self._param_value(self.contacts[name].radius, p))
        return vals[0], vals[1], (vals[2] if n > 2 else None)

    def relation_functions(self, mode: dict, integrated: bool = False):
        """(dependent coordinates' slots, q_d from the integrated relations, q̇_d from the rate relations).

        The mode's equations keep the coordinates found by integrating a rate relation (their constant
        depends on where the mode is entered); ``integrated=True`` adds those relations too, as an
        initial configuration needs them (constant from the declared initial values).
        """
        key = (mode_key(mode), integrated)
        if key not in self._relation_fns:
            sol = self.solution(mode)
            lay = self.layout
            red = sol.setup.reduction
            slots, exprs = [], []
            for q in sol.dependent:
                slots.append(lay.coordinates.index(q))
                exprs.append(red.rate_map[q.diff(t)])
            relations = dict(sol.relations)
            if integrated:
                relations = dict(setup_mode(*self._system_for(mode)).reduction.coord_map)
            rel_slots = [lay.coordinates.index(q) for q in relations]
            rel_fn = compile_functions(lay.arguments(), [lay.to_plain(v) for v in relations.values()])
            rate_fn = compile_functions(lay.arguments(), [lay.to_plain(e) for e in exprs])
            self._relation_fns[key] = (rel_slots, rel_fn, slots, rate_fn)
        return self._relation_fns[key]

    def position_constraints(self, mode: dict) -> PositionConstraints:
        """The bilateral position constraints of ``mode`` (pins, collars, bilateral contacts, loop closures) that a
        starting state must satisfy, with the dependent coordinates assembly may move."""
        key = ("positions", mode_key(mode))
        if key not in self._relation_fns:
            sol = self.solution(mode)
            red = sol.setup.reduction
            lay = self.layout
            # a unilateral contact's gap is an inequality: it opens or is refused (simulate.initial_conditions)
            rows = [r for r in red.relating if r.gap is not None and r.gap != 0 and not r.unilateral]
            labels = tuple(_row_name(r) for r in rows)
            fn = compile_functions(lay.arguments(), [lay.to_plain(r.gap) for r in rows]) if rows else None
            free = tuple(lay.coordinates.index(q) for q in red.dependent if q in lay.coordinates)
            self._relation_fns[key] = PositionConstraints(labels, fn, free)
        return self._relation_fns[key]

    def assemble(self, mode: dict, t_, y, p, where: str) -> np.ndarray:
        """The state with its coordinates put onto the mode's bilateral position constraints by Newton's method
        from the values given (:func:`rigidkin.numeric.state.assemble`), or InputError naming the constraint."""
        return assemble(self.position_constraints(mode), self.layout, t_, y, p, where)

    def project_rates(self, mode: dict, t_, y, p) -> np.ndarray:
        """The state with the dependent rates set from the rate relations of ``mode``."""
        _, _, slots, rate_fn = self.relation_functions(mode)
        y = np.array(y, dtype=float)
        if slots:
            vals = rate_fn(t_, *y[:2 * self.layout.n], *p)
            for s, v in zip(slots, vals):
                y[self.layout.n + s] = float(v)
        return y

    def relation_mismatch(self, mode: dict, t_, y, p, tol: float = 1e-7) -> list[tuple[str, float]]:
        """Integrated relations q_d = f(q_i) of ``mode`` that the state does not satisfy, when it matters.

        The core integrates an exact rate relation (r φ̇ = ẋ) from the declared initial configuration;
        a mode entered later (rolling after slipping) may have another constant of integration.  That
        only matters when the mode's balances depend on q_d; then the mode cannot be simulated here.
        """
        rel_slots, rel_fn, _, _ = self.relation_functions(mode)
        if not rel_slots:
            return []
        vals = rel_fn(t_, *y[:2 * self.layout.n], *p)
        out = []
        for s, v in zip(rel_slots, vals):
            d = float(y[s]) - float(v)
            if abs(d) > tol * max(1.0, abs(float(v))) and self._depends_on(mode, self.layout.coordinates[s]):
                out.append((self.layout.names[s], d))
        return out

    def _depends_on(self, mode: dict, q) -> bool:
        key = (mode_key(mode), q)
        if key not in self._depends:
            setup = self.solution(mode).setup
            F = setup.kin.F
            dep = False
            for bal in body_balances(setup):
                for v in (bal.force, bal.moment, bal.mass_accel, bal.momentum_rate):
                    for e in (F.x, F.y, F.z):
                        s = v.dot(e)
                        if s != 0 and s.has(q) and not algebra.is_zero(sp.diff(s, q)):
                            dep = True
                            break
            self._depends[key] = dep
        return self._depends[key]

    # choosing a consistent mode (numeric/settle.py) ---------------------------------------------------
    def regime_at(self, mode: dict, t_, y, p, forced: dict | None = None, zero_tol: float = 1e-9) -> int:
        """The regime of ``mode`` whose conditions hold at the state (see :func:`settle.regime_at`)."""
        return regime_at(self, mode, t_, y, p, forced, zero_tol)

    def settle(self, mode: dict, t_, y, p, forced: dict | None = None, zero_tol: float = 1e-9,
               force_tol: float = 1e-9) -> tuple[dict, int, list[str]]:
        """The consistent (mode, regime) at a state, starting from ``mode`` (see :func:`settle.settle`)."""
        return settle(self, mode, t_, y, p, forced, zero_tol, force_tol)

    def _param_value(self, expr, p) -> float:
        key = ("param", sp.sympify(expr))
        if key not in self._rate_fns:
            self._rate_fns[key] = compile_functions(list(self.layout.parameter_symbols), [sp.sympify(expr)])
        return float(self._rate_fns[key](*p)[0])


def _row_name(row) -> str:
    """A constraint row as a person names it: ``contact B``, ``pin O along Ex``."""
    return row.label.replace(": normal velocity", "").replace(": velocity along", " along")



def _vanishing(model, seed: int = 7) -> frozenset:
    """Watches of a reaction that vanishes identically in the regime (by symmetry: a wall nothing pushes
    against): its round-off would "reach zero" at once, so it is no event.  Decided as ``algebra.is_zero``
    decides an identity, by evaluation at random states (three, parameters at their values or random)."""
    idx = [i for i, w in enumerate(model.watches) if w.kind in ("opens", "slack")]
    if not idx:
        return frozenset()
    lay = model.layout
    rng = np.random.default_rng(seed)
    info = model.system.parameter_info
    zero = set(idx)
    for _ in range(3):
        y = np.concatenate([rng.uniform(-1.0, 1.0, 2 * lay.n), [0.0]])
        p = np.array([info[nm].value if info[nm].value is not None else rng.uniform(0.5, 2.0)
                      for nm in lay.parameters], dtype=float)
        try:
            with np.errstate(all="ignore"):
                react = model.reactions(rng.uniform(0.0, 1.0), y, p)
        except Exception:           # a singular random state: undecided, so every watch stays
            return frozenset()
        scale = 1.0 + max((abs(v) for v in react.values() if np.isfinite(v)), default=0.0)
        for i in list(zero):
            v = react.get(model.watches[i].quantity)
            if v is None or not np.isfinite(v) or abs(v) > 1e-12 * scale:
                zero.discard(i)
        if not zero:
            break
    return frozenset(zero)
