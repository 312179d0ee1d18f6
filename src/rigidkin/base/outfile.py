"""Output files written whole or not at all, and every failure to write one reported as one paragraph.

An output path is checked before any work is done (:func:`check_target`: its folder exists, it is
not a folder itself, its extension is one the writer knows), then written through :func:`writing`:
into a temporary file beside it that is renamed over the target only when everything has been
written, so that a full disk, a missing permission or an interruption leaves nothing half-written.
A device or a pipe (``/dev/null``, ``/dev/stdout``, a FIFO) is written in place.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

from .errors import RigidkinError


class OutputError(RigidkinError):
    """An output file cannot be written: a missing folder, no permission, a full disk, an unknown format."""


def check_target(path, what: str, suffixes: tuple[str, ...] | None = None) -> Path:
    """``path`` as a Path when ``what`` can be written there; otherwise an OutputError naming the reason."""
    text = os.fspath(path) if isinstance(path, (str, os.PathLike)) else None
    if not text or "\x00" in text:
        raise OutputError(f"'{path}' is not a usable file name for {what}.", where="output")
    p = Path(text)
    try:
        return _check(p, what, suffixes)
    except OSError as exc:               # a name too long, a loop of links, ...
        raise _error(exc, what, p) from None


def _check(p: Path, what: str, suffixes: tuple[str, ...] | None) -> Path:
    if p.is_dir():
        raise OutputError(f"cannot write {what} to {p}: it is a folder.",
                          hint="Give a file name inside it, e.g. " + str(p / ("out" + (suffixes or ("",))[0])) + ".")
    if suffixes is not None and p.suffix.lower() not in suffixes:
        raise OutputError(f"cannot write {what} to {p}: the extension '{p.suffix or '(none)'}' is not one of "
                          f"{', '.join(suffixes)}.", hint="Choose a file name with one of these.")
    folder = p.parent
    if not folder.exists():
        raise OutputError(f"cannot write {what} to {p}: the folder {folder} does not exist.",
                          hint="Create the folder first, or write somewhere else.")
    if not folder.is_dir():
        raise OutputError(f"cannot write {what} to {p}: {folder} is not a folder.")
    special = p.exists() and not p.is_file()
    if not os.access(p if special else folder, os.W_OK):
        raise OutputError(f"cannot write {what} to {p}: permission denied"
                          + ("." if special else f" (the folder {folder} is not writable)."),
                          hint="Write somewhere you may write to.")
    return p


@contextlib.contextmanager
def writing(path, what: str, binary: bool = False, suffixes: tuple[str, ...] | None = None):
    """A file object for ``path``: text (UTF-8, no newline translation) or ``binary``.

    The content goes to a temporary file in the same folder, renamed over ``path`` when the block
    ends without an error; on any error the temporary file is removed and an OSError becomes an
    OutputError with the path and the reason (exit status 2 at the command line).
    """
    p = check_target(path, what, suffixes)
    mode, kw = ("wb", {}) if binary else ("w", {"encoding": "utf-8", "newline": ""})
    if p.exists() and not p.is_file():          # a device or a pipe: no temporary file beside it
        try:
            with open(p, mode, **kw) as f:
                yield f
        except OSError as exc:
            raise _error(exc, what, p) from None
        return
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(dir=p.parent, prefix=".rigidkin-", suffix=".part")
        with os.fdopen(fd, mode, **kw) as f:
            yield f
        _chmod_default(tmp)
        os.replace(tmp, p)
        tmp = None
    except OSError as exc:
        raise _error(exc, what, p) from None
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)


def write_text(path, text: str, what: str) -> Path:
    """Write ``text`` to ``path`` whole or not at all (see :func:`writing`)."""
    with writing(path, what) as f:
        f.write(text)
    return Path(path)


def _error(exc: OSError, what: str, p: Path) -> OutputError:
    reason = exc.strerror or str(exc) or type(exc).__name__
    return OutputError(f"cannot write {what} to {p}: {reason[:1].lower() + reason[1:]}.",
                       hint="Nothing was written there; free some space or choose another place.")


def _chmod_default(path: str) -> None:
    """The permissions a newly created file gets (mkstemp makes it private to the user)."""
    mask = os.umask(0)
    os.umask(mask)
    with contextlib.suppress(OSError):
        os.chmod(path, 0o666 & ~mask)
