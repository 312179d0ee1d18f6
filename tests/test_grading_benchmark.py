"""The grading accuracy benchmark as a test: no wrong verdict on any step.

``benchmarks/grading/cases.toml`` holds worksheets written by hand (closed forms derived on paper, noted
beside each problem in tests/test_grading.py and in the data file): right derivations in several forms and
the classic mistakes, over 2D and 3D problems, each step with the verdict a hand grader gives.  The cause
accuracy is printed by ``benchmarks/grading_accuracy.py`` (a figure, not asserted here).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _bench():
    spec = importlib.util.spec_from_file_location("grading_accuracy", ROOT / "benchmarks" / "grading_accuracy.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("grading_accuracy", mod)      # a dataclass needs its module registered
    spec.loader.exec_module(sys.modules["grading_accuracy"])
    mod = sys.modules["grading_accuracy"]
    return mod


@pytest.mark.slow          # a minute on 2 cores: every step of the benchmark graded
def test_benchmark_has_no_wrong_verdict():
    rows = _bench().run()
    assert len(rows) >= 150
    problems = {r.problem for r in rows}
    assert len(problems) >= 6 and {"heavy-top", "benchmarks/grading/quaternion-top.toml"} <= problems   # 3D too
    assert sum(r.expect == "incorrect" for r in rows) >= 60 and sum(r.expect == "correct" for r in rows) >= 60
    wrong = [(r.case, r.step.get("claim"), r.expect, r.verdict, r.feedback) for r in rows if not r.verdict_ok]
    assert not wrong, wrong
    # one cause per wrong step (beside the note that a first integral was graded through its derivative)
    many = [(r.step.get("claim"), r.feedback) for r in rows if r.verdict == "incorrect" and
            len([f for f in r.feedback if not f.startswith("read as a first integral")]) != 1]
    assert not many, many
