"""Free-body diagrams drawn from the model: each body isolated, with every load the laws use.

The loads are the mode's force and torque applications (``ModeSetup.applications``), the very list
the balance laws sum, so the diagram shows exactly the forces of the derivation.  Each force is an
arrow at its point of application, labelled with its magnitude: applied loads (weights, springs,
given forces, sliding friction) start at their point; reactions (unknowns a constraint brings) end
at their point, drawn in another colour, in the sense their symbol is positive.  Torques and
reaction couples are curved arrows about the mass centre.  The body is drawn as its shape at a
representative configuration (the initial values unless other values are given); the surfaces
that were removed are drawn faintly for orientation.
"""

from __future__ import annotations

import io
from dataclasses import dataclass, field

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import sympy as sp  # noqa: E402
from matplotlib import patches  # noqa: E402
from matplotlib.mathtext import MathTextParser  # noqa: E402

from ..base.printing import text as plain_text  # noqa: E402
from ..derive.mode import setup_mode  # noqa: E402
from ..numeric.figure import save_figure  # noqa: E402
from .drawing import draw_body, draw_surfaces  # noqa: E402
from .geometry import Geometry, body_size  # noqa: E402
from .geometry import t as geom_t  # noqa: E402
from .notation import _vector_terms, latex  # noqa: E402

APPLIED = "#1f5fbf"
REACTION = "#c0392b"
DRIVE = "#7d3c98"        # the efforts a prescribed motion needs (a driven body's drive force and torque)

_PARSER = MathTextParser("path")


@dataclass(frozen=True)
class DrawnLoad:
    """One load as drawn: on ``body``, from ``source`` (a load or constraint name), ``reaction`` its unknown."""

    body: str
    label: str
    source: str
    reaction: str | None
    kind: str                    # "force" or "torque"
    at: tuple                    # point of application (x, y); the mass centre for a torque
    direction: tuple             # unit direction drawn (x, y); (±1 about Ez) for a torque
    description: str = ""


@dataclass
class FreeBodyDiagram:
    """The figure and the list of loads drawn on it."""

    figure: object
    loads: list[DrawnLoad] = field(default_factory=list)
    configuration: dict = field(default_factory=dict)
    assumed: list[str] = field(default_factory=list)

    def png(self, dpi: int = 110) -> bytes:
        buf = io.BytesIO()
        self.figure.savefig(buf, format="png", dpi=dpi)
        return buf.getvalue()

    def save(self, path, dpi: int = 150) -> None:
        save_figure(self.figure, path, "the free-body diagram", dpi=dpi)

    def close(self) -> None:
        plt.close(self.figure)

    def loads_on(self, body: str) -> list[DrawnLoad]:
        return [d for d in self.loads if d.body == body]


def mathtext(obj) -> str:
    """A matplotlib label for an expression: mathtext when matplotlib can typeset it, else Unicode text."""
    s = f"${latex(obj)}$"
    try:
        _PARSER.parse(s)
        return s
    except Exception:
        return plain_text(obj)


def _magnitude_label(app, setup) -> str:
    """A force's label: its reaction symbol, its magnitude when it acts along one basis vector, else its load."""
    terms = _vector_terms(app.vector)
    if app.reaction is not None:
        return mathtext(app.reaction)
    if len(terms) == 1:
        comp = terms[0][0]
        if comp.could_extract_minus_sign():
            comp = -comp
        return mathtext(setup.scalar(comp))
    return app.source


def _direction(geom: Geometry, app, q, extra) -> np.ndarray | None:
    for rates in (0.0, 0.7):
        v = geom.vector(app.vector, q, extra, rates)
        if v is not None and np.linalg.norm(v[:2]) > 1e-12:
            return v
    return None


def _application_point(geom: Geometry, app, q) -> np.ndarray:
    if app.location is not None:
        loc = geom.vector(app.location, q)
        if loc is not None:
            return loc
    if app.point is not None:
        return geom.point(app.point, q)
    return geom.point(app.body.centre, q)


def _free_symbols(v) -> set:
    out = set()
    for measure, _frame in v.args:
        for c in measure:
            out |= sp.sympify(c).free_symbols
    return out


def _draw_torque(ax, centre, sense, radius, colour, label, reaction):
    start, end = (200, 500) if sense > 0 else (500, 200)
    th = np.radians(np.linspace(start, end, 40))
    pts = centre[None, :] + radius * np.c_[np.cos(th), np.sin(th)]
    ax.plot(pts[:-3, 0], pts[:-3, 1], color=colour, lw=2, ls="--" if reaction else "-", zorder=5)
    ax.add_patch(patches.FancyArrowPatch(pts[-4], pts[-1], arrowstyle="-|>", mutation_scale=16, color=colour,
                                         lw=2, zorder=5))
    mid = pts[len(pts) // 3]
    ax.text(*(centre + 1.25 * (mid - centre)), label, color=colour, fontsize=12, ha="center", va="center",
            zorder=7, bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8))
    return [pts[:, 0].min(), pts[:, 0].max()], [pts[:, 1].min(), pts[:, 1].max()]


def _avoid_overlap(tail, head, drawn, L):
    """Shift an arrow sideways (by 0.1 L) while it lies on the line of an arrow already drawn and overlaps it."""
    d = (head - tail) / max(np.linalg.norm(head - tail), 1e-12)
    n = np.array([-d[1], d[0]])
    for _ in range(4):
        clash = False
        for t0, h0 in drawn:
            e = (h0 - t0) / max(np.linalg.norm(h0 - t0), 1e-12)
            if abs(e[0] * d[1] - e[1] * d[0]) > 0.05:
                continue
            if abs(np.dot(tail - t0, n)) > 0.05 * L:
                continue
            s0, s1 = sorted((np.dot(t0 - tail, d), np.dot(h0 - tail, d)))
            if s1 > 0.02 * L and s0 < np.linalg.norm(head - tail) - 0.02 * L:
                clash = True
                break
        if not clash:
            break
        tail, head = tail + 0.1 * L * n, head + 0.1 * L * n
    return tail, head


def _free_spot(pos, d, taken, L):
    """A label position near ``pos`` at least 0.25 L from the labels already placed."""
    n = np.array([-d[1], d[0]])
    for cand in (pos, pos + 0.3 * L * n, pos - 0.3 * L * n, pos - 0.3 * L * d, pos + 0.6 * L * n):
        if all(np.linalg.norm(cand - p) > 0.25 * L for p in taken):
            return cand
    return pos


def _draw_body_fbd(ax, geom: Geometry, setup, body, q, out: list) -> None:
    scale = geom.scale(q)
    size = max(body_size(body, geom), 0.25 * scale)
    L = 0.5 * size
    xs, ys = [], []
    draw_body(ax, body, geom, q)
    centre = geom.point(body.centre, q)[:2]
    xs += [centre[0] - 0.5 * body_size(body, geom), centre[0] + 0.5 * body_size(body, geom)]
    ys += [centre[1] - 0.5 * body_size(body, geom), centre[1] + 0.5 * body_size(body, geom)]
    # the surfaces this body touches, faint
    touching = [c.name for c in setup.system.constraints.values() if getattr(c, "body", None) is body]
    draw_surfaces(ax, geom, q, 0.6 * size, alpha=0.45, only=touching)
    labels: list = []       # where labels are (and named points, which labels keep clear of)
    for p in setup.system.points.values():
        if p.body is body:
            xy = geom.point(p, q)[:2]
            ax.annotate(p.name, xy, xytext=(-9, -11), textcoords="offset points", fontsize=9, color="#555",
                        zorder=8)
            xs.append(xy[0])
            ys.append(xy[1])
            labels.append(xy)
    torque_radius = 0.28 * size
    drawn: list = []
    for app in setup.applications:
        if app.body is not body:
            continue
        extra = {s: 1.0 for s in _free_symbols(app.vector) if s not in set(setup.system.parameters.values())}
        if app.reaction is not None:
            extra[app.reaction] = 1.0
        label = _magnitude_label(app, setup)
        reaction = app.reaction is not None
        driven = getattr(setup.system.constraints.get(app.source), "kind", "") == "drive"
        colour = DRIVE if driven else REACTION if reaction else APPLIED
        v = _direction(geom, app, q, extra)
        if app.is_torque:
            sense = 1.0 if v is None or v[2] >= 0 else -1.0
            bx, by = _draw_torque(ax, centre, sense, torque_radius, colour, label, reaction)
            torque_radius *= 1.3
            xs += bx
            ys += by
            out.append(DrawnLoad(body.name, label, app.source, str(app.reaction) if reaction else None, "torque",
                                 tuple(centre), (0.0, sense), app.label))
            continue
        at = _application_point(geom, app, q)[:2]
        if v is None:  # zero in this configuration (a spring at its natural length): a marker
            ax.plot(*at, marker="o", ms=9, mfc="none", mec=colour, mew=2, zorder=6)
            ax.annotate(label, at, xytext=(8, 8), textcoords="offset points", color=colour, fontsize=12, zorder=7)
            out.append(DrawnLoad(body.name, label, app.source, str(app.reaction) if reaction else None, "force",
                                 tuple(at), (0.0, 0.0), app.label))
            continue
        d = v[:2] / np.linalg.norm(v[:2])
        tail, head = (at - L * d, at) if reaction else (at, at + L * d)
        tail, head = _avoid_overlap(tail, head, drawn, L)
        drawn.append((tail, head))
        ax.add_patch(patches.FancyArrowPatch(tail, head, arrowstyle="-|>", mutation_scale=18, color=colour, lw=2.2,
                                             shrinkA=0, shrinkB=0, zorder=6,
                                             linestyle=(0, (4, 2)) if reaction else "-"))
        free_end = tail if reaction else head
        lab = free_end - 0.18 * L * d if reaction else free_end + 0.18 * L * d
        lab = _free_spot(lab, d, labels, L)
        labels.append(lab)
        ax.text(*lab, label, color=colour, fontsize=13, ha="center", va="center", zorder=7,
                bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8))
        xs += [tail[0], head[0], lab[0]]
        ys += [tail[1], head[1], lab[1]]
        out.append(DrawnLoad(body.name, label, app.source, str(app.reaction) if reaction else None, "force",
                             tuple(at), tuple(d), app.label))
    pad = 0.15 * L + 0.05 * size
    x0, x1, y0, y1 = min(xs) - pad, max(xs) + pad, min(ys) - pad, max(ys) + pad
    span = max(x1 - x0, y1 - y0)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    ax.set_xlim(cx - span / 2, cx + span / 2)
    ax.set_ylim(cy - span / 2, cy + span / 2)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    for s in ax.spines.values():
        s.set_visible(False)
    ax.set_title(f"{body.name} ({body.shape.kind})", fontsize=12)


def free_body_diagram(obj, bodies=None, values=None, mode=None, parameters=None) -> FreeBodyDiagram:
    """Free-body diagrams of the bodies of a System or Solution, one panel per body.

    ``values`` gives coordinates (name or symbol → number) of the configuration drawn (default: the
    initial values); ``mode`` a contact mode for a System; ``parameters`` overrides parameter values.
    """
    if hasattr(obj, "setup") and hasattr(obj, "regimes"):
        system, setup = obj.system, obj.setup
    else:
        system, setup = obj, setup_mode(obj, mode)
    geom = Geometry(system, setup, parameters)
    q = geom.configuration(values)
    chosen = [b for b in system.bodies.values() if bodies is None or b.name in bodies]
    n = len(chosen)
    cols = min(n, 3)
    rows = (n + cols - 1) // cols if n else 1
    fig = plt.figure(figsize=(4.2 * max(cols, 1), 4.4 * rows + (0.5 if cols > 1 else 0.8)))
    out: list[DrawnLoad] = []
    for i, b in enumerate(chosen):
        ax = fig.add_subplot(rows, max(cols, 1), i + 1)
        _draw_body_fbd(ax, geom, setup, b, q, out)
    handles = [patches.Patch(color=APPLIED, label="applied load (starts at its point)"),
               patches.Patch(color=REACTION, label="reaction, unknown (ends at its point)")]
    if any(getattr(system.constraints.get(d.source), "kind", "") == "drive" for d in out):
        handles.append(patches.Patch(color=DRIVE, label="effort needed to drive a prescribed motion"))
    fig.legend(handles=handles, loc="lower center", ncol=2 if cols > 1 else 1, fontsize=9, frameon=False)
    shown = ", ".join(f"{plain_text(k)} = {v:.4g}" for k, v in q.items() if k != geom_t or v)
    fig.suptitle(f"Free-body diagrams at {shown}", fontsize=10, color="#444")
    low = (0.05 if cols > 1 else 0.09) * (1.6 if len(handles) > 2 else 1.0)
    fig.tight_layout(rect=(0, low, 1, 0.95))
    return FreeBodyDiagram(fig, out, q, geom.assumed)
