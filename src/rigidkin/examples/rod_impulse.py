"""Card rod-impulse: a rod on a central pivot with a torsional spring, struck by an impulse at its end."""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("rod-impulse", title="Rod on a central pivot struck by an impulse",
                  statement="A uniform slender rod (mass m, length l) turns about a fixed pivot at its centre "
                            "O in a vertical plane; a torsional spring K at O is unwound when the rod hangs "
                            "at theta = 0. At rest, it is struck by an impulse F_hat at its lower end, "
                            "perpendicular to the rod.")
    m = s.parameter("m", "kg", "mass of the rod", value=2)
    l = s.parameter("l", "m", "length of the rod", value=1)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    K = s.parameter("K", "N*m/rad", "torsional spring constant", value=20)
    F_hat = s.parameter("F_hat", "N*s", "impulse at the lower end", value=1)
    theta = s.coordinate("theta", "angle of the rod from its hanging position, counter-clockwise",
                         initial=0.5, rate=0)
    R = s.frame("R", angle=theta, description="fixed in the rod; -Ry towards the lower end B")
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=s.origin)
    B = s.point("B", s.origin, -l / 2 * R.y, body=rod, description="lower end, where the impulse acts")
    s.pin("O", s.origin, rod)
    s.torsional_spring("spring", rod, K, theta)
    s.gravity(g)
    s.impulse("blow", B, F_hat * R.x, description="impulse perpendicular to the rod")
    return s
