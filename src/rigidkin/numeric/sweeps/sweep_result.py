"""The result of a sweep: one row per run — its inputs and parameters, each event's time and state, the final
state and how the run ended — and its table (CSV or Parquet) and figure.

Numbers only (numpy): a repeated sweep read from its numeric record (:mod:`rigidkin.numeric.sweeps.sweep_record`)
makes one without importing sympy.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...base.errors import InputError
from ...base.outfile import unique_columns
from ..compiled import batch
from ..figure import save_figure
from .tables import write_csv, write_parquet, write_table


@dataclass
class SweepResult:
    """The runs of a sweep: their inputs (``columns`` of the grid) and the batch result."""

    system_name: str
    layout: object                         # StateLayout, or the numeric record's layout (labels, parameters)
    inputs: dict[str, np.ndarray]          # varied parameters and initial values, per run
    params: np.ndarray                     # runs × n_p (every parameter)
    y0: np.ndarray                         # runs × 2n
    result: batch.BatchResult
    backend: str
    record: dict | None = None             # the numeric record a repeat can be answered from (keep_record)
    first: int = 0                         # the number of the first run (a chunk of a streamed sweep)

    def __len__(self) -> int:
        return len(self.result)

    @property
    def status(self) -> np.ndarray:
        return self.result.status

    def event_time(self, name: str) -> np.ndarray:
        return self.result.event_t[:, self._event(name)]

    def event_state(self, name: str, slot: str | None = None) -> np.ndarray:
        y = self.result.event_y[:, self._event(name)]
        return y if slot is None else y[:, self.layout.index(slot)]

    def _event(self, name):
        try:
            return self.result.event_names.index(name)
        except ValueError:
            raise InputError(f"'{name}' is not an event of this sweep.",
                             hint=f"Events: {', '.join(self.result.event_names)}.") from None

    def columns(self) -> dict[str, np.ndarray]:
        """The table: one column per input, parameter, event time and state, final time and state, status."""
        pairs = [("run", np.arange(self.first, self.first + len(self)))]
        pairs += [(name, self.params[:, j]) for j, name in enumerate(self.layout.parameters)]
        pairs += [(name, v) for name, v in self.inputs.items() if name not in self.layout.parameters]
        for k, ev in enumerate(self.result.event_names):
            pairs.append((f"{ev}: t", self.result.event_t[:, k]))
            pairs += [(f"{ev}: {lab}", self.result.event_y[:, k, i]) for i, lab in enumerate(self.layout.labels)]
        pairs.append(("end: t", self.result.t_end))
        pairs += [(f"end: {lab}", self.result.y_end[:, i]) for i, lab in enumerate(self.layout.labels)]
        pairs.append(("status", status_text(self.result.status)))
        return unique_columns(pairs)        # a parameter named run or status, an event named end: refused

    def metadata(self) -> dict[str, str]:
        """What a Parquet table keeps beside its columns: the system, the backend, the events."""
        return {"rigidkin.system": self.system_name, "rigidkin.backend": self.backend,
                "rigidkin.events": "\n".join(self.result.event_names)}

    def write(self, path) -> Path:
        """Write the table to ``path``: Parquet for ``.parquet``/``.pq`` (needs pyarrow), CSV otherwise; whole or
        not at all (OutputError: why not).  See :mod:`rigidkin.numeric.sweeps.tables`."""

        return write_table(self.columns(), path, "the sweep table", self.metadata())

    def to_csv(self, path) -> Path:
        """Write the table as CSV (numbers as ``repr`` writes them, missing values empty, names neutralised)."""

        return write_csv(self.columns(), path, "the sweep table")

    def to_parquet(self, path) -> Path:
        """Write the table as Parquet (needs pyarrow; missing values as nulls)."""

        return write_parquet(self.columns(), path, "the sweep table", self.metadata())

    def to_pandas(self):
        """The table as a pandas DataFrame, one row per run (indexed by ``run``)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_pandas() needs pandas, which is not installed: pip install 'pandas>=2.1' "
                              "(or to_csv() writes the same table without it).") from None
        cols = self.columns()
        return pd.DataFrame({k: v for k, v in cols.items() if k != "run"}, index=pd.Index(cols["run"], name="run"))

    def plot(self, path, x: str | None = None, y: str | None = None) -> Path:
        """A figure of one table column against another (default: the first event's time against the first input)."""
        from matplotlib.figure import Figure


        cols = self.columns()
        x = x or (next(iter(self.inputs)) if self.inputs else "run")
        if y is None:
            y = f"{self.result.event_names[0]}: t" if self.result.event_names else "end: t"
        for c in (x, y):
            if c not in cols:
                raise InputError(f"'{c}' is not a column of the sweep table.", hint=f"Columns: {', '.join(cols)}.")
        fig = Figure(figsize=(7, 4.5), layout="constrained")
        ax = fig.subplots()
        xs, ys = np.asarray(cols[x], dtype=float), np.asarray(cols[y], dtype=float)
        order = np.argsort(xs, kind="stable")
        ax.plot(xs[order], ys[order], ".", ms=3 if len(xs) > 200 else 6)
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        ax.set_title(f"{self.system_name}: {len(self)} runs")
        ax.grid(alpha=0.3)
        return save_figure(fig, path, dpi=120)


def status_text(codes: np.ndarray) -> np.ndarray:
    """The status of each run in words (:data:`rigidkin.numeric.compiled.batch.STATUS`), as an object array."""
    codes = np.asarray(codes).reshape(-1)
    if not codes.size:
        return np.empty(0, dtype=object)
    u, inverse = np.unique(codes, return_inverse=True)
    words = np.array([batch.STATUS.get(int(c), f"status {int(c)}") for c in u.tolist()], dtype=object)
    return words[inverse.reshape(-1)]
