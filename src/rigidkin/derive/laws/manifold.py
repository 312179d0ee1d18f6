"""Random admissible states: points on the constraint manifold, for comparing laws numerically.

Two laws of the same model agree where the model can be — on the constraint manifold — not at random
values of every coordinate: a four-bar's dependent angles must close the loop.  A random state here
draws the parameters, the independent coordinates and the rates at random, then solves the position
constraints for the dependent coordinates by Newton's method at 30 digits (a draw where the loop
cannot close is drawn again) and gives the dependent rates from the rate relations.
"""

from __future__ import annotations

import random
import weakref

import mpmath
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base import algebra

t = dynamicsymbols._t

#: Draws per admissible state before giving up (the loop cannot close for most random lengths).
TRIES = 40
DPS = 30


class Manifold:
    """Draws admissible states of ``solution`` keyed by the plain symbols of ``algebra.plain_state``."""

    def __init__(self, solution):
        red = solution.setup.reduction
        coord_map = dict(red.coord_map)
        gaps = [sp.sympify(r.gap) for r in red.relating if r.gap is not None]
        gaps = [algebra.substitute(g, coord_map) if coord_map else g for g in gaps]
        dep = [q for q in red.dependent if q not in coord_map and any(g.has(q) for g in gaps)]
        self.active = bool(dep)
        self._samples: dict = {}
        if not self.active:
            return
        gaps = [g for g in gaps if g.has(*dep)]
        plain, back = algebra.plain_state(sp.Matrix(gaps), dep)
        fwd = {v: k for k, v in back.items()}
        self.unknowns = [fwd[q] for q in dep]
        self.given = sorted(plain.free_symbols - set(self.unknowns) - {t}, key=str)
        self.gaps = [sp.lambdify(self.given + self.unknowns + [t], g, modules="mpmath") for g in plain]
        self.square = len(self.gaps) == len(self.unknowns)
        self.start = [_initial(solution.system, q) for q in dep]
        # dependent rates from the rate relations (functions of the coordinates and independent rates)
        self.rates = []
        for q in dep:
            rel = solution.rate_relations.get(q.diff(t))
            if rel is None:
                continue
            p, b = algebra.plain_state(sp.sympify(rel))
            syms = sorted(p.free_symbols - {t}, key=str)
            name = algebra.plain_state(q.diff(t))[0]
            self.rates.append((name, syms, sp.lambdify(syms + [t], p, modules="mpmath")))

    def sample(self, seed: int, i: int) -> tuple[float, dict | None]:
        """(t, admissible state) number ``i`` of the stream ``seed``: drawn once, the same for every
        comparison that asks (Newton's method at 30 digits is the cost of a draw)."""
        key = (seed, i)
        if key not in self._samples:
            rng = random.Random(f"manifold-{seed}-{i}")
            tv = rng.uniform(0.1, 1.0)
            self._samples[key] = (tv, self.draw(rng, tv))
        tv, drawn = self._samples[key]
        return tv, None if drawn is None else dict(drawn)

    def draw(self, rng: random.Random, t_value: float, known: dict | None = None) -> dict | None:
        """{plain symbol: value} of an admissible state (the gaps' symbols, the dependent coordinates and
        rates), consistent with ``known`` where it gives a value; None when no draw closes the constraints."""
        known = dict(known or {})
        with mpmath.workdps(DPS):
            for attempt in range(TRIES):
                vals = algebra.random_point([s for s in self.given if s not in known], rng)
                vals = {**{k: complex(v).real for k, v in vals.items()}, **known}
                args = [mpmath.mpf(float(complex(vals[s]).real)) for s in self.given]
                starts = [self.start] if attempt == 0 else []
                starts.append([rng.uniform(-3.2, 3.2) for _ in self.unknowns])
                root = None
                for x0 in starts:
                    root = self._solve(args, x0, t_value)
                    if root is not None:
                        break
                if root is None:
                    if known:
                        known = {}       # the given values admit no closure: draw them too
                    continue
                out = {**vals, **{u: float(r) for u, r in zip(self.unknowns, root)}}
                for name, syms, fn in self.rates:
                    for s in syms:
                        if s not in out:
                            out[s] = float(complex(algebra.random_point([s], rng)[s]).real)
                    out[name] = float(mpmath.re(fn(*[out[s] for s in syms], t_value)))
                return out
        return None

    def _solve(self, args, x0, t_value):
        def F(*x):
            return [g(*args, *x, t_value) for g in self.gaps]

        try:
            if self.square:
                root = mpmath.findroot(F, [mpmath.mpf(v) for v in x0], tol=mpmath.mpf(10) ** (4 - DPS))
            else:
                root = mpmath.findroot(F, [mpmath.mpf(v) for v in x0], tol=mpmath.mpf(10) ** (4 - DPS),
                                       solver="mdnewton")
        except (ValueError, ZeroDivisionError, TypeError):
            return None
        root = list(root) if hasattr(root, "__len__") else [root]
        if any(abs(mpmath.im(r)) > 1e-20 for r in root):
            return None
        res = F(*root)
        if max(abs(v) for v in res) > mpmath.mpf(10) ** (8 - DPS):
            return None
        return [mpmath.re(r) for r in root]


def manifold_of(solution) -> Manifold | None:
    """The solution's admissible-state sampler, or None when no dependent coordinate is left implicit
    (made once per solution: its draws are kept for every comparison)."""
    kept = _KEPT.get(id(solution))
    if kept is not None and kept[0]() is solution:
        return kept[1]
    try:
        m = Manifold(solution)
    except (AttributeError, TypeError, ValueError):
        m = None
    m = m if m is not None and m.active else None
    for k in [k for k, (ref, _) in _KEPT.items() if ref() is None]:
        del _KEPT[k]
    _KEPT[id(solution)] = (weakref.ref(solution), m)
    return m


#: id(solution) → (weak reference to it, its Manifold): kept beside the solution, not in it (numeric
#: functions are not pickled with a derivation).
_KEPT: dict = {}


def _initial(system, q) -> float:
    try:
        v = system.coordinate_of(q).initial
        return float(v) if v is not None else 0.5
    except (KeyError, TypeError, ValueError):
        return 0.5

