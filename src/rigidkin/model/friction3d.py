"""Coulomb sliding friction in three dimensions: the slip velocity anywhere in the tangent plane.

At the contact point P of a body on a surface (unit normal n into the body, tangent basis t1, t2 with
(n, t1, t2) right-handed) the slip velocity is the velocity of the body's material point at P relative
to the surface, v_s = s1 t1 + s2 t2 (its normal part vanishes while the contact is closed).

* slipping (|v_s| > 0): the friction is F = −µk N û, with û = v_s/|v_s| the unit vector of the slip
  velocity, û = û1 t1 + û2 t2, û_i = s_i/√(s1² + s2²).  û1 and û2 are named quantities (printed û_P1,
  û_P2, evaluated by their definition), so the equations of motion of a slipping mode are written with
  the slip direction as one unknown unit vector, valid while |v_s| > 0 — one regime, not one per sign.
* sticking (rolling without slip, v_s = 0): two no-slip rows with reactions F1, F2 along t1, t2, valid
  while the friction needed lies in the cone √(F1² + F2²) ≤ µs N.

For the simulator (``numeric/slip3d.py``) the slip direction is also written relative to a reference
tangent: with the t1 component as reference, û = σ (t1 + λ t2)/√(1 + λ²), λ = s2/s1, σ = sign(s1) — the
same vector wherever s1 ≠ 0, but analytic through |v_s| = 0 when the slip dies out along a direction
with s1 ≠ 0: |v_s| touches zero without changing sign, s1 crosses it.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.physics.vector import Vector

from ..base.trace import LazyEquations
from .friction_kinds import Coulomb
from .loads import Application, SlidingFriction


def direction_names(name: str) -> tuple[str, str]:
    """The names of the slip-direction components û1, û2 at contact ``name``."""
    return f"û_{name}1", f"û_{name}2"


def tangents(kin, normal: Vector) -> list[Vector]:
    """t1, t2 completing the surface normal n to a right-handed basis (n, t1, t2)."""
    return kin.tangent_basis(normal)


def slip_components(kin, relative_velocity: Vector, normal: Vector) -> tuple[sp.Expr, sp.Expr]:
    """(s1, s2): the slip velocity along t1 and t2."""
    t1, t2 = tangents(kin, normal)
    return kin.simplify_expr(relative_velocity.dot(t1)), kin.simplify_expr(relative_velocity.dot(t2))


def direction_symbols(name: str) -> tuple[sp.Symbol, sp.Symbol]:
    """û1, û2: the slip direction's components at contact ``name``, unknowns of the slipping mode's equations
    whose values are (s1, s2)/√(s1² + s2²) (:func:`direction_values`)."""
    n1, n2 = direction_names(name)
    return sp.Symbol(n1, real=True), sp.Symbol(n2, real=True)


def direction_values(s1: sp.Expr, s2: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """(û1, û2) = (s1, s2)/√(s1² + s2²): the unit vector of the slip velocity."""
    speed = sp.sqrt(s1**2 + s2**2)
    return s1 / speed, s2 / speed


def referenced_direction(s1: sp.Expr, s2: sp.Expr, reference: int, sigma) -> tuple[sp.Expr, sp.Expr]:
    """û written relative to the reference tangent (1 or 2) with σ its component's sign: analytic where
    that component is nonzero, through |v_s| = 0 included (the simulator's form)."""
    if reference == 1:
        lam = s2 / s1
        root = sp.sqrt(1 + lam**2)
        return sigma / root, sigma * lam / root
    mu = s1 / s2
    root = sp.sqrt(1 + mu**2)
    return sigma * mu / root, sigma / root


@dataclass(eq=False)
class SlidingFriction3D(SlidingFriction):
    """Coulomb sliding friction F = −µk N û at a contact in 3D (see the module docstring).

    ``contact`` is the :class:`~rigidkin.model.constraints.Contact` it acts at: its contact point (a
    sphere's C − r n, a disk's rim point) and its relative velocity are the contact's own.
    """

    contact: object = None

    def contact_location(self, kin) -> Vector:
        return self.contact.location(kin) if self.contact is not None else super().contact_location(kin)

    def relative_velocity(self, kin) -> Vector:
        return self.contact.relative_velocity(kin) if self.contact is not None else super().relative_velocity(kin)

    def slip_components(self, kin) -> tuple[sp.Expr, sp.Expr]:
        return slip_components(kin, self.relative_velocity(kin), self.normal)

    def direction(self) -> tuple[sp.Symbol, sp.Symbol]:
        return direction_symbols(self.name)

    def direction_map(self, setup) -> dict:
        """û1, û2 → their values in the mode's independent coordinates."""
        s1, s2 = (setup.scalar(s) for s in self.slip_components(setup.kin))
        return dict(zip(self.direction(), direction_values(s1, s2)))

    def trace_kinematics(self, setup) -> None:
        """The slip velocity and its direction, as the method states them (Kinematics)."""

        s1, s2 = sp.symbols(f"s_{self.name}1 s_{self.name}2", real=True)
        u1, u2 = self.direction()
        n1, n2 = direction_names(self.name)

        def equations():
            v1, v2 = (setup.kin.simplify_expr(setup.scalar(s)) for s in self.slip_components(setup.kin))
            return [(s1, v1), (s2, v2), (u1, s1 / sp.sqrt(s1**2 + s2**2)), (u2, s2 / sp.sqrt(s1**2 + s2**2))]

        setup.trace.add("Kinematics", f"Slip velocity and its direction at {self.name}", LazyEquations(equations),
                        f"v_s = s1 t1 + s2 t2 is the velocity of the material point of {self.body.name} at "
                        f"{self.name} relative to the surface; while it slips (|v_s| > 0) the friction is "
                        f"−µ N û against it, û = v_s/|v_s| = {n1} t1 + {n2} t2.")

    def sign_choices(self, kin):
        return []         # one regime: the direction is the unit vector û, valid while |v_s| > 0

    def applications(self, kin):
        t1, t2 = tangents(kin, self.normal)
        u1, u2 = self.direction()
        force = -self.mu * self._abs_normal() * (u1 * t1 + u2 * t2)
        loc = self.contact_location(kin)
        out = [Application(self.body, None, force, f"sliding friction {self.name} on {self.body.name}",
                           self.name, location=loc)]
        if self.against_body is not None:
            out.append(Application(self.against_body, None, -force,
                                   f"sliding friction {self.name} on {self.against_body.name}", self.name,
                                   location=loc))
        return out


def slip_validity(contact, setup, react) -> list[tuple[sp.Expr, str]]:
    """The 3D condition of a sticking contact as (margin ≥ 0, words): the friction within the cone µs N.
    (A slipping contact's regime, |v_s| > 0, is where its direction û is defined.)"""
    kin = setup.kin
    if kin.planar or not isinstance(contact.friction, Coulomb):
        return []
    state = setup.states.get(contact.name)
    out = []
    if state == "stick":
        names = [f"{contact.F.name}{i}" for i in (1, 2)]
        if str(contact.N) in react and all(n in react for n in names):
            N, F1, F2 = react[str(contact.N)], react[names[0]], react[names[1]]
            mu = contact.friction.static
            word = "µsN" if contact.friction.two else "µN"
            out.append((kin.simplify_expr(mu**2 * N**2 - F1**2 - F2**2),
                        f"friction at {contact.name} within the cone {word} (no slip): (µN)² − F1² − F2²"))
    return out
