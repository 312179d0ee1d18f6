"""Statically indeterminate reactions: what the balance laws determine when no-slip rows repeat each other.

A body held from slipping at two supports (a block on two rolling corners, a rod sticking on two rough
supports) has two no-slip rows that say the same thing about its motion.  The kinematics keeps one of
them (``split_redundant``); the repeated one still brings its reaction into the balance laws.  The
motion is determined, and so are the normal forces (moment balance about each support), but of the
friction forces only a combination is (their sum balances the applied tangential load).

``determinacy`` solves the balance equations A u = −b for what they determine, as the reduced
row-echelon form does: the unknowns are taken in order, each that adds to the rank is solved for, the
rest (the free reactions) are left as symbols; an unknown whose solution holds no free reaction is
determinate, the others are named, and each pivot that holds one gives a determinate combination
(F_A + F_C = 0).  Where friction is limited (|F| ≤ µN at each sticking contact) a split that sticks
exists iff the combination's value lies within Σ |c_i| µ_i N_i (the sum of intervals is an interval).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from ..base import algebra
from ..base.errors import ConstraintError
from ..base.linear import linear_form, solve_linear
from ..base.printing import text
from . import conflict
from .determinacy import _determinacy, _numeric_fast
from .regime import Condition


def split_redundant(relating, numA, A=None, b=None, tol: float = 1e-9):
    """(indices of the rows kept, rows that repeat the others): the no-slip rows are tried last, so that
    what repeats is a friction row where it can be.  ``numA`` holds the rows' rate coefficients (numbers);
    with the rows A u̇ + b (symbolic), a repeated row that asks another speed is refused."""
    import numpy as np

    order = ([i for i, r in enumerate(relating) if r.kind != "tangential"]
             + [i for i, r in enumerate(relating) if r.kind == "tangential"])
    keep = []
    for i in order:
        if np.linalg.matrix_rank(numA[keep + [i]], tol=tol) == len(keep) + 1:
            keep.append(i)
    keep.sort()
    redundant = [relating[i] for i in range(len(relating)) if i not in keep]
    if redundant and A is not None:         # the same motion, or two supports that disagree (belts at two speeds)
        nAb = _numeric_fast(A.row_join(b), 3)
        if np.linalg.matrix_rank(nAb, tol=tol * max(1.0, float(np.abs(nAb).max()))) > len(keep):
            raise ConstraintError(
                f"the constraint rows {', '.join(repr(r.label) for r in redundant)} hold the same motion as the "
                "others but ask a different speed of it: no motion satisfies them all.",
                where=", ".join(sorted({r.constraint for r in redundant})),
                hint="Two supports that hold a body from slipping must move alike; open one or let it slip.")
    return keep, redundant


def rest_configuration(system, kin, dependent, rows, trace=None) -> dict:
    """At rest on repeated supports (no degree of freedom): the coordinates the closed gaps fix (a block flat
    on its two corners: θ = 0, y = h/2), the root nearest the declared starting values.  Which reactions are
    determinate depends on the configuration, so it is found before the balance laws are solved."""
    plain = {q: sp.Dummy(q.func.__name__) for q in dependent}
    eqs = [sp.sympify(r.gap).xreplace(plain) for r in rows if r.gap is not None and r.gap != 0]
    cand = [plain[q] for q in dependent if any(e.has(plain[q]) for e in eqs)]
    if not cand or any(algebra.functions_of_time(e) for e in eqs) or sum(sp.count_ops(e) for e in eqs) > 400:
        return {}               # (a large system of gaps is left to the state: no closed form sought)
    try:
        roots = sp.solve(eqs, cand, dict=True)
    except (NotImplementedError, ValueError, TypeError):
        return {}
    values = {p.symbol: sp.Float(p.value) for p in system.parameter_info.values() if p.value is not None}
    start = {plain[q]: system.coordinate_of(q).initial for q in dependent}
    best, far = None, None
    for root in roots:
        try:
            d = sum(abs(complex(v.xreplace(values).evalf()) - (start[k] or 0.0)) for k, v in root.items()
                    if not v.has(*cand))
        except (TypeError, ValueError):
            continue
        if far is None or d < far - 1e-12:
            best, far = root, d
    if best is None and len(roots) == 1:        # parameters without values: the one root there is
        best = roots[0]
    if best is None:
        return {}
    back = {v: k for k, v in plain.items()}
    out = {back[k]: kin.simplify_expr(v) for k, v in best.items() if not v.has(*cand)}
    if trace is not None and out:
        trace.add("Kinematics", "Configuration at rest", list(out.items()),
                  "no degree of freedom: the closed contacts fix these coordinates (of the roots of their gaps, "
                  "the one nearest the declared starting values).")
    return out


@dataclass(frozen=True)
class Indeterminacy:
    """What the balance laws leave undetermined in a mode: ``reactions`` (names) cannot be found one by
    one; each of ``combinations`` (expression, value) can.  ``solved`` maps every determinate unknown
    (q̈ and reactions) to its value; ``friction`` says how friction limits were checked."""

    reactions: tuple[str, ...]
    combinations: tuple[tuple[sp.Expr, sp.Expr], ...]
    solved: dict = field(repr=False, compare=False)
    friction: tuple[str, ...] = ()
    conditions: tuple = ()

    def lines(self) -> list[str]:
        """The statement for a reader (the text under a heading "Statically indeterminate")."""
        out = [f"{' and '.join(self.reactions)} individually: statically indeterminate (the balance laws do not "
               "separate them); they determine only"]
        out += [f"    {text(c)} = {text(v)}" for c, v in self.combinations]
        return out + list(self.friction)

    def data(self) -> dict:
        """For JSON: the indeterminate reactions, the determinate combinations and the friction check."""
        return {"reactions": list(self.reactions),
                "combinations": [{"expression": str(c), "value": str(v)} for c, v in self.combinations],
                "friction": list(self.friction)}


def determinacy(setup, A: sp.Matrix, b: sp.Matrix, unknowns, equations, dof_note: str, working, trace):
    """None where the model has no repeated no-slip row (the ordinary check, ``_determinacy``, which
    refuses what is not determinate); otherwise the ``Indeterminacy`` of the balance equations."""
    import numpy as np

    red, labels = setup.reduction, [e.label for e in equations]
    if not getattr(red, "redundant", ()):
        _determinacy(A, b, unknowns, labels, dof_note, equations, setup)
        return None
    nAb = _numeric_fast(A.row_join(b), 5)
    nA = nAb[:, :-1]
    tol = 1e-9 * max(1.0, float(np.abs(nA).max()))
    rank = np.linalg.matrix_rank(nA, tol=tol)
    _, _, vh = np.linalg.svd(nA)
    null = vh[rank:].conj().T
    loose = [u for i, u in enumerate(unknowns) if null.size and np.abs(null[i]).max() > 1e-8]
    n_acc = len(red.independent)
    bad = [u for u in loose if unknowns.index(u) < n_acc or u in working]
    if bad or not loose:        # q̈ or a working reaction undetermined: the ordinary refusal; nothing loose: none
        _determinacy(A, b, unknowns, labels, dof_note, equations, setup)
        return None
    pivots: list[int] = []
    for j in range(len(unknowns)):
        if np.linalg.matrix_rank(nA[:, pivots + [j]], tol=tol) == len(pivots) + 1:
            pivots.append(j)
    free = [unknowns[j] for j in range(len(unknowns)) if j not in pivots]
    _consistent(nA, nAb[:, -1:], pivots, unknowns, equations, dof_note, setup)
    rhs = -b - (A.extract(list(range(A.rows)), [unknowns.index(f) for f in free]) * sp.Matrix(free))
    x = solve_linear(A.extract(list(range(A.rows)), pivots), rhs, simplify=setup.kin.simplify_expr)
    solved, combos = {}, []
    for j, value in zip(pivots, x):
        K, rest = linear_form([value], free)
        if all(k == 0 for k in K):
            solved[unknowns[j]] = value
        else:
            lhs = unknowns[j] - sum((setup.kin.simplify_expr(k) * f for k, f in zip(K, free)), sp.Integer(0))
            combos.append((lhs, setup.kin.simplify_expr(rest[0])))
    names = tuple(str(u) for u in unknowns if u in loose)
    friction, conds = _friction(setup, combos, solved)
    out = Indeterminacy(names, tuple(combos), solved, friction, conds)
    trace.add("Solving", "Statically indeterminate reactions", [(c, v) for c, v in combos],
              f"the constraint rows {', '.join(repr(r.label) for r in red.redundant)} repeat what the others impose, "
              "so "
              f"the balance laws determine the motion and {len(solved) - n_acc} reaction(s), but not "
              f"{', '.join(names)} one by one: only the combinations above (reduced row-echelon form of the "
              "balance equations).")
    return out


def _consistent(nA, nb, pivots, unknowns, equations, dof_note, setup) -> None:
    """Every balance equation holds with the pivots solved (least squares residual zero); where not, the
    equation in conflict is named (derive/conflict.py)."""
    import numpy as np

    x, *_ = np.linalg.lstsq(nA[:, pivots], nb, rcond=None)
    resid = np.abs(nA[:, pivots] @ x - nb).ravel()
    scale = max(1.0, float(np.abs(nb).max()))
    bad = [eq.label for i, eq in enumerate(equations) if resid[i] > 1e-8 * scale]
    named = conflict.explain(setup, equations, nA, nb, unknowns) if bad else None
    if named:
        raise ConstraintError(named[0], hint=f"{named[1]} {dof_note}", where=named[2] or None)
    if bad:
        raise ConstraintError(
            f"the balance laws give {len(equations)} equations for {len(unknowns)} unknowns "
            f"({', '.join(text(u) for u in unknowns)}), and {'; '.join(bad)} contradict the others.",
            hint=f"A load has no reaction to carry it, or a constraint is missing. {dof_note}")


def _friction(setup, combos, solved) -> tuple[tuple[str, ...], tuple]:
    """The friction limits of the sticking contacts in each combination: a split with |F_i| ≤ µ_i N_i
    exists iff |value| ≤ Σ |c_i| µ_i N_i (each F_i in one combination only, the N_i determinate)."""
    contacts = {c.F: c for c in setup.system.constraints.values()
                if getattr(c, "kind", "") == "contact" and setup.states.get(c.name) == "stick"}
    notes, conds = [], []
    seen: dict = {}
    for lhs, _ in combos:
        for f in lhs.free_symbols & set(contacts):
            seen[f] = seen.get(f, 0) + 1
    for lhs, value in combos:
        terms = [(f, lhs.coeff(f)) for f in sorted(lhs.free_symbols & set(contacts), key=str)]
        if not terms:
            continue
        names = ", ".join(contacts[f].name for f, _ in terms)
        limited = [(f, c) for f, c in terms if hasattr(contacts[f].friction, "mu")]
        if len(limited) < len(terms):
            notes.append(f"friction at {names}: a rolling (no-slip) contact carries any friction, so a split that "
                         "sticks always exists")
            continue
        if any(seen[f] > 1 or contacts[f].N not in solved for f, _ in terms) or lhs.free_symbols - set(contacts):
            notes.append(f"friction at {names}: the split is tied to other reactions; |F| ≤ µN is not checked "
                         "here (a simulation settles it)")
            continue
        cap = sum((sp.Abs(c) * getattr(contacts[f].friction, "static", contacts[f].friction.mu) * solved[contacts[f].N]
                   for f, c in terms), sp.Integer(0))
        cap = setup.kin.simplify_expr(cap)
        label = f"a split of the friction at {names} within µN exists"
        for sign in ((1,) if value == 0 else (-1, 1)):
            conds.append(Condition(setup.kin.simplify_expr(cap + sign * value), ">=", label, "validity"))
        notes.append(f"friction at {names}: a split with |F| ≤ µN at each contact exists iff |{text(lhs)}| ≤ "
                     f"{text(cap)}, that is {text(cap)} ≥ {text(sp.Abs(value))}; no split is chosen: any split within "
                     "these limits satisfies the balance laws")
    return tuple(notes), tuple(conds)


def validity(setup, react, conditions, undetermined) -> tuple:
    """The regime's validity conditions: those of each contact, the friction limits of the combinations
    (``undetermined``), and where contacts are held (``setup.held``: named ``slip``, but the others keep
    their slip speed at zero, so one sticking contact carries their friction with its own) the limit of
    that contact raised by theirs, |F| ≤ µ N + Σ µ_h N_h, as the simulator takes it."""
    out = list(conditions) + list(undetermined.conditions if undetermined else ())
    held = [setup.system.constraints[h] for h in getattr(setup, "held", ())]
    sticking = [c for c in setup.system.constraints.values() if setup.states.get(c.name) == "stick"
                and hasattr(getattr(c, "friction", None), "mu") and str(c.F) in react]
    if not held or len(sticking) != 1 or any(str(h.N) not in react for h in held):
        return tuple(out)
    c = sticking[0]
    mine = f"friction at {c.name} within "
    out = [cd for cd in out if not cd.label.startswith(mine)]
    cap = sum((getattr(x.friction, "static", x.friction.mu) * react[str(x.N)] for x in [c] + held), sp.Integer(0))
    label = (f"friction at {c.name}, which carries that of {', '.join(h.name for h in held)}, within "
             f"µN summed over them (no slip)")
    F = react[str(c.F)]
    return tuple(out) + tuple(Condition(setup.kin.simplify_expr(cap + sign * F), ">=", label, "validity")
                              for sign in ((1,) if F == 0 else (-1, 1)))
