"""The questions a user can ask of a system (a problem file's ``[ask]``, or the Python API).

A ``Question`` has a ``kind`` and parsed ``fields`` (sympy expressions, equations as ``sp.Eq``,
states as {coordinate or its rate: value}).  The problem-file reader builds them from TOML;
``rigidkin.analysis.answers.answer(system, question)`` answers them.

Kinds and their fields (all optional unless marked).  Every kind also takes ``mode`` (contact
states), ``set`` (parameter substitutions) and ``after`` (the name of an earlier question whose end
state is the start):

``eom``           the equations of motion (always answered by ``solve``)
``reaction``      ``reaction`` (name, required), ``start`` (state): the reaction along the motion from
                  ``start`` as a function of the configuration (first integral substituted)
``integral``      ``start``: the energy integral (q̇² as a function of q) from ``start``
``event``         ``when`` (an equation, required: ``N_A = 0``, ``dot(theta) = 0``, ``theta = 1``,
                  ``slip(ground) = 0``), ``start``, ``mode``: the configuration where it happens
``extreme``       ``coordinate`` (required), ``start``: the largest value reached
``threshold``     ``holds`` (an inequality, required: ``N >= 0``), ``start``, ``over`` ([a, b], the range
                  of the coordinate the motion must cover; default a full turn), ``expression`` (what to
                  report at the threshold, e.g. ``(R - r)**2*dot(theta)**2`` for v²): the smallest start
                  rate for which the condition holds along the whole motion
``equilibrium``   ``mode``: equilibrium configurations, linearised EOM, stability, natural frequencies
``impulse``       ``start``: velocities just after the system's impulses, and reaction impulses
``interval``      ``duration`` or ``until`` (equation), ``start``, ``mode``, ``regime`` (a condition):
                  the state at the end of an interval of constant forces (impulse–momentum)
``phases``        ``start``, ``phase`` (list of {name, mode, set, until}): a problem in phases
``value``         ``expression`` (required), ``at`` (state): a quantity at an instant
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

KINDS = ("eom", "reaction", "integral", "event", "extreme", "threshold", "equilibrium", "impulse", "interval",
         "phases", "value")

REQUIRED = {"reaction": ("reaction",), "event": ("when",), "extreme": ("coordinate",),
            "interval": (), "value": ("expression",), "phases": ("phase",), "threshold": ("holds",)}


@dataclass(frozen=True)
class Question:
    """One question: ``kind`` (one of KINDS), a ``name`` for the answer, parsed ``fields``."""

    kind: str
    name: str
    fields: Mapping[str, Any] = field(default_factory=dict)
    where: str = ""          # where it was written (file, line, field path) for error messages


@dataclass(frozen=True)
class Answer:
    """An answer: an exact sympy ``value`` where a closed form exists, else a number with ``tolerance``."""

    question: Question
    value: Any
    text: str
    exact: bool = True
    tolerance: float | None = None
    note: str = ""
    details: Mapping[str, Any] = field(default_factory=dict)
