"""``rigidkin draw PROBLEM -o FIGURE``: the geometry and the free-body diagrams of a problem, without solving it.

Any file that ``rigidkin validate`` accepts can be drawn, also one whose balance laws contradict each other (a
rope wrapped the wrong way round a pulley, a point placed on the wrong side): the drawing comes from the model's
geometry and the loads its mode applies, not from the equations of motion, so the wrong wrap or the misplaced
point can be seen.  Two figures: ``FIGURE`` (the bodies, surfaces, ropes and named points at the initial
configuration, or ``--at``) and ``FIGURE``'s stem with ``-fbd`` (one free-body diagram per body).
"""

from __future__ import annotations

from pathlib import Path

from ..base.errors import InputError, RigidkinError
from ..base.outfile import writing
from ..base.textsafe import figure_text
from ..io.load import value
from .common import guarded, load_system, progress, with_file
from .options import add_timeout, parse_modes

FORMATS = (".svg", ".png", ".pdf")


def register(sub) -> None:
    p = sub.add_parser("draw", help="draw the geometry and free-body diagrams of a problem, without solving it")
    p.add_argument("problem", help="a problem file (.toml) or a bundled example name")
    p.add_argument("-o", "--output", default=None,
                   help="the figure (.svg, .png or .pdf; default NAME-drawing.svg); the free-body diagrams go "
                        "beside it with -fbd added to its name")
    p.add_argument("--at", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="the configuration drawn (coordinates; default: their initial values), e.g. theta=30deg")
    p.add_argument("--mode", nargs="+", action="extend", default=[], metavar="CONTACT=STATE",
                   help="the state of a contact for the free-body diagrams: open, slip or stick")
    add_timeout(p, 300)
    p.set_defaults(func=run)


def _configuration(system, pairs: list[str]) -> dict:
    coords = {c.symbol.func.__name__: c.symbol for c in system.coordinate_info.values()}
    out = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        if not sep or name.strip() not in coords:
            raise InputError(f"--at {pair!r} names no coordinate.", where="--at",
                             hint=f"Write NAME=VALUE with a coordinate of the problem: {', '.join(coords)}.")
        out[coords[name.strip()]] = value(text, f"--at {name.strip()}")
    return out


def targets(output: str | None, problem: str) -> tuple[Path, Path]:
    """(geometry figure, free-body diagrams) paths for ``-o`` (or the problem's name)."""
    path = Path(output) if output else Path(f"{Path(problem).stem}-drawing.svg")
    if path.suffix.lower() not in FORMATS:
        raise InputError(f"the figure {str(path)!r} has no known format.", where="-o",
                         hint=f"End its name with {', '.join(FORMATS)}.")
    return path, path.with_name(f"{path.stem}-fbd{path.suffix}")


def geometry_figure(system, q: dict | None = None, mode=None):
    """A matplotlib figure of the system at ``q``: bodies, surfaces, ropes and every named point labelled."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from ..base.printing import text
    from ..derive.mode import setup_mode
    from ..report.drawing import draw_body, draw_ropes, draw_surfaces
    from ..report.geometry import Geometry

    geom = Geometry(system, setup_mode(system, mode))
    at = geom.configuration(q)
    span = geom.scale(at)
    fig, ax = plt.subplots(figsize=(6, 6))
    draw_surfaces(ax, geom, at, span)
    draw_ropes(ax, geom, at)
    for b in system.bodies.values():
        draw_body(ax, b, geom, at)
    for name in system.points:
        p = np.asarray(geom.point(name, at), dtype=float)[:2]
        ax.plot(*p, "o", ms=3, color="#b2182b", zorder=5)
        ax.annotate(figure_text(name), p, xytext=(4, 4), textcoords="offset points", fontsize=9, color="#b2182b",
                    zorder=5)
    ax.set_aspect("equal")
    ax.margins(0.15)
    ax.set_xlabel("Ex")
    ax.set_ylabel("Ey")
    shown = ", ".join(f"{text(k)} = {v:.4g}" for k, v in at.items() if getattr(k, "args", None))
    ax.set_title(figure_text(f"{system.title}\n{shown}"), fontsize=10)
    fig.tight_layout()
    return fig


def run(args) -> int:
    geometry_path, fbd_path = targets(args.output, args.problem)
    with progress(f"Reading {args.problem}"):
        system, spec = guarded(args, load_system, args.problem)
    from ..report.fbd import free_body_diagram

    try:
        q = _configuration(system, args.at)
        mode = parse_modes(args.mode) or None
        with progress("Drawing"):
            geometry = guarded(args, geometry_figure, system, q or None, mode)
            fbd = guarded(args, free_body_diagram, system, None, q or None, mode)
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    for path, fig in ((geometry_path, geometry), (fbd_path, fbd.figure)):
        with writing(path, "the drawing", binary=True, suffixes=FORMATS) as f:
            fig.savefig(f, format=path.suffix[1:].lower(), dpi=150)
        print(f"wrote {path}")
    return 0
