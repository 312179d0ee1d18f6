"""The schema of a problem file (TOML), checked with pydantic: unknown fields, missing fields and wrong
types are refused before anything is built.

A problem file has, in this order of meaning (tables may come in any order in the file):

``title``, ``statement``, ``name``; ``[parameters]`` (``m = { unit = "kg", description = "...", value =
10 }``); ``[coordinates]`` (``theta = { sense = "...", kind = "angle", initial = 0, rate = 0 }``; those
declared first stay independent; ``prescribed = "Omega*t"``/``prescribed_rate``: driven by a law of t, its
effort ``drive_effort``, default ``Q_<name>``); ``[frames]`` (``R = { parent = "F", angle = "theta", axis = "z",
basis = ["er", "et", "ez"] }``); ``[points]`` (``G = { from = "O", offset = "l/2*R.y", body = "rod" }``);
``[bodies]`` (``rod = { shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at =
"G" }``); ``[constraints]`` (``type = "pin" | "contact" | "collar" | "knife_edge" | ...``); ``[loads]``
(``type = "gravity" | "force" | "torque" | "spring" | "torsional_spring" | "rotational_spring" | "damper" |
"friction" | "impulse" | ...``); ``[inputs]`` (``F = { unit = "N", description = "...", history = "..." }``) and
``[ask]``.  Field names are those of the Python API (``System.pin(name, point, body_a, ...)``).

Expressions are strings in the safe expression language (:mod:`rigidkin.io.expressions`) or numbers.
The inertial frame ``F`` (basis ``Ex, Ey, Ez``) and the origin ``O`` always exist.
"""

from __future__ import annotations

import inspect
from typing import Annotated, Literal, Union

from pydantic import Field, create_model

from ..model.shapes import SHAPES
from .schema_base import Expr, Name, Quantity, State, Strict  # noqa: F401  (public here too)


# declarations --------------------------------------------------------------------------------------------
class ParameterSpec(Strict):
    unit: str | None = None
    dimension: str | None = None
    description: str = ""
    value: Quantity | None = None
    positive: bool = True


class InputSpec(Strict):
    """An input u(t): its unit, what it is with its positive sense, and optionally its history (an expression
    of t and the parameters) for simulations."""

    unit: str | None = None
    description: str = ""
    history: Expr | None = None


class DefinitionSpec(Strict):
    """A derived quantity: ``a = { value = "sqrt(R**2 - l**2)", unit = "m" }`` (or just the expression)."""

    value: Expr
    unit: str | None = None
    description: str = ""


class CoordinateSpec(Strict):
    sense: str
    kind: Literal["angle", "length", "other"] = "angle"
    unit: str | None = None
    initial: Quantity | None = None
    rate: Quantity | None = None
    description: str = ""
    positive: bool = False
    prescribed: Expr | None = None
    prescribed_rate: Expr | None = None
    drive_effort: Name | None = None


class FrameSpec(Strict):
    parent: Name = "F"
    angle: Expr | None = None
    axis: Expr = "z"
    basis: list[Name] | None = Field(default=None, min_length=3, max_length=3)
    sequence: str | None = None
    angles: list[Expr] | None = Field(default=None, min_length=3, max_length=3)
    # a quaternion: the names of the four Euler parameters (scalar first), declared as coordinates
    quaternion: list[Name] | None = Field(default=None, min_length=4, max_length=4)
    # the frame's angular-velocity components along its basis as speeds (quaternion or sequence)
    speeds: list[Name] | None = Field(default=None, min_length=3, max_length=3)
    initial: list[Quantity] | None = Field(default=None, min_length=4, max_length=4)   # the quaternion's start
    rates: list[Quantity] | None = Field(default=None, min_length=3, max_length=3)     # the speeds' start
    description: str = ""


class PointSpec(Strict):
    from_: Name = Field(default="O", alias="from")
    offset: Expr = 0
    body: Name | None = None
    description: str = ""


# bodies: one model per shape of the shape library, chosen by ``shape`` ------------------------------------
_WORD_FIELDS = {"axis", "toward", "a_axis", "b_axis", "about"}


def _shape_fields(cls) -> dict[str, tuple]:
    """The dimensions a shape takes (from its constructor), as pydantic field definitions."""
    out = {}
    for p in inspect.signature(cls).parameters.values():
        required = p.default is inspect.Parameter.empty
        if p.name in _WORD_FIELDS:
            out[p.name] = (str, ... if required else p.default)
        elif p.name == "centre":
            out[p.name] = (list[Expr] | None, Field(default=None, min_length=3, max_length=3))
        elif p.name == "mass" and cls.__name__ == "Massless":
            continue
        else:
            out[p.name] = (Expr | None, ... if required else None)
    return out


def _body_model(key: str, cls):
    fields = _shape_fields(cls)
    return create_model(
        f"Body_{key}", __base__=Strict,
        shape=(Literal[key], ...), frame=(Name, ...), at=(Name, ...), description=(str, ""),
        centre_name=(Name | None, None), driven=(bool, False), drive_torque=(Name | None, None),
        drive_force=(Name | None, None), drive_joint=(Name | None, None),
        drive_carrier=(Name | None, None), **fields)


BODY_MODELS = {key: _body_model(key, cls) for key, cls in SHAPES.items()}
BodySpec = Annotated[Union[tuple(BODY_MODELS.values())], Field(discriminator="shape")]  # noqa: UP007


# surfaces and constraints -----------------------------------------------------------------------------
class LineSpec(Strict):
    type: Literal["line", "plane"]
    point: Name = "O"
    normal: Expr
    body: Name | None = None
    name: str = ""


class CircleSpec(Strict):
    type: Literal["circle", "sphere"]
    centre: Name = "O"
    radius: Expr
    inside: bool = False
    body: Name | None = None
    name: str = ""
    normal: Expr | None = None


SurfaceSpec = Annotated[LineSpec | CircleSpec, Field(discriminator="type")]


class PinSpec(Strict):
    type: Literal["pin"]
    point: Name
    body_a: Name
    body_b: Name | None = None
    point_b: Name | None = None
    basis: Name | None = None
    axis: str | None = None
    prefix: Name | None = None
    description: str = ""


class FrictionCoefficients(Strict):
    """Coulomb friction with static and kinetic coefficients: ``friction = { static = "mu_s", kinetic = "mu_k" }``."""

    static: Expr | None = None
    kinetic: Expr | None = None


#: ``"smooth"``, ``"rolling"``, a coefficient µ (static and kinetic alike), or a FrictionCoefficients table.
Friction = FrictionCoefficients | Expr


class ArcSpec(Strict):
    """The part of a contact profile that exists: within ``half_angle`` of ``toward`` (fixed in the body)."""

    toward: Expr
    half_angle: Expr = "pi/2"


class ContactSpec(Strict):
    type: Literal["contact"]
    body: Name
    surface: SurfaceSpec
    centre: Name | None = None
    radius: Expr = 0
    friction: Friction = "smooth"
    unilateral: bool = True
    normal_name: Name | None = None
    friction_name: Name | None = None
    arc: ArcSpec | bool | None = None     # None: the shape's own (half shapes); false: the whole circle
    restitution: Expr | None = None       # Newton's coefficient e of its impacts (0 ≤ e ≤ 1; default 0)
    description: str = ""


class CollarSpec(Strict):
    type: Literal["collar"]
    body: Name
    along: Expr
    through: Name | None = None
    point: Name | None = None
    track_body: Name | None = None
    friction: Friction = "smooth"
    normal_name: Name | None = None
    couple_name: Name | None = None
    description: str = ""


class DiskContactSpec(Strict):
    """A thin disk (wheel, coin) of ``radius`` and unit ``axis`` touching a plane at its rim (3D)."""

    type: Literal["disk_contact"]
    body: Name
    surface: SurfaceSpec
    axis: Expr
    radius: Expr
    centre: Name | None = None
    friction: Friction = "smooth"
    unilateral: bool = True
    normal_name: Name | None = None
    friction_name: Name | None = None
    restitution: Expr | None = None
    description: str = ""


class CableSpec(Strict):
    """An inextensible cable through ``points`` (ends and pulleys); ``bodies`` gives each point's body
    ("" for the ground; default: the body each point is fixed in)."""

    type: Literal["cable"]
    points: list[Name] = Field(min_length=2)
    length: Expr
    bodies: list[str] | None = None
    tension_name: Name | None = None
    description: str = ""


class WrapSpec(Strict):
    """A pulley (or drum) a rope goes round without slipping: ``{ pulley = "wheel", radius = "R", sense = "cw" }``."""

    pulley: Name
    radius: Expr
    sense: Literal["cw", "ccw"] = "cw"
    centre: Name | None = None
    mu: Expr | None = None              # belt friction: the rope grips while T_tight ≤ T_slack e^(µφ)


class RopeSpec(Strict):
    """A rope from a point over pulleys with inertia to a point (or a drum), one tension per segment."""

    type: Literal["rope"]
    path: list[Name | WrapSpec] = Field(min_length=2)
    tensions: list[Name] | None = None
    description: str = ""


class KnifeEdgeSpec(Strict):
    """A knife edge: ``point`` of ``body`` cannot move along ``direction`` (a unit vector fixed in the body)."""

    type: Literal["knife_edge"]
    body: Name
    point: Name
    direction: Expr
    reaction_name: Name | None = None
    description: str = ""


class VelocityConstraintSpec(Strict):
    """A velocity constraint ``expression`` = 0, linear in the rates dot(q); reaction: its multiplier."""

    type: Literal["velocity_constraint"]
    expression: Expr
    reaction_name: Name | None = None
    description: str = ""


ConstraintSpec = Annotated[PinSpec | ContactSpec | CollarSpec | DiskContactSpec | CableSpec | RopeSpec
                           | KnifeEdgeSpec | VelocityConstraintSpec, Field(discriminator="type")]


# loads ----------------------------------------------------------------------------------------------------
class GravitySpec(Strict):
    type: Literal["gravity"]
    g: Expr
    direction: Expr | None = None


class ForceSpec(Strict):
    type: Literal["force"]
    point: Name
    vector: Expr
    body: Name | None = None
    on: Name | None = None          # the body whose material point momentarily at ``point`` it pushes
    description: str = ""


class TorqueSpec(Strict):
    type: Literal["torque"]
    body: Name
    vector: Expr
    reaction_body: Name | None = None
    description: str = ""


class SpringSpec(Strict):
    type: Literal["spring"]
    point_a: Name
    point_b: Name
    stiffness: Expr
    natural_length: Expr = 0
    body_a: Name | None = None
    body_b: Name | None = None
    on_a: Name | None = None        # end a acts on this body's material point momentarily at point_a
    on_b: Name | None = None
    description: str = ""


class TorsionalSpringSpec(Strict):
    type: Literal["torsional_spring"]
    body_a: Name
    stiffness: Expr
    angle: Expr
    natural_angle: Expr = 0
    body_b: Name | None = None
    axis: Expr | None = None
    description: str = ""


class DamperSpec(Strict):
    type: Literal["damper"]
    point_a: Name
    law: Expr
    along: Expr | None = None
    point_b: Name | None = None
    body_a: Name | None = None
    body_b: Name | None = None
    on_a: Name | None = None
    on_b: Name | None = None
    description: str = ""


class FrictionSpec(Strict):
    type: Literal["friction"]
    body: Name
    centre: Name
    normal: Expr
    mu: Expr
    normal_force: Expr
    radius: Expr = 0
    against_body: Name | None = None
    against_point: Name | None = None
    description: str = ""


class ImpulseSpec(Strict):
    type: Literal["impulse"]
    point: Name
    vector: Expr
    body: Name | None = None
    on: Name | None = None
    description: str = ""


class RotationalSpringSpec(Strict):
    """Torque −k (θ_rel − θ0) about ``axis`` on ``body_a``, the opposite on ``body_b`` (none: the ground)."""

    type: Literal["rotational_spring"]
    body_a: Name
    stiffness: Expr
    body_b: Name | None = None
    natural_angle: Expr = 0
    axis: Expr | None = None
    angle: Expr | None = None            # θ_rel when the frames do not give it
    description: str = ""


class RotationalDamperSpec(Strict):
    """Torque −c ω_rel about ``axis`` on ``body_a``, the opposite on ``body_b`` (none: the ground)."""

    type: Literal["rotational_damper"]
    body_a: Name
    coefficient: Expr
    body_b: Name | None = None
    axis: Expr | None = None
    description: str = ""


LoadSpec = Annotated[GravitySpec | ForceSpec | TorqueSpec | SpringSpec | TorsionalSpringSpec | DamperSpec
                     | FrictionSpec | ImpulseSpec | RotationalSpringSpec | RotationalDamperSpec,
                     Field(discriminator="type")]


# questions ------------------------------------------------------------------------------------------------
class QuestionBase(Strict):
    name: str | None = None
    description: str = ""
    mode: dict[Name, str] | None = None
    set: State | None = None
    after: str | None = None


class PhaseSpec(Strict):
    name: str | None = None
    mode: dict[Name, str] = {}
    set: State = {}
    until: str | None = None


class EomQ(QuestionBase):
    kind: Literal["eom"]


class ReactionQ(QuestionBase):
    kind: Literal["reaction"]
    reaction: Name
    start: State | None = None


class IntegralQ(QuestionBase):
    kind: Literal["integral"]
    start: State | None = None


class EventQ(QuestionBase):
    kind: Literal["event"]
    when: str
    start: State | None = None


class ExtremeQ(QuestionBase):
    kind: Literal["extreme"]
    coordinate: Name
    start: State | None = None


class ThresholdQ(QuestionBase):
    kind: Literal["threshold"]
    holds: str
    start: State | None = None
    over: list[Quantity] | None = Field(default=None, min_length=2, max_length=2)
    expression: Expr | None = None


class EquilibriumQ(QuestionBase):
    kind: Literal["equilibrium"]


class ImpulseQ(QuestionBase):
    kind: Literal["impulse"]
    start: State | None = None


class IntervalQ(QuestionBase):
    kind: Literal["interval"]
    duration: Expr | None = None
    until: str | None = None
    start: State | None = None
    regime: str | None = None


class PhasesQ(QuestionBase):
    kind: Literal["phases"]
    start: State | None = None
    phase: list[PhaseSpec] = Field(min_length=1)


class ValueQ(QuestionBase):
    kind: Literal["value"]
    expression: Expr
    at: State | None = None


QUESTION_MODELS = (EomQ, ReactionQ, IntegralQ, EventQ, ExtremeQ, ThresholdQ, EquilibriumQ, ImpulseQ, IntervalQ,
                   PhasesQ, ValueQ)
QuestionSpec = Annotated[EomQ | ReactionQ | IntegralQ | EventQ | ExtremeQ | ThresholdQ | EquilibriumQ | ImpulseQ
                         | IntervalQ | PhasesQ | ValueQ, Field(discriminator="kind")]


class AskSpec(Strict):
    eom: bool = True
    reactions: list[Name] | None = None
    question: list[QuestionSpec] = []


# the file ---------------------------------------------------------------------------------------------------
class ProblemFile(Strict):
    """A whole problem file."""

    title: str
    name: Name | None = None
    statement: str = ""
    parameters: dict[Name, ParameterSpec] = {}
    inputs: dict[Name, InputSpec] = {}
    definitions: dict[Name, DefinitionSpec | Expr] = {}
    coordinates: dict[Name, CoordinateSpec] = {}      # none only where a quaternion frame brings its own
    frames: dict[Name, FrameSpec] = {}
    points: dict[Name, PointSpec] = {}
    bodies: dict[Name, BodySpec] = Field(min_length=1)
    constraints: dict[Name, ConstraintSpec] = {}
    loads: dict[Name, LoadSpec] = {}
    ask: AskSpec = AskSpec()
