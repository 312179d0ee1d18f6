"""An animation of simulated motion, drawn from the model's geometry (planar view, Ex right, Ey up).

Every frame draws the surfaces and each body as its shape (``drawing.draw_body``) at the state the
simulation's dense output gives at that time, with the path of each mass centre so far.  The
animation plays in a report as matplotlib's HTML5 player (frames embedded, no network) and saves as
a GIF with Pillow.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.animation import FuncAnimation, PillowWriter  # noqa: E402

from ..base.outfile import write_bytes  # noqa: E402
from ..base.textsafe import figure_text  # noqa: E402
from .drawing import draw_body, draw_ropes, draw_surfaces  # noqa: E402
from .geometry import Geometry, body_size  # noqa: E402
from .geometry import t as time_symbol  # noqa: E402
from .html import offline_player  # noqa: E402


@dataclass
class MotionAnimation:
    """A matplotlib animation of a simulation, with the times of its frames."""

    animation: FuncAnimation
    figure: object
    times: np.ndarray
    fps: float
    speed: float            # playback speed relative to real time

    def to_jshtml(self) -> str:
        """An HTML5 player with the frames embedded; its icons drawn as characters (no CDN)."""
        return offline_player(self.animation.to_jshtml(fps=self.fps, embed_frames=True, default_mode="once"))

    def save_gif(self, path) -> None:
        write_bytes(path, self.gif_bytes(), "the animation", (".gif",))

    def gif_bytes(self) -> bytes:
        fd, name = tempfile.mkstemp(suffix=".gif")
        os.close(fd)
        try:
            self.animation.save(name, writer=PillowWriter(fps=self.fps))
            with open(name, "rb") as f:
                return f.read()
        finally:
            os.unlink(name)

    def close(self) -> None:
        plt.close(self.figure)


def simulation_parameters(result) -> dict:
    """The parameter values a simulation ran with (its first segment's), name → number."""
    try:
        return dict(zip(result.layout.parameters, (float(v) for v in result.segments[0].params)))
    except (AttributeError, IndexError, TypeError):
        return {}


def _frame_times(result, frames: int) -> np.ndarray:
    t0, t1 = float(result.t[0]), float(result.t_final)
    return np.linspace(t0, t1, max(2, frames))


def _state(result, system, t_: float) -> dict:
    st = result.at(t_)
    out = {info.symbol: float(st[name]) for name, info in system.coordinate_info.items()}
    out[time_symbol] = t_
    return out


def animate(system, result, frames: int = 80, duration: float | None = None, size: float = 5.0,
            dpi: int = 80, trail: bool = True) -> MotionAnimation:
    """Animate ``result`` (a ``rigidkin.numeric`` SimulationResult of ``system``).

    ``frames`` frames evenly spaced in time; ``duration`` the playing time in seconds (default: real
    time, between 2 s and 12 s).
    """
    geom = Geometry(system, values=simulation_parameters(result))
    times = _frame_times(result, frames)
    states = [_state(result, system, float(tt)) for tt in times]
    span = float(times[-1] - times[0]) or 1.0
    play = duration or min(max(span, 2.0), 12.0)
    fps = max(1.0, len(times) / play)
    speed = span / (len(times) / fps)
    # fixed limits: every point and body over the whole motion
    pts = []
    for q in states:
        for p in system.points:
            pts.append(geom.point(p, q)[:2])
    pts = np.array(pts)
    pad = max([body_size(b, geom) for b in system.bodies.values()] + [0.05 * float(np.ptp(pts, axis=0).max())])
    lo, hi = pts.min(axis=0) - pad, pts.max(axis=0) + pad
    width = float((hi - lo).max())
    centre = (lo + hi) / 2
    lims = (centre[0] - width / 2, centre[0] + width / 2), (centre[1] - width / 2, centre[1] + width / 2)
    fig, ax = plt.subplots(figsize=(size, size), dpi=dpi)
    fig.subplots_adjust(left=0.02, right=0.98, bottom=0.02, top=0.92)
    centres = {b.name: np.array([geom.point(b.centre, q)[:2] for q in states]) for b in system.bodies.values()}
    mode_at = [figure_text(result.segment_at(float(tt)).description) for tt in times]

    def draw(i):
        ax.clear()
        q = states[i]
        draw_surfaces(ax, geom, q, width)
        draw_ropes(ax, geom, q)                 # strings, ropes, belts and their fixed ends (a ceiling)
        for b in system.bodies.values():
            if trail and i > 0:
                c = centres[b.name][: i + 1]
                ax.plot(c[:, 0], c[:, 1], color="#9aa9bb", lw=1, zorder=1)
            draw_body(ax, b, geom, q)
        ax.set_xlim(*lims[0])
        ax.set_ylim(*lims[1])
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(f"t = {times[i]:.3f} s    {mode_at[i]}", fontsize=9)
        return []

    anim = FuncAnimation(fig, draw, frames=len(times), interval=1000.0 / fps, blit=False, repeat=False)
    return MotionAnimation(anim, fig, times, fps, speed)
