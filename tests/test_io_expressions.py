"""The safe expression parser: what it builds (checked against sympy objects built by hand) and what it
refuses (each refusal names the construct and its column), within bounded time."""

import time

import pytest
import sympy as sp
from sympy.physics.vector import ReferenceFrame, Vector, dynamicsymbols

from rigidkin.base.errors import InputError
from rigidkin.io.expressions import (
    MAX_EXPONENT,
    Scope,
    check_name,
    default_scope,
    parse,
    parse_condition,
    parse_equation,
    parse_scalar,
    parse_vector,
    slip,
)

t = dynamicsymbols._t
m, l, K, L0 = sp.symbols("m l K L0", positive=True)
theta, x = dynamicsymbols("theta x")
N_A = sp.Symbol("N_A", real=True)
F = ReferenceFrame("F")
R = ReferenceFrame("R")
R.orient_axis(F, F.z, theta)


@pytest.fixture
def scope() -> Scope:
    sc = default_scope()
    sc.names.update(m=m, l=l, K=K, L0=L0, theta=theta, x=x)
    sc.coordinates.update(theta=theta, x=x)
    sc.add_frame("F", ("Ex", "Ey", "Ez"), (F.x, F.y, F.z))
    sc.add_frame("R", ("er", "et", "ez"), (R.x, R.y, R.z))
    return sc


@pytest.mark.parametrize("text, expected", [
    ("l/2*sin(theta)", l * sp.sin(theta) / 2),
    ("-K*(x - L0)", -K * (x - L0)),
    ("m*l**2/12", m * l**2 / 12),
    ("2**-3", sp.Rational(1, 8)),
    ("sqrt(2*m)*cos(pi/3)", sp.sqrt(2 * m) / 2),
    ("atan2(1, 1)", sp.pi / 4),
    ("abs(x) + sign(theta) + exp(0) + log(1)", sp.Abs(x) + sp.sign(theta) + 1),
    ("asin(1) + acos(1) + atan(0) + tan(0)", sp.pi / 2),
    ("dot(theta)**2*l + ddot(x)", l * theta.diff(t) ** 2 + x.diff(t, 2)),
    ("m*t", m * t),
    ("+m - -l", m + l),
    ("1.5*m", sp.Float(1.5) * m),
    ("(((((m)))))", m),
    ("m**(1/2)", sp.sqrt(m)),
    ("m**0.5", sp.sqrt(m)),                    # a decimal is read exactly (issue 26)
])
def test_scalars(scope, text, expected):
    got = parse_scalar(text, scope)
    assert sp.simplify(got - expected) == 0


def test_numbers_pass_through(scope):
    assert parse_scalar(3, scope) == 3 and parse_scalar(0.25, scope) == sp.Rational(1, 4)   # read exactly
    assert parse_vector(0, scope) == Vector(0)


def test_vectors(scope):
    assert parse_vector("l/2*R.y", scope) == l / 2 * R.y
    assert parse_vector("-l*er", scope) == -l * R.x
    assert parse_vector("x*Ex + l*F.y - R.z/2", scope) == x * F.x + l * F.y - R.z / 2
    assert parse_vector("R.et*m", scope) == m * R.y
    assert parse_vector("(l - x)*(R.x + F.y)", scope) == (l - x) * R.x + (l - x) * F.y
    # the basis name alone is the same vector as FRAME.name
    assert parse_vector("ez", scope) == parse_vector("R.ez", scope)


def test_shared_basis_names_need_the_frame(scope):
    G = ReferenceFrame("G")
    scope.add_frame("G", ("er", "e2", "e3"), (G.x, G.y, G.z))
    with pytest.raises(InputError, match="belongs to several frames .*R, G"):
        parse_vector("er", scope)
    assert parse_vector("G.er", scope) == G.x and parse_vector("R.er", scope) == R.x


def test_equations_and_conditions(scope):
    eq = parse_equation("N_A = 0", scope.with_names({"N_A": N_A}))
    assert isinstance(eq, sp.Eq) and eq.lhs == N_A and eq.rhs == 0
    eq = parse_equation("x = l*sin(theta)", scope)
    assert eq.lhs == x and eq.rhs == l * sp.sin(theta)
    # an equation that sympy would evaluate to True stays an equation
    assert isinstance(parse_equation("dot(theta) = dot(theta)", scope), sp.Eq)
    c = parse_condition("dot(x) - l*dot(theta) > 0", scope)
    assert isinstance(c, sp.StrictGreaterThan) and c.lhs == x.diff(t) - l * theta.diff(t)
    assert isinstance(parse_condition("m <= l", scope), sp.LessThan)


def test_extra_functions(scope):
    def handler(args, node, parser):
        return slip(sp.Symbol(args[0].id))

    sc = scope.with_functions({"slip": handler})
    eq = parse_equation("slip(ground) = 0", sc)
    assert eq.lhs == slip(sp.Symbol("ground"))


@pytest.mark.parametrize("text, words", [
    ("__import__('os')", ["'__import__'", "dunder"]),
    ("().__class__.__bases__", ["'__class__'", "dunder"]),
    ("lambda: 0", ["lambda"]),
    ("9**9**9**9", ["power inside an exponent"]),
    ("m[0]", ["subscript"]),
    ("[a for a in m]", ["list comprehension"]),
    ("{a for a in m}", ["set comprehension"]),
    ("(a for a in m)", ["generator expression"]),
    ("{1: 2}", ["dict"]),
    ("m.real", ["attribute access '.real'"]),
    ("R.__dict__", ["'__dict__'"]),
    ("q.x", ["'q' is not a frame known here"]),
    ("R.w", ["'w' is not an axis of frame R"]),
    ("foo + 1", ["'foo' is not declared"]),
    ("nan", ["'nan' is not declared"]),
    ("1e999", ["not finite"]),
    ("1j", ["complex"]),
    ("'text'", ["string"]),
    ("True", ["not a number"]),
    ("m if l else 1", ["conditional"]),
    ("m == 1", ["comparison"]),
    ("m and l", ["'and'/'or'"]),
    ("m ^ 2", ["^"]),
    ("m // 2", ["//"]),
    ("m % 2", ["%"]),
    ("eval('1')", ["'eval' is not a known function"]),
    ("m(2)", ["'m' is not a function"]),
    ("sin", ["'sin' is a function"]),
    ("sin(m, l)", ["sin takes 1 argument"]),
    ("sin(x=1)", ["keyword arguments"]),
    ("sin(*m)", ["starred"]),
    ("dot(m)", ["'m' is not a coordinate"]),
    ("dot(2*theta)", ["name of one coordinate"]),
    ("R.x*R.y", ["two vectors cannot be multiplied"]),
    ("R.x + 1", ["a vector and a scalar cannot be added"]),
    ("m/R.x", ["divide by a vector"]),
    ("sin(R.x)", ["sin of a vector"]),
    ("1/0", ["division by zero"]),
    ("0**-1", ["division by zero"]),
    ("log(0)", ["infinite or undefined"]),
    ("sqrt(-1)", ["complex number"]),
    ("m**m", ["exponent m is not a number"]),
    ("m**1000", ["exponent 1000 is too large"]),
    ("(m**10)**10", ["combined exponent 100"]),
    ("(m**50)**50", ["exponent 50 is too large"]),
    ("(10**40)**100", ["too large a number"]),
    ("1" * 50, ["more than 40 digits"]),
    ("(" * 50 + "1" + ")" * 50, ["nested 50 deep"]),
    ("-" * 500 + "1", ["nested more than 100 levels"]),
    ("+".join(["m"] * 300), ["chains more than 100 operations"]),
    ("*".join(["(" + "+".join(["m"] * 90) + ")"] * 5), ["more than 400 parts"]),
    ("m +", ["not valid syntax"]),
    ("x = 1", ["not valid syntax"]),
    ("θ", ["not ASCII"]),
    ("F", ["'F' is a frame"]),
    ("", ["empty"]),
])
def test_refusals_name_the_construct(scope, text, words):
    start = time.process_time()
    with pytest.raises(InputError) as err:
        parse(text, scope, where="problem.toml, line 3, points.G.offset", want="any")
    assert time.process_time() - start < 1.0      # CPU time: other work on the machine does not count
    msg = str(err.value)
    assert msg.startswith("problem.toml, line 3, points.G.offset: ")
    for w in words:
        assert w in msg, (w, msg)


def test_columns_are_reported(scope):
    with pytest.raises(InputError, match="at column 5"):
        parse_scalar("m + foo", scope)
    with pytest.raises(InputError, match="at column 7"):
        parse_equation("N_A = bar", scope.with_names({"N_A": N_A}))


def test_huge_input_is_refused_before_parsing(scope):
    start = time.process_time()
    with pytest.raises(InputError, match="10000000 characters long"):
        parse_scalar("m" * 10_000_000, scope)
    with pytest.raises(InputError, match="characters long"):
        parse_scalar("(" * 10_000 + ")" * 10_000, scope)
    assert time.process_time() - start < 1.0


def test_scalar_and_vector_are_not_confused(scope):
    with pytest.raises(InputError, match="vector where a scalar is expected"):
        parse_scalar("l*R.y", scope)
    with pytest.raises(InputError, match="scalar where a vector is expected"):
        parse_vector("l", scope)


def test_equation_syntax(scope):
    for bad, word in [("N_A == 0", "'=='"), ("a = b = c", "exactly one '='"), ("= 3", "empty side"),
                      ("m", "exactly one '='"), ("m <= 3", "exactly one '='")]:
        with pytest.raises(InputError, match=word):
            parse_equation(bad, scope.with_names({"N_A": N_A}))
    with pytest.raises(InputError, match="not a condition"):
        parse_condition("m + 1", scope)
    with pytest.raises(InputError, match="not a condition"):
        parse_condition("0 < m < 1", scope)


def test_exponent_limit_is_inclusive(scope):
    assert parse_scalar(f"m**{MAX_EXPONENT}", scope) == m**MAX_EXPONENT
    assert parse_scalar(f"m**-{MAX_EXPONENT}", scope) == m**-MAX_EXPONENT


@pytest.mark.parametrize("name", ["sin", "dot", "t", "pi", "lambda", "_x", "__import__", "x-y", "1a", "θ"])
def test_declared_names_are_checked(name):
    with pytest.raises(InputError):
        check_name(name, "parameter", "f.toml, parameters")


def test_good_names_pass():
    for name in ("m", "m1", "F_hat", "L0", "theta_dot", "mu"):
        assert check_name(name, "parameter") == name
