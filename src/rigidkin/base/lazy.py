"""Names of a package loaded on first use: a package's public names without importing its modules.

``rigidkin.report``, ``rigidkin.numeric`` and ``rigidkin.numeric.large`` answer their public names
(``build_document``, ``simulate``, ...) from the submodules that define them, imported only when a name is
first asked for; so importing any one submodule of the package (a light one: the batch integrator, the
record of a sweep) runs no other, and ``rigidkin --help`` stays free of sympy.
"""

from __future__ import annotations

import importlib
import sys


def names_on_first_use(package: str, where: dict[str, str]):
    """The module ``__getattr__`` of ``package``: ``where`` maps a public name to the submodule (relative,
    ``".output"``) that defines it; the name is kept in the package once loaded."""

    def __getattr__(name: str):
        if name not in where:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(where[name], package), name)
        setattr(sys.modules[package], name, value)
        return value

    return __getattr__
