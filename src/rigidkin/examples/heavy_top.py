"""The heavy symmetric top: a body of revolution spinning about a fixed point O of its axis, under gravity.

``build()`` orients the top by 3-1-3 Euler angles — precession ψ about Ez (up), nutation θ (the
tilt of the axis from the vertical) and spin φ about the symmetry axis; they are singular at θ = 0,
the upright top.  ``build("123")`` uses tilt angles instead — α about Ex, β about the tilted y, then
the spin φ about the symmetry axis — which are regular upright, for the sleeping top.

I1 is the transverse moment of inertia about the fixed point O (so the central one is I1 − m l²),
I3 the axial moment, l the distance from O to the mass centre.  Closed forms: steady precession at
constant θ needs m g l = ψ̇ ω3 I3 − I1 ψ̇² cos θ, ω3 = φ̇ + ψ̇ cos θ; the upright (sleeping) top is
stable when I3² ω3² > 4 I1 m g l.
"""

import rigidkin as rk


def build(sequence: str = "313") -> rk.System:
    s = rk.System("heavy-top", title="Heavy symmetric top on a fixed point",
                  statement="A symmetric top (mass m, axial moment I3, transverse moment I1 about its "
                            "fixed tip O, mass centre at l from O) spins under gravity with its tip fixed.")
    m = s.parameter("m", "kg", "mass of the top", value=0.1)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    l = s.parameter("l", "m", "distance from the tip O to the mass centre", value=0.03)
    I1 = s.parameter("I1", "kg*m^2", "transverse moment of inertia about the tip O", value=1.2e-4)
    I3 = s.parameter("I3", "kg*m^2", "moment of inertia about the symmetry axis", value=4e-5)
    F = s.inertial
    if sequence == "313":
        psi = s.coordinate("psi", "precession: turn of the axis' vertical plane about Ez", rate=5.0)
        theta = s.coordinate("theta", "nutation: tilt of the symmetry axis from the upward vertical",
                             initial=0.5)
        phi = s.coordinate("phi", "spin about the symmetry axis", rate=150.0)
        angles = (psi, theta, phi)
    elif sequence == "123":
        alpha = s.coordinate("alpha", "tilt of the axis about Ex", initial=0.01)
        beta = s.coordinate("beta", "tilt of the axis about the once-tilted y axis", initial=0.0)
        phi = s.coordinate("phi", "spin about the symmetry axis", rate=150.0)
        angles = (alpha, beta, phi)
    else:
        raise rk.ModelError(f"the heavy top is built with sequence '313' or '123', not {sequence!r}.",
                            where="heavy-top")
    B = s.frame("B", sequence=sequence, angles=angles, basis=("e1", "e2", "e3"),
                description="fixed in the top; e3 along its symmetry axis, from the tip O to G")
    G = s.point("G", offset=l * B.z, description="mass centre")
    top = s.body("top", rk.shapes.Inertia(m, I1 - m * l**2, I1 - m * l**2, I3), frame=B, at=G)
    s.pin("O", s.origin, top, description="the tip rests in a fixed socket (a ball joint)")
    s.gravity(g, -F.z)
    return s
