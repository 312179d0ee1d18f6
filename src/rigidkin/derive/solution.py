"""Solving the balance equations: accelerations and reactions jointly, regime by regime.

The scalar equations are linear in the unknown accelerations q̈ and reactions.  Before solving,
their numeric rank at random states tells whether the model is determinate; if not, the error
names the unknowns that cannot be found or the equations that cannot hold.  When a reaction does
work (a normal force that sets a sliding-friction magnitude) all unknowns are solved jointly
(Gaussian elimination with numeric pivoting, simplified for reading).  Otherwise the accelerations
come from the reaction-free equations M q̈ = f and the reactions from the balance equations with
the accelerations known — the same unknowns, in two small steps instead of one large one (a chain
of three rods: seconds instead of minutes); both are computed when first asked for.

The equations of motion free of reactions are formed by combining each body's balance with the
weights that make workless reactions cancel (the partial velocities of the mass centre and the
partial angular velocities with respect to each independent rate); the reactions that do work (a
normal force that sets a sliding-friction magnitude) are replaced by their solved values.  These
rows give the mass matrix and forcing; their accelerations must equal the joint solution's, which
is checked every time.

Where a load depends on a sign (the direction of sliding friction; the sign of a bilateral normal
force under friction) the solution is split into regimes, each with its condition, never a
``sign()`` hidden in an expression.
"""

from __future__ import annotations

import functools
import itertools
import random
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base import algebra, display
from ..base.errors import RegimeError, RigidkinError
from ..base.linear import solve_linear
from ..base.printing import latex, text
from ..base.trace import LazyEquations, Trace
from ..base.trigforms import compact
from ..base.vectorops import dot, in_frame
from ..model.profiles import arc_margins
from ..model.speeds import quaternion_groups
from . import closed_forms, indeterminate
from .determinacy import _determinacy  # noqa: F401 (re-exported: numeric/compiled/codegen.py)
from .evaluation import reactions_at
from .keyed import keyed, to_ours
from .kinematics import linear_form
from .mode import ModeSetup
from .regime import Condition, Deferred, LazyMap, Regime  # noqa: F401 (Condition, LazyMap: re-exported)
from .to_sympy import Bridge

t = dynamicsymbols._t


@dataclass(frozen=True)
class Solution(Bridge):
    """The result of a law: equations of motion in normal and mass-matrix form, reactions, regimes.

    ``eom`` (each ``= 0``), ``accelerations`` (coordinate → q̈), ``reactions`` (name → expression
    of the state), ``mass_matrix`` and ``forcing`` refer to the single regime; with several regimes
    pick one with :meth:`regime` (they raise :class:`RegimeError` otherwise).  Every mapping is found by
    its key, by name (``'theta'``, ``'N'``, ``'dot(phi)'``) or by sympy's own symbol (derive/keyed.py);
    ``subs``, ``to_sympy``, ``to_sympy_system`` and ``rhs`` hand it to sympy, PyDy and scipy.
    """

    system: object
    method: str
    states: Mapping
    coordinates: tuple
    dependent: tuple
    relations: Mapping              # q_d → f(q_i) (integrated constraint relations)
    rate_relations: Mapping         # q̇_d → expression
    regimes: tuple[Regime, ...]
    equations: tuple                # the balance equations the law formed (BalanceEquation)
    trace: Trace = field(compare=False)
    setup: ModeSetup = field(compare=False, repr=False)

    def __post_init__(self):            # found by key, by name or by sympy's own symbol (derive/keyed.py)
        object.__setattr__(self, "relations", keyed(self.relations, "relations (q_d → f(q_i))"))
        object.__setattr__(self, "rate_relations", keyed(self.rate_relations, "rate relations (q̇_d → ...)"))

    # single-regime access -------------------------------------------------------------------
    def _one(self) -> Regime:
        if len(self.regimes) == 1:
            return self.regimes[0]
        raise RegimeError(
            f"this solution has {len(self.regimes)} regimes: "
            + "; ".join(f"[{i}] {r.describe()}" for i, r in enumerate(self.regimes)) + ".",
            hint="Pick one with solution.regime(i) or solution.regime_at(state).")

    @property
    def eom(self) -> tuple:
        return self._one().eom

    @property
    def accelerations(self) -> Mapping:
        return self._one().accelerations

    @property
    def reactions(self) -> Mapping:
        return self._one().reactions

    @property
    def mass_matrix(self) -> sp.Matrix:
        return self._one().mass_matrix

    @property
    def forcing(self) -> sp.Matrix:
        return self._one().forcing

    @property
    def validity(self) -> tuple:
        return self._one().validity

    @functools.cached_property
    def warnings(self) -> tuple[str, ...]:
        """Where the model's own laws disagree: dE/dt = ΣP_nc checked at a few random states (cheap)."""
        from .laws.consistency import power_balance_warnings

        return tuple(power_balance_warnings(self))

    def check(self, laws=None, expect=(), dimensions: bool = True):
        """Derive the equations of motion by every other law that applies and compare (a CheckReport)."""
        from .laws.crosscheck import cross_check

        return cross_check(self, laws=laws, expect=expect, dimensions=dimensions)

    def reactions_at(self, state: Mapping, values: Mapping | None = None, regime: Regime | None = None) -> dict:
        """Every reaction as a number at ``state`` ({q: value, q̇: value}; parameters from ``values`` or
        their declared values): finite wherever the physics is (a numeric solve of the balance equations
        where a closed form has 0/0)."""

        return reactions_at(self, to_ours(self.system, state, "the state"), to_ours(self.system, values), regime)

    def regime(self, index: int = 0) -> Regime:
        return self.regimes[index]

    def regime_at(self, values: Mapping) -> Regime:
        """The regime whose conditions hold at numeric ``values`` (symbols and q, q̇ → numbers).

        Coordinates and rates not given take their declared initial values (else 0), parameters their
        values.  Where a condition is exactly zero (a slip speed at a start from rest) the regime is the
        one whose condition its rate of change satisfies (the slip that starts).
        """
        values = _complete(self, to_ours(self.system, values))
        missing = sorted({str(s) for c in (c for r in self.regimes for c in r.conditions)
                          for s in sp.sympify(c.expr).free_symbols} - {str(k) for k in values} - {"t"})
        if missing:
            raise RegimeError(f"the regime depends on {', '.join(missing)}, which have no value.",
                              hint="Give the parameters values.")
        zero = []
        for r in self.regimes:
            ok = True
            for c in r.conditions:
                v = float(_evaluate(c.expr, values))
                if abs(v) <= 1e-12:
                    zero.append(c.label)
                    acc = {q.diff(t, 2): a for q, a in r.accelerations.items()}
                    v = float(_evaluate(sp.diff(c.expr, t).xreplace(acc), values))
                ok = ok and c.holds(v)
            if ok:
                return r
        if zero:
            raise RegimeError(f"at this state the condition of every regime is zero ({zero[0]}) and no slip "
                              "starts from it: the contact sticks.",
                              hint="Ask with the contact's mode set to 'stick' (mode = { contact = \"stick\" }).")
        raise RegimeError("no regime's conditions hold at the given state.")

    # presentation ------------------------------------------------------------------------------
    def __str__(self) -> str:
        return display.render(self, "text")

    def _repr_html_(self) -> str:
        return display.render(self, "html")

    def _repr_latex_(self) -> str:
        lines = []
        rel = {">": ">", "<": "<", ">=": r"\geq", "<=": r"\leq"}
        for i, r in enumerate(self.regimes):
            if len(self.regimes) > 1:
                conds = r" \text{ and } ".join(f"{latex(c.expr)} {rel[c.relation]} 0" for c in r.conditions)
                lines.append(rf"\text{{Regime {i}: }} {conds}\\")
            lines += [f"{latex(e)} = 0" + r"\\" for e in r.eom]
        return "$\\displaystyle \\begin{gathered}" + "\n".join(lines) + "\\end{gathered}$"


def _complete(solution, values: Mapping) -> dict:
    """Values with every coordinate and rate (declared initial values, else 0) and every parameter."""
    out = dict(values)
    for p in solution.system.parameter_info.values():
        if p.symbol not in out and p.value is not None:
            out[p.symbol] = p.value
    for c in solution.system.coordinate_info.values():
        if c.symbol not in out:
            out[c.symbol] = c.initial if c.initial is not None else 0
        if c.symbol.diff(t) not in out:
            out[c.symbol.diff(t)] = c.rate if c.rate is not None else 0
    return out


def _evaluate(expr, values: Mapping) -> float:
    plain, back = algebra.plain_state(sp.sympify(expr))
    fwd = {s: values[orig] for s, orig in back.items() if orig in values}
    rest = {k: v for k, v in values.items() if not isinstance(k, (sp.Derivative, sp.Function))}
    val = plain.xreplace({k: sp.Float(v) for k, v in {**fwd, **rest}.items()})
    return complex(sp.sympify(val).evalf()).real


# --------------------------------------------------------------------------------------------------
#: The seed of sympy's random algorithms (factoring, polynomial gcds inside simplification).
SYMPY_SEED = 14


def repeatable() -> None:
    """Seed sympy's random algorithms: the same input gives the same printed forms in every run."""
    from sympy.core import random as sympy_random

    sympy_random.seed(SYMPY_SEED)


def solve_balance(setup: ModeSetup, equations, balances, method: str, trace: Trace) -> Solution:
    """Solve balance equations (linear in q̈_i and reactions) for every regime of the mode."""
    repeatable()
    red = setup.reduction
    accels = [q.diff(t, 2) for q in red.independent]
    present = set().union(*[e.expr.free_symbols for e in equations]) if equations else set()
    reactions = [r for r in setup.reactions if r in present]
    missing = [r for r in setup.reactions if r not in present]
    unknowns = accels + reactions
    trace.add("Solving", "Unknowns", [],
              f"{len(equations)} scalar equations for {len(unknowns)} unknowns: "
              + ", ".join(text(u) for u in unknowns) + "."
              + (f" The reactions {', '.join(map(str, missing))} appear in no equation (they are zero)."
                 if missing else ""))
    used = set().union(*[e.expr.free_symbols for e in equations]) if equations else set()
    choices = [c for c in setup.sign_choices if c.symbol in used]
    regimes = []
    for signs in itertools.product((1, -1), repeat=len(choices)):
        sign_map = {c.symbol: s for c, s in zip(choices, signs)}
        regimes.append(_solve_regime(setup, choices, equations, balances, unknowns, reactions, missing,
                                     sign_map, trace))
    return Solution(setup.system, method, MappingProxyType(dict(setup.states)), tuple(red.independent),
                    tuple(red.dependent), MappingProxyType(dict(red.coord_map)),
                    MappingProxyType({k: setup.scalar(v) for k, v in red.rate_map.items()}),
                    tuple(regimes), tuple(equations), trace, setup)


def _solve_regime(setup, choices, equations, balances, unknowns, reactions, missing, sign_map, trace) -> Regime:
    kin, red = setup.kin, setup.reduction
    exprs = [e.expr.xreplace(sign_map) for e in equations]
    A, b = linear_form(exprs, unknowns)
    red_ = setup.reduction
    dof_note = (f"{len(red_.independent) + len(red_.dependent)} coordinates and {len(red_.relating)} "
                f"rate-relating constraint rows leave {red_.dof} degree(s) of freedom; the constraints "
                f"bring the reactions {', '.join(map(str, setup.reactions)) or 'none'}.")
    raw_rows = _projected_rows(setup, balances, sign_map)
    working = _working_reactions(raw_rows, reactions)
    # None, or what the balance laws leave undetermined (repeated no-slip rows: derive/indeterminate.py)
    undetermined = indeterminate.determinacy(setup, A, b, unknowns, equations, dof_note, working, trace)
    accel_syms = [q.diff(t, 2) for q in red.independent]
    if working or undetermined:
        solved = (undetermined.solved if undetermined
                  else dict(zip(unknowns, solve_linear(A, -b, simplify=kin.simplify_expr))))
        accels = {q: solved[q.diff(t, 2)] for q in red.independent}
        react = {str(r): solved[r] for r in reactions if r in solved}
        for r in missing:
            react[str(r)] = sp.Integer(0)
        M_raw, f_raw = _rows_to_mf(setup, raw_rows, reactions, solved, working)
        _check_consistency(M_raw, f_raw, accels, red.independent)
        accel_map, react_map = MappingProxyType(accels), MappingProxyType(react)
        how = "all unknowns from the scalar equations at once."
    else:
        M_raw, f_raw = _rows_to_mf(setup, raw_rows, reactions, {}, working)
        choice = closed_forms.choose(M_raw, f_raw)
        regime_box: list = []

        def accelerations():
            repeatable()
            M, f = regime_box[0].mass_matrix, regime_box[0].forcing
            return dict(zip(red.independent, solve_linear(M, f, simplify=kin.simplify_expr, symmetric=True)))

        def solved_reactions():
            if not reactions:          # a free body: no reaction to solve for
                return {str(r): sp.Integer(0) for r in missing}
            # a closed-form q̈ too large to read (or to build quickly): the reactions are given in terms of q̈,
            # which M q̈ = f gives at any state
            acc = accel_map if choice.closed else {q: q.diff(t, 2) for q in red.independent}
            rhs = -b - A.extract(list(range(A.rows)), list(range(len(accel_syms)))) * sp.Matrix(
                [acc[q] for q in red.independent]) if accel_syms else -b      # 0 DOF: statics
            Al = A.extract(list(range(A.rows)), list(range(len(accel_syms), len(unknowns))))
            # determinate and consistent: checked for all the unknowns together above
            repeatable()
            lam = solve_linear(Al, rhs, simplify=kin.simplify_expr)
            out = {str(r): v for r, v in zip(reactions, lam)}
            out.update({str(r): sp.Integer(0) for r in missing})
            return out

        accel_map, react_map = LazyMap(accelerations), LazyMap(solved_reactions)
        how = ("the accelerations from the reaction-free equations M q̈ = f; then the reactions from the "
               "balance equations with the accelerations known"
               + (f" (written in terms of q̈: {choice.reason})." if not choice.closed else "."))
    conditions = _regime_conditions(setup, choices, sign_map, react_map)

    @functools.cache
    def readable():
        repeatable()
        return _readable_eom(setup, M_raw, f_raw, small=closed_forms.readable_size(M_raw, f_raw))

    def validity():
        repeatable()
        return indeterminate.validity(setup, react_map, _validity(setup, react_map), undetermined)

    regime = Regime(tuple(conditions), Deferred(validity), MappingProxyType(dict(sign_map)),
                    Deferred(lambda: tuple(readable()[2])), accel_map, react_map, Deferred(lambda: readable()[0]),
                    Deferred(lambda: readable()[1]), M_raw, f_raw, undetermined)
    if not (working or undetermined):
        regime_box.append(regime)
    else:
        choice = closed_forms.FormChoice(True, 0, len(accel_syms))
    closed_forms.mark(regime, choice)
    if sign_map:
        trace.add("Solving", "Regime", [], " and ".join(str(c) for c in conditions))
    jointly = isinstance(accel_map, MappingProxyType) or accel_map.computed or (
        reactions and choice.closed and _validity_reads_reactions(setup))
    if not jointly:
        trace.add("Solving", "Mass matrix and forcing",
                  LazyEquations(lambda: [(sp.Symbol("M"), regime.mass_matrix), (sp.Symbol("f"), regime.forcing)]),
                  how)
    else:
        trace.add("Solving", "Accelerations and reactions, solved jointly",
                  LazyEquations(lambda: [(q.diff(t, 2), a) for q, a in accel_map.items()]
                                + [(sp.Symbol(k), v) for k, v in react_map.items()]), how)
    trace.add("Solving", "Equations of motion (reactions eliminated)",
              LazyEquations(lambda: [(e, 0) for e in regime.eom]),
              "each body's balance weighted by the partial velocity of its mass centre and its partial "
              "angular velocity for each independent rate: workless reactions cancel.")
    return regime


def _projected_rows(setup, balances, sign_map):
    """Σ over bodies of (F − m ā)·∂v̄/∂u + (M̄ − dH̄/dt)·∂ω/∂u for each independent rate u (negated).

    The partial velocities are the coefficients of the rates in v̄ and ω, read in one pass from their
    components (``linear_form``), kept in the frames v̄ and ω are written in (v̄ resolved in the inertial
    frame when it is written in more than two); the force (or moment) is resolved once into each of those
    frames, and each dot product is a sum of products.
    """

    rates = [q.diff(t) for q in setup.reduction.independent]
    Fr = setup.kin.F.ref
    terms: list[list] = [[] for _ in rates]
    for bal in balances:
        # each partial velocity in the frames the velocity is written in (no angle brought into a term where
        # it cancels); a mass centre's velocity written in many frames (a chain) in the inertial frame, so
        # that the force is resolved once rather than into every one of them
        v = bal.v_centre
        many = len(getattr(v, "args", ())) > 2
        parts = [(bal.force - bal.mass_accel, [(sp.Matrix(in_frame(v, Fr)), Fr)] if many else getattr(v, "args", ()))]
        parts.append((bal.moment - bal.momentum_rate, getattr(bal.omega, "args", ())))
        for force, velocity in parts:
            for m, frame in velocity:
                partial, _ = linear_form(list(m), rates)
                if not any(partial):
                    continue
                f = in_frame(force, frame)
                for k in range(len(rates)):
                    terms[k].append(dot(f, partial.col(k)))
    return [-setup.scalar(sp.Add(*row)).xreplace(sign_map) for row in terms]


def _working_reactions(rows, reactions) -> list:
    """The reactions that remain in the projected rows (they do work: e.g. N under sliding friction).

    The rows are linear in the reactions: their coefficients (one pass, ``linear_form``) are evaluated
    in machine arithmetic at two random states.
    """
    if not reactions or not rows:
        return []
    import numpy as np

    C, _ = linear_form(rows, reactions)
    entries = list(C)
    found = np.zeros(len(reactions))
    atoms = algebra.state_atoms(entries, exclude=reactions)
    for seed in (3, 4):
        vals = algebra.state_point(entries, random.Random(seed), 0.41, atoms=atoms)
        with np.errstate(all="ignore"):
            num = np.abs(np.array(algebra.evaluate(entries, vals), dtype=complex).reshape(C.shape))
        found = np.maximum(found, np.nan_to_num(num, nan=np.inf).max(axis=0))
    scale = max(1.0, float(found[np.isfinite(found)].max())) if np.isfinite(found).any() else 1.0
    return [r for j, r in enumerate(reactions) if found[j] > 1e-9 * scale]


#: Above this many degrees of freedom the mass matrix, forcing and equations of motion are left as
#: derived (no simplification for reading: nobody reads an 8 × 8 mass matrix, and code generation
#: does its own common-subexpression elimination).
READABLE_DOF = 4


def _rows_to_mf(setup, raw_rows, reactions, solved, working):
    """M and f as derived: workless reactions dropped, working ones replaced by their solved values."""
    accels = [q.diff(t, 2) for q in setup.reduction.independent]
    working = set(working)
    subs = {r: (solved[r] if r in working else sp.Integer(0)) for r in reactions}
    rows = [row.xreplace(subs) for row in raw_rows] if subs else list(raw_rows)
    A, b = linear_form(rows, accels)
    return A, -b


def _readable_eom(setup, M, f, small=True):
    """M, f and the equations of motion simplified for reading (up to READABLE_DOF degrees of freedom,
    and while M and f as derived are small enough to read: ``small``)."""
    kin, red = setup.kin, setup.reduction
    accels = [q.diff(t, 2) for q in red.independent]
    small = small and len(accels) <= READABLE_DOF
    M = M.applyfunc(kin.simplify_expr) if small else M
    f = f.applyfunc(kin.simplify_expr) if small else f
    ref = {k: v for k, v in kin.reference_values().items() if isinstance(k, sp.Symbol)}
    # Euler parameters are read on |e| = 1 (M and f, which the generated code evaluates, stay as derived)
    unit = [g.coordinates for g in quaternion_groups(setup.system)]
    eom = []
    for i in range(M.rows):
        e = sum((M[i, j] * accels[j] for j in range(len(accels))), sp.Integer(0)) - f[i]
        e = algebra.on_unit_quaternions(e, unit) if small and unit else e
        e = algebra.strip_factors(e) if small else e
        if len(accels) <= 4 and sp.count_ops(e) < 200:
            e = sp.collect(sp.expand(e), accels, func=lambda c: compact(sp.factor_terms(c)))  # shortest trig form
        e = algebra.leading_sign(e, accels, ref) * e
        eom.append(e)
    return M, f, eom


def _check_consistency(M, f, accels, coords) -> None:
    """The joint solution and the reaction-free rows must give the same accelerations."""
    if not coords:
        return
    a = sp.Matrix([accels[q] for q in coords])
    resid = M * a - f
    for e in resid:
        if not algebra.is_zero(e, tol=1e-8):
            raise RigidkinError("internal check failed: the accelerations from the joint solution do not "
                                "satisfy the reaction-free equations of motion.",
                                hint="This is a bug in rigidkin; please report the model.")


def _regime_conditions(setup, choices, sign_map, react):
    """The conditions that define the regime: the sign of each slip speed (or reaction) chosen."""
    red = setup.reduction
    conds = []
    for sc in choices:
        s = sign_map[sc.symbol]
        q = setup.scalar(sc.quantity) if sc.rate_based else react.get(str(sc.quantity), sc.quantity)
        q = setup.kin.simplify_expr(q)
        rates = [c.diff(t) for c in red.independent]
        if algebra.leading_sign(q, rates) < 0:   # read "ẋ > 0" rather than "−ẋ < 0"
            q, s = -q, -s
        conds.append(Condition(q, ">" if s > 0 else "<", sc.label))
    return conds


def _validity_reads_reactions(setup) -> bool:
    """Whether the validity conditions are written with the reactions (so they solve for them)."""
    if setup.unilateral:
        return True
    for c in setup.system.constraints.values():
        if setup.states.get(c.name) == "stick" and hasattr(getattr(c, "friction", None), "mu"):
            return True
        if callable(getattr(c, "validity", None)) and setup.states.get(c.name) != "open":
            return True
    return False


def _validity(setup, react):
    """While the solution holds: unilateral reactions push, friction within µN, arcs and ropes' grips."""
    valid = []
    for sym, row in setup.unilateral:
        if str(sym) in react:
            label = (f"{row.constraint} is taut (a cable can only pull)" if row.kind == "tension"
                     else f"{row.constraint} pushes (unilateral contact)")
            valid.append(Condition(react[str(sym)], ">=", label, "validity"))
    for c in setup.system.constraints.values():
        fr = getattr(c, "friction", None)
        if setup.states.get(c.name) == "stick" and hasattr(fr, "mu") and str(c.F) in react:
            N, F = react[str(c.N)], react[str(c.F)]
            mu, word = getattr(fr, "static", fr.mu), ("µsN" if getattr(fr, "two", False) else "µN")
            valid.append(Condition(setup.kin.simplify_expr(mu * N - F), ">=",
                                   f"friction at {c.name} within {word} (no slip)", "validity"))
            valid.append(Condition(setup.kin.simplify_expr(mu * N + F), ">=",
                                   f"friction at {c.name} within {word} (no slip)", "validity"))
    # a profile that is an arc: the contact point stays on it
    valid.extend(Condition(m, ">=", label, "validity") for m, label in arc_margins(setup))
    for c in setup.system.constraints.values():          # a constraint's own conditions (a rope's grip)
        extra = getattr(c, "validity", None)
        if callable(extra) and setup.states.get(c.name) != "open":
            valid.extend(Condition(m, ">=", label, "validity") for m, label in extra(setup, react))
    return valid
