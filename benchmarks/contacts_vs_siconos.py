"""Contacts side by side with Siconos: event times and states, against the closed forms, and CPU time.

    python benchmarks/contacts_vs_siconos.py [--siconos-python /usr/bin/python3] [--h-step 1e-4]

Six cases, each run in rigidkin (``rigidkin.numeric.simulate``) and in Siconos (``siconos_cases.py``,
through a subprocess with the interpreter that has Siconos; skipped with the reason if it cannot import it):

* ball: a ball dropped h = 0.8 m onto a floor, e = 0.5 — impact times and speeds (Siconos event-driven);
* incline: a block thrown up a rough incline (β = 0.4, µ = 0.6, v0 = 2 m/s), stops and stays — stop time and
  place (Siconos Moreau–Jean time stepping, so its event times are known to one step h);
* two supports: a level rod falling onto two supports at unequal distances a = 0.5, b = 0.2 from its centre
  (e = 0.5, smooth), six bounces — impact times, speeds and the impulse at each support against the lever
  rule P_A/P_B = b/a (Siconos event-driven);
* two supports, rough: the same rod with µ = 0.5 at both supports (Siconos Moreau–Jean: its event-driven
  integrator has no friction) — the same numbers, since a level rod meets the supports head-on;
* rocking: a block 2b × 2h (b = 0.1, h = 0.3) released at θ0 = 0.2 on one corner, corners rough (µ = 1, no
  slip) and e = 0 — impact times against the energy integral between impacts, and ω⁺/ω⁻ per impact
  against Housner's 1 − (3/2) sin²α, α = atan(b/h) (Siconos Moreau–Jean, corners as nonlinear relations);
* spring: a block on a spring (k = 10, m = 1) released 1 m stretched on a rough floor (µ = 0.3) — the two
  turning points, where it sticks at the second (same Siconos integrator).

Siconos has one friction coefficient, so µs = µk here.  CPU times are process times of one run each:
rigidkin's first run includes the symbolic derivation, its repeat run reuses it; Siconos's includes
building its model and runs with one BLAS thread (OPENBLAS_NUM_THREADS=1, OMP_NUM_THREADS=1).
"""

import argparse
import json
import math
import os
import platform
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
TWO_ROUGH = TWO | {"mu": 0.5}
ROCK = {"g": G, "m": 2.0, "b": 0.1, "h": 0.3, "tilt": 0.2, "mu": 1.0, "e": 0.0, "T": 1.85, "impacts": 6}
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
    """A level rod (centre x, y; tilt θ) falling h onto supports under its points at −a and +b, smooth, or
    rough with ``p["mu"]`` at both."""
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
        s.contact(name, rod, floor, centre=s.point(name, Gp, off * R.x, body=rod), normal_name=f"N_{name}",
                  **({"friction": p["mu"], "friction_name": f"F_{name}"} if p.get("mu") else {}))
    s.gravity(g)
    return s


def rocking_system(p):
    """A block 2b × 2h (centre x, y; tilt θ counter-clockwise) standing at tilt θ0 on its corner A = (−b, −h),
    both lower corners A and C = (b, −h) rough (µ) on a level floor."""
    s = rk.System("rocking-block")
    m, g = s.parameter("m", "kg", value=p["m"]), s.parameter("g", "m/s^2", value=p["g"])
    b, h, mu = (s.parameter("b", "m", value=p["b"]), s.parameter("h", "m", value=p["h"]),
                s.parameter("mu", "", value=p["mu"]))
    y0 = p["b"] * math.sin(p["tilt"]) + p["h"] * math.cos(p["tilt"])
    x = s.coordinate("x", "centre along Ex", kind="length", initial=0, rate=0)
    y = s.coordinate("y", "centre height", kind="length", initial=y0, rate=0)
    th = s.coordinate("theta", "tilt, counter-clockwise", initial=p["tilt"], rate=0)
    B = s.frame("B", angle=th)
    Gp = s.point("G", s.origin, x * s.inertial.x + y * s.inertial.y)
    box = s.body("block", rk.shapes.RectangularPlate(m, 2 * b, 2 * h), frame=B, at=Gp)
    floor = s.line(s.origin, s.inertial.y)
    for name, side in (("A", -1), ("C", 1)):
        corner = s.point(name, Gp, side * b * B.x - h * B.y, body=box)
        s.contact(name, box, floor, centre=corner, friction=mu, normal_name=f"N_{name}", friction_name=f"F_{name}")
    s.gravity(g)
    return s


def rocking_closed(p):
    """(t, ω⁻, ω⁺) per impact, as sizes.  Between impacts the block turns about one corner, G at R cos(α − |θ|)
    above it (R = √(b² + h²), α = atan(b/h), I_O = 4/3 m R², p² = m g R / I_O): ω² = 2p²(cos(α − θa) −
    cos(α − |θ|)) for amplitude θa, so a quarter swing lasts ∫₀^θa dθ/|ω| (θ = θa(1 − u²) takes the square
    root out of the integrand); at each impact ω⁺ = (1 − (3/2) sin²α) ω⁻ (Housner, e = 0, no slip)."""
    from scipy.integrate import quad

    R, alpha = math.hypot(p["b"], p["h"]), math.atan2(p["b"], p["h"])
    p2 = 3 * p["g"] / (4 * R)
    ratio = 1 - 1.5 * math.sin(alpha) ** 2

    def quarter(a):
        def f(u):                   # cos(α − a) − cos(α − θ) = 2 sin(α − (a + θ)/2) sin((a − θ)/2), a − θ = a u²
            x = a * u * u / 2
            return math.sqrt(2 * a / p2) / math.sqrt(math.sin(alpha - a + x) * (math.sin(x) / x if x else 1.0))
        return quad(f, 0, 1, epsabs=0, epsrel=1e-13)[0]

    a, t, out = p["tilt"], 0.0, []
    for k in range(p["impacts"]):
        t += quarter(a) * (1 if k == 0 else 2)
        w = math.sqrt(2 * p2 * (math.cos(alpha - a) - math.cos(alpha)))
        out.append((t, w, ratio * w))
        a = alpha - math.acos(math.cos(alpha) + (ratio * w) ** 2 / (2 * p2))
    return out


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
    """({case: Siconos numbers}, [why a case is missing]): empty with the reason when Siconos cannot run."""
    params = {"ball": BALL, "incline": INCLINE | {"h_step": h_step}, "spring": SPRING | {"h_step": h_step},
              "two_supports": TWO, "two_supports_rough": TWO_ROUGH | {"h_step": h_step},
              "rocking": ROCK | {"h_step": h_step}}
    script = Path(__file__).with_name("siconos_cases.py")
    try:
        probe = subprocess.run([python, "-c", "import siconos.kernel"], capture_output=True, text=True)
    except OSError as exc:
        return {}, [f"{python} cannot run ({exc.strerror})"]
    if probe.returncode:
        return {}, [f"{python} cannot import siconos.kernel ({probe.stderr.strip().splitlines()[-1:]})"]
    # one BLAS thread: Siconos's idle OpenBLAS threads otherwise spin and count as its CPU time (2–6× here)
    env = os.environ | {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    out = subprocess.run([python, str(script), json.dumps(params)], capture_output=True, text=True, timeout=900,
                         env=env)
    if out.returncode:
        return {}, [f"siconos_cases.py failed: {out.stderr.strip()[-500:]}"]
    got = json.loads(out.stdout)
    why = [f"{name}: {got.pop(name)['error']}" for name in list(got) if "error" in got[name]]
    return got, why


def _nth(items, k):
    return items[k] if k < len(items) else None


def ball_rows(sic):
    r, c1, c2 = timed(ball_system(BALL), BALL["T"], restitution=BALL["e"])
    imp, simp, rows = r.events_of("impact"), sic.get("ball", {}).get("impacts", []), []
    for k, (t, vb, va) in enumerate(ball_closed(BALL)):
        s = _nth(simp, k)
        rows.append(("ball", f"impact {k + 1} t", imp[k].t, s and s["t"], t))
        rows.append(("ball", f"impact {k + 1} ẏ⁻", imp[k].state["dot(y)"], s and s["v_before"], vb))
        rows.append(("ball", f"impact {k + 1} ẏ⁺", imp[k].after["dot(y)"], s and s["v_after"], va))
    t_inf = ball_closed(BALL)[0][0] + 2 * math.sqrt(2 * G * BALL["h"]) * BALL["e"] / (G * (1 - BALL["e"]))
    rows.append(("ball", "rest (last impact) t", r.events[-1].t, simp[-1]["t"] if simp else None, t_inf))
    rows.append(("ball", "impacts counted", float(len(imp)), float(len(simp)) if simp else None, None))
    return rows, {"ball": (c1, c2, sic.get("ball", {}).get("cpu_s"))}


def two_supports_rows(sic):
    rows, cpu = [], {}
    for case, key, p in (("two supports", "two_supports", TWO),
                         ("two supports µ=0.5", "two_supports_rough", TWO_ROUGH)):
        r, c1, c2 = timed(two_supports_system(p), p["T"], restitution=p["e"], max_events=200)
        imp, simp = r.events_of("impact"), sic.get(key, {}).get("impacts", [])
        for k, (t, _vb, va, pa, pb) in enumerate(two_supports_closed(p)):
            s = _nth(simp, k)
            nums = imp[k].impact["contacts"]
            na, nb = nums["A"]["normal_impulse"], nums["B"]["normal_impulse"]
            rows.append((case, f"impact {k + 1} t", imp[k].t, s and s["t"], t))
            rows.append((case, f"impact {k + 1} ẏ⁺", imp[k].after["dot(y)"], s and s["v_after"], va))
            rows.append((case, f"impact {k + 1} P_A", na, s and s["P_A"], pa))
            rows.append((case, f"impact {k + 1} P_B", nb, s and s["P_B"], pb))
            rows.append((case, f"impact {k + 1} P_A/P_B", na / nb, s and s["P_A"] / s["P_B"], p["b"] / p["a"]))
        cpu[case] = (c1, c2, sic.get(key, {}).get("cpu_s"))
    return rows, cpu


def rocking_rows(sic):
    r, c1, c2 = timed(rocking_system(ROCK), ROCK["T"], restitution=ROCK["e"], max_events=200)
    imp, simp, rows = r.events_of("impact"), sic.get("rocking", {}).get("impacts", []), []
    for k, (t, wb, wa) in enumerate(rocking_closed(ROCK)):
        s, sign = _nth(simp, k), (-1) ** (k + 1)          # released tilted counter-clockwise: ω < 0 first
        w0, w1 = imp[k].state["dot(theta)"], imp[k].after["dot(theta)"]
        rows.append(("rocking", f"impact {k + 1} t", imp[k].t, s and s["t"], t))
        rows.append(("rocking", f"impact {k + 1} ω⁻", w0, s and s["w_before"], sign * wb))
        rows.append(("rocking", f"impact {k + 1} ω⁺", w1, s and s["w_after"], sign * wa))
        rows.append(("rocking", f"impact {k + 1} ω⁺/ω⁻", w1 / w0, s and s["w_after"] / s["w_before"], wa / wb))
    rows.append(("rocking", "impacts before T", float(len(imp)), float(len(simp)) if simp else None,
                 float(ROCK["impacts"])))
    slid = sum(1 for seg in r.segments if "slip" in seg.mode.values())
    note = f"rocking: rigidkin segments with a corner sliding: {slid}"
    if "rocking" in sic:
        note += (f"; Siconos's largest corner speed along the floor while pressed: "
                 f"{sic['rocking']['slip_speed_max']:.1e} m/s")
    return rows, {"rocking": (c1, c2, sic.get("rocking", {}).get("cpu_s"))}, note


def friction_rows(sic):
    rows, cpu = [], {}
    r, c1, c2 = timed(incline_system(INCLINE), INCLINE["T"])
    ev = [e for e in r.events if e.kind == "sticks"][0]
    t_stop, x_stop = incline_closed(INCLINE)
    si = sic.get("incline", {})
    rows.append(("incline", "stop t", ev.t, si.get("t_stop"), t_stop))
    rows.append(("incline", "stop x", ev.state["x"], si.get("x_stop"), x_stop))
    rows.append(("incline", "final x", r.final_state["x"], si.get("x_final"), x_stop))
    cpu["incline"] = (c1, c2, si.get("cpu_s"))

    r, c1, c2 = timed(spring_system(SPRING), SPRING["T"])
    ev = [e for e in r.events if e.kind == "sticks"]
    ss = sic.get("spring", {})
    for k, (t, x) in enumerate(spring_closed(SPRING)):
        s = _nth(ss.get("turns", []), k)
        rows.append(("spring", f"turn {k + 1} t", ev[k].t, s and s["t"], t))
        rows.append(("spring", f"turn {k + 1} x", ev[k].state["x"], s and s["x"], x))
    rows.append(("spring", "final x", r.final_state["x"], ss.get("x_final"), x))
    cpu["spring"] = (c1, c2, ss.get("cpu_s"))
    return rows, cpu


def cpu_model():
    """The processor's name from /proc/cpuinfo where there is one, else what platform knows."""
    try:
        with open("/proc/cpuinfo") as f:
            return next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor() or platform.machine()


def fmt(v):
    return "—" if v is None else f"{v:.10g}" if isinstance(v, float) else str(v)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--siconos-python", default="/usr/bin/python3")
    ap.add_argument("--h-step", type=float, default=1e-4, help="Siconos's Moreau–Jean time step")
    args = ap.parse_args()
    load0 = os.getloadavg()
    sic, why = run_siconos(args.siconos_python, args.h_step)
    for line in why:
        print(f"Siconos skipped: {line}")
    rows, cpu = ball_rows(sic)
    for part in (two_supports_rows, friction_rows):
        more, c = part(sic)
        rows += more
        cpu |= c
    more, c, note = rocking_rows(sic)
    rows += more
    cpu |= c

    print(f"{platform.node()}: {cpu_model()}, {os.cpu_count()} cores, "
          f"load average {load0[0]:.2f} at the start, {os.getloadavg()[0]:.2f} at the end; Python "
          f"{platform.python_version()}; Siconos via {args.siconos_python}\n")
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
    print(f"\n{note}.")
    steps = {k: sic[k]["steps"] for k in ("incline", "spring", "two_supports_rough", "rocking") if k in sic}
    if steps:
        print(f"Siconos Moreau–Jean (time step h = {args.h_step:g} s): " +
              ", ".join(f"{k} {n} steps" for k, n in steps.items()) + "; event-driven: " +
              ", ".join(f"{k} {sic[k]['steps']} events" for k in ("ball", "two_supports") if k in sic) + ".")


if __name__ == "__main__":
    main()
