"""Batch integration over a Dask cluster (dask.distributed): the runs in chunks, one task per chunk.

The generated C source travels to the workers once (scattered); each worker compiles it into its
own code cache (or finds it there) and integrates its chunks with the same code as a local sweep,
so every run's result is identical to the local one.  ``scheduler`` is a scheduler address
(``tcp://host:8786``), a ``distributed.Client``, or ``"local"`` for a LocalCluster of ``workers``
processes on this machine (loopback only).
"""

from __future__ import annotations

import types
from collections.abc import Callable, Sequence

import numpy as np

from ...base.errors import RigidkinError
from ..compiled import batch
from ..compiled.batch import INTEGRATOR_C, INTEGRATOR_CDEF
from ..compiled.codegen import _CDEF, _build, c_available, c_source
from ..compiled.kernel import Kernel


def _chunk_task(code: tuple[str, str], y0, P, t_span, events, rtol, atol, max_step, max_steps):
    """Run on a worker: build (or load) the library and integrate one chunk."""
    ffi, lib = _build(*code)
    model = types.SimpleNamespace(ffi=ffi, lib=lib)
    return batch._run_c(model, np.ascontiguousarray(y0), np.ascontiguousarray(P), t_span[0], t_span[1], events,
                        rtol, atol, max_step, max_steps)


def _client(scheduler, workers: int | None):
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise RigidkinError("distributing a sweep needs dask.distributed, which is not installed.",
                            hint="pip install 'rigidkin[dask]'") from None
    if isinstance(scheduler, Client):
        return scheduler, None
    if scheduler in ("local", None):
        cluster = LocalCluster(n_workers=workers or batch.default_workers(), threads_per_worker=1, processes=True,
                               host="127.0.0.1", dashboard_address=None)
        return Client(cluster), cluster
    try:
        return Client(str(scheduler), timeout="15s"), None
    except (OSError, TimeoutError) as exc:
        raise RigidkinError(f"no Dask scheduler answers at {scheduler} ({exc}).", where="sweep --scheduler",
                            hint="Start one with 'dask scheduler' and workers with 'dask worker ADDRESS', or use "
                                 "--workers N for a cluster on this machine.") from None


def integrate_dask(kernel: Kernel, y0: np.ndarray, params: np.ndarray, t_span, events: Sequence[batch.Event],
                   rtol: float = 1e-10, atol: float = 1e-12, max_step: float = np.inf, max_steps: int = 1_000_000,
                   scheduler="local", workers: int | None = None, chunk: int | None = None,
                   progress: Callable[[int, int], None] | None = None) -> batch.BatchResult:
    """``batch.integrate`` over a Dask cluster; ``progress(done_runs, total_runs)`` as chunks finish."""
    if not c_available():
        raise RigidkinError("a distributed sweep needs a C compiler and cffi here and on the workers.",
                            hint="Install gcc and cffi, or run the sweep locally (it falls back to numpy).")
    from distributed import as_completed


    code = (c_source(kernel) + INTEGRATOR_C, _CDEF + INTEGRATOR_CDEF)
    _build(*code)                      # compile errors surface here, not on a worker
    y0 = np.ascontiguousarray(np.atleast_2d(y0), dtype=float)
    n = y0.shape[0]
    P = np.ascontiguousarray(np.broadcast_to(np.asarray(params, dtype=float), (n, kernel.np_)))
    t_span = (float(t_span[0]), float(t_span[1]))
    client, cluster = _client(scheduler, workers)
    try:
        n_workers = max(1, len(client.scheduler_info().get("workers", {})) or (workers or 1))
        chunk = chunk or max(64, -(-n // (4 * n_workers)))
        pieces = [(a, min(n, a + chunk)) for a in range(0, n, chunk)]
        code_f = client.scatter(code, broadcast=True, hash=False)   # a key of its own: never shared, never lost
        futures = {client.submit(_chunk_task, code_f, y0[a:b], P[a:b], t_span, list(events), rtol, atol, max_step,
                                 max_steps, pure=False): (a, b) for a, b in pieces}
        parts: dict[int, batch.BatchResult] = {}
        done = 0
        try:
            for fut in as_completed(futures):
                a, b = futures[fut]
                parts[a] = fut.result()
                done += b - a
                if progress:
                    progress(done, n)
        except RigidkinError:
            raise
        except Exception as exc:     # a worker failed: say so in one paragraph
            raise RigidkinError(f"a Dask worker failed on the sweep: {type(exc).__name__}: {exc}",
                                where="sweep --scheduler",
                                hint="Check that every worker has a C compiler, cffi and rigidkin.") from None
        return batch.BatchResult.concatenate([parts[a] for a, _ in pieces])
    finally:
        if cluster is not None:
            client.close()
            cluster.close()
