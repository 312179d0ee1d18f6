"""Numerics: right-hand sides from the solved equations, and simulation through contact modes.

The names below are imported when first used, so that a module of this package that needs only numpy (the
batch integrator, the compiled-code cache) can be imported without sympy.  ``rigidkin.numeric.simulate`` is
the function (as it always was), not the submodule of the same name.
"""

from __future__ import annotations

import importlib
import sys
import types

_LAZY = {"simulate": ".simulate", "Phase": ".simulate", "SimulationResult": ".result", "Event": ".result",
         "SimulationError": ".rhs", "make_rhs": ".rhs"}

__all__ = ["simulate", "Phase", "SimulationResult", "Event", "SimulationError", "make_rhs"]


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


class _Package(types.ModuleType):
    """Importing the submodule ``simulate`` does not replace the function ``simulate`` by the module."""

    def __setattr__(self, name, value):
        if name in _LAZY and isinstance(value, types.ModuleType):
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
