"""The per-user key of the caches and the MACs made with it: nothing is loaded from a cache folder unless
this user's rigidkin wrote it.

The key is 32 random bytes in ``secret.key`` (a regular file of ours, mode 0600) in the cache folder; a
key that is not exactly that is made anew, which voids every entry signed with the old one.  A MAC is
HMAC-SHA256 under the key over a name (what the entry is for) and the bytes: a file copied from another
entry, or recomputed with a plain hash, does not pass.  A key that cannot be read or written (a folder
named ``secret.key``, a read-only or full disk) is None: the caller runs without its cache.
"""

from __future__ import annotations

import hashlib
import hmac
import os
from pathlib import Path

from .private_files import regular_and_ours, write_private

SECRET_NAME = "secret.key"


def secret(where: Path) -> bytes | None:
    """The key of the cache folder ``where`` (made when missing or not exactly ours); None when it cannot be
    read or made."""
    path = Path(where) / SECRET_NAME
    if regular_and_ours(path, 0o077):
        try:
            key = path.read_bytes()
        except OSError:
            key = b""
        if len(key) == 32:
            return key
    key = os.urandom(32)
    try:
        write_private(path, key)
    except OSError:
        return None
    return key


def mac(key: bytes, name: str, payload: bytes) -> bytes:
    """The hex HMAC-SHA256 of ``payload`` for ``name`` under ``key`` (64 ASCII bytes)."""
    return hmac.new(key, name.encode() + b"\0" + payload, hashlib.sha256).hexdigest().encode()


def matches(key: bytes, name: str, payload: bytes, tag: bytes) -> bool:
    """``tag`` is the MAC of ``payload`` for ``name`` (compared in constant time)."""
    return hmac.compare_digest(tag, mac(key, name, payload))
