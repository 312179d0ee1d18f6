"""Expressions as plain data, evaluated with numpy over many runs at once.

A sweep completes every run's initial state through the constraints (dependent coordinates and rates as
expressions of the independent ones and the parameters).  Written as nested lists — ``["+", a, b]``,
``["*", a, b]``, ``["^", a, b]``, ``["sin", a]``, ``["n", 1.5]`` (a number), ``["a", 3]`` (the fourth
argument) — an expression can be kept in a JSON record and evaluated later without sympy and without
running any code: a repeated sweep reads it back (:mod:`rigidkin.numeric.sweeps.sweep_record`).  The first sweep
evaluates the same lists, so both give the same numbers to the last bit.

Why not ``lambdify``: its function is code, which a record must not hold, and it needs sympy to be made.
"""

from __future__ import annotations

import numpy as np

#: The functions a tree may hold: sympy's name → numpy's function.
FUNCTIONS = {"sin": np.sin, "cos": np.cos, "tan": np.tan, "asin": np.arcsin, "acos": np.arccos, "atan": np.arctan,
             "atan2": np.arctan2, "sinh": np.sinh, "cosh": np.cosh, "tanh": np.tanh, "exp": np.exp, "log": np.log,
             "Abs": np.abs, "sign": np.sign}

#: Nodes and depth at most (a larger expression is left to the full route).
MAX_NODES, MAX_DEPTH = 20_000, 200


class NotEncodable(Exception):
    """The expression holds something a tree cannot (an unknown function, a symbol not among the arguments)."""


def encode(expr, index: dict) -> list:
    """The tree of the sympy expression ``expr``; ``index`` maps each argument (symbol) to its position."""
    count = [0]

    def enc(e, depth: int = 0) -> list:
        count[0] += 1
        if count[0] > MAX_NODES or depth > MAX_DEPTH:
            raise NotEncodable("too large")
        if e in index:
            return ["a", index[e]]
        if e.is_Number or e.is_NumberSymbol:
            v = float(e)
            if not np.isfinite(v):
                raise NotEncodable(str(e))
            return ["n", v]
        if e.is_Add:
            return ["+", *[enc(a, depth + 1) for a in e.args]]
        if e.is_Mul:
            return ["*", *[enc(a, depth + 1) for a in e.args]]
        if e.is_Pow:
            return ["^", enc(e.base, depth + 1), enc(e.exp, depth + 1)]
        name = type(e).__name__
        if e.is_Function and name in FUNCTIONS:
            return [name, *[enc(a, depth + 1) for a in e.args]]
        raise NotEncodable(name)

    return enc(expr)


def evaluate(tree: list, columns: list, runs: int) -> np.ndarray:
    """The tree's value at every run: ``columns[i]`` is argument i's values (arrays of length ``runs``)."""

    def ev(node):
        op = node[0]
        if op == "a":
            return columns[node[1]]
        if op == "n":
            return node[1]
        args = [ev(a) for a in node[1:]]
        if op == "+":
            out = args[0]
            for a in args[1:]:
                out = out + a
            return out
        if op == "*":
            out = args[0]
            for a in args[1:]:
                out = out * a
            return out
        if op == "^":
            base, exp = args
            if isinstance(exp, float) and exp == int(exp) and abs(exp) <= 64:
                return np.power(np.asarray(base, dtype=float), exp)
            if isinstance(exp, float) and exp == 0.5:
                return np.sqrt(base)
            return np.power(base, exp)
        return FUNCTIONS[op](*args)

    with np.errstate(all="ignore"):
        value = ev(tree)
    return np.broadcast_to(np.asarray(value, dtype=float), (runs,)).copy()


def valid(tree, n_args: int, depth: int = 0) -> bool:
    """A tree read from a record is well formed: known operators, argument positions in range, numbers."""
    if depth > MAX_DEPTH or not isinstance(tree, list) or not tree or not isinstance(tree[0], str):
        return False
    op, rest = tree[0], tree[1:]
    if op == "a":
        return len(rest) == 1 and isinstance(rest[0], int) and 0 <= rest[0] < n_args
    if op == "n":
        return len(rest) == 1 and isinstance(rest[0], (int, float))
    if op in ("+", "*"):
        return len(rest) >= 1 and all(valid(a, n_args, depth + 1) for a in rest)
    if op == "^":
        return len(rest) == 2 and all(valid(a, n_args, depth + 1) for a in rest)
    return op in FUNCTIONS and len(rest) >= 1 and all(valid(a, n_args, depth + 1) for a in rest)
