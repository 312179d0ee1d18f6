"""The balance laws, one module each, and the dispatcher ``solve_with``."""

from __future__ import annotations

from ..errors import ModelError

METHODS = ("newton-euler",)


def solve_with(system, method: str, mode: dict, independent, substitutions: dict):
    """Derive the equations of motion of ``system`` in ``mode`` with the law named ``method``."""
    from ..mode import setup_mode
    from ..solution import solve_balance
    from ..trace import Trace
    from . import newton_euler

    key = ("solution", method, tuple(sorted(mode.items())), None if independent is None else
           tuple(map(str, independent)), tuple(sorted((str(k), str(v)) for k, v in substitutions.items())))
    if key in system._cache:
        return system._cache[key]
    setup = setup_mode(system, mode, independent, substitutions)
    if method == "newton-euler":
        trace = Trace(law=method)
        trace.extend(setup.trace)
        setup_trace, setup.trace = setup.trace, trace
        try:
            eqs = newton_euler.equations(setup)
            sol = solve_balance(setup, eqs, newton_euler.body_balances(setup), method, trace)
        finally:
            setup.trace = setup_trace
    else:
        raise ModelError(f"unknown method '{method}'.", hint=f"Use one of: {', '.join(METHODS)}.")
    system._cache[key] = sol
    return sol
