"""Grading a claim whose expansion would be huge: CPU seconds, against grading a plain correct step.

The claim ``N_A*(m + l + g + θ + θ̇ + sin θ + cos θ)^12 = θ̈`` about the ladder expands to thousands of terms;
the grader compares it without expanding it.  (This was a timed unit test, ``< 60 s``; a time is measured
here, not asserted: tests/test_grading.py keeps the verdict.)  Median of ``--repeat`` runs (default 3),
CPU seconds of this process (``time.process_time``).

    python benchmarks/grading.py [--repeat N]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from rigidkin.grading import grade, parse_worksheet

HUGE = "N_A*(m + l + g + theta + dot(theta) + sin(theta) + cos(theta))**12 = ddot(theta)"
PLAIN = "2*l*ddot(theta) = 3*g*sin(theta)"


def worksheet(claim: str) -> str:
    return f'problem = "ladder"\n[[step]]\nkind = "balance"\nclaim = {json.dumps(claim)}\n'


def seconds(claim: str, repeat: int) -> tuple[float, str]:
    times, verdict = [], ""
    for _ in range(repeat):
        t0 = time.process_time()
        verdict = grade(parse_worksheet(worksheet(claim), "worksheet.toml")).steps[0].verdict
        times.append(time.process_time() - t0)
    return statistics.median(times), verdict


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    grade(parse_worksheet(worksheet(PLAIN), "worksheet.toml"))          # imports and the ladder's derivation
    print("| claim | verdict | CPU s (median) |\n| --- | --- | --- |")
    for name, claim in (("plain balance", PLAIN), ("power 12", HUGE)):
        s, verdict = seconds(claim, args.repeat)
        print(f"| {name} | {verdict} | {s:.2f} |")


if __name__ == "__main__":
    main()
