"""The figure of a sweep: an event quantity against one swept parameter (a curve of points), or a map over two
(colour: the quantity), drawn from the runs a :class:`~rigidkin.numeric.sweeps.summary.Summary` kept."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..figure import save_figure


def plot_sweep(path, system_name: str, summary, x: tuple[str, ...], y: str | None,
               grid: dict[str, int] | None = None) -> Path:
    """Draw ``y`` (a table column; None: the first event's time) against ``x`` (one or two swept parameters).
    ``grid``: the lengths of the sweep's axes when every run was kept (a map over the whole grid is drawn cell by
    cell); otherwise the kept runs are drawn as coloured points."""
    from matplotlib.figure import Figure

    cols = summary.sample()
    y = y if y is not None else summary.keep[-1]
    ys = cols[y]
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.subplots()
    runs = f"{summary.seen:,} runs" + (f" (every {summary.stride}th drawn)" if summary.stride > 1 else "")
    if len(x) == 1:
        xs = cols[x[0]]
        order = np.argsort(xs, kind="stable")
        ax.plot(xs[order], ys[order], ".", ms=3 if len(xs) > 200 else 6)
        ax.set_xlabel(x[0])
        ax.set_ylabel(y)
        ax.grid(alpha=0.3)
    else:
        a, b = cols[x[0]], cols[x[1]]
        names = list(grid or {})
        if grid and len(grid) == 2 and names == list(x):
            shape = (grid[x[0]], grid[x[1]])
            A, B, Z = a.reshape(shape), b.reshape(shape), ys.reshape(shape)
            mesh = ax.pcolormesh(A, B, np.ma.masked_invalid(Z), shading="nearest")
        else:
            mesh = ax.scatter(a, b, c=ys, s=4 if len(a) > 2000 else 16)
        fig.colorbar(mesh, ax=ax, label=y)
        ax.set_xlabel(x[0])
        ax.set_ylabel(x[1])
    ax.set_title(f"{system_name}: {runs}")
    return save_figure(fig, path, dpi=120)
