"""pint's parsed unit definitions kept between commands, signed: no pickle is read that this user's rigidkin
did not write.

pint keeps its parsed definitions as pickles in a folder it is given.  rigidkin never gives pint the cache
folder itself: the files listed in a signed manifest (``pint/manifest``, the HMAC under the per-user key of
:mod:`rigidkin.base.signing` over every file's name and SHA-256) whose bytes match are copied into a fresh
private folder of this process, and pint reads that copy; what pint adds there is copied back with a new
manifest.  A file not in the manifest, changed, or not a regular file of ours is never given to pint.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import tempfile
from pathlib import Path

from . import cache_folder, signing, tempfiles
from .private_files import folder_problem, regular_and_ours, write_private

MANIFEST = "manifest"
MAGIC = b"rigidkin-pint-1\n"
MAX_FILE = 8 * 1024 * 1024


def kept_folder() -> Path | None:
    """``<cache>/pint`` (private, ours), or None where the cache is off, unsafe or unusable."""
    if cache_folder.disabled_by_env():
        return None
    where = cache_folder.folder(quiet=True)     # the derivation cache says why it is off when it is used
    if where is None:
        return None
    folder = where.parent / "pint"
    try:
        folder.mkdir(mode=0o700, exist_ok=True)
        return folder if not folder_problem(folder) else None
    except OSError:
        return None


def _manifest(folder: Path, key: bytes) -> dict:
    """The files the signed manifest lists ({name: sha256 hex}); {} when it is missing or not ours."""
    path = folder / MANIFEST
    if not regular_and_ours(path, 0o077):
        return {}
    try:
        data = path.read_bytes()
    except OSError:
        return {}
    head = len(MAGIC) + 64 + 1
    if not data.startswith(MAGIC) or len(data) <= head or not signing.matches(key, "pint", data[head:],
                                                                             data[len(MAGIC):head - 1]):
        return {}
    try:
        listed = json.loads(data[head:].decode())
    except ValueError:
        return {}
    ok = isinstance(listed, dict) and all(isinstance(k, str) and isinstance(v, str) for k, v in listed.items())
    return listed if ok else {}


def _plain(name: str) -> bool:
    return name not in ("", ".", "..", MANIFEST) and "/" not in name and "\0" not in name


@contextlib.contextmanager
def staged():
    """A private folder for pint holding the verified definitions (None: run without them); on leaving,
    what pint added is kept, signed."""
    folder = kept_folder()
    key = signing.secret(folder.parent / "derivations") if folder is not None else None
    if folder is None or key is None:
        yield None
        return
    listed = _manifest(folder, key)
    tmp = Path(tempfile.mkdtemp(prefix="rigidkin-units-"))
    tempfiles.register(tmp)
    try:
        given = {}
        for name, digest in listed.items():
            src = folder / name
            if not _plain(name) or not regular_and_ours(src, 0o077):
                continue
            try:
                data = src.read_bytes()
            except OSError:
                continue
            if len(data) <= MAX_FILE and hashlib.sha256(data).hexdigest() == digest:
                (tmp / name).write_bytes(data)
                given[name] = digest
        yield tmp
        _keep(folder, key, tmp, given)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
        tempfiles.release(tmp)


def _keep(folder: Path, key: bytes, tmp: Path, given: dict) -> None:
    """Copy back what pint wrote in ``tmp`` and sign the new list (nothing when nothing changed)."""
    now = {}
    for entry in os.scandir(tmp):
        if entry.is_file(follow_symlinks=False) and _plain(entry.name):
            data = Path(entry.path).read_bytes()
            now[entry.name] = (hashlib.sha256(data).hexdigest(), data)
    if {k: v[0] for k, v in now.items()} == given:
        return
    try:
        for name, (digest, data) in now.items():
            if given.get(name) != digest:
                write_private(folder / name, data)
        listed = json.dumps({k: v[0] for k, v in sorted(now.items())}).encode()
        write_private(folder / MANIFEST, MAGIC + signing.mac(key, "pint", listed) + b"\n" + listed)
    except OSError as exc:
        cache_folder.fault(folder, exc.strerror or str(exc))
