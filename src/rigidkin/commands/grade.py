"""``rigidkin grade WORKSHEET``: grade a student's derivation step by step.

Prints, for each step of the worksheet, the verdict (correct, incorrect, unreadable) and the cause of
each mistake; ``--format json`` gives ``{"problem", "steps": [{"index", "kind", "verdict", "feedback"}],
"score"}``, ``--format html`` one self-contained page (``-o`` to write it to a file).  Exit status 0 when
every step is correct, 1 otherwise, 2 bad input (the worksheet or the problem it names).
``--template PROBLEM`` prints a blank worksheet: the method's steps and, for each question, what it asks
in words and symbol with its SI unit.
"""

from __future__ import annotations

import json

from ..base.errors import InputError
from ..base.outfile import check_outputs, check_target, writing
from .common import guarded, json_safe, progress
from .options import add_timeout


def register(sub) -> None:

    p = sub.add_parser("grade", help="grade a hand derivation (a worksheet) step by step")
    p.add_argument("worksheet", nargs="?", help="a worksheet file (.toml): problem = NAME or FILE and [[step]] tables")
    p.add_argument("--template", default=None, metavar="PROBLEM",
                   help="print a blank worksheet for PROBLEM: the method's steps and what each question asks")
    p.add_argument("--format", default="text", choices=("text", "json", "html"), help="output format")
    p.add_argument("-o", "--output", default=None, metavar="FILE", help="write the report to FILE instead of stdout")
    add_timeout(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from ..grading.report import as_data, as_html, as_text
    from ..grading.steps import grade
    from ..grading.worksheet import load_worksheet

    if args.template:
        from ..grading.template import template

        with progress(f"Deriving {args.template}"):
            out = guarded(args, template, args.template)
        print(out)
        return 0
    if not args.worksheet:
        raise InputError("give a worksheet to grade, or --template PROBLEM for a blank one.", where="grade",
                         hint="rigidkin grade WORKSHEET.toml | rigidkin grade --template ladder")
    if args.output:
        check_target(args.output, "the graded worksheet")
        check_outputs({"-o": args.output}, [args.worksheet])
    with progress(f"Reading {args.worksheet}"):
        ws = guarded(args, load_worksheet, args.worksheet)
    if args.output:                                     # nor over the problem file the worksheet names
        check_outputs({"-o": args.output}, [args.worksheet, ws.problem_ref])
    with progress("Deriving the problem and grading each step"):
        report = guarded(args, grade, ws)
    if args.format == "json":
        out = json_safe(json.dumps(as_data(report), indent=2, ensure_ascii=False))
    elif args.format == "html":
        out = as_html(report)
    else:
        out = as_text(report)
    if args.output:
        with writing(args.output, "the graded worksheet") as fh:
            fh.write(out if out.endswith("\n") else out + "\n")
    else:
        print(out)
    return 0 if report.ok else 1
