"""Where derivation time goes: cProfile of ``solve()`` for a chain of rods and for chosen examples.

    python benchmarks/profile_derivation.py [--chain 4] [--examples torque-free gyroscope]
    python benchmarks/profile_derivation.py --check --chain 0 --examples rolling-disk --models four_bar

``--check`` profiles ``solve()`` and ``check()`` (the cross-check by every law) instead; ``--models`` adds
systems of benchmarks/models.py (four_bar, cart_pendulum ...).  Times are CPU seconds of the process.

For each model: the rigidkin functions with the largest cumulative time, and the functions (sympy
included) with the largest own time.  The findings and proposals are in benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import pstats
import time

from common import machine


def profile(label: str, build, top: int = 14, check: bool = False) -> str:
    system = build()
    pr = cProfile.Profile(time.process_time)
    pr.enable()
    sol = system.solve()
    for r in sol.regimes:           # M and f as derived; readable forms, q̈ and reactions are made when read
        _ = (r.raw_mass_matrix, r.raw_forcing) if hasattr(r, "raw_mass_matrix") else (r.mass_matrix, r.forcing)
    if check:
        str(sol.check())
    pr.disable()
    st = pstats.Stats(pr)
    total = st.total_tt
    out = io.StringIO()
    out.write(f"\n## {label}: {total:.2f} s under the profiler\n")
    rows = []
    for (fname, line, func), (_cc, nc, tt, ct, _callers) in st.stats.items():
        rows.append((ct, tt, nc, fname, line, func))
    mine = sorted((r for r in rows if "/rigidkin/" in r[3]), reverse=True)[:top]
    out.write("cumulative s  own s     calls  rigidkin function\n")
    for ct, tt, nc, fname, line, func in mine:
        out.write(f"{ct:12.3f} {tt:6.3f} {nc:9d}  {fname.split('/rigidkin/')[-1]}:{line} {func}\n")
    own = sorted(rows, key=lambda r: -r[1])[:top]
    out.write("own s   cumulative s     calls  function (any package)\n")
    for ct, tt, nc, fname, line, func in own:
        short = fname.split("site-packages/")[-1].split("/rigidkin/")[-1]
        out.write(f"{tt:6.3f} {ct:12.3f} {nc:9d}  {short}:{line} {func}\n")
    return out.getvalue()


def main(argv=None) -> None:
    from rigidkin import examples
    from rigidkin.examples import chain

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--chain", type=int, default=4)
    ap.add_argument("--examples", nargs="*", default=["torque-free", "boulder-push"])
    ap.add_argument("--models", nargs="*", default=[], help="systems of benchmarks/models.py")
    ap.add_argument("--check", action="store_true", help="profile solve() and check()")
    a = ap.parse_args(argv)
    import models

    print(f"# {'Check' if a.check else 'Derivation'} profile ({machine()})", flush=True)
    if a.chain:
        print(profile(f"chain of {a.chain} rods", lambda: chain.build(a.chain), check=a.check), flush=True)
    builds = [(n, lambda n=n: examples.build(n)) for n in a.examples]
    builds += [(n, getattr(models, n)) for n in a.models]
    for name, build in builds:
        try:
            print(profile(name, build, check=a.check), flush=True)
        except Exception as exc:
            print(f"\n## {name}: {type(exc).__name__}: {exc}")


if __name__ == "__main__":
    main()
