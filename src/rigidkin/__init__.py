"""rigidkin: rigid-body kinetics derived the way an engineer does it on paper.

Describe a system once (frames and bases, points, rigid bodies, constraints, loads) and derive its
kinematics, free-body loads, Euler's laws, equations of motion and reactions.

The names below are loaded when first used (``rk.System`` imports the model and sympy then), so that
``import rigidkin`` and the command line's ``--help`` stay quick.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

__version__ = "0.1.0"

#: name → (module, attribute); attribute None: the module itself.
_LAZY = {
    "System": ("rigidkin.model.system", "System"),
    "Solution": ("rigidkin.solution", "Solution"),
    "Regime": ("rigidkin.solution", "Regime"),
    "Condition": ("rigidkin.solution", "Condition"),
    "Coulomb": ("rigidkin.model.constraints", "Coulomb"),
    "shapes": ("rigidkin.model.shapes", None),
    "model": ("rigidkin.model", None),
    "jupyter": ("rigidkin.report.jupyter", None),
    "v": ("rigidkin.model.loads", "V"),
    "RigidkinError": ("rigidkin.errors", "RigidkinError"),
    "ModelError": ("rigidkin.errors", "ModelError"),
    "ConstraintError": ("rigidkin.errors", "ConstraintError"),
    "RegimeError": ("rigidkin.errors", "RegimeError"),
    "InputError": ("rigidkin.errors", "InputError"),
}

__all__ = [
    "System", "Solution", "Regime", "Condition", "Coulomb", "shapes", "model", "jupyter", "t", "v",
    "RigidkinError", "ModelError", "ConstraintError", "RegimeError", "InputError",
]

if TYPE_CHECKING:                      # for type checkers and IDEs: the names as if imported eagerly
    from . import model
    from .errors import ConstraintError, InputError, ModelError, RegimeError, RigidkinError
    from .model import shapes
    from .model.constraints import Coulomb
    from .model.loads import V as v
    from .model.system import System
    from .solution import Condition, Regime, Solution


def __getattr__(name: str):
    """Load a public name on first use and keep it in the package's namespace."""
    if name == "t":
        from sympy.physics.vector import dynamicsymbols

        value = dynamicsymbols._t
    elif name in _LAZY:
        module, attr = _LAZY[name]
        mod = importlib.import_module(module)
        value = mod if attr is None else getattr(mod, attr)
    else:
        raise AttributeError(f"module 'rigidkin' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
