"""What the subcommands share: finding a problem (a bundled example name or a file) and loading it."""

from __future__ import annotations

from pathlib import Path

from ..errors import RigidkinError


def load_system(problem: str):
    """A System from a bundled example name (``ladder``) or a problem file path.

    Returns (system, spec) where ``spec`` is the parsed problem file (None for a Python example).
    """
    from .. import examples

    path = Path(problem)
    if path.suffix == ".toml" or path.exists():
        try:
            from ..io.problem import load_problem  # the problem-file reader
        except ModuleNotFoundError:
            raise RigidkinError("problem files are not supported yet.", where=problem) from None
        return load_problem(path)
    if problem in examples.names():
        toml = examples.HERE / f"{problem}.toml"
        if toml.exists():
            try:
                from ..io.problem import load_problem
                return load_problem(toml)
            except ModuleNotFoundError:
                pass
        return examples.build(problem), None
    raise RigidkinError(f"'{problem}' is neither a problem file nor a bundled example.",
                        hint=f"Bundled examples: {', '.join(examples.names())}. Run 'rigidkin list'.")
