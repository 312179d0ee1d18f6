"""Grading a worksheet step by step against the engine's own derivation.

Each step gets a verdict — ``correct``, ``incorrect`` or ``unreadable`` (the parser could not read the
claim; its message says why) — and feedback naming the cause.  Equations (``balance``, ``eom``) are
accepted in any equivalent form: any nonzero factor, any arrangement, any valid combination of the
balance equations (:mod:`rigidkin.grading.space`).  A wrong step is matched against the common mistakes
(:mod:`rigidkin.grading.mistakes`), then compared term by term (:mod:`rigidkin.grading.feedback`), and a
later step is also graded against the student's own earlier steps: an equation that follows from them
is a *carried error*, named with the steps it comes from.
"""

from __future__ import annotations

import itertools

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.errors import InputError
from ..base.printing import text
from ..io.expressions import parse_vector
from . import space
from .answers import grade_answer
from .claims import Unreadable, parse_claim, read
from .engine import Candidate, Reference, reference
from .feedback import dimension_problem, expandable, term_diff
from .impulse import grade_impulse
from .kinds import grade_fbd, grade_kinematics
from .mistakes import force_candidates, moment_candidates, system_candidates
from .regimes import RegimeChoice, regime_choice
from .verdicts import CORRECT, INCORRECT, UNREADABLE, Carried, GradeReport, StepResult
from .worksheet import Step, Worksheet, load_worksheet

t = dynamicsymbols._t


def grade_file(path) -> GradeReport:
    return grade(load_worksheet(path))


def grade(ws: Worksheet) -> GradeReport:
    """Grade every step of a worksheet (the problem derived once, cached for the run)."""
    ref = reference(ws.problem_ref, ws.mode)
    for st in ws.steps:
        if st.kind == "answer" and st.question not in {q.name for q in ref.spec_questions()}:
            known = ", ".join(q.name for q in ref.spec_questions()) or "none"
            raise InputError(f"the problem asks no question named '{st.question}'.", where=st.where,
                             hint=f"Questions of {ws.problem}: {known}.")
    carried = Carried()
    rc = regime_choice(ref, ws)
    results = []
    for st in ws.steps:
        claim = st.claim if isinstance(st.claim, str) else "; ".join(st.claim)
        try:
            if st.kind == "kinematics":
                res = grade_kinematics(ref, st, carried)
            elif st.kind == "fbd":
                res = grade_fbd(ref, st, carried, rc.scoped(st.question, ref), rc)
            elif st.kind == "answer":
                res = grade_answer(ref, st)
            elif st.law == "impulse":
                res = grade_impulse(ref, st)
            else:
                res = grade_equation(ref, st, carried, rc)
        except Unreadable as exc:
            res = StepResult(st.index, st.kind, UNREADABLE, [str(exc)])
        res.claim = claim
        results.append(res)
    title = ws.title or getattr(ref.spec, "title", "") or ws.problem
    return GradeReport(ws.problem, title, ws.student, results)


# equations: balance and eom ---------------------------------------------------------------------------
def _candidates(ref: Reference, st: Step, variants: bool = True):
    """The engine's equations for the law the step names (all laws when it names none), cached."""
    key = ("candidates", st.law, st.body, st.point, st.direction, variants)
    if key not in ref._rows:
        ref._rows[key] = _make_candidates(ref, st, variants)
    return ref._rows[key]


def _make_candidates(ref: Reference, st: Step, variants: bool):
    bodies = [ref.body(st.body)] if st.body else list(ref.system.bodies.values())
    if None in bodies:
        raise InputError(f"the problem has no body named '{st.body}'.", where=st.where,
                         hint=f"Bodies: {', '.join(ref.system.bodies)}.")
    direction = None
    if st.direction:
        direction = read("direction", parse_vector, st.direction, ref.scope, st.where)
    out = []
    laws = [st.law] if st.law else ["force", "moment", "energy"]
    if "force" in laws:
        dirs = [(direction, st.direction)] if direction is not None else \
            (ref.directions() if st.law else ref.axes())
        for b in bodies:
            out += force_candidates(ref, b, dirs, variants)
        if len(bodies) > 1:
            out += system_candidates(ref, bodies, dirs)
    if "moment" in laws:
        axes = [(direction, st.direction)] if direction is not None else ref.axes(moment=True)
        for b in bodies:
            if st.point:
                P = ref.point_of(st.point)
                if P is None:
                    raise InputError(f"the problem has no point named '{st.point}'.", where=st.where,
                                     hint=f"Points: {', '.join(ref.system.points)}.")
                pts = [P]
            else:
                pts = ref.body_points(b) + ref.contact_spots(b) + [ref.system.origin]
            every = _candidates(ref, st, True) if not variants else None
            out += moment_candidates(ref, b, pts, axes) if variants else \
                [c for c in every if c.mistake is None and c.law == "moment" and c.body == b.name]
    if "energy" in laws:
        out += [Candidate("work–energy: dE/dt = ΣP_nc", e, None, "energy") for e in ref.energy_equation()]
    return out


def grade_equation(ref: Reference, st: Step, carried: Carried, rc: RegimeChoice | None = None) -> StepResult:
    lhs, rhs = parse_claim(ref, st)
    expr = lhs - rhs
    res = StepResult(st.index, st.kind, INCORRECT)
    notes = []
    plain_expr = ref.scalar(expr)
    if not plain_expr.has(*ref.unknowns):
        if plain_expr.has(*[q.diff(t) for q in ref.solution.coordinates]) or \
                plain_expr.has(*ref.solution.coordinates):
            notes.append("read as a first integral: graded through its time derivative")
            wrong = _constant_at_start(ref, st, expr)
            if wrong:
                res.feedback = notes + [wrong]
                return res
            expr = sp.diff(expr, t)
        else:
            res.feedback = ["it contains no acceleration and no unknown reaction, so it cannot be an equation of "
                            "motion or a balance law of this problem"]
            return res
    if st.kind == "eom":
        reacts = [r for r in ref.setup.reactions if ref.scalar(expr).has(r)]
        if reacts:
            res.feedback = [f"an equation of motion is free of the unknown reactions, but this one contains "
                            f"{', '.join(map(str, reacts))}: eliminate them"]
            res.expected = _expected_eom(ref)
            return res
    dim = dimension_problem(ref, lhs, rhs)
    scope = (rc or RegimeChoice(ref.regimes())).scoped(st.question, ref)
    regimes = scope.for_step()
    holds = {}
    for reg in ref.regimes():
        try:
            row = ref.row(expr, reg)
        except space.NotLinear:
            res.feedback = ["it is not linear in the accelerations and reactions, as every balance law is"]
            return res
        if space.is_trivial(row):
            res.feedback = ["it reduces to 0 = 0 once the constraints are used: true, but it says nothing about "
                            "the motion"]
            return res
        holds[id(reg)] = bool(space.in_span(ref.basis(reg), row))
    good = [r for r in regimes if holds[id(r)]]
    if good:
        reg = good[0]
        if len([r for r in ref.regimes() if holds[id(r)]]) == 1 and rc is not None and scope is rc:
            rc.holds_in(reg, st.index)
        res.verdict = CORRECT
        res.feedback = notes + ([scope.note() or f"a valid combination of the balance equations "
                                 f"({_regime_text(reg, ref.regimes())})"]
                                if len(ref.regimes()) > 1 and len(good) == 1 and
                                len([r for r in ref.regimes() if holds[id(r)]]) == 1 else [])
        res.expected = _expected_eom(ref) if st.kind == "eom" else ""
        if st.kind == "balance":
            carried.balances.append((st.index, None, None))
        return res
    other = next((r for r in ref.regimes() if holds[id(r)]), None)
    if other is not None:
        res.feedback = notes + [scope.wrong_regime(other)]
        res.expected = _expected_eom(ref, regimes[0]) if st.kind == "eom" else ""
        return res
    reg = regimes[0]
    row = ref.row(expr, reg)
    # one cause, the most specific: carried from an earlier step, else a named mistake, else a dimension,
    # else the term that differs (the rest of the differing terms are listed as differences)
    fb = list(notes)
    diff, target, nearest = _best_diff(ref, st, expr, reg)
    if diff is not None:
        res.differences = [(text(u), "") for u in diff.extra] + [("", text(r)) for r in diff.missing] + \
            [(text(u), text(-u)) for u in diff.signs] + [(text(u), text(r)) for u, r in diff.coefficients]
    via = _carried(ref, row, reg, carried)
    if via:
        res.carried_from = via
        many = len(via) > 1
        fb.append("carried error: it follows correctly from your step" + ("s " if many else " ")
                  + ", ".join(map(str, via)) + ", which " + ("are" if many else "is") + " wrong; otherwise it is "
                  "right")
    else:
        causes = diff.describe() if diff is not None else []
        one_sign = diff is not None and len(diff.signs) == 1 and len(causes) == 1
        named = None if one_sign else _named_mistake(ref, st, row, reg)   # one sign flipped: that is the cause
        if named:
            fb.append(named)
        elif dim:
            fb.append(dim)
        elif causes:
            more = len(causes) - 1
            fb.append(causes[0] + (f" (and {more} more differing term{'s' if more > 1 else ''}: see the "
                                   "differences)" if more else ""))
    if len(fb) == len(notes):
        fb.append("it is not a valid combination of the balance equations")
    res.feedback = fb
    res.expected = target
    if st.kind == "balance":
        carried.balances.append((st.index, expr, nearest))
    return res


def _constant_at_start(ref: Reference, st: Step, expr) -> str | None:
    """A first integral's constant, checked at the start state of the question the step names."""
    if not st.question:
        return None
    q = next((q for q in ref.spec_questions() if q.name == st.question), None)
    start = dict((q.fields.get("start") or {}) if q is not None else {})
    if not start:
        return None
    rates = {k: v for k, v in start.items() if isinstance(k, sp.Derivative)}
    at = ref.scalar(ref.scalar(expr).xreplace(rates).xreplace(start))
    if at.has(*ref.solution.coordinates) or at.atoms(sp.Derivative):
        return None                      # the start does not fix every coordinate and rate
    vals = ref.sampler.evaluate([space.to_plain(at)])
    if space.vanishes(vals) is False:
        shown = ", ".join(f"{text(k)} = {text(v)}" for k, v in start.items())
        return (f"constant: the integral does not hold at the start of '{st.question}' ({shown}); its value there "
                f"leaves {text(ref.kin.simplify_expr(at))} ≠ 0")
    return None


def _regime_text(reg, regimes) -> str:
    return f"regime {regimes.index(reg) + 1}: {reg.describe()}"


def _named_mistake(ref: Reference, st: Step, row, reg) -> str | None:
    basis = ref.basis(reg)
    cands = _all_mistakes(ref, st)
    for c in cands:
        if c.mistake is None:
            continue
        try:
            v = ref.row(c.expr, reg)
        except space.NotLinear:
            continue
        if space.in_span(basis, v):
            continue                    # the "mistake" is harmless here (e.g. P fixed)
        for j in _replaceable(ref, basis, c.correct, reg):
            trial = basis[:j] + basis[j + 1:] + [v]
            if ref.determinate_like(trial, reg) and space.in_span(trial, row):
                return c.mistake
    return None


def _all_mistakes(ref: Reference, st: Step):
    if st.kind == "balance" and st.law in ("force", "moment"):
        return _candidates(ref, st)
    # an equation of motion: every mistake of every law that leads to it
    key = "eom-mistakes"
    if key not in ref._rows:
        ref._rows[key] = _candidates(ref, Step(0, "balance", "", st.where, law="moment")) + \
            _candidates(ref, Step(0, "balance", "", st.where, law="force"))
    return ref._rows[key]


def _carried(ref: Reference, row, reg, carried: Carried) -> tuple[int, ...]:
    """The fewest earlier wrong steps this equation follows from (empty when none explains it)."""
    wrong = [(i, e, c) for i, e, c in carried.balances if e is not None]
    mods = [(i, "accel", b, v) for b, (i, v) in carried.accel.items()] + \
        [(i, "alpha", b, v) for b, (i, v) in carried.alpha.items()] + \
        [(i, "loads", b, v) for b, (i, v) in carried.loads.items()]
    base = ref.basis(reg)
    n_full = base[0].shape[1] if base else 0
    for size in range(1, 4):
        for nm in range(0, min(size, len(mods)) + 1):
            nb = size - nm
            if nb > len(wrong):
                continue
            for mset in itertools.combinations(mods, nm):
                starts = [base] if not mset else _determinate_subsets(
                    ref, [ref.row(e, reg) for e in _modified_cached(ref, mset, carried.cache)], reg)
                for start, bset in itertools.product(starts, itertools.combinations(wrong, nb)):
                    rows = [ref.row(e, reg) for _, e, _ in bset]
                    allowed = [_replaceable(ref, start, c, reg) for _, _, c in bset]
                    for drop in itertools.product(*allowed):
                        if len(set(drop)) < len(drop):
                            continue
                        trial = [r for j, r in enumerate(start) if j not in drop] + rows
                        if _spans_all(trial, n_full) or not ref.determinate_like(trial, reg):
                            continue
                        try:
                            if space.in_span(trial, row):
                                return tuple(sorted({m[0] for m in mset} | {i for i, _, _ in bset}))
                        except space.NotLinear:
                            continue
    return ()


def _determinate_subsets(ref: Reference, rows, reg) -> list:
    """The student's equations as they stand, or — when a load left off the diagram makes them imply more
    than the engine's (one equation too many) — each set with one equation left out."""
    if ref.determinate_like(rows, reg):
        return [rows]
    return [rows[:j] + rows[j + 1:] for j in range(len(rows)) if ref.determinate_like(rows[:j] + rows[j + 1:], reg)]


def _replaceable(ref: Reference, rows, counterpart, reg) -> list[int]:
    """The rows the correct form of a wrong equation could stand in for (the student wrote it in their place)."""
    if counterpart is None:
        return list(range(len(rows)))
    try:
        c = ref.row(counterpart, reg)
    except space.NotLinear:
        return list(range(len(rows)))
    out = []
    for j in range(len(rows)):
        rest = rows[:j] + rows[j + 1:] + [c]
        if space.in_span(rest, rows[j]):
            out.append(j)
    return out


def _spans_all(rows, n: int) -> bool:
    """The rows span every equation (an inconsistent set: anything would follow from it)."""
    import numpy as np

    if len(rows) < n:
        return False
    M = np.stack(rows, axis=1)
    for i in range(M.shape[0]):
        if np.all(np.isfinite(M[i])):
            return np.linalg.matrix_rank(M[i], tol=1e-9 * max(1.0, np.abs(M[i]).max())) >= n
    return False


def _modified_cached(ref: Reference, mods, cache: dict) -> list:
    key = tuple((i, kind, b.name) for i, kind, b, _ in mods)
    if key not in cache:
        cache[key] = _modified_equations(ref, mods)
    return cache[key]


def _modified_equations(ref: Reference, mods) -> list:
    """Newton–Euler for every body with the student's wrong a_G, α or diagram in place of the engine's."""
    from sympy.physics.vector import Vector

    kin = ref.kin
    exprs = []
    for b in ref.system.bodies.values():
        own = {kind: v for _, kind, body, v in mods if body is b}
        aG = own.get("accel", kin.acceleration(b.centre))
        alpha = own.get("alpha", kin.alpha(b.frame))
        if "loads" in own:
            F = Vector(0)
            for v, loc in own["loads"]:
                if loc is not None:
                    F += v
            M = ref.moment_vector(b, kin.position(b.centre), own["loads"])
        else:
            bal = ref.balance(b)
            F, M = bal.force, bal.moment
        w = kin.omega_of(b)
        dH = b.inertia.dot(alpha) + w.cross(b.inertia.dot(w))
        for e, _ in ref.axes():
            exprs.append(ref.scalar(ref.setup.vector(F - b.mass * aG).dot(e)))
        for e, _ in ref.axes(moment=True):
            exprs.append(ref.scalar(ref.setup.vector(M - dH).dot(e)))
    return [e for e in exprs if e != 0]


def _best_diff(ref: Reference, st: Step, expr, reg):
    """The engine's equation nearest to the student's, and the term-by-term differences."""

    student = ref.scalar(expr, reg)
    if not expandable(student):
        return None, "", None
    student = sp.expand(student)
    if st.kind == "eom":
        cands = [sp.expand(ref.scalar(e, reg)) for e in _eom_forms(ref, reg, student)]
    else:
        cands = [sp.expand(ref.scalar(c.expr, reg)) for c in _candidates(ref, st, variants=False)]
    best, best_e = None, None
    for c in cands:
        if c == 0:
            continue
        d = term_diff(student, c)
        if d is not None and (best is None or d.score > best.score):
            best, best_e = d, c
    target = "" if best_e is None else f"{text(sp.expand(best.scale * best_e))} = 0"
    return best, target, best_e


def _eom_forms(ref: Reference, reg, student):
    out = list(reg.eom)
    accels = [q.diff(t, 2) for q in ref.solution.coordinates]
    if len(accels) > 1:
        M, f = reg.mass_matrix, reg.forcing
        c = sp.Matrix([student.coeff(a) for a in accels])
        try:
            lam = M.T.LUsolve(c)
            out.append(sum((lam[i] * (sum((M[i, j] * accels[j] for j in range(len(accels))), sp.S.Zero) - f[i])
                            for i in range(len(accels))), sp.S.Zero))
        except (ValueError, ZeroDivisionError):
            pass
    return out


def _expected_eom(ref: Reference, reg=None) -> str:
    reg = reg or ref.regimes()[0]
    return "; ".join(f"{text(e)} = 0" for e in reg.eom)
