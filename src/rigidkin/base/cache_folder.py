"""The cache folder on disk: where the derivations (and pint's parsed unit definitions) are kept.

``$RIGIDKIN_CACHE``, else ``$XDG_CACHE_HOME/rigidkin``, else ``~/.cache/rigidkin``; the derivations in its
``derivations/`` folder.  ``RIGIDKIN_NO_CACHE=1`` leaves it alone.  A folder is used only when it is ours
and private (:mod:`rigidkin.base.private_files`); the derivation cache (:mod:`rigidkin.io.derivation_cache`)
and the unit registry (:func:`rigidkin.base.units.registry`) both find their place here.
"""

from __future__ import annotations

import os
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


def fault(where, reason: str) -> None:
    """A cache that cannot be used (read-only, full, vanished, a folder where a file should be): one line
    on stderr (a RuntimeWarning, once per command) and the command runs on without it."""
    say_once(f"the cache at {where} cannot be used ({reason}); running without the cache.", "fault")


def new_run() -> None:
    """A new command starts: its first cache fault is said again."""
    _FAULTS.clear()


def say_once(message: str, kind: str | None = None) -> None:
    """A RuntimeWarning about the cache, said once per command (:func:`new_run`; per ``kind``, else per message)."""
    if (kind or message) in _FAULTS:
        return
    _FAULTS.add(kind or message)
    warnings.warn(message, RuntimeWarning, stacklevel=3)


def folder() -> Path | None:
    """The entries' folder, made and checked private; None (with a warning) when it cannot be used safely."""
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
        fault(base, exc.strerror or str(exc))
        return None
    if why:
        if why.endswith("is not a folder"):         # a file where the folder should be: a fault, not a threat
            fault(why.removesuffix(" is not a folder"), "it is not a folder")
        else:
            say_once(f"{why}, so the derivation cache is not used (set RIGIDKIN_CACHE to a folder of your own).")
        return None
    return where
