"""Card boulder-push: a sphere pushed up an incline by a plate, with friction between plate and sphere.

x is the distance of the centre up the incline; φ the sphere's rotation, clockwise (rolling gives
r φ̇ = ẋ).  The plate pushes with force P along the incline at the sphere's down-slope point E and
translates with the centre; sliding friction µP acts at E against the relative velocity there.
"""

import rigidkin as rk


def build() -> rk.System:
    s = rk.System("boulder-push", title="Boulder pushed up an incline by a bulldozer plate",
                  statement="A uniform sphere (mass m, radius r) rolls without slip on a plane inclined at "
                            "beta; a plate pushes it up the incline with a force P parallel to the incline "
                            "through its centre; the friction coefficient between plate and sphere is mu.")
    m = s.parameter("m", "kg", "mass of the boulder", value=500)
    r = s.parameter("r", "m", "radius of the boulder", value=0.6)
    beta = s.parameter("beta", "rad", "inclination of the plane", value="15 deg")
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    P = s.parameter("P", "N", "push of the plate", value=3000)
    mu = s.parameter("mu", "", "coefficient of sliding friction between plate and sphere", value=0.3)
    x = s.coordinate("x", "distance of the centre up the incline", kind="length", initial=0, rate=0.5)
    phi = s.coordinate("phi", "rotation of the sphere, clockwise")
    I = s.frame("I", angle=beta, basis=("es", "en", "ez"), description="es up the slope, en normal to it")
    S = s.frame("S", angle=-phi, description="fixed in the sphere")
    C = s.point("C", s.origin, x * I.x + r * I.y, description="centre of the sphere")
    E = s.point("E", C, -r * I.x, description="contact with the plate (down-slope point of the sphere)")
    ball = s.body("boulder", rk.shapes.SolidSphere(m, r), frame=S, at=C)
    s.contact("ground", ball, s.line(s.origin, I.y, name="incline"), radius=r, friction="rolling",
              normal_name="N", friction_name="F")
    s.force("push", E, P * I.x, body=ball, description="normal push of the plate")
    s.friction("plate", ball, centre=C, radius=r, normal=I.x, mu=mu, normal_force=P, against_point=C,
               description="sliding friction between plate and sphere")
    s.gravity(g)
    return s
