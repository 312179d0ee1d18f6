"""A time limit on a block of code: a SIGALRM timer that raises, nesting with outer limits.

Kept apart from :mod:`rigidkin.base.algebra` (which loads sympy) so that the command line arms its
``--timeout`` without importing anything heavy.
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time


@contextlib.contextmanager
def time_limit(seconds: float | None, on_timeout=None):
    """Raise ``on_timeout()`` (default TimeoutError) if the block runs longer than ``seconds``.

    Main thread and POSIX only (elsewhere no limit).  Limits nest: an outer limit that comes first is
    left to fire, and an outer timer is restored, less the time spent, when the inner block ends.
    sympy's ``solve`` can run for minutes on an equation it cannot solve; callers fall back to a
    numerical method when the limit is hit; the command line stops a step with a clear error.
    """
    if (not seconds or seconds <= 0 or not hasattr(signal, "setitimer")
            or threading.current_thread() is not threading.main_thread()):
        yield
        return
    outer, _ = signal.getitimer(signal.ITIMER_REAL)
    if outer and outer <= seconds:
        yield
        return

    def handler(signum, frame):
        # again in 0.1 s, should this exception be swallowed where Python ignores exceptions (a gc callback,
        # a __del__): the limit still ends the block (the timer is cleared when the block is left)
        signal.setitimer(signal.ITIMER_REAL, 0.1)
        raise on_timeout() if on_timeout is not None else TimeoutError(f"gave up after {seconds} s")

    start = time.monotonic()
    old = signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
        if outer:
            signal.setitimer(signal.ITIMER_REAL, max(outer - (time.monotonic() - start), 1e-3))
