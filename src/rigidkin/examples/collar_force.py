"""Card collar-force: a rod hung from a massless collar that a known force P pushes along a track."""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("collar-force", title="Rod hung from a massless collar pushed by a force",
                  statement="A uniform slender rod (mass m, length l) hangs from a massless collar at its "
                            "end O; the collar slides without friction on a horizontal track and a known "
                            "horizontal force P acts on it.")
    m = s.parameter("m", "kg", "mass of the rod", value=1)
    l = s.parameter("l", "m", "length of the rod", value=1)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    P = s.parameter("P", "N", "force on the collar, along +Ex", value=5)
    x = s.coordinate("x", "position of the collar along the track, +Ex", kind="length", initial=0, rate=0)
    theta = s.coordinate("theta", "angle of the rod from the downward vertical, counter-clockwise",
                         initial=0, rate=0)
    F = s.inertial
    R = s.frame("R", angle=theta, description="fixed in the rod")
    O1 = s.point("C", s.origin, x * F.x, description="the collar (end O of the rod)")
    G = s.point("G", O1, -l / 2 * R.y, description="mass centre of the rod")
    collar = s.body("collar", rk.shapes.Massless(), frame=F, at=O1)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
    s.collar("track", collar, along=F.x, normal_name="N", couple_name="M_track")
    s.pin("O", O1, rod, collar)
    s.force("P", O1, P * F.x, body=collar, description="applied force P on the collar")
    s.gravity(g)
    return s
