"""Card paper-pull: a cylinder on a sheet of paper that is jerked out from under it.

x is the centre's position (+Ex), φ the cylinder's rotation (counter-clockwise).  The sheet moves
to the right with speed V, faster than the cylinder's contact point, during the time dt it takes
to leave; sliding friction µN acts between cylinder and sheet.
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("paper-pull", title="Cylinder on a sheet pulled out from under it",
                  statement="A uniform solid cylinder (mass m, radius r) rests on a thin sheet of paper on a "
                            "table. The sheet is jerked to the right so fast that during the time dt it "
                            "takes to leave the cylinder, it always moves faster than the cylinder's "
                            "contact point. The coefficient of sliding friction is mu.")
    m = s.parameter("m", "kg", "mass of the cylinder", value=1)
    r = s.parameter("r", "m", "radius of the cylinder", value=0.05)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    mu = s.parameter("mu", "", "coefficient of sliding friction, cylinder on paper", value=0.3)
    V = s.parameter("V", "m/s", "speed of the sheet", value=5)
    s.parameter("dt", "s", "time the sheet takes to leave the cylinder", value=0.1)
    x = s.coordinate("x", "position of the centre along Ex", kind="length", initial=0, rate=0)
    phi = s.coordinate("phi", "rotation of the cylinder, counter-clockwise", initial=0, rate=0)
    F = s.inertial
    B = s.frame("B", angle=phi, description="fixed in the cylinder")
    C = s.point("C", s.origin, x * F.x + r * F.y, description="centre of the cylinder")
    S = s.point("S", s.origin, V * rk.t * F.x, description="a point of the sheet, moving with it")
    cyl = s.body("cylinder", rk.shapes.Disk(m, r), frame=B, at=C)
    s.contact("paper", cyl, s.line(S, F.y, name="sheet"), radius=r, friction=mu, normal_name="N",
              description="the sheet, translating with S")
    s.gravity(g)
    return s
