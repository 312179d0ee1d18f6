"""Large systems: trees of pinned bodies by the articulated-body algorithm (numpy or C), the projected
model of large 3D systems and its linearisation about a motion, and the route that picks them."""

import importlib

#: ``rigidkin.numeric.large`` was the route's module before it became this package: its names still
#: answer here (loaded on first use, so importing a submodule loads nothing more).
_ROUTE = ("SYMBOLIC_LIMIT", "numeric_route", "simulate_tree")


def __getattr__(name: str):
    if name in _ROUTE:
        return getattr(importlib.import_module(".route", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
