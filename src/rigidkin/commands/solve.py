"""``rigidkin solve PROBLEM``: equations of motion, reactions and answers."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("solve", help="derive the equations of motion and reactions")
    p.add_argument("problem", help="a problem file or a bundled example name")
    p.add_argument("--method", default="newton-euler")
    p.set_defaults(func=run)


def run(args) -> int:
    from .common import load_system

    system, _ = load_system(args.problem)
    print(system.solve(method=args.method))
    return 0
