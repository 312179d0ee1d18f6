"""Grading accuracy: the verdicts and causes of ``rigidkin grade`` against a hand grading.

Reads ``benchmarks/grading/cases.toml`` (worksheets of right derivations in several forms and the classic
mistakes over 2D and 3D problems, each step with its expected verdict and cause), grades every step and
prints, per problem, the steps, the wrong verdicts and the cause accuracy (the expected cause is the
one feedback line the grader gives).  ``tests/test_grading_benchmark.py`` asserts zero wrong verdicts.

    PYTHONPATH=src python benchmarks/grading_accuracy.py [--show]
"""

from __future__ import annotations

import json
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "grading" / "cases.toml"
_OWN = {"expect", "cause"}


@dataclass
class Graded:
    case: str
    problem: str
    step: dict
    expect: str
    cause: str
    verdict: str
    feedback: list

    @property
    def verdict_ok(self) -> bool:
        return self.verdict == self.expect

    @property
    def cause_ok(self) -> bool:
        """The expected cause is the first (and only) cause given; a correct step needs none."""
        if self.expect == "correct" or not self.cause:
            return self.verdict_ok
        return self.verdict_ok and bool(self.feedback) and self.cause in self.feedback[-1]


def _worksheet(problem: str, steps: list[dict], motion: str = "") -> str:
    out = [f"problem = {json.dumps(problem)}"] + ([f"motion = {json.dumps(motion)}"] if motion else [])
    for s in steps:
        out.append("[[step]]")
        out += [f"{k} = {json.dumps(v, ensure_ascii=False)}" for k, v in s.items() if k not in _OWN]
    return "\n".join(out) + "\n"


def run(path: Path = CASES) -> list[Graded]:
    """Every step of every case graded (each alone, the right ones together, a ``together`` case as one)."""
    sys.path.insert(0, str(ROOT / "src"))
    from rigidkin.grading import grade, parse_worksheet

    data = tomllib.loads(path.read_text(encoding="utf-8"))
    out = []
    for case in data["case"]:
        steps = case["step"]
        if case.get("together"):
            groups = [steps]
        else:
            groups = [[s for s in steps if s["expect"] == "correct"]] + [[s] for s in steps if s["expect"] != "correct"]
        for group in groups:
            if not group:
                continue
            ws = parse_worksheet(_worksheet(case["problem"], group, case.get("motion", "")), ROOT / "worksheet.toml")
            rep = grade(ws)
            for s, res in zip(group, rep.steps):
                out.append(Graded(case["title"], case["problem"], s, s["expect"], s.get("cause", ""), res.verdict,
                                  list(res.feedback)))
    return out


def table(rows: list[Graded]) -> str:
    by = {}
    for r in rows:
        by.setdefault(Path(r.problem).stem, []).append(r)
    lines = [f"{'problem':22s} {'steps':>5s} {'wrong verdicts':>14s} {'causes right':>12s} {'cause accuracy':>14s}"]
    for name, rs in by.items():
        bad = [r for r in rs if r.expect != "correct"]
        right = sum(r.cause_ok for r in bad)
        acc = f"{right / len(bad):.0%}" if bad else "–"
        lines.append(f"{name:22s} {len(rs):5d} {sum(not r.verdict_ok for r in rs):14d} "
                     f"{right:5d} of {len(bad):<4d} {acc:>12s}")
    bad = [r for r in rows if r.expect != "correct"]
    right = sum(r.cause_ok for r in bad)
    lines.append(f"{'all':22s} {len(rows):5d} {sum(not r.verdict_ok for r in rows):14d} "
                 f"{right:5d} of {len(bad):<4d} {right / max(1, len(bad)):>12.1%}")
    return "\n".join(lines)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    rows = run()
    print(table(rows))
    if "--show" in argv:
        for r in rows:
            if not r.cause_ok:
                print(f"\n[{r.case}] {r.step.get('claim')}\n  expected {r.expect}: {r.cause!r}\n  got {r.verdict}: "
                      f"{r.feedback}")
    return 0 if all(r.verdict_ok for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
