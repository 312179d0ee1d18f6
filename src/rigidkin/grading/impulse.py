"""Grading an impulse–momentum step: ``law = "impulse"`` with an impulse question of the problem.

In the claim, ``dot(q)`` is the rate just after the blow and a reaction impulse is written with its
name and ``_hat`` (``R_Ox_hat``); the configuration is the one at the instant.  The engine's impulse
equations are linear in the rates after and the reaction impulses and determine them, so an equation
in those unknowns is a valid combination of them exactly when it holds at the engine's solution — the
claim is checked there, at random parameter values.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..base.errors import InputError
from ..base.printing import text
from . import space
from .claims import parse_claim
from .engine import Reference
from .feedback import dimension_problem
from .verdicts import CORRECT, INCORRECT, StepResult
from .worksheet import Step

t = dynamicsymbols._t


def grade_impulse(ref: Reference, st: Step) -> StepResult:
    questions = [q for q in ref.spec_questions() if q.kind == "impulse"]
    if st.question:
        questions = [q for q in questions if q.name == st.question]
    if not questions:
        raise InputError("an impulse–momentum step needs an impulse question of the problem "
                         "(kind = \"impulse\"), named with question = \"NAME\".", where=st.where)
    q = questions[0]
    a = ref.answers().get(q.name)
    res = StepResult(st.index, st.kind, INCORRECT)
    if a is None or isinstance(a, Exception):
        res.feedback = [f"the engine could not answer '{q.name}' itself ({a}), so the step is not graded"]
        return res
    hats = {name: sp.Symbol(name, real=True) for name in a.details.get("reaction_impulses", {})}
    saved = ref.scope
    ref.scope = saved.with_names(hats)
    try:
        lhs, rhs = parse_claim(ref, st)
    finally:
        ref.scope = saved
    expr = lhs - rhs
    end = dict(a.details.get("end_state", {}))
    rates = {k: v for k, v in end.items() if isinstance(k, sp.Derivative)}
    conf = {k: v for k, v in end.items() if not isinstance(k, sp.Derivative)}
    unknowns = set(rates) | set(hats.values())
    if not any(expr.has(u) for u in unknowns):
        res.feedback = ["it contains neither a rate just after the blow nor a reaction impulse"]
        return res
    at = expr.xreplace(rates).xreplace({hats[n]: v for n, v in a.details["reaction_impulses"].items()})
    at = at.xreplace(conf)
    scale = sum((abs(x) for x in sp.Add.make_args(expr.xreplace(rates).xreplace(conf))), sp.S.Zero)
    vals = ref.sampler.evaluate([space.to_plain(at), space.to_plain(scale)])
    if space.vanishes(vals[:, :1], np.abs(vals)):
        res.verdict = CORRECT
        return res
    dim = dimension_problem(ref, lhs, rhs)      # one cause: the dimension, else the values it misses
    shown = ", ".join(f"{text(k)} = {text(v)}" for k, v in rates.items())
    res.feedback.append(dim or (f"it does not hold just after the blow, where {shown}"
                                + (", " + ", ".join(f"{n} = {text(v)}" for n, v in
                                                    a.details["reaction_impulses"].items()) if hats else "")))
    res.expected = a.text
    return res
