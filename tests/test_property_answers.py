"""Property test over random problem files built from the bundled examples' vocabulary (issue 26, point 11).

Seeded and deterministic: each case draws one of a few building blocks (a pendulum with a torsional spring
and a damper, a collar on a track with a spring and a pendulum rod, a disk rolling on an incline against a
spring, a cylinder sliding onto a rough incline, a ladder on a wall and a floor, a rod whose end is held on a
line) with random parameter values in random declared units, and random starting states.  For every file:

* every printed answer passes its own back-substitution, checked here independently of the answering code:
  an equilibrium makes the accelerations (the file's equations of motion, rates zero) vanish with the
  parameters' values; each natural frequency is real and its square an eigenvalue of the numeric stiffness
  −∂q̈/∂q at that equilibrium (central differences), and the stability agrees with that stiffness; an
  event's condition holds at the reported state (the ladder's wall push by Newton's law by hand), and
  (conservative case) the reported state has the energy of the start; the sliding cylinder starts to roll
  after v0 / (g (3 µ cos β − sin β)) (by hand, and the simulation's event); a question's start off the
  rod's line is assembled onto it, θ = asin(c/l); a question refused is said (solve exits 1), never answered
  wrongly;
* every simulation, accurate and coarse, keeps its constraints and its energy balance — the closed-form
  constraints of the building block (x = l sin θ on the wall, x = r θ rolling, l sin θ = c on the line) hold
  along the history — or stops with a named stop reason and exit 3: it is never "completed" with a
  violation; a line out of reach is refused by solve and simulate naming the gap c − l.

The larger part is marked slow (``pytest -m slow``).
"""

from __future__ import annotations

import json
import math
import random
import warnings

import numpy as np
import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin.analysis.answers import answer
from rigidkin.base.errors import RigidkinError
from rigidkin.cli import main
from rigidkin.io.load import load_system

t = dynamicsymbols._t
N_QUICK, N_ALL = 6, 36
STOP_REASONS = {"mode-unavailable", "no-consistent-mode", "ambiguous", "accumulation", "max-events",
                "relation-mismatch", "outside-domain", "constraint-drift", "energy-drift"}


# building blocks --------------------------------------------------------------------------------------------
def _length(rng, lo, hi):
    """A length with a random declared unit: (TOML value text, SI value)."""
    v = round(rng.uniform(lo, hi), 2)
    if rng.random() < 0.5:
        return f'unit = "cm", value = {round(100 * v)}', round(100 * v) / 100
    return f'unit = "m", value = {v}', v


def pendulum(rng):
    """A rod pinned at O, a torsional spring to the ground, maybe a damper about the pin."""
    lt, l_ = _length(rng, 0.3, 2.0)
    k = round(rng.uniform(1, 30), 1) if rng.random() < 0.5 else 0
    c = round(rng.uniform(0.05, 1.0), 2) if rng.random() < 0.4 else 0
    th0 = round(rng.uniform(-0.8, 0.8), 3)
    w0 = round(rng.uniform(0.5, 3.0), 3)
    spring = '\nspring = { type = "rotational_spring", body_a = "rod", stiffness = "k" }' if k else ""
    pk = f'k = {{ unit = "N*m/rad", value = {k} }}\n' if k else ""
    pc = f'c = {{ unit = "N*m*s/rad", value = {c} }}\n' if c else ""
    damper = ('\ndamp = { type = "rotational_damper", body_a = "rod", coefficient = "c" }' if c else "")
    text = f"""
title = "Pendulum with a torsional spring"
[parameters]
m = {{ unit = "kg", value = {round(rng.uniform(0.2, 5), 2)} }}
l = {{ {lt} }}
{pk}{pc}g = {{ unit = "m/s^2", value = 9.81 }}
[coordinates]
theta = {{ sense = "angle of the rod from the downward vertical", initial = {th0}, rate = {w0} }}
[frames]
R = {{ angle = "theta" }}
[points]
G = {{ offset = "-l/2*R.y" }}
[bodies]
rod = {{ shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }}
[constraints]
O = {{ type = "pin", point = "O", body_a = "rod" }}
[loads]
gravity = {{ type = "gravity", g = "g" }}{spring}{damper}
[[ask.question]]
kind = "equilibrium"
[[ask.question]]
kind = "event"
name = "turns"
when = "dot(theta) = 0"
start = {{ theta = 0, "dot(theta)" = {w0} }}
"""
    return text, {"conservative": not c, "closed": []}


def collar_spring(rng):
    """A collar on a smooth track held by a spring, with a pendulum rod pinned to it."""
    lt, _ = _length(rng, 0.3, 1.5)
    L0t, _ = _length(rng, 0.1, 0.8)
    text = f"""
title = "Collar with a spring and a pendulum rod"
[parameters]
m1 = {{ unit = "kg", value = {round(rng.uniform(0.5, 4), 2)} }}
m2 = {{ unit = "kg", value = {round(rng.uniform(0.2, 3), 2)} }}
l = {{ {lt} }}
K = {{ unit = "N/m", value = {round(rng.uniform(5, 80), 1)} }}
L0 = {{ {L0t} }}
g = {{ unit = "m/s^2", value = 9.81 }}
[coordinates]
x = {{ sense = "collar along the track", kind = "length", initial = {round(rng.uniform(-0.3, 0.3), 3)}, rate = 0 }}
theta = {{ sense = "rod from the downward vertical", initial = {round(rng.uniform(-1, 1), 3)}, \
rate = {round(rng.uniform(-1, 1), 3)} }}
[frames]
R = {{ angle = "theta" }}
[points]
P = {{ offset = "x*Ex" }}
Q = {{ offset = "-L0*Ex" }}
G = {{ from = "P", offset = "-l/2*R.y" }}
[bodies]
collar = {{ shape = "point_mass", mass = "m1", frame = "F", at = "P" }}
rod = {{ shape = "slender_rod", mass = "m2", length = "l", axis = "y", frame = "R", at = "G" }}
[constraints]
track = {{ type = "collar", body = "collar", along = "Ex", normal_name = "N", couple_name = "M_track" }}
P = {{ type = "pin", point = "P", body_a = "rod", body_b = "collar" }}
[loads]
gravity = {{ type = "gravity", g = "g" }}
spring = {{ type = "spring", point_a = "P", point_b = "Q", stiffness = "K", natural_length = "L0" }}
[[ask.question]]
kind = "equilibrium"
"""
    return text, {"conservative": True, "closed": []}


def disk_spring(rng):
    """A disk rolling on an incline, held by a spring up-slope (rolling: x = r θ)."""
    rt, r_ = _length(rng, 0.05, 0.4)
    text = f"""
title = "Disk rolling against a spring"
[parameters]
m = {{ unit = "kg", value = {round(rng.uniform(0.5, 5), 2)} }}
r = {{ {rt} }}
K = {{ unit = "N/m", value = {round(rng.uniform(10, 200), 1)} }}
beta = {{ unit = "rad", value = "{rng.randint(5, 40)} deg" }}
g = {{ unit = "m/s^2", value = 9.81 }}
L0 = {{ unit = "m", value = 0.5 }}
[coordinates]
theta = {{ sense = "rotation, positive rolling down", initial = {round(rng.uniform(-2, 2), 3)}, \
rate = {round(rng.uniform(-3, 3), 3)} }}
x = {{ sense = "centre down the incline", kind = "length" }}
[frames]
I = {{ angle = "-beta", basis = ["es", "en", "ez"] }}
D = {{ angle = "-theta" }}
[points]
C = {{ offset = "x*es + r*en" }}
Q = {{ offset = "-L0*es + r*en" }}
[bodies]
disk = {{ shape = "disk", mass = "m", radius = "r", frame = "D", at = "C" }}
[constraints.P]
type = "contact"
body = "disk"
surface = {{ type = "line", point = "O", normal = "en", name = "incline" }}
radius = "r"
friction = "rolling"
normal_name = "N"
friction_name = "F"
[loads]
spring = {{ type = "spring", point_a = "C", point_b = "Q", stiffness = "K", natural_length = "L0" }}
gravity = {{ type = "gravity", g = "g" }}
[[ask.question]]
kind = "equilibrium"
"""
    return text, {"conservative": True, "closed": [("x", lambda q: q["x"] - r_ * q["theta"])]}


def sliding(rng):
    """A cylinder released on an incline with Coulomb friction (sliding, then maybe rolling)."""
    rt, _ = _length(rng, 0.05, 0.3)
    beta, mu, v0 = rng.randint(10, 50), round(rng.uniform(0.05, 0.6), 2), round(rng.uniform(0.2, 3), 2)
    text = f"""
title = "Cylinder on a rough incline"
[parameters]
m = {{ unit = "kg", value = {round(rng.uniform(0.5, 5), 2)} }}
r = {{ {rt} }}
beta = {{ unit = "rad", value = "{beta} deg" }}
g = {{ unit = "m/s^2", value = 9.81 }}
mu = {{ unit = "", value = {mu} }}
[coordinates]
x = {{ sense = "centre down the incline", kind = "length", initial = 0, rate = {v0} }}
phi = {{ sense = "rotation, clockwise", initial = 0, rate = 0 }}
[frames]
I = {{ angle = "-beta", basis = ["es", "en", "ez"] }}
B = {{ angle = "-phi" }}
[points]
C = {{ offset = "x*es + r*en" }}
[bodies]
cylinder = {{ shape = "disk", mass = "m", radius = "r", frame = "B", at = "C" }}
[constraints.ground]
type = "contact"
body = "cylinder"
surface = {{ type = "line", point = "O", normal = "en", name = "incline" }}
radius = "r"
friction = "mu"
normal_name = "N"
friction_name = "F"
[loads]
gravity = {{ type = "gravity", g = "g" }}
[[ask.question]]
kind = "phases"
name = "to_rolling"
start = {{ x = 0, "dot(x)" = {v0}, phi = 0, "dot(phi)" = 0 }}
[[ask.question.phase]]
name = "sliding"
until = "slip(ground) = 0"
[[ask.question.phase]]
name = "rolling"
mode = {{ ground = "stick" }}
"""
    return text, {"conservative": False, "closed": [], "slide": (math.radians(beta), mu, v0)}


def ladder(rng):
    """A rod on a smooth wall and floor (x = l sin θ while on the wall); the event N_A = 0."""
    lt, l_ = _length(rng, 0.5, 3.0)
    th0 = round(rng.uniform(0.05, 0.6), 3)
    text = f"""
title = "Ladder"
[parameters]
m = {{ unit = "kg", value = {round(rng.uniform(1, 20), 1)} }}
l = {{ {lt} }}
g = {{ unit = "m/s^2", value = 9.81 }}
[coordinates]
theta = {{ sense = "rod from the upward vertical", initial = {th0}, rate = 0 }}
x = {{ sense = "foot from the wall", kind = "length" }}
[frames]
R = {{ angle = "theta", basis = ["ex", "ey", "ez"] }}
[points]
B = {{ from = "O", offset = "x*Ex", body = "rod" }}
G = {{ from = "B", offset = "l/2*ey" }}
A = {{ from = "B", offset = "l*ey", body = "rod" }}
[bodies.rod]
shape = "slender_rod"
mass = "m"
length = "l"
axis = "y"
frame = "R"
at = "G"
[constraints.A]
type = "contact"
body = "rod"
surface = {{ type = "line", point = "O", normal = "Ex", name = "wall" }}
centre = "A"
normal_name = "N_A"
[constraints.B]
type = "contact"
body = "rod"
surface = {{ type = "line", point = "O", normal = "Ey", name = "floor" }}
centre = "B"
normal_name = "N_B"
[loads.gravity]
type = "gravity"
g = "g"
[[ask.question]]
kind = "event"
name = "leaves_wall"
when = "N_A = 0"
start = {{ theta = {th0}, "dot(theta)" = 0 }}
"""
    return text, {"conservative": True, "wall": l_,
                  "closed": [("x", lambda q: q["x"] - l_ * np.sin(q["theta"]))]}


def rod_on_line(rng):
    """A rod pinned at O whose end B is held on the line x = c (θ = asin(c/l)), from a rough declared angle;
    about one case in three puts the line out of reach (c > l): every command refuses it naming the residual c − l."""
    l_ = round(rng.uniform(0.5, 2.0), 2)
    c = round(l_ * (rng.uniform(1.1, 1.6) if rng.random() < 0.4 else rng.uniform(-0.9, 0.9)), 3)
    near = math.asin(c / l_) if abs(c) < l_ else math.pi / 2
    rough = round(near + rng.uniform(-0.3, 0.3), 3)
    text = f"""
title = "Rod whose end is held on a line"
[parameters]
m = {{ unit = "kg", value = {round(rng.uniform(0.5, 5), 2)} }}
l = {{ unit = "m", value = {l_} }}
c = {{ unit = "m", value = {c} }}
g = {{ unit = "m/s^2", value = 9.81 }}
[coordinates]
theta = {{ sense = "angle of the rod from the downward vertical", initial = {rough}, rate = 0 }}
[frames]
R = {{ angle = "theta" }}
[points]
B = {{ offset = "-l*R.y", body = "rod" }}
G = {{ offset = "-l/2*R.y" }}
Q = {{ offset = "c*Ex" }}
[bodies]
rod = {{ shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }}
[constraints]
O = {{ type = "pin", point = "O", body_a = "rod" }}
B = {{ type = "contact", body = "rod", centre = "B", unilateral = false, \
      surface = {{ type = "line", point = "Q", normal = "-Ex" }} }}
[loads]
gravity = {{ type = "gravity", g = "g" }}
[[ask.question]]
kind = "value"
name = "angle"
expression = "theta"
at = {{ theta = {round(near + rng.uniform(-0.3, 0.3), 3)} }}
"""
    return text, {"conservative": True, "closed": [("theta", lambda q: l_ * np.sin(q["theta"]) - c)],
                  "line": (c, l_)}


BLOCKS = (pendulum, collar_spring, disk_spring, sliding, ladder, rod_on_line)


def case(seed: int):
    rng = random.Random(seed)
    block = BLOCKS[seed % len(BLOCKS)]
    text, facts = block(rng)
    return block.__name__, text, facts


# independent checks -----------------------------------------------------------------------------------------
def _values(system):
    return {p.symbol: float(p.value) for p in system.parameter_info.values()}


def _accelerations(sol, regime, values):
    """q̈(q, q̇) of the solution as numeric functions of the independent coordinates and rates."""
    qs = list(sol.coordinates)
    acc = [sp.sympify(regime.accelerations[q]) for q in qs]
    rel = {**dict(sol.rate_relations), **dict(sol.relations)}
    for _ in range(3):
        acc = [a.xreplace(rel) for a in acc]
    plain_q = [sp.Symbol(f"q{i}") for i in range(len(qs))]
    plain_u = [sp.Symbol(f"u{i}") for i in range(len(qs))]
    m = {q.diff(t): u for q, u in zip(qs, plain_u)}
    acc = [a.xreplace(m).xreplace(dict(zip(qs, plain_q))).xreplace(values) for a in acc]
    f = sp.lambdify([plain_q, plain_u], acc, "numpy")
    return lambda q, u: np.array(f(list(q), list(u)), dtype=float)


def check_equilibria(system, sol, eqs):
    values = _values(system)
    regime = sol.regimes[0]
    acc = _accelerations(sol, regime, values)
    qs = list(sol.coordinates)
    n = len(qs)
    for e in eqs:
        q0 = np.array([float(sp.sympify(e.configuration[q]).xreplace(values)) for q in qs])
        a0 = acc(q0, np.zeros(n))
        assert np.max(np.abs(a0)) < 1e-8, f"{system.title}: {e} leaves q̈ = {a0}"
        h = 1e-6
        J = np.column_stack([(acc(q0 + h * np.eye(n)[j], np.zeros(n)) - acc(q0 - h * np.eye(n)[j], np.zeros(n)))
                             / (2 * h) for j in range(n)])
        w2 = np.sort(np.linalg.eigvals(-J).real)
        for w in e.natural_frequencies:
            wv = complex(sp.sympify(w).xreplace(values).evalf())
            assert abs(wv.imag) < 1e-9 and wv.real > 0, f"{system.title}: ω_n = {w} is not real at {e}"
            assert np.min(np.abs(w2 - wv.real ** 2)) < 1e-5 * max(1.0, wv.real ** 2), (system.title, w, w2)
        # the stiffness decides: a direction it pushes away from makes the equilibrium unstable (the real
        # frequencies printed then belong to the other directions), none makes it stable
        if w2.min() < -1e-6:
            assert e.stability.startswith("unstable"), (e, w2)
        elif w2.min() > 1e-6:
            assert e.stability.startswith(("stable", "asymptotically stable")), (e, w2)


def _energy(system, state):
    """T + U at a state (rigidkin's energy of the solution, evaluated with the parameters' values)."""
    from rigidkin.numeric import simulate

    r = simulate(system, 1e-6, {k: v for k, v in state.items()}, n_points=3)
    return float(r["E"][0])


def check_event(system, sol, ans, facts):
    d = ans.details
    if not d.get("happens"):
        return
    values = _values(system)
    state = {**d["configuration"], **{k: v for k, v in d["end_state"].items()}}
    num = {k: float(sp.sympify(v).xreplace(values).evalf()) for k, v in state.items()}
    when = ans.question.fields["when"]
    lhs = sp.sympify(when.lhs - when.rhs) if isinstance(when, sp.Eq) else sp.sympify(when)
    if "N_A" in str(lhs):     # the wall's push on the ladder, by Newton's second law on the rod (horizontal)
        th, w = num[sol.coordinates[0]], num[sol.coordinates[0].diff(t)]
        l_ = facts["wall"]
        m = [v for s, v in values.items() if s.name == "m"][0]
        g = [v for s, v in values.items() if s.name == "g"][0]
        # x_G = l/2 sin θ: N_A = m ẍ_G, ẍ_G = l/2 (cos θ θ̈ − sin θ θ̇²), θ̈ = 3g/(2l) sin θ on the wall
        acc = 3 * g / (2 * l_) * math.sin(th)
        N_A = m * l_ / 2 * (math.cos(th) * acc - math.sin(th) * w ** 2)
        assert abs(N_A) < 1e-7 * m * g, f"N_A = {N_A} at the reported state {num}"
    else:
        rates = {k: sp.Float(v) for k, v in num.items() if isinstance(k, sp.Derivative)}
        coords = {k: sp.Float(v) for k, v in num.items() if not isinstance(k, sp.Derivative)}
        residual = float(sp.sympify(lhs).xreplace(rates).xreplace(coords).xreplace(values))
        assert abs(residual) < 1e-9, f"{ans.text}: the condition is {residual} at the reported state"
    if facts["conservative"]:
        start = ans.question.fields["start"]
        e0 = _energy(system, {_name(k): float(sp.sympify(v).xreplace(values)) for k, v in start.items()})
        e1 = _energy(system, {_name(k): v for k, v in num.items()})
        assert e1 == pytest.approx(e0, rel=1e-7, abs=1e-9), f"{ans.text}: energy {e1} vs {e0} at the start"


def check_phases(system, sol, ans, facts):
    """Sliding until rolling begins: the slip vanishes at the reported end state; by hand, the slip speed
    falls at g (3 µ cos β − sin β), so rolling begins after v0 / (g (3 µ cos β − sin β)) when that is
    positive, at the speed v0 + g (sin β − µ cos β) t*; the simulation sticks then too."""
    from rigidkin.numeric import simulate

    beta, mu, v0 = facts["slide"]
    g = 9.81
    values = _values(system)
    sliding = ans.details["phases"][0]
    rate = 3 * mu * math.cos(beta) - math.sin(beta)
    assert sliding.happens == (rate > 0), ans.text
    if not sliding.happens:
        return
    end = {k: float(sp.sympify(v).xreplace(values)) for k, v in sliding.end_state.items()}
    x, phi = sol.coordinates if sol.coordinates[0].func.__name__ == "x" else sol.coordinates[::-1]
    r_ = [v for k, v in values.items() if k.name == "r"][0]
    assert abs(end[x.diff(t)] - r_ * end[phi.diff(t)]) < 1e-9 * max(1.0, v0), "the slip does not vanish there"
    t_star = v0 / (g * rate)
    assert float(sp.sympify(sliding.duration).xreplace(values)) == pytest.approx(t_star, rel=1e-10)
    assert end[x.diff(t)] == pytest.approx(v0 + g * (math.sin(beta) - mu * math.cos(beta)) * t_star, rel=1e-10)
    if t_star < 1.0:
        res = simulate(system, 1.0, n_points=11)
        assert any(abs(e.t - t_star) < 1e-6 * max(1.0, t_star) for e in res.events), (t_star, res.events)


def _name(k) -> str:
    if isinstance(k, sp.Derivative):
        return f"dot({k.expr.func.__name__})"
    return k.func.__name__


LOOSE = ("--rtol", "1e-2", "--atol", "1e-2", "--method", "RK45")   # an integration too coarse to keep the monitors


def check_simulation(path, facts, capsys):
    """From the command line, accurate and coarse: completed with the monitors within their tolerances (exit
    0), or stopped with a named reason (exit 3)."""
    outs = []
    for extra in ((), LOOSE):
        code = main(["simulate", str(path), "--t-end", "1.5", "--json", "--points", "301", "--no-cache", *extra])
        out = json.loads(capsys.readouterr().out)
        if out["stop_reason"] == "completed":
            assert code == 0 and out["status"] == "completed"
            scale = max(1.0, max(abs(v) for v in out["final_state"].values()))
            assert out["max_constraint_residual"] <= 1e-6 * scale and out["energy_drift"] <= 1e-6, out
        else:
            assert code == 3 and out["stop_reason"] in STOP_REASONS and out["status"] == "stopped", out
        outs.append(out)
    return outs


def check_histories(system, facts):
    """The building block's closed-form constraints along the histories of the Python API's simulations,
    accurate and coarse: kept at every sample of a completed run, and up to the stop of a stopped one."""
    from rigidkin.numeric import simulate

    if not facts["closed"]:
        return
    for options in ({}, {"rtol": 1e-2, "atol": 1e-2, "method": "RK45"}):
        r = simulate(system, 1.5, n_points=301, **options)
        closed = r.reactions.get("N_A")
        keep = slice(None) if r.stop_reason == "completed" else slice(0, -1)   # a drift stop: its last sample
        tol = 1e-6 * max(1.0, float(np.max(np.abs(r.y[:, :r.layout.n]))))
        for _, gap in facts["closed"]:
            g = np.abs(gap(r.q))[keep]
            if closed is not None:            # the wall: only while the rod touches it
                g = g[np.abs(closed[keep]) > 0]
            assert np.max(g, initial=0.0) <= tol, (system.title, options, r.stop_reason, np.max(g))


# the property ------------------------------------------------------------------------------------------------
def _run(seed, tmp_path, capsys):
    name, text, facts = case(seed)
    path = tmp_path / f"{name}-{seed}.toml"
    path.write_text(text)
    if "line" in facts and abs(facts["line"][0]) > facts["line"][1]:
        return _unreachable(path, facts, capsys)
    system, spec = load_system(str(path))
    sol = system.solve()
    answered = 0
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        answers = list(_answers(system, spec.questions))
    for ans in answers:
        answered += 1
        if "line" in facts:               # the question's at assembled onto the line: θ = asin(c/l), said so
            c, l_ = facts["line"]
            assert float(sp.sympify(ans.value).xreplace(_values(system))) == pytest.approx(math.asin(c / l_),
                                                                                        abs=1e-12)
            assert any("assembled onto them" in str(w.message) for w in said)
        if ans.question.kind == "equilibrium":
            check_equilibria(system, sol, ans.details["equilibria"])
        elif ans.question.kind == "event":
            check_event(system, sol, ans, facts)
        elif ans.question.kind == "phases":
            check_phases(system, system.solve(mode={"ground": "slip"}), ans, facts)
    code = main(["solve", str(path), "--no-cache"])
    capsys.readouterr()
    assert code == (0 if answered == len(spec.questions) else 1)      # a refused question is said: exit 1
    check_simulation(path, facts, capsys)
    check_histories(system, facts)
    return answered


def _unreachable(path, facts, capsys):
    """A line the rod end cannot reach: solve and simulate refuse it (exit 2), naming the gap c − l."""
    c, l_ = facts["line"]
    for argv in (["solve", str(path), "--no-cache"], ["simulate", str(path), "--t-end", "0.5", "--no-cache"]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert f"contact B keeps a residual of {abs(c) - l_:.4g}" in err, err


def _answers(system, questions):
    """Each question's answer, or nothing where it is refused with a reason (a refusal is never wrong)."""
    context = {}
    for q in questions:
        try:
            a = answer(system, q, context)
        except RigidkinError as exc:
            assert str(exc) and "internal error" not in str(exc)
            continue
        context[q.name] = a
        yield a


HEAVY = {0, 1, 3, 4}     # the four quick seeds that take longest (5-19 s each on 2 cores): with the slow ones
SEEDS = [s if s < N_QUICK and s not in HEAVY else pytest.param(s, marks=pytest.mark.slow) for s in range(N_ALL)]


@pytest.mark.parametrize("seed", SEEDS)
def test_random_problem_answers_check_themselves(seed, tmp_path, capsys):
    _run(seed, tmp_path, capsys)


def test_generator_is_deterministic():
    assert [case(s)[1] for s in range(10)] == [case(s)[1] for s in range(10)]
    assert len({case(s)[1] for s in range(N_ALL)}) == N_ALL
    lines = [case(s)[2]["line"] for s in range(N_ALL) if "line" in case(s)[2]]
    assert any(abs(c) > l_ for c, l_ in lines) and any(abs(c) < l_ for c, l_ in lines)   # both kinds drawn
