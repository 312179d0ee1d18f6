"""What a user names and types: a problem (a bundled example's name or a problem file) loaded as a
System, and a value typed on its own (SI, or with a unit: ``"30 deg"``).

Shared by the commands and the grader, which read the same problems and the same values.
"""

from __future__ import annotations

import math
from pathlib import Path

from .. import examples
from ..base.errors import RigidkinError
from ..base.units import parse_quantity
from .locate import resolve_problem


def load_system(problem: str):
    """A System from a bundled example name (``ladder``) or a problem file path.

    Returns (system, spec) where ``spec`` is the parsed problem file (None for a Python example).
    A bundled example with a problem file (``examples/ladder.toml``) is read from that file.
    """
    from .problem import load_problem  # the schema and the expression language: pydantic, sympy

    path = Path(problem)
    if path.suffix == ".toml" and not path.exists() and path.stem in examples.names():
        raise RigidkinError(f"there is no file {problem}.", where=problem,
                            hint=f"The bundled example of that name is solved with 'rigidkin solve {path.stem}'.")
    how, _ = resolve_problem(problem)       # a file on disk first; a folder never hides an example
    if how == "file" and (path.suffix == ".toml" or path.exists()):
        return load_problem(path)
    if problem in examples.names():
        toml = examples.HERE / f"{problem}.toml"
        if toml.exists():
            return load_problem(toml)
        return examples.build(problem), None
    raise RigidkinError(f"'{problem}' is neither a problem file nor a bundled example.",
                        hint=f"Bundled examples: {', '.join(examples.names())}. Run 'rigidkin list'.")


def value(text: str, where: str) -> float:
    """A number typed on the command line or in a worksheet: SI, or with a unit (``"30 deg"``), finite.

    Every command reads its values here, through rigidkin's one quantity parser.
    """
    v = parse_quantity(text, None, where)
    if not math.isfinite(v):
        raise RigidkinError(f"'{text}' is not a finite number.", where=where,
                            hint="Give a finite value, e.g. 0.5 or '30 deg'.")
    return v
