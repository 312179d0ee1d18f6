"""The derivation cache: a problem derived once, read back by every later command on the same file.

What is kept: the System built from a problem file with the derivations it made (equations of motion
and reactions of every mode and law asked for so far, the kinematics), the parsed file and the
answers to its questions.  ``solve``, ``check``, ``simulate``, ``report`` and ``sweep`` on the same file
read one entry and add to it what they derive; the numbers given on the command line (``--set``,
``--initial``) are applied after the derivation, and modes and laws are looked up inside the entry.

Key: the SHA-256 of the problem file's bytes — exactly the bytes parsed: a command reads its file once
(:class:`rigidkin.io.load.Source`) — and its resolved path (a bundled example: its name and
file), rigidkin's version and a fingerprint of its code (size and time of every module), Python's and
sympy's versions.  A changed file, rigidkin or sympy gives a new entry.

Where: ``derivations/`` in the code cache folder (``$RIGIDKIN_CACHE``, else ``$XDG_CACHE_HOME/rigidkin``,
else ``~/.cache/rigidkin``).  ``--no-cache`` on a command, or ``RIGIDKIN_NO_CACHE=1``, leaves it alone.

Safety: an entry is a pickle, so it is read only when it is certainly one we wrote.  The folder must be
ours and private (mode 0700; ``$RIGIDKIN_CACHE`` naming a folder others may write to is not used, with
a warning); entries are written atomically (a temporary file renamed), mode 0600; an entry is read only
when it is a regular file (no link), ours, writable by no one else, and its HMAC-SHA256 — keyed by a
secret of 32 random bytes kept 0600 in the folder, over the entry's key and bytes — matches.  Anything
else is not unpickled: the problem is derived again and the entry replaced.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import os
import sys
import warnings
from pathlib import Path

from .. import __version__
from ..base import cache_folder, signing
from ..base.cache_folder import cache_dir, disabled_by_env, folder  # noqa: F401  (public here too)
from ..base.errors import RigidkinError
from ..base.private_files import regular_and_ours, write_private
from ..base.signing import SECRET_NAME
from ..base.trace import Trace
from .source import read_source

MAGIC = b"rigidkin-derivation-2\n"
MAX_ENTRY = 256 * 1024 * 1024            # bytes: a larger derivation is not kept
MAX_ENTRIES = 200                         # the oldest beyond these are removed when one is written
_CACHED = type(functools.cache(len))              # a memoized function (functools.cache) in what is kept


def secret(where: Path) -> bytes | None:
    """The folder's HMAC key (:func:`rigidkin.base.signing.secret`); None when it cannot be read or made."""
    key = signing.secret(where)
    if key is None:
        cache_folder.fault(where / SECRET_NAME, "the key of the cache cannot be read or written")
    return key


def _code_fingerprint() -> bytes:
    """Size and modification time of every module of rigidkin, and sympy's and cloudpickle's versions."""
    import importlib.util

    h = hashlib.sha256()
    root = Path(__file__).parent.parent          # the rigidkin package
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d != "__pycache__")
        for name in sorted(filenames):
            if name.endswith((".py", ".toml", ".json")):
                st = os.stat(os.path.join(dirpath, name))
                h.update(f"{os.path.relpath(os.path.join(dirpath, name), root)}\0{st.st_size}\0{st.st_mtime_ns}\n"
                         .encode())
    for package, release in (("sympy", "release.py"), ("cloudpickle", "__init__.py")):
        spec = importlib.util.find_spec(package)
        if spec is not None and spec.origin:
            try:
                h.update(package.encode() + (Path(spec.origin).parent / release).read_bytes())
            except OSError:
                h.update(package.encode())
    return h.digest()


def problem_source(problem) -> tuple[str, bytes] | None:
    """(resolved path or example name, bytes) of a problem (a name, a path, or a
    :class:`rigidkin.io.load.Source` already read); None: not cacheable (it cannot be read)."""
    try:
        source = read_source(problem)
    except RigidkinError:
        return None
    return source.name, source.data


def key_of(problem) -> str | None:
    """The entry's key: made from exactly the bytes that are parsed (pass the command's
    :class:`rigidkin.io.load.Source`; a name or path is read now)."""
    source = problem_source(problem)
    if source is None:
        return None
    name, data = source
    h = hashlib.sha256(MAGIC)
    for part in (__version__.encode(), sys.version.encode(), _code_fingerprint(), name.encode(),
                 hashlib.sha256(data).digest()):
        h.update(len(part).to_bytes(8, "little") + part)
    return h.hexdigest()


def _mac(secret_key: bytes, key: str, payload: bytes) -> bytes:
    return signing.mac(secret_key, key, payload)


def _read_signed(path: Path, key: str) -> bytes | None:
    """The payload of the file ``path`` if it is certainly ours (see the module docstring), else None (and a
    file that is there but not ours to trust is removed)."""
    if not path.exists() and not path.is_symlink():
        return None
    ok = regular_and_ours(path, 0o022)
    data = b""
    if ok:
        try:
            with open(path, "rb") as f:
                data = f.read(MAX_ENTRY + 1024)
        except OSError:
            ok = False
    head = len(MAGIC) + 64 + 1
    ok = ok and data.startswith(MAGIC) and len(data) > head and data[head - 1:head] == b"\n"
    secret_key = secret(path.parent) if ok else None
    if secret_key is not None and signing.matches(secret_key, key, data[head:], data[len(MAGIC):head - 1]):
        return data[head:]
    _remove(path)
    return None


def _write_signed(path: Path, key: str, payload: bytes) -> bool:
    """Write ``payload`` with its MAC atomically (mode 0600); False when it cannot be written."""
    if len(payload) > MAX_ENTRY:
        return False
    secret_key = secret(path.parent)
    if secret_key is None:
        return False
    try:
        write_private(path, MAGIC + _mac(secret_key, key, payload) + b"\n" + payload)
    except OSError as exc:
        cache_folder.fault(path, exc.strerror or str(exc))
        return False
    _prune(path.parent)
    return True


def read(where: Path, key: str) -> dict | None:
    """The derivation entry of ``key`` if it is certainly ours, else None."""
    payload = _read_signed(where / f"{key}.pkl", key)
    if payload is None:
        return None
    import pickle

    try:
        entry = pickle.loads(payload)          # authenticated: written by this user's rigidkin
    except Exception:
        entry = None
    if isinstance(entry, dict) and "system" in entry:
        return entry
    _remove(where / f"{key}.pkl")
    return None


def _remove(path: Path) -> None:
    with contextlib.suppress(OSError):
        path.unlink()


def kept_keys(system) -> frozenset:
    """What the system's derivation holds that is kept (:meth:`rigidkin.derive.derivation.Derivation.inventory`)."""
    derived = getattr(system, "_derived", None)
    return frozenset() if derived is None else frozenset(repr(k) for k in derived.inventory())


def dumps(entry: dict) -> bytes | None:
    """The entry's pickle: the System with its derivations only (numeric functions and compiled code are
    not kept); None when something in it cannot be pickled."""
    import copyreg
    import io

    try:
        import cloudpickle
    except ImportError:                   # a dependency of rigidkin; without it nothing is kept
        return None

    from .spec import ProblemSpec

    system = entry["system"]

    class Pickler(cloudpickle.Pickler):
        def reducer_override(self, obj):
            if obj is system:
                state = dict(obj.__dict__)
                derived = state.get("_derived")     # its symbolic stages (rigidkin.derive.derivation.Derivation)
                state["_derived"] = None if derived is None else derived.symbolic()
                state["_kinematic_equations"] = None
                return copyreg.__newobj__, (type(obj),), state
            if type(obj) is ProblemSpec and obj.data is not None:     # the schema's tree: pydantic, not needed
                state = dict(obj.__dict__)
                state["data"] = None
                return copyreg.__newobj__, (ProblemSpec,), state
            if type(obj) is Trace and any(st.section == "Checks" for st in obj.steps):
                state = dict(obj.__dict__)          # a cross-check's record: made again when one is asked for
                state["steps"] = [st for st in obj.steps if st.section != "Checks"]
                return copyreg.__newobj__, (Trace,), state
            if type(obj) is _CACHED and "<locals>" in getattr(obj, "__qualname__", ""):
                return functools.cache, (obj.__wrapped__,)        # a memoized closure: its code, not its memo
            return super().reducer_override(obj)

    buf = io.BytesIO()
    try:
        Pickler(buf, protocol=5).dump(entry)
    except Exception:
        return None
    return buf.getvalue()


def write(where: Path, key: str, entry: dict) -> bool:
    """Store the entry atomically (mode 0600); False when it cannot be pickled or is too large."""
    payload = dumps(entry)
    return payload is not None and _write_signed(where / f"{key}.pkl", key, payload)


def _output_name(key: str, options) -> str:
    return key + "-" + hashlib.sha256(repr(tuple(options)).encode()).hexdigest()[:24]


def read_kept(problem: str, options, suffix: str, use: bool = True) -> dict | None:
    """A JSON record kept for ``problem`` under these ``options`` (a tuple of what changes it) — what a
    command printed (``.out``), a sweep's numeric record (``.rec``) — when it is certainly ours; None
    otherwise.  Reads no derivation and imports no sympy."""
    if not use or disabled_by_env():
        return None
    key = key_of(problem)
    where = folder() if key else None
    if where is None:
        return None
    name = _output_name(key, options)
    payload = _read_signed(where / f"{name}{suffix}", name)
    if payload is None:
        return None
    import json

    try:
        out = json.loads(payload.decode())
    except ValueError:
        return None
    return out if isinstance(out, dict) else None


def write_kept(problem: str, options, suffix: str, record: dict, use: bool = True) -> bool:
    """Keep a JSON record for ``problem`` under these ``options`` (see :func:`read_kept`)."""
    if not use or disabled_by_env():
        return False
    key = key_of(problem)
    where = folder() if key else None
    if where is None:
        return False
    import json

    name = _output_name(key, options)
    try:
        payload = json.dumps(record, allow_nan=False).encode()
    except (TypeError, ValueError):
        return False
    return _write_signed(where / f"{name}{suffix}", name, payload)


def read_output(problem: str, options, use: bool = True) -> dict | None:
    """What a command printed for ``problem`` with these output ``options`` (a tuple of what changes the
    output), when it was kept: {"text": ..., "status": ...}; None otherwise.  A repeated ``rigidkin solve``
    prints at once."""
    out = read_kept(problem, options, ".out", use)
    if out is not None and isinstance(out.get("text"), str) and isinstance(out.get("status"), int):
        return out
    return None


def write_output(problem: str, options, text: str, status: int, use: bool = True) -> bool:
    """Keep what a command printed (see :func:`read_output`)."""
    return write_kept(problem, options, ".out", {"text": text, "status": status}, use)


def _prune(where: Path) -> None:
    try:
        entries = [e for e in os.scandir(where) if e.name.endswith((".pkl", ".out", ".rec"))
                   and e.is_file(follow_symlinks=False)]
        if len(entries) > MAX_ENTRIES:
            entries.sort(key=lambda e: e.stat(follow_symlinks=False).st_mtime)
            for e in entries[:len(entries) - MAX_ENTRIES]:
                _remove(Path(e.path))
    except OSError:
        pass


class CachedProblem:
    """A problem as a command uses it: ``system`` (with the derivations already cached), ``spec`` (the
    parsed file, None for a Python example) and ``answers`` (None until answered); ``save()`` stores
    whatever was derived since."""

    def __init__(self, problem, load, use: bool = True):
        """``problem`` is best the command's :class:`rigidkin.io.load.Source` (the bytes read once: the key is
        made from them and ``load()`` builds (system, spec) from them when the cache has no entry)."""
        self.problem = problem
        self.answers = None
        self.hit = False
        self._where = self._key = None
        self._seen: frozenset = frozenset()
        self._answers_seen = None
        if use and not disabled_by_env():
            self._key = key_of(problem)
            self._where = folder() if self._key else None
        entry = read(self._where, self._key) if self._where else None
        if entry is not None:
            self.system, self.spec, self.answers = entry["system"], entry.get("spec"), entry.get("answers")
            self.hit, self._seen, self._answers_seen = True, kept_keys(self.system), self.answers
            for message in getattr(self.spec, "reading_warnings", ()):   # said again: the file was read before
                warnings.warn(message, UserWarning, stacklevel=2)
        else:
            self.system, self.spec = load()

    def save(self) -> bool:
        """Write the entry when something new was derived or answered; True when written."""
        if self._where is None:
            return False
        seen = kept_keys(self.system)
        if seen <= self._seen and self.answers is self._answers_seen:
            return False
        entry = {"system": self.system, "spec": self.spec, "answers": self.answers}
        if write(self._where, self._key, entry):
            self._seen, self._answers_seen = seen, self.answers
            return True
        return False
