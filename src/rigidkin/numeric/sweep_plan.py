"""A sweep's runs as numbers: the values of each axis, the size a table of runs may have, and each run's
initial state completed through the constraints (trees of :mod:`rigidkin.numeric.exprtree`).

Numbers only (numpy): shared by the full sweep (:mod:`rigidkin.numeric.sweep`) and the repeated sweep read
from its numeric record (:mod:`rigidkin.numeric.sweep_record`), so both plan their runs alike.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError


def axis(spec) -> np.ndarray:
    """Values of a swept quantity: an array, or ``(start, stop, count)`` (inclusive, evenly spaced)."""
    if isinstance(spec, tuple) and len(spec) == 3:
        start, stop, count = spec
        if int(count) != count or count < 1:
            raise InputError(f"the count of a sweep axis must be a whole number ≥ 1, not {count}.")
        return np.linspace(float(start), float(stop), int(count))
    arr = np.atleast_1d(np.asarray(spec, dtype=float))
    if arr.ndim != 1 or not np.all(np.isfinite(arr)):
        raise InputError("the values of a sweep axis must be finite numbers.")
    return arr


def axis_length(spec) -> int:
    """How many values an axis spec gives, without making them."""
    if isinstance(spec, tuple) and len(spec) == 3:
        try:
            return max(int(spec[2]), 0)
        except (TypeError, ValueError, OverflowError):
            raise InputError(f"the count of a sweep axis must be a whole number ≥ 1, not {spec[2]!r}.") from None
    return int(np.size(spec))


def check_runs(lengths: list[int], n: int, n_p: int, events: int = 4, grid: bool = True) -> int:
    """The number of runs of a sweep with axes of these ``lengths`` (a model of ``n`` coordinates and ``n_p``
    parameters), refused (InputError) when its table would not fit in memory.

    Every run keeps its parameters, inputs, initial and final states, and each event's time and
    state (``events``: how many events, estimated); see :data:`rigidkin.limits.MEMORY_LIMIT`.
    """
    from ..limits import check_memory, sweep_bytes

    runs = (math.prod(lengths) if grid else max(lengths)) if lengths else 1
    per_run = 3 * n_p + 2 * len(lengths) + 6 * 2 * n + 2 * events * (2 * n + 1) + 8
    check_memory(sweep_bytes(runs, per_run), f"a sweep of {runs:,} runs", "sweep",
                 hint="Use fewer values per axis (or fewer axes), or split the sweep into several and join the "
                      "tables.")
    return runs


def complete(Y: np.ndarray, P: np.ndarray, rel: tuple[list, list], given: set, args=None) -> None:
    """Each run's dependent coordinates, then rates, from the constraints (``relations``), in place; the slots
    in ``given`` keep their values."""
    from .exprtree import evaluate

    runs = len(Y)
    for k, group in enumerate(rel):
        cols = [np.zeros(runs), *Y.T, *P.T]
        for i, expr in group:
            if i in given:
                continue
            if isinstance(expr, list):
                Y[:, i] = evaluate(expr, cols, runs)
            else:
                Y[:, i] = _vector_eval(args, expr, cols, runs)
            if k == 0:
                cols = [np.zeros(runs), *Y.T, *P.T]


#: lambdify's namespace: numpy's own functions (``modules="numpy"`` would star-import numpy's every submodule,
#: a tenth of a second at each command's start).
_NUMPY = ({"numpy": np}, np)


def _vector_eval(args, expr, columns, runs) -> np.ndarray:
    """``expr`` (of the layout's arguments) at every run at once."""
    from .codesafe import safe_lambdify

    f = safe_lambdify(args, [expr], modules=list(_NUMPY), cse=False, where="sweep")
    with np.errstate(all="ignore"):
        return np.broadcast_to(np.asarray(f(*columns)[0], dtype=float), (runs,)).copy()
