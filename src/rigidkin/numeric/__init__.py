"""Numerics: right-hand sides from the solved equations, and simulation through contact modes."""

from .result import Event, SimulationResult
from .rhs import SimulationError, make_rhs
from .simulate import Phase, simulate

__all__ = ["simulate", "Phase", "SimulationResult", "Event", "SimulationError", "make_rhs"]
