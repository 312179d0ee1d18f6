"""``rigidkin list``: the bundled examples, one line each."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("list", help="list the bundled examples")
    p.set_defaults(func=run)


def run(args) -> int:
    from .. import examples
    from ..errors import RigidkinError
    from ..textsafe import terminal_safe
    from .common import load_system

    for name in examples.names():
        form = "toml" if (examples.HERE / f"{name}.toml").exists() else "py"
        try:
            system, _ = load_system(name)
            title = system.title
        except RigidkinError as exc:
            title = f"(cannot be loaded: {exc})"
        print(terminal_safe(f"{name:22s} {form:5s} {title}", newlines=False))
    return 0
