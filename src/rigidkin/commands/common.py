"""What the subcommands share: opening a problem (loaded by :mod:`rigidkin.io.load`, or read from the
derivation cache), a progress line for slow steps, a time limit, and turning unexpected failures into one
paragraph.
"""

from __future__ import annotations

import threading
from contextlib import contextmanager

from ..base.errors import RigidkinError
from ..base.textsafe import terminal_safe
from ..base.timelimit import time_limit as limit
from ..io.derivation_cache import CachedProblem
from ..io.load import load_system, read_source
from .deadline import set_step


def source_of(args):
    """The problem file of ``args.problem`` read once for the whole command (:class:`rigidkin.io.load.Source`):
    what is parsed, what the caches' keys are made of."""
    source = getattr(args, "_source", None)
    if source is None:
        source = read_source(args.problem)
        args._source = source
    return source


def open_problem(args):
    """The problem of ``args.problem`` as a :class:`rigidkin.io.derivation_cache.CachedProblem`: read from the
    derivation cache when it was derived before (unless ``--no-cache``), else built from the bytes read."""
    source = source_of(args)
    return CachedProblem(source, lambda: load_system(source), use=not getattr(args, "no_cache", False))


def problem_inputs(args) -> list:
    """The files a command on ``args.problem`` reads (to refuse an output over one of them)."""
    try:
        source = source_of(args)
    except RigidkinError:
        return []
    return [source.path] if source.path is not None else []


@contextmanager
def progress(message: str, delay: float = 1.0):
    """Show a rich status line on a terminal's stderr when the step takes longer than ``delay`` seconds."""
    import sys


    set_step(message)
    if not _is_terminal(sys.stderr):            # rich (slow to import) only where something is shown
        yield
        return
    from rich.console import Console

    console = Console(stderr=True)
    if not console.is_terminal:
        yield
        return
    status = console.status(message)
    lock, state = threading.Lock(), {"done": False, "started": False}

    def start():
        with lock:
            if not state["done"]:
                status.start()
                state["started"] = True

    timer = threading.Timer(delay, start)
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
        with lock:
            state["done"] = True
            if state["started"]:
                status.stop()


def _is_terminal(stream) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError, OSError):
        return False


class TimeLimit(RigidkinError):
    """A step ran past a time limit of its own (the whole command's ``--timeout`` is
    :class:`rigidkin.commands.deadline.TimeLimitReached`)."""


def time_limit(seconds: float | None, what: str):
    """Stop ``what`` with a clear error after ``seconds`` (main thread, POSIX; otherwise no limit)."""

    def error():
        return TimeLimit(f"{what} took longer than {seconds:g} s and was stopped.",
                         hint="Simplify the model, or allow more time with --timeout SECONDS (0: no limit).")

    return limit(seconds, error)


def json_safe(text: str) -> str:
    """JSON text for a terminal: control characters inside its strings written as ``\\uXXXX`` escapes."""
    import json


    if terminal_safe(text) == text:
        return text
    return "".join(ch if terminal_safe(ch) == ch else json.dumps(ch)[1:-1] for ch in text)


def guarded(args, fn, *a, **kw):
    """Run ``fn``; an unexpected exception becomes one paragraph (the traceback only with --debug)."""
    try:
        return fn(*a, **kw)
    except (RigidkinError, KeyboardInterrupt, BrokenPipeError):
        raise
    except (RecursionError, MemoryError) as exc:
        if getattr(args, "debug", False):
            raise
        raise RigidkinError(f"the problem is too large to handle ({type(exc).__name__}).",
                            hint="Simplify the model or its expressions.") from None
    except Exception as exc:
        if getattr(args, "debug", False):
            raise
        raise RigidkinError(f"internal error: {type(exc).__name__}: {exc}",
                            hint="This is a bug in rigidkin: run again with --debug for the traceback and report "
                                 "it with the problem file.") from None


def with_file(exc: RigidkinError, spec) -> RigidkinError:
    """Say which problem file an error of the model (found while solving) comes from."""
    if spec is not None and str(spec.path) not in (exc.where or ""):
        exc.where = f"{spec.path}" + (f", {exc.where}" if exc.where else "")
    return exc
