"""What a sweep gives back on the terminal: how its runs ended, and the range and percentiles of every event's
time — gathered chunk by chunk, in memory bounded whatever the sweep's size.

Counts, hits and ranges are exact over every run.  Percentiles are of every run up to :data:`SAMPLE` runs,
beyond that of an even sample (every k-th run of the grid, k = ⌈runs / SAMPLE⌉), which the summary says.
The same sample keeps the columns a figure needs (:mod:`rigidkin.numeric.sweeps.sweep_plot`).
"""

from __future__ import annotations

import math

import numpy as np

from ...base.errors import InputError
from ..compiled.batch import STATUS

#: The most runs whose event times (and figure columns) a summary keeps.
SAMPLE = 1_000_000
#: The percentiles shown.
PERCENTILES = (5, 50, 95)


class Summary:
    """Counts by outcome, event hits, ranges and percentiles of event times over a sweep's chunks."""

    def __init__(self, runs: int, keep: tuple[str, ...] = (), sample: int = SAMPLE):
        self.runs = int(runs)
        self.stride = max(1, math.ceil(self.runs / sample))
        self.keep = tuple(keep)
        self.counts: dict[int, int] = {}
        self.names: tuple[str, ...] = ()
        self.hits: np.ndarray | None = None
        self.low: np.ndarray | None = None
        self.high: np.ndarray | None = None
        self.times: list[np.ndarray] = []
        self.kept: dict[str, list[np.ndarray]] = {}
        self.seen = 0

    def add(self, part) -> None:
        """Count one chunk (a SweepResult whose runs start at ``part.first``)."""
        res = part.result
        codes, n = np.unique(np.asarray(res.status, dtype=int), return_counts=True)
        for c, k in zip(codes.tolist(), n.tolist()):
            self.counts[c] = self.counts.get(c, 0) + k
        ne = len(res.event_names)
        if self.hits is None:
            self.names = tuple(res.event_names)
            self.hits, self.low, self.high = np.zeros(ne, dtype=np.int64), np.full(ne, np.inf), np.full(ne, -np.inf)
            first_time = f"{self.names[0]}: t" if ne else "end: t"
            self.keep = tuple(first_time if c is None else c for c in self.keep)     # None: the first event's time
            missing = [c for c in self.keep if c not in _column_names(part)]
            if missing:
                raise InputError(f"'{missing[0]}' is not a column of the sweep table.", where="--plot",
                                 hint=f"Columns: {', '.join(_column_names(part))}.")
        t = res.event_t
        if ne:
            hit = ~np.isnan(t)
            self.hits += hit.sum(axis=0)
            with np.errstate(invalid="ignore"):
                self.low = np.fmin(self.low, np.nanmin(np.where(hit, t, np.inf), axis=0))
                self.high = np.fmax(self.high, np.nanmax(np.where(hit, t, -np.inf), axis=0))
        rows = np.flatnonzero((np.arange(part.first, part.first + len(part)) % self.stride) == 0)
        self.times.append(t[rows].copy())
        if self.keep:
            cols = part.columns()
            for c in self.keep:
                self.kept.setdefault(c, []).append(np.asarray(cols[c], dtype=float)[rows].copy())
        self.seen += len(part)

    def sample(self) -> dict[str, np.ndarray]:
        """The kept columns of the sampled runs."""
        return {c: np.concatenate(v) if v else np.zeros(0) for c, v in self.kept.items()}

    def status_counts(self) -> dict[str, int]:
        """How many runs ended in each way, in the order of the status codes."""
        return {STATUS.get(c, f"status {c}"): self.counts[c] for c in sorted(self.counts)}

    def event_stats(self) -> list[dict]:
        """Per event: its name, how many runs reached it, and (where any did) the range and percentiles of its time."""
        times = np.concatenate(self.times) if self.times else np.zeros((0, len(self.names)))
        out = []
        for k, name in enumerate(self.names):
            row = {"event": name, "hits": int(self.hits[k]), "runs": self.seen}
            ts = times[:, k][~np.isnan(times[:, k])]
            if row["hits"]:
                row["min"], row["max"] = float(self.low[k]), float(self.high[k])
            if ts.size:
                row.update({f"p{q}": float(v) for q, v in zip(PERCENTILES, np.percentile(ts, PERCENTILES))})
            out.append(row)
        return out

    def lines(self) -> list[str]:
        """The summary as lines of text."""
        out = ["  outcomes: " + ", ".join(f"{v:,} {k}" for k, v in self.status_counts().items())]
        for row in self.event_stats():
            line = f"  event {row['event']}: {row['hits']:,} of {row['runs']:,} runs"
            if row["hits"]:
                line += f"; t from {row['min']:.6g} to {row['max']:.6g} s"
                if "p50" in row:
                    line += ", " + ", ".join(f"p{q} {row[f'p{q}']:.6g}" for q in PERCENTILES)
            out.append(line)
        if self.stride > 1:
            out.append(f"  (percentiles of every {self.stride}th run: {math.ceil(self.seen / self.stride):,} runs)")
        return out


def _column_names(part) -> list[str]:
    names = ["run", *part.layout.parameters, *part.inputs]
    for ev in part.result.event_names:
        names += [f"{ev}: t", *(f"{ev}: {lab}" for lab in part.layout.labels)]
    return [*dict.fromkeys(names), "end: t", *(f"end: {lab}" for lab in part.layout.labels)]
