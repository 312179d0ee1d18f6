"""The safe expression language of problem files: a restricted parser that builds sympy objects.

A string such as ``"l/2*sin(theta)"``, ``"-K*(x - L0)"`` or ``"l/2*R.y"`` is parsed with Python's
``ast`` module and the tree is walked against a whitelist; sympy objects are built node by node.
Nothing is evaluated by Python (no ``eval``, ``exec``, ``sympify`` or ``parse_expr``).

The language:

* numbers (finite, real), declared names (parameters, coordinates, ``t``, ``pi``), ``+ - * / **``,
  unary minus, parentheses;
* ``**`` with a numeric exponent of at most ``MAX_EXPONENT`` in magnitude (``MAX_NUMBER_EXPONENT`` for a
  number raised to a power), no powers inside an exponent (``9**9**9**9`` is refused), no number with
  more than ``MAX_DIGITS`` digits or of magnitude above ``MAX_MAGNITUDE`` (written or computed:
  ``3**100``, ``exp(10**10)``), and functions nested at most ``MAX_CALLS_NESTED`` deep;
* the functions ``sin cos tan asin acos atan atan2 sqrt exp log abs sign``;
* ``dot(q)`` and ``ddot(q)``: the first and second time derivatives of a coordinate q (``ddot`` only
  where the scope allows accelerations: in questions and expected equations, not in loads or geometry);
* basis vectors where a vector is expected: ``FRAME.x`` / ``FRAME.y`` / ``FRAME.z``, ``FRAME.<basis
  name>`` (``F.Ex``, ``A.er``), or a basis name alone when only one frame has it (``Ex``, ``er``);
* equations ``"lhs = rhs"`` (an ``sp.Eq``) and conditions ``"lhs > rhs"`` (``<``, ``<=``, ``>=``).

Everything else — attribute access other than ``FRAME.axis``, subscripts, lambdas, comprehensions,
strings, comparisons in an expression, calls of other names, dunder names, undeclared names — is
refused with an :class:`~rigidkin.base.errors.InputError` that says which construct and at which column.
The size of the input is bounded (length, nesting depth, number of nodes), so parsing never hangs.
The language's words — limits, functions, reserved names, refused constructs — are in
:mod:`rigidkin.io.language` (public here too).
"""

from __future__ import annotations

import ast
import math

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base.errors import InputError
from ..model.checks import check_identifier, numeric_value
from ..model.values import exact_decimal
from .language import (  # noqa: F401  (public here too: the language's limits, functions and reserved names)
    CONSTRUCTS,
    FUNCTIONS,
    HINT,
    MAX_CALLS_NESTED,
    MAX_DEPTH,
    MAX_DIGITS,
    MAX_EXPONENT,
    MAX_LENGTH,
    MAX_MAGNITUDE,
    MAX_NESTING,
    MAX_NODES,
    MAX_NUMBER_EXPONENT,
    OPERATORS,
    RELATIONS,
    RESERVED,
    slip,
)
from .scope import Scope, default_scope  # noqa: F401  (public here too: the language's scope)

t = dynamicsymbols._t


# --------------------------------------------------------------------------------------------------
def _snippet(text: str) -> str:
    s = text if len(text) <= 60 else text[:57] + "..."
    return repr(s)


class _Parser:
    def __init__(self, text: str, scope: Scope, where: str | None, offset: int = 0):
        self.text, self.scope, self.where, self.offset = text, scope, where, offset
        self.calls = 0              # functions being called around the node being built
        self.source = ""            # the text the tree was parsed from (for decimals as written)

    def fail(self, message: str, node: ast.AST | None = None, hint: str | None = HINT) -> InputError:
        col = getattr(node, "col_offset", None)
        at = f" at column {col + 1 + self.offset}" if col is not None else ""
        return InputError(f"in the expression {_snippet(self.text)}{at}: {message}.", where=self.where, hint=hint)

    # entry --------------------------------------------------------------------------------------
    def tree(self, source: str, condition: bool = False) -> ast.expr:
        depth = deepest = 0
        for ch in source:
            if ch in "([{":
                depth += 1
                deepest = max(deepest, depth)
            elif ch in ")]}":
                depth -= 1
        if deepest > MAX_NESTING:
            raise self.fail(f"brackets are nested {deepest} deep (at most {MAX_NESTING})", hint=None)
        stripped = source.strip()
        self.offset += len(source) - len(source.lstrip())
        try:
            tree = ast.parse(stripped, mode="eval")
            self.source = stripped
        except SyntaxError as exc:
            col = f" at column {exc.offset + self.offset}" if exc.offset else ""
            raise InputError(f"the expression {_snippet(self.text)} is not valid syntax{col} ({exc.msg}).",
                             where=self.where, hint=HINT) from None
        except (ValueError, RecursionError, MemoryError, OverflowError) as exc:
            raise InputError(f"the expression {_snippet(self.text)} cannot be read ({type(exc).__name__}).",
                             where=self.where, hint=HINT) from None
        # bounded size and depth, counted without recursion
        count, stack = 0, [(tree.body, 1)]
        while stack:
            node, d = stack.pop()
            count += 1
            if count > MAX_NODES:
                raise self.fail(f"it has more than {MAX_NODES} parts; split it or simplify it", hint=None)
            if d > MAX_DEPTH:
                raise self.fail(f"it is nested more than {MAX_DEPTH} levels deep (or chains more than {MAX_DEPTH} "
                                "operations)", hint="Split it with intermediate parameters or simplify it.")
            stack.extend((c, d + 1) for c in ast.iter_child_nodes(node))
        self.screen(tree.body, condition)
        return tree.body

    def screen(self, root: ast.AST, condition: bool = False) -> None:
        """Refuse the worst construct first: names starting with '_' (dunders), then forbidden syntax."""
        nodes = sorted(ast.walk(root), key=lambda n: (getattr(n, "col_offset", 0), getattr(n, "end_col_offset", 0)))
        for node in nodes:
            name = node.id if isinstance(node, ast.Name) else node.attr if isinstance(node, ast.Attribute) else None
            if name is not None and name.startswith("_"):
                what = "the name" if isinstance(node, ast.Name) else "attribute access to"
                raise self.fail(f"{what} '{name}' is not allowed (names starting with '_', such as dunder names, "
                                "are refused)", node)
        for node in nodes:
            if type(node) in CONSTRUCTS and not (condition and node is root and isinstance(node, ast.Compare)):
                raise self.fail(f"{CONSTRUCTS[type(node)]} is not allowed", node)

    # nodes --------------------------------------------------------------------------------------
    def build(self, node: ast.AST):
        method = getattr(self, f"_{type(node).__name__}", None)
        if method is not None:
            try:
                return method(node)
            except InputError:
                raise
            except (TypeError, ValueError, ArithmeticError, AttributeError, RecursionError) as exc:
                raise self.fail(f"it cannot be evaluated ({type(exc).__name__}: {str(exc)[:80]})", node,
                                hint=None) from None
        if type(node) in CONSTRUCTS:
            raise self.fail(f"{CONSTRUCTS[type(node)]} is not allowed", node)
        raise self.fail(f"the construct '{type(node).__name__}' is not allowed", node)

    def _Constant(self, node: ast.Constant):
        v = node.value
        if isinstance(v, bool) or v is None or v is Ellipsis:
            raise self.fail(f"the constant {v!r} is not a number", node)
        if isinstance(v, str | bytes):
            raise self.fail("a string literal is not allowed (names are written without quotes)", node)
        if isinstance(v, complex):
            raise self.fail("complex numbers are not allowed", node)
        if isinstance(v, int):
            if len(str(abs(v))) > MAX_DIGITS:
                raise self.fail(f"the number has more than {MAX_DIGITS} digits", node)
            return sp.Integer(v)
        if isinstance(v, float):
            if not math.isfinite(v):
                raise self.fail(f"the number {v} is not finite", node)
            written = ast.get_source_segment(self.source, node) or ""      # the decimal as written: read exactly
            return exact_decimal(written if written.replace(".", "").isdigit() else repr(v), MAX_DIGITS)
        raise self.fail(f"the constant {v!r} is not allowed", node)

    def _Name(self, node: ast.Name):
        name = node.id
        if name.startswith("__") and name.endswith("__") or name.startswith("_"):
            raise self.fail(f"the name '{name}' is not allowed (names starting with '_', such as dunder names, "
                            "are refused)", node)
        if not name.isascii():
            raise self.fail(f"the name '{name}' is not ASCII", node)
        sc = self.scope
        if name in sc.names:
            return sc.names[name]
        if name in sc.vectors:
            return sc.vectors[name]
        if name in sc.ambiguous:
            frames = sc.ambiguous[name]
            raise self.fail(f"the basis name '{name}' belongs to several frames ({', '.join(frames)})", node,
                            hint=f"Write {frames[0]}.{name} or {frames[1]}.{name}.")
        if name in sc.frames:
            raise self.fail(f"'{name}' is a frame, not a vector", node,
                            hint=f"Name one of its basis vectors: {name}.x, {name}.y or {name}.z.")
        if name in FUNCTIONS or name in ("dot", "ddot") or name in sc.functions:
            raise self.fail(f"'{name}' is a function; call it with an argument, e.g. {name}(...)", node)
        known = sorted(set(sc.names) | set(sc.vectors))
        shown = ", ".join(known[:25]) + (", ..." if len(known) > 25 else "")
        raise self.fail(f"the name '{name}' is not declared", node,
                        hint=f"Declare it (as a parameter or coordinate) or use a known name: {shown}.")

    def _Attribute(self, node: ast.Attribute):
        attr = node.attr
        if attr.startswith("_"):
            raise self.fail(f"attribute access '.{attr}' is not allowed (names starting with '_', such as "
                            "dunder names, are refused)", node)
        if isinstance(node.value, ast.Name) and node.value.id not in self.scope.frames \
                and node.value.id not in self.scope.names:
            frames = ", ".join(self.scope.frames) or "none"
            raise self.fail(f"'{node.value.id}' is not a frame known here, so '{node.value.id}.{attr}' is not a basis "
                            "vector", node, hint=f"Frames known here: {frames} (a frame's own angle cannot use it).")
        if not isinstance(node.value, ast.Name) or node.value.id not in self.scope.frames:
            raise self.fail(f"attribute access '.{attr}' is not allowed: only FRAME.axis names a basis vector",
                            node)
        axes = self.scope.frames[node.value.id]
        if attr not in axes:
            raise self.fail(f"'{attr}' is not an axis of frame {node.value.id}", node,
                            hint=f"Use one of: {', '.join(axes)}.")
        return axes[attr]

    def _UnaryOp(self, node: ast.UnaryOp):
        if isinstance(node.op, ast.USub):
            return -self.build(node.operand)
        if isinstance(node.op, ast.UAdd):
            return self.build(node.operand)
        raise self.fail(f"the operator {OPERATORS.get(type(node.op), type(node.op).__name__)} is not allowed",
                        node)

    def _BinOp(self, node: ast.BinOp):
        op = type(node.op)
        if op in OPERATORS:
            raise self.fail(f"the operator {OPERATORS[op]} is not allowed", node)
        if op is ast.Pow:
            return self._power(node)
        a, b = self.build(node.left), self.build(node.right)
        va, vb = isinstance(a, Vector), isinstance(b, Vector)
        if op in (ast.Add, ast.Sub):
            if va != vb:
                scalar = b if va else a
                if scalar != 0:
                    raise self.fail("a vector and a scalar cannot be added", node,
                                    hint="Multiply the scalar by a basis vector (e.g. l*R.y).")
                a, b = (a, Vector(0)) if va else (Vector(0), b)
            return a + b if op is ast.Add else a - b
        if op is ast.Mult:
            if va and vb:
                raise self.fail("two vectors cannot be multiplied", node,
                                hint="A vector is a scalar times a basis vector, e.g. l/2*R.y.")
            return a * b
        if op is ast.Div:
            if vb:
                raise self.fail("cannot divide by a vector", node)
            if not va and b == 0:
                raise self.fail("division by zero", node)
            return a / b
        raise self.fail(f"the operator {op.__name__} is not allowed", node)

    def _power(self, node: ast.BinOp):
        for sub in ast.walk(node.right):
            if isinstance(sub, ast.BinOp) and isinstance(sub.op, ast.Pow):
                raise self.fail("a power inside an exponent (a tower such as 9**9**9) is not allowed", node,
                                hint=f"Exponents must be numbers of magnitude at most {MAX_EXPONENT}.")
        base, expo = self.build(node.left), self.build(node.right)
        if isinstance(base, Vector) or isinstance(expo, Vector):
            raise self.fail("a vector cannot be raised to a power or be an exponent", node)
        if not expo.is_number:
            raise self.fail(f"the exponent {expo} is not a number", node,
                            hint=f"Exponents must be numbers of magnitude at most {MAX_EXPONENT}.")
        e = numeric_value(expo)
        limit = MAX_NUMBER_EXPONENT if base.is_number else MAX_EXPONENT
        if e is None or e.imag or not math.isfinite(e.real) or abs(e.real) > limit:
            raise self.fail(f"the exponent {expo} is too large (at most {limit} in magnitude"
                            f"{' for a power of a symbol' if limit == MAX_EXPONENT else ''})", node,
                            hint="Write the power out with intermediate parameters, or check the exponent.")
        if base.is_number:
            b = numeric_value(base)
            if b is None or not math.isfinite(abs(b)):
                raise self.fail("the base of the power is not a finite number", node)
            if b != 0 and abs(e.real) * math.log10(abs(b)) > math.log10(MAX_MAGNITUDE):
                raise self.fail(f"the power is too large a number (above {MAX_MAGNITUDE:.0e})", node)
            if b == 0 and e.real < 0:
                raise self.fail("division by zero (0 to a negative power)", node)
        result = base**expo
        for p in sp.preorder_traversal(result):
            if isinstance(p, sp.Pow) and not p.base.is_number and p.exp.is_number \
                    and abs(complex(sp.N(p.exp, 15)).real) > MAX_EXPONENT:
                raise self.fail(f"the combined exponent {p.exp} is too large (at most {MAX_EXPONENT})", node)
        return result

    def _Call(self, node: ast.Call):
        if not isinstance(node.func, ast.Name):
            if isinstance(node.func, ast.Attribute):
                self._Attribute(node.func)           # refuses dunders and attribute access first
            raise self.fail("only the whitelisted functions can be called", node)
        name = node.func.id
        if name.startswith("_"):
            raise self.fail(f"the name '{name}' is not allowed (names starting with '_', such as dunder "
                            "names, are refused)", node)
        if node.keywords:
            raise self.fail(f"keyword arguments in {name}(...) are not allowed", node)
        if any(isinstance(a, ast.Starred) for a in node.args):
            raise self.fail(f"starred arguments in {name}(...) are not allowed", node)
        if name in ("dot", "ddot"):
            return self._derivative(node, name)
        if name in self.scope.functions:
            return self.scope.functions[name](node.args, node, self)
        if name not in FUNCTIONS:
            what = "is not a function" if name in self.scope.names else "is not a known function"
            raise self.fail(f"'{name}' {what}", node, hint=f"The functions are {', '.join(FUNCTIONS)}, "
                                                              "dot and ddot.")
        fn, arity = FUNCTIONS[name]
        if len(node.args) != arity:
            raise self.fail(f"{name} takes {arity} argument{'s' if arity > 1 else ''}, not {len(node.args)}", node)
        self.calls += 1
        if self.calls > MAX_CALLS_NESTED:
            raise self.fail(f"functions are nested more than {MAX_CALLS_NESTED} deep", node,
                            hint="Split the expression with intermediate parameters.")
        try:
            args = [self.build(a) for a in node.args]
        finally:
            self.calls -= 1
        if any(isinstance(a, Vector) for a in args):
            raise self.fail(f"{name} of a vector is not defined", node)
        for a in args:
            self.bounded(a, node)
        return self.bounded(fn(*args), node)

    def bounded(self, value, node):
        """``value``, refused when it is a number that is not finite, not real, or too large."""
        if isinstance(value, sp.Basic) and not value.free_symbols:
            v = numeric_value(value)
            if value.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
                raise self.fail("it evaluates to an infinite or undefined value (division by zero?)", node, hint=None)
            if v is not None and not (math.isfinite(v.real) and math.isfinite(v.imag)
                                      and abs(v) <= MAX_MAGNITUDE):
                raise self.fail(f"{sp.sstr(value)[:40]} is too large a number (above {MAX_MAGNITUDE:.0e}) or not "
                                "finite", node, hint="Write numbers of a sensible size in SI units.")
            if v is not None and abs(v.imag) > 1e-12 * max(1.0, abs(v.real)):
                raise self.fail(f"{sp.sstr(value)[:40]} is a complex number, not a real one", node,
                                hint="acos and asin take values between -1 and 1; log and sqrt take values ≥ 0.")
        return value

    def _derivative(self, node: ast.Call, name: str):
        if len(node.args) != 1 or not isinstance(node.args[0], ast.Name):
            raise self.fail(f"{name}() takes the name of one coordinate, e.g. {name}(theta)", node)
        q = node.args[0].id
        if q in self.scope.speeds and q not in self.scope.coordinates:
            return self._speed_rate(node, name, q)
        if q not in self.scope.coordinates:
            known = ", ".join(self.scope.coordinates) or "none"
            raise self.fail(f"'{q}' is not a coordinate, so {name}({q}) is not defined", node,
                            hint=f"The coordinates are: {known}.")
        order = 1 if name == "dot" else 2
        if order > self.scope.max_derivative:
            raise self.fail(f"{name}({q}), an acceleration, cannot appear here: a load, a constraint or the geometry "
                            "depends on the state (coordinates and rates), not on accelerations", node,
                            hint="Write the load in the coordinates and their rates (dot(q)); accelerations are "
                                 "unknowns the laws solve for.")
        return self.scope.coordinates[q].diff(t, 1 if name == "dot" else 2)

    def _speed_rate(self, node: ast.Call, name: str, w: str):
        """dot(w) of a speed w: its rate ẇ, an acceleration (ddot would be a third derivative)."""
        if name == "ddot":
            raise self.fail(f"ddot({w}) is not defined: {w} is a speed, and dot({w}) is already its rate", node,
                            hint=f"Write dot({w}) for the rate of the speed {w}.")
        if self.scope.max_derivative < 2:
            raise self.fail(f"dot({w}), the rate of the speed {w}, is an acceleration and cannot appear here: a "
                            "load, a constraint or the geometry depends on the state (coordinates and speeds)",
                            node, hint=f"Write the load in the coordinates and the speeds ({w}).")
        return self.scope.speeds[w].diff(t)

    # results ------------------------------------------------------------------------------------
    def check(self, value):
        if isinstance(value, Vector):
            for measure, _frame in value.args:
                for comp in measure:
                    self.check(sp.sympify(comp))
            return value
        if not isinstance(value, sp.Basic):
            raise self.fail(f"the result {value!r} is not an expression")
        if value.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            raise self.fail("it evaluates to an infinite or undefined value (division by zero?)", hint=None)
        if value.has(sp.I):
            raise self.fail("it evaluates to a complex number", hint="Expressions must be real.")
        return self.bounded(value, None)


def _prepare(text, where: str | None) -> str:
    if isinstance(text, bool) or not isinstance(text, str | int | float):
        raise InputError(f"expected an expression (a string) or a number, not {type(text).__name__}.",
                         where=where)
    if isinstance(text, int | float):
        return text
    if len(text) > MAX_LENGTH:
        raise InputError(f"the expression is {len(text)} characters long (at most {MAX_LENGTH}).", where=where,
                         hint="Split the problem into parameters, or simplify the expression.")
    if "\x00" in text:
        raise InputError("the expression contains a NUL character.", where=where)
    if not text.strip():
        raise InputError("the expression is empty.", where=where, hint="Write an expression, e.g. \"l/2\".")
    return text


def _number(value, where):
    if isinstance(value, int):
        if len(str(abs(value))) > MAX_DIGITS:
            raise InputError(f"the number has more than {MAX_DIGITS} digits.", where=where)
        return sp.Integer(value)
    if not math.isfinite(value):
        raise InputError(f"the number {value} is not finite.", where=where, hint="Give a finite real number.")
    if abs(value) > MAX_MAGNITUDE:
        raise InputError(f"the number {value:g} is too large (above {MAX_MAGNITUDE:.0e}).", where=where,
                         hint="Give the value in SI units of a sensible size.")
    return exact_decimal(repr(value), MAX_DIGITS)           # read exactly: 0.1 is 1/10


def parse(text: str | int | float, scope: Scope, where: str | None = None, want: str = "scalar"):
    """Parse an expression into a sympy expression (``want="scalar"``) or a Vector (``want="vector"``).

    ``want="any"`` returns whichever it is.  Numbers given directly (TOML integers and floats) are
    accepted as they are; a vector field also accepts the number 0 (the zero vector).
    """
    text = _prepare(text, where)
    if isinstance(text, int | float):
        value = _number(text, where)
    else:
        p = _Parser(text, scope, where)
        value = p.check(p.build(p.tree(text)))
    return _want(value, want, text, where)


def _want(value, want, text, where):
    is_vec = isinstance(value, Vector)
    if want == "vector" and not is_vec:
        if value == 0:
            return Vector(0)
        raise InputError(f"the expression {_snippet(str(text))} is a scalar where a vector is expected.",
                         where=where, hint="Multiply by a basis vector, e.g. \"l/2*R.y\" or \"-l*er\".")
    if want == "scalar" and is_vec:
        raise InputError(f"the expression {_snippet(str(text))} is a vector where a scalar is expected.",
                         where=where, hint="Write a scalar expression (no basis vectors).")
    return value


def parse_scalar(text, scope: Scope, where: str | None = None) -> sp.Expr:
    """A scalar expression."""
    return parse(text, scope, where, "scalar")


def parse_vector(text, scope: Scope, where: str | None = None) -> Vector:
    """A vector expression: scalars times basis vectors."""
    return parse(text, scope, where, "vector")


def _split_equation(text: str, where) -> tuple[str, str, int]:
    positions = [i for i, ch in enumerate(text) if ch == "="
                 and (i == 0 or text[i - 1] not in "=<>!") and (i + 1 == len(text) or text[i + 1] != "=")]
    if "==" in text:
        raise InputError(f"the equation {_snippet(text)} uses '=='.", where=where,
                         hint="Write an equation with a single '=', e.g. \"N_A = 0\".")
    if len(positions) != 1:
        raise InputError(f"{_snippet(text)} is not an equation: it needs exactly one '=' "
                         f"(it has {len(positions)}).", where=where,
                         hint="Write it as \"lhs = rhs\", e.g. \"N_A = 0\".")
    i = positions[0]
    return text[:i], text[i + 1:], i + 1


def parse_equation(text, scope: Scope, where: str | None = None) -> sp.Eq:
    """An equation ``"lhs = rhs"`` between scalars, as an unevaluated ``sp.Eq``."""
    text = _prepare(text, where)
    if not isinstance(text, str):
        raise InputError(f"expected an equation such as \"N_A = 0\", not the number {text}.", where=where)
    left, right, split = _split_equation(text, where)
    sides = []
    for part, offset in ((left, 0), (right, split)):
        if not part.strip():
            raise InputError(f"the equation {_snippet(text)} has an empty side.", where=where,
                             hint="Write it as \"lhs = rhs\", e.g. \"N_A = 0\".")
        p = _Parser(part, scope, where, offset)
        p.text = text
        sides.append(_want(p.check(p.build(p.tree(part))), "scalar", text, where))
    return sp.Eq(sides[0], sides[1], evaluate=False)


def parse_condition(text, scope: Scope, where: str | None = None) -> sp.core.relational.Relational:
    """A condition ``"lhs > rhs"`` (or ``<``, ``<=``, ``>=``) between scalars, unevaluated."""
    text = _prepare(text, where)
    if not isinstance(text, str):
        raise InputError(f"expected a condition such as \"dot(x) > 0\", not the number {text}.", where=where)
    p = _Parser(text, scope, where)
    node = p.tree(text, condition=True)
    if not isinstance(node, ast.Compare) or len(node.ops) != 1 or type(node.ops[0]) not in RELATIONS:
        raise InputError(f"{_snippet(text)} is not a condition.", where=where,
                         hint="Write one comparison with <, >, <= or >=, e.g. \"dot(x) - r*dot(phi) > 0\".")
    lhs = _want(p.check(p.build(node.left)), "scalar", text, where)
    rhs = _want(p.check(p.build(node.comparators[0])), "scalar", text, where)
    return RELATIONS[type(node.ops[0])](lhs, rhs, evaluate=False)


def check_name(name: str, kind: str, where: str | None = None) -> str:
    """A name a problem file declares: an ASCII identifier as :func:`rigidkin.model.checks.check_identifier`
    allows it (no keyword, no name the engine makes), and not a word of the expression language."""

    check_identifier(name, kind, where, InputError)
    if name in RESERVED:
        raise InputError(f"the {kind} name '{name}' shadows the built-in '{name}' of the expression language.",
                         where=where, hint=f"Choose another name; reserved: {', '.join(sorted(RESERVED))}.")
    return name
