"""Generalised speeds u that differ from the coordinate rates q̇, and the kinematic equations q̇ = W(q) u.

Most problems take the rates of the coordinates as their speeds (u = q̇).  A 3D body is better
described, as in Kane's method, by the components of its angular velocity along its own basis:
``ω = w₁ b₁ + w₂ b₂ + w₃ b₃``.  Then the equations of motion are written in ẇ, and the coordinates
follow from the *kinematic differential equations* q̇ = W(q) w.

* Euler parameters (a unit quaternion e = e₀ + e₁ i + e₂ j + e₃ k) orient a frame without a singular
  configuration; with the body's angular velocity components as speeds
  ė = ½ Q(e) w,   Q(e) = [[−e₁, −e₂, −e₃], [e₀, −e₃, e₂], [e₃, e₀, −e₁], [−e₂, e₁, e₀]],
  which keeps |e| constant exactly (d|e|²/dt = eᵀQ(e)w = 0).  The frame's direction cosines are
  those of e/|e| (the rotation does not depend on |e|), so every identity of the kinematics holds
  at any e ≠ 0 and a numeric drift of |e| changes nothing physical; the simulator projects |e|
  back to 1 by a stabilisation term (see :func:`quaternion_rates`).
* Euler angles (a rotation sequence, or a chain of single-axis frames) may take the same speeds on
  request: ω·bᵢ = Σ Y_ij(q) q̇_j is solved for the angles' rates, q̇ = Y(q)⁻¹ (w − …), singular where
  the sequence is (that is the sequence's own singularity, now only in q̇, not in the dynamics).

``SpeedGroup`` holds one such set; ``KinematicEquations`` gathers, for a whole system, its
configuration variables q, its speeds u (q̇ where nothing else is said) and the map q̇ → W(q) u.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base.errors import ModelError

t = dynamicsymbols._t

#: Rate of the stabilisation term that pulls |e| back to 1 in simulation: ė = ½Q(e)w + k(1 − |e|²)e,
#: per unit of the speeds' scale (1/s).  The rotation is that of e/|e|, so the term changes nothing physical.
STABILISATION = 1.0


def quaternion_matrix(e) -> sp.Matrix:
    """Q(e) (4 × 3): ė = ½ Q(e) w for body-frame angular velocity components w."""
    e0, e1, e2, e3 = e
    return sp.Matrix([[-e1, -e2, -e3], [e0, -e3, e2], [e3, e0, -e1], [-e2, e1, e0]])


def quaternion_dcm(e, normalised: bool = True) -> sp.Matrix:
    """``child.dcm(parent)`` of the rotation by the quaternion e (scalar first): row i is bᵢ in the
    parent's basis.  ``normalised``: that of e/|e| (orthogonal for any e ≠ 0)."""
    e0, e1, e2, e3 = e
    R = sp.Matrix([
        [e0**2 + e1**2 - e2**2 - e3**2, 2 * (e1 * e2 + e0 * e3), 2 * (e1 * e3 - e0 * e2)],
        [2 * (e1 * e2 - e0 * e3), e0**2 - e1**2 + e2**2 - e3**2, 2 * (e2 * e3 + e0 * e1)],
        [2 * (e1 * e3 + e0 * e2), 2 * (e2 * e3 - e0 * e1), e0**2 - e1**2 - e2**2 + e3**2]])
    if normalised:
        R = R / (e0**2 + e1**2 + e2**2 + e3**2)
    return R


def quaternion_rates(e, w, stabilisation=0) -> sp.Matrix:
    """ė = ½ Q(e) w (+ k (1 − |e|²) e with ``stabilisation`` k, which pulls a drifted |e| back to 1)."""
    rates = quaternion_matrix(e) * sp.Matrix(w) / 2
    if stabilisation:
        n2 = sum(x**2 for x in e)
        rates += stabilisation * (1 - n2) * sp.Matrix(e)
    return rates


def quaternion_from_axis_angle(axis, angle) -> tuple:
    """(cos θ/2, sin θ/2 n) for a rotation by ``angle`` about the unit ``axis`` (3 numbers)."""
    import math

    n = math.sqrt(sum(float(a) ** 2 for a in axis))
    if n == 0:
        raise ModelError("the axis of a rotation must not be zero.", where="quaternion")
    s = math.sin(float(angle) / 2) / n
    return (math.cos(float(angle) / 2), *(float(a) * s for a in axis))


@dataclass(eq=False)
class SpeedGroup:
    """Speeds that replace the rates of some coordinates: ``speeds`` (dynamicsymbols w(t)), and the
    kinematic equations ``qdot`` (q̇_j → expression of q and speeds) for ``coordinates``.

    ``kind`` is ``"quaternion"`` (Euler parameters of ``frame``) or ``"angular"`` (angles with the
    frame's angular-velocity components as speeds).  ``initial`` holds the speeds' initial values."""

    frame: object
    coordinates: tuple
    speeds: tuple
    qdot: dict
    kind: str
    names: tuple
    initial: tuple = (None, None, None)
    quasi: tuple = ()          # quasi-coordinates π with π̇ = w (what the symbolic core integrates)

    @property
    def W(self) -> sp.Matrix:
        """∂q̇/∂u over this group's coordinates and speeds."""
        rows = [self.qdot[q.diff(t)] for q in self.coordinates]
        return sp.Matrix(rows).jacobian(list(self.speeds))

    def equations(self) -> list[tuple]:
        """(q̇_j, W(q) u) pairs, for the trace."""
        return [(q.diff(t), self.qdot[q.diff(t)]) for q in self.coordinates]


def angular_group(frame, parent_ref, coordinates, names, inertial_ref) -> SpeedGroup:
    """Kane's choice for a frame oriented by angles: w_i = ω·b_i (ω of ``frame`` in the inertial frame),
    solved for the rates of ``coordinates``; the rates of other coordinates in ω stay as they are."""
    w = tuple(dynamicsymbols(n, real=True) for n in names)
    omega = frame.ref.ang_vel_in(inertial_ref)
    comps = [omega.dot(b) for b in (frame.x, frame.y, frame.z)]
    rates = [q.diff(t) for q in coordinates]
    dummies = [sp.Dummy(f"r{i}") for i in range(len(rates))]
    fwd = dict(zip(rates, dummies))
    eqs = [sp.expand(sp.sympify(c).xreplace(fwd)) - wi for c, wi in zip(comps, w)]
    Y = sp.Matrix(eqs).jacobian(dummies)
    where = f"frame {frame.name}"
    if any(sp.sympify(c).has(*[q.diff(t, 2) for q in coordinates]) for c in comps):
        raise ModelError("the angular velocity involves accelerations.", where=where)
    if Y.rows != 3 or Y.cols != 3:
        raise ModelError("three coordinates are needed for three angular speeds.", where=where)
    rest = sp.Matrix(eqs).xreplace(dict.fromkeys(dummies, 0))
    try:
        sol = Y.LUsolve(-rest)
    except (ValueError, ZeroDivisionError):
        raise ModelError(f"the angular velocity of {frame.name} does not determine the rates of "
                         + ", ".join(q.func.__name__ for q in coordinates) + ".", where=where,
                         hint="List the three angles that orient the frame.") from None
    qdot = {r: sp.trigsimp(sp.simplify(s)) for r, s in zip(rates, sol)}
    return SpeedGroup(frame, tuple(coordinates), w, qdot, "angular", tuple(names))


def quaternion_group(frame, e, names) -> SpeedGroup:
    """Euler parameters ``e`` of ``frame`` with its angular-velocity components as speeds (ė = ½ Q(e) w)."""
    w = tuple(dynamicsymbols(n, real=True) for n in names)
    rates = quaternion_rates(e, w)
    qdot = {q.diff(t): r for q, r in zip(e, rates)}
    return SpeedGroup(frame, tuple(e), w, qdot, "quaternion", tuple(names))


class KinematicEquations:
    """q (every coordinate, Euler parameters included), u (the speeds) and q̇ = W(q) u for a system.

    ``speeds`` lists q̇_j for each coordinate whose rate is its speed and the group's speeds in place
    of the rates they replace (at the position of the group's first coordinate)."""

    def __init__(self, system):
        groups = list(getattr(system, "speed_groups", {}).values())
        self.groups = groups
        owner = {q: g for g in groups for q in g.coordinates}
        quasi = {p for g in groups for p in g.quasi}
        self.configuration = tuple(q for q in system.coordinates if q not in quasi)
        speeds, seen = [], set()
        for q in self.configuration:
            g = owner.get(q)
            if g is None:
                speeds.append(q.diff(t))
            elif id(g) not in seen:
                seen.add(id(g))
                speeds.extend(g.speeds)
        self.speeds = tuple(speeds)
        self.qdot = {k: v for g in groups for k, v in g.qdot.items()}
        self.replaced = tuple(q for g in groups for q in g.coordinates)

    @property
    def trivial(self) -> bool:
        """True when every speed is a coordinate rate (u = q̇)."""
        return not self.groups

    def rate_expressions(self) -> list:
        """q̇ of every coordinate as an expression of q and the speeds."""
        return [self.qdot.get(q.diff(t), q.diff(t)) for q in self.configuration]

    def W(self) -> sp.Matrix:
        """W(q) = ∂q̇/∂u (n_q × n_u)."""
        return sp.Matrix(self.rate_expressions()).jacobian(list(self.speeds))

    def substitute(self, x):
        """An expression or vector with the replaced rates q̇_j written as W(q) u (and their q̈_j as
        d/dt of that, with q̇ again replaced)."""
        if not self.qdot:
            return x
        m = dict(self.qdot)
        for q in self.replaced:
            acc = q.diff(t, 2)
            m[acc] = sp.diff(self.qdot[q.diff(t)], t).xreplace(self.qdot)
        if isinstance(x, Vector):
            if x == Vector(0):
                return x
            return Vector([(comp.xreplace(m), fr) for comp, fr in x.args])
        return sp.sympify(x).xreplace(m)

    def speed_rates(self) -> tuple:
        """u̇ (the speeds' derivatives: q̈_j or ẇ)."""
        return tuple(u.diff(t) for u in self.speeds)


def quasi_coordinate(name: str, speed) -> sp.Expr:
    """A quasi-coordinate π(t) whose time derivative is the speed w(t) (π̇ = w, π̈ = ẇ).

    No position depends on it; it lets the symbolic core, which reads rates as q̇ and accelerations
    as q̈ of its coordinates, work in the speeds unchanged: its rate *is* w, so every equation is
    written in w and ẇ."""
    from sympy.core.function import UndefinedFunction

    func = UndefinedFunction(name, __dict__={"fdiff": lambda self, argindex=1: speed}, real=True)
    return func(t)


def is_quasi(system, q) -> bool:
    """True for a quasi-coordinate (the integral of a speed, which locates nothing)."""
    return any(q in g.quasi for g in getattr(system, "speed_groups", {}).values())


def quaternion_groups(system) -> list[SpeedGroup]:
    """The speed groups of the frames that ``system`` orients by Euler parameters."""
    return [g for g in getattr(system, "speed_groups", {}).values() if g.kind == "quaternion"]


def euler_norms(system) -> list[tuple[str, object]]:
    """(frame name, e₀² + e₁² + e₂² + e₃²) for each frame oriented by Euler parameters: the printed
    equations of motion are written with that sum = 1 (``solution._readable_eom``)."""
    return [(g.frame.name, sp.Add(*[e**2 for e in g.coordinates])) for g in quaternion_groups(system)]


def require_rate_speeds(system, what: str) -> None:
    """Refuse, in one paragraph, a closed-form analysis (``what``) that linearises in q and q̇ when the
    system's speeds are not the coordinate rates (body angular-velocity components, quaternions)."""
    ke = speeds_of(system)
    if ke.trivial:
        return
    named = ", ".join(u.func.__name__ for u in ke.speeds if not isinstance(u, sp.Derivative))
    raise ModelError(f"{what} is written for the coordinates and their rates (u = q̇), but this system's speeds "
                     f"include {named}, which are not coordinate rates (q̇ = W(q) u).", where=system.name,
                     hint="Linearise numerically with rigidkin.numeric.large.projected.ProjectedModel(system): its "
                          "state_matrix() and linearise() handle any speeds; or declare the frame without "
                          "speeds= (and without a quaternion) to keep u = q̇.")


def speeds_of(system) -> KinematicEquations:
    """The kinematic equations of ``system`` (kept on it until its description changes)."""
    k = getattr(system, "_kinematic_equations", None)
    if k is None:
        k = KinematicEquations(system)
        if hasattr(system, "_kinematic_equations"):
            system._kinematic_equations = k
    return k
