"""Chains of n rods past one machine's size: time per RHS (forward dynamics) against Pinocchio's ABA.

For n = 5, 10, 20, 30, 50 (``--sizes``) and the bundled chain of n rods (examples/chain.py):

* rigidkin's O(n) RHS: ``numeric.articulated.ArticulatedModel.rates`` (the articulated-body algorithm
  on the tree read from the model; what ``simulate`` uses past ``numeric.large.SYMBOLIC_LIMIT``);
* Pinocchio's ``aba`` on the same chain built as revolute-z joints (Python call, one per RHS);
* the symbolic route ``simulate`` uses below the limit (``Hybrid.model(...).rates``: the derivation
  and lambdified M, f) and the projected route (``numeric.projected.ProjectedModel.rhs``), each in a
  child process with a time limit (``--limit`` seconds for building it), where they finish.

rigidkin's RHS is timed with its step in C (``numeric/aba_c.py``, what a gravity-only tree uses) and
in numpy (what a tree with other loads uses).  Every RHS is checked against Pinocchio's accelerations
first (relative angles: θ̈_i − θ̈_{i−1}).
Times are CPU seconds per call (best of repeats); the table gives the growth from the smallest to the
largest n and the ratio to Pinocchio, all measured in one run.

    python benchmarks/chain_scaling.py [--sizes 5 10 20 30 50] [--limit 120]
"""

from __future__ import annotations

import argparse
import importlib
import itertools
import multiprocessing as mp
import time

import numpy as np

CLOCK = time.process_time


def per_call(f, min_time: float = 0.2, repeats: int = 5) -> float:
    """Best CPU seconds per call of ``f()`` over ``repeats`` batches of at least ``min_time`` each."""
    f()
    k, t0 = 0, CLOCK()
    while CLOCK() - t0 < min_time / 4:
        f()
        k += 1
    k = max(k, 1)
    best = float("inf")
    for _ in range(repeats):
        t0 = CLOCK()
        for _ in range(k * 4):
            f()
        best = min(best, (CLOCK() - t0) / (k * 4))
    return best


def chain(n):
    return importlib.import_module("rigidkin.examples.chain").build(n)


def state(n):
    rng = np.random.default_rng(n)
    return rng.uniform(-1.5, 1.5, n), rng.uniform(-1.0, 1.0, n)


def states(n, count=16):
    """Distinct states to cycle through (a RHS that remembers its last state must not answer from memory)."""
    rng = np.random.default_rng(n + 1)
    return [(rng.uniform(-1.5, 1.5, n), rng.uniform(-1.0, 1.0, n)) for _ in range(count)]


def pinocchio_chain(n, m=1.0, l=1.0, g=9.81):
    """The same chain in Pinocchio: revolute-z joints, each rod's centre l/2 below its joint."""
    import pinocchio as pin

    model = pin.Model()
    parent = 0
    for i in range(n):
        place = pin.SE3(np.eye(3), np.array([0.0, 0.0 if i == 0 else -l, 0.0]))
        parent = model.addJoint(parent, pin.JointModelRZ(), place, f"j{i}")
        inertia = pin.Inertia(m, np.array([0.0, -l / 2, 0.0]), np.diag([m * l * l / 12, 0.0, m * l * l / 12]))
        model.appendBodyToJoint(parent, inertia, pin.SE3.Identity())
    model.gravity.linear = np.array([0.0, -g, 0.0])
    return model, model.createData()


def relative(theta):
    return np.concatenate([theta[:1], np.diff(theta)])


def measure_articulated(n, use_c=True):
    from rigidkin.numeric.large.articulated import ArticulatedModel
    from rigidkin.numeric.state import parameter_vector

    s = chain(n)
    t0 = CLOCK()
    am = ArticulatedModel(s, use_c=use_c)
    p = parameter_vector(s, am.layout)
    q, u = state(n)
    y = np.concatenate([q, u, [0.0]])
    am.rates(0.0, y, p)
    build = CLOCK() - t0
    ys = itertools.cycle([np.concatenate([a, b, [0.0]]) for a, b in states(n)])
    return build, per_call(lambda: am.rates(0.0, next(ys), p)), am.rates(0.0, y, p)[n:2 * n]


def measure_pinocchio(n):
    import pinocchio as pin

    model, data = pinocchio_chain(n)
    q, u = state(n)
    qr, ur, tau = relative(q), relative(u), np.zeros(n)
    xs = itertools.cycle([(relative(a), relative(b)) for a, b in states(n)])

    def call():
        a, b = next(xs)
        return pin.aba(model, data, a, b, tau)
    return per_call(call), np.array(pin.aba(model, data, qr, ur, tau))


def _child(kind, n, out):
    """Build the symbolic or projected RHS of the chain in a child process; report build time, time per call."""
    try:
        from rigidkin.numeric.state import parameter_vector

        s = chain(n)
        q, u = state(n)
        t0 = CLOCK()
        if kind == "symbolic":
            from rigidkin.numeric.simulate import hybrid_of

            hyb = hybrid_of(s)
            model = hyb.model({}, 0)
            p = parameter_vector(s, hyb.layout)
            y = np.concatenate([q, u, [0.0]])
            ys = itertools.cycle([np.concatenate([a, b, [0.0]]) for a, b in states(n)])
            f = lambda: model.rates(0.0, next(ys), p)                              # noqa: E731
            acc = lambda: model.rates(0.0, y, p)[n:2 * n]                          # noqa: E731
        else:
            from rigidkin.numeric.large.projected import ProjectedModel

            rhs = ProjectedModel(s).rhs()
            y = np.concatenate([q, u])
            ys = itertools.cycle([np.concatenate([a, b]) for a, b in states(n)])
            f = lambda: rhs(0.0, next(ys))                                          # noqa: E731
            acc = lambda: rhs(0.0, y)[n:]                                           # noqa: E731
        f()
        build = CLOCK() - t0
        out.put((build, per_call(f), list(acc())))
    except Exception as exc:                                                       # reported in the table
        out.put(repr(exc))


def measure_child(kind, n, limit):
    ctx = mp.get_context("spawn")          # a fresh interpreter: nothing inherited from the parent's threads
    out = ctx.Queue()
    proc = ctx.Process(target=_child, args=(kind, n, out))
    proc.start()
    proc.join(limit)
    if proc.is_alive():
        proc.terminate()
        proc.join()
        return None
    try:
        res = out.get(timeout=5)
    except Exception:                      # the child died without a word
        return "no result"
    return res


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[5, 10, 20, 30, 50])
    ap.add_argument("--limit", type=float, default=120.0, help="seconds allowed to build a symbolic RHS")
    args = ap.parse_args(argv)
    rows = []
    for n in args.sizes:
        build, t_aba, acc = measure_articulated(n)
        _, t_np, acc_np = measure_articulated(n, use_c=False)
        t_pin, acc_pin = measure_pinocchio(n)
        err = max(float(np.max(np.abs(relative(a) - acc_pin)) / max(1.0, np.max(np.abs(acc_pin))))
                  for a in (acc, acc_np))
        row = {"n": n, "build": build, "aba": t_aba, "numpy": t_np, "pin": t_pin, "err": err}
        for kind in ("symbolic", "projected"):
            res = measure_child(kind, n, args.limit)
            if isinstance(res, str):
                row[kind] = res
                print(f"  {kind} route at n = {n}: {res}", flush=True)
            elif res is not None:
                e2 = float(np.max(np.abs(relative(np.array(res[2])) - acc_pin)) / max(1.0, np.max(np.abs(acc_pin))))
                row[kind] = (res[0], res[1], e2)
        rows.append(row)
        print(f"n = {n}: done", flush=True)
    us = 1e6
    print()
    print(f"{'n':>3} | {'rigidkin O(n) µs':>16} | {'(numpy) µs':>10} | {'Pinocchio µs':>12} | {'ratio':>6} | "
          f"{'agree':>8} | "
          f"{'symbolic µs (build s)':>22} | {'projected µs (build s)':>23}")
    for r in rows:
        cells = []
        for kind in ("symbolic", "projected"):
            v = r.get(kind)
            cells.append("error" if isinstance(v, str) else
                         f"{v[1] * us:10.1f} ({v[0]:7.1f})" if v else f"> {args.limit:.0f} s build")
        print(f"{r['n']:>3} | {r['aba'] * us:16.1f} | {r['numpy'] * us:10.0f} | {r['pin'] * us:12.2f} | "
              f"{r['aba'] / r['pin']:6.1f} | "
              f"{r['err']:8.1e} | {cells[0]:>22} | {cells[1]:>23}")
    a, b = rows[0], rows[-1]
    print()
    print(f"growth of the time per RHS from n = {a['n']} to n = {b['n']} (×{b['n'] / a['n']:.0f} bodies):")
    print(f"  rigidkin O(n) RHS  ×{b['aba'] / a['aba']:.1f} (C step); ×{b['numpy'] / a['numpy']:.1f} (numpy step)")
    print(f"  Pinocchio ABA      ×{b['pin'] / a['pin']:.1f}")
    for kind in ("symbolic", "projected"):
        done = [r for r in rows if isinstance(r.get(kind), tuple)]
        if len(done) >= 2:
            print(f"  {kind:<18} ×{done[-1][kind][1] / done[0][kind][1]:.1f} (n = {done[0]['n']} to "
                  f"{done[-1]['n']}, where it finished)")
    print(f"build of the O(n) model: {a['build']:.2f} s at n = {a['n']}, {b['build']:.2f} s at n = {b['n']}")


if __name__ == "__main__":
    main()
