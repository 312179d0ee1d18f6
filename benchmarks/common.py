"""What the benchmarks share: medians of repeated runs, time limits, and plain-text tables."""

from __future__ import annotations

import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))


class TimeLimit(Exception):
    """A measurement ran past its time limit."""


def time_limit(seconds: float | None):
    """Interrupt the block after ``seconds`` (main thread, POSIX) with TimeLimit."""
    from rigidkin.base.algebra import time_limit as limit

    return limit(seconds, TimeLimit)


#: Single-threaded figures are CPU seconds of this process (``time.process_time``): on a shared machine
#: the wall clock also counts the time other processes hold the cores.  Parallel figures are wall time.
CLOCK = time.process_time


def cold_caches() -> None:
    """Forget what earlier runs computed: sympy's cache and rigidkin's module-level caches."""
    from sympy.core.cache import clear_cache

    clear_cache()
    for name, module in list(sys.modules.items()):
        if name.startswith("rigidkin") and module is not None:
            for attr, value in vars(module).items():
                if "CACHE" in attr.upper() and isinstance(value, dict):
                    value.clear()


def median_time(fn: Callable[[], object], repeats: int = 3, limit: float | None = None,
                clock: Callable[[], float] = CLOCK, cold: bool = False) -> tuple[float, object]:
    """(median time of ``repeats`` calls, the last call's result); raises TimeLimit past ``limit`` (wall).

    ``cold``: clear the caches before each call (a derivation measured as if for the first time).
    """
    times, out = [], None
    for _ in range(repeats):
        if cold:
            cold_caches()
        with time_limit(limit):
            t0 = clock()
            out = fn()
            times.append(clock() - t0)
    return statistics.median(times), out


def per_call(fn: Callable[[], object], min_time: float = 0.1, repeats: int = 9,
             clock: Callable[[], float] = CLOCK) -> float:
    """Median seconds per call of a fast function (each of ``repeats`` loops runs at least ``min_time``)."""
    n = 1
    while True:
        t0 = clock()
        for _ in range(n):
            fn()
        dt = clock() - t0
        if dt >= min_time / 4:
            break
        n *= 4
    n = max(1, int(n * min_time / max(dt, 1e-9)))
    res = []
    for _ in range(repeats):
        t0 = clock()
        for _ in range(n):
            fn()
        res.append((clock() - t0) / n)
    return statistics.median(res)


def table(title: str, header: list[str], rows: list[list], note: str = "") -> str:
    """A plain-text table with right-aligned columns."""
    cells = [[_cell(c) for c in r] for r in rows]
    widths = [max(len(h), *(len(r[i]) for r in cells)) if cells else len(h) for i, h in enumerate(header)]
    line = "  ".join(h.rjust(w) for h, w in zip(header, widths))
    out = [f"\n## {title}", line, "-" * len(line)]
    out += ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in cells]
    if note:
        out.append(note)
    return "\n".join(out)


def _cell(v) -> str:
    if v is None:
        return "–"
    if isinstance(v, float):
        if v == 0:
            return "0"
        if abs(v) >= 1000 or abs(v) < 1e-3:
            return f"{v:.3g}"
        return f"{v:.3g}" if abs(v) < 10 else f"{v:.1f}"
    return str(v)


def machine() -> str:
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return f"{cores} cores, load average {load:.1f} at start (timings on a busy machine vary)"
