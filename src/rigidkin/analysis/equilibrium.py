"""Equilibria and linearisation: configurations at rest, linearised EOM, stability, natural frequencies.

At an equilibrium every rate and acceleration vanishes: the accelerations of the solution, with the
rates set to zero, give equations in the coordinates alone (solved in closed form where sympy can).
About an equilibrium q_e the reaction-free equations M(q) q̈ = f(q, q̇) linearise to
M δq̈ + C δq̇ + K δq = 0 with M = M(q_e), C = −∂f/∂q̇, K = −∂f/∂q at (q_e, 0).  One degree of
freedom: ω_n = sqrt(K/M), ζ = C/(2 sqrt(K M)).  Several: det(K − ω² M) = 0 (exact when small).
Stability is decided from the eigenvalues of the first-order system with the parameters' values; where
the linearisation holds a parameter without a value it is stated as a condition (one degree of freedom,
undamped: stable while K/M > 0) or left undecided, never decided with a stand-in number.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra
from ..base.errors import RigidkinError
from ..base.printing import text
from .events import SOLVE_SECONDS, _num, numeric_values
from .linear import _is_real, explicit_time, linearise_about, position_gaps, present, single_regime

t = dynamicsymbols._t


_RELATIVE = "a relative equilibrium: at rest relative to the driven bodies, whose motion is prescribed"


@dataclass(frozen=True)
class Equilibrium:
    """An equilibrium configuration with its linearisation."""

    configuration: dict
    M: sp.Matrix
    C: sp.Matrix
    K: sp.Matrix
    linear_eom: tuple                      # expressions = 0 in the deviations δq (written as q)
    natural_frequencies: tuple = ()        # exact ω_n (undamped) where found
    damping_ratios: tuple = ()
    eigenvalues: tuple = ()                # of the first-order system, numeric (parameter values)
    stability: str = ""                    # "stable", "asymptotically stable", "unstable", "marginal"
    notes: tuple = field(default=())

    def __str__(self) -> str:
        conf = ", ".join(f"{text(q)} = {text(v)}" for q, v in self.configuration.items())
        out = f"{'relative ' if _RELATIVE in self.notes else ''}equilibrium {conf}: {self.stability}"
        if self.natural_frequencies:
            out += "; ω_n = " + ", ".join(text(w) for w in self.natural_frequencies)
        if self.damping_ratios:
            out += "; ζ = " + ", ".join(text(z) for z in self.damping_ratios)
        return out


def equilibria(solution, limit: int = 8) -> list[Equilibrium]:
    """Equilibrium configurations of a single-regime solution, each linearised (and so back-substituted).

    Dependent coordinates that the equations still contain are unknowns too, with the position
    constraints as equations.  Equations that depend on t explicitly (a driving law) have no
    equilibrium for all t: refused with that reason.
    """
    regime, M, f = single_regime(solution, "an equilibrium")
    qs = list(solution.coordinates)
    rest = {q.diff(t): 0 for q in qs}
    for q in solution.dependent:
        rest[q.diff(t)] = 0
    f0 = f.xreplace(rest)
    if any(explicit_time(e) for e in f0):
        raise RigidkinError("the equations of motion depend on t explicitly (a driving law), so no "
                            "configuration is at rest for all t: there is no equilibrium to give.",
                            where="equilibrium", hint="Write the coordinates relative to the driven frame when "
                                                      "the driving is a steady rotation (a relative "
                                                      "equilibrium), or simulate.")
    found = present(list(M) + list(f))
    extra = [q for q in solution.dependent if q in found and not isinstance(q, sp.Derivative)]
    unknowns = qs + extra
    plain = {q: sp.Symbol(q.func.__name__, real=True) for q in unknowns}
    eqs = [algebra.readable(sp.sympify(e)).xreplace(plain) for e in f0]
    eqs = [e for e in eqs if e != 0]
    if not eqs:
        raise RigidkinError("every configuration is an equilibrium (no generalised force acts).")
    if extra:
        eqs += [algebra.readable(g.xreplace(rest)).xreplace(plain) for _, g in position_gaps(solution)]
    try:
        with algebra.time_limit(SOLVE_SECONDS):
            sols = sp.solve(eqs, [plain[q] for q in unknowns], dict=True)
    except (NotImplementedError, TimeoutError):
        sols = []
    if not sols:
        raise RigidkinError("sympy finds no closed-form equilibrium configuration.",
                            hint="Search numerically with simulate(), or give the configuration to linearise().")
    back = {v: k for k, v in plain.items()}
    values = known_values(solution)       # a parameter without a value: real for the values that make it so
    out = []
    for sol in sols[:limit]:
        conf = {back[k]: algebra.readable(v) for k, v in sol.items()}
        if any(v.has(*plain.values()) for v in conf.values()):
            continue                # a family of configurations with a free coordinate: none is isolated
        if not all(_is_real(v, values) for v in conf.values()):
            continue
        for q in qs:
            conf.setdefault(q, sp.Integer(0))
        if _off_arc(solution, regime, conf) or _off_domain(solution, conf):
            continue            # a contact point off its profile's arc, a disk past lying flat: not the model's
        out.append(linearise(solution, conf))
    if not out:
        raise RigidkinError("every equilibrium configuration found puts a contact point off its profile's arc "
                            "(the curved face of a half shape does not touch there) or a contact outside the "
                            "configurations its geometry describes (a disk past lying flat), or is not real, so "
                            "the model has none.")
    return out


def _off_domain(solution, conf) -> bool:
    """True when ``conf`` lies outside a contact's domain of validity (``domain``: a disk leaned past flat)."""
    values = numeric_values(solution)
    kin = solution.setup.kin
    for c in solution.system.constraints.values():
        for expr, _, _ in (c.domain(kin) if hasattr(c, "domain") else ()):
            try:
                v = _num(sp.sympify(expr).xreplace(conf), values)
            except (TypeError, ValueError):
                continue
            if not v > 1e-12:
                return True
    return False


def _off_arc(solution, regime, conf) -> bool:
    """True when an arc condition of the regime (model.profiles) fails at the configuration ``conf``."""
    values = numeric_values(solution)
    point = {**{q.diff(t): 0 for q in conf}, **conf}
    for cond in regime.validity:
        if "on its arc" not in cond.label:
            continue
        try:
            v = _num(cond.expr.xreplace(point), values)
        except (TypeError, ValueError):
            continue
        if not cond.holds(v, 1e-9):
            return True
    return False


def linearise(solution, at: dict) -> Equilibrium:
    """Linearise the reaction-free EOM about the configuration ``at`` (rates zero).

    Refused, with the residual, when ``at`` is not an equilibrium (a generalised force does not vanish
    there) or when the equations depend on t explicitly.  Dependent coordinates are eliminated.
    """
    lin = linearise_about(solution, at, rest=True, what="equilibrium")
    regime = solution.regimes[0]
    qs = list(solution.coordinates)
    us = [q.diff(t) for q in qs]
    point = dict(lin.point)
    n = len(qs)
    Mmat, Cmat = lin.M, lin.C
    Kmat = sp.zeros(n, n)
    kept = [q for q in qs if q not in lin.ignorable]
    for j, q in enumerate(kept):
        Kmat[:, qs.index(q)] = lin.K[:, j]
    acc = [q.diff(t, 2) for q in qs]
    eom = []
    for i in range(n):
        e = sum((Mmat[i, j] * acc[j] + Cmat[i, j] * us[j] + Kmat[i, j] * qs[j] for j in range(n)), sp.Integer(0))
        eom.append(algebra.readable(e))
    configuration = {q: v for q, v in point.items() if not isinstance(q, sp.Derivative)
                     and (q in at or q in lin.dependent or q not in lin.ignorable)}
    values = numeric_values(solution)
    unset = _unset(solution, (Mmat, Cmat, Kmat))
    # natural frequencies (undamped) where exact
    freqs, zetas, notes, roots = [], [], [], None
    if n == 1:
        k, m, c = Kmat[0, 0], Mmat[0, 0], Cmat[0, 0]
        if _positive(k / m, values, unset):
            wn = algebra.readable(sp.sqrt(k / m))
            freqs.append(wn)
            if c != 0:
                zetas.append(algebra.readable(c / (2 * sp.sqrt(k * m))))
    elif n <= 3:
        w2 = sp.Symbol("_w2")
        try:
            with algebra.time_limit(SOLVE_SECONDS):
                roots = sp.solve((Kmat - w2 * Mmat).det(), w2)
        except (NotImplementedError, TimeoutError):
            roots = []
            notes.append("no closed-form natural frequencies in time: see the eigenvalues (numeric)")
        for r in roots:
            if _positive(r, values, unset):
                freqs.append(algebra.readable(sp.sqrt(r)))
    if unset:
        stab, eig = _conditional_stability(Mmat, Cmat, Kmat, unset, roots), ()
        return _finish(solution, regime, point, configuration, (Mmat, Cmat, Kmat), eom, freqs, zetas, eig, stab,
                       list(lin.notes) + notes)
    # stability from the first-order system with numbers
    Mn = np.array([[_num(Mmat[i, j], values) for j in range(n)] for i in range(n)])
    Kn = np.array([[_num(Kmat[i, j], values) for j in range(n)] for i in range(n)])
    Cn = np.array([[_num(Cmat[i, j], values) for j in range(n)] for i in range(n)])
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(Mn, Kn), -np.linalg.solve(Mn, Cn)]])
    eig = np.linalg.eigvals(A)
    re = eig.real.max()
    if re > 1e-9:
        stab = "unstable"
    elif re < -1e-9:
        stab = "asymptotically stable"
    else:
        kev = np.linalg.eigvals(np.linalg.solve(Mn, Kn)).real
        neutral = int(np.sum(np.abs(kev) <= 1e-9 * max(1.0, np.abs(kev).max())))
        if np.all(kev > -1e-9 * max(1.0, np.abs(kev).max())):
            stab = "stable (undamped oscillation about it)"
            if neutral:
                stab += f", with {neutral} neutral mode(s) (free rigid-body motion)"
        else:
            stab = "marginal (linearisation inconclusive)"
    notes.append("stability decided with the parameters' values: "
                 + ", ".join(f"{k} = {v:g}" for k, v in values.items()))
    return _finish(solution, regime, point, configuration, (Mmat, Cmat, Kmat), eom, freqs, zetas, eig, stab,
                   list(lin.notes) + notes)


def known_values(solution) -> dict:
    """The parameters that have a value, with it (no stand-in for those without)."""
    return {p.symbol: p.value for p in solution.system.parameter_info.values() if p.value is not None}


def _unset(solution, matrices) -> list:
    """The parameters without a value that the linearisation holds, by name."""
    missing = {p.symbol for p in solution.system.parameter_info.values() if p.value is None}
    found = set().union(*(sp.Matrix(x).free_symbols for x in matrices))
    return sorted(found & missing, key=lambda s: s.name)


def _positive(expr, values, unset) -> bool:
    """``expr`` > 0 with the parameters' values; with a parameter left without a value, unless its sign is known
    to be negative or zero (then the frequency is kept, real where the condition holds)."""
    if not unset or not (sp.sympify(expr).free_symbols & set(unset)):
        return _num(expr, values) > 0
    known = {k: v for k, v in values.items() if k not in unset}
    e = sp.sympify(expr).xreplace({k: sp.Float(v) for k, v in known.items()})
    return e.is_nonpositive is not True


def _conditional_stability(Mmat, Cmat, Kmat, unset, roots=None) -> str:
    """Stability where a parameter has no value: decided from the signs of ω² that the parameters' signs fix
    (undamped), a condition for one undamped degree of freedom, else undecided."""
    names = ", ".join(text(s) for s in unset)
    verb = "has" if len(unset) == 1 else "have"
    undamped = all(c == 0 for c in Cmat)
    if undamped and Mmat.shape == (1, 1):
        roots = [algebra.readable(Kmat[0, 0] / Mmat[0, 0])]
    if undamped and roots is not None and len(roots) == Mmat.shape[0]:
        signs = [sp.sympify(r) for r in roots]
        if any(r.is_negative for r in signs):
            return "unstable"
        if all(r.is_nonnegative for r in signs):
            neutral = sum(1 for r in signs if r.is_zero)
            if neutral == len(signs):
                return "marginal (linearisation inconclusive)"
            return "stable (undamped oscillation about it)" + (
                f", with {neutral} neutral mode(s) (free rigid-body motion)" if neutral else "")
        if len(signs) == 1:
            r = signs[0]
            return (f"stable (undamped oscillation about it) while {text(r)} > 0, unstable while {text(r)} < 0 "
                    f"({names} {verb} no value)")
    return f"stability undecided: it depends on {names}, which {verb} no value (give {names} a value)"


def _finish(solution, regime, point, configuration, mats, eom, freqs, zetas, eig, stab, notes) -> Equilibrium:
    """The equilibrium with the notes every one carries (contact conditions, a relative equilibrium)."""
    values = numeric_values(solution)
    Mmat, Cmat, Kmat = mats
    for cond in regime.validity:
        v = _num(cond.expr.xreplace(point), values)
        if not cond.holds(v, 1e-9):
            notes.append(f"but {cond.label} fails there ({text(cond.expr)} = {v:.4g})")
    if any(c.kind in ("drive", "prescribed coordinate") for c in solution.system.constraints.values()):
        notes.insert(0, _RELATIVE)     # a driven body turns: at rest relative to it, not to the ground
    return Equilibrium(configuration, Mmat, Cmat, Kmat, tuple(eom), tuple(freqs), tuple(zetas),
                       tuple(complex(e) for e in eig), stab, tuple(notes))
