"""Card disk-spring-incline: a disk rolling on an incline, with a spring at its centre anchored up-slope.

θ is the disk's rotation, positive when it rolls down; x is the distance its centre has moved down
the slope (rolling gives x = r θ).  The spring is unstretched at θ = 0.
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("disk-spring-incline", title="Disk with a spring, rolling on an incline",
                  statement="A uniform disk (mass m, radius r) rolls without slip down a plane inclined at "
                            "beta; a spring (constant K) parallel to the incline joins its centre to a "
                            "point up-slope and is unstretched at theta = 0.")
    m = s.parameter("m", "kg", "mass of the disk", value=2)
    r = s.parameter("r", "m", "radius of the disk", value=0.2)
    K = s.parameter("K", "N/m", "spring constant", value=50)
    beta = s.parameter("beta", "rad", "inclination of the plane", value="20 deg")
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    L0 = s.parameter("L0", "m", "natural length of the spring", value=0.5)
    theta = s.coordinate("theta", "rotation of the disk, positive when it rolls down the incline",
                         initial=0, rate=0)
    x = s.coordinate("x", "distance of the centre down the incline from its position at theta = 0",
                     kind="length")
    I = s.frame("I", angle=-beta, basis=("es", "en", "ez"), description="es down the slope, en normal to it")
    D = s.frame("D", angle=-theta, description="fixed in the disk")
    C = s.point("C", s.origin, x * I.x + r * I.y, description="centre of the disk")
    Q = s.point("Q", s.origin, -L0 * I.x + r * I.y, description="anchor of the spring, up-slope")
    disk = s.body("disk", rk.shapes.Disk(m, r), frame=D, at=C)
    s.contact("P", disk, s.line(s.origin, I.y, name="incline"), radius=r, friction="rolling",
              normal_name="N", friction_name="F")
    s.spring("spring", C, Q, K, natural_length=L0)
    s.gravity(g)
    return s
