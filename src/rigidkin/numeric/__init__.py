"""Numerics: right-hand sides from the solved equations, and simulation through contact modes.

The names below are imported when first used, so that a module of this package that needs only numpy (the
batch integrator, the compiled-code cache) can be imported without sympy.  ``rigidkin.numeric.simulate`` is
the function (as it always was), not the submodule of the same name.
"""

from __future__ import annotations

import sys
import types

from ..base.lazy import names_on_first_use

_LAZY = {"simulate": ".simulate", "Phase": ".simulate", "SimulationResult": ".result", "Event": ".result",
         "SimulationError": ".rhs", "make_rhs": ".rhs"}

__all__ = ["simulate", "Phase", "SimulationResult", "Event", "SimulationError", "make_rhs"]


__getattr__ = names_on_first_use(__name__, _LAZY)


class _Package(types.ModuleType):
    """Importing the submodule ``simulate`` does not replace the function ``simulate`` by the module."""

    def __setattr__(self, name, value):
        if name in _LAZY and isinstance(value, types.ModuleType):
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
