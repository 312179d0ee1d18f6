"""The system model: parameters, coordinates, frames, points, bodies, constraints and loads."""

from . import shapes
from .bodies import Body
from .constraints import Cable, Collar, Contact, Pin
from .frames import Frame
from .friction_kinds import Coulomb
from .loads import Damper, Force, Gravity, SlidingFriction, Spring, Torque, TorsionalSpring
from .points import Point
from .quantities import Coordinate, Parameter
from .surfaces import Circle, Line, Plane, Sphere
from .system import System

__all__ = ["shapes", "Body", "Cable", "Collar", "Contact", "Coulomb", "Pin", "Frame", "Damper", "Force", "Gravity",
           "SlidingFriction", "Spring", "Torque", "TorsionalSpring", "Point", "Coordinate", "Parameter",
           "Circle", "Line", "Plane", "Sphere", "System"]
