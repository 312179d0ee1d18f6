"""Dimensional analysis of equations: every term of a sum must have the same dimension.

A term's dimension follows from the parameters' units (``System.parameter_info[name].dimension``),
the coordinates' kinds (an angle is dimensionless, a length is L; each time derivative divides by T),
time t (T), the unknown reactions (a force M·L·T⁻², a couple M·L²·T⁻², a reaction impulse times T)
and the signs of friction (dimensionless).  Numbers are dimensionless; the argument of sin, cos, exp,
log ... must be dimensionless; a power of a dimensioned base needs a numeric exponent.  Every sum,
at any depth, is checked.

``check_equation`` reports, for an equation ``lhs = rhs``, the dimension of each term and the terms
that disagree with the others (the majority; on a tie, the terms with the highest time derivative set
the reference), naming both dimensions.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from .errors import RigidkinError
from .printing import text
from .units import LENGTH, MASS, ONE, TIME, Dimension

t = dynamicsymbols._t

FORCE = MASS * LENGTH / TIME**2
TORQUE = FORCE * LENGTH


class DimensionMismatch(RigidkinError):
    """Two terms of a sum (or a function's argument) have dimensions that cannot be added."""

    def __init__(self, message, *, term=None, dimension=None, other=None, other_dimension=None, where=None):
        self.term, self.dimension, self.other, self.other_dimension = term, dimension, other, other_dimension
        super().__init__(message, where=where)


class UnknownDimension(DimensionMismatch):
    """A symbol whose dimension is not known (not a parameter, coordinate or reaction, or a parameter
    declared without a unit): nothing can be said about the terms it enters."""


def symbol_dimensions(system, setup=None) -> dict:
    """Symbol (or coordinate function) → Dimension for the parameters, coordinates, reactions and signs."""
    dims: dict = {t: TIME}
    for p in system.parameter_info.values():
        dims[p.symbol] = p.dimension
    for c in system.coordinate_info.values():
        dims[c.symbol] = c.dimension
    for g in getattr(system, "speed_groups", {}).values():     # angular-velocity components as speeds
        for w in g.speeds:
            dims[w] = ONE / TIME
    if setup is not None:
        for row in setup.rows:
            d = TORQUE if row.kind == "torque" else FORCE
            dims[row.reaction] = d
            dims[sp.Symbol(f"{row.reaction.name}_hat", real=True)] = d * TIME
        for sc in setup.sign_choices:
            dims[sc.symbol] = ONE
    for name, c in system.constraints.items():
        for r in c.reactions():
            dims.setdefault(r, TORQUE if r.name.startswith("M_") else FORCE)
        dims.setdefault(sp.Symbol(f"sigma_{name}"), ONE)
        dims.setdefault(sp.Symbol(f"sigma_{name}_N"), ONE)
    for ld in system.loads.values():
        for attr in ("sign_symbol", "normal_sign_symbol"):
            s = getattr(ld, attr, None)
            if isinstance(s, sp.Symbol):
                dims[s] = ONE
    return dims


def _lookup(dims: dict, s) -> Dimension | None:
    if s in dims:
        return dims[s]
    for k, v in dims.items():   # symbols with other assumptions but the same name (parsed input)
        if isinstance(k, sp.Symbol) and isinstance(s, sp.Symbol) and k.name == s.name:
            return v
    return None


def dimension_of(expr, dims: dict) -> Dimension:
    """The dimension of ``expr``; raises DimensionMismatch naming the terms that cannot be added."""
    e = sp.sympify(expr)
    if e.is_Number or e in (sp.pi, sp.E, sp.I) or e.is_NumberSymbol:
        return ONE
    if getattr(e, "is_Defined", False):            # a derived quantity: the dimension of its definition
        return dimension_of(e.definition, dims)
    if isinstance(e, sp.Derivative):
        base = dimension_of(e.expr, dims)
        for v, n in e.variable_count:
            base = base / dimension_of(v, dims) ** int(n)
        return base
    if isinstance(e, sp.Symbol):
        d = _lookup(dims, e)
        if d is None:
            raise UnknownDimension(f"the dimension of '{text(e)}' is not known (it is not a parameter, coordinate "
                                    "or reaction).", term=e)
        return d
    if isinstance(e, sp.Function) and isinstance(e.func, sp.core.function.UndefinedFunction):
        d = _lookup(dims, e)
        if d is None:
            raise UnknownDimension(f"the dimension of '{text(e)}' is not known.", term=e)
        return d
    if e.is_Add:
        terms = [(a, dimension_of(a, dims)) for a in e.args]
        ref_term, ref = _reference(terms)
        for a, d in terms:
            if d != ref:
                raise DimensionMismatch(f"the term {text(a)} has dimension {d} but {text(ref_term)} has {ref}, "
                                        f"in {text(e)}.", term=a, dimension=d, other=ref_term, other_dimension=ref)
        return ref
    if e.is_Mul:
        out = ONE
        for a in e.args:
            out = out * dimension_of(a, dims)
        return out
    if e.is_Pow:
        b, x = e.args
        db = dimension_of(b, dims)
        if db.is_dimensionless:
            dx = dimension_of(x, dims)
            if not dx.is_dimensionless:
                raise DimensionMismatch(f"the exponent {text(x)} has dimension {dx}.", term=x, dimension=dx,
                                        other=e, other_dimension=ONE)
            return ONE
        if not x.is_Number:
            raise DimensionMismatch(f"{text(b)} (dimension {db}) is raised to the non-numeric power {text(x)}.",
                                    term=e, dimension=db, other=x, other_dimension=ONE)
        return db ** float(x) if not x.is_Integer else db ** int(x)
    if isinstance(e, (sp.Abs, sp.re, sp.im)):
        return dimension_of(e.args[0], dims)
    if isinstance(e, (sp.Max, sp.Min)):
        return dimension_of(sp.Add(*e.args) if len(e.args) > 1 else e.args[0], dims)
    if isinstance(e, sp.sign):
        dimension_of(e.args[0], dims)
        return ONE
    if isinstance(e, sp.Function):
        if isinstance(e, sp.atan2):
            dimension_of(e.args[0] + e.args[1], dims)
            return ONE
        for a in e.args:
            d = dimension_of(a, dims)
            if not d.is_dimensionless:
                raise DimensionMismatch(f"the argument {text(a)} of {e.func.__name__} has dimension {d}; it must be "
                                        "dimensionless.", term=a, dimension=d, other=e, other_dimension=ONE)
        return ONE
    raise DimensionMismatch(f"cannot tell the dimension of {text(e)}.", term=e)


def _order(term) -> int:
    ds = [sum(n for _, n in d.variable_count) for d in sp.sympify(term).atoms(sp.Derivative)]
    return max(ds) if ds else 0


def _reference(terms):
    """The dimension most terms share (on a tie, that of the terms with the highest time derivative)."""
    counts = Counter(d for _, d in terms)
    best = max(counts.values())
    tied = [d for d, c in counts.items() if c == best]
    if len(tied) > 1:
        tied.sort(key=lambda d: -max(_order(a) for a, dd in terms if dd == d))
    ref = tied[0]
    return next(a for a, d in terms if d == ref), ref


@dataclass(frozen=True)
class DimensionReport:
    """The dimensional check of one equation: its terms with their dimensions and the ones that disagree."""

    label: str
    lhs: sp.Expr
    rhs: sp.Expr
    terms: tuple            # (term, Dimension | None)
    dimension: Dimension | None
    offending: tuple        # (term, Dimension | None, reason)

    @property
    def consistent(self) -> bool:
        return not self.offending

    def __str__(self) -> str:
        if self.consistent:
            return f"{self.label}: every term has dimension {self.dimension}."
        parts = [f"the term {text(term)} has dimension {d if d is not None else '?'} ({why})"
                 for term, d, why in self.offending]
        return f"{self.label}: dimensionally inconsistent — " + "; ".join(parts) + "."


def terms_of(lhs, rhs) -> list:
    """The terms of ``lhs = rhs`` as written (the right side's with their sign changed)."""
    out = list(sp.Add.make_args(sp.sympify(lhs))) if sp.sympify(lhs) != 0 else []
    out += [-a for a in sp.Add.make_args(sp.sympify(rhs))] if sp.sympify(rhs) != 0 else []
    return out


def check_equation(lhs, rhs, dims: dict, label: str = "equation") -> DimensionReport:
    """Check ``lhs = rhs`` term by term; ``dims`` from :func:`symbol_dimensions`."""
    terms = terms_of(lhs, rhs)
    known, offending = [], []
    for a in terms:
        try:
            known.append((a, dimension_of(a, dims)))
        except DimensionMismatch as exc:
            offending.append((a, None, exc.message))
    ref = None
    if known:
        _, ref = _reference(known)
        for a, d in known:
            if d != ref:
                offending.append((a, d, f"the other terms have {ref}"))
    return DimensionReport(label, sp.sympify(lhs), sp.sympify(rhs), tuple(known), ref, tuple(offending))


def check_solution(solution) -> list[DimensionReport]:
    """Every balance equation, equation of motion, acceleration and reaction of a solution, checked."""
    system, setup = solution.system, solution.setup
    dims = symbol_dimensions(system, setup)
    out = []
    for eq in solution.equations:
        out.append(check_equation(eq.lhs, eq.rhs, dims, eq.label))
    for i, r in enumerate(solution.regimes):
        tag = f" (regime {i + 1})" if len(solution.regimes) > 1 else ""
        for k, e in enumerate(r.eom):
            out.append(check_equation(e, 0, dims, f"equation of motion {k + 1}{tag}"))
        if not _ready(r.accelerations) or not _ready(r.reactions):
            out.append(_mass_form(r, solution.coordinates, dims, tag))
        for q, a in (r.accelerations.items() if _ready(r.accelerations) else ()):
            out.append(check_equation(q.diff(t, 2), a, dims, f"acceleration {text(q.diff(t, 2))}{tag}"))
        for name, v in (r.reactions.items() if _ready(r.reactions) else ()):
            sym = sp.Symbol(name, real=True)
            if v != 0 and _lookup(dims, sym) is not None:
                out.append(check_equation(sym, v, dims, f"reaction {name}{tag}"))
    return out


def _ready(mapping) -> bool:
    """False for a lazy mapping not computed yet (large systems: not worth solving just to check units)."""
    return getattr(mapping, "computed", True)


def _mass_form(regime, coords, dims, tag) -> DimensionReport:
    """Each row of M q̈ = f: its inertia and forcing terms share one dimension."""
    M, f = regime.mass_matrix, regime.forcing
    bad, last = [], None
    for i in range(M.rows):
        lhs = sum((M[i, j] * q.diff(t, 2) for j, q in enumerate(coords)), sp.Integer(0))
        rep = check_equation(lhs, f[i], dims, f"row {i + 1} of M q̈ = f{tag}")
        last = rep
        if not rep.consistent:
            bad.append(rep)
    if bad:
        return bad[0]
    return last if last is not None else DimensionReport(f"M q̈ = f{tag}", sp.Integer(0), sp.Integer(0), (), None, ())
