"""The model's own laws agree: the power balance dE/dt = ΣP_nc at a few numeric states.

Every solution ``solve`` returns is checked this cheap way (random states and parameter sets, the
accelerations from the solution's own M q̈ = f): when Euler's laws and the work–energy law of the same
model disagree, the model says two different things (a spring whose end moves over a body, a
potential that is not the work of its force), and the output warns.  The full comparison of every law
is ``Solution.check`` / ``rigidkin check``.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base.algebra import time_limit
from ...base.errors import RigidkinError
from ...base.trace import Trace

t = dynamicsymbols._t

#: Random states at which the power balance is evaluated (a failure at any one is a disagreement).
STATES = 6
#: The check is meant to be cheap: beyond this many seconds it is left to ``rigidkin check``.
SECONDS = 3.0


def power_balance_warnings(solution) -> list[str]:
    """One sentence per regime where dE/dt − ΣP_nc does not vanish with the solution's accelerations.

    An undecided check (too few states could be evaluated, an energy that cannot be formed, a system
    so large that the check would take more than ``SECONDS``) gives no warning: only a definite
    disagreement does.
    """

    if not solution.coordinates:        # a mode at rest: no motion, no power to balance
        return []
    try:
        with time_limit(SECONDS):
            return _warnings(solution)
    except TimeoutError:
        return []


def _warnings(solution) -> list[str]:
    from .compare import Sampler, holds_numerically
    from .energy import kinetic_energy, nonconservative_power, potential_energy
    from .manifold import manifold_of

    setup = solution.setup
    kept, setup.trace = setup.trace, Trace(law="power balance")   # the steps go to a throwaway trace
    try:
        E = kinetic_energy(setup) + potential_energy(setup)
        powers = nonconservative_power(setup)
    except (RigidkinError, NotImplementedError, TypeError, ValueError):
        return []
    finally:
        setup.trace = kept
    P = sum((p.power for p in powers), sp.Integer(0))
    out = []
    for i, regime in enumerate(solution.regimes):
        try:
            e = setup.reduction.reduce(sp.diff(E, t) - P).xreplace(dict(regime.signs))   # q̇_d of kept q_d
            used = [r for r in setup.reactions if e.has(r)]
            if used:
                e = e.xreplace({r: regime.reactions[r.name] for r in used}).xreplace(dict(regime.signs))
            ok, how = holds_numerically(e, regime, solution.coordinates,
                                         Sampler(STATES, seed=11, manifold=manifold_of(solution)))
        except (RigidkinError, ArithmeticError, KeyError, TypeError, ValueError, RecursionError):
            continue
        if ok or "fails" not in how:
            continue
        tag = f" (regime {i + 1}: {regime.describe()})" if len(solution.regimes) > 1 else ""
        names = ", ".join(p.name for p in powers if not p.is_zero) or "none"
        out.append(f"the model's laws disagree{tag}: dE/dt ≠ ΣP_nc at a random state ({how}; E = T + U with "
                   f"U of {', '.join(ld.name for ld in setup.loads if getattr(ld, 'conservative', False)) or 'no load'}"
                   f", non-conservative powers: {names}). A load's potential or power does not match its force "
                   f"(a load at a point that moves over its body?); compare the laws with `rigidkin check`.")
    return out


__all__ = ["power_balance_warnings", "STATES"]
