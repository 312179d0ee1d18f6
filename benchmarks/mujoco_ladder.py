"""The ladder beside a numeric engine: MuJoCo against rigidkin, to the moment the rod leaves the wall.

    python benchmarks/mujoco_ladder.py [--theta0 0.2]

MuJoCo (optional: ``pip install mujoco``): a capsule rod (mass 10 kg, length 2 m, radius 1 mm,
the inertia of a slender rod) between a frictionless floor and wall (condim 1), planar joints
(x, z slides and a hinge about y), released from rest at θ0.  The wall lets go when its contact
force vanishes; MuJoCo's soft contacts make that force chatter, so both its first and its last
zero are reported.  rigidkin: the compiled sweep (one run) and the simulator
(``rigidkin.numeric.simulate``), both to the event N_A = 0.  For each: the angle error against the
closed form θ = acos(2/3 cos θ0), the relative energy error at the event, the wall time to it.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from common import machine, table

M, L, G, R = 10.0, 2.0, 9.81, 1e-3
I_G = M * L * L / 12

XML = """
<mujoco>
  <option timestep="{dt}" integrator="{integrator}" gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1" condim="1"/>
    <geom name="wall" type="plane" size="0 0 1" zaxis="1 0 0" condim="1"/>
    <body name="rod" pos="0 0 0">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="z" type="slide" axis="0 0 1"/>
      <joint name="phi" type="hinge" axis="0 1 0"/>
      <geom name="rod" type="capsule" fromto="0 0 -{h} 0 0 {h}" size="{r}" condim="1"/>
      <inertial pos="0 0 0" mass="{m}" diaginertia="{i} {i} 1e-6"/>
    </body>
  </worldbody>
</mujoco>
"""


def energy(theta, x_g, z_g, vx, vz, w):
    return 0.5 * M * (vx * vx + vz * vz) + 0.5 * I_G * w * w + M * G * z_g


def run_mujoco(theta0: float, dt: float, integrator: str, t_max: float = 10.0):
    import mujoco

    model = mujoco.MjModel.from_xml_string(XML.format(dt=dt, integrator=integrator, h=L / 2, r=R, m=M, i=I_G))
    data = mujoco.MjData(model)
    wall_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "wall")
    data.qpos[:] = [R + L / 2 * math.sin(theta0), R + L / 2 * math.cos(theta0), -theta0]
    mujoco.mj_forward(model, data)
    e0 = energy(theta0, data.qpos[0], data.qpos[1], 0, 0, 0)
    force = np.zeros(6)
    first = last = None
    pushed = False
    t0 = time.perf_counter()
    while data.time < t_max:
        mujoco.mj_step(model, data)
        fw = 0.0
        for k in range(data.ncon):
            c = data.contact[k]
            if wall_id in (c.geom1, c.geom2):
                mujoco.mj_contactForce(model, data, k, force)
                fw += abs(force[0])
        theta = -data.qpos[2]
        state = (data.time, theta, energy(theta, data.qpos[0], data.qpos[1], *data.qvel[:2], -data.qvel[2]))
        if fw > 0:
            pushed = True
            last = None
        elif pushed:
            if first is None:
                first = state + (time.perf_counter() - t0,)
            if last is None:
                last = state + (time.perf_counter() - t0,)
        if data.qpos[0] - R - L / 2 * math.sin(theta) > 0.05 or theta > 1.5:
            break        # the rod is well clear of the wall: the last zero is behind us
    return first, last, e0


def run_rigidkin(theta0: float):
    from rigidkin import examples
    from rigidkin.numeric import simulate
    from rigidkin.numeric.sweeps.sweep import sweep

    s = examples.build("ladder")
    sweep(s, {"theta": [theta0]}, stop_at="N_A")               # derive and compile (cached)
    t0 = time.perf_counter()
    res = sweep(s, {"theta": [theta0]}, stop_at="N_A", workers=1)
    wall_sweep = time.perf_counter() - t0
    th, x, w, vx = res.event_state("N_A")[0]
    xg, zg = x - L / 2 * math.sin(th), L / 2 * math.cos(th)
    vxg, vzg = vx - L / 2 * math.cos(th) * w, -L / 2 * math.sin(th) * w
    e0 = M * G * L / 2 * math.cos(theta0)
    sweep_row = (th, energy(th, xg, zg, vxg, vzg, w) / e0 - 1, wall_sweep)
    simulate(s, 0.1, initial_state={"theta": theta0})           # derive the modes once
    t0 = time.perf_counter()
    sim = simulate(s, 3.0, initial_state={"theta": theta0})
    wall_sim = time.perf_counter() - t0
    ev = next(e for e in sim.events if e.contact == "A")
    st = ev.state
    th, x, w, vx = st["theta"], st["x"], st["dot(theta)"], st["dot(x)"]
    xg, zg = x - L / 2 * math.sin(th), L / 2 * math.cos(th)
    vxg, vzg = vx - L / 2 * math.cos(th) * w, -L / 2 * math.sin(th) * w
    sim_row = (th, energy(th, xg, zg, vxg, vzg, w) / e0 - 1, wall_sim)
    return sweep_row, sim_row


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--theta0", type=float, default=0.2, help="release angle from the wall [rad]")
    a = ap.parse_args(argv)
    th0 = a.theta0
    exact = math.acos(2 / 3 * math.cos(th0))
    print(f"# Ladder: MuJoCo and rigidkin ({machine()})\nθ0 = {th0} rad; exact contact loss at "
          f"{math.degrees(exact):.4f}°", flush=True)
    rows = []
    (th, de, wt), (th2, de2, wt2) = run_rigidkin(th0)
    rows.append(["rigidkin sweep (compiled DOP853)", "-", math.degrees(th - exact), de, wt])
    rows.append(["rigidkin simulate (solve_ivp DOP853)", "-", math.degrees(th2 - exact), de2, wt2])
    try:
        import mujoco  # noqa: F401
    except ImportError:
        print(table("Wall-contact loss", ["engine", "dt", "angle error °", "energy error", "wall s"], rows,
                    "MuJoCo is not installed (pip install 'rigidkin[bench]'): no MuJoCo rows."))
        return
    for integrator in ("Euler", "RK4", "implicitfast"):
        for dt in (1e-3, 1e-4):
            first, last, e0 = run_mujoco(th0, dt, integrator)
            for label, st in (("first zero", first), ("last zero", last)):
                if st is None:
                    rows.append([f"MuJoCo {integrator}, {label}", dt, "never", None, None])
                    continue
                t_, th_m, e_, wall = st
                rows.append([f"MuJoCo {integrator}, {label}", dt, math.degrees(th_m - exact), e_ / e0 - 1, wall])
    print(table("Wall-contact loss: angle error against acos(2/3 cos θ0), relative energy error, wall time to it",
                ["engine", "dt", "angle error °", "energy error", "wall s"], rows,
                "energy error = E(event)/E(0) − 1 (E = T + V, V from the floor); MuJoCo's wall force is a soft "
                "contact force: its first and last zero bracket the loss."), flush=True)


if __name__ == "__main__":
    main()
