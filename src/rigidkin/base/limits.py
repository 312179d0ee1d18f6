"""How much memory a command may ask for, estimated before anything is allocated.

Time histories (``simulate --points``) and sweep tables (one row per run) grow with numbers the user
types.  Their size is estimated from those numbers first, and a request above :data:`MEMORY_LIMIT`
is refused with one paragraph that says how large it would be and what to do, instead of growing
to gigabytes before anything is said.
"""

from __future__ import annotations

from .errors import InputError

#: The most memory (bytes) that histories or a sweep table may take: 1 GiB.
MEMORY_LIMIT = 1 << 30

#: Bytes per stored number, with room for the temporary copies made while sampling and writing.
_BYTES_PER_VALUE = 8 * 4


def history_bytes(points: int, columns: int) -> int:
    """Estimated memory of time histories: ``points`` samples of ``columns`` numbers (and their copies)."""
    return int(points) * int(columns) * _BYTES_PER_VALUE


def sweep_bytes(runs: int, per_run: int) -> int:
    """Estimated memory of a sweep: ``runs`` rows of ``per_run`` numbers (inputs, parameters, events, ends)."""
    return int(runs) * int(per_run) * _BYTES_PER_VALUE


def check_memory(estimate: int, what: str, where: str, hint: str, limit: int = MEMORY_LIMIT) -> None:
    """Refuse (InputError) when ``estimate`` bytes exceed ``limit``."""
    if estimate > limit:
        raise InputError(f"{what} would take about {_size(estimate)} of memory; the limit is {_size(limit)}.",
                         where=where, hint=hint)


def _size(n: int) -> str:
    for unit, scale in (("TB", 1 << 40), ("GB", 1 << 30), ("MB", 1 << 20), ("kB", 1 << 10)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{n} bytes"
