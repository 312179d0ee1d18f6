"""Card ladder: a uniform rod sliding on a frictionless wall and floor.

θ is the angle between the rod and the wall; x is the distance of the foot B from the wall.  While
the rod touches the wall, x = l sin θ (the wall contact is a constraint), so the system has one
degree of freedom; when the wall reaction reaches zero the contact opens and x becomes free.  The floor
also waits under the upper end A (a contact that is open until A comes down onto it).
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("ladder", title="Ladder sliding on a frictionless wall and floor",
                  statement="A uniform slender rod (mass m, length l) has its upper end A on a frictionless "
                            "vertical wall and its lower end B on a frictionless floor; it starts at rest "
                            "against the wall and slides down.")
    m = s.parameter("m", "kg", "mass of the rod", value=10)
    l = s.parameter("l", "m", "length of the rod", value=2)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    theta = s.coordinate("theta", "angle between the rod and the wall, from the upward vertical, positive "
                                  "as the foot moves away from the wall", initial=0.3, rate=0)
    x = s.coordinate("x", "distance of the foot B from the wall, along Ex", kind="length")
    F = s.inertial
    R = s.frame("R", angle=theta, basis=("ex", "ey", "ez"), description="fixed in the rod; ey from B to A")
    B = s.point("B", s.origin, x * F.x, description="lower end, on the floor")
    G = s.point("G", B, l / 2 * R.y, description="mass centre")
    A = s.point("A", B, l * R.y, description="upper end, on the wall")
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
    for p in (A, B):
        p.body = rod
    s.contact("A", rod, s.line(s.origin, F.x, name="wall"), centre=A, normal_name="N_A",
              description="wall: pushes along +Ex")
    s.contact("B", rod, s.line(s.origin, F.y, name="floor"), centre=B, normal_name="N_B",
              description="floor: pushes along +Ey")
    s.contact("A_floor", rod, s.line(s.origin, F.y, name="floor"), centre=A, normal_name="N_Af",
              description="the floor under the upper end A: open until A comes down onto it")
    s.gravity(g)
    return s
