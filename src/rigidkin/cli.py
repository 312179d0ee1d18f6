# PYTHON_ARGCOMPLETE_OK
"""The ``rigidkin`` command line.

Each subcommand lives in its own module ``rigidkin.commands.<name>`` with a ``register(subparsers)``
function; this module only assembles them.  Every stop has an exit status that says what happened
(:mod:`rigidkin.commands.options`): 0 success, 1 a question unanswered or laws that disagree, 2 bad
input (one paragraph, never a traceback; ``--debug`` shows it), 3 a simulation stopped early because
the model cannot go on, 4 the time limit, 130 interrupted.  Everything printed to the terminal that
came from a file or the command line has its control characters escaped.  ``--ascii`` (before or after
the subcommand, or ``RIGIDKIN_ASCII=1``) prints everything in plain ASCII (rates as primes: ``theta''``), for
terminal fonts that put a combining dot on the next letter; ``--version`` prints the installed version.

Shell completion (argcomplete): ``eval "$(register-python-argcomplete rigidkin)"`` in ``~/.bashrc``
or ``~/.zshrc`` completes subcommands, options, choices and the PROBLEM argument (bundled example
names and ``.toml`` files).  Nothing heavy is imported to parse the line: each subcommand module
imports what it uses when it runs.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import sys
import warnings

from . import examples
from .base import cache_folder
from .base.errors import RigidkinError
from .base.plaintext import AsciiStream
from .base.textsafe import terminal_safe
from .commands.deadline import TimeLimitReached, deadline
from .commands.options import EXIT_INPUT, EXIT_INTERRUPTED, EXIT_OK, EXIT_TIME, Parser

COMMANDS = ("solve", "list", "validate", "check", "simulate", "sweep", "report", "draw", "grade", "variants")


def build_parser() -> argparse.ArgumentParser:
    p = Parser(prog="rigidkin", description="Rigid-body kinetics derived step by step.",
               epilog="Exit status: 0 success, 1 a question unanswered (solve) or laws that disagree (check), "
                      "2 bad input or an output that cannot be written, 3 a simulation stopped early (the model "
                      "cannot go on), 4 the time limit (--timeout) reached, 130 interrupted.")
    p.add_argument("--debug", action="store_true", help="show Python tracebacks")
    p.add_argument("--version", action=_Version, help="print rigidkin's version (and Python's) and exit")
    sub = p.add_subparsers(dest="command", required=True)
    for name in COMMANDS:
        try:
            module = importlib.import_module(f"rigidkin.commands.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"rigidkin.commands.{name}":
                continue
            raise
        module.register(sub)
    for parser in (p, *sub.choices.values()):      # before or after the subcommand
        parser.add_argument("--ascii", action="store_true", default=argparse.SUPPRESS,
                            help="print in plain ASCII, readable in any monospace font: rates as primes "
                                 "(theta', theta''), Greek letters spelled, x^2, a*b (also RIGIDKIN_ASCII=1)")
    for parser in sub.choices.values():
        for action in parser._actions:
            if action.dest == "problem":
                action.completer = complete_problem
    return p


def version() -> str:
    """rigidkin's version as installed (package metadata; no heavy import)."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("rigidkin")
    except PackageNotFoundError:        # run from a source tree that was never installed
        return "0+unknown (not installed: pip install -e .)"


class _Version(argparse.Action):
    """``--version``: the installed version, read only when asked for."""

    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        v = sys.version_info
        print(f"rigidkin {version()} (Python {v.major}.{v.minor}.{v.micro})")
        parser.exit()


def complete_problem(prefix: str = "", **_) -> list[str]:
    """Shell completion of a PROBLEM: the bundled examples' names and the ``.toml`` files (and folders)
    that start with ``prefix``."""

    found = [n for n in examples.names() if n.startswith(prefix)]
    folder, _, stem = prefix.rpartition("/")
    try:
        entries = sorted(os.scandir(folder or "."), key=lambda e: e.name)
    except OSError:
        entries = []
    for e in entries:
        if not e.name.startswith(stem) or (e.name.startswith(".") and not stem.startswith(".")):
            continue
        path = f"{folder}/{e.name}" if folder else e.name
        if e.is_dir():
            found.append(path + "/")
        elif e.name.endswith(".toml"):
            found.append(path)
    return found


def _complete(parser) -> None:
    """Answer a shell's completion request (argcomplete sets ``_ARGCOMPLETE``) and exit; else nothing."""
    if "_ARGCOMPLETE" not in os.environ:
        return
    try:
        import argcomplete
    except ImportError:                 # completion asked for but argcomplete not installed: complete nothing
        sys.exit(0)
    argcomplete.autocomplete(parser)


def say(text: str) -> None:
    """One paragraph on stderr, prefixed ``rigidkin:``, control characters escaped."""
    print(f"rigidkin: {terminal_safe(text)}", file=sys.stderr)


def main(argv: list[str] | None = None) -> int:
    """Run a command; ``argv`` None reads the program's arguments and arms the hard stop of ``--timeout``."""
    parser = build_parser()
    _complete(parser)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:            # a refused option (status 2, said on stderr) or --help (0)
        return exc.code if isinstance(exc.code, int) else EXIT_INPUT
    with _ascii(getattr(args, "ascii", False) or os.environ.get("RIGIDKIN_ASCII", "") not in ("", "0")):
        return _run(args, argv)


def _run(args, argv) -> int:
    try:
        with deadline(getattr(args, "timeout", None), hard_stop=argv is None), _safe_warnings(), \
                cache_folder.one_command(_warning_line):
            return int(args.func(args) or EXIT_OK)
    except RigidkinError as exc:
        if args.debug:
            raise
        say(str(exc))
        return EXIT_INPUT
    except TimeLimitReached as exc:
        _flush()
        say(str(exc))
        return EXIT_TIME
    except BrokenPipeError:
        return EXIT_OK
    except KeyboardInterrupt:
        say("interrupted")
        return EXIT_INTERRUPTED
    except (MemoryError, RecursionError) as exc:
        if args.debug:
            raise
        say(f"the problem is too large to handle ({type(exc).__name__}). Simplify the model or its expressions, "
            "or ask for fewer samples or runs.")
        return EXIT_INPUT
    except Exception as exc:
        if args.debug:
            raise
        say(f"internal error: {type(exc).__name__}: {exc} This is a bug in rigidkin: run again with --debug for "
            "the traceback and report it with the problem file.")
        return EXIT_INPUT


@contextlib.contextmanager
def _ascii(on: bool):
    """Under ``--ascii`` everything printed (results, messages) is written in plain ASCII."""
    if not on:
        yield
        return
    out, err = sys.stdout, sys.stderr
    sys.stdout, sys.stderr = AsciiStream(out), AsciiStream(err)
    try:
        yield
    finally:
        sys.stdout, sys.stderr = out, err


@contextlib.contextmanager
def _safe_warnings():
    """Warnings (ours and the libraries') shown as ``rigidkin: warning: ...`` with control characters escaped
    (a glyph warning of matplotlib names the character of a title it cannot draw)."""
    original = warnings.showwarning

    def show(message, category, filename, lineno, file=None, line=None):
        _warning_line(message, file)

    warnings.showwarning = show
    try:
        yield
    finally:
        warnings.showwarning = original


def _warning_line(message, file=None) -> None:
    """``rigidkin: warning: ...`` on stderr, one line, control characters escaped."""
    with contextlib.suppress(OSError, ValueError):
        (file or sys.stderr).write(f"rigidkin: warning: {terminal_safe(str(message), newlines=False)}\n")


def _flush() -> None:
    with contextlib.suppress(OSError, ValueError):
        sys.stdout.flush()


if __name__ == "__main__":
    sys.exit(main())
