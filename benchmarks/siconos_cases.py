"""The contact benchmark cases simulated in Siconos; prints one JSON object (event times, states, CPU s).

Run with the interpreter that has Siconos (Debian: ``apt-get install python3-siconos``, then
``/usr/bin/python3 benchmarks/siconos_cases.py``); ``contacts_vs_siconos.py`` calls it through a subprocess.
The parameters come as one JSON object on the command line (the same numbers rigidkin gets).

Cases (coordinates as in the rigidkin models, each a point mass or a ball with two or three coordinates):

* ``ball``: a ball dropped h onto a floor, Newton restitution e; Siconos ``EventDriven`` (Lsodar between
  events, an impact LCP and an acceleration LCP at events).  Reports the impact times and the speeds
  before and after.
* ``incline``: a block thrown up a rough incline (µ) with speed v0, tan β ≤ µ so that it stops and stays;
  Siconos ``TimeStepping`` Moreau–Jean (θ = 0.5) with a 2D ``FrictionContact`` (``NewtonImpactFrictionNSL``).
  The stop time is the first step end with |ẋ| below 1e-9 m/s (resolution: the step h).
* ``two_supports``: a level rod falling onto two supports at unequal distances from its centre, e, smooth;
  event-driven: impact times, speeds and the impulse at each support (lever rule P_A a = P_B b).
* ``spring``: a block on a spring, released stretched on a rough floor (µ): it turns, slides back, and
  sticks once |k x| ≤ µ m g.  Same Siconos integrator; the turning times are the step ends where ẋ changes
  sign or vanishes.
* ``two_supports_rough``: the same rod with Coulomb friction µ at both supports; Moreau–Jean time stepping
  (event-driven Siconos has no friction): an impact is a step whose impulse reverses ẏ.
* ``rocking``: a block (half width b, half height h) released tilted on one lower corner, both corners
  rough (µ high enough that they do not slip), e at the corners; q = (x, y, θ), each corner a 2D frictional
  contact whose gap and tangential place are nonlinear in θ (``LagrangianScleronomousR`` with a small C
  plugin, compiled here with ``cc``: Siconos 4.4's Python relations crash in ``MoreauJeanOSI``); Moreau–Jean
  time stepping.  An impact is the step around a sign change of θ where ω jumps most.
"""

import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import siconos.kernel as sk


def _cpu():
    return time.process_time()


def ball(p):
    """Bouncing ball, event-driven: impact times and normal speeds before / after each impact."""
    g, h, e, r, m, T = p["g"], p["h"], p["e"], p["r"], p["m"], p["T"]
    t0 = _cpu()
    q0, v0 = [r + h], [0.0]
    ds = sk.LagrangianLinearTIDS(q0, v0, np.array([[m]]))
    ds.setFExtPtr(np.array([-m * g]))
    inter = sk.Interaction(sk.NewtonImpactNSL(e), sk.LagrangianLinearTIR(np.array([[1.0]]), np.array([-r])))
    nsds = sk.NonSmoothDynamicalSystem(0.0, T)
    nsds.insertDynamicalSystem(ds)
    nsds.link(inter, ds)
    sim = sk.EventDriven(nsds, sk.TimeDiscretisation(0.0, p.get("h_out", 0.01)))
    osi = sk.LsodarOSI()
    osi.setTol(1, p.get("rtol", 1e-10), p.get("atol", 1e-12))
    sim.insertIntegrator(osi)
    sim.insertNonSmoothProblem(sk.LCP(), sk.SICONOS_OSNSP_ED_IMPACT)
    sim.insertNonSmoothProblem(sk.LCP(), sk.SICONOS_OSNSP_ED_SMOOTH_ACC)
    sim.initialize()
    impacts = []
    steps = 0
    while sim.hasNextEvent() and steps < p.get("max_steps", 20000):
        sim.advanceToEvent()
        steps += 1
        impact = sim.eventsManager().nextEvent().getType() == 2   # a non-smooth event: an impact
        if impact:
            before = {"t": sim.nextTime(), "y": float(ds.q()[0]), "v_before": float(ds.velocity()[0])}
        sim.processEvents()
        if impact:
            impacts.append(before | {"v_after": float(ds.velocity()[0])})
    cpu = _cpu() - t0
    return {"impacts": impacts, "final": {"t": sim.startingTime(), "y": float(ds.q()[0]),
                                          "dot_y": float(ds.velocity()[0])}, "cpu_s": cpu, "steps": steps}


def _time_stepping(nsds, h):
    """Moreau–Jean (θ = 0.5) with a 2D friction-contact problem solved to 1e-14 (at most 1000 iterations)."""
    osnspb = sk.FrictionContact(2)
    osnspb.numericsSolverOptions().iparam[0] = 1000
    osnspb.numericsSolverOptions().dparam[0] = 1e-14
    return sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(0.5), osnspb)


def _friction_block(p, q0, v0, fext, k=0.0):
    """A point mass with coordinates (x along the surface, y off it), one frictional contact at y = 0.

    Moreau–Jean time stepping; returns (times, x, ẋ, cpu)."""
    m, mu, h, T = p["m"], p["mu"], p["h_step"], p["T"]
    t0 = _cpu()
    if k:
        K = np.array([[k, 0.0], [0.0, 0.0]])
        ds = sk.LagrangianLinearTIDS(q0, v0, m * np.eye(2), K, np.zeros((2, 2)))
    else:
        ds = sk.LagrangianLinearTIDS(q0, v0, m * np.eye(2))
    ds.setFExtPtr(np.array(fext, dtype=float))
    H = np.array([[0.0, 1.0], [1.0, 0.0]])                      # normal gap y, tangential x
    inter = sk.Interaction(sk.NewtonImpactFrictionNSL(0.0, 0.0, mu, 2), sk.LagrangianLinearTIR(H))
    nsds = sk.NonSmoothDynamicalSystem(0.0, T)
    nsds.insertDynamicalSystem(ds)
    nsds.link(inter, ds)
    sim = _time_stepping(nsds, h)
    ts, xs, vs = [0.0], [q0[0]], [v0[0]]
    while sim.hasNextEvent():
        sim.computeOneStep()
        ts.append(sim.nextTime())
        xs.append(float(ds.q()[0]))
        vs.append(float(ds.velocity()[0]))
        sim.nextStep()
    return np.array(ts), np.array(xs), np.array(vs), _cpu() - t0


def incline(p):
    """Block thrown up a rough incline (x down the slope): the step where it stops, and where."""
    g, b, m, v0 = p["g"], p["beta"], p["m"], p["v0"]
    fext = [m * g * np.sin(b), -m * g * np.cos(b)]
    ts, xs, vs, cpu = _friction_block(p, [0.0, 0.0], [-v0, 0.0], fext)
    i = int(np.argmax(np.abs(vs) < 1e-9))
    return {"t_stop": float(ts[i]), "x_stop": float(xs[i]), "x_final": float(xs[-1]),
            "dot_x_final": float(vs[-1]), "cpu_s": cpu, "steps": len(ts) - 1}


def spring(p):
    """Block on a spring on a rough floor, released stretched: turning times and positions, then rest."""
    g, m, k, x0 = p["g"], p["m"], p["k"], p["x0"]
    ts, xs, vs, cpu = _friction_block(p, [x0, 0.0], [0.0, 0.0], [0.0, -m * g], k=k)
    turns = []
    for i in range(2, len(ts)):
        # ẋ reaches zero (a tolerance of 1e-9 m/s) or changes sign between two step ends
        if abs(vs[i]) < 1e-9 and abs(vs[i - 1]) >= 1e-9 or vs[i] * vs[i - 1] < 0:
            turns.append({"t": float(ts[i]), "x": float(xs[i])})
    return {"turns": turns, "x_final": float(xs[-1]), "dot_x_final": float(vs[-1]), "cpu_s": cpu,
            "steps": len(ts) - 1}


def two_supports(p):
    """A level rod (mass m, length l) falling h onto two supports under its points at −a and +b from the
    centre, e at both, smooth: q = (y, θ), gaps y − a θ and y + b θ (exact here: θ stays 0 when the
    supports strike together).  Event-driven as the ball; the impulses per support at each impact."""
    g, h, e, m, length, a, b, T = p["g"], p["h"], p["e"], p["m"], p["l"], p["a"], p["b"], p["T"]
    t0 = _cpu()
    ds = sk.LagrangianLinearTIDS([h, 0.0], [0.0, 0.0], np.diag([m, m * length**2 / 12]))
    ds.setFExtPtr(np.array([-m * g, 0.0]))
    nsds = sk.NonSmoothDynamicalSystem(0.0, T)
    nsds.insertDynamicalSystem(ds)
    inters = []
    for row in ([[1.0, -a]], [[1.0, b]]):
        inter = sk.Interaction(sk.NewtonImpactNSL(e), sk.LagrangianLinearTIR(np.array(row)))
        nsds.link(inter, ds)
        inters.append(inter)
    sim = sk.EventDriven(nsds, sk.TimeDiscretisation(0.0, p.get("h_out", 0.01)))
    osi = sk.LsodarOSI()
    osi.setTol(1, p.get("rtol", 1e-10), p.get("atol", 1e-12))
    sim.insertIntegrator(osi)
    sim.insertNonSmoothProblem(sk.LCP(), sk.SICONOS_OSNSP_ED_IMPACT)
    sim.insertNonSmoothProblem(sk.LCP(), sk.SICONOS_OSNSP_ED_SMOOTH_ACC)
    sim.initialize()
    impacts, steps = [], 0
    while sim.hasNextEvent() and steps < p.get("max_steps", 20000):          # to T, as rigidkin runs
        sim.advanceToEvent()
        steps += 1
        impact = sim.eventsManager().nextEvent().getType() == 2
        if impact:
            before = {"t": sim.nextTime(), "v_before": float(ds.velocity()[0])}
        sim.processEvents()
        if impact and len(impacts) < p.get("impacts", 6):
            impacts.append(before | {"v_after": float(ds.velocity()[0]), "w_after": float(ds.velocity()[1]),
                                     "P_A": float(inters[0].lambda_(1)[0]), "P_B": float(inters[1].lambda_(1)[0])})
    return {"impacts": impacts, "cpu_s": _cpu() - t0, "steps": steps}


def two_supports_rough(p):
    """The rod on two supports with Coulomb friction µ at both, q = (x, y, θ) (gaps y ∓ a θ, tangents x):
    Moreau–Jean; an impact is a step whose impulse takes ẏ from below −g h to above zero."""
    g, h, e, m, length, a, b, T = p["g"], p["h"], p["e"], p["m"], p["l"], p["a"], p["b"], p["T"]
    t0 = _cpu()
    ds = sk.LagrangianLinearTIDS([0.0, h, 0.0], [0.0, 0.0, 0.0], np.diag([m, m, m * length**2 / 12]))
    ds.setFExtPtr(np.array([0.0, -m * g, 0.0]))
    nsds = sk.NonSmoothDynamicalSystem(0.0, T)
    nsds.insertDynamicalSystem(ds)
    inters = []
    for d in (-a, b):
        H = np.array([[0.0, 1.0, d], [1.0, 0.0, 0.0]])
        inters.append(sk.Interaction(sk.NewtonImpactFrictionNSL(e, 0.0, p["mu"], 2), sk.LagrangianLinearTIR(H)))
        nsds.link(inters[-1], ds)
    sim = _time_stepping(nsds, p["h_step"])
    impacts, steps = [], 0
    while sim.hasNextEvent():                                           # to T, as rigidkin runs
        v0 = float(ds.velocity()[1])
        sim.computeOneStep()
        steps += 1
        v1 = float(ds.velocity()[1])
        if v0 < -g * p["h_step"] and v1 > 0 and len(impacts) < p.get("impacts", 6):
            lam = [inter.lambda_(1) for inter in inters]
            impacts.append({"t": sim.nextTime(), "v_before": v0, "v_after": v1, "w_after": float(ds.velocity()[2]),
                            "P_A": float(lam[0][0]), "P_B": float(lam[1][0]), "F_A": float(lam[0][1]),
                            "F_B": float(lam[1][1])})
        sim.nextStep()
    return {"impacts": impacts, "cpu_s": _cpu() - t0, "steps": steps}


CORNERS_C = r"""
#include <math.h>
/* q = (x, y, theta); z = (b, h); a lower corner at (s b, -h) in the block: y = (height, place along Ex) */
static void corner_h(double s, const double* q, double* y, const double* z)
{
  double c = cos(q[2]), sn = sin(q[2]);
  y[0] = q[1] + s * z[0] * sn - z[1] * c;
  y[1] = q[0] + s * z[0] * c + z[1] * sn;
}
static void corner_G(double s, const double* q, double* G, const double* z)   /* 2 x 3, column-major */
{
  double c = cos(q[2]), sn = sin(q[2]);
  G[0] = 0.0; G[1] = 1.0; G[2] = 1.0; G[3] = 0.0;
  G[4] = s * z[0] * c + z[1] * sn; G[5] = -s * z[0] * sn + z[1] * c;
}
void hA(unsigned int nq, double* q, unsigned int ny, double* y, unsigned int nz, double* z) { corner_h(-1, q, y, z); }
void hC(unsigned int nq, double* q, unsigned int ny, double* y, unsigned int nz, double* z) { corner_h(1, q, y, z); }
void GA(unsigned int nq, double* q, unsigned int ny, double* G, unsigned int nz, double* z) { corner_G(-1, q, G, z); }
void GC(unsigned int nq, double* q, unsigned int ny, double* G, unsigned int nz, double* z) { corner_G(1, q, G, z); }
"""


def _corner_plugin(folder):
    """Compile the corner relations into ``folder/corners.so``; the plugin prefix, or raise with cc's message."""
    src = os.path.join(folder, "corners.c")
    with open(src, "w") as f:
        f.write(CORNERS_C)
    cc = os.environ.get("CC", "cc")
    try:
        out = subprocess.run([cc, "-O2", "-shared", "-fPIC", "-o", os.path.join(folder, "corners.so"), src, "-lm"],
                             capture_output=True, text=True)
    except FileNotFoundError:
        raise RuntimeError(f"no C compiler {cc!r} to build the corner plugin (set CC)") from None
    if out.returncode:
        raise RuntimeError(f"cc could not build the corner plugin: {out.stderr.strip()[-300:]}")
    return os.path.join(folder, "corners")


def rocking(p):
    """Block (half width b, half height h, mass m) released at tilt θ0 on corner A = (−b, −h), corners rough
    (µ) with restitution e; Moreau–Jean.  Impacts: t (step end), ω before and after, the new corner's
    normal and tangential impulse; and whether a corner slid (largest tangential corner speed while in contact)."""
    g, m, b, h, th0, T = p["g"], p["m"], p["b"], p["h"], p["tilt"], p["T"]
    with tempfile.TemporaryDirectory() as folder:
        plugin = _corner_plugin(folder)
        t0 = _cpu()
        q0 = [0.0, b * np.sin(th0) + h * np.cos(th0), th0]
        ds = sk.LagrangianDS(q0, [0.0, 0.0, 0.0], np.diag([m, m, m * (b * b + h * h) / 3]))
        ds.setzPtr(np.array([b, h]))
        ds.setFExtPtr(np.array([0.0, -m * g, 0.0]))
        nsds = sk.NonSmoothDynamicalSystem(0.0, T)
        nsds.insertDynamicalSystem(ds)
        inters = []
        for c in "AC":
            rel = sk.LagrangianScleronomousR(f"{plugin}:h{c}", f"{plugin}:G{c}")
            inters.append(sk.Interaction(sk.NewtonImpactFrictionNSL(p["e"], 0.0, p["mu"], 2), rel))
            nsds.link(inters[-1], ds)
        sim = _time_stepping(nsds, p["h_step"])
        ts, th, w, lam, slip = [0.0], [th0], [0.0], [(0.0, 0.0, 0.0, 0.0)], 0.0
        while sim.hasNextEvent():
            sim.computeOneStep()
            ts.append(sim.nextTime())
            th.append(float(ds.q()[2]))
            w.append(float(ds.velocity()[2]))
            la, lc = inters[0].lambda_(1), inters[1].lambda_(1)
            lam.append((float(la[0]), float(la[1]), float(lc[0]), float(lc[1])))
            for inter, ln in zip(inters, (la, lc)):
                if ln[0] > 0:                       # pressed: the corner's speed along the floor
                    slip = max(slip, abs(float(inter.y(1)[1])))
            sim.nextStep()
        cpu = _cpu() - t0
    th, w = np.array(th), np.array(w)
    impacts = []
    for i in np.nonzero(np.sign(th[1:]) != np.sign(th[:-1]))[0]:
        lo, hi = max(i - 3, 0), min(i + 4, len(w) - 1)
        j = lo + int(np.argmax(np.abs(np.diff(w[lo:hi + 1]))))       # the step with the impulse
        new = 2 if w[j] < 0 else 0                                  # ω < 0: C strikes; ω > 0: A strikes
        impacts.append({"t": ts[j + 1], "w_before": float(w[j]), "w_after": float(w[j + 1]),
                        "P_N": lam[j + 1][new], "P_T": lam[j + 1][new + 1]})
        if len(impacts) >= p.get("impacts", 6):
            break
    return {"impacts": impacts, "slip_speed_max": slip, "cpu_s": cpu, "steps": len(ts) - 1}


CASES = {"ball": ball, "incline": incline, "spring": spring, "two_supports": two_supports,
         "two_supports_rough": two_supports_rough, "rocking": rocking}


def main():
    params = json.loads(sys.argv[1]) if len(sys.argv) > 1 else {}
    out = {}
    for name, fn in CASES.items():
        if name in params:
            try:
                out[name] = fn(params[name])
            except (RuntimeError, OSError) as exc:      # e.g. no C compiler for the rocking block's plugin
                out[name] = {"error": str(exc)}
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
