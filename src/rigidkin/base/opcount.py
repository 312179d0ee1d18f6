"""Operation counts equal to ``sympy.count_ops``, found with each shared subexpression counted once.

``sympy.count_ops(e)`` walks the tree of ``e``, collects one symbol per operation (ADD, MUL, SIN …) and
adds them up symbolically.  Its count is a sum over the nodes of the tree, and each node's share depends
on that node alone, so the same count is found by counting each distinct subexpression once and adding
whole integers.  The rules per node are sympy's, line for line: a negative coefficient is a NEG, a
denominator a DIV, a negative term of a sum a SUB, a product of k factors k − 1 MULs, a power or a
function one operation, e and exp(·) one EXP.
"""

from __future__ import annotations

import sympy as sp
from sympy.core.function import _coeff_isneg
from sympy.core.relational import Relational


def count_ops(expr, memo: dict | None = None) -> int:
    """``sympy.count_ops(expr)`` (an integer), counting each shared subexpression once; ``memo`` (a dict)
    may be shared by several calls on expressions with common parts."""
    expr = sp.sympify(expr)
    if not isinstance(expr, sp.Expr) or expr.is_Relational or isinstance(expr, Relational):
        return int(sp.count_ops(expr))
    return _Counter({} if memo is None else memo).count(expr)


def _whole_numerator(a) -> bool:
    """Whether ``sympy.fraction`` puts every factor of the product ``a`` in the numerator: none is a
    fraction, and every power among them has a positive whole exponent."""
    for term in a.args:
        if term.is_Rational:
            if not term.is_Integer:
                return False
        elif isinstance(term, sp.exp) or (term.is_Pow and not (term.exp.is_Integer and term.exp > 0)):
            return False
    return True


class _Counter:
    def __init__(self, memo: dict):
        self.memo = memo

    def count(self, a) -> int:
        hit = self.memo.get(a)
        if hit is None:
            hit = self.memo[a] = self._node(a)
        return hit

    def _node(self, a) -> int:
        if a.is_Rational:
            if a is not sp.S.One:
                return (1 if a.p < 0 else 0) + (1 if a.q != 1 else 0)
        elif a.is_Mul or a.is_MatMul:
            c = 0
            if _coeff_isneg(a):
                c += 1
                a = a.as_two_terms()[1] if a.args[0] is sp.S.NegativeOne else -a
            if _whole_numerator(a):        # sp.fraction(a) would give (a, 1): no need to rebuild a
                return c + self._rest(a)
            n, d = sp.fraction(a)
            if n.is_Integer:
                return c + 1 + (1 if n < 0 else 0) + self.count(d)
            if d is not sp.S.One:
                if not d.is_Integer:
                    c += self.count(d)
                return c + 1 + self.count(n)
            return c + self._rest(a)
        elif a.is_Add or a.is_MatAdd:
            args = list(a.args)
            c = negs = 0
            for i, ai in enumerate(args):
                if _coeff_isneg(ai):
                    negs += 1
                    c += self.count(-ai)
                else:
                    c += self.count(ai)
                if i > 0:
                    c += 1                  # an ADD or a SUB
            if negs == len(args):           # -x - y: a NEG and a SUB
                c += 1
            return c                        # -x + y: one SUB in place of an ADD, the same count
        return self._rest(a)

    def _rest(self, a) -> int:
        if a.is_Pow and a.exp is sp.S.NegativeOne:
            return 1 + self.count(a.base)
        if a == sp.S.Exp1:
            return 1
        if a.is_Pow and a.base == sp.S.Exp1:
            return 1 + self.count(a.exp)
        c = 0
        if a.is_Mul or isinstance(a, sp.core.operations.LatticeOp):
            c += len(a.args) - 1
        elif a.args and (a.is_Pow or a.is_Function or isinstance(a, (sp.Derivative, sp.Integral, sp.Sum))):
            c += 1
        if not a.is_Symbol:
            c += sum(self.count(x) for x in a.args)
        return c
