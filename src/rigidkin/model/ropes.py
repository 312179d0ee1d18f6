"""Ropes over pulleys with inertia: no slip on each pulley, a tension of its own in every straight segment.

A rope runs from one end to the other over pulleys (disk bodies on fixed or moving axles), in the
plane of motion; an end may be a drum the rope is wound on (its end fixed to the drum).  Each pulley
is a :class:`Wrap`: the body, its radius and the sense in which the rope goes round it (``"cw"``: the
pulley on the right of the rope as it runs from the first end to the last; ``"ccw"``: on its left).
Between two stations the rope is a straight segment along their common tangent.  With signed radii
a = σ_i r_i and b = σ_j r_j (σ = +1 counter-clockwise, −1 clockwise) and d = C_j − C_i between the
centres, the segment's direction e and the right normal n = e × Ez are

    n = ((a − b) d − L Ez × d)/|d|²,   e = Ez × n = (L d + (a − b) Ez × d)/|d|²,   L = √(|d|² − (a − b)²),

and its tangent points are Q_i = C_i + a n, Q_j = C_j + b n (an end is a station of radius 0).

No slip: where the rope leaves or meets a pulley it moves with the pulley's rim, so each segment's
ends move with the material points of the bodies at its tangent points, and an inextensible segment
keeps (v(Q_j) − v(Q_i))·e = 0.  That is one constraint row per segment; its reaction is the segment's
tension T_k, pulling the station before along +e at Q_i and the station after along −e at Q_j.  The
tensions on the two sides of a pulley differ by what its inertia and bearing need (the rope's grip
carries the difference).  The rows are workless (the power of T_k is −T_k times the row), and every
tension must stay ≥ 0: a rope can only pull (validity conditions "… is taut").
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector

from ..base.errors import ModelError
from .constraints import Constraint, Row
from .loads import Application, moves_in
from .points import Point

_SENSES = {"cw": -1, "clockwise": -1, "ccw": 1, "counterclockwise": 1, "counter-clockwise": 1}


@dataclass(frozen=True, eq=False)
class Wrap:
    """The rope passes round ``body`` (a pulley, drum or wheel) at ``radius`` from ``centre`` (default: the
    body's reference point), clockwise (``"cw"``) or counter-clockwise (``"ccw"``) as it runs from the
    first end to the last."""

    body: object
    radius: sp.Expr
    sense: str = "cw"
    centre: Point | None = None
    mu: sp.Expr | None = None      # belt friction on it: no slip while T_tight ≤ T_slack e^{µ φ}

    @property
    def sign(self) -> int:
        return _SENSES[self.sense]


@dataclass(frozen=True, eq=False)
class _Station:
    point: Point          # an end point, or the pulley's centre
    body: object          # the body whose material point the rope moves with there (None: the ground)
    signed_radius: sp.Expr
    label: str
    mu: sp.Expr | None = None
    sign: int = 0         # +1: the rope goes round counter-clockwise, −1 clockwise (0: an end)


@dataclass(eq=False)
class Rope(Constraint):
    """An inextensible rope from ``stations[0]`` to ``stations[-1]`` over pulleys, not slipping on them."""

    stations: tuple = ()
    tension_names: tuple = ()

    kind = "rope"
    states = ("taut", "open")

    @property
    def tensions(self) -> list[sp.Symbol]:
        return [sp.Symbol(n, real=True) for n in self.tension_names]

    def reactions(self):
        return self.tensions

    def reaction_label(self, sym) -> str:
        """``tension of rope r between A and pulley``: what each reaction is, for printed results."""
        k = self.tension_names.index(sym.name)
        return f"tension of rope {self.name} between {self.stations[k].label} and {self.stations[k + 1].label}"

    def _span(self, kin, k: int):
        si, sj = self.stations[k], self.stations[k + 1]
        Ci, Cj = kin.position(si.point), kin.position(sj.point)
        d = kin.simplify_vector(Cj - Ci)
        a, b = si.signed_radius, sj.signed_radius
        D2 = kin.simplify_expr(d.dot(d))
        L = kin.magnitude(d) if a == b else _root(kin, D2 - (a - b) ** 2)
        return Ci, Cj, d, a, b, D2, L

    def length(self, kin, k: int = 0) -> sp.Expr:
        """L = √(|d|² − (a − b)²): the straight length of segment k between its tangent points."""
        return self._span(kin, k)[-1]

    def segment(self, kin, k: int) -> tuple[Vector, Vector, Vector]:
        """(e, Q_k, Q_{k+1}): the direction and tangent points of segment k (positions from the origin)."""
        Ci, Cj, d, a, b, D2, L = self._span(kin, k)
        ez = kin.F.z
        n = kin.simplify_vector(((a - b) * d - L * ez.cross(d)) / D2)
        e = kin.simplify_vector((L * d + (a - b) * ez.cross(d)) / D2)
        return e, Ci + a * n, Cj + b * n

    def rows(self, kin, state):
        if state == "open":
            return []
        if not kin.planar:
            raise ModelError("ropes over pulleys are planar (the plane of Ex, Ey) only.", where=f"rope {self.name}")
        out = []
        for k, T in enumerate(self.tensions):
            si, sj = self.stations[k], self.stations[k + 1]
            e, Qi, Qj = self.segment(kin, k)
            vi = self._velocity(kin, si, Qi)
            vj = self._velocity(kin, sj, Qj)
            apps = []
            if si.body is not None:
                apps.append(Application(si.body, None, T * e, f"rope tension {T} on {si.body.name}", self.name,
                                        reaction=T, location=Qi))
            if sj.body is not None:
                apps.append(Application(sj.body, None, -T * e, f"rope tension {T} on {sj.body.name}", self.name,
                                        reaction=T, location=Qj))
            velocity = kin.simplify_expr((vj - vi).dot(e))
            out.append(Row(self.name, f"rope {self.name}: segment {si.label}–{sj.label} inextensible, no slip",
                           velocity, T, tuple(apps), unilateral=True, kind="tension"))
        return out

    def validity(self, setup, react) -> list[tuple[sp.Expr, str]]:
        """Belt friction (capstan): on a pulley with ``mu`` the rope grips while each side's tension is at
        most e^{µφ} times the other's, φ the wrap angle (the turn from the incoming segment's direction to
        the outgoing one's, in the wrap's sense, in (0, 2π]).  (expression ≥ 0, label) pairs."""
        kin, out = setup.kin, []
        ez = kin.F.z
        for k in range(1, len(self.stations) - 1):
            st = self.stations[k]
            if st.mu is None:
                continue
            e_in, e_out = self.segment(kin, k - 1)[0], self.segment(kin, k)[0]
            y = kin.simplify_expr(st.sign * e_in.cross(e_out).dot(ez))
            x = kin.simplify_expr(e_in.dot(e_out))
            phi = sp.pi + sp.atan2(-y, -x)
            grip = sp.exp(st.mu * phi)
            t_in = react.get(self.tension_names[k - 1], self.tensions[k - 1])
            t_out = react.get(self.tension_names[k], self.tensions[k])
            label = f"rope {self.name} grips {st.label} (|T| ratio ≤ e^(µφ), φ = {phi})"
            out.append((kin.simplify_expr(setup.scalar(t_in * grip - t_out)), label))
            out.append((kin.simplify_expr(setup.scalar(t_out * grip - t_in)), label))
        return out

    @staticmethod
    def _velocity(kin, station, location):
        if station.signed_radius == 0:
            return kin.velocity(station.point)          # an end: a material point of its body (checked)
        return kin.material_velocity(station.body, location)


def _root(kin, square) -> sp.Expr:
    """√square (a segment's length), with |x| resolved by the sign of x in the reference configuration, as
    Kinematics.magnitude does; where x is zero there (no initial values), x itself (a length as written)."""
    root = sp.sqrt(sp.factor(sp.trigsimp(sp.expand(square))))
    if root.has(sp.Abs):
        ref = kin.reference_values()
        repl = {}
        for a in root.atoms(sp.Abs):
            try:
                val = float(a.args[0].subs(ref))
            except (TypeError, ValueError):
                val = 0.0
            repl[a] = -a.args[0] if val < 0 else a.args[0]
            note = f"|{a.args[0]}| = {repl[a]} (the length of a rope segment, positive)"
            if note not in kin.assumptions:
                kin.assumptions.append(note)
        root = root.xreplace(repl)
    return root


def build_rope(system, name: str, path, tensions=None, description: str = "") -> Rope:
    """The Rope ``name`` along ``path``: end, Wrap…, end.  An end is a point (of the body it is fixed in,
    or the ground) or ``(point, body)``; ``tensions`` names the segments' tensions (default T_name_1 …)."""
    where = f"rope {name}"
    path = list(path)
    if len(path) < 2:
        raise ModelError("a rope needs its two ends (and the pulleys between them).", where=where)
    stations = []
    for k, item in enumerate(path):
        end = k in (0, len(path) - 1)
        if isinstance(item, Wrap):                 # at an end: the rope is wound on it (a drum), end fixed to it
            if item.sense not in _SENSES:
                raise ModelError(f"the sense of a wrap is 'cw' or 'ccw', not {item.sense!r}.", where=where)
            body = system._check_body(item.body, where)
            centre = system._check_point(item.centre, where) if item.centre is not None else body.reference
            if moves_in(centre, body, system.inertial.ref):
                raise ModelError(f"the centre {centre.name} of the pulley {body.name} is not fixed in it.", where=where)
            r = sp.sympify(item.radius)
            if r.is_positive is False or r == 0:
                raise ModelError(f"the radius of the pulley {body.name} must be positive.", where=where)
            mu = None if item.mu is None else sp.sympify(item.mu)
            stations.append(_Station(centre, body, item.sign * r, body.name, mu, item.sign))
            continue
        if not end:
            raise ModelError(f"station {k + 1} of the rope is a point; between the ends a rope runs over pulleys "
                             "(rigidkin.model.ropes.Wrap).", where=where)
        point, body = (item if isinstance(item, tuple) else (item, None))
        point = system._check_point(point, where)
        body = system._check_body(body, where, True) if body is not None else point.body
        if moves_in(point, body, system.inertial.ref):
            owner = f"body {body.name}" if body is not None else "the ground"
            raise ModelError(f"the end {point.name} of the rope moves relative to {owner}, so it is not a point of "
                             "it.", where=where, hint="Fix the end in the body the rope pulls (body = ...).")
        stations.append(_Station(point, body, sp.Integer(0), point.name))
    n = len(stations) - 1
    if tensions is None:
        tensions = [f"T_{name}" if n == 1 else f"T_{name}_{k + 1}" for k in range(n)]
    tensions = list(tensions)
    if len(tensions) != n:
        raise ModelError(f"the rope has {n} segments, so it needs {n} tension names, not {len(tensions)}.",
                         where=where)
    return Rope(name, stations=tuple(stations), tension_names=tuple(tensions), description=description)
