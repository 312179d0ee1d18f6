"""Contact profiles that are arcs: the part of a circle (or sphere) of a body that exists.

A half cylinder's curved face is the half of its circle on the side ``toward`` points to: it touches a
surface only while the direction from its centre to the contact point, −n (n the surface normal into
the body), lies within π/2 of ``toward``.  Beyond that the edge of the flat face meets the surface
instead, and the contact as modelled no longer exists.

An :class:`Arc` states this for a contact: the unit vector ``toward`` (fixed in the body) at the middle
of the arc and the ``half_angle`` on either side.  The contact holds while its *arc margin*

    m = (−n)·toward − cos(half_angle) ≥ 0

which the solution lists as a validity condition (equilibria outside it are not equilibria of the
model) and a simulation watches (it stops, with that reason, when the margin reaches zero).  Half
cylinders, semicircular disks and hemispheres carry their arcs by default (half angle π/2) when the
contact's centre is their flat-face centre and its radius their radius.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector

from ..base.errors import ModelError
from ..base.printing import text, text_vector


@dataclass(frozen=True, eq=False)
class Arc:
    """The directions of a profile that exist: within ``half_angle`` of ``toward`` (a unit vector fixed
    in the body), seen from the profile's centre."""

    toward: Vector
    half_angle: sp.Expr = sp.pi / 2

    def margin(self, contact, kin) -> sp.Expr:
        """(−n)·toward − cos(half_angle): positive while the contact point lies on the arc."""
        n = contact.normal(kin)
        return kin.simplify_expr((-n).dot(self.toward) - sp.cos(self.half_angle))

    def describe(self) -> str:
        return f"within {text(self.half_angle)} of {text_vector(self.toward)}"


def default_arc(body, centre, radius) -> Arc | None:
    """The arc of a half shape's curved face, when the contact is that face; else None (a full circle)."""
    shape = getattr(body, "shape", None)
    toward = getattr(shape, "toward", None)
    if toward is None or not hasattr(shape, "radius"):
        return None
    if centre is not body.reference or sp.simplify(sp.sympify(radius) - shape.radius) != 0:
        return None
    return Arc(body.frame.unit(toward), sp.pi / 2)


def arc_for(arc, body, centre, radius, where: str) -> Arc | None:
    """The arc a contact is given: None (the default of its body's shape), False (a full circle), an
    :class:`Arc`, or (toward, half_angle)."""
    if arc is None:
        return default_arc(body, centre, radius)
    if arc is False:
        return None
    if isinstance(arc, Arc):
        out = arc
    elif isinstance(arc, (tuple, list)) and len(arc) == 2 and isinstance(arc[0], Vector):
        out = Arc(arc[0], sp.sympify(arc[1]))
    else:
        raise ModelError(f"arc must be False (a full circle), an Arc or (toward, half_angle), not {arc!r}.",
                         where=where)
    if sp.sympify(radius) == 0:
        raise ModelError("a point contact (radius 0) has no arc.", where=where)
    ha = out.half_angle
    if ha.is_number and not (0 < float(ha) <= float(sp.pi)):
        raise ModelError(f"the half angle of an arc must lie in (0, π], not {ha}.", where=where)
    drift = out.toward.dt(body.frame.ref)
    if drift != 0 and any(sp.simplify(x) != 0 for x in drift.to_matrix(body.frame.ref)):
        raise ModelError(f"the middle of the arc ('toward') must be a direction fixed in {body.name}'s frame "
                         f"{body.frame.name}.", where=where, hint=f"Write it in {body.frame.name}'s basis.")
    return out


def arc_margins(setup) -> list[tuple[sp.Expr, str]]:
    """(margin ≥ 0, label) for every closed contact whose profile is an arc, in the mode's coordinates."""
    out = []
    for c in setup.system.constraints.values():
        arc = getattr(c, "arc", None)
        if arc is None or setup.states.get(c.name) == "open":
            continue
        m = setup.kin.simplify_expr(setup.scalar(arc.margin(c, setup.kin)))
        out.append((m, f"{c.name} touches on its arc ({arc.describe()})"))
    return out
