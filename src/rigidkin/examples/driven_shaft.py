"""A uniform rod hinged to a vertical shaft that a motor turns at a constant rate Ω (a one-arm governor).

The shaft is a driven body: its frame S turns about the vertical Ey by the given angle Ω t, so it has
no coordinate of its own; the rod, hinged to it at O on the axis, swings in the shaft's plane by θ
from the downward vertical.  The drive brings, as reactions, the force and torque the motor and the
bearings must apply to keep the shaft at Ω: T_motor about Ey is "the torque needed to turn the
shaft", positive in the sense of Ω.

Closed forms: θ̈ = (Ω² cos θ − 3g/(2l)) sin θ; the relative equilibrium cos θ* = 3g/(2lΩ²) (for
Ω² > 3g/(2l)), about which the rod oscillates at Ω sin θ*; the motor torque is the rate of the
angular momentum about the shaft, T_motor = d/dt (⅓ m l² sin²θ Ω) = ⅓ m l² Ω θ̇ sin 2θ, zero at the
relative equilibrium.
"""

from sympy.physics.vector import dynamicsymbols

import rigidkin as rk

TITLE = "Rod on a shaft driven at a constant rate"


def build() -> rk.System:
    s = rk.System("driven-shaft", title=TITLE,
                  statement="A uniform rod OA (mass m, length l) is hinged at O to a vertical shaft that a motor "
                            "turns at the constant rate Omega; the rod swings in the shaft's plane.")
    t = dynamicsymbols._t
    m = s.parameter("m", "kg", "mass of the rod", value=2.0)
    l = s.parameter("l", "m", "length of the rod", value=0.8)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    Omega = s.parameter("Omega", "rad/s", "rate at which the motor turns the shaft", value=6.0)
    th = s.coordinate("theta", "angle of the rod from the downward shaft, in the shaft's plane", initial=0.5)
    S = s.frame("S", angle=Omega * t, axis="y", basis=("sx", "sy", "sz"), description="turns with the shaft")
    shaft = s.drive("shaft", S, s.origin, torque="T_motor", description="turned by the motor at Omega")
    R = s.frame("R", S, angle=th, axis="z", basis=("rx", "ry", "rz"), description="fixed in the rod")
    G = s.point("G", offset=-l / 2 * R.y, description="mass centre of the rod")
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
    s.pin("O", s.origin, rod, shaft, axis="S.z", description="hinge on the shaft's axis, its pin along sz")
    s.gravity(g, -s.inertial.y)
    return s
