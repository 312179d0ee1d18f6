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

from dataclasses import dataclass, field

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..errors import ModelError, RigidkinError
from ..model.constraints import ROLLING, SMOOTH, Contact, Coulomb
from .rhs import SimulationError, compile_functions, regime_rates
from .state import StateLayout

t = dynamicsymbols._t

OPEN, SLIP, STICK = "open", "slip", "stick"


class ModeUnavailable(RigidkinError):
    """A mode the motion needs cannot be derived from the model (e.g. no coordinate lets a contact open)."""


def mode_key(mode: dict) -> tuple:
    return tuple(sorted(mode.items()))


def describe_mode(system, mode: dict) -> str:
    """``A open, B closed (smooth)``: the contacts' states in words."""
    words = []
    for name, st in sorted(mode.items()):
        c = system.constraints[name]
        if st == OPEN:
            words.append(f"{name} open")
        elif st == STICK:
            words.append(f"{name} rolling" if c.radius != 0 else f"{name} sticking")
        elif c.friction == SMOOTH:
            words.append(f"{name} closed")
        else:
            words.append(f"{name} slipping")
    return ", ".join(words) or "no contacts"


@dataclass(frozen=True)
class Watch:
    """A quantity of the state whose zero ends a regime, and what that zero means."""

    kind: str            # "opens", "impact", "sticks", "slips", "reverses"
    name: str            # the contact or load
    label: str           # e.g. "contact A opens"
    direction: int       # the sign of the crossing that counts (solve_ivp's convention)
    slip_sign: int = 0   # "slips": the sign σ of the slip that begins


@dataclass
class ModeModel:
    """Numeric functions of one regime of one mode (parameters passed at call time)."""

    system: object
    mode: dict
    regime_index: int
    solution: object
    layout: StateLayout
    rhs_function: object
    aux_function: object
    reaction_names: list
    watches: list
    residual_names: list
    friction_names: list
    conservative: bool
    _cache_key: tuple = field(default=(None, None), repr=False)
    _cache_val: list = field(default=None, repr=False)

    @property
    def regime(self):
        return self.solution.regime(self.regime_index)

    @property
    def description(self) -> str:
        from ..printing import text as show

        words = describe_mode(self.system, self.mode)
        conds = [f"{show(c.expr)} {c.relation.replace('>=', '≥').replace('<=', '≤')} 0"
                 for c in self.regime.conditions]
        return words + (f" ({', '.join(conds)})" if conds else "")

    def aux(self, t_: float, y: np.ndarray, p) -> list:
        """Reactions, watch values, constraint residuals, T, U and friction forces at one state."""
        key = (t_, y.tobytes(), tuple(p))
        if self._cache_key == key:
            return self._cache_val
        with np.errstate(all="ignore"):
            vals = list(self.aux_function(t_, *y[:2 * self.layout.n], *p))
        self._cache_key, self._cache_val = key, vals
        return vals

    def slices(self):
        nr, nw, ns = len(self.reaction_names), len(self.watches), len(self.residual_names)
        return (slice(0, nr), slice(nr, nr + nw), slice(nr + nw, nr + nw + ns), nr + nw + ns,
                slice(nr + nw + ns + 2, None))

    def reactions(self, t_, y, p) -> dict:
        return dict(zip(self.reaction_names, map(float, self.aux(t_, y, p)[self.slices()[0]])))

    def watch_values(self, t_, y, p) -> list:
        return [float(v) for v in self.aux(t_, y, p)[self.slices()[1]]]

    def residuals(self, t_, y, p) -> dict:
        return dict(zip(self.residual_names, map(float, self.aux(t_, y, p)[self.slices()[2]])))

    def energy(self, t_, y, p) -> tuple[float, float]:
        i = self.slices()[3]
        vals = self.aux(t_, y, p)
        return float(vals[i]), float(vals[i + 1])

    def frictions(self, t_, y, p) -> dict:
        return dict(zip(self.friction_names, map(float, self.aux(t_, y, p)[self.slices()[4]])))

    def evaluate(self, times: np.ndarray, ys: np.ndarray, p) -> dict:
        """Every aux quantity at many states at once (arrays), by name."""
        n = len(times)
        with np.errstate(all="ignore"):
            vals = self.aux_function(times, *ys[:2 * self.layout.n], *p)
        vals = [np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy() for v in vals]
        r, _, s, e, f = self.slices()
        out = {"reactions": dict(zip(self.reaction_names, vals[r])),
               "residuals": dict(zip(self.residual_names, vals[s])),
               "T": vals[e], "U": vals[e + 1],
               "frictions": dict(zip(self.friction_names, vals[f]))}
        return out


class Hybrid:
    """The modes of one system: derived once each, with their numeric functions and transitions."""

    def __init__(self, system, layout: StateLayout | None = None):
        self.system = system
        self.layout = layout or StateLayout.of(system)
        self.contacts = {n: c for n, c in system.constraints.items() if isinstance(c, Contact)}
        self._solutions: dict = {}
        self._models: dict = {}
        self._contact_fns: dict = {}
        self._rate_fns: dict = {}
        self._relation_fns: dict = {}
        self._depends: dict = {}
        self._kin = None

    # derivation ------------------------------------------------------------------------------
    def solution(self, mode: dict):
        """The Solution of ``mode`` (every contact named), or ModeUnavailable with the model's reason."""
        key = mode_key(mode)
        if key not in self._solutions:
            try:
                self._solutions[key] = self.system.solve(mode=dict(mode))
            except ModelError as exc:   # ConstraintError included
                self._solutions[key] = ModeUnavailable(
                    f"the mode ({describe_mode(self.system, mode)}) cannot be derived from the model: "
                    f"{exc.message}", where=self.system.name, hint=exc.hint)
        sol = self._solutions[key]
        if isinstance(sol, Exception):
            raise sol
        return sol

    @property
    def kin(self):
        if self._kin is None:
            from ..kinematics import Kinematics

            self._kin = self.system._cache.get("kin") or Kinematics(self.system)
            self.system._cache["kin"] = self._kin
        return self._kin

    def default_mode(self) -> dict:
        """Every contact closed: rolling contacts stick, the others slip (friction decides later)."""
        return {n: (STICK if c.friction == ROLLING else SLIP) for n, c in self.contacts.items()}

    def model(self, mode: dict, regime_index: int) -> ModeModel:
        key = (mode_key(mode), regime_index)
        if key not in self._models:
            self._models[key] = self._build(dict(mode), regime_index)
        return self._models[key]

    def _build(self, mode: dict, k: int) -> ModeModel:
        sol = self.solution(mode)
        reg = sol.regime(k)
        setup = sol.setup
        lay = self.layout
        kin = setup.kin
        react = dict(reg.reactions)
        rsub = {sp.Symbol(n, real=True): v for n, v in react.items()}
        signs = dict(reg.signs)
        # energy and the power of non-conservative loads and reactions
        from ..laws.energy import kinetic_energy, nonconservative_power, potential_energy

        T, U = kinetic_energy(setup), potential_energy(setup)
        powers = nonconservative_power(setup)
        P = sum((pw.power for pw in powers), sp.Integer(0)).xreplace(signs).xreplace(rsub)
        conservative = all(pw.power == 0 for pw in powers)
        qdot, udot = regime_rates(sol, k, lay)
        rhs_fn = compile_functions(lay.arguments(), [lay.to_plain(e) for e in (*qdot, *udot, P)])
        # watches
        watches, wexprs = [], []

        def watch(w, e):
            e = sp.sympify(e)
            plain = lay.to_plain(e)
            if not (plain.free_symbols - set(lay.parameter_symbols)):
                return          # a constant never crosses zero
            watches.append(w)
            wexprs.append(e)

        for name, c in self.contacts.items():
            st = mode[name]
            if st == OPEN:
                watch(Watch("impact", name, f"contact {name} closes (impact)", -1), c.gap(kin))
                continue
            if c.unilateral and str(c.N) in react:
                watch(Watch("opens", name, f"contact {name} opens", -1), react[str(c.N)])
            if st == STICK and isinstance(c.friction, Coulomb):
                mu, N = c.friction.mu, react.get(str(c.N), sp.Integer(0))
                if kin.planar:
                    F = react.get(str(c.F), sp.Integer(0))
                    watch(Watch("slips", name, f"contact {name} starts to slip", -1, -1), mu * N - F)
                    watch(Watch("slips", name, f"contact {name} starts to slip", -1, +1), mu * N + F)
                else:
                    Fs = [v for n_, v in react.items() if n_.startswith(str(c.F))]
                    watch(Watch("slips", name, f"contact {name} starts to slip", -1),
                          mu**2 * N**2 - sum((f**2 for f in Fs), sp.Integer(0)))
        choices = {sc.label: sc for sc in setup.sign_choices}
        for cond in reg.conditions:
            sc = choices.get(cond.label)
            load = sc.load if sc is not None else cond.label
            kind = "sticks" if (load in self.contacts and sc is not None and sc.rate_based
                                and isinstance(self.contacts[load].friction, Coulomb)) else "reverses"
            label = (f"contact {load} stops slipping" if kind == "sticks"
                     else f"{cond.label} changes sign")
            watch(Watch(kind, load, label, -1 if cond.relation in (">", ">=") else +1), cond.expr)
        # constraint residuals: the gaps of the closed rows (position level)
        residual_names, rexprs = [], []
        for row in setup.rows:
            if row.gap is not None and row.gap != 0:
                residual_names.append(row.label.replace(": normal velocity", "").replace(": velocity along",
                                                                                           " along"))
                rexprs.append(row.gap)
        # friction forces along the contact tangent (stick: the reaction; slip: −µ N σ)
        friction_names, fexprs = [], []
        for name, c in self.contacts.items():
            if not isinstance(c.friction, Coulomb) and c.friction != ROLLING:
                continue
            if mode[name] == STICK and str(c.F) in react:
                friction_names.append(str(c.F))
                fexprs.append(react[str(c.F)])
            elif mode[name] == SLIP and isinstance(c.friction, Coulomb):
                sc = next((s for s in setup.sign_choices if s.load == name and s.rate_based), None)
                if sc is not None and sc.symbol in signs:
                    friction_names.append(str(c.F))
                    fexprs.append(-c.friction.mu * react.get(str(c.N), sp.Integer(0)) * signs[sc.symbol])
        for name, c in self.contacts.items():      # the friction limit µN of every Coulomb contact
            if isinstance(c.friction, Coulomb):
                friction_names.append(f"mu*{c.N}")
                fexprs.append(c.friction.mu * react.get(str(c.N), sp.Integer(0)) if mode[name] != OPEN
                              else sp.Integer(0))
        names = list(react)
        exprs = [*(react[n] for n in names), *wexprs, *rexprs, T, U, *fexprs]
        aux_fn = compile_functions(lay.arguments(), [lay.to_plain(e) for e in exprs])
        return ModeModel(self.system, mode, k, sol, lay, rhs_fn, aux_fn, names, watches, residual_names,
                         friction_names, conservative)

    # contact quantities in the full state ----------------------------------------------------------
    def contact_functions(self, name: str):
        """(gap(q), normal speed(q, q̇), slip speed(q, q̇) or None) of a contact, in every coordinate."""
        if name not in self._contact_fns:
            c = self.contacts[name]
            kin = self.kin
            exprs = [c.gap(kin), c.rows(kin, SLIP)[0].velocity]
            if kin.planar and c.friction != SMOOTH:
                exprs.append(c.slip_velocity(kin))
            f = compile_functions(self.layout.arguments(), [self.layout.to_plain(e) for e in exprs])
            self._contact_fns[name] = (f, len(exprs))
        return self._contact_fns[name]

    def contact_state(self, name: str, t_, y, p) -> tuple[float, float, float | None]:
        f, n = self.contact_functions(name)
        vals = [float(v) for v in f(t_, *y[:2 * self.layout.n], *p)]
        return vals[0], vals[1], (vals[2] if n > 2 else None)

    def rate_of_condition(self, mode: dict, k: int, cond_index: int):
        """A function giving d/dt of regime k's condition ``cond_index`` in regime k (its own accelerations)."""
        key = (mode_key(mode), k, cond_index)
        if key not in self._rate_fns:
            sol = self.solution(mode)
            reg = sol.regime(k)
            red = sol.setup.reduction
            e = sp.diff(reg.conditions[cond_index].expr, t)
            acc = {q.diff(t, 2): a for q, a in reg.accelerations.items()}
            e = e.xreplace(red.accel_map).xreplace(red.rate_map).xreplace(acc)
            self._rate_fns[key] = compile_functions(self.layout.arguments(), [self.layout.to_plain(e)])
        return self._rate_fns[key]

    def relation_functions(self, mode: dict):
        """(dependent coordinates' slots, q_d from the integrated relations, q̇_d from the rate relations)."""
        key = mode_key(mode)
        if key not in self._relation_fns:
            sol = self.solution(mode)
            lay = self.layout
            red = sol.setup.reduction
            slots, exprs = [], []
            for q in sol.dependent:
                slots.append(lay.coordinates.index(q))
                exprs.append(red.rate_map[q.diff(t)])
            rel_slots = [lay.coordinates.index(q) for q in sol.relations]
            rel_fn = compile_functions(lay.arguments(), [lay.to_plain(v) for v in sol.relations.values()])
            rate_fn = compile_functions(lay.arguments(), [lay.to_plain(e) for e in exprs])
            self._relation_fns[key] = (rel_slots, rel_fn, slots, rate_fn)
        return self._relation_fns[key]

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
            from .. import algebra
            from ..laws.newton_euler import body_balances

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

    # choosing a consistent mode ---------------------------------------------------------------------
    def regime_at(self, mode: dict, t_, y, p, forced: dict | None = None, zero_tol: float = 1e-9) -> int:
        """The regime whose conditions hold at the state; at a zero, the one whose motion leaves it consistently.

        ``forced`` maps a sign choice's load name to the sign σ it must have (a slip that begins).
        """
        sol = self.solution(mode)
        if len(sol.regimes) == 1:
            return 0
        forced = forced or {}
        choices = {sc.label: sc for sc in sol.setup.sign_choices}
        candidates = []
        for k, reg in enumerate(sol.regimes):
            ok = True
            for ci, cond in enumerate(reg.conditions):
                sc = choices.get(cond.label)
                if sc is not None and sc.load in forced:
                    if reg.signs.get(sc.symbol) != forced[sc.load]:
                        ok = False
                        break
                    continue
                val = self._condition_value(mode, k, ci, t_, y, p)
                if abs(val) <= zero_tol * max(1.0, float(np.max(np.abs(y[:2 * self.layout.n])))):
                    rate = float(self.rate_of_condition(mode, k, ci)(t_, *y[:2 * self.layout.n], *p)[0])
                    if not cond.holds(rate):
                        ok = False
                        break
                elif not cond.holds(val):
                    ok = False
                    break
            if ok:
                candidates.append(k)
        if not candidates:
            raise SimulationError(f"at t = {t_:.10g} no friction direction of the mode "
                                  f"({describe_mode(self.system, mode)}) is consistent with the motion.",
                                  where=self.system.name,
                                  hint="The friction would have to stick where the model cannot stick "
                                       "(a friction load or a collar), or the friction law has no solution here.")
        return candidates[0]

    def _condition_value(self, mode, k, ci, t_, y, p) -> float:
        key = (mode_key(mode), k, "cond", ci)
        if key not in self._rate_fns:
            cond = self.solution(mode).regime(k).conditions[ci]
            self._rate_fns[key] = compile_functions(self.layout.arguments(), [self.layout.to_plain(cond.expr)])
        return float(self._rate_fns[key](t_, *y[:2 * self.layout.n], *p)[0])

    def settle(self, mode: dict, t_, y, p, forced: dict | None = None, zero_tol: float = 1e-9,
               force_tol: float = 1e-9) -> tuple[dict, int, list[str]]:
        """The consistent (mode, regime) at a state, starting from the candidate ``mode``.

        Closed Coulomb contacts whose slip speed is zero are tried sticking; a sticking contact that
        needs more friction than µN slips in the direction the friction saturates; a unilateral
        contact whose normal reaction would pull opens.  Contacts are never closed here (an impact
        does that).  Returns (mode, regime, notes).
        """
        mode, forced, notes = dict(mode), dict(forced or {}), []
        scale = max(1.0, float(np.max(np.abs(y[:2 * self.layout.n]))))
        for name, c in self.contacts.items():
            if mode[name] != OPEN and isinstance(c.friction, Coulomb) and name not in forced:
                _, _, s = self.contact_state(name, t_, y, p)
                if s is not None and abs(s) <= zero_tol * scale:
                    mode[name] = STICK
                elif s is not None:
                    mode[name] = SLIP
        seen = set()
        for _ in range(4 * len(self.contacts) + 4):
            key = (mode_key(mode), tuple(sorted(forced.items())))
            if key in seen:
                break
            seen.add(key)
            self.solution(mode)          # ModeUnavailable propagates
            k = self.regime_at(mode, t_, y, p, forced, zero_tol)
            model = self.model(mode, k)
            react = model.reactions(t_, y, p)
            fscale = max(1.0, max((abs(v) for v in react.values()), default=1.0))
            changed = False
            # a unilateral contact that would pull opens (the most negative first)
            pulling = [(react[str(c.N)], n) for n, c in self.contacts.items()
                       if mode[n] != OPEN and c.unilateral and str(c.N) in react
                       and react[str(c.N)] < -force_tol * fscale]
            if pulling:
                _, n = min(pulling)
                mode[n] = OPEN
                forced.pop(n, None)
                notes.append(f"{n} opens: its normal reaction would pull ({react[str(self.contacts[n].N)]:.4g})")
                continue
            for n, c in self.contacts.items():
                if mode[n] != STICK or not isinstance(c.friction, Coulomb):
                    continue
                N, F = react.get(str(c.N), 0.0), react.get(str(c.F), 0.0)
                mu = float(self._param_value(c.friction.mu, p))
                if abs(F) > mu * abs(N) + force_tol * fscale:
                    if not self.kin.planar:
                        raise SimulationError(f"at t = {t_:.10g} contact {n} needs more friction than µN to "
                                              "stick, and slipping in three dimensions is not simulated yet.",
                                              where=self.system.name)
                    mode[n] = SLIP
                    forced[n] = -1 if F > 0 else 1
                    notes.append(f"{n} slips: sticking needs |F| = {abs(F):.4g} > µN = {mu * abs(N):.4g}")
                    changed = True
                    break
            if changed:
                continue
            return mode, k, notes
        raise SimulationError(f"at t = {t_:.10g} no contact mode is consistent with the state "
                              f"(tried up to {describe_mode(self.system, mode)}).", where=self.system.name,
                              hint="Sticking and slipping are both inconsistent here (a Painlevé-type paradox), "
                                   "or the contacts keep opening and closing.")

    def _param_value(self, expr, p) -> float:
        key = ("param", sp.sympify(expr))
        if key not in self._rate_fns:
            self._rate_fns[key] = compile_functions(list(self.layout.parameter_symbols), [sp.sympify(expr)])
        return float(self._rate_fns[key](*p)[0])
