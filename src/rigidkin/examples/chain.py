"""A chain of n uniform rods (an n-link pendulum) hanging from a fixed pin and swinging in a vertical plane.

Rod i (mass m, length l) is pinned to rod i−1 at its upper end P_{i−1} (P_0 is the fixed pin O);
θ_i is its angle from the downward vertical, counter-clockwise (absolute angles).  Every pin is
built into the coordinates, so the chain has n degrees of freedom and 2n pin reactions.  It is the
scaling model of the benchmarks: the classic n-link pendulum of multibody codes.
"""

import rigidkin as rk

#: The title of the default chain (n = 5); ``rigidkin list`` reads it without building.
TITLE = "Chain of 5 uniform rods"


def build(n: int = 5) -> rk.System:
    """The chain of ``n`` identical rods (n ≥ 1), released from rest with θ_i = 0.3 + 0.1 i rad."""
    if not isinstance(n, int) or isinstance(n, bool) or n < 1:
        raise rk.ModelError(f"a chain needs a whole number of rods n ≥ 1, not {n!r}.", where="chain")
    s = rk.System(f"chain{n}", title=f"Chain of {n} uniform rods",
                  statement=f"{n} uniform slender rods (each of mass m and length l) hang end to end from a "
                            "fixed frictionless pin, joined by frictionless pins, and swing in a vertical "
                            "plane under gravity.")
    m = s.parameter("m", "kg", "mass of each rod", value=1)
    l = s.parameter("l", "m", "length of each rod", value=1)
    g = s.parameter("g", "m/s^2", "gravitational acceleration", value=9.81)
    top, above = s.origin, None
    for i in range(1, n + 1):
        th = s.coordinate(f"theta{i}", f"angle of rod {i} from the downward vertical, counter-clockwise",
                          initial=0.3 + 0.1 * i, rate=0)
        R = s.frame(f"R{i}", angle=th, basis=(f"e{i}x", f"e{i}y", f"e{i}z"),
                    description=f"fixed in rod {i}; -e{i}y from its upper end to its lower end")
        G = s.point(f"G{i}", top, -l / 2 * R.y, description=f"mass centre of rod {i}")
        rod = s.body(f"rod{i}", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
        s.pin(f"P{i - 1}", top, rod, above, description="fixed pin" if above is None else f"joins rods {i - 1}, {i}")
        if i < n:
            top = s.point(f"P{i}", top, -l * R.y, body=rod, description=f"joint of rods {i} and {i + 1}")
        above = rod
    s.gravity(g)
    return s
