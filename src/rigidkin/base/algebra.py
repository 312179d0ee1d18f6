"""Algebra helpers shared by the laws: readable simplification, time derivatives, reading equations.

sympy's ``simplify`` is thorough but can be very slow on the large expressions that multibody
kinematics produce.  rigidkin therefore simplifies in a fixed, bounded pipeline (reduction modulo
sin² + cos² = 1, factor_terms, the shortest trigonometric form) and skips the costly steps above a size
limit.  The zero test by random evaluation and the walks over shared subexpressions live in
:mod:`rigidkin.base.sampling` (public here too: ``algebra.is_zero``, ``algebra.plain_state`` ...).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import sympy as sp
from sympy.core.function import AppliedUndef

from .sampling import (  # noqa: F401  (public here too: algebra.is_zero, algebra.plain_state ...)
    atoms_of,
    evaluate,
    functions_of_time,
    is_zero,
    numeric_value,
    plain_state,
    random_point,
    state_atoms,
    state_point,
    t,
    xreplace_shared,
)
from .timelimit import time_limit  # noqa: F401  (public here too: algebra.time_limit)
from .trigforms import compact

#: Above this operation count the costly simplification steps are skipped.
SIMPLIFY_LIMIT = 400


def time_derivatives(exprs, memo: dict | None = None) -> list:
    """d/dt of each expression (q(t) → q̇, q̇ → q̈, parameters constant), one pass with every shared
    subexpression differentiated once (sympy's ``diff`` differentiates a repeated subtree each time).
    ``memo``: a dict kept between calls on expressions that share subtrees (expression → its rate)."""
    memo = {} if memo is None else memo
    zero = sp.Integer(0)

    def d(e):
        hit = memo.get(e)
        if hit is not None:
            return hit
        if e.is_Number or e.is_NumberSymbol or (e.is_Symbol and e != t):
            out = zero
        elif e == t:
            out = sp.Integer(1)
        elif e.is_Add:
            out = sp.Add(*[d(a) for a in e.args])
        elif e.is_Mul:
            args = e.args
            parts = []
            for i, a in enumerate(args):
                da = d(a)
                if da != 0:
                    parts.append(sp.Mul(*args[:i], da, *args[i + 1:]))
            out = sp.Add(*parts)
        elif e.is_Pow and not e.exp.has(t):
            db = d(e.base)
            out = e.exp * e.base ** (e.exp - 1) * db if db != 0 else zero
        elif isinstance(e, sp.sin):
            out = sp.cos(e.args[0]) * d(e.args[0])
        elif isinstance(e, sp.cos):
            out = -sp.sin(e.args[0]) * d(e.args[0])
        elif isinstance(e, (AppliedUndef, sp.Derivative)) and e.has(t):
            out = e.diff(t)
        elif not e.has(t):
            out = zero
        else:
            out = e.diff(t)
        memo[e] = out
        return out

    return [d(sp.sympify(e)) for e in exprs]


def readable(expr: sp.Basic) -> sp.Basic:
    """Simplify for a person to read: reduction modulo sin² + cos² = 1, factor_terms and the shortest
    trigonometric form (M + m sin²α), bounded by size.

    The work is done on plain symbols standing for q(t), q̇, q̈ (sympy is several times faster on
    symbols than on functions of time and their derivatives), then the state is put back.
    """
    expr = sp.sympify(expr)
    if expr.is_number or expr.is_Symbol:
        return sp.nsimplify(expr) if expr.is_Float else expr
    plain, back = plain_state(expr)
    key = plain
    hit = _READABLE_CACHE.get(key)
    if hit is None:
        hit = compact(_readable_plain(plain))
        if len(_READABLE_CACHE) > 20000:
            _READABLE_CACHE.clear()
        _READABLE_CACHE[key] = hit
    return hit.xreplace(back) if back else hit


_READABLE_CACHE: dict = {}


def _ops(e) -> int:
    return sp.count_ops(e)


def trig_reduce(expr: sp.Basic) -> sp.Basic:
    """Simplify a rational expression in sines and cosines by reduction modulo sin² + cos² = 1.

    Each angle a gets symbols S = sin a, C = cos a; the expression is cancelled as a rational
    function and its numerator and denominator reduced by S² + C² − 1 (trying both term orders and
    keeping the shorter).  This is polynomial algebra, far cheaper than ``trigsimp`` on the
    expressions multibody kinematics produce, and it decides the identities that matter here.
    """
    # radicals of parameters (sqrt(R² − l²/4) and sqrt(4R² − l²)) in one canonical form, then symbols
    expr = expr.replace(lambda x: x.is_Pow and x.exp.is_Rational and not x.exp.is_Integer and x.base.is_Add,
                        lambda x: sp.Pow(sp.factor(x.base), x.exp))
    radicals = sorted({x for x in atoms_of([expr], sp.Pow) if x.exp.is_Rational and not x.exp.is_Integer
                       and not x.base.is_Symbol}, key=sp.default_sort_key)
    rad = {x: sp.Dummy(f"rad{i}", positive=True) for i, x in enumerate(radicals)}
    if rad:
        out = trig_reduce(expr.xreplace(rad))
        return out.xreplace({v: k for k, v in rad.items()})
    trig = list(atoms_of([expr], (sp.sin, sp.cos, sp.tan)))
    if not trig:
        return sp.cancel(expr) if expr.is_rational_function() else expr
    e = expr.rewrite(sp.tan, sp.sin) if expr.has(sp.tan) else expr
    e = e.xreplace({f: sp.expand_trig(f) for f in atoms_of([e], (sp.sin, sp.cos))
                    if f.args[0].is_Add or f.args[0].is_Mul and f.args[0].args[0].is_Integer})
    args = sorted({f.args[0] for f in atoms_of([e], (sp.sin, sp.cos))}, key=sp.default_sort_key)
    S = [sp.Dummy(f"s{i}") for i in range(len(args))]
    C = [sp.Dummy(f"c{i}") for i in range(len(args))]
    fwd = {}
    for a, si, ci in zip(args, S, C):
        fwd[sp.sin(a)] = si
        fwd[sp.cos(a)] = ci
    p = e.xreplace(fwd)
    if atoms_of([p], sp.Function):
        return expr
    try:
        num, den = sp.fraction(sp.cancel(p))
        rels = [si**2 + ci**2 - 1 for si, ci in zip(S, C)]
        best = None
        for order in (S + C, C + S):
            gens = order + sorted(p.free_symbols - set(S) - set(C), key=sp.default_sort_key)
            n_r = sp.reduced(num, rels, *gens)[1] if num.free_symbols & set(S + C) else num
            d_r = sp.reduced(den, rels, *gens)[1] if den.free_symbols & set(S + C) else den
            cand = sp.cancel(n_r / d_r)
            if best is None or _ops(cand) < _ops(best):
                best = cand
    except (sp.PolynomialError, NotImplementedError, sp.polys.polyerrors.PolificationFailed):
        return expr
    back = {v: k for k, v in fwd.items()}
    return best.xreplace(back)


def _tidy(e: sp.Basic) -> sp.Basic:
    """Collect sums by the rates (R θ̇² − r θ̇² → (R − r) θ̇²) wherever that shortens them."""
    rates = sorted((s for s in e.free_symbols if s.name.endswith("_d1") and s.name.startswith("_")), key=str)

    def collect(x):
        c = sp.collect(x, rates, func=sp.factor_terms)
        return c if _ops(c) < _ops(x) else x

    out = e.replace(lambda x: x.is_Add and x.has(*rates), collect) if rates else e
    out = out if _ops(out) <= _ops(e) else e
    num, den = sp.fraction(out)
    if den != 1 and den.could_extract_minus_sign():
        out = sp.factor_terms(-num) / sp.factor_terms(-den)
    return out


#: Reduction modulo sin² + cos² = 1 is skipped when an expression has more angles than this (its cost
#: grows quickly with the number of angles, and a chain's long expressions are not read by people).
TRIG_ARGS_LIMIT = 3


#: A large expression (over SIMPLIFY_LIMIT operations) over more distinct denominators than this is not
#: reduced: bringing it over one denominator (``cancel``) costs minutes (Lagrange's accelerations of a
#: cylinder rolling in a rolling shell: 989 operations over 7 denominators) for a form nobody reads.
DENOMINATORS_LIMIT = 3


def _denominators(expr: sp.Basic) -> int:
    """The number of distinct non-constant denominators (negative powers) in ``expr``."""
    return len({a.base for a in atoms_of([expr], sp.Pow) if a.exp.is_negative and not a.base.is_number})


def _readable_plain(expr: sp.Basic) -> sp.Basic:
    n_args = len({f.args[0] for f in atoms_of([expr], (sp.sin, sp.cos))})
    if n_args > TRIG_ARGS_LIMIT:
        return expr
    ops = _ops(expr)
    limit = {0: 4 * SIMPLIFY_LIMIT, 1: 4 * SIMPLIFY_LIMIT, 2: SIMPLIFY_LIMIT}.get(n_args, 150)
    if ops > limit or (ops > SIMPLIFY_LIMIT and _denominators(expr) > DENOMINATORS_LIMIT):
        return expr
    try:
        e = trig_reduce(expr)
        if _ops(e) > _ops(expr):
            e = expr
        e = sp.factor_terms(e)
        if _ops(e) <= 40:
            e4 = sp.factor(e)
            if _ops(e4) < _ops(e):
                e = e4
        return _tidy(e)
    except (sp.PolynomialError, NotImplementedError, RecursionError):
        return expr


def on_unit_quaternions(expr: sp.Basic, groups) -> sp.Basic:
    """``expr`` on |e| = 1 for each group of Euler parameters (e₀, e₁, e₂, e₃ as functions of time): its
    numerator and denominator reduced modulo e₀² + e₁² + e₂² + e₃² − 1 (e₀² eliminated, the textbook form
    1 − 2(e₂² + e₃²)), kept where that is not longer.  For reading only: the engine's equations hold for
    any e ≠ 0 (its rotation is that of e/|e|), a person's on |e| = 1."""
    if not groups:
        return expr
    plain, back = plain_state(sp.sympify(expr))
    fwd = {v: k for k, v in back.items()}
    rels = [sum(fwd[e] ** 2 for e in g) - 1 for g in groups if all(e in fwd for e in g)]
    if not rels:
        return expr
    lead = [fwd[e] for g in groups if all(e in fwd for e in g) for e in g]
    try:
        num, den = sp.fraction(sp.together(plain))
        gens = lead + sorted((num * den).free_symbols - set(lead), key=sp.default_sort_key)
        out = sp.reduced(sp.expand(num), rels, *gens)[1] / sp.reduced(sp.expand(den), rels, *gens)[1]
    except (sp.PolynomialError, sp.polys.polyerrors.PolificationFailed, NotImplementedError, ZeroDivisionError):
        return expr
    out = out.xreplace(back)
    return out if _ops(out) <= _ops(expr) else expr


def strip_factors(expr: sp.Basic, keep: Iterable[sp.Basic] = ()) -> sp.Basic:
    """Drop the constant factors (numbers, parameter combinations) of an expression ``= 0``.

    ``3*m*l*(2*θ̈ − g sinθ)/2 = 0`` becomes ``2*θ̈ − g sinθ = 0``.  Factors that contain a
    coordinate or its rates are kept (they could vanish).  A parameter combination such as
    (R − r) is taken to be nonzero, as it is in any problem that does not degenerate.
    """
    expr = sp.factor_terms(sp.together(expr))
    if not expr.is_Mul:
        expr = sp.factor(expr) if sp.count_ops(expr) < 80 else expr
    num, _den = sp.fraction(expr)
    expr = num
    if not expr.is_Mul:
        return expr
    kept = []
    for f in expr.args:
        if f.is_number or not functions_of_time(f) and not f.has(t):
            continue   # a nonzero constant or parameter combination
        kept.append(f)
    return sp.Mul(*kept) if kept else sp.Integer(1)


def leading_sign(expr: sp.Basic, unknowns: Iterable[sp.Basic], values: Mapping | None = None) -> int:
    """Sign to multiply an equation ``= 0`` by so that its first unknown has a positive coefficient.

    The coefficient's sign is read at ``values`` (parameter values) when it is not a plain number,
    so that 3(r − R) θ̈ with R > r reads as 3(R − r) θ̈.
    """
    for u in unknowns:
        c = sp.diff(expr, u) if expr.has(u) else sp.Integer(0)
        if c == 0:
            continue
        if values:
            try:
                v = complex(sp.sympify(c).xreplace({k: sp.Float(x) for k, x in values.items()}).evalf())
                if not c.free_symbols - set(values) and abs(v.imag) < 1e-12 and v.real != 0:
                    return -1 if v.real < 0 else 1
            except (TypeError, ValueError):
                pass
        c_num = sp.Mul(*[a for a in sp.Mul.make_args(c) if a.is_number]) if c.is_Mul else c
        if c_num.is_number:
            return -1 if c_num < 0 else 1
        return 1
    return 1


def substitute(expr, mapping: Mapping):
    """``xreplace`` that also reaches into sympy vectors and matrices."""
    from sympy.physics.vector import Vector

    if not mapping:
        return expr
    if isinstance(expr, Vector):
        memo = dict(mapping)
        return Vector([(sp.Matrix(xreplace_shared(list(m), mapping, memo)), frame) for m, frame in expr.args]) \
            if expr.args else expr
    if isinstance(expr, (int, float)):
        expr = sp.sympify(expr)
    if isinstance(expr, sp.Expr):
        return xreplace_shared([expr], mapping)[0]
    return expr.xreplace(mapping)           # matrices, dyadics


def is_transcendental_in(expr: sp.Basic, x: sp.Symbol) -> bool:
    """True when ``x`` appears both bare and inside a function (θ = k sin θ): no closed-form root."""
    inside = any(f.has(x) for f in expr.atoms(sp.Function))
    bare = expr.xreplace({f: sp.Dummy() for f in expr.atoms(sp.Function) if f.has(x)}).has(x)
    return inside and bare
