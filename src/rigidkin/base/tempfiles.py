"""Temporary files removed however the process ends: normally, on an error, on Ctrl-C, SIGTERM or SIGHUP.

Every temporary file rigidkin writes beside an output or in its cache (``.rigidkin-XXXX.part``,
``.tmp-XXXX``), and every temporary folder (a compiler's build folder, the private folder of compiled
libraries, pint's staged definitions), is registered here while it exists.  An error or Ctrl-C
(KeyboardInterrupt) removes it through the writer's ``finally``; SIGTERM and SIGHUP, whose default
action ends the process at once, get a handler that removes everything registered and then ends the
process by the same signal (so the exit status is the signal's, as before).  A handler the program
installed itself is called after the cleanup; an ignored signal stays ignored.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import threading

_LIVE: set[str] = set()
_LOCK = threading.Lock()
_PREVIOUS: dict[int, object] = {}
SIGNALS = tuple(getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n))


def register(path) -> None:
    """``path`` is a temporary file (or folder) of ours: removed if a signal ends the process before
    :func:`release`."""
    path = str(path)
    with _LOCK:
        _LIVE.add(path)
    install()


def release(path) -> None:
    """``path`` was renamed into place or removed: nothing to clean up any more."""
    path = str(path)
    with _LOCK:
        _LIVE.discard(path)


def live() -> frozenset[str]:
    """The temporary files registered now."""
    with _LOCK:
        return frozenset(_LIVE)


def remove_all() -> None:
    """Remove every registered temporary file (what the signal handlers do)."""
    with _LOCK:
        paths = list(_LIVE)
        _LIVE.clear()
    for p in paths:
        if os.path.isdir(p) and not os.path.islink(p):
            shutil.rmtree(p, ignore_errors=True)
            continue
        with contextlib.suppress(OSError):
            os.unlink(p)


def install() -> None:
    """Install the SIGTERM and SIGHUP handlers (main thread only; an ignored signal is left ignored)."""
    if threading.current_thread() is not threading.main_thread():
        return
    for sig in SIGNALS:
        if sig in _PREVIOUS:
            continue
        try:
            previous = signal.getsignal(sig)
            if previous == signal.SIG_IGN:
                continue
            signal.signal(sig, _handler)
        except (ValueError, OSError):          # not the main interpreter, or a platform without it
            continue
        _PREVIOUS[sig] = previous


def _handler(signum, frame) -> None:
    remove_all()
    previous = _PREVIOUS.get(signum)
    if callable(previous) and previous is not _handler:
        previous(signum, frame)
        return
    signal.signal(signum, signal.SIG_DFL)       # end the process by the signal itself, as without us
    os.kill(os.getpid(), signum)
