"""What a user names and types: a problem (a bundled example's name or a problem file) read once and loaded
as a System, and a value typed on its own (SI, or with a unit: ``"30 deg"``).

A problem is read into a :class:`Source` once per command: its bytes are what is parsed and what the
derivation cache's key is made of, so a file changed while a command runs can never give an entry for other
equations.  Shared by the commands and the grader, which read the same problems and the same values.
"""

from __future__ import annotations

import math

from .. import examples
from ..base.errors import RigidkinError
from ..base.units import parse_quantity
from .source import MAX_FILE_BYTES, Source, read_bytes, read_source  # noqa: F401  (public here too)


def load_system(problem):
    """A System from a bundled example name (``ladder``), a problem file path or a :class:`Source`.

    Returns (system, spec) where ``spec`` is the parsed problem file (None for a Python example).
    A bundled example with a problem file (``examples/ladder.toml``) is read from that file.  A Source is
    built from exactly its bytes (the file is not read again).
    """
    source = read_source(problem)
    if source.path is None:
        return examples.build(source.problem), None
    from .problem import build_problem  # the schema and the expression language: pydantic, sympy
    from .reading import parse_bytes

    text, data = parse_bytes(source.data, source.path)
    return build_problem(data, text, source.path)


def value(text: str, where: str) -> float:
    """A number typed on the command line or in a worksheet: SI, or with a unit (``"30 deg"``), finite.

    Every command reads its values here, through rigidkin's one quantity parser.
    """
    v = parse_quantity(text, None, where)
    if not math.isfinite(v):
        raise RigidkinError(f"'{text}' is not a finite number.", where=where,
                            hint="Give a finite value, e.g. 0.5 or '30 deg'.")
    return v
