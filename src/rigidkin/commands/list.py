"""``rigidkin list``: the bundled examples, one line each."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("list", help="list the bundled examples")
    p.set_defaults(func=run)


def run(args) -> int:
    from .. import examples
    from .common import load_system

    for name in examples.names():
        system, _ = load_system(name)
        print(f"{name:22s} {system.title}")
    return 0
