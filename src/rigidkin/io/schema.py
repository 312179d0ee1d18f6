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

The tables are defined one concept per module and all named here: the building blocks in
:mod:`.schema_base`, the declarations (parameters, inputs, definitions, coordinates, frames, points) in
:mod:`.schema_declarations`, the bodies in :mod:`.schema_bodies`, the surfaces and constraints in
:mod:`.schema_constraints`, the loads in :mod:`.schema_loads`, the questions in :mod:`.schema_questions`.
"""

from __future__ import annotations

from pydantic import Field

# every table is public here too (readers name them S.ContactSpec, S.ProblemFile, ...)
from .schema_base import Expr, Name, Quantity, State, Strict  # noqa: F401
from .schema_bodies import _WORD_FIELDS, BODY_MODELS, BodySpec  # noqa: F401
from .schema_constraints import (  # noqa: F401
    ArcSpec,
    CableSpec,
    CircleSpec,
    CollarSpec,
    ConstraintSpec,
    ContactSpec,
    DiskContactSpec,
    Friction,
    FrictionCoefficients,
    KnifeEdgeSpec,
    LineSpec,
    PinSpec,
    RopeSpec,
    SurfaceSpec,
    VelocityConstraintSpec,
    WrapSpec,
)
from .schema_declarations import (  # noqa: F401
    CoordinateSpec,
    DefinitionSpec,
    FrameSpec,
    InputSpec,
    ParameterSpec,
    PointSpec,
)
from .schema_loads import (  # noqa: F401
    DamperSpec,
    ForceSpec,
    FrictionSpec,
    GravitySpec,
    ImpulseSpec,
    LoadSpec,
    RotationalDamperSpec,
    RotationalSpringSpec,
    SpringSpec,
    TorqueSpec,
    TorsionalSpringSpec,
)
from .schema_questions import (  # noqa: F401
    QUESTION_MODELS,
    AskSpec,
    EomQ,
    EquilibriumQ,
    EventQ,
    ExtremeQ,
    ImpulseQ,
    IntegralQ,
    IntervalQ,
    PhaseSpec,
    PhasesQ,
    QuestionBase,
    QuestionSpec,
    ReactionQ,
    ThresholdQ,
    ValueQ,
)


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
