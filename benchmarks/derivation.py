"""Derivation speed: every bundled example, and a chain of n uniform rods against KanesMethod.

    python benchmarks/derivation.py [--repeats 3] [--max-n 10] [--solve-limit 150]
    python benchmarks/derivation.py --ratios [--repeats 3]      # the issue-16 table (a few minutes)
    python benchmarks/derivation.py --ratios --chains 6 10 --chains-only --repeats 5     # the chains alone

``--ratios``: rigidkin / KanesMethod CPU time, same process, cold caches, for the chain at n = 6, 10
and 20, every 3D example and the Whipple bicycle.  rigidkin: ``System.solve()`` and M, f as derived
(``regime.raw_mass_matrix``, ``raw_forcing``; reactions, q̈ and the readable forms are made when first
read).  KanesMethod: the chain built with sympy.physics.mechanics alone (``models.kane_chain``); an
example's model handed over from rigidkin's mode setup (``kane_on_model``: the setup is timed with it,
as the model must come from somewhere — the column "Kane eqs" times ``kanes_equations`` alone); the
bicycle: sympy's own test_kane3 model (``bicycle.sympy_bicycle``) against ``examples.bicycle.projected()``.

Examples: ``rigidkin.examples.build(name).solve()`` on a fresh system each run (the solution is
cached per system), against sympy.physics.mechanics KanesMethod on the same model (rigidkin's
mode setup handed to KanesMethod by ``laws.mechanics_model``, then ``kanes_equations``).
Chain: KanesMethod on the chain built here with sympy.physics.mechanics alone, against rigidkin's
full solve (accelerations and reactions solved symbolically) and against rigidkin's balance
equations alone (what the implicit generated code needs).  Operation counts are after CSE, of the
mass matrix and forcing (KanesMethod) and of rigidkin's reaction-free mass matrix and forcing.
"""

from __future__ import annotations

import argparse

from common import TimeLimit, machine, median_time, table, time_limit
from models import kane_chain, ops_after_cse


def kane_on_model(name: str):
    """KanesMethod on a bundled example's model (rigidkin's setup, sympy's KanesMethod)."""
    import sympy as sp
    from sympy.physics.mechanics import KanesMethod
    from sympy.physics.vector import dynamicsymbols

    from rigidkin import examples
    from rigidkin.derive.laws.mechanics_model import build
    from rigidkin.derive.mode import setup_mode

    t = dynamicsymbols._t
    setup = setup_mode(examples.build(name))
    model = build(setup, "forces", "kane")
    qs = list(setup.system.coordinates)
    us = [dynamicsymbols(f"u_{q.func.__name__}") for q in qs]
    to_u = {q.diff(t): u for q, u in zip(qs, us)}
    ind = set(setup.reduction.independent)
    u_ind = [u for q, u in zip(qs, us) if q in ind]
    u_dep = [u for q, u in zip(qs, us) if q not in ind]
    vc = [sp.sympify(r.velocity).xreplace(to_u) for r in model.rows][:len(u_dep)]
    km = KanesMethod(model.frame, q_ind=qs, u_ind=u_ind, kd_eqs=[q.diff(t) - u for q, u in zip(qs, us)],
                     u_dependent=u_dep or None, velocity_constraints=vc or None)
    km.kanes_equations(model.bodies, model.loads)
    return km


#: The bundled examples that are three-dimensional (their ratio is part of the issue-16 table).
EXAMPLES_3D = ("gyroscope", "heavy-top", "rolling-disk", "sphere-on-sphere", "torque-free")


def rigidkin_solve(system):
    """System.solve() and the mass matrix and forcing as derived (what the benchmark times)."""
    sol = system.solve()
    for r in sol.regimes:       # (a rigidkin before lazy readable forms: its M and f, made in solve())
        _ = (r.raw_mass_matrix, r.raw_forcing) if hasattr(r, "raw_mass_matrix") else (r.mass_matrix, r.forcing)
    return sol


def kane_parts(name: str) -> tuple[float, float]:
    """(model from rigidkin's setup + KanesMethod, KanesMethod alone) CPU seconds for an example."""
    import time

    from sympy.physics.mechanics import KanesMethod

    t0 = time.process_time()
    captured = {}
    real = KanesMethod.kanes_equations

    def timed(self, *a, **k):
        t1 = time.process_time()
        out = real(self, *a, **k)
        captured["eqs"] = time.process_time() - t1
        return out

    KanesMethod.kanes_equations = timed
    try:
        kane_on_model(name)
    finally:
        KanesMethod.kanes_equations = real
    return time.process_time() - t0, captured["eqs"]


def ratio_table(repeats: int, chains=(6, 10, 20), chains_only: bool = False) -> str:
    import statistics
    import time

    from common import cold_caches

    from rigidkin import examples
    from rigidkin.examples import chain

    def paired(fa, fb, reps, parts=False):
        """rigidkin, then KanesMethod, ``reps`` times in turn (both under the same load): the median
        times and the median of the ratios of the pairs.  ``parts``: ``fb`` returns (Kane s, Kane eqs s)."""
        rows = []
        for _ in range(reps):
            cold_caches()
            t0 = time.process_time()
            fa()
            a = time.process_time() - t0
            cold_caches()
            t0 = time.process_time()
            out = fb()
            b, eq = out if parts else (time.process_time() - t0, None)
            rows.append((a, b, eq, a / b))
        med = [statistics.median(r[i] for r in rows) if rows[0][i] is not None else None for i in range(4)]
        return med

    rigidkin_solve(examples.build("ladder"))      # imports and lazy module loads, untimed
    kane_parts("ladder")
    rigidkin_solve(chain.build(2))
    kane_chain(2)
    rows = []
    for n in chains:
        reps = repeats if n <= 10 else 1
        t_rk, t_km, _, ratio = paired(lambda n=n: rigidkin_solve(chain.build(n)), lambda n=n: kane_chain(n), reps)
        rows.append([f"chain n = {n}", t_rk, t_km, None, ratio])
        print(f"  chain {n} done", flush=True)
    for name in () if chains_only else EXAMPLES_3D:
        t_rk, t_km, t_eq, ratio = paired(lambda name=name: rigidkin_solve(examples.build(name)),
                                         lambda name=name: kane_parts(name), repeats,
                                         parts=True)
        rows.append([name, t_rk, t_km, t_eq, ratio])
        print(f"  {name} done", flush=True)
    if not chains_only:
        import bicycle as bike

        from rigidkin.examples import bicycle

        t_rk, t_km, _, ratio = paired(bicycle.projected, bike.sympy_bicycle, repeats)
        rows.append(["Whipple bicycle", t_rk, t_km, None, ratio])
    return table("rigidkin / KanesMethod, derivation (CPU s, same process, cold caches)",
                 ["model", "rigidkin", "KanesMethod", "Kane eqs", "ratio"], rows,
                 "rigidkin: System.solve() with M and f as derived (reactions, q̈ and readable forms on demand); "
                 "bicycle: examples.bicycle.projected().\nKanesMethod: chain built with sympy.physics.mechanics "
                 "alone; examples: model from rigidkin's mode setup + KanesMethod (setup included; 'Kane eqs' = "
                 "kanes_equations alone); bicycle: sympy's test_kane3 model.\nratio = rigidkin / KanesMethod "
                 f"(the two in turn, {repeats} pairs, n = 20 one pair; times and ratio the medians over the pairs).")


def examples_table(repeats: int, limit: float) -> str:
    from rigidkin import examples

    rows = []
    for name in examples.names():
        if name == "chain":
            continue
        try:
            t_rk, _ = median_time(lambda name=name: rigidkin_solve(examples.build(name)), repeats, limit,
                                   cold=True)
        except TimeLimit:
            rows.append([name, f"> {limit:.0f}", None, None, "no"])
            continue
        except Exception as exc:  # an example another engineer is still building
            rows.append([name, f"error: {type(exc).__name__}", None, None, "–"])
            continue
        try:
            t_km, _ = median_time(lambda name=name: kane_on_model(name), repeats, limit, cold=True)
            ratio = t_rk / t_km
        except Exception:
            t_km = ratio = None
        rows.append([name, t_rk, t_km, ratio, "yes" if t_rk <= 1.0 else "no"])
    return table(f"Derivation of every bundled example (CPU s, median of {repeats} runs, cold caches)",
                 ["example", "rigidkin solve", "KanesMethod", "ratio", "≤ 1 s"], rows,
                 "ratio = rigidkin / KanesMethod (< 1: rigidkin faster); KanesMethod gives M, f only "
                 "(no reactions, not solved), rigidkin gives solved accelerations, reactions, M and f.")


def chain_table(ns, repeats: int, solve_limit: float, eq_limit: float) -> str:
    from rigidkin.derive.laws import newton_euler
    from rigidkin.derive.mode import setup_mode
    from rigidkin.examples import chain
    from rigidkin.numeric.compiled.codegen import kernel, operation_count

    rows = []
    solve_ok = eq_ok = True
    for n in ns:
        reps = repeats if n <= 5 else 1
        t_km, km = median_time(lambda n=n: kane_chain(n)[0], reps, cold=True)
        ops_km = ops_after_cse(list(km.mass_matrix) + list(km.forcing))
        row = [n, t_km, ops_km]
        if solve_ok:
            try:
                t_rk, sol = median_time(lambda n=n: rigidkin_solve(chain.build(n)), reps if n <= 2 else 1, solve_limit,
                                        cold=True)
                with time_limit(solve_limit):
                    ops_rk = ops_after_cse(list(sol.mass_matrix) + list(sol.forcing))
                    # the explicit accelerations (solved on demand) only while that stays small
                    ops_acc = ops_after_cse(list(sol.accelerations.values())) if n <= 3 else None
                row += [t_rk, t_rk / t_km, ops_rk, ops_acc]
            except TimeLimit:
                solve_ok = False
                row += [f"> {solve_limit:.0f}", None, None, None]
        else:
            row += [None] * 4
        if eq_ok:
            try:
                def equations(n=n):
                    s = chain.build(n)
                    return s, newton_euler.equations(setup_mode(s))
                t_eq, (s, _) = median_time(equations, reps, eq_limit, cold=True)
                with time_limit(eq_limit):
                    row += [t_eq, t_eq / t_km, operation_count(kernel(s, form="implicit"))]
            except TimeLimit:
                eq_ok = False
                row += [f"> {eq_limit:.0f}", None, None]
        else:
            row += [None] * 3
        rows.append(row)
        print(f"  chain n={n} done", flush=True)
    return table("Chain of n rods: derivation time (CPU s, cold caches) and operations after CSE",
                 ["n", "Kane t", "Kane ops", "rk solve t", "ratio", "rk M,f ops", "rk q̈ ops", "rk eqs t", "ratio",
                  "rk A,b ops"], rows,
                 "Kane: sympy.physics.mechanics KanesMethod built here (mass matrix and forcing, unsolved).\n"
                 "rk solve: System.solve() (reaction-free M and f; q̈ and reactions solved on demand: q̈ ops "
                 "for n ≤ 3 only).\n"
                 "rk eqs: the Newton–Euler balance equations only (what the implicit generated code uses; "
                 "A,b ops include the 2n pin reactions).\nratio = rigidkin / KanesMethod; – = not run "
                 "(a smaller n already passed the time limit).")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--max-n", type=int, default=10)
    ap.add_argument("--solve-limit", type=float, default=150.0, help="seconds for one rigidkin chain solve")
    ap.add_argument("--eq-limit", type=float, default=120.0)
    ap.add_argument("--limit", type=float, default=120.0, help="seconds for one example")
    ap.add_argument("--skip-examples", action="store_true")
    ap.add_argument("--ratios", action="store_true", help="only the issue-16 ratio table")
    ap.add_argument("--chains", nargs="*", type=int, default=[6, 10, 20], help="chain lengths of the ratio table")
    ap.add_argument("--chains-only", action="store_true", help="the ratio table for the chains alone")
    a = ap.parse_args(argv)
    print(f"# Derivation speed ({machine()})", flush=True)
    if a.ratios:
        print(ratio_table(a.repeats, a.chains, a.chains_only), flush=True)
        return
    if not a.skip_examples:
        print(examples_table(a.repeats, a.limit), flush=True)
    ns = [n for n in (1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20) if n <= a.max_n]
    print(chain_table(ns, a.repeats, a.solve_limit, a.eq_limit), flush=True)


if __name__ == "__main__":
    main()
