"""The Whipple bicycle's derivation against sympy's own Kane bicycle, interleaved in one process.

Five pairs (rigidkin's ``examples.bicycle.projected()``, then sympy's test_kane3 model), caches cleared before
each; prints (rigidkin CPU s, sympy CPU s, ratio) per pair and the median ratio.  Interleaving puts both
under the same load.

    python benchmarks/bicycle_interleaved.py
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

import bicycle as bike  # noqa: E402
from common import cold_caches  # noqa: E402
from derivation import rigidkin_solve  # noqa: E402


def main() -> None:
    from rigidkin import examples
    from rigidkin.examples import bicycle

    rigidkin_solve(examples.build("ladder"))          # imports and lazy module loads, untimed
    rows = []
    for _ in range(5):
        cold_caches()
        t0 = time.process_time()
        bicycle.projected()
        a = time.process_time() - t0
        cold_caches()
        t0 = time.process_time()
        bike.sympy_bicycle()
        b = time.process_time() - t0
        rows.append((a, b, a / b))
    print("rigidkin s   sympy Kane s   ratio")
    for a, b, r in rows:
        print(f"{a:10.2f}   {b:12.2f}   {r:5.2f}")
    print(f"median ratio {statistics.median(r for _, _, r in rows):.2f}")


if __name__ == "__main__":
    main()
