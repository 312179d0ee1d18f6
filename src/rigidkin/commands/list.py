"""``rigidkin list``: the bundled examples, one line each (and a note where a file or folder here shares a name)."""

from __future__ import annotations

from .. import examples
from ..base.textsafe import terminal_safe
from ..io.locate import clashes


def register(sub) -> None:
    p = sub.add_parser("list", help="list the bundled examples")
    p.set_defaults(func=run)


def run(args) -> int:
    """One line per example: its name, its form and its title (read from the file: nothing is built)."""
    import tomllib

    clash = clashes(examples.names())
    for name in examples.names():
        form = "toml" if (examples.HERE / f"{name}.toml").exists() else "py"
        try:
            title = examples.title(name)
        except (OSError, SyntaxError, tomllib.TOMLDecodeError) as exc:
            title = f"(cannot be read: {exc})"
        print(terminal_safe(f"{name:22s} {form:5s} {title}", newlines=False))
        if name in clash:
            print(terminal_safe(f"{'':22s} note: {clash[name]}", newlines=False))
    return 0
