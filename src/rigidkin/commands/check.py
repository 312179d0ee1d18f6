"""``rigidkin check PROBLEM``: derive the equations of motion by every law that applies and compare them.

Prints a table law × equation (agrees / disagrees / does not apply, and how it was decided), the
dimensional check of every derived equation, and for each ``--expect "lhs = rhs"`` whether it is
equivalent to the derived equation of motion (and if not, which terms differ and whether it is
dimensionally consistent).  Exit status 0 when everything agrees, 1 otherwise (2: an error).
"""

from __future__ import annotations

import dataclasses
import json

from ..base.errors import RigidkinError
from ..base.textsafe import terminal_safe
from ..derive.laws import parse_method
from .common import guarded, json_safe, open_problem, progress, with_file
from .options import add_no_cache, add_timeout, parse_modes


def register(sub) -> None:

    p = sub.add_parser("check", help="cross-check the equations of motion by every law, and their dimensions")
    p.add_argument("problem", help="a problem file (.toml) or a bundled example name (see 'rigidkin list')")
    p.add_argument("--expect", action="append", default=[], metavar="EQUATION",
                   help='an equation of motion to compare, in the file syntax: "lhs = rhs" or an expression '
                        'meaning = 0, e.g. "3/2*m*r**2*ddot(theta) + K*r**2*theta = m*g*r*sin(beta)" (repeatable)')
    p.add_argument("--method", default="newton-euler", help="the reference law (default: newton-euler)")
    p.add_argument("--laws", default=None, metavar="LIST",
                   help="comma-separated laws to compare (default: every law that may apply)")
    p.add_argument("--mode", nargs="+", action="extend", default=[], metavar="CONTACT=STATE",
                   help="the state of a contact: open, slip or stick (repeatable)")
    p.add_argument("--no-dimensions", action="store_true", help="skip the dimensional analysis")
    p.add_argument("--format", default="text", choices=("text", "json"), help="output format")
    add_no_cache(p)
    add_timeout(p)
    p.set_defaults(func=run)


def parse_expectation(text: str, system):
    """The user's equation as an ``sp.Eq`` (or an expression meaning = 0), read by the safe parser."""
    from ..io.expressions import parse_equation, parse_scalar
    from ..io.problem import system_scope

    scope = system_scope(system)
    bare = text.replace("<=", "").replace(">=", "").replace("==", "")
    if "=" in bare:
        return parse_equation(text, scope, where="--expect")
    return parse_scalar(text, scope, where="--expect")


def run(args) -> int:
    from ..base.printing import text

    with progress(f"Reading {args.problem}"):
        derived = guarded(args, open_problem, args)
    system, spec = derived.system, derived.spec
    expected = [(e, parse_expectation(e, system)) for e in args.expect]
    laws = None if args.laws is None else [w.strip() for w in args.laws.split(",") if w.strip()]
    if laws is not None:
        for w in laws:
            parse_method(w)
    from ..derive.laws.crosscheck import cross_check, expectation

    try:
        with progress("Deriving by every law"):
            sol = guarded(args, system.solve, method=args.method, mode=parse_modes(args.mode))
            report = guarded(args, cross_check, sol, laws=laws, dimensions=not args.no_dimensions)
            exps = tuple(guarded(args, expectation, sol, eq, label=src) for src, eq in expected)
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    report = dataclasses.replace(report, expectations=exps)
    try:
        with progress("Writing the comparison"):
            out = json_safe(json.dumps(_json(report, text), indent=2)) if args.format == "json" else \
                terminal_safe(guarded(args, str, report))
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    print(out)
    derived.save()
    return 0 if report.ok else 1


def _json(report, text) -> dict:
    return {
        "system": report.system,
        "reference": report.reference,
        "ok": report.ok,
        "verdicts": [{"law": v.law, "equation": v.equation, "result": v.status, "how": v.how,
                      "law_expression": None if v.ours is None else str(v.ours),
                      "reference_expression": None if v.reference is None else str(v.reference)}
                     for v in report.verdicts],
        "dimensions": [{"equation": d.label, "consistent": d.consistent,
                        "dimension": None if d.dimension is None else str(d.dimension),
                        "offending": [{"term": str(term), "dimension": None if dim is None else str(dim),
                                       "why": why} for term, dim, why in d.offending]}
                       for d in report.dimensions],
        "expected": [{"equation": e.text, "equivalent": e.equivalent, "how": e.how,
                      "derived": None if e.derived is None else str(e.derived),
                      "differences": [{"given": None if a is None else str(a), "derived": None if b is None else str(b)}
                                      for a, b in e.differences],
                      "dimensionally_consistent": None if e.dimensions is None else e.dimensions.consistent,
                      "dimension_report": None if e.dimensions is None else str(e.dimensions)}
                     for e in report.expectations],
    }
