"""The words of the problem files' expression language: its limits, its functions, the names it reserves.

What an expression string may hold (see :mod:`rigidkin.io.expressions`, the parser that reads it): its
size and the size of the numbers in it (the ``MAX_`` limits), the whitelisted functions of one scalar
(``FUNCTIONS``: sin, cos ... sign), the names the language gives a meaning (``RESERVED``: no parameter,
coordinate or frame may take them), ``slip(contact)`` — the slip speed at a contact in an event
condition — and the constructs and operators it refuses, each with the words that name it in a message.
"""

from __future__ import annotations

import ast
from collections.abc import Callable

import sympy as sp

#: Limits on an expression string.
MAX_LENGTH = 1000          # characters
MAX_NESTING = 20           # nested brackets
MAX_DEPTH = 100            # depth of the syntax tree
MAX_NODES = 400            # nodes of the syntax tree
MAX_EXPONENT = 12          # |p| in x**p (x not a number: (x + 1)**p would expand into p + 1 terms)
MAX_NUMBER_EXPONENT = 100  # |p| in a**p with a number a (6.67*10**-11)
MAX_DIGITS = 40            # digits of a number (written or computed)
MAX_MAGNITUDE = 1e40       # |value| of a number written or computed (3**100, exp(10**10) are refused)
MAX_CALLS_NESTED = 4       # functions called inside functions: sin(exp(cos(x)))

#: The whitelisted functions: name → (sympy function, number of arguments).
FUNCTIONS: dict[str, tuple[Callable, int]] = {
    "sin": (sp.sin, 1), "cos": (sp.cos, 1), "tan": (sp.tan, 1),
    "asin": (sp.asin, 1), "acos": (sp.acos, 1), "atan": (sp.atan, 1), "atan2": (sp.atan2, 2),
    "sqrt": (sp.sqrt, 1), "exp": (sp.exp, 1), "log": (sp.log, 1), "abs": (sp.Abs, 1), "sign": (sp.sign, 1),
}

#: Names that the language itself gives a meaning: they cannot be declared as parameters, coordinates,
#: frames or basis vectors.
RESERVED = frozenset(FUNCTIONS) | {"dot", "ddot", "t", "pi", "slip"}

#: ``slip(contact)`` in an event condition: the slip speed at a contact, as an unevaluated function
#: of a symbol named after the contact (``slip(ground)`` → ``slip(Symbol('ground'))``).
slip = sp.Function("slip")

#: The constructs refused, with the words that name them in a message.
CONSTRUCTS = {
    ast.Subscript: "a subscript ([...])", ast.Lambda: "a lambda expression", ast.ListComp: "a list comprehension",
    ast.SetComp: "a set comprehension", ast.DictComp: "a dict comprehension",
    ast.GeneratorExp: "a generator expression", ast.List: "a list ([...])", ast.Tuple: "a tuple (a, b)",
    ast.Set: "a set ({...})", ast.Dict: "a dict ({...})", ast.Compare: "a comparison",
    ast.BoolOp: "'and'/'or'", ast.IfExp: "a conditional expression (if/else)", ast.JoinedStr: "an f-string",
    ast.FormattedValue: "an f-string", ast.NamedExpr: "an assignment expression (:=)", ast.Await: "'await'",
    ast.Yield: "'yield'", ast.YieldFrom: "'yield from'", ast.Starred: "a starred expression (*x)",
    ast.Slice: "a slice (a:b)",
}
#: The operators refused (``+ - * / **`` are the language's), with the words that name them.
OPERATORS = {
    ast.FloorDiv: "//", ast.Mod: "%", ast.MatMult: "@", ast.BitXor: "^ (write ** for a power)",
    ast.BitAnd: "&", ast.BitOr: "|", ast.LShift: "<<", ast.RShift: ">>", ast.Invert: "~", ast.Not: "not",
}
#: The relations of a condition (``lhs > rhs``): the comparison of the syntax tree → sympy's relation.
RELATIONS = {ast.Lt: sp.StrictLessThan, ast.Gt: sp.StrictGreaterThan, ast.LtE: sp.LessThan,
              ast.GtE: sp.GreaterThan}
#: What an expression may hold, in one sentence: the hint of a refusal.
HINT = ("Expressions use numbers, declared names, + - * / ** and parentheses, the functions sin, cos, "
         "sqrt ... (see rigidkin.io.expressions), dot(q), ddot(q) and basis vectors such as F.x or R.y.")
