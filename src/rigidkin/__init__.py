"""rigidkin: rigid-body kinetics derived the way an engineer does it on paper.

Describe a system once (frames and bases, points, rigid bodies, constraints, loads) and derive its
kinematics, free-body loads, Euler's laws, equations of motion and reactions.

The names below are loaded when first used (``rk.System`` imports the model and sympy then), so that
``import rigidkin`` and the command line's ``--help`` stay quick.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
from typing import TYPE_CHECKING

__version__ = "0.1.0"

#: name → (module, attribute); attribute None: the module itself.
_LAZY = {
    "System": ("rigidkin.model.system", "System"),
    "Solution": ("rigidkin.derive.solution", "Solution"),
    "Regime": ("rigidkin.derive.solution", "Regime"),
    "Condition": ("rigidkin.derive.solution", "Condition"),
    "Coulomb": ("rigidkin.model.constraints", "Coulomb"),
    "shapes": ("rigidkin.model.shapes", None),
    "model": ("rigidkin.model", None),
    "jupyter": ("rigidkin.report.jupyter", None),
    "v": ("rigidkin.model.loads", "V"),
    "RigidkinError": ("rigidkin.base.errors", "RigidkinError"),
    "ModelError": ("rigidkin.base.errors", "ModelError"),
    "ConstraintError": ("rigidkin.base.errors", "ConstraintError"),
    "RegimeError": ("rigidkin.base.errors", "RegimeError"),
    "InputError": ("rigidkin.base.errors", "InputError"),
}

__all__ = [
    "System", "Solution", "Regime", "Condition", "Coulomb", "shapes", "model", "jupyter", "t", "v",
    "RigidkinError", "ModelError", "ConstraintError", "RegimeError", "InputError",
]

if TYPE_CHECKING:                      # for type checkers and IDEs: the names as if imported eagerly
    from . import model
    from .base.errors import ConstraintError, InputError, ModelError, RegimeError, RigidkinError
    from .derive.solution import Condition, Regime, Solution
    from .model import shapes
    from .model.constraints import Coulomb
    from .model.loads import V as v
    from .model.system import System


def __getattr__(name: str):
    """Load a public name on first use and keep it in the package's namespace."""
    if name == "t":
        from sympy.physics.vector import dynamicsymbols

        value = dynamicsymbols._t
    elif name in _LAZY:
        module, attr = _LAZY[name]
        mod = importlib.import_module(module)
        value = mod if attr is None else getattr(mod, attr)
    elif name in _MOVED:                       # a module that moved (rk.units): the module at its new path
        value = importlib.import_module(f"rigidkin.{_MOVED[name]}")
    else:
        raise AttributeError(f"module 'rigidkin' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


#: Modules that moved when the package tree became the layer diagram: old path → new path (under
#: ``rigidkin.``).  ``import rigidkin.errors`` and ``from rigidkin.numeric import codegen`` keep working and
#: give the very module of the new path (the same object, so patches and ``isinstance`` agree).
_MOVED = {
    "algebra": "base.algebra",
    "analysis.dimensions": "base.dimensions",
    "derivation_cache": "io.derivation_cache",
    "determinacy": "derive.determinacy",
    "errors": "base.errors",
    "evaluation": "derive.evaluation",
    "kinematics": "derive.kinematics",
    "laws": "derive.laws",
    "limits": "base.limits",
    "linear": "base.linear",
    "mode": "derive.mode",
    "numeric.aba_c": "numeric.large.aba_c",
    "numeric.articulated": "numeric.large.articulated",
    "numeric.batch": "numeric.compiled.batch",
    "numeric.batch_dask": "numeric.sweeps.batch_dask",
    "numeric.cache": "numeric.compiled.cache",
    "numeric.codegen": "numeric.compiled.codegen",
    "numeric.codesafe": "numeric.compiled.codesafe",
    "numeric.contact_lcp": "numeric.contacts.contact_lcp",
    "numeric.contact_modes": "numeric.contacts.contact_modes",
    "numeric.csource": "numeric.compiled.csource",
    "numeric.exprtree": "numeric.sweeps.exprtree",
    "numeric.impact": "numeric.contacts.impact",
    "numeric.linearise": "numeric.large.linearise",
    "numeric.modes": "numeric.contacts.modes",
    "numeric.projected": "numeric.large.projected",
    "numeric.projected_assembly": "numeric.large.projected_assembly",
    "numeric.settle": "numeric.contacts.settle",
    "numeric.slip3d": "numeric.contacts.slip3d",
    "numeric.sweep": "numeric.sweeps.sweep",
    "numeric.sweep_plan": "numeric.sweeps.sweep_plan",
    "numeric.sweep_record": "numeric.sweeps.sweep_record",
    "numeric.sweep_result": "numeric.sweeps.sweep_result",
    "numeric.tables": "numeric.sweeps.tables",
    "numeric.transition": "numeric.contacts.transition",
    "numeric.tree": "numeric.large.tree",
    "outfile": "base.outfile",
    "printing": "base.printing",
    "private_files": "base.private_files",
    "regime": "derive.regime",
    "solution": "derive.solution",
    "textsafe": "base.textsafe",
    "timelimit": "base.timelimit",
    "trace": "base.trace",
    "trigforms": "base.trigforms",
    "units": "base.units",
    "vectorops": "base.vectorops",
}


class _MovedFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds an old module path of :data:`_MOVED` and answers with the module at its new path."""

    @staticmethod
    def new_path(fullname: str) -> str | None:
        parts = fullname.split(".")
        for i in range(len(parts), 1, -1):
            moved = _MOVED.get(".".join(parts[1:i]))
            if moved is not None:
                return ".".join(["rigidkin", moved, *parts[i:]])
        return None

    def find_spec(self, fullname, path=None, target=None):
        if not fullname.startswith("rigidkin.") or self.new_path(fullname) is None:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec):
        module = importlib.import_module(self.new_path(spec.name))
        spec.loader_state = module.__spec__
        return module

    def exec_module(self, module):
        module.__spec__ = module.__spec__.loader_state           # the module keeps its own spec


if not any(isinstance(f, _MovedFinder) for f in sys.meta_path):
    sys.meta_path.insert(0, _MovedFinder())      # before the path finder, which would load a copy
