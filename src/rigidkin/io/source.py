"""A problem as read, once: the bytes of its file (size-limited), or the name of a bundled example built in
Python.  What is parsed and what the caches' keys are made of are these bytes (:class:`Source`)."""

from __future__ import annotations

import os
import stat
from dataclasses import dataclass
from pathlib import Path

from .. import examples
from ..base.errors import InputError, RigidkinError
from .locate import resolve_problem

#: Larger files are refused before they are read (a problem description is a few kilobytes).
MAX_FILE_BYTES = 1_000_000


@dataclass(frozen=True)
class Source:
    """A problem as read, once: ``problem`` as named, ``name`` its identity (the resolved path, or
    ``example:NAME`` for a bundled example built in Python), ``path`` the file read (None for a Python
    example) and ``data`` its bytes."""

    problem: str
    name: str
    path: Path | None
    data: bytes


def read_bytes(path: Path | str, what: str = "the problem file") -> bytes:
    """A file's bytes, read once, size-limited (:data:`MAX_FILE_BYTES`); every failure an InputError."""
    path = Path(path)
    try:
        if not _regular(os.stat(path)):               # a FIFO or a device: refused before it is opened
            raise InputError("is not a file.", where=str(path), hint="Give the path of a .toml problem file.")
        with open(path, "rb") as f:
            st = os.fstat(f.fileno())
            if not _regular(st):
                raise InputError("is not a file.", where=str(path), hint="Give the path of a .toml problem file.")
            if st.st_size > MAX_FILE_BYTES:
                raise InputError(f"{what} is {st.st_size} bytes long (at most {MAX_FILE_BYTES}).", where=str(path),
                                 hint="A problem file describes one system in a few kilobytes; check that this is "
                                      "the right file.")
            data = f.read(MAX_FILE_BYTES + 1)
    except IsADirectoryError:
        raise InputError("is not a file.", where=str(path), hint="Give the path of a .toml problem file.") from None
    except OSError as exc:
        raise InputError(f"cannot read {what} ({exc.strerror or exc}).", where=str(path),
                         hint="Check the path; 'rigidkin list' shows the bundled examples.") from None
    if len(data) > MAX_FILE_BYTES:
        raise InputError(f"{what} is longer than {MAX_FILE_BYTES} bytes.", where=str(path))
    return data


def _regular(st) -> bool:
    return stat.S_ISREG(st.st_mode)


def read_source(problem) -> Source:
    """The problem ``problem`` names (a file path or a bundled example's name), read once."""
    if isinstance(problem, Source):
        return problem
    problem = str(problem)
    path = Path(problem)
    if path.suffix == ".toml" and not path.exists() and path.stem in examples.names():
        raise RigidkinError(f"there is no file {problem}.", where=problem,
                            hint=f"The bundled example of that name is solved with 'rigidkin solve {path.stem}'.")
    how, _ = resolve_problem(problem)       # a file on disk first; a folder never hides an example
    if how == "file" and (path.suffix == ".toml" or path.exists()):
        return Source(problem, str(path.resolve()), path, read_bytes(path))
    if problem in examples.names():
        toml = examples.HERE / f"{problem}.toml"
        if toml.exists():
            return Source(problem, str(toml.resolve()), toml, read_bytes(toml))
        return Source(problem, f"example:{problem}", None, b"")    # a Python example: its code is the source
    raise RigidkinError(f"'{problem}' is neither a problem file nor a bundled example.",
                        hint=f"Bundled examples: {', '.join(examples.names())}. Run 'rigidkin list'.")
