"""Rolling and sliding contact of a thin disk (a wheel, a coin) with a plane, in three dimensions.

A disk of radius r, centre C and unit axis a (fixed in the disk) touches a plane of unit normal n
(pointing from the plane into the body) at the point of its rim nearest the plane:

    P = C − r û,   û = (n − (a·n) a) / |n − (a·n) a| = a × (n × a) / |a × (n × a)|,

û being the unit vector in the disk's plane that points away from the plane.  It is not C − r n as
for a sphere: a leaning wheel touches the ground below its centre only in the disk's own plane.  The
gap is the height of the centre minus r sqrt(1 − (a·n)²).  Rolling without slip asks the material
point of the disk at P to move with the surface along the two tangent directions (two
non-integrable velocity constraints), and the normal row keeps P on the plane.

Domain of validity: û·n = sqrt(1 − (a·n)²) > 0.  Its square root is resolved once, by its sign in the
reference configuration (û·n = cos θ for a lean θ), so the formulas hold on that side of lying flat
only; there û·n → 0, the disk's face meets the plane — a change of contact the model does not
describe.  :meth:`DiskContact.domain` gives that condition: the simulator watches it and refuses a
start outside it, and answers outside it are not given.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector

from ..base import algebra
from ..base.errors import ModelError
from .constraints import Contact
from .surfaces import Line


@dataclass(eq=False)
class DiskContact(Contact):
    """A thin disk (radius ``radius``, unit ``axis`` fixed in ``body``) touching a plane at its rim.

    Everything else (states open / slip / stick, the normal and no-slip rows and their reactions,
    Coulomb friction) is as for :class:`rigidkin.model.constraints.Contact`; only the contact point
    and the gap follow the disk's geometry.
    """

    axis: Vector = None

    kind = "contact"          # a contact like any other for the laws, modes and reports

    def __post_init__(self):
        where = f"contact {self.name}"
        if not isinstance(self.surface, Line):
            raise ModelError("a disk profile can touch a plane (System.plane) only; a disk on a curved "
                             "surface has no closed-form contact point.", where=where,
                             hint="Model the curved surface's body as touching a sphere profile instead.")
        if not isinstance(self.axis, Vector) or self.axis == Vector(0):
            raise ModelError(f"the disk axis must be a nonzero vector fixed in the body, not {self.axis!r}.",
                             where=where, hint="Give e.g. axis=W.y for a wheel turning about its frame's y.")
        if not algebra.is_zero(self.axis.dot(self.axis) - 1):
            raise ModelError(f"the disk axis {self.axis} is not a unit vector.", where=where,
                             hint="Divide it by its length, or use a basis vector of the disk's frame.")
        if self.axis.dt(self.body.frame.ref) != Vector(0) and \
                not all(algebra.is_zero(c) for c in self.axis.dt(self.body.frame.ref).to_matrix(self.body.frame.ref)):
            raise ModelError(f"the disk axis {self.axis} turns relative to the body {self.body.name}.", where=where,
                             hint=f"Give a vector fixed in the frame of {self.body.name} ({self.body.frame.name}).")

    def rim_direction(self, kin) -> Vector:
        """û: the unit vector in the disk's plane from the contact point towards the centre."""
        cache = kin.__dict__.setdefault("_rim_directions", {})
        if self.name in cache:
            return cache[self.name]
        a, n = self.axis, self.normal(kin)
        an = a.dot(n)
        in_plane = n - an * a
        if sp.count_ops(an) <= 8:
            u = in_plane / kin.magnitude(in_plane)        # readable (cos θ), its sign settled
        else:
            u = in_plane / sp.sqrt(1 - an**2)             # |n − (a·n) a|² = 1 − (a·n)² for unit a, n
        cache[self.name] = u
        return u

    def domain(self, kin) -> list[tuple[sp.Expr, str, str]]:
        """(expr, what its zero is, why the model ends there): the conditions ``expr > 0`` within which the
        contact's geometry is exact — here û·n > 0, the disk not flat."""
        cache = kin.__dict__.setdefault("_disk_domains", {})
        if self.name not in cache:
            un = kin.simplify_expr(self.rim_direction(kin).dot(self.normal(kin)))
            cache[self.name] = [(un, f"the disk of contact {self.name} comes to lie flat on the plane",
                                 "its face meets the plane, a change of contact this model (the rim on the "
                                 "plane) does not describe")]
        return cache[self.name]

    def validity(self, setup, react) -> list:
        """The contact's conditions (friction within its cone) and its geometry's domain: the disk not past flat."""
        return [*super().validity(setup, react),
                *((expr, f"the disk of contact {self.name} not lying flat (its rim, not its face, on the plane)")
                  for expr, _, _ in self.domain(setup.kin))]

    def location(self, kin) -> Vector:
        return kin.position(self.centre) - self.radius * self.rim_direction(kin)

    def gap(self, kin) -> sp.Expr:
        cache = kin.__dict__.setdefault("_disk_gaps", {})
        if self.name not in cache:
            n = self.normal(kin)
            height = (kin.position(self.centre) - kin.position(self.surface.point)).dot(n)
            cache[self.name] = kin.simplify_expr(height - self.radius * self.rim_direction(kin).dot(n))
        return cache[self.name]
