"""Sweeps of any size: streamed chunk by chunk (the same table as the whole sweep, row for row), the memory
estimate of the chunks in flight, the summary, the figure, and the GPU kernel source run on the CPU — each
against the closed form of the ladder's release, cos θ = ⅔ cos θ₀, or against the whole, unchunked sweep."""

from __future__ import annotations

import csv
import shutil
import subprocess

import numpy as np
import pytest

from rigidkin.base.errors import InputError
from rigidkin.cli import main
from rigidkin.numeric.compiled import codegen
from rigidkin.numeric.compiled.batch import INTEGRATOR_C, integrate
from rigidkin.numeric.compiled.cache import build
from rigidkin.numeric.compiled.csource import c_source
from rigidkin.numeric.compiled.devsource import HOST_CDEF, device_source
from rigidkin.numeric.sweeps import gpu
from rigidkin.numeric.sweeps.stream import write_sweep
from rigidkin.numeric.sweeps.summary import Summary
from rigidkin.numeric.sweeps.sweep import Prepared, check_size, sweep
from rigidkin.numeric.sweeps.sweep_plan import IN_FLIGHT, axes_of, grid_inputs

needs_c = pytest.mark.skipif(not codegen.c_available(), reason="no C compiler")
VARY = {"theta": (0.1, 1.3, 9), "l": [0.5, 1.0, 2.5, 4.0]}


pytestmark = pytest.mark.usefixtures("code_cache")      # conftest: compiled once per session


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_grid_chunks_are_the_whole_grid_in_order():
    axes = axes_of({"a": (0, 1, 3), "b": [5.0, 6.0], "c": (1, 2, 4)})
    mesh = [m.ravel() for m in np.meshgrid(*axes.values(), indexing="ij")]
    for lo, hi in ((0, 24), (5, 11), (23, 24), (7, 7)):
        part = grid_inputs(axes, lo, hi)
        for (name, values), whole in zip(part.items(), mesh):
            assert np.array_equal(values, whole[lo:hi]), name


@needs_c
@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_streamed_table_equals_the_whole_sweep_row_for_row(ladder, tmp_path, suffix):
    if suffix == ".parquet":
        pq = pytest.importorskip("pyarrow.parquet")
    whole, streamed = tmp_path / f"whole{suffix}", tmp_path / f"streamed{suffix}"
    res = sweep(ladder, VARY, stop_at="N_A")
    res.write(whole)
    prep = Prepared(ladder, VARY, stop_at="N_A", stream=5)
    seen = []
    summary, first = write_sweep(prep, streamed, chunk=5, progress=lambda d, t: seen.append((d, t)))
    assert seen[-1] == (36, 36) and len(seen) == 8                     # 36 runs in chunks of 5
    if suffix == ".csv":
        assert streamed.read_bytes() == whole.read_bytes()
        rows = _rows(streamed)
        th0 = np.array([float(r["theta"]) for r in rows])
        th = np.array([float(r["N_A: theta"]) for r in rows])
        assert np.max(np.abs(th - np.arccos(2 / 3 * np.cos(th0)))) < 1e-9     # the closed form of the release
        assert [int(r["run"]) for r in rows] == list(range(36))
    else:
        a, b = pq.read_table(whole), pq.read_table(streamed)
        assert a.column_names == b.column_names and a.num_rows == b.num_rows == 36
        for name in a.column_names:
            assert a.column(name).to_pylist() == b.column(name).to_pylist(), name
    assert summary.status_counts() == {"terminal event": 36}


@needs_c
def test_summary_counts_and_percentiles_against_the_table(ladder, tmp_path):
    """A short end time: the runs whose release (from a long sweep) comes later reach the end time instead."""
    vary = {"theta": (0.1, 1.3, 25)}
    long = sweep(ladder, vary, stop_at="N_A")
    t_release = long.event_time("N_A")
    t_end = float(np.mean(np.sort(t_release)[11:13]))           # between two releases
    prep = Prepared(ladder, vary, stop_at="N_A", t_end=t_end, stream=4)
    summary, _ = write_sweep(prep, tmp_path / "s.csv", chunk=4)
    early = int(np.sum(t_release < t_end))
    assert 0 < early < 25
    assert summary.status_counts() == {"reached the end time": 25 - early, "terminal event": early}
    (row,) = summary.event_stats()
    hit = t_release[t_release < t_end]
    assert row["hits"] == early
    assert row["min"] == pytest.approx(hit.min(), rel=1e-9) and row["max"] == pytest.approx(hit.max(), rel=1e-9)
    assert row["p50"] == pytest.approx(np.percentile(hit, 50), rel=1e-9)
    sampled = Summary(25, sample=10)                      # every 3rd run: percentiles of the sample, said so
    assert sampled.stride == 3


def test_memory_estimate_counts_the_chunks_in_flight(ladder):
    vary = {"l": (0.5, 2.5, 1_000_000)}
    with pytest.raises(InputError, match="limit is 1 GB"):
        check_size(ladder, vary)                                      # held whole: refused, as before
    assert check_size(ladder, vary, chunk=1 << 16) == 1_000_000       # streamed: three chunks at a time
    assert check_size(ladder, {"l": (0.5, 2.5, 10_000_000)}, chunk=1 << 16) == 10_000_000
    assert check_size(ladder, {"l": (0.5, 2.5, 10)}, chunk=1 << 16) == 10
    with pytest.raises(InputError, match=f"{IN_FLIGHT * 10_000_000:,} at a time"):
        check_size(ladder, {"l": (0.5, 2.5, 10_000_000), "g": (1, 10, 10)}, chunk=10_000_000)


@needs_c
def test_command_summary_and_map(tmp_path, capsys):
    out, fig = tmp_path / "t.csv", tmp_path / "map.png"
    assert main(["sweep", "ladder", "--param", "theta=0.2:1.0:5", "l=1:2:3", "--stop-at", "N_A", "-o", str(out),
                 "--plot", str(fig), "--plot-y", "N_A: theta"]) == 0
    said = capsys.readouterr().out
    assert "15 runs of ladder" in said and "event N_A: 15 of 15 runs; t from" in said and "p50" in said
    assert fig.stat().st_size > 1000
    assert main(["sweep", "ladder", "--param", "theta=0.2:1.0:5", "--stop-at", "N_A", "-o", str(out),
                 "--plot", str(fig), "--plot-x", "g"]) == 2
    assert "not a swept parameter" in capsys.readouterr().err


def test_gpu_backend_without_a_gpu_says_so(monkeypatch):
    monkeypatch.setitem(gpu._PRESENT, "gpu", False)
    with pytest.raises(InputError, match="GPU backend needs CuPy"):
        gpu.resolve_backend("gpu")
    assert gpu.resolve_backend("auto") == "auto" and gpu.resolve_backend("c") == "c"


def _ladder_kernel(ladder):
    prep = Prepared(ladder, {"theta": (0.1, 1.3, 7)}, stop_at="N_A", backend="c")
    k, events, model = prep._model(0)
    return prep, k, events, model


@needs_c
def test_gpu_kernel_source_run_on_the_cpu_equals_the_c_backend(ladder):
    """The very text NVRTC would compile, built as plain C and run run-by-run on the host."""
    prep, k, events, model = _ladder_kernel(ladder)
    src = device_source(c_source(k) + INTEGRATOR_C)
    ffi, lib = build(src, HOST_CDEF)
    _, P, Y = prep.plan(0, prep.runs)
    n, ny, ne = Y.shape[0], Y.shape[1], len(events)
    ev_t, ev_y = np.empty((n, ne)), np.empty((n, ne, ny))
    t_end, y_end, status, nfev = np.empty(n), np.empty((n, ny)), np.empty(n, dtype=np.intc), np.empty(n, np.int64)
    ints = [np.array([getattr(e, a) if a != "terminal" else int(e.terminal) for e in events], dtype=np.intc)
            for a in ("output", "direction", "terminal")]
    buf = ffi.from_buffer
    lib.rk_sweep_host(n, buf("double[]", Y), buf("double[]", P), 0.0, 10.0, 1e-10, 1e-12, np.inf, 1_000_000, ne,
                      *(buf("int[]", a) for a in ints), buf("double[]", ev_t), buf("double[]", ev_y),
                      buf("double[]", t_end), buf("double[]", y_end), buf("int[]", status), buf("long[]", nfev))
    ref = integrate(model, Y, P, (0.0, 10.0), events)
    assert np.array_equal(status, ref.status) and np.array_equal(nfev, ref.nfev)
    np.testing.assert_allclose(ev_t, ref.event_t, rtol=1e-13)
    np.testing.assert_allclose(ev_y, ref.event_y, rtol=1e-12, atol=1e-14)
    th = ev_y[:, 0, 0]
    assert np.max(np.abs(th - np.arccos(2 / 3 * np.cos(Y[:, 0])))) < 1e-9


_FAKE_CUDA = r"""
#include <math.h>
#include <string.h>
#define __device__
#define __global__
struct rk_dim3 { unsigned x, y, z; };
static struct rk_dim3 blockIdx, blockDim, threadIdx;
static double __longlong_as_double(long long v) { double d; memcpy(&d, &v, 8); return d; }
static long long __double_as_longlong(double d) { long long v; memcpy(&v, &d, 8); return v; }
"""


@needs_c
@pytest.mark.skipif(shutil.which("g++") is None, reason="no C++ compiler")
def test_gpu_kernel_source_parses_as_cuda_cpp(ladder, tmp_path):
    """NVRTC compiles C++: the device text, on its CUDA branch (device qualifiers mapped to nothing), and on its
    host branch, parses as C++ (no jump over an initialisation, no C-only construct)."""
    _, k, _, _ = _ladder_kernel(ladder)
    src = device_source(c_source(k) + INTEGRATOR_C)
    cuda = tmp_path / "k_cuda.cpp"
    cuda.write_text("#define __CUDACC__ 1\n" + _FAKE_CUDA + src)
    host = tmp_path / "k_host.cpp"
    host.write_text(src)
    for f in (cuda, host):
        r = subprocess.run(["g++", "-std=c++14", "-fsyntax-only", "-w", str(f)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr[:2000]
    assert 'extern "C" __global__' in src.split("#else")[0]


@needs_c
def test_record_sweep_planned_ahead_writes_the_whole_sweeps_table(ladder, tmp_path, monkeypatch):
    """A repeat answered from the numeric record plans each chunk in a thread while the one before is integrated:
    the table is still the whole sweep's, byte for byte, every chunk planned once and in order; a chunk the planner
    refuses stops the sweep at that chunk, after the earlier ones, and no table is left."""
    from rigidkin.numeric.sweeps import sweep_record

    whole = tmp_path / "whole.csv"
    res = sweep(ladder, VARY, stop_at="N_A", keep_record=True)
    res.write(whole)
    rec = res.record
    assert rec is not None
    src = sweep_record.run(rec, VARY, {}, {}, 10.0, 1e-10, 1e-12, None, None, stream=5)
    assert src.plan_ahead
    calls, threads = [], set()
    plan = src.plan

    def spy(first, stop):
        import threading

        calls.append((first, stop))
        threads.add(threading.current_thread().name)
        return plan(first, stop)

    monkeypatch.setattr(src, "plan", spy)
    streamed = tmp_path / "streamed.csv"
    write_sweep(src, streamed, chunk=5)
    assert streamed.read_bytes() == whole.read_bytes()
    assert calls == [(a, min(36, a + 5)) for a in range(0, 36, 5)]
    assert all(name.startswith("rk-plan") for name in threads)

    src = sweep_record.run(rec, VARY, {}, {}, 10.0, 1e-10, 1e-12, None, None, stream=5)
    plan, done = src.plan, []

    def failing(first, stop):                 # a chunk the planner refuses (as a value that is not finite is)
        if first == 10:
            raise InputError("the sweep's values are not all finite numbers.", where="sweep")
        return plan(first, stop)

    orig = src.integrate
    monkeypatch.setattr(src, "plan", failing)
    monkeypatch.setattr(src, "integrate", lambda first, *a: done.append(first) or orig(first, *a))
    with pytest.raises(InputError, match="not all finite"):
        write_sweep(src, tmp_path / "bad.csv", chunk=5)
    assert done == [0, 5] and not (tmp_path / "bad.csv").exists()


@needs_c
def test_record_chunk_off_the_constraints_takes_the_full_route(tmp_path, monkeypatch, capsys):
    """A repeat from the numeric record checks its first chunk's starts before it runs, and each later chunk's as
    it is planned: a later chunk off the constraints (the foot x held where l = 1.9999 puts A off the wall) sends
    the whole command back to the full route, which refuses it with the same paragraph as without the record, and
    no table is left."""
    import math

    from rigidkin.numeric.sweeps import stream, sweep_record

    monkeypatch.delenv("RIGIDKIN_NO_CACHE", raising=False)          # the record kept and read
    monkeypatch.setattr(stream, "CHUNK", 5)
    raised = []
    checked_plan = sweep_record.Planner.checked_plan

    def spy(self, first, stop):
        try:
            return checked_plan(self, first, stop)
        except sweep_record.OffConstraints:
            raised.append(first)
            raise

    monkeypatch.setattr(sweep_record.Planner, "checked_plan", spy)
    fixed = ["--initial", "theta=0.3", f"x={2 * math.sin(0.3)!r}", "--stop-at", "N_A"]
    assert main(["sweep", "ladder", "--param", "l=2,2", *fixed, "-o", str(tmp_path / "keep.csv")]) == 0   # the record
    capsys.readouterr()
    off = ["sweep", "ladder", "--param", "l=2,2,2,2,2,1.9999,1.9999", *fixed]
    assert main([*off, "-o", str(tmp_path / "runs.csv")]) == 2
    err = capsys.readouterr().err
    assert raised == [5] and not (tmp_path / "runs.csv").exists()
    assert main([*off, "--no-cache", "-o", str(tmp_path / "runs.csv")]) == 2
    assert capsys.readouterr().err == err and "starts with contact A apart" in err
