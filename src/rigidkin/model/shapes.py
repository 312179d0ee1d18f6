"""The shape library: central inertia dyadic and mass-centre offset of common rigid bodies.

Every shape is given in the axes of its body's frame: ``axis="z"`` names the body-frame direction
of a rod's length or a disk's symmetry axis; ``toward="y"`` names the direction from a half shape's
flat-face centre to its mass centre.  A shape's *reference point* is where the user places it: the
mass centre for symmetric shapes, the centre of the flat face for half shapes (semicircular disk,
half-cylinder, hemisphere), whose mass centres lie 4r/(3π) and 3r/8 from it.  The inertia returned
is about the mass centre (parallel-axis transfer done here, exactly).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.mechanics import inertia, inertia_of_point_mass
from sympy.physics.vector import Dyadic, Vector

from .checks import NONNEGATIVE, POSITIVE, require
from .frames import Frame


def parallel_axis(mass: sp.Expr, offset: Vector, frame: Frame) -> Dyadic:
    """m[(r·r)U − r⊗r]: the dyadic to add to a central inertia to get it about a point at ``offset``."""
    return inertia_of_point_mass(mass, offset, frame.ref)


def _axes(frame: Frame, axis: str, toward: str | None = None):
    """Unit vectors along ``axis``, ``toward`` and their cross product, in the body frame."""
    a = frame.unit(axis)
    if toward is None:
        return a, None, None
    b = frame.unit(toward)
    return a, b, a.cross(b)


def _sym(a: Vector, b: Vector) -> Dyadic:
    return a.outer(b)


@dataclass(frozen=True)
class Shape:
    """Base class: mass, central inertia in a frame, offset of the mass centre from the reference point."""

    mass: sp.Expr

    kind = "shape"
    #: What each dimension must be: "positive" (a mass, a length, a radius) or "nonnegative".
    rules = {"mass": POSITIVE}

    def __post_init__(self):
        self.check()

    def check(self, values: dict | None = None, where: str | None = None) -> None:
        """Refuse a mass or dimension that is not positive (or not ≥ 0 where zero is allowed), with the
        parameters' numeric ``values`` put in when given."""
        for key, rule in self.rules.items():
            v = getattr(self, key, None)
            if v is not None:
                require(v, rule, f"{key.replace('_', ' ')} of the {self.kind}", where, values)

    def central_inertia(self, frame: Frame) -> Dyadic:
        raise NotImplementedError

    def centre_offset(self, frame: Frame) -> Vector:
        return Vector(0)

    @property
    def dimensions(self) -> dict:
        """The dimensions used by drawings and reports (name → expression)."""
        return {k: v for k, v in self.__dict__.items() if k != "mass" and isinstance(v, sp.Basic)}


def _about_axis(frame: Frame, axis: str, I_axis, I_trans) -> Dyadic:
    """An axisymmetric inertia: I_axis about ``axis``, I_trans about every perpendicular axis."""
    a = frame.unit(axis)
    unit = frame.x.outer(frame.x) + frame.y.outer(frame.y) + frame.z.outer(frame.z)
    return I_trans * unit + (I_axis - I_trans) * a.outer(a)


@dataclass(frozen=True)
class SlenderRod(Shape):
    """Uniform slender rod of length ``length`` along ``axis``: I = m l²/12 about its transverse axes."""

    length: sp.Expr = sp.Integer(1)
    axis: str = "x"
    kind = "slender rod"
    rules = {"mass": POSITIVE, "length": POSITIVE}

    def central_inertia(self, frame):
        return _about_axis(frame, self.axis, 0, self.mass * self.length**2 / 12)


@dataclass(frozen=True)
class ThinRing(Shape):
    """Thin circular ring (hoop) of radius r: m r² about its axis, m r²/2 about a diameter."""

    radius: sp.Expr = sp.Integer(1)
    axis: str = "z"
    kind = "thin ring"
    rules = {"mass": POSITIVE, "radius": POSITIVE}

    def central_inertia(self, frame):
        r = self.radius
        return _about_axis(frame, self.axis, self.mass * r**2, self.mass * r**2 / 2)


@dataclass(frozen=True)
class Disk(Shape):
    """Uniform disk or solid cylinder (length along ``axis``, 0 for a disk): m r²/2 about its axis."""

    radius: sp.Expr = sp.Integer(1)
    length: sp.Expr = sp.Integer(0)
    axis: str = "z"
    kind = "disk"
    rules = {"mass": POSITIVE, "radius": POSITIVE, "length": NONNEGATIVE}

    def central_inertia(self, frame):
        m, r, L = self.mass, self.radius, self.length
        return _about_axis(frame, self.axis, m * r**2 / 2, m * r**2 / 4 + m * L**2 / 12)


SolidCylinder = Disk


@dataclass(frozen=True)
class HollowCylinder(Shape):
    """Hollow cylinder (radii r_outer, r_inner; thin-walled when r_inner is None) of given length."""

    radius: sp.Expr = sp.Integer(1)
    inner_radius: sp.Expr | None = None
    length: sp.Expr = sp.Integer(0)
    axis: str = "z"
    kind = "hollow cylinder"
    rules = {"mass": POSITIVE, "radius": POSITIVE, "inner_radius": NONNEGATIVE, "length": NONNEGATIVE}

    def central_inertia(self, frame):
        m, ro, L = self.mass, self.radius, self.length
        ri = ro if self.inner_radius is None else self.inner_radius
        return _about_axis(frame, self.axis, m * (ro**2 + ri**2) / 2,
                           m * (3 * (ro**2 + ri**2) + L**2) / 12)


@dataclass(frozen=True)
class SolidSphere(Shape):
    """Uniform solid sphere: 2 m r²/5 about every axis through its centre."""

    radius: sp.Expr = sp.Integer(1)
    kind = "solid sphere"
    rules = {"mass": POSITIVE, "radius": POSITIVE}

    def central_inertia(self, frame):
        return _about_axis(frame, "z", *(2 * self.mass * self.radius**2 / 5,) * 2)


@dataclass(frozen=True)
class SphericalShell(Shape):
    """Thin spherical shell: 2 m r²/3 about every axis through its centre."""

    radius: sp.Expr = sp.Integer(1)
    kind = "spherical shell"
    rules = {"mass": POSITIVE, "radius": POSITIVE}

    def central_inertia(self, frame):
        return _about_axis(frame, "z", *(2 * self.mass * self.radius**2 / 3,) * 2)


@dataclass(frozen=True)
class HalfCylinder(Shape):
    """Solid half-cylinder (a semicircular disk when ``length`` = 0), placed by its flat-face centre O.

    ``axis`` is the cylinder axis; ``toward`` points from O into the curved half.  The mass centre
    is at 4r/(3π) along ``toward``.  About O: m r²/2 about the axis, m r²/4 + m L²/12 about the two
    other directions; the central values follow by the parallel-axis theorem (exact).
    """

    radius: sp.Expr = sp.Integer(1)
    length: sp.Expr = sp.Integer(0)
    axis: str = "z"
    toward: str = "-y"
    kind = "half cylinder"
    rules = {"mass": POSITIVE, "radius": POSITIVE, "length": NONNEGATIVE}

    @property
    def centre_distance(self) -> sp.Expr:
        return 4 * self.radius / (3 * sp.pi)

    def centre_offset(self, frame):
        return self.centre_distance * frame.unit(self.toward)

    def central_inertia(self, frame):
        m, r, L = self.mass, self.radius, self.length
        a, b, c = _axes(frame, self.axis, self.toward)
        about_O = (m * r**2 / 2) * _sym(a, a) + (m * r**2 / 4 + m * L**2 / 12) * (_sym(b, b) + _sym(c, c))
        return about_O - parallel_axis(m, self.centre_offset(frame), frame)


def SemicircularDisk(mass, radius, axis="z", toward="-y") -> HalfCylinder:  # noqa: N802 - a shape name
    """Thin semicircular disk: a half-cylinder of zero length (mass centre 4r/(3π) from the flat edge)."""
    return HalfCylinder(mass, radius, sp.Integer(0), axis, toward)


@dataclass(frozen=True)
class Hemisphere(Shape):
    """Solid hemisphere placed by its flat-face centre O; mass centre 3r/8 along ``toward``.

    About O the inertia is 2 m r²/5 about every axis (half a sphere); central values follow exactly.
    """

    radius: sp.Expr = sp.Integer(1)
    toward: str = "-y"
    kind = "hemisphere"
    rules = {"mass": POSITIVE, "radius": POSITIVE}

    @property
    def centre_distance(self) -> sp.Expr:
        return 3 * self.radius / 8

    def centre_offset(self, frame):
        return self.centre_distance * frame.unit(self.toward)

    def central_inertia(self, frame):
        m, r = self.mass, self.radius
        about_O = _about_axis(frame, "z", 2 * m * r**2 / 5, 2 * m * r**2 / 5)
        return about_O - parallel_axis(m, self.centre_offset(frame), frame)


@dataclass(frozen=True)
class RectangularPlate(Shape):
    """Thin rectangular plate with side ``a`` along ``a_axis`` and side ``b`` along ``b_axis``."""

    a: sp.Expr = sp.Integer(1)
    b: sp.Expr = sp.Integer(1)
    a_axis: str = "x"
    b_axis: str = "y"
    kind = "rectangular plate"
    rules = {"mass": POSITIVE, "a": POSITIVE, "b": POSITIVE}

    def central_inertia(self, frame):
        m, a, b = self.mass, self.a, self.b
        ea, eb, en = _axes(frame, self.a_axis, self.b_axis)
        return (m * b**2 / 12) * _sym(ea, ea) + (m * a**2 / 12) * _sym(eb, eb) \
            + (m * (a**2 + b**2) / 12) * _sym(en, en)


@dataclass(frozen=True)
class Box(Shape):
    """Uniform rectangular box with sides a, b, c along the body frame's x, y, z."""

    a: sp.Expr = sp.Integer(1)
    b: sp.Expr = sp.Integer(1)
    c: sp.Expr = sp.Integer(1)
    kind = "box"
    rules = {"mass": POSITIVE, "a": POSITIVE, "b": POSITIVE, "c": POSITIVE}

    def central_inertia(self, frame):
        m, a, b, c = self.mass, self.a, self.b, self.c
        return inertia(frame.ref, m * (b**2 + c**2) / 12, m * (a**2 + c**2) / 12, m * (a**2 + b**2) / 12)


@dataclass(frozen=True)
class PointMass(Shape):
    """A particle: mass without rotational inertia."""

    kind = "point mass"

    def central_inertia(self, frame):
        return Dyadic(0)


@dataclass(frozen=True)
class Massless(Shape):
    """A massless body (a collar, a link) that carries loads and constraints: ΣF = 0, ΣM = 0."""

    mass: sp.Expr = sp.Integer(0)
    kind = "massless"
    rules = {"mass": NONNEGATIVE}

    def central_inertia(self, frame):
        return Dyadic(0)


@dataclass(frozen=True)
class Inertia(Shape):
    """A user-given inertia: tensor components in the body axes.

    ``Ixy``, ``Iyz``, ``Izx`` are components of the inertia tensor (I_xy = −∫ x y dm).  With
    ``about="reference"`` they are about the reference point and ``centre`` (components in the body
    frame) locates the mass centre from it; the central inertia follows by the parallel-axis theorem.
    """

    Ixx: sp.Expr = sp.Integer(0)
    Iyy: sp.Expr = sp.Integer(0)
    Izz: sp.Expr = sp.Integer(0)
    Ixy: sp.Expr = sp.Integer(0)
    Iyz: sp.Expr = sp.Integer(0)
    Izx: sp.Expr = sp.Integer(0)
    centre: tuple = field(default=(0, 0, 0))
    about: str = "centre"
    kind = "given inertia"
    rules = {"mass": NONNEGATIVE, "Ixx": NONNEGATIVE, "Iyy": NONNEGATIVE, "Izz": NONNEGATIVE}

    def centre_offset(self, frame):
        cx, cy, cz = (sp.sympify(c) for c in self.centre)
        return cx * frame.x + cy * frame.y + cz * frame.z

    def central_inertia(self, frame):
        given = inertia(frame.ref, self.Ixx, self.Iyy, self.Izz, self.Ixy, self.Iyz, self.Izx)
        if self.about == "centre":
            return given
        return given - parallel_axis(self.mass, self.centre_offset(frame), frame)


SHAPES = {
    "slender_rod": SlenderRod,
    "rod": SlenderRod,
    "thin_ring": ThinRing,
    "ring": ThinRing,
    "disk": Disk,
    "solid_cylinder": Disk,
    "hollow_cylinder": HollowCylinder,
    "solid_sphere": SolidSphere,
    "sphere": SolidSphere,
    "spherical_shell": SphericalShell,
    "half_cylinder": HalfCylinder,
    "semicircular_disk": SemicircularDisk,
    "hemisphere": Hemisphere,
    "rectangular_plate": RectangularPlate,
    "plate": RectangularPlate,
    "box": Box,
    "point_mass": PointMass,
    "particle": PointMass,
    "massless": Massless,
    "inertia": Inertia,
}
