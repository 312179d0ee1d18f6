"""A mode of a system: the state of every contact (open, slipping, sticking) and what follows from it.

``setup_mode`` gathers, for one mode, the constraint rows that are active, the loads (the system's
own and the sliding friction of slipping contacts), every force and torque application with the
unknown reactions they carry, the signs on which friction directions depend, and the reduction to
independent coordinates.  Every balance law starts from the same ``ModeSetup``, so they all see the
same free-body diagrams.  It records the frames, coordinates and kinematics in the trace.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import sympy as sp

from ..base.errors import ModelError
from ..base.printing import text
from ..base.trace import LazyEquations, Trace
from ..model.loads import Application, SignChoice
from ..model.speeds import is_quasi
from .derivation import derivation_of
from .indeterminate import rest_configuration
from .kinematics import Kinematics, Reduction, reduce_constraints


@dataclass
class ModeSetup:
    """Everything the laws need for one mode of one system."""

    system: object
    kin: Kinematics
    states: dict
    rows: list
    loads: list
    applications: list[Application]
    reactions: list[sp.Symbol]
    sign_choices: list[SignChoice]
    reduction: Reduction
    substitutions: dict
    trace: Trace = field(default_factory=Trace)
    held: tuple = ()     # contacts whose friction the sticking ones carry (statically indeterminate)

    def vector(self, v):
        """A vector with the dependent rates and accelerations eliminated (q_d kept: frames may turn with them)."""
        return self.reduction.reduce(v)

    def scalar(self, e):
        """A scalar in the independent coordinates: rates eliminated, integrated q_d and substitutions applied."""
        e = self.reduction.to_independent(sp.sympify(e))
        return e.xreplace(self.substitutions) if self.substitutions else e

    @property
    def unilateral(self) -> list:
        """(reaction, row) for each unilateral normal reaction active in this mode."""
        return [(r.reaction, r) for r in self.rows if r.unilateral]


def mode_key(system, mode: dict, independent, substitutions, integrate: bool = True) -> tuple:
    ind = None if independent is None else tuple(str(q) for q in independent)
    return (tuple(sorted(mode.items())), ind, tuple(sorted((str(k), str(v)) for k, v in substitutions.items())),
            integrate)


def setup_mode(system, mode: dict | None = None, independent=None, substitutions: dict | None = None,
               integrate: bool = True) -> ModeSetup:
    """Build (and keep in the system's derivation) the ModeSetup for ``mode``.

    With ``integrate=False`` the dependent coordinates whose relation comes from integrating a rate
    relation (φ = (R − r)θ/r, with a constant fixed by the initial configuration) stay coordinates of
    their own: the equations hold whatever the constant (a mode entered later in a simulation).
    """
    mode = dict(mode or {})
    substitutions = dict(substitutions or {})
    key = mode_key(system, mode, independent, substitutions, integrate)
    if (kept := derivation_of(system).setup(key)) is not None:
        return kept
    for name in mode:
        if name not in system.constraints:
            raise ModelError(f"the mode names '{name}', which is not a constraint of the system.",
                             where="mode", hint=f"Constraints: {', '.join(system.constraints) or 'none'}.")
    kin = derivation_of(system).kinematics(checks=lambda k: (_check_model(system, k), _check_fixed_points(system, k)))
    trace = Trace(law="kinematics")
    _trace_frames(system, kin, trace)
    states, rows, loads = {}, [], list(system.loads.values())
    for name, c in system.constraints.items():
        st = mode.get(name) or c.default_state(kin)
        if st not in c.states:
            raise ModelError(f"state '{st}' is not one of {', '.join(c.states)}.", where=f"mode of {name}")
        states[name] = st
        rows.extend(c.rows(kin, st))
        loads.extend(c.loads(kin, st))
    red = reduce_constraints(system, kin, rows, independent, trace)
    if not integrate and red.rate_integrated:
        red = replace(red, coord_map={k: v for k, v in red.coord_map.items() if k not in red.rate_integrated},
                      rate_integrated=frozenset())
    held = _held_contacts(system, kin, red, loads, mode, trace)
    if held and integrate and not red.independent:      # at rest, held: where the closed gaps put it
        red.coord_map = {**red.coord_map, **rest_configuration(system, kin, red.dependent,
                                                               [*red.built_in, *red.relating], trace)}
    loads = [ld for ld in loads if not (getattr(ld, "name", None) in held and ld.kind == "sliding friction")]
    apps, signs = [], []
    for ld in loads:
        apps.extend(ld.applications(kin))
        signs.extend(ld.sign_choices(kin))
    for row in rows:
        apps.extend(row.applications)
    reactions = [row.reaction for row in rows]
    # a sign choice on a quantity that vanishes identically in this mode is not a regime
    kept = []
    for sc in signs:
        if sc.rate_based and kin.is_zero(red.to_independent(sc.quantity)):
            raise ModelError(f"the slip speed of sliding friction '{sc.load}' is zero for every motion the "
                             "coordinates allow, so its direction is undefined.", where=f"friction {sc.load}",
                             hint="Make the contact rolling (stick), or add a coordinate that lets it slip.")
        kept.append(sc)
    setup = ModeSetup(system, kin, states, rows, loads, apps, reactions, kept, red, substitutions, trace)
    setup.held = held
    _trace_kinematics(setup)
    for ld in loads:                    # a load that states kinematics of its own (3D slip direction)
        if hasattr(ld, "trace_kinematics"):
            ld.trace_kinematics(setup)
    derivation_of(system).keep_setup(key, setup)
    return setup


def _held_contacts(system, kin, red, loads, mode, trace) -> tuple[str, ...]:
    """Contacts named ``slip`` whose slip speed the other constraints hold at zero (a rod at rest on two
    rough supports, one of them sticking): their friction cannot be told apart from the sticking
    contacts' friction (statically indeterminate), so it is carried by those and this contact acts
    without friction of its own in the mode.  Only where the mode names the state explicitly."""
    held = []
    for ld in loads:
        if ld.kind != "sliding friction" or mode.get(getattr(ld, "name", None)) != "slip":
            continue
        c = system.constraints.get(ld.name)
        if c is None or getattr(c, "kind", "") != "contact" or not red.dependent:
            continue
        if kin.is_zero(red.to_independent(c.slip_velocity(kin))):
            held.append(ld.name)
            trace.add("Kinematics", f"Friction at {ld.name} statically indeterminate", [],
                      f"the other constraints hold the slip speed at {ld.name} at zero, so its friction cannot be "
                      f"separated from the friction of the sticking contacts: they carry it together "
                      f"(their sum is determined, the split is not).")
    return tuple(held)


def _check_model(system, kin) -> None:
    """Something to move and something moving: coordinates, bodies, and every coordinate used."""
    if not system.bodies:
        raise ModelError("the system has no bodies, so there is nothing to derive.", where=system.name,
                         hint="Add a body with System.body(...).")
    if not system.coordinates:
        raise ModelError("the system has no coordinates, so nothing can move.", where=system.name,
                         hint="Declare the generalised coordinates with System.coordinate(...).")
    used = set()
    for p in system.points.values():
        for m, _fr in kin.position(p).args:
            used |= {f for f in m.atoms(sp.Function)}
    for fr in system.frames.values():
        for a in (fr.angle,) + tuple(fr.angles or ()):
            if a is not None:
                used |= {f for f in sp.sympify(a).atoms(sp.Function)}

    unused = [q for q in system.coordinates if q not in used and not is_quasi(system, q)]
    if unused:
        names = ", ".join(q.func.__name__ for q in unused)
        raise ModelError(f"the coordinates {names} locate no point and turn no frame, so they move nothing.",
                         where=system.name, hint="Use them in a point's offset or a frame's angle, or remove them.")


def _check_fixed_points(system, kin) -> None:
    """A point declared fixed in a body must not move relative to it (its offset from the mass centre is
    constant in the body frame); otherwise its velocity would not be the body's material velocity."""
    for p in system.points.values():
        b = p.body
        if b is None or p is b.centre:
            continue
        rel = kin.position(p) - kin.position(b.centre)
        drift = rel.dt(b.frame.ref)
        if drift != 0 and not kin.is_zero_vector(drift):
            raise ModelError(f"point {p.name} is declared fixed in body {b.name}, but it moves relative to it "
                             f"(its offset from {b.centre.name} changes in frame {b.frame.name} at "
                             f"{text(kin.simplify_vector(drift))}).", where=f"point {p.name}",
                             hint="Locate it by a vector fixed in the body's frame, or do not fix it in the "
                                  "body (a contact point that moves round a wheel is not a material point).")


def _trace_frames(system, kin, trace: Trace) -> None:
    F = system.inertial
    trace.add("Frames and coordinates", "Inertial frame",
              [], f"F is the ground; its basis {', '.join(F.basis)} is fixed "
                  f"({F.basis[2]} = {F.basis[0]} × {F.basis[1]}).")
    for c in system.coordinate_info.values():
        trace.add("Frames and coordinates", f"Coordinate {c.name}", [],
                  f"{text(c.symbol)} ({c.kind}): {c.sense or c.description or 'no sense given'}")
    for fr in system.frames.values():
        if fr.parent is None:
            continue
        eqs = [(v, v.express(fr.parent.ref)) for v in (fr.x, fr.y, fr.z)]
        if fr.sequence:
            why = (f"{fr.name} is rotated from {fr.parent.name} by the body-fixed sequence {fr.sequence} "
                   f"({', '.join(text(a) for a in fr.angles)}).")
        else:
            why = f"{fr.name} is rotated from {fr.parent.name} by {text(fr.angle)} about {text(fr.axis)}."
        if fr.description:
            why = why.rstrip(".") + f" ({fr.description})."
        trace.add("Frames and coordinates", f"Frame {fr.name} and its basis", eqs, why)


def _trace_kinematics(setup: ModeSetup) -> None:
    system, kin, red, tr = setup.system, setup.kin, setup.reduction, setup.trace
    for b in system.bodies.values():
        tr.add("Kinematics", f"Angular velocity of {b.name}",
               LazyEquations(lambda b=b: [(sp.Symbol(f"ω_{b.name}"), red.reduce(kin.omega_of(b)))]),
               f"{b.frame.name} turns with {b.name}; the angular velocity adds up along the chain of frames.")
    for b in system.bodies.values():
        G = b.centre
        tr.add("Kinematics", f"Mass centre {G.name} of {b.name}",
               LazyEquations(lambda G=G: [(sp.Symbol(f"r_{G.name}"), kin.position(G)),
                                          (sp.Symbol(f"v_{G.name}"), red.reduce(kin.velocity(G))),
                                          (sp.Symbol(f"a_{G.name}"), red.reduce(kin.acceleration(G)))]),
               "velocity and acceleration by the transport theorem, F d/dt r = B d/dt r + ω × r.")
    for note in kin.assumptions:
        tr.add("Kinematics", "Assumption", [], note)
    if not red.independent:
        moving = [k for k, v in red.rate_map.items() if v != 0]
        tr.add("Kinematics", "No degree of freedom", [(k, v) for k, v in red.rate_map.items()],
               "the constraints of this mode fix every coordinate: "
               + ("the bodies are carried along by the moving surfaces" if moving else "the bodies are at rest")
               + "; there is no equation of motion, and the reactions follow from the balance laws (statics).")
