"""The GPU backend without a GPU: the CUDA branch of the device source (``__CUDACC__`` defined, so its own NAN,
INFINITY, isnan, isfinite, signbit, memcpy and memset, and its thread index from block and thread numbers) compiled
by the system C++ compiler, each CUDA thread of a launch run in turn on the host, behind a stand-in for the few
CuPy calls :mod:`rigidkin.numeric.sweeps.gpu` makes.  The stand-in checks every launch argument against the
kernel's C signature (a scalar of the wrong width, an array of the wrong type is an error, as it would be garbage
on the GPU), so ``GpuModel.integrate_batch``, the sweep with ``backend="gpu"`` and ``rigidkin sweep --backend gpu``
run as they would on a card.  Each is compared with the C backend on the same runs, and the ladder's release angle
with its closed form acos(⅔ cos θ₀).  (``tests/test_sweep_stream.py`` runs the host branch and parses the CUDA
branch; this file runs the CUDA branch and the Python side of the launch.)"""

from __future__ import annotations

import csv
import re
import shutil
import subprocess
import sys
import types

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.cli import main
from rigidkin.numeric.compiled import codegen
from rigidkin.numeric.sweeps import gpu
from rigidkin.numeric.sweeps.sweep import sweep

pytestmark = [pytest.mark.skipif(not codegen.c_available(), reason="no C compiler"),
              pytest.mark.skipif(shutil.which("g++") is None, reason="no C++ compiler")]

#: What NVRTC provides and a host C++ compiler does not: qualifiers, the launch's indices, the bit casts.
_CUDA_ON_HOST = r"""
#include <math.h>
#include <string.h>
#define __device__
#define __global__
struct rk_dim3 { unsigned x, y, z; };
static struct rk_dim3 blockIdx, blockDim, threadIdx;
static double __longlong_as_double(long long v) { double d; memcpy(&d, &v, 8); return d; }
static long long __double_as_longlong(double d) { long long v; memcpy(&v, &d, 8); return v; }
"""

_C_TO_NUMPY = {"long": np.int64, "int": np.int32, "double": np.float64}


def kernel_signature(source: str) -> list[tuple[str, bool]]:
    """(C base type, is a pointer) of each parameter of ``rk_sweep_dev``, read from the source."""
    head = re.search(r'extern "C" __global__.*?rk_sweep_dev\((.*?)\)\s*\{', source, re.S)
    assert head, "the CUDA branch has no kernel rk_sweep_dev"
    out = []
    for param in head.group(1).split(","):
        words = param.replace("*", " * ").split()
        out.append((next(w for w in words if w in _C_TO_NUMPY), "*" in words))
    return out


class _DeviceArray(np.ndarray):
    """A "device" array: a numpy array with CuPy's ``get()``."""

    def get(self):
        return np.array(self)


class _Kernel:
    """A compiled kernel: a launch runs every (block, thread) of the grid in turn on the host."""

    def __init__(self, lib, ffi, signature):
        self.lib, self.ffi, self.signature, self.launches = lib, ffi, signature, []

    def __call__(self, grid, block, args):
        assert len(args) == len(self.signature), "wrong number of kernel arguments"
        c_args = []
        for i, (arg, (ctype, pointer)) in enumerate(zip(args, self.signature)):
            want = _C_TO_NUMPY[ctype]
            if pointer:
                assert isinstance(arg, _DeviceArray), f"argument {i}: a host array where the kernel reads {ctype} *"
                assert arg.dtype == want and arg.flags.c_contiguous, f"argument {i}: {arg.dtype}, not {ctype} *"
                c_args.append(self.ffi.from_buffer(f"{ctype}[]", arg))
            else:
                assert type(arg) is want, f"argument {i}: {type(arg).__name__}, not {ctype}"
                c_args.append(arg.item())
        self.launches.append((grid[0], block[0], int(args[0])))
        self.lib.rk_launch(grid[0], block[0], *c_args)


def _compile(source: str, folder) -> _Kernel:
    """The CUDA branch of ``source`` and a host launcher, built by g++ and opened with cffi."""
    import cffi

    sig = kernel_signature(source)
    params = ", ".join(f"{t} {'*' if p else ''}a{i}" for i, (t, p) in enumerate(sig))
    names = ", ".join(f"a{i}" for i in range(len(sig)))
    launcher = f"""
extern "C" void rk_launch(unsigned grid, unsigned block, {params}) {{
    blockDim.x = block;
    for (unsigned b = 0; b < grid; b++)
        for (unsigned th = 0; th < block; th++) {{ blockIdx.x = b; threadIdx.x = th; rk_sweep_dev({names}); }}
}}
"""
    n = len(list(folder.glob("k*.cpp")))
    cpp, so = folder / f"k{n}.cpp", folder / f"k{n}.so"
    cpp.write_text("#define __CUDACC__ 1\n" + _CUDA_ON_HOST + source + launcher)
    r = subprocess.run(["g++", "-std=c++14", "-O1", "-shared", "-fPIC", "-w", "-o", str(so), str(cpp)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[:3000]
    ffi = cffi.FFI()
    ffi.cdef(f"void rk_launch(unsigned grid, unsigned block, {params});")
    return _Kernel(ffi.dlopen(str(so)), ffi, sig)


def fake_cupy(folder) -> types.ModuleType:
    """The CuPy calls the GPU backend makes, on the host: RawModule (compiled as above), asarray, empty, and one
    "device" for ``gpu_present``."""
    cp = types.ModuleType("cupy")
    cp.kernels = []

    class RawModule:
        def __init__(self, code, options=(), name_expressions=None):
            assert "--std=c++14" in options
            self.kernel = _compile(code, folder)
            cp.kernels.append(self.kernel)

        def get_function(self, name):
            assert name == "rk_sweep_dev"
            return self.kernel

    cp.RawModule = RawModule
    cp.asarray = lambda a, dtype=None: np.ascontiguousarray(a, dtype=dtype).view(_DeviceArray)
    cp.empty = lambda shape, dtype=float: np.full(shape, -7, dtype=dtype).view(_DeviceArray)   # not zeroed
    runtime = types.SimpleNamespace(getDeviceCount=lambda: 1,
                                    getDeviceProperties=lambda i: {"name": b"host stand-in"})
    cp.cuda = types.SimpleNamespace(runtime=runtime, Device=lambda *a: types.SimpleNamespace(synchronize=lambda: None))
    return cp


@pytest.fixture
def cupy_on_host(tmp_path, monkeypatch):
    cp = fake_cupy(tmp_path)
    monkeypatch.setitem(sys.modules, "cupy", cp)
    monkeypatch.setitem(gpu._PRESENT, "gpu", True)
    monkeypatch.setenv("RIGIDKIN_CACHE", str(tmp_path / "rk-cache"))
    return cp


@pytest.fixture(scope="module")
def ladder():
    return rk.examples.build("ladder")


def test_signature_reader_reads_the_kernel():
    src = 'extern "C" __global__ void rk_sweep_dev(long n, const double *y0, int ne, long *nfev) {'
    assert kernel_signature(src) == [("long", False), ("double", True), ("int", False), ("long", True)]


def test_gpu_sweep_launches_the_cuda_branch_and_equals_the_c_backend(ladder, cupy_on_host, monkeypatch):
    """Runs over several device batches (a short last one), blocks not filled by the runs (threads past the last
    run return at once), two swept axes (parameters read per run) and a recorded event beside the stop."""
    monkeypatch.setattr(gpu, "DEVICE_BATCH", 16)
    monkeypatch.setattr(gpu, "BLOCK", 5)
    vary = {"theta": (0.1, 1.3, 9), "l": [0.5, 2.0, 3.5, 5.0]}
    opts = dict(stop_at="N_A", record=["theta=0.6"])
    g = sweep(ladder, vary, backend="gpu", **opts)
    c = sweep(ladder, vary, backend="c", **opts)
    assert g.backend == "gpu" and c.backend == "c"
    (kern,) = cupy_on_host.kernels
    assert [n for _, _, n in kern.launches] == [16, 16, 4]               # 36 runs, 16 at a time
    assert all(grid * block >= n and (grid - 1) * block < n for grid, block, n in kern.launches)
    gr, cr = g.result, c.result
    assert gr.event_names == cr.event_names == ("N_A", "theta=0.6")
    np.testing.assert_array_equal(gr.status, cr.status)
    np.testing.assert_array_equal(gr.nfev, cr.nfev)
    np.testing.assert_allclose(gr.event_t, cr.event_t, rtol=1e-13, atol=0)     # NaN where a run missed theta=0.6
    np.testing.assert_allclose(gr.event_y, cr.event_y, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(gr.y_end, cr.y_end, rtol=1e-12, atol=1e-14)
    th0, th = g.inputs["theta"], g.event_state("N_A", "theta")
    assert np.max(np.abs(th - np.arccos(2 / 3 * np.cos(th0)))) < 1e-9
    reached = np.isfinite(gr.event_t[:, 1])          # released beyond 0.6 rad: the recorded angle never happens
    assert reached.any() and not reached.all()
    np.testing.assert_allclose(gr.event_y[reached, 1, 0], 0.6, atol=1e-12)


@pytest.mark.slow
def test_gpu_sweep_without_events_runs_to_the_end_time(cupy_on_host):
    """No event (a pendulum chain to t = 0.5 s): the kernel's one-column placeholder buffers, status 0, and the
    final states of the C backend."""
    from rigidkin.examples import chain as chains

    chain = chains.build(2)
    vary = {"theta1": (0.1, 1.0, 6)}
    g = sweep(chain, vary, t_end=0.5, stop_at=[], backend="gpu")
    c = sweep(chain, vary, t_end=0.5, stop_at=[], backend="c")
    assert g.result.event_t.shape == c.result.event_t.shape
    np.testing.assert_array_equal(g.result.status, c.result.status)
    np.testing.assert_allclose(g.result.t_end, 0.5, rtol=0, atol=0)
    np.testing.assert_allclose(g.result.y_end, c.result.y_end, rtol=1e-12, atol=1e-14)


def test_command_backend_gpu_writes_the_c_backends_table(cupy_on_host, tmp_path, capsys, monkeypatch):
    """``rigidkin sweep --backend gpu``, first derived then answered from the numeric record, against the table
    of ``--backend c``: the same rows, numbers equal to 1e-12."""
    from rigidkin.commands import sweep as command

    monkeypatch.delenv("RIGIDKIN_NO_CACHE", raising=False)          # the record kept and read
    routes = []
    from_record = command._from_record
    monkeypatch.setattr(command, "_from_record", lambda *a: routes.append(from_record(*a)) or routes[-1])
    args = ["sweep", "ladder", "--param", "theta=0.1:1.2:7", "l=1,3", "--stop-at", "N_A"]
    for name, backend in (("gpu1", "gpu"), ("gpu2", "gpu"), ("c", "c")):
        assert main([*args, "--backend", backend, "-o", str(tmp_path / f"{name}.csv")]) == 0
    assert len(cupy_on_host.kernels) == 2               # the derived sweep, then the record's
    assert routes[0] is None and routes[1].model.backend == "gpu"
    capsys.readouterr()

    def rows(name):
        with open(tmp_path / f"{name}.csv", newline="") as f:
            return list(csv.reader(f))

    c = rows("c")
    assert len(c) == 15 and c[0][-1] == "status"
    for name in ("gpu1", "gpu2"):
        g = rows(name)
        assert g[0] == c[0] and [r[-1] for r in g] == [r[-1] for r in c]
        np.testing.assert_allclose(np.array([r[:-1] for r in g[1:]], dtype=float),
                                   np.array([r[:-1] for r in c[1:]], dtype=float), rtol=1e-12, atol=1e-14)
    head = c[0]
    th0 = np.array([float(r[head.index("theta")]) for r in c[1:]])
    th = np.array([float(r[head.index("N_A: theta")]) for r in c[1:]])
    assert np.max(np.abs(th - np.arccos(2 / 3 * np.cos(th0)))) < 1e-9


def test_launch_with_a_wrong_argument_type_is_caught(ladder, cupy_on_host):
    """The stand-in is strict: a 32-bit run count where the kernel reads ``long`` is refused, so the tests above
    would catch such a launch."""
    from rigidkin.numeric.sweeps.sweep import Prepared

    prep = Prepared(ladder, {"theta": (0.2, 0.4, 3)}, stop_at="N_A", backend="gpu")
    _, _, model = prep._model(0)
    f = model.function()
    with pytest.raises(AssertionError, match="int32, not long"):
        f((1,), (4,), (np.int32(3),) + (None,) * (len(f.signature) - 1))
