"""The starting state a problem declares, checked by the same rule as a simulation's before an answer uses it.

``declared_start`` takes the coordinates' declared ``initial`` values (zero where none is declared), fills the
dependent coordinates the constraints give in closed form, and puts the coordinates onto the bilateral position
constraints by Newton's method (:func:`rigidkin.numeric.state.assemble`): it returns the coordinates that moved,
or refuses (InputError) naming the constraint and its residual.  ``solve`` and ``report`` call it, so that a
problem whose declared start the constraints cannot reach is not answered as if it could.
"""

from __future__ import annotations

import numpy as np

from ..derive.derivation import derivation_of
from .contacts.modes import Hybrid
from .contacts.vocabulary import OPEN, ModeUnavailable
from .state import assembled_changes, initial_values, parameter_vector


def declared_start(system, mode: dict | None = None) -> dict[str, tuple[float, float]]:
    """The declared start assembled onto the constraints of ``mode`` (default: each contact's default state):
    name → (declared, assembled) for every coordinate that moved; {} when nothing is declared, nothing moved,
    or a parameter has no value (nothing to check numerically).  InputError when it cannot be assembled."""
    if not any(c.initial is not None for c in system.coordinate_info.values()):
        return {}
    hyb = derivation_of(system).hybrid(lambda: Hybrid(system))
    lay = hyb.layout
    if any(p.value is None for p in system.parameter_info.values()):
        return {}
    p = parameter_vector(system, lay)
    mode = dict(mode or {})
    full = {name: mode.get(name) or c.default_state(hyb.kin) for name, c in hyb.contacts.items()}
    if all(st == OPEN for st in full.values()) and not hyb.position_constraints(full).labels:
        return {}
    _, declared = initial_values(system, lay)
    y = np.zeros(2 * lay.n)
    for i, v in declared.items():
        y[i] = v
    try:
        rel_slots, rel_fn, _, _ = hyb.relation_functions(full, integrated=True)
    except ModeUnavailable:
        return {}
    for s, v in zip(rel_slots, rel_fn(0.0, *y, *p) if rel_slots else ()):
        if s not in declared and np.isfinite(float(v)):
            y[s] = float(v)
    y = hyb.assemble(full, 0.0, y, p, f"declared initial state of {system.name}")
    return assembled_changes(lay, declared, y)
