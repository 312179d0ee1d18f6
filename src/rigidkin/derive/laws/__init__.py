"""The balance laws, one module each, and the dispatcher ``solve_with``.

Methods: ``newton-euler`` (1st law and 2nd law about each mass centre), ``about-point:P`` (1st law and
2nd law about the point or constraint P), ``work-energy`` (dE/dt = ΣP_nc, one degree of freedom),
``lagrange`` and ``kane`` (sympy.physics.mechanics built from the same model).  The impulse–momentum
law answers questions about instants and intervals (``laws.impulse``), not equations of motion.
The names of the laws, ``parse_method`` and ``NotApplicable`` live in ``laws.methods``.
"""

from __future__ import annotations

from ...base.errors import ModelError
from ...base.trace import Trace
from ..derivation import derivation_of
from .methods import METHODS, NotApplicable, parse_method  # noqa: F401 (the laws' vocabulary)


def solve_with(system, method: str, mode: dict, independent, substitutions: dict, integrate: bool = True,
               **options):
    """Derive the equations of motion of ``system`` in ``mode`` with the law named ``method``."""
    from ..mode import setup_mode
    from ..solution import solve_balance
    from . import newton_euler

    name, options = parse_method(method, options)
    key = (name, tuple(sorted(options.items(), key=str)), tuple(sorted(mode.items())),
           None if independent is None else tuple(map(str, independent)),
           tuple(sorted((str(k), str(v)) for k, v in substitutions.items())), integrate)
    if (kept := derivation_of(system).solution(key)) is not None:
        return kept
    setup = setup_mode(system, mode, independent, substitutions, integrate)
    label = name if name != "about-point" else f"about-point:{options['point']}"
    trace = Trace(law=label)
    trace.extend(setup.trace)
    setup_trace, setup.trace = setup.trace, trace
    try:
        if name == "newton-euler":
            eqs = newton_euler.equations(setup)
            sol = solve_balance(setup, eqs, newton_euler.body_balances(setup), name, trace)
        elif name == "about-point":
            from . import about_point

            eqs = about_point.equations(setup, options["point"], options.get("body"))
            sol = solve_balance(setup, eqs, newton_euler.body_balances(setup), label, trace)
        else:
            eqs = equations_for(setup, name)
            setup.trace = setup_trace
            reference = solve_with(system, "newton-euler", mode, independent, substitutions, integrate)
            setup.trace = trace
            from .assemble import solution_from_rows

            sol = solution_from_rows(setup, eqs, name, trace, reference)
    finally:
        setup.trace = setup_trace
    derivation_of(system).keep_solution(key, sol)
    return sol


def equations_for(setup, name: str, **options) -> list:
    """The equations a law gives in ``setup`` (reaction-free for work-energy, lagrange and kane)."""
    if name == "newton-euler":
        from . import newton_euler

        return newton_euler.equations(setup)
    if name == "about-point":
        from . import about_point

        return about_point.equations(setup, options["point"], options.get("body"))
    if name == "work-energy":
        from . import energy

        return energy.equations(setup)
    if name == "lagrange":
        from . import lagrange

        return lagrange.equations(setup)
    if name == "kane":
        from . import kane

        return kane.equations(setup)
    raise ModelError(f"unknown method '{name}'.", hint=f"Use one of: {', '.join(METHODS)}.")
