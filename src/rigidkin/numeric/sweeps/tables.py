"""Tables of runs written fast: CSV, and Parquet through pyarrow (an optional dependency).

A table is a mapping of column names to equal-length numpy arrays: floats, integers, or text (an
object or string array, such as a run's status).  Both writers go through :func:`rigidkin.base.outfile.writing`
(the whole file or nothing).

CSV: numbers are written as Python writes them (the shortest text that reads back as the same
float: ``repr``), a missing value (NaN: an event that did not happen) as an empty cell; names and
text are neutralised for spreadsheets (:func:`rigidkin.base.textsafe.safe_csv_cell`: a cell that would
start a formula gets a leading apostrophe) and quoted where CSV needs it.  The cost is the
formatting of floats, so each distinct text is made once: a column of few values (a fixed
parameter) formats its distinct values, a column equal to an earlier one row by row (a run's final
state when it ended at its event) reuses that column's cells, and rows are joined in blocks.

Parquet (``.parquet``, ``.pq``): the same columns with their types — float64 with missing values as
nulls, int64, text dictionary-encoded — and the names exactly as given (Parquet holds data, not
formulas).  Without pyarrow, :func:`require_parquet` says so before any work is done.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ...base.errors import RigidkinError
from ...base.outfile import OutputError, writing
from ...base.textsafe import safe_csv_cell

#: File extensions written as Parquet; any other is CSV.
PARQUET_SUFFIXES = (".parquet", ".pq")
#: Rows formatted and joined at a time (bounds the memory of the cells).
BLOCK_ROWS = 65_536

_INSTALL = "pip install 'rigidkin[parquet]' (or pip install pyarrow)"


def table_format(path) -> str:
    """``"parquet"`` for a ``.parquet`` or ``.pq`` file, else ``"csv"``."""
    return "parquet" if Path(str(path)).suffix.lower() in PARQUET_SUFFIXES else "csv"


def require_parquet(path, what: str = "the table"):
    """The ``pyarrow`` module (with ``pyarrow.parquet`` loaded), or an OutputError (exit status 2) saying
    that Parquet needs it and how to get it."""

    try:
        import pyarrow
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise OutputError(f"cannot write {what} to {path}: Parquet files need the pyarrow package, which is not "
                          "installed.", where="output",
                          hint=f"Install it with {_INSTALL}, or write CSV instead (-o {Path(str(path)).stem}.csv)."
                          ) from None
    return pyarrow


def write_table(columns: Mapping[str, np.ndarray], path, what: str = "the table",
                metadata: Mapping[str, str] | None = None) -> Path:
    """Write ``columns`` to ``path`` as Parquet or CSV, by its extension (:func:`table_format`)."""
    if table_format(path) == "parquet":
        return write_parquet(columns, path, what, metadata)
    return write_csv(columns, path, what)


# CSV ------------------------------------------------------------------------------------------------------------
def _quoted(text: str) -> str:
    """A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break."""
    if any(c in text for c in ',"\r\n'):
        return '"' + text.replace('"', '""') + '"'
    return text


def _text_cell(value) -> str:

    if isinstance(value, (float, np.floating)):
        return "" if np.isnan(value) else repr(float(value))
    if isinstance(value, (int, np.integer, bool, np.bool_)):
        return str(value)
    return _quoted(str(safe_csv_cell("" if value is None else str(value))))


class _FloatCells:
    """Float cells of one block of rows, sharing the text of equal values and of equal earlier columns."""

    SAMPLE = 64

    def __init__(self, rows: int):
        self.rows = rows
        self.probe = np.unique(np.linspace(0, rows - 1, min(rows, self.SAMPLE)).astype(int)) if rows else None
        self.done: list[tuple[np.ndarray, np.ndarray, list[str]]] = []     # (bits, nan, cells) per column

    def __call__(self, a: np.ndarray) -> list[str]:
        a = np.ascontiguousarray(a, dtype=np.float64)
        bits, nan = a.view(np.int64), np.isnan(a)
        cells = self._from_earlier(bits, nan, a)
        if cells is None:
            cells = self._format(a, bits)
        if nan.any():
            for i in np.flatnonzero(nan).tolist():
                cells[i] = ""
        self.done.append((bits, nan, cells))
        return cells

    def _from_earlier(self, bits, nan, a) -> list[str] | None:
        """The cells of an earlier column equal to this one in at least half its rows, the others made anew."""
        p = self.probe
        for b, n, cells in self.done:
            if np.count_nonzero((b[p] == bits[p]) | (n[p] & nan[p])) * 2 < len(p):
                continue
            same = (b == bits) | (n & nan)
            k = int(np.count_nonzero(same))
            if k * 2 < self.rows:
                continue
            if k == self.rows:
                return cells
            out, values = list(cells), a.tolist()
            for i in np.flatnonzero(~same).tolist():
                out[i] = repr(values[i])
            return out
        return None

    def _format(self, a, bits) -> list[str]:
        sample = bits[self.probe]
        if np.unique(sample).size * 4 <= sample.size:            # few distinct values: each formatted once
            u, inverse = np.unique(bits, return_inverse=True)
            if u.size * 4 <= bits.size:
                text = np.array(list(map(repr, u.view(np.float64).tolist())), dtype=object)
                return text[inverse.reshape(-1)].tolist()
        return list(map(repr, a.tolist()))


def _cells(a: np.ndarray, floats: _FloatCells) -> list[str]:
    kind = a.dtype.kind
    if kind == "f":
        return floats(a)
    if kind in "iu":
        return list(map(str, a.tolist()))
    values = a.tolist()
    if set(map(type, values)) <= {str}:          # words (a status): each distinct one made once
        cells = {v: _text_cell(v) for v in set(values)}
        return list(map(cells.__getitem__, values))
    return [_text_cell(v) for v in values]


def _columns(columns: Mapping[str, np.ndarray]) -> tuple[list[str], list[np.ndarray], int]:

    names = [str(n) for n in columns]
    arrays = [np.asarray(v) for v in columns.values()]
    arrays = [a.reshape(-1) if a.ndim else np.full(1, a) for a in arrays]
    rows = {len(a) for a in arrays}
    if len(rows) > 1:
        raise RigidkinError(f"the columns of the table have different lengths ({', '.join(map(str, sorted(rows)))}).",
                            where="table")
    return names, arrays, rows.pop() if rows else 0


def csv_text_blocks(columns: Mapping[str, np.ndarray], block_rows: int = BLOCK_ROWS, header: bool = True):
    """The CSV text of a table, header first (unless not ``header``: a later chunk of a streamed table), in
    blocks of ``block_rows`` rows (lines end in CRLF).  Large blocks are formatted by pyarrow where it is
    installed (:func:`_arrow_block`: the same bytes, in vectorised code)."""
    names, arrays, rows = _columns(columns)
    if header:
        yield ",".join(_text_cell(n) for n in names) + "\r\n"
    pa = _pyarrow() if rows >= ARROW_ROWS and names else None
    if pa is not None:
        yield from _arrow_blocks(arrays, rows, min(block_rows, ARROW_BLOCK))
        return
    for start in range(0, rows, block_rows):
        stop = min(rows, start + block_rows)
        floats = _FloatCells(stop - start)
        cells = [_cells(a[start:stop], floats) for a in arrays]
        yield "\r\n".join(map(",".join, zip(*cells))) + "\r\n"


#: Tables of at least this many rows are formatted by pyarrow where it is installed, in blocks of ARROW_BLOCK rows
#: on every core (pyarrow's compute functions release the GIL), a few blocks ahead of the writing.
ARROW_ROWS = 4096
ARROW_BLOCK = 8192
#: Floats whose shortest text pyarrow writes as Python's ``repr`` does (plain decimals); others go through repr.
_ARROW_RANGE = (1e-4, 1e10)


def _pyarrow():
    try:
        import pyarrow
        import pyarrow.compute  # noqa: F401
    except ImportError:
        return None
    return pyarrow


def _arrow_blocks(arrays: list[np.ndarray], rows: int, block_rows: int):
    """The blocks' text in order, formatted by a pool of threads, at most two blocks per thread ahead."""
    import os
    from collections import deque
    from concurrent.futures import ThreadPoolExecutor

    workers = max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1))
    starts = iter(range(0, rows, block_rows))
    with ThreadPoolExecutor(workers) as pool:
        ahead: deque = deque()
        for start in starts:
            ahead.append(pool.submit(_arrow_block, [a[start:start + block_rows] for a in arrays]))
            if len(ahead) >= 2 * workers:
                yield ahead.popleft().result()
        while ahead:
            yield ahead.popleft().result()


def _arrow_block(arrays: list[np.ndarray]) -> str:
    """CSV lines of one block, byte for byte those of the Python formatter: floats as their shortest
    round-trip text (pyarrow's; whole numbers, which pyarrow writes without ``.0``, and values outside
    ``_ARROW_RANGE``, where the two write exponents differently, by ``repr`` itself), NaN as an empty cell.
    A column equal bit for bit to an earlier one (a run's final state when it ended at its event) reuses its
    text, a constant column (a fixed parameter) is formatted once, and the lines are joined inside pyarrow:
    no Python object per row."""
    import pyarrow as pa
    import pyarrow.compute as pc

    rows = len(arrays[0])
    cells, done = [], []                         # done: (bits, text) of the float columns formatted so far
    for a in arrays:
        kind = a.dtype.kind
        if kind == "f":
            a = np.ascontiguousarray(a, dtype=np.float64)
            bits = a.view(np.int64)
            text = next((t for b, t in done if np.array_equal(b, bits)), None)
            if text is None:
                text = _arrow_floats(pa, pc, a, bits)
                done.append((bits, text))
        elif kind in "iu":
            text = pc.cast(pa.array(a.astype(np.int64)), pa.string())
        else:
            text = pa.array(_cells(a, _FloatCells(len(a))), type=pa.string())
        cells.append(text)
    if all(isinstance(c, pa.Scalar) for c in cells):
        cells[0] = pa.repeat(cells[0], rows)
    cells[-1] = pc.binary_join_element_wise(cells[-1], pa.scalar("\r\n"), "")     # each line's end
    lines = pc.binary_join_element_wise(*cells, ",", null_handling="replace", null_replacement="")
    if isinstance(lines, pa.Scalar):
        lines = pa.repeat(lines, rows)
    width = 8 if pa.types.is_large_string(lines.type) else 4
    offsets = np.frombuffer(lines.buffers()[1], dtype=np.int64 if width == 8 else np.int32)
    start, stop = int(offsets[lines.offset]), int(offsets[lines.offset + len(lines)])
    return bytes(memoryview(lines.buffers()[2])[start:stop]).decode("utf-8")


def _arrow_floats(pa, pc, a: np.ndarray, bits: np.ndarray):
    """The text of one float column (a pyarrow string array, or a scalar when every value is the same)."""
    if bits.size and bool(np.all(bits == bits[0])):
        return pa.scalar(_text_cell(float(a[0])), type=pa.string())
    nan = np.isnan(a)
    text = pc.cast(pa.array(a, mask=nan if nan.any() else None, type=pa.float64()), pa.string())
    with np.errstate(invalid="ignore"):
        mag = np.abs(a)
        other = ~nan & np.isfinite(a) & ((a == np.trunc(a)) | (mag < _ARROW_RANGE[0]) | (mag >= _ARROW_RANGE[1]))
    if other.any():
        text = pc.replace_with_mask(text, pa.array(other),
                                    pa.array([repr(v) for v in a[other].tolist()], type=pa.string()))
    return text


def write_csv(columns: Mapping[str, np.ndarray], path, what: str = "the table",
              block_rows: int = BLOCK_ROWS) -> Path:
    """Write the table as CSV to ``path``, whole or not at all (OutputError: why not)."""

    with writing(path, what) as fh:
        for text in csv_text_blocks(columns, block_rows):
            fh.write(text)
    return Path(path)


# Parquet --------------------------------------------------------------------------------------------------------
def arrow_table(columns: Mapping[str, np.ndarray], metadata: Mapping[str, str] | None = None):
    """The table as a ``pyarrow.Table``: floats (NaN as null), integers, text dictionary-encoded."""
    pa = require_parquet("a table")
    names, arrays, _ = _columns(columns)
    out = []
    for a in arrays:
        kind = a.dtype.kind
        if kind == "f":
            a = np.asarray(a, dtype=np.float64)
            nan = np.isnan(a)
            out.append(pa.array(a, mask=nan if nan.any() else None, type=pa.float64()))
        elif kind in "iu":
            out.append(pa.array(a.astype(np.int64), type=pa.int64()))
        elif kind == "b":
            out.append(pa.array(a, type=pa.bool_()))
        else:                                   # text: each distinct value once, and a code per row
            out.append(_dictionary(pa, a))
    meta = {str(k).encode(): str(v).encode() for k, v in (metadata or {}).items()}
    return pa.Table.from_arrays(out, names=names).replace_schema_metadata(meta or None)


def _dictionary(pa, a: np.ndarray):
    """A text column dictionary-encoded, the words in order of first appearance: by pyarrow where every value is a
    string (no Python work per row), else value by value."""
    if all(isinstance(v, str) for v in a[:: max(1, a.size // 64)].tolist()):
        try:
            return pa.array(a, type=pa.string()).dictionary_encode()
        except (pa.ArrowInvalid, pa.ArrowTypeError):
            pass
    labels: dict = {}
    codes = [labels.setdefault(v, len(labels)) for v in a.tolist()]
    words = [None if v is None else str(v) for v in labels]
    return pa.DictionaryArray.from_arrays(pa.array(np.asarray(codes, dtype=np.int32)),
                                          pa.array(words, type=pa.string()))


def write_parquet(columns: Mapping[str, np.ndarray], path, what: str = "the table",
                  metadata: Mapping[str, str] | None = None) -> Path:
    """Write the table as Parquet to ``path``, whole or not at all; needs pyarrow (:func:`require_parquet`)."""

    require_parquet(path, what)
    import pyarrow.parquet as pq

    table = arrow_table(columns, metadata)
    with writing(path, what, binary=True) as fh:
        pq.write_table(table, fh, use_dictionary=_few_values(columns))
    return Path(path)


def _few_values(columns: Mapping[str, np.ndarray]) -> list[str]:
    """The columns worth a Parquet dictionary: text, and numbers with few distinct values (a fixed parameter).
    Trying a dictionary on every column costs more than writing the whole table."""
    names = []
    for name, a in columns.items():
        a = np.asarray(a).reshape(-1)
        if a.dtype.kind not in "fiub":
            names.append(str(name))
            continue
        probe = a[:: max(1, a.size // 64)]
        if np.unique(probe).size * 4 <= probe.size:
            names.append(str(name))
    return names
