"""The ``rigidkin`` command line: solve, list (more commands arrive with the problem-file format).

Errors are printed as one paragraph and exit with status 2; ``--debug`` shows the traceback.
"""

from __future__ import annotations

import argparse
import sys

from .errors import RigidkinError


def _cmd_list(args) -> int:
    from . import examples

    for name in examples.names():
        try:
            s = examples.build(name)
            print(f"{name:22s} {s.title}")
        except (ImportError, AttributeError):
            print(f"{name:22s} (problem file)")
    return 0


def _cmd_solve(args) -> int:
    from . import examples

    if args.problem not in examples.names():
        raise RigidkinError(f"'{args.problem}' is not a bundled example.", where="rigidkin solve",
                            hint=f"Known examples: {', '.join(examples.names())}.")
    system = examples.build(args.problem)
    print(system.solve(method=args.method))
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rigidkin", description="Rigid-body kinetics derived step by step.")
    p.add_argument("--debug", action="store_true", help="show Python tracebacks")
    sub = p.add_subparsers(dest="command", required=True)
    sp_list = sub.add_parser("list", help="list the bundled examples")
    sp_list.set_defaults(func=_cmd_list)
    sp_solve = sub.add_parser("solve", help="derive the equations of motion and reactions")
    sp_solve.add_argument("problem", help="a bundled example name")
    sp_solve.add_argument("--method", default="newton-euler")
    sp_solve.set_defaults(func=_cmd_solve)
    return p


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except RigidkinError as exc:
        if args.debug:
            raise
        print(f"rigidkin: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
