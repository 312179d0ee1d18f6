"""Expressions of the motion at random states: the state an expression depends on, and its value there.

Multibody expressions are large trees that share most of their subtrees; every walk here visits a shared
subexpression once.  The state an expression depends on (q(t), q̇, q̈ and the parameters) is found and
stood in for by plain symbols; random states (positive parameters in [0.5, 2], the rest of magnitude
0.3 to 1.5) give numbers; the expression is evaluated there in machine arithmetic.  Whether an
expression is identically zero is decided the way a careful engineer would check: at several random
states (an analytic expression that vanishes at random points is zero with probability one), to 30
digits where machine arithmetic cannot tell.
"""

from __future__ import annotations

import cmath
import random
from collections.abc import Iterable, Mapping

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.physics.vector import dynamicsymbols

t = dynamicsymbols._t

def atoms_of(exprs: Iterable, types: type | tuple) -> set:
    """The subexpressions of ``exprs`` (expressions or matrices) that are instances of ``types`` —
    ``Basic.atoms`` for several expressions at once, each shared subexpression visited once (multibody
    expressions share most of their subtrees, which ``atoms`` walks again at every occurrence)."""
    seen: set = set()
    out: set = set()
    roots = []                  # held here, with every subexpression under them: no id is reused meanwhile
    for e in exprs:
        if isinstance(e, sp.MatrixBase):
            roots.extend(e)
        elif isinstance(e, sp.Basic):
            roots.append(e)
    stack = list(roots)
    while stack:
        e = stack.pop()
        if id(e) in seen:
            continue
        seen.add(id(e))
        if isinstance(e, types):
            out.add(e)
        stack.extend(e.args)
    return out


def xreplace_shared(exprs: Iterable, mapping: Mapping, memo: dict | None = None) -> list:
    """``[e.xreplace(mapping) for e in exprs]`` with each shared subexpression rebuilt once (``xreplace``
    walks a repeated subtree again at every occurrence).  ``memo`` (subexpression → replacement, holding
    ``mapping``) may be kept between calls on expressions that share subtrees."""
    if memo is None:
        memo = dict(mapping)
    elif not memo:
        memo.update(mapping)

    def rep(e):
        hit = memo.get(e)
        if hit is not None:
            return hit
        if not e.args:
            out = e
        else:
            args = [rep(a) for a in e.args]
            out = e.func(*args) if any(a is not b for a, b in zip(args, e.args)) else e
        memo[e] = out
        return out

    return [rep(e) for e in exprs]


def functions_of_time(expr: sp.Basic) -> set[sp.Function]:
    """The undefined functions of time (coordinates, specified motions) an expression contains."""
    return {f for f in atoms_of([expr], AppliedUndef) if f.args == (t,)}


def plain_state(expr: sp.Basic, extra_functions: Iterable[sp.Function] = ()) -> tuple[sp.Basic, dict]:
    """Replace q(t), q̇, q̈ ... by plain symbols; returns (expression, plain symbol → original)."""
    funcs = functions_of_time(expr) | set(extra_functions)
    forward: dict = {}
    back: dict = {}
    derivs = sorted(atoms_of([expr], sp.Derivative), key=lambda d: -sum(c for _, c in d.variable_count))
    for d in derivs:
        if d.expr in funcs:
            order = sum(c for _, c in d.variable_count)
            s = sp.Symbol(f"_{d.expr.func.__name__}_d{order}", real=True)
            forward[d] = s
            back[s] = d
    for f in funcs:
        s = sp.Symbol(f"_{f.func.__name__}_d0", real=True)
        forward[f] = s
        back[s] = f
    if not forward:
        return expr, back
    if isinstance(expr, sp.MatrixBase):
        return expr.__class__(expr.rows, expr.cols, xreplace_shared(list(expr), forward)), back
    return xreplace_shared([expr], forward)[0], back


def random_point(symbols: Iterable[sp.Symbol], rng: random.Random) -> dict:
    """Random values: positive symbols in [0.5, 2], others in [-1.5, 1.5] (avoiding tiny magnitudes)."""
    values = {}
    for s in sorted(symbols, key=str):      # a fixed order: the same values under any hash seed
        if s.is_positive:
            values[s] = sp.Float(rng.uniform(0.5, 2.0))
        else:
            v = rng.uniform(0.3, 1.5)
            values[s] = sp.Float(v if rng.random() < 0.5 else -v)
    return values


def numeric_value(expr: sp.Basic, rng: random.Random) -> complex:
    """Evaluate an expression of the state and parameters at one random point."""
    plain, _ = plain_state(sp.sympify(expr))
    free = plain.free_symbols - {t}
    values = random_point(free, rng)
    values[t] = sp.Float(rng.uniform(0.1, 1.0))
    return complex(plain.xreplace(values).evalf(30))


def state_atoms(exprs, exclude=()) -> list:
    """The plain symbols of ``plain_state`` (each with the q(t), q̇ ... it stands for) and the parameters
    that ``exprs`` depend on: [(symbol for random_point, the object in the expressions)]."""
    funcs: set = set()
    derivs: set = set()
    syms: set = set()
    for a in atoms_of([sp.sympify(e) for e in exprs], (sp.Symbol, sp.Derivative, AppliedUndef)):
        (derivs if isinstance(a, sp.Derivative) else funcs if isinstance(a, AppliedUndef) else syms).add(a)
    out = []
    funcs = {f for f in funcs if f.args == (t,)}
    for d in derivs:
        if d.expr in funcs:
            out.append((sp.Symbol(f"_{d.expr.func.__name__}_d{sum(c for _, c in d.variable_count)}", real=True), d))
    out += [(sp.Symbol(f"_{f.func.__name__}_d0", real=True), f) for f in funcs]
    syms.discard(t)
    syms.difference_update(exclude)
    return out + [(s_, s_) for s_ in syms]


def state_point(exprs, rng: random.Random, t_value: float, exclude=(), atoms=None) -> dict:
    """Random values of everything ``exprs`` depend on, keyed by the objects themselves (q(t), q̇, q̈,
    parameters) — the same values ``random_point`` gives the plain symbols of ``plain_state``, without
    rewriting the expressions; time takes ``t_value``; the symbols in ``exclude`` get no value.
    ``atoms``: ``state_atoms(exprs, exclude)`` when already found."""
    atoms = state_atoms(exprs, exclude) if atoms is None else atoms
    back = dict(atoms)
    values = random_point(back, rng)
    out = {back[k]: float(v) for k, v in values.items()}
    out[t] = t_value
    return out


_UNARY = {sp.sin: cmath.sin, sp.cos: cmath.cos, sp.tan: cmath.tan, sp.exp: cmath.exp, sp.log: cmath.log,
          sp.asin: cmath.asin, sp.acos: cmath.acos, sp.atan: cmath.atan, sp.sinh: cmath.sinh,
          sp.cosh: cmath.cosh, sp.tanh: cmath.tanh, sp.Abs: abs}


def evaluate(exprs, values: Mapping) -> list[complex]:
    """Each expression as a complex number at ``values`` (symbols, q(t), q̇ ... → numbers): machine
    arithmetic over the expression tree, each shared subexpression once (no code generation, no 30-digit
    evalf).  A value that cannot be formed (0⁻¹, an unknown function without arguments) is nan."""
    memo: dict = {k: complex(v) for k, v in values.items()}

    def ev(e):
        hit = memo.get(e)
        if hit is not None:
            return hit
        try:
            if e.is_Number or e.is_NumberSymbol:
                v = complex(e)
            elif e.is_Add:
                v = sum(ev(a) for a in e.args)
            elif e.is_Mul:
                v = 1
                for a in e.args:
                    v *= ev(a)
            elif e.is_Pow:
                b, x = ev(e.base), e.exp
                v = b ** int(x) if x.is_Integer else (cmath.sqrt(b) if x == sp.S.Half else b ** ev(x))
            elif e.func in _UNARY:
                v = _UNARY[e.func](ev(e.args[0]))
            elif getattr(e, "is_Defined", False):
                v = ev(e.definition)             # a derived quantity means its definition
            elif e.is_Function and e.args and all(isinstance(a, sp.Expr) for a in e.args):
                args = [ev(a) for a in e.args]
                v = complex(e.func(*[sp.Float(a.real) if a.imag == 0 else sp.Float(a.real) + sp.I * a.imag
                                     for a in args]).evalf())
            else:
                v = complex(e.evalf())
        except (ZeroDivisionError, OverflowError, TypeError, ValueError, AttributeError):
            v = complex("nan")
        memo[e] = v
        return v

    return [ev(sp.sympify(e)) for e in exprs]


def _machine_verdict(expr: sp.Basic, trials: int, seed: int, tol: float) -> bool | None:
    """``is_zero`` in machine arithmetic at the same random states: True when every value is far below
    ``tol``, False when one is far from zero beyond any rounding of its terms, None when a value is
    in between (then the 30-digit evaluation decides)."""
    rng = random.Random(seed)
    terms = list(sp.Add.make_args(expr))
    atoms = state_atoms([expr])
    zero = True
    for _ in range(trials):
        vals = state_point([expr], rng, 0.0, atoms=atoms)
        vals[t] = rng.uniform(0.1, 1.0)          # the draws numeric_value makes
        v = evaluate(terms, vals)
        total = abs(sum(v))
        if total != total:
            return None
        if total < 1e-3 * tol:
            continue
        zero = False
        if total > 1e-6 and total > 1e-9 * max(abs(x) for x in v):
            return False
    return True if zero else None


def is_zero(expr: sp.Basic, trials: int = 4, seed: int = 1, tol: float = 1e-10) -> bool:
    """True when ``expr`` vanishes identically (random evaluation, scaled tolerance).

    Machine arithmetic decides where it can (a value far from zero, or every value far below the
    tolerance); a value in between is evaluated to 30 digits."""
    expr = sp.sympify(expr)
    if expr == 0:
        return True
    if expr.is_number:
        return abs(complex(expr.evalf())) < tol
    verdict = _machine_verdict(expr, trials, seed, tol)
    if verdict is not None:
        return verdict
    rng = random.Random(seed)
    for _ in range(trials):
        try:
            v = numeric_value(expr, rng)
        except (TypeError, ValueError, ZeroDivisionError):
            return False
        if not (abs(v) < tol):
            return False
    return True
