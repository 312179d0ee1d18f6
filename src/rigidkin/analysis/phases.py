"""Problems in phases: one mode after another, the state carried across, each phase ended by an event.

A phase names the contacts' states (``mode``), parameter substitutions (``set``: µ = 0 on a
frictionless stretch) and the event that ends it (``until``: ``x = d``, ``slip(ground) = 0``).  Within
a phase the regime (the sliding direction) is the one whose conditions hold at the phase's start.
When every acceleration is constant in the phase (constant forces: the impulse–momentum case) the
state is exact: q(τ) = q0 + q̇0 τ + ½ q̈ τ², and the end time is the first positive root of the
event condition, solved in closed form.  A phase whose event never comes (the root is negative or
complex) is reported as impossible with the condition under which it would happen (for slip-to-roll:
rolling needs 3µ cos β − sin β > 0), never as a negative time.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import RigidkinError
from ..base.printing import text
from .events import _num, condition_expression, numeric_values

t = dynamicsymbols._t


@dataclass(frozen=True)
class Phase:
    """One phase: contact states, parameter substitutions, and the event that ends it."""

    name: str
    mode: dict = field(default_factory=dict)
    set: dict = field(default_factory=dict)
    until: sp.Basic | None = None


@dataclass(frozen=True)
class PhaseResult:
    name: str
    happens: bool
    regime: str
    duration: sp.Expr | None
    start_state: dict
    end_state: dict
    notes: tuple = ()

    def __str__(self) -> str:
        if not self.happens:
            return f"{self.name}: the end event never happens ({'; '.join(self.notes)})"
        d = "open-ended" if self.duration is None else f"lasts {text(self.duration)}"
        return f"{self.name} ({self.regime}): {d}"


class _StandIns:
    """Positive symbols standing in for compound expressions (with their sign at the parameters' values)."""

    def __init__(self, values: dict):
        self.values, self.forward, self.back = values, {}, {}

    def __call__(self, v):
        v = sp.sympify(v)
        if v.is_number or v.is_Symbol or not v.free_symbols:
            return v
        if v not in self.forward:
            sign = 1 if _num(v, self.values) >= 0 else -1
            d = sp.Dummy(f"k{len(self.forward)}", positive=True)
            self.forward[v], self.back[d] = sign * d, sign * v
        return self.forward[v]


def full_state(system, start: dict) -> dict:
    """Every coordinate and rate: given values, else the declared initial values, else 0."""
    out = {}
    for c in system.coordinate_info.values():
        q, u = c.symbol, c.symbol.diff(t)
        q0 = start.get(q, c.initial if c.initial is not None else 0)
        u0 = start.get(u, c.rate if c.rate is not None else 0)
        out[q] = sp.nsimplify(q0) if isinstance(q0, float) else sp.sympify(q0)
        out[u] = sp.nsimplify(u0) if isinstance(u0, float) else sp.sympify(u0)
    return out


def _at(expr, state: dict):
    e = sp.sympify(expr)
    rates = {k: v for k, v in state.items() if isinstance(k, sp.Derivative)}
    coords = {k: v for k, v in state.items() if not isinstance(k, sp.Derivative)}
    return e.xreplace(rates).xreplace(coords)


def _choose_regime(solution, state, values):
    if len(solution.regimes) == 1:
        return solution.regimes[0]
    for r in solution.regimes:
        ok = True
        for c in r.conditions:
            v = _num(_at(c.expr, state), values)
            if v == 0 or abs(v) < 1e-12:
                # on the boundary: decide by the rate of the quantity under this regime
                acc = {q.diff(t, 2): a for q, a in r.accelerations.items()}
                dv = _num(_at(sp.diff(c.expr, t).xreplace(acc), state), values)
                v = dv
            if not c.holds(v):
                ok = False
                break
        if ok:
            return r
    raise RigidkinError("no regime's conditions hold at the start of the phase.")


def _condition_text(expr, system, inclusive: bool = False) -> str | None:
    """'c > 0' (``inclusive``: 'c ≥ 0', as a validity condition such as |F| ≤ µs N holds at equality) read
    for a person: solved for a friction coefficient (or another parameter) when linear in it; None when
    it holds for every positive value of that parameter."""
    expr = algebra.readable(expr)
    params = [p.symbol for p in system.parameter_info.values() if expr.has(p.symbol)]
    params.sort(key=lambda s: (0 if s.name.startswith("mu") else 1, s.name))
    values = numeric_values_for(system)
    for p in params:
        if expr.is_polynomial(p) and sp.degree(expr, p) == 1:
            free = sp.Dummy(p.name)
            bound = sp.solve(expr.xreplace({p: free}), free)
            if len(bound) == 1:
                b = algebra.readable(bound[0])
                rel = ">" if _num(sp.diff(expr, p), values) > 0 else "<"
                if rel == ">" and p.is_positive and _num(b, values) <= 0 and not b.free_symbols - {p}:
                    return None
                if rel == ">" and p.is_positive and _num(b, values) < 0:
                    return None
                if inclusive:
                    rel = {">": "≥", "<": "≤"}[rel]
                return f"{text(p)} {rel} {text(b)}"
    return f"{text(expr)} {'≥' if inclusive else '>'} 0"


def numeric_values_for(system) -> dict:
    return {p.symbol: (p.value if p.value is not None else 1.0) for p in system.parameter_info.values()}


def run_phases(system, phases: list[Phase], start: dict | None = None) -> list[PhaseResult]:
    """Solve a problem phase by phase from ``start`` (all coordinates and rates)."""
    state = full_state(system, dict(start or {}))
    results = []
    tau = sp.Symbol("tau", nonnegative=True)
    for ph in phases:
        sol = system.solve(mode=ph.mode, substitutions=ph.set)
        values = numeric_values(sol)
        values.update({k: v for k, v in ph.set.items() if isinstance(k, sp.Symbol) and
                       isinstance(v, (int, float))})
        regime = _choose_regime(sol, state, values)
        desc = regime.describe() if len(sol.regimes) > 1 else "single regime"
        setup = sol.setup
        accels = dict(regime.accelerations)
        # accelerations of the dependent coordinates (from the constraint relations)
        for qd2, expr in setup.reduction.accel_map.items():
            qd = qd2.args[0]
            e = setup.scalar(expr).xreplace({q.diff(t, 2): a for q, a in accels.items()})
            accels[qd] = algebra.readable(e)
        start_state = dict(state)
        # dependent rates must agree with the mode's constraints
        for rate, rel in sol.rate_relations.items():
            v = _at(rel, state)
            if not algebra.is_zero(_at(rate, state) - v):
                start_state[rate] = algebra.readable(v)
        constant = all(not algebra.functions_of_time(a) and not a.has(t) for a in accels.values())
        if ph.until is None:
            notes = []
            for cond in regime.validity:
                cexpr = algebra.readable(_at(cond.expr, start_state))
                ctext = _condition_text(cexpr, system, inclusive=cond.relation in (">=", "<="))
                if _num(cexpr, values) < 0:
                    notes.append(f"{cond.label} fails at the start: {ctext or 'it'} is needed")
                elif ctext:
                    notes.append(f"{cond.label} holds while {ctext}")
            results.append(PhaseResult(ph.name, True, desc, None, start_state, start_state, tuple(notes)))
            state = start_state
            continue
        if any(algebra.plain_state(sp.sympify(a))[0].has(t) for a in accels.values()):
            raise RigidkinError(f"phase '{ph.name}': the accelerations depend on t explicitly (a driving law), "
                                "so the phase has no closed-form end state for its start alone.",
                                hint="Use a simulation for this phase.")
        if not constant:
            raise RigidkinError(f"phase '{ph.name}': the accelerations are not constant, so there is no "
                                "closed-form end state here.", hint="Use a simulation for this phase.")
        # solve with positive stand-ins for the constant accelerations and start values, so that
        # sympy can simplify (a τ²/2 = d gives τ = sqrt(2d/a) with a > 0), then put them back
        stand = _StandIns(values)
        standin, back = stand, stand.back

        traj = {}
        for c in system.coordinate_info.values():
            q, u = c.symbol, c.symbol.diff(t)
            a = standin(accels.get(q, sp.Integer(0)))
            q0, u0 = standin(start_state[q]), standin(start_state[u])
            traj[q] = q0 + u0 * tau + a * tau**2 / 2
            traj[u] = u0 + a * tau
        g = condition_expression(sol, ph.until, regime)
        g_tau = sp.expand(_at(g, traj))
        roots = sp.solve(g_tau, tau) if g_tau.has(tau) else []
        if not roots:
            free = sp.Symbol("tau")
            roots = [r for r in sp.solve(g_tau.xreplace({tau: free}), free)]
        vals2 = {**values, **{d: _num(v, values) for d, v in back.items()}}
        good = [(r, _num(r, vals2)) for r in roots]
        positive = [(r, v) for r, v in good if v == v and v > 1e-12]
        notes = []
        if not positive:
            for r, _ in good:
                for part in sp.fraction(sp.together(r)):
                    pv = _num(part, vals2)
                    if part.free_symbols and pv < 0:
                        cond = _condition_text(algebra.readable(part.xreplace(back)), system)
                        if cond:
                            notes.append(cond)
            need = "; it would need " + " and ".join(dict.fromkeys(notes)) if notes else ""
            results.append(PhaseResult(ph.name, False, desc, None, start_state, start_state,
                                       (f"{text(ph.until)} is never reached{need}",)))
            break
        r, _ = min(positive, key=lambda rv: rv[1])
        for part in sp.fraction(sp.together(r)):
            if part.free_symbols and not (part.is_positive or part.is_nonnegative):
                cond = _condition_text(algebra.readable(part.xreplace(back) * (1 if _num(part, vals2) > 0
                                                                              else -1)), system)
                if cond:
                    notes.append("requires " + cond)
        end = {k: algebra.readable(sp.simplify(sp.simplify(v.xreplace({tau: r})).xreplace(back)))
               for k, v in traj.items()}
        duration = algebra.readable(sp.simplify(r).xreplace(back))
        results.append(PhaseResult(ph.name, True, desc, duration, start_state, end, tuple(notes)))
        state = end
    return results
