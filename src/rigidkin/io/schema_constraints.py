"""The problem file's ``[constraints]``: the surfaces a contact touches, and one table per constraint type
(pin, contact, collar, disk_contact, cable, rope, knife_edge, velocity_constraint), chosen by ``type``."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import Field, WrapValidator, field_validator

from .schema_base import Expr, Name, Strict


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
    restitution: Expr | None = None       # e of its jerk as it re-tightens after going slack (0 ≤ e ≤ 1; default 0)
    description: str = ""


class WrapSpec(Strict):
    """A pulley (or drum) a rope goes round without slipping: ``{ pulley = "wheel", radius = "R", sense = "cw" }``."""

    pulley: Name
    radius: Expr
    sense: Literal["cw", "ccw"] = "cw"
    centre: Name | None = None
    mu: Expr | None = None              # belt friction: the rope grips while T_tight ≤ T_slack e^(µφ)

    @field_validator("sense", mode="before")
    @classmethod
    def _sense(cls, value: Any) -> Any:
        if value not in ("cw", "ccw"):
            raise ValueError("sense must be \"cw\" (the pulley on the rope's right as it runs from the first end "
                             "to the last) or \"ccw\" (on its left)")
        return value


def _point_or_pulley(value: Any, handler: Any) -> Any:
    """A rope path entry: a point name as it is, or a table checked as a WrapSpec (its own errors, its own fields)."""
    if isinstance(value, str):
        return value
    if not isinstance(value, dict | WrapSpec):
        raise ValueError("expected a point name (a string) or a pulley table "
                         "{ pulley = BODY, radius = ..., sense = \"cw\" | \"ccw\" }")
    return handler(value)


#: One entry of a rope's path: a point name (str, passed as it is) or a pulley (WrapSpec). Not a union, so a
#: wrong pulley table is reported at its own field (path[1].sense), not as "not a string".
PathEntry = Annotated[WrapSpec, WrapValidator(_point_or_pulley)]


class RopeSpec(Strict):
    """A rope from a point over pulleys with inertia to a point (or a drum), one tension per segment."""

    type: Literal["rope"]
    path: list[PathEntry] = Field(min_length=2)
    tensions: list[Name] | None = None
    restitution: Expr | None = None       # e of its jerk as it re-tightens after going slack (0 ≤ e ≤ 1; default 0)
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
