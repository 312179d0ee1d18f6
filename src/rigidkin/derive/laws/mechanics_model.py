"""The model as sympy.physics.mechanics objects, for the Lagrange and Kane adapters.

Bodies become ``RigidBody`` objects (mass centre with its velocity from the position vector, body
frame, mass, central inertia); loads become (point, force) and (frame, torque) pairs acting at
points whose velocity is that of the material point of the loaded body; conservative loads give a
potential energy from their own ``potential``.  Constraint rows are handed over as they are (velocity
expressions in all the coordinate rates, with their gaps) for the mechanics tools' own constraint
handling: our reduction to independent coordinates is not used, so the derivation is independent.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.mechanics import Point, RigidBody
from sympy.physics.vector import Vector, dynamicsymbols

from ..mode import ModeSetup
from .methods import NotApplicable

t = dynamicsymbols._t


@dataclass
class MechanicsModel:
    """Bodies, loads, potential and constraints ready for LagrangesMethod / KanesMethod."""

    frame: object
    bodies: list
    loads: list                     # (Point | ReferenceFrame, Vector): non-conservative or all
    potential: sp.Expr
    holonomic: list = field(default_factory=list)      # gaps f(q, t) = 0
    nonholonomic: list = field(default_factory=list)   # velocity rows, linear in q̇
    rows: list = field(default_factory=list)           # the relating rows (any form), for Kane
    evidence: list = field(default_factory=list)       # reactions a load depends on (brought into evidence)
    points: list = field(default_factory=list)         # (mechanics Point, rigidkin body) of every point made


def build(setup: ModeSetup, conservative: str = "potential", method: str = "lagrange",
          evidence: bool = False) -> MechanicsModel:
    """The mechanics objects of ``setup``; ``conservative`` = "potential" (in U) or "forces" (as loads).

    A load that depends on a reaction (Coulomb friction set by a normal force) makes the method not
    applicable, unless ``evidence``: then the reaction is listed in ``evidence`` and its forces (every
    application of its row) are added to the loads, for an auxiliary speed to bring it into evidence.
    """
    kin = setup.kin
    N = kin.F.ref
    reactions = set(setup.reactions)
    bodies, points = [], []
    for b in setup.system.bodies.values():
        if b.is_massless:
            continue
        mc = Point(f"{b.centre.name}_{b.name}")
        mc.set_vel(N, kin.position(b.centre).dt(N))
        points.append((mc, b))
        bodies.append(RigidBody(b.name, mc, b.frame.ref, b.mass, (b.inertia, mc)))
    load_of = {ld.name: ld for ld in setup.loads}
    loads, U, wanted = [], sp.Integer(0), []
    for ld in setup.loads:
        if conservative == "potential" and getattr(ld, "conservative", False):
            pot = ld.potential(kin)
            if pot is not None:
                U += pot
    for i, app in enumerate(setup.applications):
        if app.reaction is not None:
            continue                       # constraint forces: handled by the method's constraints
        ld = load_of.get(app.source)
        if conservative == "potential" and ld is not None and getattr(ld, "conservative", False) \
                and ld.potential(kin) is not None:
            continue
        used = [r for r in reactions if _vector_has(app.vector, r)]
        if used and evidence:
            wanted.extend(r for r in used if r not in wanted)
        elif used:
            raise NotApplicable(f"the {app.label} depends on the reaction(s) {', '.join(map(str, used))}, which "
                                f"{method} eliminates (Coulomb friction set by a normal force).",
                                where=setup.system.name, hint="Euler's laws (newton-euler) handle it.")
        if app.is_torque:
            loads.append((app.body.frame.ref, app.vector))
        else:
            loc = app.location if app.location is not None else kin.position(app.point)
            p = Point(f"load{i}")
            p.set_vel(N, kin.material_velocity(app.body, loc))
            points.append((p, app.body))
            loads.append((p, app.vector))
    for row in setup.rows:
        if row.reaction not in wanted:
            continue
        for k, app in enumerate(row.applications):
            if app.is_torque:
                raise NotApplicable(f"the reaction couple {row.reaction} cannot be brought into evidence here.",
                                    where=setup.system.name, hint="Euler's laws (newton-euler) handle it.")
            loc = app.location if app.location is not None else kin.position(app.point)
            p = Point(f"{row.reaction}_{k}")
            p.set_vel(N, kin.material_velocity(app.body, loc))
            points.append((p, app.body))
            loads.append((p, app.vector))
    model = MechanicsModel(N, bodies, loads, U, points=points)
    model.evidence = [(r, next(row for row in setup.rows if row.reaction == r)) for r in wanted]
    for row in setup.rows:
        v = kin.simplify_expr(row.velocity)
        if kin.is_zero(v):
            continue
        model.rows.append(row)
        gap = row.gap
        if gap is not None and not kin.is_zero(gap) and kin.is_zero(sp.diff(gap, t) - v) \
                and not sp.sympify(gap).has(*reactions):
            model.holonomic.append(kin.simplify_expr(gap))
        else:
            model.nonholonomic.append(v)
    return model


def _vector_has(v: Vector, sym) -> bool:
    if v == Vector(0):
        return False
    return any(m.has(sym) for m, _ in v.args)
