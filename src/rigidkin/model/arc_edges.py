"""The next contact shapes of a half shape's curved face: the edges at the ends of its arc.

A half cylinder (semicircular disk, hemisphere) touching by its curved face has the arc π/2 about its
``toward`` (:mod:`rigidkin.model.profiles`).  In planar motion the arc ends at the two ends of the flat
face's diameter, E = O ± r (e_z × toward), O the flat-face centre: there the edge (a corner of the section)
meets the surface, and beyond it the flat face, which touches through both edges.  The body's shape knows
them, so they are added for the simulation without a declaration: point contacts ``<contact>_edge1``
(at O + r e_z × toward) and ``<contact>_edge2`` (at O − r e_z × toward), on the same surface, with the
contact's friction and restitution.  They live in a copy of the system that only the hybrid model uses
(:func:`with_edges`): solving, reporting and drawing the system itself do not see them.

Edges are added only where the argument above holds: planar kinematics, the default arc of a half shape
(half angle π/2, the contact's centre its flat-face centre and its radius the shape's), a fixed straight
surface (a floor, an incline), and names that are free.  Elsewhere the simulation stops where the arc ends,
as before.
"""

from __future__ import annotations

import copy

import sympy as sp
from sympy.physics.vector import Vector, express

from .constraints import Contact
from .points import Point
from .surfaces import Line


def edge_offsets(contact, plane_normal) -> tuple | None:
    """(offset of edge 1, offset of edge 2) from the contact's centre, in the body's frame, when the contact
    is the curved face of a half shape with its default arc touching a fixed line; else None."""
    arc, body = getattr(contact, "arc", None), contact.body
    shape = getattr(body, "shape", None)
    if arc is None or getattr(shape, "toward", None) is None or not hasattr(shape, "radius"):
        return None
    if contact.centre is not body.reference or sp.simplify(sp.sympify(contact.radius) - shape.radius) != 0:
        return None
    if sp.simplify(arc.half_angle - sp.pi / 2) != 0 or not isinstance(contact.surface, Line):
        return None
    if contact.surface.body is not None:
        return None
    toward = body.frame.unit(shape.toward)
    if arc.toward != toward:
        return None
    side = express(plane_normal, body.frame.ref).cross(toward)
    if side == Vector(0):
        return None
    r = sp.sympify(contact.radius)
    return r * side, -r * side


def with_edges(system, plane_normal):
    """(the system with the edge contacts of every half shape's curved face, {arc contact: (edge names)}),
    or (system, {}) when none has edges.  The copy shares everything else (bodies, frames, coordinates)."""
    edges, points, contacts = {}, {}, {}
    for name, c in system.constraints.items():
        if not isinstance(c, Contact) or type(c) is not Contact:
            continue
        offs = edge_offsets(c, plane_normal)
        if offs is None:
            continue
        names = (f"{name}_edge1", f"{name}_edge2")
        new = []
        for en, off in zip(names, offs):
            e = Contact(en, body=c.body, centre=Point(en, c.centre, off, c.body,
                                                      f"edge of the flat face at the end of {name}'s arc"),
                        radius=sp.Integer(0), surface=c.surface, friction=c.friction, unilateral=True,
                        description=f"the edge at the end of the arc of {name} (added: the body's shape has it)")
            e.edge_of = name
            new.append(e)
        taken = set(system.constraints) | set(system.points)
        reactions = {str(s) for e in new for s in e.reactions()}
        if taken & set(names) or any(f"symbol:{r}" in system._names for r in reactions):
            continue                        # a name already used: no edges (the simulation stops at the arc's end)
        edges[name] = names
        for e in new:
            points[e.name], contacts[e.name] = e.centre, e
    if not edges:
        return system, {}
    ext = copy.copy(system)
    ext.points = {**system.points, **points}
    ext.constraints = {**system.constraints, **contacts}
    ext._derived = ext._kinematic_equations = None
    return ext, edges
