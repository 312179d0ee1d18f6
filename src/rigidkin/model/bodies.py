"""Rigid bodies: mass, mass centre, body frame and the inertia dyadic about the mass centre."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Dyadic

from .frames import Frame
from .points import Point
from .shapes import Shape


@dataclass(eq=False)
class Body:
    """A rigid body; ``centre`` is its mass centre, ``reference`` the point where its shape was placed."""

    name: str
    shape: Shape
    frame: Frame
    reference: Point
    centre: Point
    description: str = ""

    @property
    def mass(self) -> sp.Expr:
        return sp.sympify(self.shape.mass)

    @property
    def inertia(self) -> Dyadic:
        """Inertia dyadic about the mass centre, in the body frame (built once for the body's shape and frame:
        sympy's dyadic algebra is slow, and every law and check reads it)."""
        shape, frame = self.shape, self.frame
        made = self.__dict__.get("_inertia")
        if made is None or made[0] is not shape or made[1] is not frame:
            made = self.__dict__["_inertia"] = (shape, frame, shape.central_inertia(frame))
        return made[2]

    @property
    def is_massless(self) -> bool:
        return self.mass == 0

    def __repr__(self) -> str:
        return f"Body({self.name}: {self.shape.kind})"
