"""A torque-free rigid body in 3D: a book (uniform box) tossed spinning, with no load at all.

The box has sides a > b > c along its frame's x, y, z, so its principal moments about the mass
centre are I1 = m(b² + c²)/12 < I2 = m(a² + c²)/12 < I3 = m(a² + b²)/12: y is the intermediate
axis.  The orientation is a body-fixed 2-1-3 sequence from the inertial frame — q1 about Ey, then q2
about the tilted x, then q3 about the body z — so a spin about the intermediate axis is q1 = Ω t with
q2 = q3 = 0, far from the sequence's singularity at q2 = ±90°.  The mass centre moves uniformly
(x, y, z); its motion is decoupled from the rotation.  Energy and |H̄|² are conserved; a spin about
the intermediate axis is unstable, growing as exp(λ t), λ = Ω sqrt((I2 − I1)(I3 − I2)/(I1 I3)).
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("torque-free", title="Torque-free rigid body (a tossed book)",
                  statement="A uniform box (a book, sides a > b > c) is tossed spinning about one of its "
                            "principal axes; no force or torque acts on it.")
    m = s.parameter("m", "kg", "mass of the book", value=1.0)
    a = s.parameter("a", "m", "longest side, along the body x", value=0.24)
    b = s.parameter("b", "m", "middle side, along the body y (the intermediate axis)", value=0.16)
    c = s.parameter("c", "m", "shortest side, along the body z", value=0.04)
    q1 = s.coordinate("q1", "first angle of the 2-1-3 sequence: about Ey", rate=10.0)
    q2 = s.coordinate("q2", "second angle: about the tilted x axis", initial=1e-3)
    q3 = s.coordinate("q3", "third angle: about the body z axis", initial=1e-3)
    x = s.coordinate("x", "mass centre along Ex", kind="length")
    y = s.coordinate("y", "mass centre along Ey", kind="length")
    z = s.coordinate("z", "mass centre along Ez", kind="length")
    F = s.inertial
    B = s.frame("B", sequence="213", angles=(q1, q2, q3), basis=("bx", "by", "bz"),
                description="fixed in the book, along its edges")
    G = s.point("G", offset=x * F.x + y * F.y + z * F.z, description="mass centre")
    s.body("book", rk.shapes.Box(m, a, b, c), frame=B, at=G)
    return s
