"""Grading a hand derivation step by step, and problem sets made from a problem.

A *worksheet* (TOML) names a problem and lists the student's steps in the method's order — kinematics,
free-body diagram, balance laws, equations of motion, answers.  :func:`grade_file` derives every step
itself (the problem's own solution) and returns a :class:`~rigidkin.grading.verdicts.GradeReport`: a
verdict per step (correct, incorrect, unreadable) with the cause of each mistake.
:mod:`rigidkin.grading.variants` makes problem sets (changed parameters, answer keys, Moodle XML).
"""

from __future__ import annotations

from .steps import grade, grade_file
from .verdicts import GradeReport, StepResult
from .worksheet import Step, Worksheet, load_worksheet, parse_worksheet

__all__ = ["GradeReport", "StepResult", "Step", "Worksheet", "grade", "grade_file", "load_worksheet",
           "parse_worksheet"]
