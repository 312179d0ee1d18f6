"""Figures of a simulation for the report: time histories, phase portraits, the events table.

The time histories are the simulation's own figure (``SimulationResult.plot``: coordinates, rates,
reactions and energy, modes shaded, events numbered).  The phase portrait draws each coordinate
against its rate, one line per mode segment (a jump at an impact shows as a gap), with the start,
the end and every event marked with the same numbers.
"""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
from matplotlib.figure import Figure as MplFigure  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from ..base.printing import greek  # noqa: E402
from ..base.textsafe import figure_text  # noqa: E402
from ..numeric.figure import _plain_text  # noqa: E402
from .animate import animate  # noqa: E402
from .blocks import Animation, Figure, Paragraph, Table  # noqa: E402

_UNITS = {"angle": ("rad", "rad/s"), "length": ("m", "m/s")}


def png(fig, dpi: int = 100) -> bytes:
    buf = io.BytesIO()
    try:
        fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    except ValueError:                       # a title mathtext cannot parse: drawn as the plain text it is
        _plain_text(fig)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight")
    return buf.getvalue()


def phase_portrait(result, coordinates=None, max_panels: int = 4) -> MplFigure:
    """Each coordinate against its rate, segment by segment, with the start (○), end (■) and events numbered."""
    names = list(coordinates or result.layout.names)[:max_panels]
    n = len(names)
    fig = MplFigure(figsize=(4.6 * min(n, 2), 4.0 * ((n + 1) // 2)), layout="constrained")
    axes = np.atleast_1d(fig.subplots((n + 1) // 2, min(n, 2))).ravel()
    seg = result.segment
    for ax, name in zip(axes, names):
        q, u = result[name], result[f"dot({name})"]
        for s in np.unique(seg):
            m = seg == s
            ax.plot(q[m], u[m], lw=1.4, color=f"C{int(s) % 10}",
                    label=figure_text(result.segments[int(s)].description) if len(result.segments) > 1 else None)
        ax.plot(q[0], u[0], "o", mfc="white", mec="k", ms=7, zorder=5, label="start")
        ax.plot(q[-1], u[-1], "s", color="k", ms=6, zorder=5, label="end")
        for i, e in enumerate(result.events, 1):
            if name in e.state:
                x, y = e.state[name], e.state.get(f"dot({name})", np.nan)
                ax.plot(x, y, "D", color="#c0392b", ms=6, zorder=6)
                ax.annotate(str(i), (x, y), xytext=(5, 5), textcoords="offset points", color="#c0392b",
                            fontsize=10, zorder=7)
        unit, rate_unit = _UNITS.get(result.kinds.get(name, ""), ("", "1/s"))
        g = greek(name)
        ax.set_xlabel(f"{g} [{unit}]" if unit else g)
        ax.set_ylabel(f"d{g}/dt [{rate_unit}]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="best")
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_locator(MaxNLocator(5))
        ax.ticklabel_format(style="sci", scilimits=(-3, 4), useMathText=True)
    for ax in axes[n:]:
        ax.set_visible(False)
    fig.suptitle(f"{figure_text(result.title)}: phase portrait", fontsize=11)
    return fig


def events_table(result) -> Table:
    rows = []
    for i, e in enumerate(result.events, 1):
        state = ", ".join(f"{greek(k)} = {v:.6g}" for k, v in e.state.items())
        rows.append((str(i), f"{e.t:.10g}", e.name, e.kind, f"{e.mode_before} → {e.mode_after}", state))
    return Table(("#", "t [s]", "Event", "Kind", "Modes", "State at the event"), tuple(rows), "Events")


def simulation_blocks(result, solution=None, figures: bool = True, animation: bool = True, gif: bool = False,
                      frames: int = 80) -> list:
    """The report's Simulation section: a summary, the events, time histories, phase portrait, animation."""
    import matplotlib.pyplot as plt

    out = [Paragraph(f"Simulated from t = {result.t[0]:.4g} s to t = {result.t_final:.6g} s ({result.status}: "
                     f"{result.message}). Energy drift {result.energy_drift:.3g} (relative; {result.energy_balance});"
                     f" largest constraint residual {result.max_residual:.3g}.")]
    modes = ", ".join(f"{s.t0:.6g}–{s.t1:.6g} s: {s.description}" for s in result.segments)
    out.append(Paragraph(f"Modes: {modes}."))
    out.append(events_table(result) if result.events else Paragraph("No event ended a mode in this interval."))
    for w in result.warnings:
        out.append(Paragraph(f"Warning: {w}"))
    if not figures:
        return out
    fig = result.plot()
    try:
        out.append(Figure("time-histories", png(fig), "Time histories: coordinates, rates, reactions and energy; "
                                                      "modes shaded, events numbered (dotted lines).",
                          "time histories"))
    finally:
        plt.close(fig)
    fig = phase_portrait(result)
    out.append(Figure("phase-portrait", png(fig), "Phase portrait of each coordinate: start ○, end ■, events ◆ "
                                                   "numbered as in the events table.", "phase portrait"))
    if animation and solution is not None:
        anim = animate(solution.system, result, frames=frames)
        try:
            out.append(Animation("motion", anim.to_jshtml(), anim.gif_bytes() if gif else None,
                                 f"The motion, drawn from the model's geometry ({len(anim.times)} frames over "
                                 f"{result.t_final - result.t[0]:.4g} s, played at {anim.speed:.3g}× real time)."))
        finally:
            anim.close()
    return out
