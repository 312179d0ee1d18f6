"""Numbers for drawings: where the points and bodies of a system are in a given configuration.

``Geometry`` turns the model's position vectors and body frames into fast numeric functions of the
coordinates (all of them, independent and dependent), with the parameters at their values.  A
*configuration* gives every coordinate a number: the ones given, else the declared initial values;
coordinates that a constraint makes dependent follow from its integrated relation (x = l sin θ).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy as sp
from sympy.physics.vector import Dyadic, Vector, dynamicsymbols

from ..base import algebra
from ..base.errors import InputError
from ..derive.mode import setup_mode
from ..numeric.compiled.codesafe import safe_lambdify

t = dynamicsymbols._t


def _key(system, k):
    """A coordinate (dynamicsymbol) from a name, a symbol or a dynamicsymbol (``t``: the time)."""
    if k == "t":
        return t
    if isinstance(k, str):
        info = system.coordinate_info.get(k)
        if info is None:
            raise InputError(f"'{k}' is not a coordinate of {system.name}.", where="configuration",
                             hint=f"Coordinates: {', '.join(system.coordinate_info)}.")
        return info.symbol
    return k


class Geometry:
    """Numeric positions and orientations of a system's points and bodies (parameters at their values).

    Components are in the inertial basis for a planar model; a 3D model is seen from the side, with
    gravity pointing down the screen (``view``: the rows are the screen's right, up and depth).

    ``values`` overrides parameter values (symbol or name → number); a parameter without a value is
    drawn at 1 and listed in ``assumed``.
    """

    def __init__(self, system, setup=None, values: Mapping | None = None):
        self.system = system
        self.setup = setup or setup_mode(system)
        self.F = system.inertial
        self.coordinates = tuple(system.coordinates)
        self.assumed: list[str] = []
        params = dict(system.parameter_values())
        for name, info in system.parameter_info.items():
            if info.symbol not in params:
                params[info.symbol] = 1.0
                self.assumed.append(name)
        for k, v in (values or {}).items():
            sym = system.parameters.get(k) if isinstance(k, str) else k
            if sym is None:
                raise InputError(f"'{k}' is not a parameter of {system.name}.", where="configuration")
            params[sym] = float(v)
        self.params = {k: sp.Float(v) for k, v in params.items()}
        self._qsyms = [sp.Symbol(f"_q{i}", real=True) for i in range(len(self.coordinates))]
        self._tsym = sp.Symbol("_time", real=True)
        self._qmap = dict(zip(self.coordinates, self._qsyms))
        self._args = [*self._qsyms, self._tsym]
        kin = self.setup.kin
        self.view = np.eye(3) if kin.planar else self._view()
        self._points = {}
        for name, p in system.points.items():
            self._points[name] = self._lambdify(kin.position(p))
        self._axes = {}
        for name, b in system.bodies.items():
            cols = [self._components(v) for v in (b.frame.x, b.frame.y, b.frame.z)]
            self._axes[name] = safe_lambdify(self._args, sp.Matrix.hstack(*cols), cse=False, where="drawing")

    def _view(self) -> np.ndarray:
        """Rows: the screen's right, up and depth directions for a 3D model — up against gravity (Ey if
        there is none), right the horizontal direction nearest to Ex."""
        up = np.array([0.0, 1.0, 0.0])
        for ld in self.system.loads.values():
            if ld.kind == "gravity":
                d = np.array([float(c) for c in ld.direction.to_matrix(self.F.ref).xreplace(self.params)])
                up = -d / np.linalg.norm(d)
        right = np.array([1.0, 0.0, 0.0]) - up[0] * up
        if np.linalg.norm(right) < 1e-6:
            right = np.array([0.0, 1.0, 0.0]) - up[1] * up
        right /= np.linalg.norm(right)
        return np.vstack([right, up, np.cross(right, up)])

    # symbolic → numeric ----------------------------------------------------------------------------
    def _components(self, v: Vector) -> sp.Matrix:
        m = v.to_matrix(self.F.ref) if v != Vector(0) else sp.zeros(3, 1)
        return m.xreplace(self._qmap).xreplace({t: self._tsym}).xreplace(self.params)

    def _lambdify(self, v: Vector):
        return safe_lambdify(self._args, self._components(v), cse=False, where="drawing")

    def _vector(self, q: Mapping) -> list[float]:
        """The arguments of the numeric functions: every coordinate, then the time (key ``t``, default 0)."""
        return [float(q[c]) for c in self.coordinates] + [float(q.get(t, 0.0))]

    # configurations ----------------------------------------------------------------------------------
    def configuration(self, values: Mapping | None = None) -> dict:
        """Every coordinate → a number: given values, else initial values (0 when none is declared);
        dependent coordinates from their integrated constraint relations.  The time ``t`` (key ``t``,
        default 0) places surfaces and points that move with time."""
        given = {_key(self.system, k): float(v) for k, v in (values or {}).items()}
        out = {t: given.pop(t, 0.0)}
        for info in self.system.coordinate_info.values():
            if info.symbol in given:
                out[info.symbol] = given[info.symbol]
            elif info.initial is not None:
                out[info.symbol] = float(info.initial)
            else:
                out[info.symbol] = 0.0
        coord_map = self.setup.reduction.coord_map
        for qd, expr in coord_map.items():
            if qd in given:
                continue
            val = self.evaluate(expr, out)
            if val is not None:
                out[qd] = val
        return out

    def evaluate(self, expr, q: Mapping, extra: Mapping | None = None, rates: float = 0.0) -> float | None:
        """A scalar at configuration ``q`` (rates set to ``rates``; other unknowns from ``extra``)."""
        plain, back = algebra.plain_state(sp.sympify(expr))
        subs = {}
        for s, orig in back.items():
            if isinstance(orig, sp.Derivative):
                subs[s] = sp.Float(rates)
            elif orig in q:
                subs[s] = sp.Float(q[orig])
        val = plain.xreplace(subs).xreplace({t: sp.Float(q.get(t, 0.0))}).xreplace(self.params)
        if extra:
            val = val.xreplace({k: sp.Float(v) for k, v in extra.items()})
        try:
            z = complex(sp.N(val))
        except (TypeError, ValueError):
            return None
        return z.real if abs(z.imag) < 1e-9 * max(1.0, abs(z.real)) else None

    def vector(self, v: Vector, q: Mapping, extra: Mapping | None = None, rates: float = 0.0) -> np.ndarray | None:
        """A vector's components in the inertial basis at ``q`` (None where they are not numbers)."""
        if isinstance(v, Dyadic) or v == Vector(0):
            return np.zeros(3)
        comps = v.to_matrix(self.F.ref)
        out = [self.evaluate(c, q, extra, rates) for c in comps]
        if any(c is None for c in out):
            return None
        return self.view @ np.array(out, dtype=float)

    # where things are ----------------------------------------------------------------------------------
    def point(self, point, q: Mapping) -> np.ndarray:
        name = point if isinstance(point, str) else point.name
        return self.view @ np.asarray(self._points[name](*self._vector(q)), dtype=float).reshape(3)

    def axes(self, body, q: Mapping) -> np.ndarray:
        """The body frame's unit vectors (columns) in the inertial basis."""
        name = body if isinstance(body, str) else body.name
        return self.view @ np.asarray(self._axes[name](*self._vector(q)), dtype=float).reshape(3, 3)

    def number(self, expr) -> float:
        """A parameter expression (a length, a radius) as a number."""
        return float(sp.sympify(expr).xreplace(self.params))

    def scale(self, q: Mapping) -> float:
        """A characteristic length of the drawing: the spread of the points and the sizes of the shapes."""
        pts = np.array([self.point(n, q) for n in self.system.points])
        spread = float(np.ptp(pts[:, :2], axis=0).max()) if len(pts) > 1 else 0.0
        sizes = [body_size(b, self) for b in self.system.bodies.values()]
        return max([spread, *sizes, 1e-9]) or 1.0


def body_size(body, geom: Geometry) -> float:
    """The largest dimension of a body's shape (0 for a particle)."""
    kind = body.shape.kind
    if kind in ("given inertia", "massless", "point mass"):
        return 0.0
    dims = [abs(geom.number(v)) for k, v in body.shape.dimensions.items() if v is not None and k != "centre"]
    if kind in ("disk", "thin ring", "hollow cylinder", "solid sphere", "spherical shell", "half cylinder",
                "hemisphere"):
        dims = [2 * abs(geom.number(body.shape.radius))] + dims
    return max(dims, default=0.0)
