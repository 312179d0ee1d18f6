"""Card disk-in-track: a uniform disk rolling without slip inside a fixed circular track.

θ is the angle of OC from the downward vertical (counter-clockwise); φ the disk's own rotation,
measured clockwise, so that rolling gives r φ̇ = (R − r) θ̇.
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("disk-in-track", title="Disk rolling inside a circular track",
                  statement="A uniform disk (mass m, radius r) rolls without slip on the inside of a fixed "
                            "circular track of radius R, in a vertical plane.")
    m = s.parameter("m", "kg", "mass of the disk", value=1)
    r = s.parameter("r", "m", "radius of the disk", value=0.1)
    R = s.parameter("R", "m", "radius of the track", value=1)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    theta = s.coordinate("theta", "angle of OC from the downward vertical, counter-clockwise", initial=0.5, rate=0)
    phi = s.coordinate("phi", "rotation of the disk, clockwise")
    A = s.frame("A", angle=theta, basis=("et", "er_in", "ez"),
                description="follows the line OC; er_in points from C towards O")
    D = s.frame("D", angle=-phi, description="fixed in the disk")
    C = s.point("C", s.origin, -(R - r) * A.y, description="centre of the disk")
    disk = s.body("disk", rk.shapes.Disk(m, r), frame=D, at=C)
    s.contact("P", disk, s.circle(s.origin, R, inside=True, name="track"), radius=r, friction="rolling",
              normal_name="N", friction_name="F")
    s.gravity(g)
    return s
