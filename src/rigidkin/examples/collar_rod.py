"""Card collar-rod: a collar on a frictionless horizontal track with a pendulum rod pinned to it."""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("collar-rod", title="Collar on a track with a pendulum rod",
                  statement="A collar of mass m1 slides without friction on a horizontal track; a uniform "
                            "slender rod (mass m2, length l) pinned to it swings in the vertical plane.")
    m1 = s.parameter("m1", "kg", "mass of the collar", value=2)
    m2 = s.parameter("m2", "kg", "mass of the rod", value=1)
    l = s.parameter("l", "m", "length of the rod", value=1)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    x = s.coordinate("x", "position of the collar along the track, +Ex", kind="length", initial=0, rate=0)
    theta = s.coordinate("theta", "angle of the rod from the downward vertical, counter-clockwise",
                         initial=0.5, rate=0)
    F = s.inertial
    R = s.frame("R", angle=theta, description="fixed in the rod; -Ry from the pin to the free end")
    P = s.point("P", s.origin, x * F.x, description="the pin, at the collar")
    G = s.point("G", P, -l / 2 * R.y, description="mass centre of the rod")
    collar = s.body("collar", rk.shapes.PointMass(m1), frame=F, at=P)
    rod = s.body("rod", rk.shapes.SlenderRod(m2, l, axis="y"), frame=R, at=G)
    s.collar("track", collar, along=F.x, normal_name="N", couple_name="M_track")
    s.pin("P", P, rod, collar)
    s.gravity(g)
    return s
