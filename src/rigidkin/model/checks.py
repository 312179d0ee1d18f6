"""The rules every value given to rigidkin obeys, whether it comes from a problem file or the Python API.

One rule per kind of value:

* a **name** (of a parameter, coordinate, frame, basis vector, point, body, constraint, reaction,
  load, or the problem itself) is an ASCII identifier ``[A-Za-z][A-Za-z0-9_]*`` of at most
  ``MAX_NAME`` characters, not a Python or C keyword, and not a name the engine makes for itself
  (``q_theta`` and ``u_theta`` for the state, ``sigma_A`` for a friction sign, ``X0`` for an unknown
  of generated code ...): :func:`check_identifier`, :func:`generated_clash`;
* a **physical quantity** is real and finite once the parameters' numeric values are put in, and
  positive where physics says so (a mass, a length, a radius, a stiffness) or at least not negative
  (a friction coefficient µ, a natural length): :func:`require`.

A value that depends on the state (a radius written with a coordinate) is checked as far as sympy's
assumptions allow; a value that is a number once the parameters are known is checked as a number.
Numbers are evaluated in floating point with a bounded evaluator (never sympy's arbitrary precision),
so the check itself cannot run away.
"""

from __future__ import annotations

import cmath
import keyword
import math
import re

import sympy as sp

from ..base.errors import ModelError

MAX_NAME = 64
_IDENTIFIER = re.compile(r"[A-Za-z][A-Za-z0-9_]*")

#: C keywords and names of the C library that generated code uses: a name in generated code never
#: collides with them, whatever the code generator does with it.
C_RESERVED = frozenset(("auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else",
    "enum", "extern", "float", "for", "goto", "if", "inline", "int", "long", "register", "restrict", "return",
    "short", "signed", "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void", "volatile",
    "while", "_Bool", "_Complex", "_Imaginary", "bool", "true", "false", "NULL", "main", "system", "exit", "abort",
    "malloc", "free", "memcpy", "printf", "errno", "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt",
    "exp", "log", "fabs", "pow", "sinh", "cosh", "tanh", "copysign", "isfinite", "isnan"))

#: Prefixes of the names the engine makes from other names: q_<coordinate>, u_<coordinate> (the state
#: of a simulation), ua_<reaction> (Kane's auxiliary speeds), sigma_<contact> (the sign of a slip).
GENERATED_PREFIXES = ("q_", "u_", "ua_", "sigma_")
#: Whole names the engine uses: X0, X1 ... (unknowns of generated code), Delta_t (an interval).
_GENERATED = re.compile(r"X\d+|Delta_t")
#: Suffixes the engine adds to a reaction or coordinate name: R_Ox_hat, theta_dot_after, theta_dot_end.
GENERATED_SUFFIXES = ("_hat", "_dot_after", "_dot_end")

POSITIVE, NONNEGATIVE, REAL = "positive", "nonnegative", "real"
_RULE_WORDS = {POSITIVE: "positive", NONNEGATIVE: "zero or positive", REAL: "real and finite"}


def _err(error, message, where, hint):
    return error(message, where=where, hint=hint)


def check_identifier(name, kind: str, where: str | None = None, error: type = ModelError) -> str:
    """A name as the rules above allow it (refused with one paragraph otherwise)."""
    shown = repr(name) if not isinstance(name, str) or len(name) <= 40 else repr(name[:37] + "...")
    hint = ("Use ASCII letters, digits and underscores, starting with a letter "
            f"(at most {MAX_NAME} characters), e.g. theta, m1, R_A.")
    if not isinstance(name, str):
        raise _err(error, f"{shown} is not a valid name for a {kind} (a name is a string).", where, hint)
    if not name.isascii():
        odd = next(ch for ch in name if not ch.isascii())
        raise _err(error, f"the {kind} name {shown} has the non-ASCII character {odd!r} (U+{ord(odd):04X}); "
                          "names are ASCII so that look-alike letters cannot pass for others.", where, hint)
    if len(name) > MAX_NAME:
        raise _err(error, f"the {kind} name {shown} is {len(name)} characters long (at most {MAX_NAME}).", where,
                   hint)
    if name.startswith("_"):
        raise _err(error, f"the {kind} name {shown} starts with '_'.", where, "Names start with a letter.")
    if not _IDENTIFIER.fullmatch(name):
        raise _err(error, f"{shown} is not a valid name for a {kind}.", where, hint)
    if keyword.iskeyword(name) or keyword.issoftkeyword(name) or name in ("True", "False", "None"):
        raise _err(error, f"the {kind} name {shown} is a Python keyword and cannot be used in expressions.", where,
                   "Choose another name.")
    if name in C_RESERVED:
        raise _err(error, f"the {kind} name {shown} is a C keyword or C library name, which generated code "
                          "cannot use.", where, "Choose another name (e.g. add a letter or digit).")
    if name.startswith(GENERATED_PREFIXES) or _GENERATED.fullmatch(name):
        raise _err(error, f"the {kind} name {shown} has the form of a name rigidkin makes itself "
                          f"({', '.join(p + '...' for p in GENERATED_PREFIXES)}, X0, X1 ..., Delta_t).", where,
                   "Choose another name.")
    return name


_PROBLEM_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]*")


def check_problem_name(name, where: str | None = None, error: type = ModelError) -> str:
    """The name of a problem (``name = "heavy-top"``): ASCII letters, digits, '_' and '-', starting with a
    letter, at most ``MAX_NAME`` characters (it names files and appears in generated code's comments)."""
    if not isinstance(name, str) or len(name) > MAX_NAME or not _PROBLEM_NAME.fullmatch(name):
        shown = repr(name) if not isinstance(name, str) or len(name) <= 40 else repr(name[:37] + "...")
        raise _err(error, f"{shown} is not a valid problem name.", where,
                   f"Use ASCII letters, digits, '_' and '-', starting with a letter (at most {MAX_NAME} characters), "
                   "e.g. name = \"heavy-top\".")
    return name


def problem_name(stem: str) -> str:
    """A valid problem name made from a file name (characters other than letters, digits, '_', '-' → '_')."""
    name = re.sub(r"[^A-Za-z0-9_-]", "_", stem.encode("ascii", "replace").decode())[:MAX_NAME]
    return name if name[:1].isalpha() else ("p" + name)[:MAX_NAME]


def generated_clash(name: str, coordinates, reactions) -> str | None:
    """The engine's name that ``name`` would equal, given the coordinate and reaction names (None if none)."""
    for base in (*coordinates, *reactions):
        for suffix in GENERATED_SUFFIXES:
            if name == f"{base}{suffix}":
                return f"the name rigidkin makes from {base} ({base}{suffix})"
    return None


# numbers ------------------------------------------------------------------------------------------------
_FUNCS = {sp.sin: cmath.sin, sp.cos: cmath.cos, sp.tan: cmath.tan, sp.asin: cmath.asin, sp.acos: cmath.acos,
          sp.atan: cmath.atan, sp.exp: cmath.exp, sp.log: cmath.log, sp.sinh: cmath.sinh, sp.cosh: cmath.cosh,
          sp.tanh: cmath.tanh, sp.Abs: abs}


class _Unknown(Exception):
    pass


def _num(e, depth=0) -> complex:
    if depth > 200:
        raise _Unknown
    if e.is_Integer:
        if abs(int(e)) > 10**300:
            raise OverflowError
        return complex(int(e))
    if e.is_Rational:
        return complex(int(e.p) / int(e.q))
    if e.is_Float:
        return complex(float(e))
    if e is sp.pi:
        return complex(math.pi)
    if e is sp.E:
        return complex(math.e)
    if e is sp.S.ImaginaryUnit:
        return 1j
    if e in (sp.oo, -sp.oo, sp.zoo, sp.nan):
        return complex(math.inf)
    args = [_num(a, depth + 1) for a in e.args]
    if e.is_Add:
        return sum(args)
    if e.is_Mul:
        out = complex(1)
        for a in args:
            out *= a
        return out
    if e.is_Pow:
        b, x = args
        if b == 0:
            if x.real < 0:
                return complex(math.inf)
            return complex(0) if x.real > 0 else complex(1)
        return b ** x
    if isinstance(e, sp.atan2):
        y, x = args
        if abs(y.imag) > 1e-12 or abs(x.imag) > 1e-12:
            return complex(math.nan, math.nan)
        return complex(math.atan2(y.real, x.real))
    if isinstance(e, sp.sign):
        (a,) = args
        return complex(0 if a == 0 else a / abs(a))
    for f, g in _FUNCS.items():
        if isinstance(e, f):
            return complex(g(*args))
    raise _Unknown


def numeric_value(expr) -> complex | None:
    """``expr`` as a complex number when it has no symbols (inf when it overflows), else None.

    Evaluated in floating point (bounded time whatever the expression); None when it has a function
    this evaluator does not know.
    """
    try:
        if expr.free_symbols:
            return None
        return _num(expr)
    except _Unknown:
        return None
    except (OverflowError, ZeroDivisionError, ValueError):
        return complex(math.inf)


def require(value, rule: str, what: str, where: str | None = None, values: dict | None = None,
            error: type = ModelError):
    """Refuse ``value`` (a sympy expression or number) unless it obeys ``rule`` ("positive",
    "nonnegative" or "real"), with the parameters' numeric ``values`` put in; returns ``value``."""
    expr = sp.sympify(value)
    if not isinstance(expr, sp.Expr):
        return value
    hint = None
    if values:
        sub = expr.xreplace({k: sp.Float(v) for k, v in values.items() if v is not None})
    else:
        sub = expr
    num = numeric_value(sub)
    shown = str(value) if len(str(value)) <= 60 else str(value)[:57] + "..."
    given = f" (= {num.real:.6g} with the parameters' values)" if num is not None and sub is not expr \
        and expr.free_symbols and math.isfinite(num.real) else ""
    if num is not None:
        if not (math.isfinite(num.real) and math.isfinite(num.imag)):
            raise _err(error, f"the {what} {shown} is not finite{given}.", where,
                       "Give a finite value (check divisions by zero and huge powers).")
        if abs(num.imag) > 1e-12 * max(1.0, abs(num.real)):
            raise _err(error, f"the {what} {shown} is not a real number (it is the complex number "
                              f"{num.real:.6g}{num.imag:+.6g}i: acos of a number beyond ±1, the log or square root of "
                              "a negative number?).", where, "Give a real value.")
        bad = rule == POSITIVE and num.real <= 0 or rule == NONNEGATIVE and num.real < 0
        if bad:
            hint = f"A {what} must be {_RULE_WORDS[rule]}."
            raise _err(error, f"the {what} {shown} is {num.real:.6g}{given}, but it must be {_RULE_WORDS[rule]}.",
                       where, hint)
        return value
    if expr.is_extended_real is False:
        raise _err(error, f"the {what} {shown} is not a real number (it is complex).", where, "Give a real value.")
    if rule == POSITIVE and (expr.is_positive is False):
        raise _err(error, f"the {what} {shown} is never positive (with the parameters as declared), but it must be "
                          "positive.", where, f"A {what} must be positive; check its sign.")
    if rule == NONNEGATIVE and (expr.is_nonnegative is False):
        raise _err(error, f"the {what} {shown} is negative (with the parameters as declared), but it must be zero "
                          "or positive.", where, f"A {what} must be zero or positive; check its sign.")
    return value
