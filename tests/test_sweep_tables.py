"""Sweep tables: the CSV and Parquet writers give back exactly the runs in memory (numbers as numbers,
missing values as empty cells or nulls, event names as columns), neutralise text for spreadsheets, and
refuse Parquet without pyarrow in one paragraph (exit status 2) before anything is run."""

from __future__ import annotations

import csv
import io
import math
import sys

import numpy as np
import pytest

from rigidkin import examples
from rigidkin.base.textsafe import safe_csv_cell
from rigidkin.cli import main
from rigidkin.numeric.sweeps.sweep import sweep
from rigidkin.numeric.sweeps.tables import csv_text_blocks, table_format, write_csv, write_parquet


@pytest.fixture(scope="module")
def ladder_runs():
    """Five ladders to wall-contact loss, with θ = 0.8 recorded (reached by some runs only)."""
    return sweep(examples.build("ladder"), {"theta": (0.2, 1.0, 5)}, stop_at="N_A", record=["theta=0.8"])


def _reference_csv(columns) -> str:
    """The table as the csv module writes it cell by cell: repr of each float, '' for NaN, text neutralised."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\r\n")
    w.writerow([safe_csv_cell(n) for n in columns])
    rows = len(next(iter(columns.values())))
    for r in range(rows):
        cells = []
        for a in columns.values():
            v = a[r]
            if isinstance(v, (float, np.floating)):
                cells.append("" if np.isnan(v) else repr(float(v)))
            else:
                cells.append(safe_csv_cell(str(v)))
        w.writerow(cells)
    return buf.getvalue()


def _assert_same_column(name, got, want):
    if want.dtype.kind == "f":
        got = np.asarray(got, dtype=float)
        assert np.array_equal(np.isnan(got), np.isnan(want)), name
        ok = ~np.isnan(want)
        assert np.array_equal(got[ok], want[ok]), name                          # exactly, not approximately
        assert np.array_equal(np.signbit(got[ok]), np.signbit(want[ok])), name
    else:
        assert [str(v) for v in got] == [str(v) for v in want], name


def test_csv_round_trip_equals_the_runs_in_memory(ladder_runs, tmp_path):
    out = ladder_runs.write(tmp_path / "runs.csv")
    cols = ladder_runs.columns()
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == list(cols)
    for name in ("N_A: t", "N_A: theta", "N_A: dot(x)", "theta=0.8: t", "end: t", "status"):
        assert name in rows[0]                                           # every event's time and state is a column
    for name, want in cols.items():
        got = [float(r[name]) if r[name] != "" else math.nan for r in rows] if want.dtype.kind == "f" else \
            [r[name] for r in rows]
        _assert_same_column(name, got, want)
    assert [r["status"] for r in rows] == ["terminal event"] * 5
    th0 = np.array([float(r["theta"]) for r in rows])
    assert np.allclose(np.cos([float(r["N_A: theta"]) for r in rows]), 2 / 3 * np.cos(th0), atol=1e-9)
    reached = [r["theta=0.8: t"] != "" for r in rows]
    assert reached == list((th0 <= 0.8) & (np.arccos(2 / 3 * np.cos(th0)) > 0.8))   # the runs that pass θ = 0.8
    assert 0 < sum(reached) < 5
    assert out.read_bytes().decode() == _reference_csv(cols)           # byte for byte the cell-by-cell writer


def test_csv_writer_neutralises_text_and_keeps_numbers():
    n = 9
    cols = {
        "run": np.arange(n),
        "=HYPERLINK(\"http://x\",\"a,b\")": np.linspace(-1, 1, n),     # a name that would be a formula
        "fixed": np.full(n, 9.81),                                       # few values: formatted once
        "zeros": np.array([0.0, -0.0] * 4 + [math.nan]),                 # the sign of zero kept
        "tiny/huge": np.array([5e-324, 1e-5, 1e16, 1e22, 0.1 + 0.2, math.inf, -math.inf, 123456789.0, 1 / 3]),
        "copy": np.linspace(-1, 1, n),                                   # equal to an earlier column
        "half copy": np.where(np.arange(n) < 6, np.linspace(-1, 1, n), 7.5),
        "note": np.array(["=1+2", "-1.5", "+cmd", "@SUM(A1)", "plain", "a,b", 'say "hi"', "\tx", "-x"],
                         dtype=object),
    }
    text = "".join(csv_text_blocks(cols))
    assert text == _reference_csv(cols)
    rows = list(csv.reader(io.StringIO(text, newline="")))
    assert rows[0][1].startswith("'=")                                   # the name cannot start a formula
    note = [r[-1] for r in rows[1:]]
    assert note == ["'=1+2", "-1.5", "'+cmd", "'@SUM(A1)", "plain", "a,b", 'say "hi"', "'\tx", "'-x"]
    for r, v in zip(rows[1:], cols["tiny/huge"]):
        assert float(r[4]) == v                                          # numbers stay numbers, exactly
    assert [r[3] for r in rows[1:]] == ["0.0", "-0.0"] * 4 + [""]
    # blocks of any size give the same text
    assert "".join(csv_text_blocks(cols, block_rows=2)) == text


def test_vectorised_csv_text_equals_the_csv_module_byte_for_byte():
    """A table long enough for the pyarrow formatter (blocks on every core): whole numbers, ±0, values outside
    pyarrow's plain-decimal range, subnormals, ±inf, NaN, a constant column, a column equal to an earlier one and
    one equal to it in part, text that needs quoting or neutralising — the bytes the csv module writes."""
    pytest.importorskip("pyarrow.compute")
    from rigidkin.numeric.sweeps import tables

    rng = np.random.default_rng(7)
    n = tables.ARROW_ROWS + 3 * tables.ARROW_BLOCK + 17
    special = np.array([0.0, -0.0, 1.0, -1.0, 2.0, 1e9, 9999999999.0, 1e10, 1e15, 1e16, 1e300, 5e-324, 1e-4,
                        9.999e-5, 1.0000000000000002e-4, 0.1, 1 / 3, -2.5, np.nan, np.inf, -np.inf, 123456.0, 1e-300,
                        2.2250738585072014e-308, 0.30000000000000004])
    wide = rng.standard_normal(n) * 10.0 ** rng.integers(-12, 14, n)
    part = wide.copy()
    part[::3] = 0.25
    cols = {"run": np.arange(n), "g": np.full(n, 9.81), "special": rng.choice(special, n), "x": wide,
            "end: x": wide.copy(), "part": part, "gaps": np.where(rng.random(n) < 0.3, np.nan, wide),
            "none": np.full(n, np.nan), "zero": np.full(n, -0.0),
            "status": np.array(rng.choice(["terminal event", "a,b", 'say "x"', "=1+2", "line\nbreak"], n),
                               dtype=object)}
    assert "".join(csv_text_blocks(cols)) == _reference_csv(cols)
    assert "".join(csv_text_blocks({"k": np.full(n, 2.0), "l": np.full(n, np.nan)})) == \
        _reference_csv({"k": np.full(n, 2.0), "l": np.full(n, np.nan)})                # every column constant


def test_csv_is_written_whole_or_not_at_all(tmp_path):
    cols = {"run": np.arange(3), "x": np.array([1.0, math.nan, 2.5])}
    path = write_csv(cols, tmp_path / "t.csv")
    assert path.read_bytes().decode() == "run,x\r\n0,1.0\r\n1,\r\n2,2.5\r\n"
    from rigidkin.base.outfile import OutputError

    with pytest.raises(OutputError, match="does not exist"):
        write_csv(cols, tmp_path / "missing" / "t.csv")


def test_parquet_round_trip_equals_the_runs_in_memory(ladder_runs, tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    out = ladder_runs.write(tmp_path / "runs.parquet")
    table = pq.read_table(out)
    cols = ladder_runs.columns()
    assert table.column_names == list(cols)                              # event names as columns
    assert table.schema.field("N_A: t").type == "double" and table.schema.field("run").type == "int64"
    for name, want in cols.items():
        col = table.column(name)
        if want.dtype.kind == "f":
            assert col.null_count == int(np.isnan(want).sum()), name    # a missing event is a null
            got = col.to_numpy(zero_copy_only=False)
        else:
            got = col.to_pylist()
        _assert_same_column(name, got, want)
    assert table.column("theta=0.8: t").null_count > 0
    meta = table.schema.metadata
    assert meta[b"rigidkin.system"] == b"ladder" and b"N_A" in meta[b"rigidkin.events"]


def test_parquet_keeps_names_and_text_exactly(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    cols = {"=x": np.array([1.5, math.nan]), "status": np.array(["=1+2", "terminal event"], dtype=object)}
    table = pq.read_table(write_parquet(cols, tmp_path / "t.pq"))
    assert table.column_names == ["=x", "status"]
    assert table.column("status").to_pylist() == ["=1+2", "terminal event"]
    assert table.column("=x").to_pylist() == [1.5, None]


def test_cli_writes_parquet(tmp_path, capsys):
    pq = pytest.importorskip("pyarrow.parquet")
    out = tmp_path / "runs.parquet"
    assert main(["sweep", "ladder", "--param", "theta=0.2:0.6:3", "--stop-at", "N_A", "-o", str(out)]) == 0
    table = pq.read_table(out)
    th0, th = (np.asarray(table.column(c).to_numpy()) for c in ("theta", "N_A: theta"))
    assert np.allclose(np.cos(th), 2 / 3 * np.cos(th0), atol=1e-9)
    assert table.column("status").to_pylist() == ["terminal event"] * 3
    assert "Wrote the table to" in capsys.readouterr().out


def test_parquet_without_pyarrow_is_refused_before_the_sweep(tmp_path, capsys, monkeypatch):
    for name in [m for m in sys.modules if m == "pyarrow" or m.startswith("pyarrow.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "pyarrow", None)                    # import pyarrow → ImportError
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    import rigidkin.numeric.sweeps.sweep as numeric_sweep

    monkeypatch.setattr(numeric_sweep, "sweep", lambda *a, **k: pytest.fail("the sweep ran"))
    out = tmp_path / "runs.parquet"
    code = main(["sweep", "ladder", "--param", "theta=0.2:0.6:3", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2
    assert "pyarrow" in err and "runs.parquet" in err and "pip install" in err and ".csv" in err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert not out.exists() and list(tmp_path.iterdir()) == []
    with pytest.raises(Exception, match="pyarrow"):
        write_parquet({"x": np.zeros(2)}, tmp_path / "t.parquet")


@pytest.mark.parametrize("name, kind", [("a.parquet", "parquet"), ("a.PQ", "parquet"), ("a.csv", "csv"),
                                        ("a.txt", "csv"), ("a", "csv")])
def test_the_format_follows_the_extension(name, kind):
    assert table_format(name) == kind
