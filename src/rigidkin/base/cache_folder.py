"""The cache folder on disk: where the derivations (and pint's parsed unit definitions) are kept.

``$RIGIDKIN_CACHE``, else ``$XDG_CACHE_HOME/rigidkin``, else ``~/.cache/rigidkin``; the derivations in its
``derivations/`` folder.  ``RIGIDKIN_NO_CACHE=1`` leaves it alone.  A folder is used only when it is ours
and private (:mod:`rigidkin.base.private_files`); the derivation cache (:mod:`rigidkin.io.derivation_cache`)
and the unit registry (:func:`rigidkin.base.units.registry`) both find their place here.
"""

from __future__ import annotations

import contextlib
import os
import threading
import warnings
from pathlib import Path

from .private_files import folder_problem, unsafe_ancestor


def disabled_by_env() -> bool:
    """``RIGIDKIN_NO_CACHE`` is set (to anything but 0, no or false): the cache is left alone."""
    return os.environ.get("RIGIDKIN_NO_CACHE", "").strip().lower() not in ("", "0", "no", "false")


def cache_dir() -> Path:
    """The cache folder: ``$RIGIDKIN_CACHE``, else ``$XDG_CACHE_HOME/rigidkin``, else ``~/.cache/rigidkin``
    (the same as the compiled-code cache, :func:`rigidkin.numeric.compiled.cache.cache_dir`)."""
    env = os.environ.get("RIGIDKIN_CACHE")
    if env:
        return Path(env).expanduser()
    return Path(os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")) / "rigidkin"


_FAULTS: set[str] = set()
_SAY: list = []                 # the running command's printer of one stderr line (cli), if any
_LOCK = threading.Lock()        # compiled batches and sweeps may meet a fault in several threads at once


def fault(where, reason: str) -> None:
    """A cache that cannot be used (read-only, full, vanished, a folder where a file should be): one line
    on stderr (once per command) and the command runs on without it."""
    say_once(f"the cache at {where} cannot be used ({reason}); running without the cache.", "fault")


def new_run() -> None:
    """A new run starts (Python use): its first cache fault is said again."""
    with _LOCK:
        _FAULTS.clear()


@contextlib.contextmanager
def one_command(say):
    """A command runs: each of its cache faults is said once, by ``say(message)`` (one line on its stderr),
    whatever the warnings filter is (``always`` would repeat a warning, ``default`` hide it in the next
    command of the same process, a caller's ``catch_warnings`` swallow it)."""
    with _LOCK:
        _FAULTS.clear()
        before = _SAY[:]
        _SAY[:] = [say]
    try:
        yield
    finally:
        with _LOCK:
            _SAY[:] = before
            _FAULTS.clear()


def say_once(message: str, kind: str | None = None) -> None:
    """A cache fault said once per command (:func:`one_command`, :func:`new_run`; per ``kind``, else per
    message): by the command's printer, or outside a command as a RuntimeWarning."""
    with _LOCK:
        if (kind or message) in _FAULTS:
            return
        _FAULTS.add(kind or message)
        say = _SAY[0] if _SAY else None
    if say is not None:
        say(message)
    else:
        warnings.warn(message, RuntimeWarning, stacklevel=3)


def folder(quiet: bool = False) -> Path | None:
    """The entries' folder, made and checked private; None (with a warning, unless ``quiet``: the caller says
    nothing about it) when it cannot be used safely."""
    base = Path(os.path.realpath(cache_dir()))           # a link is judged by where it leads
    where = base / "derivations"
    try:
        if not os.path.lexists(base):
            base.parent.mkdir(parents=True, exist_ok=True)
            base.mkdir(mode=0o700, exist_ok=True)
        why = folder_problem(base) or unsafe_ancestor(base)
        if not why:
            if not os.path.lexists(where):
                where.mkdir(mode=0o700, exist_ok=True)
            why = folder_problem(where)
            if not why and os.lstat(where).st_mode & 0o077:
                os.chmod(where, 0o700)                   # our own folder: make it private
    except OSError as exc:
        if not quiet:
            fault(base, exc.strerror or str(exc))
        return None
    if why:
        if quiet:
            return None
        if why.endswith("is not a folder"):         # a file where the folder should be: a fault, not a threat
            fault(why.removesuffix(" is not a folder"), "it is not a folder")
        else:
            say_once(f"{why}, so the derivation cache is not used (set RIGIDKIN_CACHE to a folder of your own).")
        return None
    return where
