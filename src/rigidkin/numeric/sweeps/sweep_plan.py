"""A sweep's runs as numbers: the values of each axis, the size a table of runs may have, and each run's
initial state completed through the constraints (trees of :mod:`rigidkin.numeric.sweeps.exprtree`).

Numbers only (numpy): shared by the full sweep (:mod:`rigidkin.numeric.sweeps.sweep`) and the repeated sweep read
from its numeric record (:mod:`rigidkin.numeric.sweeps.sweep_record`), so both plan their runs alike.
"""

from __future__ import annotations

import math

import numpy as np

from ...base.errors import InputError
from ...base.limits import check_memory, sweep_bytes
from .exprtree import evaluate

#: Chunks a streamed sweep holds at once: one being integrated, one waiting for the writer, one being written.
IN_FLIGHT = 3
#: The most runs one streamed sweep makes (a table of about 25 GB as CSV for the ladder).
MAX_STREAMED = 100_000_000


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


def check_runs(lengths: list[int], n: int, n_p: int, events: int = 4, grid: bool = True,
               chunk: int | None = None) -> int:
    """The number of runs of a sweep with axes of these ``lengths`` (a model of ``n`` coordinates and ``n_p``
    parameters), refused (InputError) when what it holds at once would not fit in memory.

    Every run keeps its parameters, inputs, initial and final states, and each event's time and
    state (``events``: how many events, estimated).  A sweep held whole (``chunk`` None) holds every
    run; a sweep streamed to its table ``chunk`` runs at a time holds :data:`IN_FLIGHT` chunks (one
    integrated, one waiting, one written) and its axes' values, whatever its size.  See
    :data:`rigidkin.base.limits.MEMORY_LIMIT`.
    """

    runs = (math.prod(lengths) if grid else max(lengths)) if lengths else 1
    if chunk is not None and runs > MAX_STREAMED:
        raise InputError(f"a sweep of {runs:,} runs is more than one command runs ({MAX_STREAMED:,}).", where="sweep",
                         hint="Use fewer values per axis (or fewer axes), or split the sweep into several.")
    per_run = 3 * n_p + 2 * len(lengths) + 6 * 2 * n + 2 * events * (2 * n + 1) + 8
    held = runs if chunk is None else min(runs, IN_FLIGHT * int(chunk))
    estimate = sweep_bytes(held, per_run) + (0 if chunk is None else 8 * sum(lengths))
    check_memory(estimate, f"a sweep of {runs:,} runs" + ("" if chunk is None else f" ({held:,} at a time)"),
                 "sweep", hint="Write it to a table (the command streams it chunk by chunk), or use fewer values "
                               "per axis (or fewer axes), or split the sweep into several and join the tables.")
    return runs


def declared_state(system, n: int) -> np.ndarray:
    """The state the problem declares: each coordinate's initial value and rate (zero where none is given)."""
    y = np.zeros(2 * n)
    for i, c in enumerate(system.coordinate_info.values()):
        if c.initial is not None:
            y[i] = float(c.initial)
        if c.rate is not None:
            y[n + i] = float(c.rate)
    return y


def runs_grid(vary, base_p, y_base, parameters, labels, given: set, grid: bool = True, unknown=None,
              rows: tuple[int, int] | None = None, axes: dict | None = None):
    """(inputs per run, parameters runs × n_p, states runs × 2n): every combination of the axes of ``vary``
    (``grid``) or the axes side by side, over the base values; ``given`` gains the state slots the axes set.
    ``unknown(name)``: the error for an axis that is neither a parameter nor a state label.  ``rows``
    (first, stop): only those runs of the sweep, in the same order (a chunk); ``axes``: the axes' values, made
    once for every chunk (:func:`axes_of`)."""
    axes = axes_of(vary) if axes is None else axes
    runs = sweep_runs(axes, grid)
    lo, hi = (0, runs) if rows is None else (max(0, rows[0]), min(runs, rows[1]))
    inputs = grid_inputs(axes, lo, hi, grid)
    runs = hi - lo
    parameters, labels = list(parameters), list(labels)
    P = np.tile(np.asarray(base_p, dtype=float), (runs, 1))
    Y = np.tile(np.asarray(y_base, dtype=float), (runs, 1))
    for name, values in inputs.items():
        if name in parameters:
            P[:, parameters.index(name)] = values
        elif name in labels:
            Y[:, labels.index(name)] = values
            given.add(labels.index(name))
        else:
            raise unknown(name) if unknown else InputError(f"'{name}' is not a parameter or state of the sweep.")
    return inputs, P, Y


def axes_of(vary) -> dict[str, np.ndarray]:
    """The values of every axis of ``vary``, by name."""
    return {str(k): axis(spec) for k, spec in (vary or {}).items()}


def sweep_runs(axes: dict[str, np.ndarray], grid: bool = True) -> int:
    """How many runs the axes make: the product of their lengths (``grid``), or their common length (zipped)."""
    if not axes:
        return 1
    if grid:
        return math.prod(len(a) for a in axes.values())
    lengths = {len(a) for a in axes.values()}
    if len(lengths) > 1:
        raise InputError("zipped sweep axes must have equal lengths.", hint="Use a grid, or give equal counts.")
    return lengths.pop()


def grid_inputs(axes: dict[str, np.ndarray], lo: int, hi: int, grid: bool = True) -> dict[str, np.ndarray]:
    """Each axis's value at runs ``lo`` … ``hi - 1``: the grid in C order (the last axis fastest, as
    ``meshgrid(indexing="ij")`` ravelled), or the axes side by side."""
    if not axes:
        return {}
    if not grid:
        return {k: a[lo:hi] for k, a in axes.items()}
    shape = tuple(len(a) for a in axes.values())
    index = np.unravel_index(np.arange(lo, hi, dtype=np.int64), shape) if hi > lo else [np.zeros(0, int)] * len(shape)
    return {k: a[i] for (k, a), i in zip(axes.items(), index)}


def complete(Y: np.ndarray, P: np.ndarray, rel: tuple[list, list], given: set, symbolic=None) -> None:
    """Each run's dependent coordinates, then rates, from the constraints (``relations``), in place; the slots
    in ``given`` keep their values.  A relation that is a tree is evaluated here; one that is still a sympy
    expression (the full sweep's, where no tree could be made) by ``symbolic(expr, columns, runs)``."""

    runs = len(Y)
    cols = [np.zeros(runs), *Y.T, *P.T]          # views: each slot completed is seen by the next
    for i, expr in (*rel[0], *rel[1]):
        if i in given:
            continue
        Y[:, i] = evaluate(expr, cols, runs) if isinstance(expr, list) else symbolic(expr, cols, runs)
