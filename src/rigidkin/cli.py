"""The ``rigidkin`` command line.

Each subcommand lives in its own module ``rigidkin.commands.<name>`` with a ``register(subparsers)``
function; this module only assembles them.  Errors are printed as one paragraph and exit with
status 2; ``--debug`` shows the traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from .errors import RigidkinError

COMMANDS = ("solve", "list", "validate", "check", "simulate", "sweep", "report", "grade", "variants")


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rigidkin", description="Rigid-body kinetics derived step by step.")
    p.add_argument("--debug", action="store_true", help="show Python tracebacks")
    sub = p.add_subparsers(dest="command", required=True)
    for name in COMMANDS:
        try:
            module = importlib.import_module(f"rigidkin.commands.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"rigidkin.commands.{name}":
                continue
            raise
        module.register(sub)
    return p


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except RigidkinError as exc:
        if args.debug:
            raise
        print(f"rigidkin: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        return 0
    except KeyboardInterrupt:
        print("rigidkin: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
