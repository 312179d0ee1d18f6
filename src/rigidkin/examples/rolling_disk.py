"""A rolling disk (a coin) on a horizontal plane: rolling without slip in three dimensions.

The heading ψ turns about Ez (up), the lean θ tilts the disk about its heading direction Yx, and
the spin φ turns the disk about its axle Ly; x, y, z locate its centre C.  The disk touches the
plane at the lowest point of its rim, C − a û with û the unit vector in the disk's plane pointing
up (not straight below C once it leans).  The normal row gives z = a cos θ (holonomic); rolling
gives two velocity constraints that cannot be integrated (nonholonomic), so ẋ and ẏ follow from ψ̇,
θ̇ and φ̇ and the coin keeps three degrees of freedom.  Rolling upright at spin rate Ω = φ̇ is stable
when Ω² > m g a I1 / (I3 (I3 + m a²)), i.e. Ω² > g / (3a) for a thin uniform disk.
"""

import rigidkin as rk


def build(shape: str = "disk") -> rk.System:
    """The coin; ``shape="ring"`` makes it a thin hoop (I3 = m a², I1 = m a²/2) instead."""
    if shape not in ("disk", "ring"):
        raise rk.ModelError(f"the rolling disk is a 'disk' or a 'ring', not {shape!r}.", where="rolling-disk")
    s = rk.System("rolling-disk", title="Rolling disk (coin) on a plane",
                  statement=f"A thin uniform {'disk' if shape == 'disk' else 'ring (hoop)'} (mass m, radius a) "
                            "rolls without slipping on a horizontal plane; it can lean, turn and spin.")
    m = s.parameter("m", "kg", "mass of the disk", value=0.01)
    a = s.parameter("a", "m", "radius of the disk", value=0.0125)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    F = s.inertial
    psi = s.coordinate("psi", "heading: turn of the disk's plane about Ez")
    theta = s.coordinate("theta", "lean of the disk's plane from the vertical, about the heading Yx",
                         initial=0.01)
    phi = s.coordinate("phi", "spin of the disk about its axle Ly; positive rolls it forward along Yx", rate=30.0)
    x = s.coordinate("x", "centre of the disk along Ex", kind="length")
    y = s.coordinate("y", "centre of the disk along Ey", kind="length")
    z = s.coordinate("z", "height of the centre of the disk above the plane", kind="length")
    Y = s.frame("Y", angle=psi, axis="z", description="heading frame: Yx along the line of travel")
    L = s.frame("L", parent=Y, angle=theta, axis="x", description="lean frame: Ly along the axle")
    D = s.frame("D", parent=L, angle=phi, axis="y", description="fixed in the disk")
    C = s.point("C", offset=x * F.x + y * F.y + z * F.z, description="centre of the disk")
    profile = rk.shapes.Disk(m, a, axis="y") if shape == "disk" else rk.shapes.ThinRing(m, a, axis="y")
    disk = s.body("disk", profile, frame=D, at=C)
    s.disk_contact("P", disk, s.plane(s.origin, F.z, name="ground"), axis=D.y, radius=a, friction="rolling",
                   normal_name="N", friction_name="F")
    s.gravity(g, -F.z)
    return s
