"""Reference frames and their bases, on ``sympy.physics.vector.ReferenceFrame``.

A frame is the inertial frame F (basis Ex, Ey, Ez) or a frame rotated from another one: by an angle
about an axis (any number of intermediate frames: one that follows a line of centres, a body frame),
or by a body-fixed sequence of three angles (3-1-3 Euler angles, 3-2-1 yaw-pitch-roll), or by four Euler
parameters (a quaternion: no singular configuration; see ``rigidkin.model.speeds``).  The basis
vectors keep the names the user gives them (``er, eθ, ez``) for printing.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import ReferenceFrame, Vector

from ..base.errors import ModelError

_AXES = {"x": 0, "y": 1, "z": 2}


@dataclass(eq=False)
class Frame:
    """A reference frame with a named right-handed basis (x, y, z)."""

    name: str
    ref: ReferenceFrame
    basis: tuple[str, str, str]
    parent: Frame | None = None
    angle: sp.Expr | None = None
    axis: Vector | None = None
    sequence: str | None = None
    angles: tuple | None = None
    description: str = ""
    quaternion: tuple | None = None     # Euler parameters (e0, e1, e2, e3) when oriented by a quaternion
    speeds: tuple | None = None         # its angular-velocity components w1, w2, w3 when they are speeds

    @property
    def x(self) -> Vector:
        return self.ref.x

    @property
    def y(self) -> Vector:
        return self.ref.y

    @property
    def z(self) -> Vector:
        return self.ref.z

    def unit(self, spec: str) -> Vector:
        """A basis vector by name: ``"x"``, ``"-y"``, or the basis name (``"er"``, ``"-Ey"``)."""
        s = spec.strip()
        sign = 1
        if s.startswith("-"):
            sign, s = -1, s[1:].strip()
        elif s.startswith("+"):
            s = s[1:].strip()
        if s in _AXES:
            return sign * (self.x, self.y, self.z)[_AXES[s]]
        if s in self.basis:
            return sign * (self.x, self.y, self.z)[self.basis.index(s)]
        raise ModelError(f"'{spec}' is not a basis vector of frame {self.name} "
                         f"(its basis is {', '.join(self.basis)}).")

    def __getattr__(self, item):
        # basis vectors by their names: F.Ex, A.er
        basis = self.__dict__.get("basis")
        if basis and item in basis:
            return (self.ref.x, self.ref.y, self.ref.z)[basis.index(item)]
        raise AttributeError(item)

    def __repr__(self) -> str:
        return f"Frame({self.name}: {', '.join(self.basis)})"


def make_reference_frame(name: str, basis: tuple[str, str, str], latex: tuple[str, str, str]) -> ReferenceFrame:
    """A sympy ReferenceFrame whose basis vectors print with the given names."""
    ref = ReferenceFrame(name, latexs=latex)
    ref.str_vecs = list(basis)
    ref.pretty_vecs = list(basis)
    return ref
