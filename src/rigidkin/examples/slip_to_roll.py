"""Card slip-to-roll: a cylinder released on an incline, first frictionless, then rough.

x is the distance of the centre down the incline, φ the cylinder's rotation (clockwise, i.e. the
sense of rolling down).  On the rough part sliding friction µN acts until the slip speed ẋ − r φ̇
vanishes; from then on the cylinder rolls.
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("slip-to-roll", title="Cylinder sliding onto a rough part of an incline",
                  statement="A uniform solid cylinder (mass m, radius r) is released from rest on a plane "
                            "inclined at beta. The first stretch, of length d, is frictionless; after it "
                            "the coefficient of sliding friction is mu.")
    m = s.parameter("m", "kg", "mass of the cylinder", value=1)
    r = s.parameter("r", "m", "radius of the cylinder", value=0.1)
    beta = s.parameter("beta", "rad", "inclination of the plane", value="30 deg")
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    mu = s.parameter("mu", "", "coefficient of sliding friction on the rough part", value=0.4)
    s.parameter("d", "m", "length of the frictionless stretch", value=1)
    x = s.coordinate("x", "distance of the centre down the incline", kind="length", initial=0, rate=0)
    phi = s.coordinate("phi", "rotation of the cylinder, clockwise (the sense of rolling down)",
                       initial=0, rate=0)
    I = s.frame("I", angle=-beta, basis=("es", "en", "ez"), description="es down the slope, en normal to it")
    B = s.frame("B", angle=-phi, description="fixed in the cylinder")
    C = s.point("C", s.origin, x * I.x + r * I.y, description="centre of the cylinder")
    cyl = s.body("cylinder", rk.shapes.Disk(m, r), frame=B, at=C)
    s.contact("ground", cyl, s.line(s.origin, I.y, name="incline"), radius=r, friction=mu, normal_name="N",
              friction_name="F")
    s.gravity(g)
    return s
