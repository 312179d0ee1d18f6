"""The GPU backend of sweeps: the generated C of the model and the batch integrator, one run per thread,
compiled for an NVIDIA GPU by NVRTC through CuPy (``pip install cupy-cuda12x``; optional).

Why CuPy's NVRTC modules rather than JAX/diffrax: the C backend's own text runs on the GPU
(:func:`rigidkin.numeric.compiled.devsource.device_source` changes qualifiers only), so the GPU integrates
with the same generated expressions, the same DOP853 steps and step-size control, and the same terminal
events located by the same Brent iteration to 4 ε in time — its table matches the C backend's to the
rounding of the GPU's libm (a few ulp per step), not merely to the tolerance.  JAX would need a second code
generator and a second integrator (diffrax's Tsit5), whose tables differ from the C backend's at rtol.
CuPy is a thin, well-kept layer (RawModule, device arrays); it is not needed to install or test rigidkin: the
device source is compiled as plain C and run on the CPU in the tests, where the shim maps it to the host, and its
CUDA branch is compiled by the host's C++ compiler and launched thread by thread behind a stand-in for the CuPy
calls made here, which checks every launch argument against the kernel's signature (``tests/test_gpu_launch_cpu.py``).

``backend="auto"`` picks the GPU only when CuPy imports and sees a device; ``backend="gpu"`` without one is an
InputError that says what is missing.
"""

from __future__ import annotations

import importlib.util
from types import SimpleNamespace

import numpy as np

from ...base.errors import InputError
from ..compiled.batch import BatchResult
from ..compiled.devsource import device_source

#: Runs sent to the GPU at a time (device memory: about 1 kB a run for the ladder's outputs).
DEVICE_BATCH = 1 << 21
#: Threads per block.
BLOCK = 64

_PRESENT: dict[str, bool] = {}


def gpu_present() -> bool:
    """Whether CuPy is installed and sees at least one CUDA device (asked once per process)."""
    if "gpu" not in _PRESENT:
        ok = False
        if importlib.util.find_spec("cupy") is not None:
            try:
                import cupy

                ok = cupy.cuda.runtime.getDeviceCount() > 0
            except Exception:        # noqa: BLE001  (no driver, no device: CuPy raises its own errors)
                ok = False
        _PRESENT["gpu"] = ok
    return _PRESENT["gpu"]


def resolve_backend(backend: str) -> str:
    """``"gpu"`` for ``"auto"`` when a GPU is present, the backend as given otherwise; ``"gpu"`` without a GPU is
    refused (InputError) before anything is derived."""
    if backend == "gpu":
        if not gpu_present():
            raise InputError("the GPU backend needs CuPy and a CUDA device, and this machine has "
                             + ("no CUDA device CuPy can use." if importlib.util.find_spec("cupy") else
                                "no CuPy installed."), where="--backend",
                             hint="Install CuPy for your CUDA (pip install cupy-cuda12x) on a machine with an NVIDIA "
                                  "GPU, or use --backend c.")
        return "gpu"
    if backend == "auto" and gpu_present():
        return "gpu"
    return backend


class GpuModel:
    """A sweep's model on the GPU: the device form of its C file, compiled by NVRTC on first use."""

    backend = "gpu"

    def __init__(self, c_text: str, n_p: int):
        self.source = device_source(c_text)
        self.kernel = SimpleNamespace(np_=n_p)     # what batch.integrate reads of a model: the parameter count
        self.lib = None
        self._function = None

    def function(self):
        """The compiled kernel ``rk_sweep_dev`` (NVRTC, through CuPy's RawModule; cached by CuPy on disk)."""
        if self._function is None:
            import cupy

            module = cupy.RawModule(code=self.source, options=("--std=c++14",), name_expressions=None)
            self._function = module.get_function("rk_sweep_dev")
        return self._function

    def integrate_batch(self, y0, P, t0, t1, events, rtol, atol, max_step, max_steps) -> BatchResult:
        """Every run, :data:`DEVICE_BATCH` at a time, one run per GPU thread."""
        import cupy

        f = self.function()
        n, ny, ne = y0.shape[0], y0.shape[1], len(events)
        ev_out = cupy.asarray(np.array([e.output for e in events] or [0], dtype=np.int32))
        ev_dir = cupy.asarray(np.array([e.direction for e in events] or [0], dtype=np.int32))
        ev_term = cupy.asarray(np.array([int(e.terminal) for e in events] or [0], dtype=np.int32))
        out = BatchResult(tuple(e.name for e in events), np.empty((n, ne)), np.empty((n, ne, ny)), np.empty(n),
                          np.empty((n, ny)), np.empty(n, dtype=int), np.empty(n, dtype=int))
        m = max(ne, 1)
        for a in range(0, n, DEVICE_BATCH):
            b = min(n, a + DEVICE_BATCH)
            k = b - a
            d_y0, d_p = cupy.asarray(y0[a:b]), cupy.asarray(P[a:b])
            ev_t, ev_y = cupy.empty((k, m)), cupy.empty((k, m, ny))
            t_end, y_end = cupy.empty(k), cupy.empty((k, ny))
            status, nfev = cupy.empty(k, dtype=np.int32), cupy.empty(k, dtype=np.int64)
            f(((k + BLOCK - 1) // BLOCK,), (BLOCK,),
              (np.int64(k), d_y0, d_p, np.float64(t0), np.float64(t1), np.float64(rtol), np.float64(atol),
               np.float64(max_step), np.int64(max_steps), np.int32(ne), ev_out, ev_dir, ev_term, ev_t, ev_y, t_end,
               y_end, status, nfev))
            out.event_t[a:b] = ev_t.get()[:, :ne]
            out.event_y[a:b] = ev_y.get()[:, :ne]
            out.t_end[a:b], out.y_end[a:b] = t_end.get(), y_end.get()
            out.status[a:b], out.nfev[a:b] = status.get(), nfev.get()
        return out
