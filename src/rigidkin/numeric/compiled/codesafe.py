"""What generated code may contain: rigidkin's own names and sympy's own mathematics, nothing else.

Generated code (the C of :mod:`rigidkin.numeric.compiled.codegen`, the Python that ``lambdify`` writes and
``exec``-utes) is made from expressions only — never from a title, a name, a description or a sense.
Before any code is printed:

* every symbol is renamed to one of our own names (``_a0, _a1, …``; the mapping stays in Python), so a
  user's name never reaches the source, whatever the Python API was given;
* every node of every expression must be one of sympy's own classes, and no undefined function
  (``Function("…")(x)``, whose name a printer would copy), derivative, integral, lambda, matrix symbol or
  string node may remain (:func:`check_expressions`);
* the C statements printed from them are audited: printable ASCII, no comment, no string or
  preprocessor character, and every identifier one we chose or a function of ``<math.h>``
  (:func:`audit_c`).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence

import sympy as sp
from sympy.core.function import AppliedUndef

from ...base.errors import RigidkinError
from ...model.definitions import expand
from ...model.inputs import InputSymbol  # an input u(t): a Symbol (renamed like every symbol)


class UnsafeCodeError(RigidkinError):
    """An expression or a piece of generated code holds something that must not reach generated code."""


_FORBIDDEN = (AppliedUndef, sp.Derivative, sp.Integral, sp.Subs, sp.Lambda, sp.MatrixSymbol, sp.Indexed,
              sp.IndexedBase, sp.core.symbol.Str)


def _describe(node) -> str:
    if isinstance(node, AppliedUndef):
        return "an undefined function"
    return f"a {type(node).__name__}"


def check_expressions(exprs: Iterable, symbols: Iterable[sp.Symbol] | None = None, where: str = "") -> list:
    """The expressions as sympy objects, after checking that they are plain mathematics.

    Every node must be a class of sympy itself (no subclass defined elsewhere, whose printing sympy does
    not control), and none of the kinds whose printed form carries a name (undefined functions, matrix
    symbols, strings, derivatives, integrals, lambdas).  With ``symbols``, every symbol must be one of them.
    """
    allowed = set(symbols) if symbols is not None else None
    # derived quantities (a = √(R² − l²)) by their definitions
    out = [expand(sp.sympify(e)) for e in exprs]
    seen: set = set()
    stack = list(out)
    while stack:                                        # every distinct node once (shared subtrees too)
        node = stack.pop()
        if not isinstance(node, sp.Basic) or node in seen:
            continue
        seen.add(node)
        stack.extend(node.args)
        mod = type(node).__module__ or ""
        if isinstance(node, _FORBIDDEN) or not (mod.startswith("sympy.") or type(node) is InputSymbol):
            raise UnsafeCodeError(f"an expression contains {_describe(node)}, which is not plain mathematics, "
                                  "so no code is generated for it.", where=where or "code generation",
                                  hint="Every quantity must be a parameter, a coordinate, a rate or time, "
                                       "combined with sympy's own functions.")
        if allowed is not None and isinstance(node, sp.Symbol) and node not in allowed:
            raise UnsafeCodeError("an expression contains a quantity that is neither a coordinate, a rate, "
                                  "time nor a parameter, so no code is generated for it.",
                                  where=where or "code generation")
    return out


def mangled(args: Sequence[sp.Symbol], prefix: str = "_a") -> list[sp.Symbol]:
    """Our own names for ``args`` (``_a0, _a1, …``), with the same assumptions (so nothing re-simplifies)."""
    return [sp.Symbol(f"{prefix}{i}", **a.assumptions0) for i, a in enumerate(args)]


def safe_lambdify(args: Sequence[sp.Symbol], exprs, modules="numpy", cse: bool = True, where: str = "") -> Callable:
    """``sympy.lambdify(args, exprs)`` with the arguments renamed to our own names first and the expressions
    checked (:func:`check_expressions`): the Python source lambdify writes holds no user text.

    ``exprs`` is a list of expressions (or of lists of them, one level), or one matrix; the function returns
    the same shape.
    """
    args = list(args)
    new = mangled(args)
    sub = dict(zip(args, new))
    if isinstance(exprs, sp.MatrixBase):
        flat = [e.xreplace(sub) for e in check_expressions(list(exprs), args, where)]
        return sp.lambdify(new, sp.Matrix(exprs.rows, exprs.cols, flat), modules=modules, cse=cse)
    nested = [isinstance(e, (list, tuple)) for e in exprs]
    flat = [x for e, n in zip(exprs, nested) for x in (e if n else [e])]
    flat = [e.xreplace(sub) for e in check_expressions(flat, args, where)]
    it = iter(flat)
    shaped = [[next(it) for _ in e] if n else next(it) for e, n in zip(exprs, nested)]
    return sp.lambdify(new, shaped, modules=modules, cse=cse)


# C ------------------------------------------------------------------------------------------------------------
def _math_names() -> frozenset:
    from sympy.printing.c import C99CodePrinter

    p = C99CodePrinter()
    names = {"fabs", "pow", "fmod", "sqrt", "INFINITY", "NAN", "HUGE_VAL"}
    for v in p.known_functions.values():
        if isinstance(v, str):
            names.add(v)
        else:
            names.update(item[1] for item in v if len(item) > 1 and isinstance(item[1], str))
    names.update(v for v in getattr(p, "math_macros", {}).values() if isinstance(v, str))
    return frozenset(n for n in names if re.fullmatch(r"[A-Za-z_]\w*", n))


_C_OK_CHARS = re.compile(r"[A-Za-z0-9_ \n\[\]().+\-*/=,;<>!&|?:]*")
_C_IDENT = re.compile(r"(?<![\w.])[A-Za-z_]\w*")
_C_OWN = re.compile(r"(?:[wv]\d+|T|y|p|X|M|dy|o|const|double|return|if|rk_lu_solve|RK_\w+)")


def audit_c(lines: Sequence[str], extra: Iterable[str] = ()) -> None:
    """Refuse C statements that hold anything but our names, numbers, operators and ``<math.h>`` functions."""
    allowed = _MATH | set(extra)
    for line in lines:
        bad = "" if _C_OK_CHARS.fullmatch(line) and "/*" not in line and "//" not in line else line
        if not bad:
            bad = next((w for w in _C_IDENT.findall(line) if w not in allowed and not _C_OWN.fullmatch(w)), "")
        if bad:
            raise UnsafeCodeError("the generated C holds a name rigidkin did not choose; it is not compiled.",
                                  where="code generation",
                                  hint="This is a bug in rigidkin's code generator; the numpy backend still works "
                                       "(backend='numpy').")


_MATH = _math_names()
