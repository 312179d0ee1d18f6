"""The Whipple bicycle of the benchmark by Meijaard, Papadopoulos, Ruina & Schwab (2007).

Four rigid bodies — rear wheel R, rear frame B (with the rider), front frame H (fork and handlebar),
front wheel F — joined by three hinges (the hubs and the steering head) and touching the level
ground at two knife-edge wheels that roll without slipping.  The axes are the paper's: Ex forward,
Ey to the right, Ez down; gravity acts along +Ez.  The rear contact point is at (x, y) on the ground;
the yaw ψ turns about Ez, the roll φ about the yawed forward axis (positive: leaning to the right),
the pitch θB about the rolled y axis; the steer δ turns the front frame about the steering axis,
which is tilted back by the head angle λ from the vertical (positive: steering to the right); θR and
θF turn the wheels about their axles.  In the reference configuration (upright, straight ahead) the
pitch is zero and every frame is aligned with the ground's axes, so the paper's Table 1 positions and
inertia tensors are entered as they are printed.

Constraints: the rear contact normal is built into the coordinates (the rear wheel's centre is at
rR above its contact, in the wheel's plane); the front wheel touching the ground relates the pitch
to roll and steer (holonomic, no closed form); the four no-slip rows cannot be integrated
(nonholonomic).  The bicycle therefore has three degrees of freedom — roll, steer and the rear
wheel's rotation — with x, y, ψ, θB and θF dependent.  The paper linearises its motion about upright
straight running at speed v = −rR θ̇R: M q̈ + v C1 q̇ + (g K0 + v² K2) q = f for q = (φ, δ);
``lean_steer_matrices`` computes M, C1, K0 and K2 from this model (see
:mod:`rigidkin.numeric.large.projected`).
"""

import sympy as sp

import rigidkin as rk

#: The title ``build()`` gives the system (``rigidkin list`` reads it without building).
TITLE = "Whipple bicycle (benchmark of Meijaard et al. 2007)"

#: Meijaard et al. (2007), Table 1: the benchmark bicycle's parameters (SI units).
BENCHMARK = {
    "w": 1.02, "c": 0.08, "lam": "pi/10", "g": 9.81,
    "rR": 0.3, "mR": 2.0, "IRxx": 0.0603, "IRyy": 0.12,
    "xB": 0.3, "zB": -0.9, "mB": 85.0, "IBxx": 9.2, "IByy": 11.0, "IBzz": 2.8, "IBxz": 2.4,
    "xH": 0.9, "zH": -0.7, "mH": 4.0, "IHxx": 0.05892, "IHyy": 0.06, "IHzz": 0.00708, "IHxz": -0.00756,
    "rF": 0.35, "mF": 3.0, "IFxx": 0.1405, "IFyy": 0.28,
}

_UNITS = {"w": "m", "c": "m", "lam": "rad", "g": "m/s^2", "rR": "m", "rF": "m", "xB": "m", "zB": "m",
          "xH": "m", "zH": "m", "mR": "kg", "mB": "kg", "mH": "kg", "mF": "kg"}

_DESCRIPTIONS = {
    "w": "wheelbase", "c": "trail", "lam": "steer axis tilt from the vertical (head angle)",
    "g": "gravitational acceleration", "rR": "rear wheel radius", "mR": "rear wheel mass",
    "IRxx": "rear wheel moment of inertia about a diameter", "IRyy": "rear wheel moment about its axle",
    "xB": "rear frame mass centre, ahead of the rear contact", "zB": "rear frame mass centre, along Ez (down)",
    "mB": "rear frame (and rider) mass", "IBxx": "rear frame inertia Ixx", "IByy": "rear frame inertia Iyy",
    "IBzz": "rear frame inertia Izz", "IBxz": "rear frame product of inertia Ixz",
    "xH": "front frame mass centre, ahead of the rear contact", "zH": "front frame mass centre, along Ez",
    "mH": "front frame mass", "IHxx": "front frame inertia Ixx", "IHyy": "front frame inertia Iyy",
    "IHzz": "front frame inertia Izz", "IHxz": "front frame product of inertia Ixz",
    "rF": "front wheel radius", "mF": "front wheel mass", "IFxx": "front wheel moment about a diameter",
    "IFyy": "front wheel moment about its axle",
}


class WhippleBicycle(rk.System):
    """The bicycle's System: ``solve`` points to the projected equations instead of running for hours."""

    def solve(self, *args, **kwargs):
        raise rk.ModelError("System.solve eliminates the dependent rates and every reaction in closed form, which "
                            "does not finish in useful time for the Whipple bicycle (five dependent rates through "
                            "the front wheel's contact geometry).", where="bicycle",
                            hint="Use rigidkin.examples.bicycle.projected() (rigidkin.numeric.large.projected): its "
                                 "linearise(), accelerations() and rhs() give the motion numerically.")


def build() -> rk.System:
    s = WhippleBicycle("bicycle", title=TITLE,
                       statement="The benchmark bicycle: rear wheel, rear frame with rider, front frame and front "
                                 "wheel, hinged at the hubs and the steering head, rolling without slip on level "
                                 "ground (Meijaard, Papadopoulos, Ruina & Schwab 2007, Table 1).")
    P = {}
    for name, value in BENCHMARK.items():
        positive = not name.startswith("z") and name != "IHxz"
        val = float(sp.pi / 10) if value == "pi/10" else value
        unit = _UNITS.get(name, "kg*m^2")
        P[name] = s.parameter(name, unit, _DESCRIPTIONS[name], value=val, positive=positive)
    F = s.inertial
    # independent coordinates first: roll, steer, rear wheel; then the dependent ones
    phi = s.coordinate("phi", "roll of the rear frame about the yawed forward axis; positive leans right")
    delta = s.coordinate("delta", "steer of the front frame about the steering axis; positive steers right")
    thR = s.coordinate("theta_R", "rotation of the rear wheel about its axle (−v/rR when rolling forward)")
    x = s.coordinate("x", "rear contact point along Ex", kind="length")
    y = s.coordinate("y", "rear contact point along Ey", kind="length")
    psi = s.coordinate("psi", "yaw of the rear frame about Ez (down)")
    thB = s.coordinate("theta_B", "pitch of the rear frame about the rolled y axis (zero when upright)")
    thF = s.coordinate("theta_F", "rotation of the front wheel about its axle")
    Y = s.frame("Y", angle=psi, axis="z", description="yaw frame")
    L = s.frame("L", parent=Y, angle=phi, axis="x", description="roll frame")
    B = s.frame("B", parent=L, angle=thB, axis="y", description="rear frame (with the rider)")
    Rw = s.frame("R", parent=B, angle=thR, axis="y", description="rear wheel")
    lam = P["lam"]
    steer_axis = sp.sin(lam) * B.x + sp.cos(lam) * B.z
    H = s.frame("H", parent=B, angle=delta, axis=steer_axis, description="front frame: fork and handlebar")
    s.frame("S", parent=H, angle=lam, axis="y", description="fixed in the front frame; Sz along the steering "
                                                                 "axis, pointing down")
    Fw = s.frame("Fw", parent=H, angle=thF, axis="y", description="front wheel")
    w, c, rR, rF = P["w"], P["c"], P["rR"], P["rF"]
    PR = s.point("P_R", offset=x * F.x + y * F.y, description="rear contact point (on the ground)")
    CR = s.point("C_R", PR, -rR * L.z, description="rear wheel centre")
    GB = s.point("G_B", CR, P["xB"] * B.x + (P["zB"] + rR) * B.z, description="rear frame mass centre")
    ST = s.point("S_H", CR, (w + c) * B.x + rR * B.z,
                 description="where the steering axis meets the ground in the reference configuration")
    CF = s.point("C_F", ST, -c * H.x - rF * H.z, description="front wheel centre")
    GH = s.point("G_H", ST, (P["xH"] - w - c) * H.x + P["zH"] * H.z, description="front frame mass centre")
    rear_wheel = s.body("rear_wheel", rk.shapes.Inertia(P["mR"], P["IRxx"], P["IRyy"], P["IRxx"]), frame=Rw, at=CR)
    rear_frame = s.body("rear_frame", rk.shapes.Inertia(P["mB"], P["IBxx"], P["IByy"], P["IBzz"], 0, 0, P["IBxz"]),
                        frame=B, at=GB)
    front_frame = s.body("front_frame", rk.shapes.Inertia(P["mH"], P["IHxx"], P["IHyy"], P["IHzz"], 0, 0,
                                                          P["IHxz"]), frame=H, at=GH)
    front_wheel = s.body("front_wheel", rk.shapes.Inertia(P["mF"], P["IFxx"], P["IFyy"], P["IFxx"]), frame=Fw, at=CF)
    ST.body = rear_frame
    ground = s.plane(s.origin, -F.z, name="ground")
    s.disk_contact("rear", rear_wheel, ground, axis=Rw.y, radius=rR, friction="rolling",
                   description="rear tyre on the ground: knife edge, no slip")
    s.disk_contact("front", front_wheel, ground, axis=Fw.y, radius=rF, friction="rolling",
                   description="front tyre on the ground: knife edge, no slip")
    s.pin("rear_hub", CR, rear_wheel, rear_frame, axis="B.y", description="rear hub")
    s.pin("steering", ST, front_frame, rear_frame, axis="S.z", description="steering head")
    s.pin("front_hub", CF, front_wheel, front_frame, axis="H.y", description="front hub")
    s.gravity(P["g"], F.z)
    return s


#: ``setup_mode`` / ``System.solve`` eliminate the dependent rates in closed form; for this model that
#: elimination does not finish in useful time, so tools that need it skip the bicycle and
#: :mod:`rigidkin.numeric.large.projected` derives its motion instead.
SYMBOLIC_SETUP = False


def projected(system: rk.System | None = None):
    """The bicycle's equations of motion projected on roll, steer and rear-wheel rates (numeric)."""
    from rigidkin.numeric.large.projected import ProjectedModel

    s = system or build()
    phi, delta, thR = s.coordinates[:3]
    return ProjectedModel(s, independent=(phi, delta, thR))


def upright(model) -> list:
    """The upright, straight-ahead configuration (every coordinate zero; the pitch follows the front contact)."""
    return model.configuration([0.0] * len(model.coordinates))


def linearise_at(model, v: float):
    """The linearisation about upright straight running at forward speed ``v`` (θ̇R = −v/rR)."""
    rR = model.values[model.system.parameters["rR"]]
    phi, delta = model.system.coordinates[:2]
    return model.linearise(upright(model), [0.0, 0.0, -v / rR], [phi, delta])


def lean_steer_matrices(model) -> dict:
    """M, C1, K0, K2 of M q̈ + v C1 q̇ + (g K0 + v² K2) q = f for q = (φ, δ), from linearisations at v = 0, 1."""
    g = float(model.values[model.system.parameters["g"]])
    still, moving = linearise_at(model, 0.0), linearise_at(model, 1.0)
    M = still.M[:2, :2]
    K0 = still.K[:2, :2] / g
    C1 = moving.C[:2, :2]
    K2 = moving.K[:2, :2] - g * K0
    return {"M": M, "C1": C1, "K0": K0, "K2": K2}


def eigenvalues(matrices: dict, v: float, g: float = 9.81):
    """Eigenvalues of the lean–steer equations at speed ``v`` from the matrices."""
    import numpy as np

    M, C, K = matrices["M"], v * matrices["C1"], g * matrices["K0"] + v**2 * matrices["K2"]
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Minv @ K, -Minv @ C]])
    return np.linalg.eigvals(A)
