"""Large systems: trees of pinned bodies by the articulated-body algorithm (numpy or C), the projected
model of large 3D systems and its linearisation about a motion, and the route that picks them."""

from ...base.lazy import names_on_first_use

#: ``rigidkin.numeric.large`` was the route's module before it became this package: its names still
#: answer here (loaded on first use, so importing a submodule loads nothing more).
__getattr__ = names_on_first_use(__name__, dict.fromkeys(("SYMBOLIC_LIMIT", "numeric_route", "simulate_tree"),
                                                         ".route"))
