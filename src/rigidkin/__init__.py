"""rigidkin: rigid-body kinetics derived the way an engineer does it on paper.

Describe a system once (frames and bases, points, rigid bodies, constraints, loads) and derive its
kinematics, free-body loads, Euler's laws, equations of motion and reactions.
"""

from sympy.physics.vector import dynamicsymbols

from . import model
from .errors import ConstraintError, InputError, ModelError, RegimeError, RigidkinError
from .model import shapes
from .model.constraints import Coulomb
from .model.loads import V as v
from .model.system import System
from .solution import Condition, Regime, Solution

t = dynamicsymbols._t

__all__ = [
    "System", "Solution", "Regime", "Condition", "Coulomb", "shapes", "model", "t", "v",
    "RigidkinError", "ModelError", "ConstraintError", "RegimeError", "InputError",
]
__version__ = "0.1.0"
