"""Test helpers: numeric comparison of expressions at random states and parameter values; the command line
run in a process of its own."""

from __future__ import annotations

import os
import random
import subprocess
import sys
from pathlib import Path

import sympy as sp
from sympy.physics.vector import dynamicsymbols

t = dynamicsymbols._t
SRC = str(Path(__file__).resolve().parents[1] / "src")      # this tree's rigidkin, not an installed copy


def rigidkin_env(base=None, **extra) -> dict:
    """The environment of a child process that imports this tree's rigidkin: ``base`` (default: this
    process's environment) with ``PYTHONPATH`` set to src, and ``extra``."""
    env = dict(os.environ if base is None else base, PYTHONPATH=SRC)
    env.update(extra)
    return env


def benchmark_models():
    """benchmarks/models.py (the four-bar, the Kane chain ... that the benchmarks time): one copy of each
    model for the benchmarks and the tests."""
    import importlib.util

    name = "rigidkin_benchmark_models"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, Path(SRC).parent / "benchmarks" / "models.py")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        sys.modules[name] = module
    return sys.modules[name]


def rod_pendulum(shape=None, *, pin: bool = True, values: dict | None = None):
    """A rod (mass m, length l; ``shape(m, l)``, default a uniform slender rod) hung from O, θ from the
    downward vertical, under gravity g; pinned at O unless ``pin=False``; ``values`` gives m, l, g numbers.
    Returns (system, rod, θ, its frame R, (m, l, g))."""
    import rigidkin as rk

    values = values or {}
    s = rk.System("pendulum")
    m, l, g = (s.parameter(n, u, value=values.get(n)) for n, u in (("m", "kg"), ("l", "m"), ("g", "m/s^2")))
    th = s.coordinate("theta", "from the downward vertical")
    R = s.frame("R", angle=th)
    G = s.point("G", offset=-l / 2 * R.y)
    rod = s.body("rod", (shape or (lambda m, l: rk.shapes.SlenderRod(m, l, axis="y")))(m, l), frame=R, at=G)
    if pin:
        s.pin("O", s.origin, rod)
    s.gravity(g)
    return s, rod, th, R, (m, l, g)


def pushed_block(unit: str = "N"):
    """A block (2 kg) on a smooth rail along Ex, pushed by an input F (in ``unit``), from x = 0."""
    import rigidkin as rk

    s = rk.System("block")
    m = s.parameter("m", "kg", value=2.0)
    F = s.input("F", unit, "push along Ex")
    x = s.coordinate("x", "block along Ex", kind="length", initial=0.0)
    C = s.point("C", offset=x * s.inertial.x)
    b = s.body("block", rk.shapes.PointMass(m), frame=s.inertial, at=C)
    s.collar("rail", b, s.inertial.x, point=C)
    s.force("push", C, F * s.inertial.x)
    return s


def gliding_block():
    """A block (1 kg) gliding on a smooth rail along Ex at 1 m/s from x = 0: no input, no load along it."""
    import rigidkin as rk

    s = rk.System("free")
    m = s.parameter("m", "kg", value=1.0)
    x = s.coordinate("x", kind="length", initial=0.0, rate=1.0)
    C = s.point("C", offset=x * s.inertial.x)
    b = s.body("b", rk.shapes.PointMass(m), frame=s.inertial, at=C)
    s.collar("rail", b, s.inertial.x, point=C)
    return s


def rigidkin_process(*args, env=None, timeout=600, text=True, **kw) -> subprocess.CompletedProcess:
    """``python -m rigidkin ARGS`` in a process of its own (output captured unless ``stdout`` is given)."""
    if "stdout" not in kw:
        kw["capture_output"] = True
    return subprocess.run([sys.executable, "-m", "rigidkin", *map(str, args)], env=rigidkin_env(env), text=text,
                          timeout=timeout, **kw)


def plain(expr, coords):
    """Replace q(t), q̇, q̈ of ``coords`` by plain symbols q, qd, qdd."""
    m = {}
    for q in coords:
        n = q.func.__name__
        m[q.diff(t, 2)] = sp.Symbol(f"{n}_dd")
        m[q.diff(t)] = sp.Symbol(f"{n}_d")
    e = sp.sympify(expr).xreplace(m)
    return e.xreplace({q: sp.Symbol(n.func.__name__) for n, q in zip(coords, coords)})


def sample(symbols, n=20, seed=0, ranges=None):
    """n dicts of random values: ``ranges`` maps a symbol name to (lo, hi); default (0.5, 2)."""
    rng = random.Random(seed)
    ranges = ranges or {}
    out = []
    for _ in range(n):
        out.append({s: rng.uniform(*ranges.get(str(s), (0.5, 2.0))) for s in symbols})
    return out


def values_match(a, b, coords, n=20, seed=0, ranges=None, tol=1e-9, factor=False):
    """True when expressions a and b (of the state and parameters) agree at n random points.

    With ``factor=True`` they need only agree up to a nonzero factor that may depend on the
    parameters but not on the state (two forms of one equation ``= 0``).
    """
    a, b = plain(a, coords), plain(b, coords)
    syms = sorted((a.free_symbols | b.free_symbols) - {t}, key=str)
    state_names = {f"{q.func.__name__}{suf}" for q in coords for suf in ("", "_d", "_dd")}
    fa, fb = sp.lambdify(syms, a, "mpmath"), sp.lambdify(syms, b, "mpmath")
    points = sample(syms, n, seed, ranges)
    groups = [points[i:i + 4] for i in range(0, n, 4)] if factor else [[p] for p in points]
    for group in groups:
        ratio = None
        params = group[0]
        for vals in group:
            vals = {s: (vals[s] if str(s) in state_names else params[s]) for s in syms}
            args = [vals[s] for s in syms]
            va, vb = complex(fa(*args)), complex(fb(*args))
            if not factor:
                if abs(va - vb) > tol * max(1.0, abs(va), abs(vb)):
                    return False
                continue
            if abs(vb) < 1e-12:
                if abs(va) > 1e-9:
                    return False
                continue
            r = va / vb
            if abs(r) < 1e-12:
                return False
            if ratio is None:
                ratio = r
            elif abs(r - ratio) > tol * max(1, abs(ratio)):
                return False
    return True


def solve_accels(eqs, coords):
    """Accelerations from a list of equations (= 0) linear in q̈."""
    acc = [q.diff(t, 2) for q in coords]
    sol = sp.solve(eqs, acc, dict=True)[0]
    return {q: sol[q.diff(t, 2)] for q in coords}
