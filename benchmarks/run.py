"""Run every benchmark and print its tables: ``python benchmarks/run.py [--quick]``.

Each benchmark also runs alone (``python benchmarks/<name>.py --help``).  ``--quick`` uses fewer
repeats and smaller sizes (a few minutes instead of about half an hour on 2 cores).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))


def main(argv=None) -> None:
    import derivation
    import mujoco_ladder
    import profile_derivation
    import rhs
    import sweep

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--skip", nargs="*", default=[],
                    help="benchmarks to leave out: derivation rhs sweep mujoco profile")
    a = ap.parse_args(argv)
    plan = [
        ("rhs", lambda: rhs.main()),
        ("sweep", lambda: sweep.main(["--dask"] + (["--baseline-runs", "30", "--chain-runs", "200",
                                                    "--diffrax-runs", "10000"] if a.quick else []))),
        ("mujoco", lambda: mujoco_ladder.main([])),
        ("derivation", lambda: derivation.main(["--repeats", "1", "--max-n", "5"] if a.quick else [])),
        ("profile", lambda: profile_derivation.main(["--chain", "3"] if a.quick else [])),
    ]
    for name, fn in plan:
        if name in a.skip:
            continue
        t0 = time.perf_counter()
        fn()
        print(f"({name}: {time.perf_counter() - t0:.0f} s)\n", flush=True)


if __name__ == "__main__":
    main()
