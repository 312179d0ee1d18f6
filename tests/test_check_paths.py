"""The short cuts of ``check`` (derive/laws: compare, manifold) against what they stand for.

Independent references: ``sympy.count_ops`` for ``ops_above``; the manifold's own Newton solve for the
kept admissible states (each satisfies the loop's position constraints to 20 digits, and a second sampler
of the same seed meets the same states); ``sympy.lambdify`` for the tree evaluator of the comparisons.
"""

import random
import sys
from pathlib import Path

import mpmath
import numpy as np
import sympy as sp

from rigidkin import examples
from rigidkin.base import algebra
from rigidkin.derive.laws.compare import Sampler, evaluator, ops_above
from rigidkin.derive.laws.manifold import manifold_of

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import models  # noqa: E402


def _exprs(sol):
    out = [e.expr for e in sol.equations]
    for r in sol.regimes:
        out += [*r.raw_mass_matrix, *r.raw_forcing]
    return out


def test_ops_above_is_count_ops_above():
    exprs = _exprs(examples.build("rolling-disk").solve()) + _exprs(examples.build("collar-force").solve())
    for e in exprs:
        n = sp.count_ops(e)
        for limit in (0, 5, 60, 199, 250, 399, 1000):
            assert ops_above(e, limit) == (n > limit), (e, limit)


def test_admissible_states_are_kept_and_close_the_loop():
    sol = models.four_bar().solve()
    m = manifold_of(sol)
    assert m is not None and manifold_of(sol) is m
    a, b = Sampler(seed=5, manifold=m), Sampler(seed=5, manifold=m)
    for i in range(4):
        s = a.accelerations(sol.regimes[0], sol.coordinates, i)
        assert s == b.accelerations(sol.regimes[0], sol.coordinates, i)
        tv, state = m.sample(5, i)
        with mpmath.workdps(30):
            args = [mpmath.mpf(state[g]) for g in m.given] + [mpmath.mpf(state[u]) for u in m.unknowns]
            # floats of a 30-digit root: the gaps vanish to the floats' precision
            assert all(abs(g(*args, tv)) < 1e-12 for g in m.gaps)


def test_tree_evaluation_equals_lambdify():
    sol = examples.build("gyroscope").solve()
    r = sol.regimes[0]
    plain, _ = algebra.plain_state(r.raw_mass_matrix.row_join(r.raw_forcing))
    syms = sorted(plain.free_symbols, key=str)
    fn, ref = evaluator(plain, syms), sp.lambdify(syms, plain, modules=["numpy"])
    rng = random.Random(2)
    for _ in range(5):
        p = [rng.uniform(-1.5, 1.5) for _ in syms]
        assert np.allclose(fn(*p), np.array(ref(*p), dtype=complex), rtol=1e-13, atol=1e-13)
