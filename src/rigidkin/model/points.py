"""Points located by vectors from other points; a point may be fixed in a body.

Positions are kept as the chain of offsets the user gave (``A = B + l Ry``); the position from the
origin O is their sum.  A point fixed in a body moves with it; the system checks that its offset
from the body's mass centre is constant in the body frame.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from sympy.physics.vector import Point as SpPoint
from sympy.physics.vector import Vector


@dataclass(eq=False)
class Point:
    """A point: ``position`` (from ``parent``) and optionally the ``body`` it is fixed in."""

    name: str
    parent: Point | None = None
    offset: Vector = field(default_factory=lambda: Vector(0))
    body: object | None = None  # model.bodies.Body
    description: str = ""
    sp: SpPoint = field(init=False, repr=False)

    def __post_init__(self):
        self.sp = SpPoint(self.name)
        if self.parent is not None:
            self.sp.set_pos(self.parent.sp, self.offset)

    def position(self) -> Vector:
        """Position vector from the system's origin (the root of the chain of offsets)."""
        p, r = self, Vector(0)
        while p.parent is not None:
            r = r + p.offset
            p = p.parent
        return r

    def pos_from(self, other: Point) -> Vector:
        """Vector from ``other`` to this point."""
        return self.position() - other.position()

    def __repr__(self) -> str:
        on = f" on {self.body.name}" if self.body is not None else ""
        return f"Point({self.name}{on})"
