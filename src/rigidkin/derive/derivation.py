"""What is derived from a System: its derivation, built in stages, each derived once and kept.

The System is the description (bodies, frames, constraints, loads); the Derivation is what follows from
it, stage by stage: the ``kinematics`` (positions, velocities and accelerations by the transport
theorem), the ``setups`` of its modes (the active constraint rows, loads and reactions of each state of
the contacts, reduced to independent coordinates), the ``solutions`` (equations of motion and reactions
by each balance law in each mode), the ``numeric`` hybrid model a simulation integrates, the
``articulated`` model of a long tree of pinned bodies, and the compiled ``kernels``.  A stage is derived
on first use and kept; a change to the description voids the whole derivation (the System resets its
slot), and :func:`derivation_of` starts a new one.  The symbolic stages (kinematics, setups, solutions)
outlive the process in the derivation cache (:meth:`Derivation.symbolic`); the numeric ones are made
again.
"""

from __future__ import annotations

from collections.abc import Callable


class Derivation:
    """The stages derived from one System (see the module's docstring); keyed stages are looked up with
    ``setup(key)``, ``solution(key)`` and ``kernel(key)`` (None until derived) and kept with ``keep_…``."""

    def __init__(self, system):
        self.system = system
        self._kinematics = None
        self._setups: dict = {}            # mode key → ModeSetup
        self._solutions: dict = {}         # (law, options, mode, independent, substitutions, integrate) → Solution
        self._hybrid = None                # the numeric hybrid model (numeric.contacts.modes.Hybrid)
        self._articulated: tuple | None = None     # (ArticulatedModel or None,) once decided
        self._kernels: dict = {}           # (mode, regime, form) → compiled Kernel

    # kinematics ----------------------------------------------------------------------------------
    def kinematics(self, checks: Callable | None = None):
        """The system's Kinematics; ``checks(kin)`` runs when it is first derived (it may refuse the model,
        and then nothing is kept)."""
        if self._kinematics is None:
            from .kinematics import Kinematics  # sympy: kept out of start-up (derive.laws is read there)

            kin = Kinematics(self.system)
            if checks is not None:
                checks(kin)
            self._kinematics = kin
        return self._kinematics

    # modes and laws ------------------------------------------------------------------------------
    def setup(self, key):
        """The ModeSetup of the mode ``key`` (:func:`rigidkin.derive.mode.mode_key`), None until derived."""
        return self._setups.get(key)

    def keep_setup(self, key, setup):
        self._setups[key] = setup
        return setup

    def solution(self, key):
        """The Solution by one law in one mode (``key``), None until derived."""
        return self._solutions.get(key)

    def keep_solution(self, key, solution):
        self._solutions[key] = solution
        return solution

    # numeric models ------------------------------------------------------------------------------
    def hybrid(self, build: Callable):
        """The numeric hybrid model (the modes' functions a simulation integrates), made by ``build()`` once."""
        if self._hybrid is None:
            self._hybrid = build()
        return self._hybrid

    def articulated(self, build: Callable):
        """The articulated-body model of a long tree of pinned bodies, or None when ``build()`` found none."""
        if self._articulated is None:
            self._articulated = (build(),)
        return self._articulated[0]

    def kernel(self, key):
        """The compiled kernel of (mode, regime, form) ``key``, None until made."""
        return self._kernels.get(key)

    def keep_kernel(self, key, kernel):
        self._kernels[key] = kernel
        return kernel

    # what outlives the process -------------------------------------------------------------------
    def symbolic(self) -> Derivation:
        """This derivation's symbolic stages only (kinematics, setups, solutions): what the derivation cache
        keeps (numeric functions and compiled code are made again)."""
        kept = Derivation(self.system)
        kept._kinematics, kept._setups, kept._solutions = self._kinematics, self._setups, self._solutions
        return kept

    def inventory(self) -> frozenset:
        """What the symbolic stages hold: ("kinematics",), ("setup", *key), ("solution", law, *key)."""
        names = {("kinematics",)} if self._kinematics is not None else set()
        names.update(("setup",) + k for k in self._setups)
        names.update(("solution",) + k for k in self._solutions)
        return frozenset(names)


def derivation_of(system) -> Derivation:
    """The system's current derivation (a new, empty one after its description changed)."""
    derived = getattr(system, "_derived", None)
    if derived is None:
        derived = system._derived = Derivation(system)
    return derived
