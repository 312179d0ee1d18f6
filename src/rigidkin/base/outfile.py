"""Output files written whole or not at all, never over an input, and every failure reported as one paragraph.

An output path is checked before any work is done (:func:`check_target`: its folder exists, it is
not a folder itself, its extension is one the writer knows; :func:`check_outputs`: no output is an input
of the command, no two outputs are one file), then written through :func:`writing`:

* a regular file (or a name not there yet) is written into a temporary file beside it that is renamed
  over it only when everything has been written, so that a full disk, a size limit, a missing permission
  or an interruption (Ctrl-C, SIGTERM, SIGHUP: :mod:`rigidkin.base.tempfiles`) leaves the old file as it
  was and no temporary file behind.  A link to a regular file keeps being a link: its target is replaced.
  The file keeps the permissions it had.
* anything else is written through, never replaced: a character device (``/dev/null``, a terminal), a
  FIFO, and every path that is or leads through ``/dev`` or ``/proc`` (``/dev/stdout`` is the standard
  output rigidkin was given — a pipe, a terminal, or a file the shell opened, appended to with ``>>``).
"""

from __future__ import annotations

import contextlib
import os
import stat
import sys
import tempfile
from pathlib import Path

from . import tempfiles
from .errors import RigidkinError


class OutputError(RigidkinError):
    """An output file cannot be written: a missing folder, no permission, a full disk, an unknown format."""


#: Folders whose entries are the system's special files: written through, never renamed over (except the
#: ordinary files of /dev/shm, a memory file system).
SPECIAL_ROOTS = ("/dev/", "/proc/", "/sys/")
ORDINARY = ("/dev/shm/",)
_STANDARD = {"/dev/stdout": 1, "/dev/stderr": 2, "/proc/self/fd/1": 1, "/proc/self/fd/2": 2,
             "/dev/fd/1": 1, "/dev/fd/2": 2}


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
    if suffixes is not None and p.suffix.lower() not in suffixes and not through(p):
        raise OutputError(f"cannot write {what} to {p}: the extension '{p.suffix or '(none)'}' is not one of "
                          f"{', '.join(suffixes)}.", hint="Choose a file name with one of these.")
    if not os.path.lexists(p) and _special(p):
        raise OutputError(f"cannot write {what} to {p}: there is no such device.",
                          hint="Name an existing device (/dev/stdout, /dev/null) or a file in a folder of yours.")
    if through(p):
        if not os.access(p, os.W_OK) and _standard_fd(p) is None:
            raise OutputError(f"cannot write {what} to {p}: permission denied.",
                              hint="Write somewhere you may write to.")
        return p
    folder = Path(os.path.realpath(p)).parent
    if not folder.exists():
        raise OutputError(f"cannot write {what} to {p}: the folder {folder} does not exist.",
                          hint="Create the folder first, or write somewhere else.")
    if not folder.is_dir():
        raise OutputError(f"cannot write {what} to {p}: {folder} is not a folder.")
    if not os.access(folder, os.W_OK):
        raise OutputError(f"cannot write {what} to {p}: permission denied (the folder {folder} is not writable).",
                          hint="Write somewhere you may write to.")
    return p


def _hops(p: Path) -> list[str]:
    """``p`` and every path its chain of links passes through (absolute, at most 40 hops)."""
    hops, cur = [], os.path.abspath(p)
    for _ in range(40):
        hops.append(cur)
        try:
            target = os.readlink(cur)
        except OSError:
            break
        cur = os.path.normpath(os.path.join(os.path.dirname(cur), target))
    return hops


def _special(p: Path) -> bool:
    """``p`` is, or leads through, a folder of special files."""
    return any(h.startswith(SPECIAL_ROOTS) and not h.startswith(ORDINARY) for h in _hops(p))


def through(path) -> bool:
    """``path`` is written through, never replaced: it exists and is not a regular file, or it is (or leads
    through) a special folder such as ``/dev`` or ``/proc``."""
    p = Path(path)
    if _special(p):
        return os.path.lexists(p)
    try:
        return not stat.S_ISREG(os.stat(p).st_mode)
    except OSError:
        return False


def _standard_fd(p: Path) -> int | None:
    """The descriptor when ``p`` names one of this process's open files (``/dev/stdout``, ``/dev/fd/3``,
    ``/proc/self/fd/1``): written on the descriptor itself, at its offset, appending if it appends."""
    for h in _hops(p):
        if h in _STANDARD:
            return _STANDARD[h]
        for prefix in ("/dev/fd/", "/proc/self/fd/", f"/proc/{os.getpid()}/fd/"):
            if h.startswith(prefix) and h[len(prefix):].isdigit():
                return int(h[len(prefix):])
    return None


def identity(path) -> tuple:
    """What file ``path`` is: (device, inode) when it exists, else its resolved path."""
    try:
        st = os.stat(path)
        return ("file", st.st_dev, st.st_ino)
    except OSError:
        return ("new", os.path.realpath(path))


def check_outputs(outputs: dict, inputs=()) -> None:
    """Refuse, before anything runs, an output that is one of the ``inputs`` (the problem file, a worksheet,
    every file they name) and two outputs that are one file.  ``outputs`` maps an option (``--csv``) to its
    path (None: not asked for).  Devices (``/dev/null``, a terminal) may be named by several outputs."""
    seen: dict[tuple, str] = {}
    ins = {}
    for i in inputs:
        if i is not None and os.path.exists(i):
            ins[identity(i)] = str(i)
    for option, path in outputs.items():
        if path is None:
            continue
        ident = identity(path)
        if ident in ins:
            raise OutputError(f"{option} {path} is {ins[ident]}, an input of this command: writing there would "
                              "replace it. Nothing was run.", hint="Write the output to another file.")
        try:
            shared = stat.S_ISCHR(os.stat(path).st_mode)
        except OSError:
            shared = False
        if ident in seen and not shared:
            raise OutputError(f"{option} {path} and {seen[ident]} are the same file: one would replace the other. "
                              "Nothing was run.", hint="Give each output its own file name.")
        seen[ident] = f"{option} {path}"


def unique_columns(pairs, reserved=()) -> dict:
    """The (name, values) ``pairs`` as a dict, refusing a name that appears twice or is one of ``reserved``
    (a column of the writer's own): no column of an output may silently replace another."""
    out: dict = {}
    for name, values in pairs:
        if name in out or name in reserved:
            raise OutputError(f"two columns of the output would be named '{name}': one would be lost.",
                              hint="Rename the parameter, coordinate or reaction of that name in the problem.")
        out[name] = values
    return out


@contextlib.contextmanager
def writing(path, what: str, binary: bool = False, suffixes: tuple[str, ...] | None = None):
    """A file object for ``path``: text (UTF-8, no newline translation) or ``binary``.

    A regular file: the content goes to a temporary file beside it, renamed over ``path`` when the block
    ends without an error; on any error or signal the temporary file is removed.  Anything else is written
    through (see the module docstring).  An OSError becomes an OutputError with the path and the reason
    (exit status 2 at the command line).
    """
    p = check_target(path, what, suffixes)
    mode, kw = ("wb", {}) if binary else ("w", {"encoding": "utf-8", "newline": ""})
    if through(p):
        try:
            with _open_through(p, binary) as f:
                yield f
        except OSError as exc:
            raise _error(exc, what, p) from None
        return
    real = Path(os.path.realpath(p))               # a link to a file stays a link: its target is replaced
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(dir=real.parent, prefix=".rigidkin-", suffix=".part")
        tempfiles.register(tmp)
        with os.fdopen(fd, mode, **kw) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        _chmod_like(tmp, real)
        os.replace(tmp, real)
        tempfiles.release(tmp)
        tmp = None
    except OSError as exc:
        raise _error(exc, what, p) from None
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
            tempfiles.release(tmp)


@contextlib.contextmanager
def _open_through(p: Path, binary: bool):
    """A device, a FIFO, the standard output: opened for writing without truncating or replacing it (the
    standard output and error are written on their own descriptors, so ``>> log`` appends)."""
    n = _standard_fd(p)
    if n is not None:
        with contextlib.suppress(OSError, ValueError):
            (sys.stdout if n == 1 else sys.stderr).flush()
        fd = os.dup(n)
    else:                                      # a device or a FIFO; a regular file behind /proc is truncated
        regular = stat.S_ISREG(os.stat(p).st_mode)
        fd = os.open(p, os.O_WRONLY | getattr(os, "O_NOCTTY", 0) | (os.O_TRUNC if regular else 0))
    kw = {} if binary else {"encoding": "utf-8", "newline": ""}
    with os.fdopen(fd, "wb" if binary else "w", **kw) as f:
        yield f


def write_text(path, text: str, what: str) -> Path:
    """Write ``text`` to ``path`` whole or not at all (see :func:`writing`)."""
    with writing(path, what) as f:
        f.write(text)
    return Path(path)


def write_bytes(path, data: bytes, what: str, suffixes: tuple[str, ...] | None = None) -> Path:
    """Write ``data`` to ``path`` whole or not at all (see :func:`writing`)."""
    with writing(path, what, binary=True, suffixes=suffixes) as f:
        f.write(data)
    return Path(path)


def _error(exc: OSError, what: str, p: Path) -> OutputError:
    reason = exc.strerror or str(exc) or type(exc).__name__
    return OutputError(f"cannot write {what} to {p}: {reason[:1].lower() + reason[1:]}.",
                       hint="Nothing was written there (a file that was there is as it was); free some space or "
                            "choose another place.")


def _chmod_like(tmp: str, target: Path) -> None:
    """The permissions of the file replaced, or those a newly created file gets (mkstemp makes it private)."""
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        mask = os.umask(0)
        os.umask(mask)
        mode = 0o666 & ~mask
    with contextlib.suppress(OSError):
        os.chmod(tmp, mode)
