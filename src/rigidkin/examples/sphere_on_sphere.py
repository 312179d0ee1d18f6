"""Card sphere-on-sphere: a uniform sphere rolling without slip on top of a fixed sphere.

θ is the rolling sphere's absolute rotation (clockwise from its position on top), φ the angle of
the line of centres from the upward vertical (clockwise), ρ the distance between the centres.
While in contact ρ = R + r and rolling gives (R + r) φ̇ = r θ̇; after the contact opens the sphere
flies free with three coordinates.
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("sphere-on-sphere", title="Sphere rolling on a fixed sphere",
                  statement="A uniform sphere (mass m, radius r) rolls without slip on top of a fixed "
                            "sphere of radius R, in a vertical plane through both centres.")
    m = s.parameter("m", "kg", "mass of the rolling sphere", value=1)
    r = s.parameter("r", "m", "radius of the rolling sphere", value=0.1)
    R = s.parameter("R", "m", "radius of the fixed sphere", value=1)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    theta = s.coordinate("theta", "absolute rotation of the rolling sphere, clockwise, zero on top",
                         initial=1.1, rate=0)
    phi = s.coordinate("phi", "angle of the line of centres OC from the upward vertical, clockwise")
    rho = s.coordinate("rho", "distance OC between the centres", kind="length", positive=True)
    A = s.frame("A", angle=-phi, basis=("et", "er", "ez"), description="er along the line of centres OC")
    B = s.frame("B", angle=-theta, description="fixed in the rolling sphere")
    C = s.point("C", s.origin, rho * A.y, description="centre of the rolling sphere")
    ball = s.body("sphere", rk.shapes.SolidSphere(m, r), frame=B, at=C)
    s.contact("P", ball, s.circle(s.origin, R, name="fixed sphere"), radius=r, friction="rolling",
              normal_name="N", friction_name="F")
    s.gravity(g)
    return s
