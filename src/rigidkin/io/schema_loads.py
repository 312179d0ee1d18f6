"""The problem file's ``[loads]``: one table per load type (gravity, force, torque, springs, dampers,
friction, impulse), chosen by ``type``."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from .schema_base import Expr, Name, Strict


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
