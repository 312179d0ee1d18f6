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
"""

import json
import sys
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
    osi = sk.MoreauJeanOSI(0.5)
    osnspb = sk.FrictionContact(2)
    osnspb.numericsSolverOptions().iparam[0] = 1000
    osnspb.numericsSolverOptions().dparam[0] = 1e-14
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), osi, osnspb)
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
    while sim.hasNextEvent() and steps < p.get("max_steps", 20000) and len(impacts) < p.get("impacts", 6):
        sim.advanceToEvent()
        steps += 1
        impact = sim.eventsManager().nextEvent().getType() == 2
        if impact:
            before = {"t": sim.nextTime(), "v_before": float(ds.velocity()[0])}
        sim.processEvents()
        if impact:
            impacts.append(before | {"v_after": float(ds.velocity()[0]), "w_after": float(ds.velocity()[1]),
                                     "P_A": float(inters[0].lambda_(1)[0]), "P_B": float(inters[1].lambda_(1)[0])})
    return {"impacts": impacts, "cpu_s": _cpu() - t0, "steps": steps}


CASES = {"ball": ball, "incline": incline, "spring": spring, "two_supports": two_supports}


def main():
    params = json.loads(sys.argv[1]) if len(sys.argv) > 1 else {}
    out = {}
    for name, fn in CASES.items():
        if name in params:
            out[name] = fn(params[name])
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
