"""Files and folders of this user only: the checks both caches make before they trust what is on disk.

A cache that loads what it finds (a compiled library, a pickled derivation) must know that no other user
of the machine could have put it there: the folder is ours and writable by no one else, no folder above it
lets another user swap it, and each file is a regular file of ours written atomically with mode 0600.
"""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

from . import tempfiles


def uid() -> int:
    """This process's user id (-1 where the platform has none)."""
    return os.getuid() if hasattr(os, "getuid") else -1


def folder_problem(folder: Path, st: os.stat_result | None = None) -> str:
    """Why ``folder`` itself is not private to us ("" when it is)."""
    st = os.lstat(folder) if st is None else st
    if not stat.S_ISDIR(st.st_mode):
        return f"{folder} is not a folder"
    if st.st_mode & stat.S_IWOTH:
        return f"{folder} is writable by every user of this machine (mode {stat.filemode(st.st_mode)})"
    if uid() >= 0 and st.st_uid != uid():
        return f"{folder} belongs to another user (uid {st.st_uid})"
    return ""


def unsafe_ancestor(folder: Path) -> str:
    """A folder above ``folder`` through which another user could swap it, or ""."""
    for parent in Path(os.path.abspath(folder)).parents:
        try:
            st = os.stat(parent)
        except OSError:
            continue
        if uid() >= 0 and st.st_uid not in (0, uid()):
            return f"{parent} belongs to another user (uid {st.st_uid})"
        if st.st_mode & stat.S_IWOTH and not st.st_mode & stat.S_ISVTX:
            return f"{parent} is writable by every user of this machine"
    return ""


def regular_and_ours(path: Path, mode_mask: int = stat.S_IWGRP | stat.S_IWOTH) -> bool:
    """``path`` is a regular file (not a link) of ours with none of the ``mode_mask`` bits set."""
    try:
        st = os.lstat(path)
    except OSError:
        return False
    return stat.S_ISREG(st.st_mode) and (uid() < 0 or st.st_uid == uid()) and not st.st_mode & mode_mask


def write_private(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically, mode 0600 (a temporary file of ours renamed over it)."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
    tempfiles.register(tmp)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    finally:
        tempfiles.release(tmp)
