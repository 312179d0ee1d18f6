"""A gyroscope in gimbals: a rotor spinning on an axle that can turn in azimuth and elevation.

The outer gimbal A turns about the vertical Ez (azimuth ψ, a hinge at O); the inner gimbal B, which
carries the axle Bx, turns about A's horizontal y axis (elevation θ, a hinge at O); the rotor C
spins on the axle (spin φ, a hinge at its centre G, at distance l from O along the axle).  The gimbals
are light (massless), so the rotor's weight is carried to O through them.  With the axle horizontal
the gyroscope precesses steadily at Ω = m g l/(I3 s) for the rotor spin s, and the bearings press
on the rotor with the gyroscopic couple I3 s Ω about By.
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("gyroscope", title="Gyroscope in light gimbals",
                  statement="A rotor (mass m, axial moment I3, transverse moment I1 about its centre) spins "
                            "on an axle of length l pivoted at O in two light gimbals (azimuth and "
                            "elevation hinges).")
    m = s.parameter("m", "kg", "mass of the rotor", value=0.5)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    l = s.parameter("l", "m", "distance from the pivot O to the rotor's centre G", value=0.1)
    r = s.parameter("r", "m", "radius of the rotor (a uniform disk)", value=0.05)
    F = s.inertial
    psi = s.coordinate("psi", "azimuth of the axle: turn of the outer gimbal about Ez", rate=1.0)
    theta = s.coordinate("theta", "elevation of the axle above the horizontal: turn of the inner gimbal "
                                  "about -Ay (positive raises the rotor)")
    phi = s.coordinate("phi", "spin of the rotor about the axle Bx", rate=300.0)
    A = s.frame("A", angle=psi, axis="z", description="outer gimbal: turns about the vertical")
    B = s.frame("B", parent=A, angle=-theta, axis="y", description="inner gimbal: Bx along the axle")
    C = s.frame("C", parent=B, angle=phi, axis="x", description="fixed in the rotor")
    G = s.point("G", offset=l * B.x, description="centre of the rotor")
    OA = s.point("O_A", offset=0, description="the pivot, as a point of the outer gimbal")
    OB = s.point("O_B", offset=0, description="the pivot, as a point of the inner gimbal")
    outer = s.body("outer", rk.shapes.Massless(), frame=A, at=OA)
    inner = s.body("inner", rk.shapes.Massless(), frame=B, at=OB)
    rotor = s.body("rotor", rk.shapes.Disk(m, r, axis="x"), frame=C, at=G)
    s.pin("azimuth", OA, outer, axis="A.z", prefix="R_A", description="azimuth hinge (bearing in the base)")
    s.pin("elevation", OB, inner, outer, point_b=OA, axis="B.y", prefix="R_E", description="elevation hinge")
    s.pin("bearing", G, rotor, inner, axis="B.x", prefix="R_S",
          description="spin bearings of the rotor on the axle")
    s.gravity(g, -F.z)
    return s
