"""Contacts side by side with Siconos: event times and states, against the closed forms, and CPU time.

    python benchmarks/contacts_vs_siconos.py [--siconos-python /usr/bin/python3] [--h-step 1e-4]

Four cases, each run in rigidkin (``rigidkin.numeric.simulate``) and in Siconos (``siconos_cases.py``,
through a subprocess with the interpreter that has Siconos; skipped with the reason if it cannot import it):

* ball: a ball dropped h = 0.8 m onto a floor, e = 0.5 — impact times and speeds (Siconos event-driven);
* incline: a block thrown up a rough incline (β = 0.4, µ = 0.6, v0 = 2 m/s), stops and stays — stop time and
  place (Siconos Moreau–Jean time stepping, so its event times are known to one step h);
* two supports: a level rod falling onto two supports at unequal distances (e = 0.5, smooth) — impact
  times, speeds and the impulse at each support against the lever rule (Siconos event-driven);
* spring: a block on a spring (k = 10, m = 1) released 1 m stretched on a rough floor (µ = 0.3) — the two
  turning points, where it sticks at the second (same Siconos integrator).

Siconos has one friction coefficient, so µs = µk here.  CPU times are process times of one run each:
rigidkin's first run includes the symbolic derivation, its repeat run reuses it; Siconos's includes
building its model.
"""

import argparse
import json
import math
import subprocess
import time
from pathlib import Path

import rigidkin as rk
from rigidkin.numeric import simulate

G = 9.81
BALL = {"g": G, "h": 0.8, "e": 0.5, "r": 0.1, "m": 2.0, "T": 2.0}
INCLINE = {"g": G, "beta": 0.4, "m": 2.0, "v0": 2.0, "mu": 0.6, "T": 1.0}
SPRING = {"g": G, "m": 1.0, "k": 10.0, "x0": 1.0, "mu": 0.3, "T": 5.0}
TWO = {"g": G, "h": 0.2, "e": 0.5, "m": 1.5, "l": 1.2, "a": 0.5, "b": 0.2, "T": 1.0, "impacts": 6}
N_IMPACTS = 6


def ball_system(p):
    s = rk.System("ball")
    m, r, g = (s.parameter("m", "kg", value=p["m"]), s.parameter("r", "m", value=p["r"]),
               s.parameter("g", "m/s^2", value=p["g"]))
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=p["r"] + p["h"], rate=0)
    phi = s.coordinate("phi", "rotation, clockwise", initial=0, rate=0)
    D = s.frame("D", angle=-phi)
    C = s.point("C", s.origin, x * s.inertial.x + y * s.inertial.y)
    ball = s.body("ball", rk.shapes.SolidSphere(m, r), frame=D, at=C)
    s.contact("floor", ball, s.line(s.origin, s.inertial.y), radius=r)
    s.gravity(g)
    return s


def incline_system(p):
    s = rk.System("block-on-incline")
    m, g = s.parameter("m", "kg", value=p["m"]), s.parameter("g", "m/s^2", value=p["g"])
    b, mu = s.parameter("beta", "rad", value=p["beta"]), s.parameter("mu", "", value=p["mu"])
    x = s.coordinate("x", "distance down the slope", kind="length", initial=0, rate=-p["v0"])
    y = s.coordinate("y", "distance off the slope", kind="length", initial=0, rate=0)
    I = s.frame("I", angle=-b, basis=("es", "en", "ez"))
    P = s.point("G", offset=x * I.es + y * I.en)
    blk = s.body("block", rk.shapes.PointMass(m), frame=I, at=P)
    s.contact("ground", blk, s.line(s.origin, I.en), centre=P, friction=mu, normal_name="N", friction_name="F")
    s.gravity(g)
    return s


def spring_system(p):
    s = rk.System("spring-on-rough-floor")
    m, k = s.parameter("m", "kg", value=p["m"]), s.parameter("k", "N/m", value=p["k"])
    g, mu = s.parameter("g", "m/s^2", value=p["g"]), s.parameter("mu", "", value=p["mu"])
    x = s.coordinate("x", "stretch of the spring", kind="length", initial=p["x0"], rate=0)
    y = s.coordinate("y", "height off the floor", kind="length", initial=0, rate=0)
    P = s.point("P", s.origin, x * s.inertial.x + y * s.inertial.y)
    blk = s.body("block", rk.shapes.PointMass(m), frame=s.inertial, at=P)
    s.contact("floor", blk, s.line(s.origin, s.inertial.y), centre=P, friction=mu, normal_name="N",
              friction_name="F")
    s.spring("spring", P, s.origin, k, 0, body_a=blk)
    s.gravity(g)
    return s


def two_supports_system(p):
    """A level rod (centre x, y; tilt θ) falling h onto supports under its points at −a and +b, smooth."""
    s = rk.System("rod-on-two-supports")
    m, length = s.parameter("m", "kg", value=p["m"]), s.parameter("l", "m", value=p["l"])
    g = s.parameter("g", "m/s^2", value=p["g"])
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=p["h"], rate=0)
    th = s.coordinate("theta", "tilt, counter-clockwise", initial=0, rate=0)
    R = s.frame("R", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    rod = s.body("rod", rk.shapes.SlenderRod(m, length, axis="x"), frame=R, at=Gp)
    floor = s.line(s.origin, s.inertial.y)
    for name, off in (("A", -p["a"]), ("B", p["b"])):
        s.contact(name, rod, floor, centre=s.point(name, Gp, off * R.x, body=rod), normal_name=f"N_{name}")
    s.gravity(g)
    return s


def two_supports_closed(p):
    """(t, ẏ⁻, ẏ⁺, P_A, P_B) per impact: the ball's times; P_A + P_B = m (1 + e) v, P_A a = P_B b."""
    out = []
    for t, vb, va in ball_closed(p | {"r": 0.0}):
        total = p["m"] * (va - vb)
        out.append((t, vb, va, total * p["b"] / (p["a"] + p["b"]), total * p["a"] / (p["a"] + p["b"])))
    return out


def timed(system, T, **kw):
    """(result, CPU s of the first run, CPU s of a repeat run)."""
    t0 = time.process_time()
    simulate(system, T, **kw)
    t1 = time.process_time()
    res = simulate(system, T, **kw)
    return res, t1 - t0, time.process_time() - t1


# closed forms ---------------------------------------------------------------------------------------
def ball_closed(p):
    v0, e, g = math.sqrt(2 * p["g"] * p["h"]), p["e"], p["g"]
    t, out = math.sqrt(2 * p["h"] / g), []
    for k in range(N_IMPACTS):
        out.append((t, -v0 * e**k, v0 * e ** (k + 1)))
        t += 2 * v0 * e ** (k + 1) / g
    return out


def incline_closed(p):
    a = p["g"] * (math.sin(p["beta"]) + p["mu"] * math.cos(p["beta"]))
    return p["v0"] / a, -p["v0"] ** 2 / (2 * a)


def spring_closed(p):
    w, xk, x, out = math.sqrt(p["k"] / p["m"]), p["mu"] * p["m"] * p["g"] / p["k"], p["x0"], []
    n = 0
    while abs(x) > xk:                                     # each half swing is about ±x_k, π/ω long
        n += 1
        x = -x + 2 * xk if x > 0 else -x - 2 * xk
        out.append((n * math.pi / w, x))
    return out


# the comparison ---------------------------------------------------------------------------------------
def run_siconos(python, h_step):
    params = {"ball": BALL, "incline": INCLINE | {"h_step": h_step}, "spring": SPRING | {"h_step": h_step},
              "two_supports": TWO}
    script = Path(__file__).with_name("siconos_cases.py")
    probe = subprocess.run([python, "-c", "import siconos.kernel"], capture_output=True, text=True)
    if probe.returncode:
        return None, f"{python} cannot import siconos.kernel ({probe.stderr.strip().splitlines()[-1:]})"
    out = subprocess.run([python, str(script), json.dumps(params)], capture_output=True, text=True, timeout=600)
    if out.returncode:
        return None, f"siconos_cases.py failed: {out.stderr.strip()[-500:]}"
    return json.loads(out.stdout), None


def fmt(v):
    return "—" if v is None else f"{v:.10g}" if isinstance(v, float) else str(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--siconos-python", default="/usr/bin/python3")
    ap.add_argument("--h-step", type=float, default=1e-4, help="Siconos time step for the friction cases")
    args = ap.parse_args()
    sic, why = run_siconos(args.siconos_python, args.h_step)
    if sic is None:
        print(f"Siconos skipped: {why}")
    rows = []          # (case, quantity, rigidkin, siconos, closed form)
    cpu = {}

    r, c1, c2 = timed(ball_system(BALL), BALL["T"], restitution=BALL["e"])
    imp = r.events_of("impact")
    simp = sic["ball"]["impacts"] if sic else []
    for k, (t, vb, va) in enumerate(ball_closed(BALL)):
        s = simp[k] if k < len(simp) else None
        rows.append(("ball", f"impact {k + 1} t", imp[k].t, s and s["t"], t))
        rows.append(("ball", f"impact {k + 1} ẏ⁻", imp[k].state["dot(y)"], s and s["v_before"], vb))
        rows.append(("ball", f"impact {k + 1} ẏ⁺", imp[k].after["dot(y)"], s and s["v_after"], va))
    t_inf = ball_closed(BALL)[0][0] + 2 * math.sqrt(2 * G * BALL["h"]) * BALL["e"] / (G * (1 - BALL["e"]))
    rows.append(("ball", "rest (last impact) t", r.events[-1].t, simp[-1]["t"] if simp else None, t_inf))
    rows.append(("ball", "impacts counted", float(len(imp)), float(len(simp)) if sic else None, None))
    cpu["ball"] = (c1, c2, sic and sic["ball"]["cpu_s"])

    r, c1, c2 = timed(two_supports_system(TWO), TWO["T"], restitution=TWO["e"], max_events=200)
    imp = r.events_of("impact")
    simp = sic["two_supports"]["impacts"] if sic and "two_supports" in sic else []
    for k, (t, _vb, va, pa, pb) in enumerate(two_supports_closed(TWO)):
        s = simp[k] if k < len(simp) else None
        nums = imp[k].impact["contacts"]
        rows.append(("two supports", f"impact {k + 1} t", imp[k].t, s and s["t"], t))
        rows.append(("two supports", f"impact {k + 1} ẏ⁺", imp[k].after["dot(y)"], s and s["v_after"], va))
        rows.append(("two supports", f"impact {k + 1} P_A", nums["A"]["normal_impulse"], s and s["P_A"], pa))
        rows.append(("two supports", f"impact {k + 1} P_B", nums["B"]["normal_impulse"], s and s["P_B"], pb))
    cpu["two supports"] = (c1, c2, sic and sic.get("two_supports", {}).get("cpu_s"))

    r, c1, c2 = timed(incline_system(INCLINE), INCLINE["T"])
    ev = [e for e in r.events if e.kind == "sticks"][0]
    t_stop, x_stop = incline_closed(INCLINE)
    si = sic["incline"] if sic else {}
    rows.append(("incline", "stop t", ev.t, si.get("t_stop"), t_stop))
    rows.append(("incline", "stop x", ev.state["x"], si.get("x_stop"), x_stop))
    rows.append(("incline", "final x", r.final_state["x"], si.get("x_final"), x_stop))
    cpu["incline"] = (c1, c2, si.get("cpu_s"))

    r, c1, c2 = timed(spring_system(SPRING), SPRING["T"])
    ev = [e for e in r.events if e.kind == "sticks"]
    sturns = sic["spring"]["turns"] if sic else []
    for k, (t, x) in enumerate(spring_closed(SPRING)):
        s = sturns[k] if k < len(sturns) else None
        rows.append(("spring", f"turn {k + 1} t", ev[k].t, s and s["t"], t))
        rows.append(("spring", f"turn {k + 1} x", ev[k].state["x"], s and s["x"], x))
    rows.append(("spring", "final x", r.final_state["x"], sic and sic["spring"]["x_final"], x))
    cpu["spring"] = (c1, c2, sic and sic["spring"]["cpu_s"])

    print("| case | quantity | rigidkin | Siconos | closed form | rigidkin − closed | Siconos − closed |")
    print("|---|---|---|---|---|---|---|")
    for case, q, a, b, c in rows:
        da = None if c is None else a - c
        db = None if c is None or b is None else b - c
        print(f"| {case} | {q} | {fmt(a)} | {fmt(b)} | {fmt(c)} | {fmt(da) if da is None else f'{da:.1e}'} "
              f"| {fmt(db) if db is None else f'{db:.1e}'} |")
    print()
    print("| case | rigidkin CPU s (first / repeat) | Siconos CPU s | ratio rigidkin/Siconos (first / repeat) |")
    print("|---|---|---|---|")
    for case, (c1, c2, cs) in cpu.items():
        ratio = "—" if not cs else f"{c1 / cs:.2g} / {c2 / cs:.2g}"
        print(f"| {case} | {c1:.3g} / {c2:.3g} | {fmt(cs) if cs is None else f'{cs:.3g}'} | {ratio} |")
    if sic:
        print(f"\nSiconos friction cases: Moreau–Jean time step h = {args.h_step:g} s "
              f"({sic['incline']['steps']} and {sic['spring']['steps']} steps); ball: event-driven, "
              f"{sic['ball']['steps']} events.")


if __name__ == "__main__":
    main()
