"""Drawing a system's bodies and surfaces in the plane of motion (Ex to the right, Ey up).

Each body is drawn as its shape, from the model's geometry at a configuration: a slender rod as a
bar between its ends, a disk or ring as a circle with a radius line fixed in the body (so that its
rotation shows), a sphere shaded, half shapes as a half disk on the side of their mass centre,
plates and boxes as their outline, a particle as a dot.  Surfaces (walls, floors, tracks) are drawn
as lines or circles hatched on the side away from the body.  A 3D model is drawn in its projection
on the Ex–Ey plane.
"""

from __future__ import annotations

import numpy as np
from matplotlib import patches
from matplotlib.collections import LineCollection

from .geometry import Geometry

BODY_FACE = "#c9d6e8"
BODY_EDGE = "#1f3b5c"
SURFACE = "#8a8a8a"


def _xy(v) -> np.ndarray:
    return np.asarray(v, dtype=float)[:2]


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    n = np.linalg.norm(v)
    return v / n if n > 1e-12 else v


def _body_axis(shape, axes: np.ndarray, name: str) -> np.ndarray:
    """A body-frame direction (``"x"``, ``"-y"``) in the inertial basis."""
    s = name.strip()
    sign = -1.0 if s.startswith("-") else 1.0
    s = s.lstrip("+-")
    return sign * axes[:, "xyz".index(s[-1])]


def _half_disk(centre, toward, radius, n=40) -> np.ndarray:
    u = _unit(_xy(toward))
    w = np.array([-u[1], u[0]])
    ang = np.linspace(-np.pi / 2, np.pi / 2, n)
    arc = centre[None, :] + radius * (np.cos(ang)[:, None] * u + np.sin(ang)[:, None] * w)
    return np.vstack([arc, arc[:1]])


def draw_body(ax, body, geom: Geometry, q, alpha: float = 1.0, zorder: int = 2) -> list:
    """Draw ``body`` at configuration ``q``; returns the artists."""
    shape, kind = body.shape, body.shape.kind
    axes = geom.axes(body, q)
    ref = _xy(geom.point(body.reference, q))
    centre = _xy(geom.point(body.centre, q))
    face = dict(facecolor=BODY_FACE, edgecolor=BODY_EDGE, linewidth=1.6, alpha=alpha, zorder=zorder)
    out = []
    if kind == "slender rod":
        a = _xy(_body_axis(shape, axes, shape.axis))
        L = geom.number(shape.length)
        ends = np.array([centre - a * L / 2, centre + a * L / 2])
        out.append(ax.plot(ends[:, 0], ends[:, 1], color=BODY_EDGE, lw=7, solid_capstyle="round", alpha=alpha,
                           zorder=zorder)[0])
        out.append(ax.plot(ends[:, 0], ends[:, 1], color=BODY_FACE, lw=4, solid_capstyle="round", alpha=alpha,
                           zorder=zorder)[0])
    elif kind in ("disk", "thin ring", "hollow cylinder", "solid sphere", "spherical shell"):
        r = geom.number(shape.radius)
        axis = _body_axis(shape, axes, getattr(shape, "axis", "z"))
        L = geom.number(getattr(shape, "length", 0) or 0)
        if kind in ("disk", "hollow cylinder") and abs(axis[2]) < 0.5 and L > 0:
            a = _xy(axis)
            n = np.array([-a[1], a[0]])
            corners = [centre + s1 * a * L / 2 + s2 * n * r for s1, s2 in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            out.append(ax.add_patch(patches.Polygon(corners, closed=True, **face)))
        else:
            ring = kind in ("thin ring", "spherical shell")
            if ring:
                out.append(ax.add_patch(patches.Circle(centre, r, fill=False, edgecolor=BODY_EDGE, lw=3,
                                                       alpha=alpha, zorder=zorder)))
            else:
                out.append(ax.add_patch(patches.Circle(centre, r, **face)))
            if kind == "hollow cylinder" and shape.inner_radius is not None:
                ri = geom.number(shape.inner_radius)
                out.append(ax.add_patch(patches.Circle(centre, ri, facecolor="white", edgecolor=BODY_EDGE, lw=1.2,
                                                       alpha=alpha, zorder=zorder)))
            if kind == "solid sphere":
                out.append(ax.add_patch(patches.Circle(centre + np.array([-0.3, 0.3]) * r, 0.35 * r,
                                                       facecolor="white", edgecolor="none", alpha=0.5 * alpha,
                                                       zorder=zorder)))
            # a radius fixed in the body shows its rotation
            cands = [axes[:, i] for i in range(3) if abs(np.dot(axes[:, i], axis)) < 0.5]
            mark = max(cands, key=lambda v: np.linalg.norm(v[:2]))
            tip = centre + r * _unit(_xy(mark))
            out.append(ax.plot([centre[0], tip[0]], [centre[1], tip[1]], color=BODY_EDGE, lw=1.4, alpha=alpha,
                               zorder=zorder + 0.1)[0])
    elif kind in ("half cylinder", "hemisphere"):
        r = geom.number(shape.radius)
        toward = _body_axis(shape, axes, shape.toward)
        out.append(ax.add_patch(patches.Polygon(_half_disk(ref, toward, r), closed=True, **face)))
    elif kind == "rectangular plate":
        ea, eb = _body_axis(shape, axes, shape.a_axis), _body_axis(shape, axes, shape.b_axis)
        a, b = geom.number(shape.a), geom.number(shape.b)
        corners = [_xy(np.r_[centre, 0] + s1 * ea * a / 2 + s2 * eb * b / 2)
                   for s1, s2 in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        out.append(ax.add_patch(patches.Polygon(corners, closed=True, **face)))
    elif kind == "box":
        from scipy.spatial import ConvexHull

        a, b, c = (geom.number(v) for v in (shape.a, shape.b, shape.c))
        pts = np.array([_xy(np.r_[centre, 0] + sx * axes[:, 0] * a / 2 + sy * axes[:, 1] * b / 2
                            + sz * axes[:, 2] * c / 2) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        try:
            hull = pts[ConvexHull(pts).vertices]
        except Exception:  # degenerate projection (a box seen edge-on): its bounding segment
            hull = pts
        out.append(ax.add_patch(patches.Polygon(hull, closed=True, **face)))
    elif kind == "point mass":
        out.append(ax.plot(*centre, "o", ms=13, color=BODY_EDGE, alpha=alpha, zorder=zorder)[0])
    elif kind == "massless":
        h = 0.04 * geom.scale(q)
        out.append(ax.add_patch(patches.Rectangle(centre - h, 2 * h, 2 * h, facecolor="white", edgecolor=BODY_EDGE,
                                                  lw=1.6, alpha=alpha, zorder=zorder)))
    else:  # a given inertia: a dashed circle of a representative size around the mass centre
        r = 0.1 * geom.scale(q)
        out.append(ax.add_patch(patches.Circle(centre, r, fill=False, edgecolor=BODY_EDGE, ls="--", lw=1.5,
                                               alpha=alpha, zorder=zorder)))
    # the mass centre
    if kind not in ("point mass", "massless"):
        out.append(ax.plot(*centre, marker="o", ms=7, mfc="white", mec=BODY_EDGE, mew=1.3, alpha=alpha,
                           zorder=zorder + 0.2)[0])
        out.append(ax.plot(*centre, marker="+", ms=7, color=BODY_EDGE, mew=1.1, alpha=alpha,
                           zorder=zorder + 0.3)[0])
    return out


def _hatch(ax, p0, p1, side, length, n=14, zorder=0.5):
    """Short hatch marks on ``side`` of the segment p0–p1 (a surface's solid side)."""
    segs = []
    d = p1 - p0
    side = _unit(side)
    along = _unit(d)
    for s in np.linspace(0, 1, n):
        base = p0 + s * d
        segs.append([base, base + length * (side * 0.8 - along * 0.6)])
    return ax.add_collection(LineCollection(segs, colors=SURFACE, linewidths=0.8, zorder=zorder))


def _clip_to_other_lines(geom: Geometry, q, surf, p0, p1):
    """The part of the segment p0–p1 on the bodies' side of every other fixed straight surface (a wall
    stops at the floor); the whole segment when that part would be too short to show."""
    lo, hi = 0.0, 1.0
    for _c, kind, other in surfaces(geom.system):
        if kind != "surface" or other is surf or other.kind != "line" or other.body is not None:
            continue
        n = geom.vector(other.normal, q)
        if n is None:
            continue
        n = _xy(n)
        o = _xy(geom.point(other.point, q))
        f0, f1 = float(np.dot(p0 - o, n)), float(np.dot(p1 - o, n))
        if f0 < 0 and f1 < 0:
            return p0, p1
        if f0 < 0:
            lo = max(lo, f0 / (f0 - f1))
        elif f1 < 0:
            hi = min(hi, f0 / (f0 - f1))
    if hi - lo < 0.1:
        return p0, p1
    return p0 + lo * (p1 - p0), p0 + hi * (p1 - p0)


def surfaces(system) -> list:
    """(constraint, kind, surface object) for every surface and track of the system."""
    out = []
    for c in system.constraints.values():
        if getattr(c, "surface", None) is not None:
            out.append((c, "surface", c.surface))
        elif c.kind == "collar" and c.track_body is None:
            out.append((c, "track", c))
    return out


def draw_surfaces(ax, geom: Geometry, q, span: float, alpha: float = 1.0, only=None) -> list:
    """Draw the fixed surfaces and tracks (lines hatched on the solid side, circles) of the system."""
    out = []
    seen = set()
    for c, kind, obj in surfaces(geom.system):
        if only is not None and c.name not in only:
            continue
        if kind == "surface":
            surf = obj
            if id(surf) in seen:
                continue
            seen.add(id(surf))
            if surf.kind == "line":
                p = _xy(geom.point(surf.point, q))
                n = geom.vector(surf.normal, q)
                if n is None:
                    continue
                n = _unit(_xy(n))
                tang = np.array([-n[1], n[0]])
                body_pt = _xy(geom.point(c.centre, q))
                s_body = float(np.dot(body_pt - p, tang))
                p0, p1 = p + tang * (s_body - span), p + tang * (s_body + span)
                p0, p1 = _clip_to_other_lines(geom, q, surf, p0, p1)
                out.append(ax.plot(*np.array([p0, p1]).T, color=SURFACE, lw=1.5, alpha=alpha, zorder=0.6)[0])
                out.append(_hatch(ax, p0, p1, -n, 0.06 * span, n=22, zorder=0.5))
            else:
                cen = _xy(geom.point(surf.centre, q))
                R = geom.number(surf.radius)
                out.append(ax.add_patch(patches.Circle(cen, R, fill=False, edgecolor=SURFACE, lw=1.5, alpha=alpha,
                                                       zorder=0.6)))
                outer = R * (1.06 if surf.inside else 0.94)
                out.append(ax.add_patch(patches.Circle(cen, outer, fill=False, edgecolor=SURFACE, lw=0.6,
                                                       ls=(0, (2, 2)), alpha=alpha, zorder=0.5)))
        else:
            p = _xy(geom.point(obj.through, q))
            a = geom.vector(obj.along, q)
            if a is None:
                continue
            a = _unit(_xy(a))
            body_pt = _xy(geom.point(obj.point, q))
            s_body = float(np.dot(body_pt - p, a))
            p0, p1 = p + a * (s_body - span), p + a * (s_body + span)
            out.append(ax.plot(*np.array([p0, p1]).T, color=SURFACE, lw=3, alpha=0.6 * alpha, zorder=0.6)[0])
    return out


ROPE = "#7a4b1e"


def _rope_segments(geom: Geometry, rope, q) -> list[tuple[np.ndarray, np.ndarray]]:
    """The tangent points (Q_i, Q_j) of each straight segment of a rope over pulleys (model.ropes: with signed
    radii a, b and d = C_j − C_i, n = ((a − b) d − L Ez × d)/|d|², Q_i = C_i + a n, Q_j = C_j + b n)."""
    out = []
    for si, sj in zip(rope.stations, rope.stations[1:]):
        ci, cj = _xy(geom.point(si.point, q)), _xy(geom.point(sj.point, q))
        a, b = geom.number(si.signed_radius), geom.number(sj.signed_radius)
        d = cj - ci
        d2 = float(d @ d)
        if d2 < 1e-24 or d2 < (a - b) ** 2:
            continue
        ez_d = np.array([-d[1], d[0]])
        n = ((a - b) * d - np.sqrt(d2 - (a - b) ** 2) * ez_d) / d2
        out.append((ci + a * n, cj + b * n))
    return out


def _anchor(ax, p, away, size, zorder):
    """A fixed end: a short hatched ceiling (or wall) across the rope at ``p``, on the side ``away``."""
    u = _unit(away)
    w = np.array([-u[1], u[0]])
    p0, p1 = p - w * size, p + w * size
    ax.plot(*np.array([p0, p1]).T, color=SURFACE, lw=1.5, zorder=zorder)
    _hatch(ax, p0, p1, u, 0.35 * size, n=8, zorder=zorder)


def draw_ropes(ax, geom: Geometry, q, alpha: float = 1.0, zorder: float = 1.5) -> int:
    """Draw every rope, string, belt and cable of the system at ``q``: straight segments between tangent points,
    the arcs it lies on round each pulley, and a hatched anchor where an end is fixed to the ground.  Returns
    how many ropes and cables were drawn."""
    drawn = 0
    size = 0.06 * geom.scale(q)
    for c in geom.system.constraints.values():
        if c.kind == "rope" and getattr(c, "stations", ()):
            segs = _rope_segments(geom, c, q)
            for qi, qj in segs:
                ax.plot(*np.array([qi, qj]).T, color=ROPE, lw=1.6, alpha=alpha, zorder=zorder, solid_capstyle="round")
            for k, st in enumerate(c.stations[1:-1], start=1):       # the arc on pulley k, from in to out
                if k - 1 >= len(segs) or k >= len(segs):
                    continue
                centre, r = _xy(geom.point(st.point, q)), abs(geom.number(st.signed_radius))
                t_in, t_out = (np.degrees(np.arctan2(*(p - centre)[::-1])) for p in (segs[k - 1][1], segs[k][0]))
                start, end = (t_in, t_out) if st.sign > 0 else (t_out, t_in)
                ax.add_patch(patches.Arc(centre, 2 * r, 2 * r, theta1=start, theta2=end, color=ROPE, lw=1.6,
                                         alpha=alpha, zorder=zorder + 0.6))
            for st, seg, tip in ((c.stations[0], segs[:1], 0), (c.stations[-1], segs[-1:], 1)):
                if st.body is None and seg and not st.signed_radius:
                    end, other = seg[0][tip], seg[0][1 - tip]
                    _anchor(ax, end, end - other, size, zorder)
            drawn += 1
        elif c.kind == "cable" and getattr(c, "points", ()):
            pts = np.array([_xy(geom.point(p, q)) for p in c.points])
            ax.plot(pts[:, 0], pts[:, 1], color=ROPE, lw=1.6, alpha=alpha, zorder=zorder)
            for tip, nxt, body in ((0, 1, c.bodies[0]), (-1, -2, c.bodies[-1])):
                if body is None and len(pts) > 1:
                    _anchor(ax, pts[tip], pts[tip] - pts[nxt], size, zorder)
            drawn += 1
    return drawn
