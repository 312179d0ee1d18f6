"""``rigidkin variants PROBLEM --count N --seed S [--vary NAME=LOW:HIGH ...]``: a problem set.

Each variant has new parameter values (three significant figures, reproducible from the seed) and an
answer key (numbers with tolerances) from solving the variant itself, checked against the problem's
exact answer where there is one.  ``-o set.xml`` writes Moodle XML (numerical questions),
``--prairielearn DIR`` a PrairieLearn question folder per variant;
``--format json`` prints the key as data.  Every question of the problem is kept: one that gives no
number (a function of the state with no start to evaluate it at) is named with why, and the exit status
is then 1 (0: every question has its keys; 2: bad input).
"""

from __future__ import annotations

import json

from ..base.errors import InputError, RigidkinError
from ..base.outfile import check_outputs, check_target, writing
from ..base.textsafe import terminal_safe
from ..base.units import parse_quantity
from .common import guarded, json_safe, problem_inputs, progress, source_of
from .options import add_timeout


def register(sub) -> None:

    p = sub.add_parser("variants", help="make a problem set: variants with changed values and checked answer keys")
    p.add_argument("problem", help="a problem file (.toml) or a bundled example name")
    p.add_argument("--count", type=int, default=5, help="how many variants (default 5, at most 200)")
    p.add_argument("--seed", type=int, default=1, help="the seed of the values drawn (default 1)")
    p.add_argument("--vary", nargs="+", action="extend", default=[], metavar="NAME=LOW:HIGH",
                   help="the range of a parameter, in its declared unit or with a unit (repeatable; default: every "
                        "parameter with a value except accelerations such as g, within ±20%%)")
    p.add_argument("--tolerance", type=float, default=0.01, help="relative tolerance of the keys (default 0.01)")
    p.add_argument("--format", default="text", choices=("text", "json", "moodle"), help="what to print")
    p.add_argument("-o", "--output", default=None, metavar="FILE.xml", help="write the Moodle XML to FILE.xml")
    p.add_argument("--prairielearn", default=None, metavar="FOLDER",
                   help="write PrairieLearn questions into FOLDER (a question folder per variant)")
    add_timeout(p)
    p.set_defaults(func=run)


def _declared_units(args) -> dict:
    """The units the problem file declares for its parameters ({} for a bundled example built in Python)."""
    import tomllib

    try:
        source = source_of(args)
        data = tomllib.loads(source.data.decode("utf-8")) if source.path is not None else {}
    except (RigidkinError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return {}                                # said when the problem is loaded
    params = data.get("parameters") if isinstance(data, dict) else None
    return {k: v["unit"] for k, v in params.items() if isinstance(v, dict) and isinstance(v.get("unit"), str)} \
        if isinstance(params, dict) else {}


def _check_vary(args, vary: dict) -> None:
    """Each ``--vary`` bound finite and, with a unit, of the parameter's declared dimension (``m=1 s:2 s``
    for a mass is refused)."""
    units = _declared_units(args) if vary else {}
    for name, bounds in vary.items():
        for text in bounds:
            parse_quantity(text, units.get(name), f"--vary {name}")


def run(args) -> int:
    import math

    from ..grading.exports import as_moodle, as_prairielearn
    from ..grading.variants import as_data, as_text, left_out, make_set, parse_vary

    if not (math.isfinite(args.tolerance) and 0 < args.tolerance < 1):
        raise InputError("--tolerance is a relative tolerance between 0 and 1.", where="--tolerance")
    if args.output:
        check_target(args.output, "the Moodle XML", (".xml",))
        check_outputs({"-o": args.output}, problem_inputs(args))
    vary = parse_vary(args.vary)
    _check_vary(args, vary)
    with progress(f"Solving {args.count} variants of {args.problem}"):
        ps = guarded(args, make_set, args.problem, args.count, args.seed, vary, args.tolerance)
    if args.output:
        with writing(args.output, "the Moodle XML", suffixes=(".xml",)) as fh:
            fh.write(as_moodle(ps))
    if args.prairielearn:
        as_prairielearn(ps, args.prairielearn)
    if args.format == "json":
        print(json_safe(json.dumps(as_data(ps), indent=2, ensure_ascii=False)))
    elif args.format == "moodle":
        print(as_moodle(ps), end="")
    else:
        print(terminal_safe(as_text(ps)))
    return 1 if left_out(ps) else 0
