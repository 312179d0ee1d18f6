"""Steady motions and their linearisation: a spinning top, a rolling coin, a bead in a spinning frame.

A steady motion keeps some coordinates constant while others — the *ignorable* ones, which appear
in neither the mass matrix nor the forcing (the spin of a top, the heading of a coin) — turn at
constant rates.  It is checked to be one (the accelerations of the chosen coordinates vanish there,
or it is refused with the residual); about it the reaction-free equations M(q) q̈ = f(q, q̇)
linearise to

    M δq̈ + C δq̇ + K δq = 0,   M = M(x*), C = −∂f/∂q̇, K = −∂f/∂q at the steady state x*,

(∂M/∂q q̈* drops out because q̈* = 0 on a steady motion), with dependent coordinates eliminated
(:mod:`rigidkin.analysis.linear`).  C holds the gyroscopic terms.  The characteristic polynomial
det(λ I − A) is exact (sympy); eigenvalues are numeric with the parameters' values; the critical
values of a parameter (a spin rate at which an eigenvalue crosses zero) are closed forms where sympy
finds them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from sympy.physics.vector import dynamicsymbols

from .linear import SteadyMotion, linearise_about, residual_at, single_regime

t = dynamicsymbols._t

__all__ = ["SteadyMotion", "linearise", "residual"]


def residual(solution, at: Mapping) -> dict:
    """q̈ of each independent coordinate at the state ``at``: all zero on a steady motion."""
    _, M, f = single_regime(solution, "a steady motion")
    acc = residual_at(M, f, dict(at), min(len(solution.coordinates), 4))
    return dict(zip(solution.coordinates, acc))


def linearise(solution, at: Mapping, check: bool = True, inputs: Sequence = (),
              values: Mapping | None = None) -> SteadyMotion:
    """Linearise the reaction-free equations of ``solution`` about the steady motion ``at``.

    ``at`` gives every independent rate and every coordinate that is not ignorable (coordinates
    and rates → values or expressions).  The accelerations must vanish there, or it is refused with
    them (``check=False`` skips the refusal; the residual is kept on the result).  ``inputs``: symbols
    in the forcing whose columns form B.
    """
    return linearise_about(solution, at, rest=False, inputs=inputs, check=check, values=values)
