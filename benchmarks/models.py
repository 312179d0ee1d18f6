"""The models the benchmarks time: baselines built with sympy.physics.mechanics (independent of rigidkin) and
rigidkin models.  The tests use the same ones (tests/helpers.py: benchmark_models), so each model is written once."""

from __future__ import annotations

import sympy as sp
import sympy.physics.mechanics as me


def kane_chain(n: int):
    """The n-rod chain (uniform rods m, l; absolute angles from the downward vertical) by KanesMethod.

    Returns (KanesMethod, q, u, (m, l, g)); ``km.mass_matrix`` and ``km.forcing`` are filled.
    """
    q = me.dynamicsymbols(f"q1:{n + 1}")
    u = me.dynamicsymbols(f"u1:{n + 1}")
    m, l, g = sp.symbols("m l g", positive=True)
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    bodies, loads, top = [], [], O
    for i in range(n):
        A = N.orientnew(f"A{i}", "Axis", (q[i], N.z))
        A.set_ang_vel(N, u[i] * N.z)
        G = top.locatenew(f"G{i}", -l / 2 * A.y)
        G.v2pt_theory(top, N, A)
        bodies.append(me.RigidBody(f"rod{i}", G, A, m, (me.inertia(A, 0, 0, m * l ** 2 / 12), G)))
        loads.append((G, -m * g * N.y))
        top = top.locatenew(f"P{i}", -l * A.y)
        top.v2pt_theory(G, N, A)
    km = me.KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=[qi.diff() - ui for qi, ui in zip(q, u)])
    km.kanes_equations(bodies, loads)
    return km, q, u, (m, l, g)


def ops_after_cse(exprs) -> int:
    """Operation count (sympy.count_ops) of expressions after common-subexpression elimination."""
    exprs = [sp.sympify(e) for e in exprs]
    subs, reduced = sp.cse(exprs, order="none")
    return int(sum(sp.count_ops(e) for _, e in subs) + sum(sp.count_ops(e) for e in reduced))


# rigidkin models of the systems of issue 31 ---------------------------------------------------------
def four_bar():
    """A four-bar linkage (1 DOF, a closed loop of three uniform rods under gravity; test_core_more uses it too)."""
    import rigidkin as rk

    s = rk.System("four-bar")
    m, L1, L2, L3, d, g = (s.parameter(n, u, value=v) for n, u, v in (
        ("m", "kg", 1), ("L1", "m", 0.3), ("L2", "m", 1.0), ("L3", "m", 0.6), ("d", "m", 0.8), ("g", "m/s^2", 9.81)))
    th1 = s.coordinate("theta1", "crank angle from Ex, counter-clockwise", initial=1.2, rate=0)
    th2 = s.coordinate("theta2", "coupler angle from Ex, counter-clockwise", initial=0.2)
    th3 = s.coordinate("theta3", "rocker angle from Ex, counter-clockwise", initial=1.9)
    F = s.inertial
    R1, R2, R3 = (s.frame(f"R{i}", angle=a) for i, a in ((1, th1), (2, th2), (3, th3)))
    A = s.point("A", s.origin, L1 * R1.x)
    B2 = s.point("B2", A, L2 * R2.x)
    D = s.point("D", s.origin, d * F.x)
    B3 = s.point("B3", D, L3 * R3.x)
    crank = s.body("crank", rk.shapes.SlenderRod(m, L1, axis="x"), frame=R1, at=s.point("G1", s.origin, L1 / 2 * R1.x))
    coupler = s.body("coupler", rk.shapes.SlenderRod(m, L2, axis="x"), frame=R2, at=s.point("G2", A, L2 / 2 * R2.x))
    rocker = s.body("rocker", rk.shapes.SlenderRod(m, L3, axis="x"), frame=R3, at=s.point("G3", D, L3 / 2 * R3.x))
    A.body, B2.body, B3.body = crank, coupler, rocker
    s.pin("O", s.origin, crank)
    s.pin("A", A, coupler, crank)
    s.pin("D", D, rocker)
    s.pin("B", B2, coupler, rocker, point_b=B3)
    s.gravity(g)
    return s


def cart_pendulum(links: int = 3):
    """A cart on a rail (pushed by P) carrying a chain of ``links`` uniform rods (absolute angles)."""
    import rigidkin as rk

    s = rk.System(f"{links}-link cart")
    M = s.parameter("M", "kg", value=2.0)
    m = s.parameter("m", "kg", value=0.5)
    l = s.parameter("l", "m", value=0.8)
    g = s.parameter("g", "m/s^2", value=9.81)
    P = s.parameter("P", "N", "push on the cart", value=0, positive=False)
    x = s.coordinate("x", "of the cart along Ex", kind="length")
    C = s.point("C", offset=x * s.inertial.x)
    cart = s.body("cart", rk.shapes.PointMass(M), frame=s.inertial, at=C)
    s.collar("rail", cart, s.inertial.x, point=C)
    top, above = C, cart
    for i in range(1, links + 1):
        th = s.coordinate(f"theta{i}", f"of rod {i} from the downward vertical", initial=0.1 * i)
        R = s.frame(f"R{i}", angle=th)
        G = s.point(f"G{i}", top, -l / 2 * R.y)
        rod = s.body(f"rod{i}", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
        s.pin(f"hinge{i}", top, rod, body_b=above)
        end = s.point(f"E{i}", top, -l * R.y, body=rod)
        top, above = end, rod
    s.gravity(g)
    s.force("push", C, P * s.inertial.x)
    return s


def cylinder_in_shell():
    """A uniform cylinder rolling inside a thin cylindrical shell that rolls on the floor (2 DOF)."""
    import rigidkin as rk

    s = rk.System("cylinder in a shell")
    M = s.parameter("M", "kg", "mass of the shell", value=2.0)
    m = s.parameter("m", "kg", "mass of the cylinder", value=1.0)
    R = s.parameter("R", "m", "radius of the shell", value=0.5)
    r = s.parameter("r", "m", "radius of the cylinder", value=0.1)
    g = s.parameter("g", "m/s^2", value=9.81)
    F = s.inertial
    x = s.coordinate("x", "centre of the shell along Ex", kind="length")
    psi = s.coordinate("psi", "rotation of the shell, clockwise")
    th = s.coordinate("theta", "of the line of centres from the downward vertical", initial=0.4)
    phi = s.coordinate("phi", "rotation of the cylinder, clockwise")
    S = s.frame("S", angle=-psi)
    A = s.frame("A", angle=th)
    D = s.frame("D", angle=-phi)
    O = s.point("Os", s.origin, x * F.x + R * F.y)
    C = s.point("C", O, -(R - r) * A.y)
    shell = s.body("shell", rk.shapes.ThinRing(M, R), frame=S, at=O)
    cyl = s.body("cylinder", rk.shapes.Disk(m, r), frame=D, at=C)
    s.contact("floor", shell, s.line(s.origin, F.y, name="floor"), radius=R, friction="rolling", normal_name="N1",
              friction_name="F1")
    s.contact("inner", cyl, s.circle(O, R, inside=True, body=shell, name="shell"), radius=r, friction="rolling",
              normal_name="N2", friction_name="F2")
    s.gravity(g)
    return s


def ball_on_turntable():
    """A ball rolling on a massive disk free to spin about the vertical (3D rolling on a moving body)."""
    import rigidkin as rk

    s = rk.System("ball on a turntable")
    m = s.parameter("m", "kg", "mass of the ball", value=1.0)
    r = s.parameter("r", "m", "radius of the ball", value=0.1)
    Md = s.parameter("Md", "kg", "mass of the turntable", value=20.0)
    a = s.parameter("a", "m", "radius of the turntable", value=1.0)
    g = s.parameter("g", "m/s^2", value=9.81)
    F = s.inertial
    psi = s.coordinate("psi", "turntable angle about Ez", rate=2.0)
    x = s.coordinate("x", "centre of the ball along Ex", kind="length", initial=0.3)
    y = s.coordinate("y", "centre of the ball along Ey", kind="length")
    z = s.coordinate("z", "height of the centre", kind="length", initial=0.1)
    T = s.frame("T", angle=psi, axis="z")
    B = s.frame("B", quaternion=True, speeds=("wx", "wy", "wz"), initial=(1, 0, 0, 0))
    C = s.point("C", offset=x * F.x + y * F.y + z * F.z)
    disk = s.body("turntable", rk.shapes.Disk(Md, a, axis="z"), frame=T, at=s.origin)
    ball = s.body("ball", rk.shapes.SolidSphere(m, r), frame=B, at=C)
    s.pin("axle", s.origin, disk, axis="T.z")
    s.contact("P", ball, s.plane(s.origin, F.z, body=disk, name="turntable"), centre=C, radius=r,
              friction="rolling", normal_name="N")
    s.gravity(g, -F.z)
    return s
