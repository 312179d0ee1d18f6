"""The time limit of a whole command (``--timeout``): every step, printing included, ends by it.

Three layers, each catching what the one before cannot:

1. A SIGALRM timer (:func:`rigidkin.base.timelimit.time_limit`, so that the shorter limits of single steps
   nest inside it) raises :class:`TimeLimitReached` in the main thread.  It is a BaseException, so
   no ``except Exception`` in a library (sympy, a fallback) can swallow it; the command line prints
   one paragraph and exits with status 4.
2. When the command runs as a program (``hard_stop``), a watchdog thread stops the process with
   the same paragraph and status a second after the limit, should the exception have been caught
   or the main thread be waiting in code that ignores signals.
3. A watchdog process kills the program (SIGKILL) three seconds after the limit, for a computation
   stuck inside one long call of compiled code that never lets other threads run.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time

from ..base.timelimit import time_limit
from .options import EXIT_TIME

#: Seconds after the limit before the watchdog thread, and then the watchdog process, stop the program.
GRACE_THREAD, GRACE_PROCESS = 1.0, 3.0

#: What the command is doing now (set by :func:`rigidkin.commands.common.progress`), for the message.
_STEP = {"now": ""}


class TimeLimitReached(BaseException):
    """The command ran past its ``--timeout`` (a BaseException: libraries must not swallow it)."""

    def __init__(self, seconds: float, step: str = ""):
        self.seconds = seconds
        self.step = step
        super().__init__(message(seconds, step))


def message(seconds: float, step: str = "") -> str:
    """The paragraph printed when the limit is reached."""
    where = f" while {step[:1].lower() + step[1:]}" if step else ""
    return (f"time limit reached: the command took longer than {seconds:g} s (--timeout {seconds:g}) and was "
            f"stopped{where}. Allow more time with --timeout SECONDS (0: no limit), or simplify the model.")


def set_step(text: str) -> None:
    """Record what the command is doing (named in the message if the limit is reached)."""
    _STEP["now"] = text


@contextlib.contextmanager
def deadline(seconds: float | None, hard_stop: bool = False):
    """Bound the block by ``seconds`` (None or 0: no limit); see the module docstring for the layers."""
    if not seconds or seconds <= 0:
        yield
        return

    set_step("")
    done = threading.Event()
    child = _watchdog_process(seconds + GRACE_PROCESS) if hard_stop else None

    def watchdog():
        if not done.wait(seconds + GRACE_THREAD):
            text = f"rigidkin: {message(seconds, _STEP['now'])}\n"     # no flush: the main thread may hold stdout
            with contextlib.suppress(OSError):
                os.write(2, text.encode("utf-8", "replace"))
            _end(child)
            os._exit(EXIT_TIME)

    if hard_stop:
        threading.Thread(target=watchdog, name="rigidkin-deadline", daemon=True).start()
    try:
        with time_limit(seconds, lambda: TimeLimitReached(seconds, _STEP["now"])):
            yield
    finally:
        done.set()
        _end(child)


def _watchdog_process(after: float) -> int | None:
    """A child process that kills this one (SIGKILL) ``after`` seconds from now, unless it ends first."""
    if not hasattr(os, "fork"):
        return None
    parent = os.getpid()
    try:
        pid = os.fork()
    except OSError:
        return None
    if pid:
        return pid
    try:                                   # the child: only os calls, never back into the caller's code
        end = time.monotonic() + after
        while time.monotonic() < end:
            time.sleep(0.1)
            if os.getppid() != parent:
                os._exit(0)
        os.write(2, f"rigidkin: {message(after - GRACE_PROCESS)} (killed)\n".encode())
        os.kill(parent, signal.SIGKILL)
    finally:
        os._exit(0)


def _end(child: int | None) -> None:
    if child:
        with contextlib.suppress(OSError):
            os.kill(child, signal.SIGKILL)
        with contextlib.suppress(OSError):
            os.waitpid(child, 0)
