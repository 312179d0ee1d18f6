"""Reading a student's claim: an equation (a balance law, an equation of motion, an impulse–momentum
equation) or an expression, in the problem's own names.  A claim the parser refuses makes the step
unreadable, and the parser's message says where and why.
"""

from __future__ import annotations

import sympy as sp

from ..base.errors import RigidkinError
from ..io.expressions import parse_equation, parse_scalar
from .engine import Reference
from .worksheet import Step


class Unreadable(Exception):
    """The claim of a step could not be read: the step's verdict is ``unreadable``."""


def read(kind: str, fn, *args):
    """Run a parser; its refusal makes the step unreadable (the message says where and why)."""
    try:
        return fn(*args)
    except RigidkinError as exc:
        raise Unreadable(f"unreadable {kind}: {exc.message}" + (f" {exc.hint}" if exc.hint else "")) from None


def parse_claim(ref: Reference, st: Step):
    """The two sides of an equation claimed in a step (an expression alone is ``expression = 0``)."""
    txt = st.claim
    bare = txt.replace("<=", "").replace(">=", "").replace("==", "")
    if "=" in bare:
        eq = read("equation", parse_equation, txt, ref.scope, st.where)
        return eq.lhs, eq.rhs
    return read("equation", parse_scalar, txt, ref.scope, st.where), sp.Integer(0)
