"""The compiled-code cache: shared libraries built from our own generated C, safe on a shared machine.

Where: ``$RIGIDKIN_CACHE``, else ``$XDG_CACHE_HOME/rigidkin``, else ``~/.cache/rigidkin``.  The folder
is created private (mode 0700).  A library ``rk_<digest>.so`` is named by the hash of the source it is
built from, the compiler and the flags; beside it ``rk_<digest>.c`` (the source) and
``rk_<digest>.sha256`` (the digest and the hash of the library's bytes).  A library is loaded only when

* the folder is owned by the user and writable by no one else (the folder ``$RIGIDKIN_CACHE`` names is
  refused when others may write to it: a world-writable folder such as /tmp, or one owned by someone else);
* the library, its source and its record are regular files (no links), owned by the user and writable
  by no one else;
* the stored source is exactly the source asked for, and the record is the HMAC-SHA256, under this
  user's key (``secret.key`` in the folder, :mod:`rigidkin.base.signing`), of the digest, the source and
  the library's bytes: a library swapped in with a recomputed plain hash does not pass.

The verified bytes are copied into a private folder of this process and loaded from there, so the file
checked is the file loaded.  Anything else is not loaded: the library is rebuilt (in the cache when the
cache folder is ours, else in a private temporary folder of this process).  A cache folder that cannot be
used (read-only, full, removed while running) is said in one warning and the library built privately.
The compiler runs on our own generated source only, with
a fixed argument list and no shell.
"""

from __future__ import annotations

import atexit
import contextlib
import hashlib
import hmac
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import threading
import warnings
from pathlib import Path

from ...base import signing, tempfiles
from ...base.cache_folder import fault
from ...base.errors import RigidkinError
from ...base.private_files import folder_problem, regular_and_ours, unsafe_ancestor, write_private


class CacheError(RigidkinError):
    """The code cache cannot be used safely."""


_LOADED: dict[str, tuple] = {}
_LOCK = threading.Lock()
_PRIVATE: list[Path] = []


def cache_dir() -> Path:
    """Where compiled models are kept: ``$RIGIDKIN_CACHE`` or ``~/.cache/rigidkin`` (XDG)."""
    env = os.environ.get("RIGIDKIN_CACHE")
    if env:
        return Path(env).expanduser()
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "rigidkin"


def compiler() -> str | None:
    """The C compiler to use ($CC, else cc/gcc/clang on the PATH), or None."""
    for name in (os.environ.get("CC"), "cc", "gcc", "clang"):
        if name and shutil.which(name):
            return shutil.which(name)
    return None


def checked_folder() -> Path:
    """The cache folder, made and checked private (see the module docstring).

    ``$RIGIDKIN_CACHE`` naming a folder others may write to (or one of someone else's) is refused with a
    :class:`CacheError`; the default folder in that state is replaced by a private temporary one.
    """
    folder = Path(os.path.realpath(cache_dir()))         # a link is judged by where it leads
    explicit = bool(os.environ.get("RIGIDKIN_CACHE"))
    try:
        st = os.lstat(folder)
    except FileNotFoundError:
        st = None
    except OSError as exc:
        raise CacheError(f"the code cache folder {folder} cannot be read ({exc.strerror}).",
                         hint="Set RIGIDKIN_CACHE to a folder of your own.") from None
    if st is None:
        try:
            folder.parent.mkdir(parents=True, exist_ok=True)
            folder.mkdir(mode=0o700)
        except FileExistsError:
            pass
        except OSError as exc:
            fault(folder, exc.strerror or str(exc))
            return private_folder()
        try:
            st = os.lstat(folder)
        except OSError as exc:
            fault(folder, exc.strerror or str(exc))
            return private_folder()
    if not stat.S_ISDIR(st.st_mode):                  # a file where the folder should be: a fault, not a threat
        fault(folder, "it is not a folder")
        return private_folder()
    why = folder_problem(folder, st) or unsafe_ancestor(folder)
    if why:
        if explicit:
            raise CacheError(f"{why}, so rigidkin keeps no compiled code there.", where="RIGIDKIN_CACHE",
                             hint="Another user could put a library there that rigidkin would load. Point "
                                  "RIGIDKIN_CACHE to a folder of your own (rigidkin creates it with mode 0700).")
        warnings.warn(f"the code cache is not private ({why}); compiling into a private temporary folder instead.",
                      RuntimeWarning, stacklevel=3)
        return private_folder()
    if st.st_mode & 0o077:
        try:
            os.chmod(folder, 0o700)            # our own folder: make it private
        except OSError:
            return private_folder()
    return folder


def private_folder() -> Path:
    """A folder of this process only (mode 0700), removed at exit."""
    if not _PRIVATE or not _PRIVATE[0].is_dir():       # none yet, or removed (a signal's cleanup)
        _PRIVATE.clear()
        p = Path(tempfile.mkdtemp(prefix="rigidkin-"))
        tempfiles.register(p)                       # removed on SIGTERM and SIGHUP too
        _PRIVATE.append(p)
        atexit.register(shutil.rmtree, p, True)
    return _PRIVATE[0]


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _record(key: bytes, digest: str, source: str, lib: bytes) -> str:
    """The record of a library: its digest and the MAC of the digest, source and library under ``key``."""
    tag = signing.mac(key, "compiled:" + digest, _sha(source.encode()).encode() + b"\0" + lib).decode()
    return f"{digest}\n{tag}\n"


def _trusted(folder: Path, digest: str, source: str) -> bytes | None:
    """The bytes of the cached library of ``digest`` when they may be loaded (see the module docstring)."""
    paths = [folder / f"rk_{digest}{ext}" for ext in (".so", ".c", ".sha256")]
    if not all(regular_and_ours(p) for p in paths):
        return None
    key = signing.secret(folder)
    if key is None:
        return None
    try:
        lib, src, rec = (p.read_bytes() for p in paths)
    except OSError:
        return None
    ok = src == source.encode() and hmac.compare_digest(rec, _record(key, digest, source, lib).encode())
    return lib if ok else None


def flags(size: int) -> list[str]:
    """Compiler flags for a source of ``size`` characters: -O3 for small models (the batch integrator's loops run
    about 30 % faster than at -O2, with bit-identical results: no fast-math, ISO C so no FMA contraction),
    -O2 for larger ones, -O1 for huge ones (compile time)."""
    opt = "-O3" if size < 100_000 else "-O2" if size < 400_000 else "-O1"
    return [opt, "-fPIC", "-shared", "-fno-math-errno", "-std=c99"]


def digest_of(source: str, cc: str | None, flag_list) -> str:
    return _sha("\0".join([source, cc or "", *flag_list, sys.platform]).encode())[:32]


def _compile(cc: str, flag_list: list[str], source: str, folder: Path, error) -> bytes:
    """Compile ``source`` in a fresh private folder inside ``folder``; the library's bytes.  A cache folder
    that fails (read-only, full, removed) is said once and the build done in this process's private folder."""
    if folder == private_folder():
        return _compile_in(cc, flag_list, source, folder, error)
    try:
        return _compile_in(cc, flag_list, source, folder, error)
    except OSError as exc:
        reason = exc.strerror or str(exc)
    except error:                                  # perhaps the folder (full, removed), perhaps the code: try once more
        reason = "the build could not be written there"
    lib = _compile_in(cc, flag_list, source, private_folder(), error)
    fault(folder, reason)
    return lib


def _compile_in(cc: str, flag_list: list[str], source: str, folder: Path, error) -> bytes:
    with tempfile.TemporaryDirectory(dir=folder, prefix=".build-") as tmp, _registered(tmp):
        src = Path(tmp) / "model.c"
        src.write_text(source)
        out = Path(tmp) / "model.so"
        run = subprocess.run([cc, *flag_list, "-o", str(out), str(src), "-lm"], capture_output=True, text=True,
                             timeout=900, shell=False, stdin=subprocess.DEVNULL)
        if run.returncode != 0:
            last = run.stderr.strip().splitlines()[-1][:300] if run.stderr.strip() else f"exit {run.returncode}"
            raise error(f"the C compiler failed on the generated code: {last}",
                        hint="This is a bug in rigidkin's code generator; the numpy backend still works "
                             "(backend='numpy').")
        return out.read_bytes()


@contextlib.contextmanager
def _registered(path):
    tempfiles.register(path)
    try:
        yield
    finally:
        tempfiles.release(path)


def build(source: str, cdef: str, error=CacheError):
    """Compile ``source`` to a shared library (cached, checked) and load it with cffi; returns (ffi, lib).

    ``source`` must be generated by rigidkin itself; ``error`` is the error class for a failed compile.
    """
    cc = compiler()
    if cc is None:
        raise error("no C compiler is available here.", hint="Install gcc, or use backend='numpy'.")
    flag_list = flags(len(source))
    digest = digest_of(source, cc, flag_list)
    with _LOCK:
        folder = checked_folder()                        # a few stats: refused even when already loaded
        if digest in _LOADED:
            return _LOADED[digest]
        lib = _trusted(folder, digest, source)
        if lib is None:
            lib = _compile(cc, flag_list, source, folder, error)
            key = signing.secret(folder) if folder != private_folder() else None
            if key is None and folder != private_folder():
                fault(folder / signing.SECRET_NAME, "the key of the cache cannot be read or written")
            if key is not None:
                try:
                    for ext, data in ((".c", source.encode()), (".so", lib),
                                      (".sha256", _record(key, digest, source, lib).encode())):
                        write_private(folder / f"rk_{digest}{ext}", data)
                except OSError as exc:                    # full, read-only, vanished: the library still loads
                    fault(folder, exc.strerror or str(exc))
        return _load_private(digest, lib, cdef)


def _load_private(digest: str, lib: bytes, cdef: str):
    """Load the library's (verified or just built) bytes from a copy in this process's private folder."""
    path = private_folder() / f"rk_{digest}.so"
    if not path.exists():
        write_private(path, lib)
    return _load(path, digest, cdef)


def _load(path: Path, digest: str, cdef: str):
    import cffi

    ffi = cffi.FFI()
    ffi.cdef(cdef)
    lib = ffi.dlopen(str(path))
    _LOADED[digest] = (ffi, lib)
    return ffi, lib
