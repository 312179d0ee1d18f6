"""Velocity constraints: knife edges and general linear constraints on the rates.

A **knife edge** (a skate's blade, the runner of a Chaplygin sleigh, a wheel whose spin is not
modelled) is a point P of a body whose velocity along a direction e fixed in the body is zero:

    v_P · e = 0,

one non-integrable (nonholonomic) row like a rolling contact's no-slip row, enforced by a lateral
force N e at P (the edge's sideways reaction, either sign).

A **general velocity constraint** is an expression in the rates, linear in them, that must vanish:
Σ a_j(q, t) q̇_j + b(q, t) = 0.  Its reaction is a multiplier λ: the constraint adds the
generalised force λ a_j to the equation of q_j.  For the balance laws of each body it is realised as
forces at the mass centres and torques on the bodies whose power is λ Σ a_j q̇_j for every motion
(the least-norm choice: F_b = λ Σ_j y_j ∂v̄_b/∂q̇_j, M_b = λ Σ_j y_j ∂ω_b/∂q̇_j with J Jᵀ y = a).  λ
and the motion are the constraint's own; how the other reactions share it depends on that choice,
so write a physical constraint (a knife edge, a contact) where there is one.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base import algebra
from ..base.errors import ModelError
from .constraints import Constraint, Row, _two_sided
from .points import Point
from .values import _expr

t = dynamicsymbols._t


@dataclass(eq=False)
class KnifeEdge(Constraint):
    """``point`` of ``body`` cannot move along the unit ``direction`` fixed in the body: v_P·e = 0.

    Reaction: the lateral force ``N_<name>`` (or ``reaction_name``) along e at P, either sign.
    """

    body: object = None
    point: Point = None
    direction: Vector = None
    reaction_name: str | None = None

    kind = "knife edge"

    @property
    def N(self) -> sp.Symbol:
        return sp.Symbol(self.reaction_name or f"N_{self.name}", real=True)

    def reactions(self):
        return [self.N]

    def rows(self, kin, state):
        loc = kin.position(self.point)
        v = kin.material_velocity(self.body, loc)
        e = self.direction
        return [Row(self.name, f"knife edge {self.name}: no velocity along {e}", kin.simplify_expr(v.dot(e)), self.N,
                    _two_sided(self.N, e, "force", self.body, self.point, None, None,
                               f"lateral force {self.N} of the knife edge", self.name, loc=loc), kind="normal")]


@dataclass(eq=False)
class VelocityConstraint(Constraint):
    """``expression`` = 0, an expression linear in the coordinates' rates; reaction: the multiplier λ.

    See the module's docstring for how λ acts on the bodies.
    """

    expression: sp.Expr = None
    reaction_name: str | None = None

    kind = "velocity constraint"

    @property
    def multiplier(self) -> sp.Symbol:
        return sp.Symbol(self.reaction_name or f"lambda_{self.name}", real=True)

    def reactions(self):
        return [self.multiplier]

    def coefficients(self, system) -> tuple[list, list, sp.Expr]:
        """(coordinates, a_j, b) with expression = Σ a_j q̇_j + b."""
        qs = list(system.coordinates)
        rates = [q.diff(t) for q in qs]
        e = sp.sympify(self.expression)
        a = [sp.diff(e, r) for r in rates]
        b = sp.expand(e - sum((aj * r for aj, r in zip(a, rates)), sp.Integer(0)))
        return qs, a, b

    def rows(self, kin, state):
        lam = self.multiplier
        return [Row(self.name, f"velocity constraint {self.name}", kin.simplify_expr(self.expression), lam,
                    self._applications(kin), kind="force")]

    def _applications(self, kin):
        cache = kin.__dict__.setdefault("_velocity_constraint_apps", {})
        if self.name in cache:
            return cache[self.name]
        system = kin.system
        qs, a, _ = self.coefficients(system)
        rates = [q.diff(t) for q in qs]
        bodies = list(system.bodies.values())
        frame = kin.F
        axes = [frame.x, frame.y] if kin.planar else [frame.x, frame.y, frame.z]
        turn_axes = [frame.z] if kin.planar else [frame.x, frame.y, frame.z]
        columns = []            # (body, is_torque, axis, ∂(velocity·axis)/∂q̇_j for each j)
        for b in bodies:
            v, w = kin.velocity(b.centre), kin.omega_of(b)
            for e in axes:
                columns.append((b, False, e, [sp.diff(v.dot(e), r) for r in rates]))
            for e in turn_axes:
                columns.append((b, True, e, [sp.diff(w.dot(e), r) for r in rates]))
        J = sp.Matrix([[c[3][j] for c in columns] for j in range(len(rates))])
        JJ = (J * J.T).applyfunc(kin.simplify_expr)
        det = kin.simplify_expr(JJ.det()) if JJ.rows <= 4 else JJ.det()
        if algebra.is_zero(det):
            raise ModelError("the constraint's generalised force cannot be carried by the bodies: some coordinate "
                             "moves no body (J Jᵀ is singular).", where=f"velocity constraint {self.name}",
                             hint="Write the constraint as a knife edge or a contact at a point of a body.")
        y = JJ.LUsolve(sp.Matrix(a)).applyfunc(kin.simplify_expr)
        lam = self.multiplier
        apps = []
        for b in bodies:
            F = sum((kin.simplify_expr(sum((y[j] * c[3][j] for j in range(len(rates))), sp.Integer(0))) * c[2]
                     for c in columns if c[0] is b and not c[1]), Vector(0))
            M = sum((kin.simplify_expr(sum((y[j] * c[3][j] for j in range(len(rates))), sp.Integer(0))) * c[2]
                     for c in columns if c[0] is b and c[1]), Vector(0))
            if Vector(0) != F:
                apps.extend(_two_sided(lam, F, "force", b, b.centre, None, None,
                                       f"reaction {lam} of {self.name} on {b.name}", self.name))
            if Vector(0) != M:
                apps.extend(_two_sided(lam, M, "torque", b, None, None, None,
                                       f"reaction couple {lam} of {self.name} on {b.name}", self.name))
        cache[self.name] = tuple(apps)
        return cache[self.name]


class VelocityConstraintMethods:
    """Knife edges and general velocity constraints (mixed into System)."""

    def knife_edge(self, name: str, body, point: Point | str, direction: Vector, reaction_name: str | None = None,
                   description: str = "") -> KnifeEdge:
        """A knife edge: ``point`` of ``body`` cannot move along ``direction`` (a unit vector fixed in the body).

        E.g. a Chaplygin sleigh's runner at P behind the mass centre: ``s.knife_edge("edge", sleigh, P, B.y)``;
        the reaction ``N_edge`` is the lateral force on the body along B.y.
        """
        self._claim(name, "constraint", "constraint")
        where = f"knife edge {name}"
        b = self._check_body(body, where)
        p = self._check_point(point, where)
        e = self._check_vector(direction, where)
        if e == Vector(0) or not algebra.is_zero(e.dot(e) - 1):
            raise ModelError(f"the direction {e} of a knife edge is not a unit vector.", where=where,
                             hint="Give a basis vector of the body's frame, e.g. B.y (the blade's sideways axis).")
        drift = e.dt(b.frame.ref)
        if drift != Vector(0) and not all(algebra.is_zero(c) for c in drift.to_matrix(b.frame.ref)):
            raise ModelError(f"the direction {e} turns relative to the body {b.name}.", where=where,
                             hint=f"Give a vector fixed in the frame of {b.name} ({b.frame.name}).")
        con = KnifeEdge(name, body=b, point=p, direction=e, reaction_name=reaction_name, description=description)
        self._claim(con.N.name, "reaction", owner=where)
        return self._add_constraint(con)

    def velocity_constraint(self, name: str, expression, reaction_name: str | None = None,
                            description: str = "") -> VelocityConstraint:
        """A general velocity constraint ``expression`` = 0, linear in the coordinates' rates.

        E.g. ``s.velocity_constraint("skate", -sin(th)*x.diff(t) + cos(th)*y.diff(t))``.  Its reaction is
        the multiplier ``lambda_<name>`` (generalised force λ ∂(expression)/∂q̇_j on each coordinate).
        """
        self._claim(name, "constraint", "constraint")
        where = f"velocity constraint {name}"
        e = _expr(expression, where)
        qs = list(self.coordinates)
        rates = [q.diff(t) for q in qs]
        if not e.has(*rates):
            raise ModelError(f"{e} contains no rate of a coordinate, so it constrains no velocity.", where=where,
                             hint="Write it in the rates, e.g. x.diff(t)*sin(theta) - y.diff(t)*cos(theta).")
        if e.has(*[q.diff(t, 2) for q in qs]):
            raise ModelError(f"{e} contains an acceleration; a velocity constraint is written in rates.",
                             where=where)
        scale = sp.Dummy("s")
        if not algebra.is_zero(sp.diff(e.xreplace({r: scale * r for r in rates}), scale, 2)):
            raise ModelError(f"{e} is not linear in the rates; only constraints linear in the rates are supported.",
                             where=where)
        con = VelocityConstraint(name, expression=e, reaction_name=reaction_name, description=description)
        self._claim(con.multiplier.name, "reaction", owner=where)
        return self._add_constraint(con)
