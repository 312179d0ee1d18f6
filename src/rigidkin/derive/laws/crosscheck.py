"""Cross-check: the equations of motion by every law that applies, compared with each other.

For a solution (usually Newton–Euler), every other law is run on the same mode: the 2nd law about each
pin, collar and contact point (``about-point:P``), ``work-energy`` (one degree of freedom),
``lagrange`` and ``kane``.  For each regime and each independent coordinate the accelerations
q̈ = f(q, q̇) are compared; the reaction-free equations of the 2nd law about P are checked to hold
with the reference accelerations.  How each agreement was decided is recorded:

* symbolically, when the difference simplifies to zero (or, for an equation ``= 0``, when the ratio
  of two forms is a nonzero constant), else
* numerically, at ``SAMPLES`` random states and parameter sets, to a relative tolerance ``RTOL``.

A law that does not apply (work–energy with two degrees of freedom; Lagrange or Kane with friction
set by a normal reaction) is listed with the reason.  The dimensions of every equation are checked
(``rigidkin.base.dimensions``).  A user's equation (``expect``) is compared with the derived one:
equivalent or not, which terms differ, and whether it is dimensionally consistent.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base import algebra
from ...base.dimensions import check_equation, check_solution, symbol_dimensions
from ...base.errors import RigidkinError
from ...base.printing import text
from ..mode import setup_mode
from . import solve_with
from .about_point import reaction_free
from .compare import (  # noqa: F401  (public through here)
    MIN_SAMPLES,
    RTOL,
    SAMPLES,
    SYMBOLIC_LIMIT,
    Sampler,
    _numeric_compare,
    _numeric_points,
    compare,
    holds_numerically,
    numerically_equal,
    same_equation,
)
from .energy import kinetic_energy, nonconservative_power, potential_energy
from .manifold import manifold_of
from .methods import NotApplicable

t = dynamicsymbols._t

@dataclass(frozen=True)
class Verdict:
    """One cell of the table: a law's equation compared with the reference."""

    law: str
    equation: str
    status: str            # "agrees", "disagrees", "does not apply", "error"
    how: str
    ours: sp.Expr | None = None
    reference: sp.Expr | None = None

    @property
    def failed(self) -> bool:
        return self.status in ("disagrees", "error", "undecided")


@dataclass(frozen=True)
class Expectation:
    """A user's equation compared with the derived equations of motion."""

    given: sp.Expr                 # as ``lhs − rhs`` (= 0)
    text: str
    equivalent: bool
    how: str
    regime: int | None = None
    differences: tuple = ()        # (term in the given equation or None, term of the derived one or None)
    residual: sp.Expr | None = None
    dimensions: object = None      # DimensionReport
    derived: sp.Expr | None = None

    def describe(self) -> str:
        lines = [f"expected: {self.text}"]
        if self.equivalent:
            lines.append(f"  equivalent to the derived equation of motion ({self.how}).")
        else:
            lines.append(f"  NOT equivalent to the derived equation of motion ({self.how}).")
            if self.derived is not None:
                lines.append(f"  derived:  {text(self.derived)} = 0")
            for mine, theirs in self.differences:
                if mine is not None and theirs is not None:
                    lines.append(f"  the term {text(mine)} differs: the derived equation has {text(theirs)}")
                elif mine is not None:
                    lines.append(f"  the term {text(mine)} is not in the derived equation")
                else:
                    lines.append(f"  the derived equation has the term {text(theirs)}, missing here")
            if not self.differences and self.residual is not None:
                lines.append(f"  with the derived accelerations it leaves {text(self.residual)} ≠ 0")
        if self.dimensions is not None:
            lines.append("  dimensions: " + ("consistent" if self.dimensions.consistent else str(self.dimensions)))
        return "\n".join(lines)


@dataclass(frozen=True)
class CheckReport:
    """The cross-check of one solution: law × equation verdicts, dimensions, expectations."""

    system: str
    reference: str
    verdicts: tuple
    dimensions: tuple = ()
    expectations: tuple = ()
    seconds: float = 0.0
    notes: tuple = field(default=())

    @property
    def ok(self) -> bool:
        return (not any(v.failed for v in self.verdicts) and all(d.consistent for d in self.dimensions)
                and all(e.equivalent for e in self.expectations))

    def table(self) -> str:
        rows = [("law", "equation", "result", "how decided")]
        for v in self.verdicts:
            rows.append((v.law, v.equation, v.status, v.how))
        w = [max(len(r[i]) for r in rows[:]) for i in range(3)]
        w = [min(x, 40) for x in w]
        out = []
        for i, r in enumerate(rows):
            out.append(f"{r[0]:<{w[0]}}  {r[1]:<{w[1]}}  {r[2]:<{w[2]}}  {r[3]}")
            if i == 0:
                out.append("-" * (sum(w) + 6 + 20))
        return "\n".join(out)

    def __str__(self) -> str:
        lines = [f"Cross-check of {self.system}: every law against {self.reference}", self.table()]
        bad = [v for v in self.verdicts if v.status == "disagrees"]
        for v in bad:
            lines.append(f"{v.law} disagrees on {v.equation}:\n  {v.law}: {_short(v.ours)}\n"
                         f"  {self.reference}: {_short(v.reference)}")
        if self.dimensions:
            wrong = [d for d in self.dimensions if not d.consistent]
            lines.append(f"Dimensions: {len(self.dimensions) - len(wrong)} of {len(self.dimensions)} equations "
                         "consistent." + ("" if not wrong else ""))
            lines += [f"  {d}" for d in wrong]
        for e in self.expectations:
            lines.append(e.describe())
        if not self.verdicts and self.ok:
            lines.append("No law was compared: no degree of freedom remains in this mode, so there is no equation "
                         "of motion to compare (the reactions follow from statics).")
        else:
            lines.append("All agree." if self.ok else "Disagreement found.")
        return "\n".join(lines)


# comparison ---------------------------------------------------------------------------------------
def _short(expr, limit: int = 400) -> str:
    """An expression for the report: in full when short, else its start and its size."""
    shown = text(expr)
    if len(shown) <= limit:
        return shown
    return f"{shown[:limit]}… ({len(shown)} characters in all)"


def candidate_laws(solution) -> list[str]:
    """Every other law for this mode: the 2nd law about each constraint point, energy, Lagrange, Kane."""
    system = solution.system
    out = []
    for name, c in system.constraints.items():
        state = solution.states.get(name)
        if c.kind in ("pin", "collar") or (c.kind == "contact" and state != "open"):
            out.append(f"about-point:{name}")
    if not out:
        out.append("about-point:O")
    if solution.coordinates:     # at rest (no degree of freedom) these laws have no equation to give
        out += ["work-energy", "lagrange", "kane"]
    base = solution.method
    return [m for m in ["newton-euler"] + out if m != base]


def _mode_args(solution):
    """(mode, independent, substitutions) that reproduce the solution's mode (independent None: default)."""

    kin, cons = solution.setup.kin, solution.system.constraints
    mode = {k: v for k, v in solution.states.items() if k in cons and v != cons[k].default_state(kin)}
    subs = dict(solution.setup.substitutions)
    default = setup_mode(solution.system, mode, None, subs).reduction.independent
    independent = None if tuple(default) == tuple(solution.coordinates) else solution.coordinates
    return mode, independent, subs


def cross_check(solution, laws=None, expect=(), dimensions: bool = True) -> CheckReport:
    """Derive the EOM by every law in ``laws`` (default: all that may apply) and compare with ``solution``."""

    t0 = time.time()
    system = solution.system
    mode, independent, subs = _mode_args(solution)
    verdicts = []
    laws = list(laws) if laws is not None else candidate_laws(solution)
    for law in laws:
        try:
            other = solve_with(system, law, mode, independent, subs)
        except NotApplicable as exc:
            verdicts.append(Verdict(law, "all", "does not apply", exc.message))
            if law == "work-energy":
                verdicts.extend(_power_balance(solution))
            continue
        except RigidkinError as exc:
            verdicts.append(Verdict(law, "all", "error", str(exc)))
            continue
        verdicts.extend(_compare_solutions(solution, other, law))
        if law.startswith("about-point"):
            verdicts.extend(_reaction_free_rows(solution, other, law))
    dims = ()
    if dimensions:
        dims = tuple(check_solution(solution))
    exps = tuple(expectation(solution, e) for e in expect)
    report = CheckReport(system.name, solution.method, tuple(verdicts), dims, exps, time.time() - t0)
    _record(solution, report)
    return report


def _record(solution, report: CheckReport) -> None:
    """The cross-check in the solution's trace (section "Checks"), once per law."""
    tr = solution.trace
    seen = {st.title for st in tr.steps if st.section == "Checks"}
    by_law: dict = {}
    for v in report.verdicts:
        by_law.setdefault(v.law, []).append(v)
    for law, vs in by_law.items():
        title = f"Cross-check: {law}"
        if title in seen:
            continue
        statuses = {v.status for v in vs}
        summary = ("does not apply: " + vs[0].how if statuses == {"does not apply"} else
                   "; ".join(f"{v.equation}: {v.status} ({v.how})" for v in vs if v.status != "does not apply"))
        tr.add("Checks", title, [(v.ours, v.reference) for v in vs if v.status == "disagrees"], summary)
    if report.dimensions and "Dimensions" not in seen:
        wrong = [d for d in report.dimensions if not d.consistent]
        tr.add("Checks", "Dimensions", [], f"{len(report.dimensions) - len(wrong)} of {len(report.dimensions)} "
               "equations dimensionally consistent" + ("" if not wrong else ": " + "; ".join(map(str, wrong))) + ".")


def _regime_pairs(ref, other):
    pairs = []
    for r in ref.regimes:
        match = [o for o in other.regimes if dict(o.signs) == dict(r.signs)]
        pairs.append((r, match[0] if match else None))
    return pairs


def _compare_solutions(ref, other, law) -> list[Verdict]:
    out = []
    many = len(ref.regimes) > 1
    big = len(ref.coordinates) > 2
    for i, (r, o) in enumerate(_regime_pairs(ref, other)):
        tag = f" [regime {i + 1}]" if many else ""
        if o is None:
            out.append(Verdict(law, f"regime {i + 1}", "disagrees", "the law has no regime with these signs: "
                               + r.describe()))
            continue
        if big:
            out.extend(_compare_numerically(ref, r, o, law, tag))
            continue
        for q in ref.coordinates:
            a, b = o.accelerations.get(q), r.accelerations[q]
            label = f"{text(q.diff(t, 2))}{tag}"
            if a is None:
                out.append(Verdict(law, label, "error", "the law does not give this acceleration"))
                continue
            ok, how = compare(a, b, manifold_of(ref))
            out.append(Verdict(law, label, _status(ok, how), how, a, b))
        if len(ref.coordinates) == 1 and o.eom and r.eom:
            ok, how = same_equation(o.eom[0], r.eom[0])
            if ok:
                out.append(Verdict(law, f"EOM{tag}", "agrees", how, o.eom[0], r.eom[0]))
    return out


def _compare_numerically(ref, r, o, law, tag) -> list[Verdict]:
    """Accelerations of both laws from their own M q̈ = f, solved numerically at the same random states."""
    coords = ref.coordinates
    sampler = Sampler(manifold=manifold_of(ref))
    bad, used = set(), 0
    for i in range(sampler.n):
        try:
            a = sampler.accelerations(r, coords, i)
            b = sampler.accelerations(o, coords, i)
        except np.linalg.LinAlgError:
            continue
        if not all(np.isfinite(v) for v in list(a.values()) + list(b.values())):
            continue
        used += 1
        for q in coords:
            k = algebra.plain_state(q.diff(t, 2))[0]
            if abs(a[k] - b[k]) > RTOL * max(1.0, abs(a[k]), abs(b[k])):
                bad.add(q)
    how = (f"numeric: M q̈ = f of each law solved at {used} random states and parameter sets, "
           f"rel. tol. {RTOL:g}")
    out = []
    for k, q in enumerate(coords):
        ok = used >= MIN_SAMPLES and q not in bad
        out.append(Verdict(law, f"{text(q.diff(t, 2))}{tag}", "agrees" if ok else "disagrees", how,
                           None if ok else _row(o, k), None if ok else _row(r, k)))
    return out


def _status(ok: bool, how: str) -> str:
    """The verdict a comparison supports: an undecided numeric comparison is not a disagreement."""
    return "agrees" if ok else ("undecided" if "undecided" in how else "disagrees")


def _row(regime, k):
    """Row k of M q̈ − f (for showing a disagreement without solving symbolically)."""
    return regime.eom[k] if k < len(regime.eom) else None


def _power_balance(ref) -> list[Verdict]:
    """dE/dt = Σ P_nc along the reference accelerations and reactions (a check for any number of DOF)."""

    setup = ref.setup
    try:
        E = kinetic_energy(setup) + potential_energy(setup)
        P = sum((p.power for p in nonconservative_power(setup)), sp.Integer(0))
    except RigidkinError as exc:
        return [Verdict("work-energy", "dE/dt = ΣP_nc", "error", str(exc))]
    out = []
    many = len(ref.regimes) > 1
    for i, r in enumerate(ref.regimes):
        e = ref.setup.reduction.reduce(sp.diff(E, t) - P).xreplace(dict(r.signs))   # ė = W(q)u where kept
        if ref.setup.reactions and e.has(*ref.setup.reactions):
            react = {sp.Symbol(k, real=True): v for k, v in r.reactions.items()}
            e = e.xreplace(react).xreplace(dict(r.signs))
        if len(ref.coordinates) > 2:
            ok, how = holds_numerically(e, r, ref.coordinates, Sampler(manifold=manifold_of(ref)))
            resid = e
        else:
            resid = e.xreplace({q.diff(t, 2): a for q, a in r.accelerations.items()})
            ok, how = compare(resid, 0, manifold_of(ref))
        tag = f" [regime {i + 1}]" if many else ""
        out.append(Verdict("work-energy", f"dE/dt = ΣP_nc{tag}", "agrees" if ok else "disagrees",
                           "holds with the reference accelerations and reactions; " + how, resid, 0))
    return out


def _reaction_free_rows(ref, other, law) -> list[Verdict]:
    """Each reaction-free 2nd-law equation about P holds with the reference accelerations."""

    out = []
    setup = other.setup
    rows = reaction_free(setup, other.equations)
    many = len(ref.regimes) > 1
    for eq in rows:
        for i, r in enumerate(ref.regimes):
            e = eq.expr.xreplace(dict(r.signs))
            if len(ref.coordinates) > 2:
                ok, how = holds_numerically(e, r, ref.coordinates, Sampler(manifold=manifold_of(ref)))
            else:
                resid = e.xreplace({q.diff(t, 2): a for q, a in r.accelerations.items()})
                ok, how = compare(resid, 0, manifold_of(ref))
            tag = f" [regime {i + 1}]" if many else ""
            along = eq.label.rsplit("along ", 1)[-1] if "along " in eq.label else ""
            name = f"{eq.body}: reaction-free 2nd law" + (f" along {along}" if along and not setup.kin.planar else "")
            out.append(Verdict(law, f"{name}{tag}", "agrees" if ok else "disagrees",
                               "holds with the reference accelerations; " + how, e, 0))
    return out


# the user's equation ----------------------------------------------------------------------------------
def expectation(solution, given, label: str | None = None) -> Expectation:
    """Compare a user's equation (``sp.Eq`` or an expression ``= 0``) with the derived equations of motion."""

    setup = solution.setup
    if isinstance(given, sp.Eq):
        lhs, rhs = given.lhs, given.rhs
    else:
        lhs, rhs = sp.sympify(given), sp.Integer(0)
    shown = label or f"{text(lhs)} = {text(rhs)}"
    dims = check_equation(lhs, rhs, symbol_dimensions(solution.system, setup), "expected equation")
    e = setup.scalar(lhs - rhs)
    accels = [q.diff(t, 2) for q in solution.coordinates]
    reacts = [r for r in setup.reactions if e.has(r)]
    if not e.has(*accels) and not reacts:
        return Expectation(e, shown, False, "it contains neither an acceleration of the independent coordinates "
                           + ", ".join(text(q) for q in solution.coordinates) + " nor a reaction", dimensions=dims)
    best = None
    for i, r in enumerate(solution.regimes):
        resid = e.xreplace(dict(r.signs))
        if reacts:
            resid = resid.xreplace({sym: r.reactions[str(sym)] for sym in reacts}).xreplace(dict(r.signs))
        resid = resid.xreplace({q.diff(t, 2): a for q, a in r.accelerations.items()})
        ok, how = compare(resid, 0, manifold_of(solution))
        what = "accelerations and reactions" if reacts else "accelerations"
        if ok:
            return Expectation(e, shown, True, f"it holds for every state with the derived {what}; " + how,
                               i if len(solution.regimes) > 1 else None, dimensions=dims)
        if best is None:
            best = (i, r, resid, what)
    i, r, resid, what = best
    diffs, derived = _term_differences(e.xreplace(dict(r.signs)), r, solution) if not reacts else ([], None)
    resid = solution.setup.kin.simplify_expr(resid) if sp.count_ops(resid) < 200 else resid
    return Expectation(e, shown, False, f"it does not hold with the derived {what}",
                       i if len(solution.regimes) > 1 else None, tuple(diffs), resid, dims, derived)


def _term_differences(e, regime, solution):
    """Terms of ``e`` that differ from the derived equation scaled to match it best (1 DOF), or the
    derived combination with the same acceleration coefficients (several DOF)."""
    accels = [q.diff(t, 2) for q in solution.coordinates]
    if len(accels) == 1:
        derived = regime.eom[0]
    else:
        M, f = regime.mass_matrix, regime.forcing
        c = sp.Matrix([sp.expand(e).coeff(a) for a in accels])
        try:
            lam = M.T.LUsolve(c)
        except (ValueError, ZeroDivisionError):
            return [], None
        derived = sum((lam[i] * (sum((M[i, j] * accels[j] for j in range(len(accels))), sp.Integer(0)) - f[i])
                       for i in range(len(accels))), sp.Integer(0))
        derived = algebra.readable(derived)
    U = list(sp.Add.make_args(sp.expand(e)))
    R = list(sp.Add.make_args(sp.expand(derived)))
    if len(U) * len(R) > 400:       # too many terms to pair up: the residual says what differs
        return [], derived
    scales = []
    for u in U:
        for r in R:
            try:
                c = sp.cancel(u / r)
            except (sp.PolynomialError, ZeroDivisionError):
                continue
            if c != 0 and not algebra.functions_of_time(c) and not c.has(t) and not c.has(*accels) \
                    and not any(sp.sympify(c - s) == 0 for s in scales):
                scales.append(c)
    best, best_score = sp.Integer(1), -1
    for c in scales[:40]:
        score = sum(1 for u in U if any(_eq(u, c * r) for r in R))
        if score > best_score:
            best, best_score = c, score
    scaled = [best * r for r in R]
    left_u = [u for u in U if not any(_eq(u, r) for r in scaled)]
    left_r = [r for r in scaled if not any(_eq(u, r) for u in U)]
    pairs = []
    for u in list(left_u):
        for r in list(left_r):
            ratio = sp.cancel(u / r)
            if not algebra.functions_of_time(ratio) and not ratio.has(t):
                pairs.append((u, sp.expand(r)))
                left_u.remove(u)
                left_r.remove(r)
                break
    pairs += [(u, None) for u in left_u] + [(None, sp.expand(r)) for r in left_r]
    return pairs, sp.expand(best * derived)


def _eq(a, b) -> bool:
    d = sp.expand(a - b)
    return d == 0 or sp.cancel(d) == 0
