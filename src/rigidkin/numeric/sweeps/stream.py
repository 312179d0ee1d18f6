"""A sweep of any size written to its table chunk by chunk: memory bounded by the chunk, not the sweep.

The runs are planned (the grid's values at those runs, each state completed), integrated, summarised and
written :data:`CHUNK` at a time, in the order of the whole grid; a thread writes one chunk's table (CSV text,
or a Parquet row group) while the next chunk is integrated (the compiled integrator releases the GIL), so the
table's formatting overlaps the integration; a sweep answered from its numeric record also plans the next chunk
in a thread meanwhile (numpy only), so nothing per run is left serial on the main thread but the summary.  At
most :data:`~rigidkin.numeric.sweeps.sweep_plan.IN_FLIGHT` chunks are alive at once.  The table is the one the
whole sweep would write: the same rows, the same bytes for CSV, the same values for Parquet (one row group a
chunk).
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

from ...base.outfile import writing
from .summary import Summary
from .tables import _few_values, arrow_table, csv_text_blocks, require_parquet, table_format

#: Runs per chunk of a streamed sweep.
CHUNK = 1 << 16


def write_sweep(source, path, chunk: int | None = None, progress: Callable[[int, int], None] | None = None,
                summary: Summary | None = None):
    """Integrate every run of ``source`` (a :class:`~rigidkin.numeric.sweeps.sweep.Prepared`, or the numeric
    record's, with ``runs`` and ``part(first, stop)``) and write the table to ``path`` (CSV, or Parquet by its
    extension), whole or not at all.  Returns the summary (counts, event-time ranges and percentiles, the
    sample kept for a figure) and the first chunk's result (the backend, the record)."""
    chunk = int(chunk or CHUNK)
    runs = source.runs
    summary = summary or Summary(runs)
    parquet = table_format(path) == "parquet"
    if parquet:
        require_parquet(path, "the sweep table")
    jobs: queue.Queue = queue.Queue(maxsize=1)
    failure: list[BaseException] = []
    first_part = None
    with writing(path, "the sweep table", binary=parquet) as fh:
        writer = threading.Thread(target=_writer, args=(jobs, fh, parquet, failure), daemon=True)
        writer.start()
        ahead = _Ahead(source, runs, chunk)
        try:
            for a in range(0, runs, chunk):
                part = ahead.part(a)
                if first_part is None:
                    first_part = part
                summary.add(part)
                cols = part.columns()
                meta = part.metadata()
                del part
                while not failure:
                    try:
                        jobs.put((a == 0, cols, meta), timeout=0.5)
                        break
                    except queue.Full:
                        continue
                del cols
                if failure:
                    break
                if progress is not None:
                    progress(min(runs, a + chunk), runs)
        finally:
            ahead.close()
            jobs.put(None)
            writer.join()
        if failure:
            raise failure[0]
    return summary, first_part


class _Ahead:
    """The chunks of ``source`` integrated in order, each planned in a thread while the one before is integrated,
    where the source allows it (``plan_ahead``: a planner of numpy only); else each planned when its turn comes."""

    def __init__(self, source, runs: int, chunk: int):
        self.source, self.runs, self.chunk = source, runs, chunk
        self.pool = self.next = None
        if getattr(source, "plan_ahead", False) and runs > chunk:
            self.pool = ThreadPoolExecutor(1, thread_name_prefix="rk-plan")
            self.next = self.pool.submit(source.plan, 0, min(runs, chunk))

    def part(self, a: int):
        """The result of the chunk that starts at run ``a``."""
        stop = min(self.runs, a + self.chunk)
        if self.pool is None:
            return self.source.part(a, stop)
        planned = self.next.result()                      # a planning error is raised here, at its chunk
        self.next = self.pool.submit(self.source.plan, stop, min(self.runs, stop + self.chunk)) \
            if stop < self.runs else None
        return self.source.part(a, stop, planned=planned)

    def close(self) -> None:
        if self.pool is not None:
            self.pool.shutdown(wait=True, cancel_futures=True)


def _writer(jobs: queue.Queue, fh, parquet: bool, failure: list) -> None:
    """Write each chunk's table as it comes (None: the end)."""
    pq_writer = None
    try:
        while True:
            job = jobs.get()
            if job is None:
                break
            if failure:
                continue
            first, cols, meta = job
            if parquet:
                import pyarrow.parquet as pq

                table = arrow_table(cols, meta)
                if pq_writer is None:
                    pq_writer = pq.ParquetWriter(fh, table.schema, use_dictionary=_few_values(cols))
                pq_writer.write_table(table)
            else:
                for text in csv_text_blocks(cols, header=first):
                    fh.write(text)
        if pq_writer is not None:
            pq_writer.close()
    except BaseException as exc:       # noqa: BLE001  (handed to the main thread, raised there)
        failure.append(exc)
        while jobs.get() is not None:  # let the producer finish
            pass
