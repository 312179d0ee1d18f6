"""Animation of a three-dimensional motion with matplotlib's 3D axes.

``Scene3D`` turns the model's positions and body frames into numeric functions of the coordinates
(straight from the kinematics, with no constraint elimination, so it also serves the bicycle) and
draws each body by its shape: disks and rings as their rims with a spoke that shows the spin, rods
as segments, boxes as wire frames, spheres as three great circles, and every body as the skeleton
joining its mass centre to the points fixed in it.  A thin disk that touches a plane
(:class:`rigidkin.model.rolling3d.DiskContact`) is drawn as its rim whatever its shape is declared
as (the bicycle's wheels are given by their inertia only).  Planes are drawn as a grid under the
motion; each mass centre leaves a trail.  ``animate3d`` plays a rigidkin simulation result, or
any sampled motion (times and coordinate values), as a :class:`rigidkin.report.animate.MotionAnimation`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import sympy as sp  # noqa: E402
from matplotlib.animation import FuncAnimation  # noqa: E402
from sympy.physics.vector import Vector, dynamicsymbols  # noqa: E402

from ..base.errors import InputError  # noqa: E402
from ..base.textsafe import figure_text  # noqa: E402
from ..derive.kinematics import Kinematics  # noqa: E402
from ..model import shapes as S  # noqa: E402
from ..model.rolling3d import DiskContact  # noqa: E402
from ..model.surfaces import Line  # noqa: E402
from ..numeric.compiled.codesafe import safe_lambdify  # noqa: E402
from .animate import MotionAnimation  # noqa: E402

t = dynamicsymbols._t

_COLOURS = ["#1f5fa8", "#c0392b", "#2e8b57", "#8e44ad", "#d35400", "#2c3e50"]


class Scene3D:
    """Numeric positions of a system's points, body axes and rims at any configuration."""

    def __init__(self, system, values: Mapping | None = None):
        self.system = system
        self.kin = kin = Kinematics(system)
        F = kin.F.ref
        params = dict(system.parameter_values())
        for k, v in (values or {}).items():
            params[system.parameters[k] if isinstance(k, str) else k] = v
        missing = [p for p in system.parameters.values() if p not in params]
        if missing:
            raise InputError(f"the parameters {', '.join(map(str, missing))} have no values to draw with.",
                             where=f"animation of {system.name}", hint="Pass values={name: number}.")
        self.params = {k: sp.Float(v) for k, v in params.items()}
        self.coordinates = tuple(system.coordinates)
        qs = [sp.Symbol(f"_q{i}", real=True) for i in range(len(self.coordinates))]
        self._args = qs + [sp.Symbol("_time", real=True)]
        self._rep = dict(zip(self.coordinates, qs))

        def num(M):
            return safe_lambdify(self._args, M.xreplace(self._rep).xreplace({t: self._args[-1]}).xreplace(self.params),
                                 cse=False, where="animation")

        def comps(v):
            return v.to_matrix(F) if v != Vector(0) else sp.zeros(3, 1)

        self._points = {n: num(comps(kin.position(p))) for n, p in system.points.items()}
        self._axes = {n: num(sp.Matrix.hstack(*[comps(v) for v in (b.frame.x, b.frame.y, b.frame.z)]))
                      for n, b in system.bodies.items()}
        self.rims = {}       # body name → (centre point name, axis function, radius)
        for c in system.constraints.values():
            if isinstance(c, DiskContact):
                self.rims[c.body.name] = (c.centre.name, num(comps(c.axis)), float(c.radius.xreplace(self.params)))
        self.planes = [c.surface for c in system.constraints.values()
                       if isinstance(getattr(c, "surface", None), Line) and c.surface.body is None]
        self._plane_fns = [(num(comps(kin.position(pl.point))), num(comps(pl.normal))) for pl in self.planes]

    # numbers -----------------------------------------------------------------------------------
    def _vec(self, q) -> list:
        if isinstance(q, Mapping):
            return [float(q[c]) for c in self.coordinates] + [float(q.get(t, 0.0))]
        q = list(q)
        return [float(x) for x in q[:len(self.coordinates)]] + [float(q[len(self.coordinates)])
                                                               if len(q) > len(self.coordinates) else 0.0]

    def point(self, name: str, q) -> np.ndarray:
        return np.asarray(self._points[name](*self._vec(q)), dtype=float).reshape(3)

    def axes(self, body: str, q) -> np.ndarray:
        """Columns: the body frame's unit vectors in the inertial basis."""
        return np.asarray(self._axes[body](*self._vec(q)), dtype=float).reshape(3, 3)

    def rim(self, body: str, q, n: int = 48) -> np.ndarray:
        """Points (n × 3) of the rim of a disk-like body: its disk contact's, or its Disk/ThinRing shape's."""
        b = self.system.bodies[body]
        if body in self.rims:
            centre, axis_fn, r = self.rims[body]
            c = self.point(centre, q)
            a = np.asarray(axis_fn(*self._vec(q)), dtype=float).reshape(3)
        elif isinstance(b.shape, (S.Disk, S.ThinRing)):
            c = self.point(b.centre.name, q)
            a = self.axes(body, q) @ _unit_of(b.frame, b.shape.axis)
            r = float(sp.sympify(b.shape.radius).xreplace(self.params))
        else:
            raise InputError(f"body {body} is not a disk or a ring.", where="animation")
        a = a / np.linalg.norm(a)
        e1 = np.cross(a, [0.0, 0.0, 1.0])
        if np.linalg.norm(e1) < 1e-6:
            e1 = np.cross(a, [1.0, 0.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(a, e1)
        s = np.linspace(0, 2 * np.pi, n)
        return c + r * (np.outer(np.cos(s), e1) + np.outer(np.sin(s), e2))

    # drawing -----------------------------------------------------------------------------------
    def segments(self, q) -> list[tuple[np.ndarray, str]]:
        """Polylines (k × 3 arrays) to draw for each body at ``q``, with their colours."""
        out = []
        for i, (name, b) in enumerate(self.system.bodies.items()):
            col = _COLOURS[i % len(_COLOURS)]
            G = self.point(b.centre.name, q)
            R = self.axes(name, q)
            sh = b.shape
            if name in self.rims or isinstance(sh, (S.Disk, S.ThinRing)):
                rim = self.rim(name, q)
                out.append((rim, col))
                centre = self.point(self.rims[name][0], q) if name in self.rims else G
                r = np.linalg.norm(rim[0] - centre)
                out.append((np.array([centre, centre + r * R[:, 0]]), col))     # a spoke shows the spin
            elif isinstance(sh, S.SlenderRod):
                half = float(sp.sympify(sh.length).xreplace(self.params)) / 2
                u = R @ _unit_of(b.frame, sh.axis)
                out.append((np.array([G - half * u, G + half * u]), col))
            elif isinstance(sh, S.Box):
                out += [(e, col) for e in _box_edges(G, R, [float(sp.sympify(x).xreplace(self.params))
                                                            for x in (sh.a, sh.b, sh.c)])]
            elif isinstance(sh, (S.SolidSphere, S.SphericalShell)):
                r = float(sp.sympify(sh.radius).xreplace(self.params))
                s = np.linspace(0, 2 * np.pi, 48)
                for i1, i2 in ((0, 1), (1, 2), (2, 0)):
                    out.append((G + r * (np.outer(np.cos(s), R[:, i1]) + np.outer(np.sin(s), R[:, i2])), col))
            joints = [p for p in self.system.points.values() if p.body is b and p is not b.centre]
            for c in self.system.constraints.values():       # the joints a body is pinned at
                if getattr(c, "kind", "") == "pin":
                    if c.body_a is b:
                        joints.append(c.point)
                    if c.body_b is b:
                        joints.append(c.point_b or c.point)
            for p in dict.fromkeys(joints):
                out.append((np.array([G, self.point(p.name, q)]), col))
        return out

    def extent(self, qs: Sequence) -> tuple[np.ndarray, float]:
        """Centre and half-width of a cube that holds every point and rim over the motion."""
        pts = [self.point(n, q) for q in qs for n in self.system.points]
        for q in qs[:: max(1, len(qs) // 10)]:
            for seg, _ in self.segments(q):
                pts.extend(seg)
        pts = np.array(pts)
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        half = max(float((hi - lo).max()) / 2 * 1.1, 1e-3)
        return (lo + hi) / 2, half


def _unit_of(frame, spec: str) -> np.ndarray:
    v = frame.unit(spec)
    return np.array([float(v.dot(e)) for e in (frame.x, frame.y, frame.z)])


def _box_edges(G, R, sides) -> list[np.ndarray]:
    a, b, c = (x / 2 for x in sides)
    corners = {(i, j, k): G + R @ np.array([i * a, j * b, k * c]) for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)}
    edges = []
    for (i, j, k), p in corners.items():
        for d in range(3):
            idx = [i, j, k]
            if idx[d] < 0:
                idx[d] = 1
                edges.append(np.array([p, corners[tuple(idx)]]))
    return edges


def _samples(system, result, times, states, frames):
    """Times and coordinate vectors (every coordinate, in declaration order) to draw."""
    coords = list(system.coordinates)
    if result is not None:
        t0, t1 = float(result.t[0]), float(result.t_final)
        ts = np.linspace(t0, t1, max(2, frames))
        names = [c.func.__name__ for c in coords]
        qs = []
        for tt in ts:
            st = result.at(float(tt))
            qs.append([float(st[nm]) for nm in names] + [float(tt)])
        return ts, qs
    if times is None or states is None:
        raise InputError("give a simulation result, or times and states (one row of coordinates per time).",
                         where="animate3d")
    ts = np.asarray(times, dtype=float)
    arr = np.asarray(states, dtype=float)
    if arr.ndim != 2 or arr.shape[0] != len(ts) or arr.shape[1] < len(coords):
        raise InputError(f"states must have one row per time and at least {len(coords)} columns (the coordinates "
                         f"{', '.join(c.func.__name__ for c in coords)}), not shape {arr.shape}.", where="animate3d")
    pick = np.linspace(0, len(ts) - 1, min(len(ts), max(2, frames))).round().astype(int)
    return ts[pick], [list(arr[i, :len(coords)]) + [float(ts[i])] for i in pick]


def animate3d(system, result=None, *, times=None, states=None, frames: int = 80, duration: float | None = None,
              size: float = 5.0, dpi: int = 80, trail: bool = True, values: Mapping | None = None,
              elev: float = 25.0, azim: float = -60.0, z_down: bool = False) -> MotionAnimation:
    """Animate a 3D motion: a rigidkin ``SimulationResult`` of ``system``, or ``times`` with ``states``
    (rows of every coordinate's value, e.g. the first columns of a ProjectedModel's solve_ivp result).

    ``z_down`` flips the vertical axis of the view for models whose Ez points down (the bicycle).
    """
    scene = Scene3D(system, values)
    ts, qs = _samples(system, result, times, states, frames)
    span = float(ts[-1] - ts[0]) or 1.0
    play = duration or min(max(span, 2.0), 12.0)
    fps = max(1.0, len(ts) / play)
    speed = span / (len(ts) / fps)
    centre, half = scene.extent(qs)
    trails = {b.name: np.array([scene.point(b.centre.name, q) for q in qs]) for b in system.bodies.values()}
    fig = plt.figure(figsize=(size, size), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    planes = []
    for pfn, nfn in scene._plane_fns:
        p0 = np.asarray(pfn(*scene._vec(qs[0])), dtype=float).reshape(3)
        nrm = np.asarray(nfn(*scene._vec(qs[0])), dtype=float).reshape(3)
        planes.append((p0, nrm / np.linalg.norm(nrm)))

    def draw(i):
        ax.clear()
        q = qs[i]
        for p0, nrm in planes:
            _draw_plane(ax, p0, nrm, centre, half)
        for seg, col in scene.segments(q):
            ax.plot(seg[:, 0], seg[:, 1], seg[:, 2], color=col, lw=1.6)
        if trail and i > 0:
            for tr in trails.values():
                ax.plot(tr[: i + 1, 0], tr[: i + 1, 1], tr[: i + 1, 2], color="#9aa9bb", lw=0.8)
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(*((centre[2] + half, centre[2] - half) if z_down else (centre[2] - half, centre[2] + half)))
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        ax.set_title(f"{figure_text(system.title)}   t = {ts[i]:.3f} s", fontsize=9)
        return []

    anim = FuncAnimation(fig, draw, frames=len(ts), interval=1000.0 / fps, blit=False, repeat=False)
    return MotionAnimation(anim, fig, np.asarray(ts), fps, speed)


def _draw_plane(ax, p0, nrm, centre, half):
    """A grid on the plane through p0 with normal nrm, around the motion's centre."""
    e1 = np.cross(nrm, [0.0, 0.0, 1.0])
    if np.linalg.norm(e1) < 1e-6:
        e1 = np.cross(nrm, [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(nrm, e1)
    c = centre - np.dot(centre - p0, nrm) * nrm
    for s in np.linspace(-half, half, 7):
        for u, v in ((e1, e2), (e2, e1)):
            a, b = c + s * u - half * v, c + s * u + half * v
            ax.plot([a[0], b[0]], [a[1], b[1]], [a[2], b[2]], color="#c8ced6", lw=0.6)
