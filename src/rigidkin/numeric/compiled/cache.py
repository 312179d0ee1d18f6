"""The compiled-code cache: shared libraries built from our own generated C, safe on a shared machine.

Where: ``$RIGIDKIN_CACHE``, else ``$XDG_CACHE_HOME/rigidkin``, else ``~/.cache/rigidkin``.  The folder
is created private (mode 0700).  A library ``rk_<digest>.so`` is named by the hash of the source it is
built from, the compiler and the flags; beside it ``rk_<digest>.c`` (the source) and
``rk_<digest>.sha256`` (the digest and the hash of the library's bytes).  A library is loaded only when

* the folder is owned by the user and writable by no one else (the folder ``$RIGIDKIN_CACHE`` names is
  refused when others may write to it: a world-writable folder such as /tmp, or one owned by someone else);
* the library, its source and its record are regular files (no links), owned by the user and writable
  by no one else;
* the stored source is exactly the source asked for, and the record's hashes match the source and the
  library's bytes.

Anything else is not loaded: the library is rebuilt (in the cache when the cache folder is ours, else in
a private temporary folder of this process).  The compiler runs on our own generated source only, with
a fixed argument list and no shell.
"""

from __future__ import annotations

import atexit
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import warnings
from pathlib import Path

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
            raise CacheError(f"the code cache folder {folder} cannot be created ({exc.strerror}).",
                             hint="Set RIGIDKIN_CACHE to a writable folder of your own.") from None
        st = os.lstat(folder)
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
    if not _PRIVATE:
        p = Path(tempfile.mkdtemp(prefix="rigidkin-"))
        _PRIVATE.append(p)
        atexit.register(shutil.rmtree, p, True)
    return _PRIVATE[0]


def _sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _record(digest: str, lib: bytes) -> str:
    return f"{digest}\n{_sha(lib)}\n"


def _trusted(folder: Path, digest: str, source: str) -> bool:
    """True when the cached library of ``digest`` may be loaded (see the module docstring)."""
    paths = [folder / f"rk_{digest}{ext}" for ext in (".so", ".c", ".sha256")]
    if not all(regular_and_ours(p) for p in paths):
        return False
    try:
        lib, src, rec = (p.read_bytes() for p in paths)
    except OSError:
        return False
    return src == source.encode() and rec.decode(errors="replace") == _record(digest, lib)


def flags(size: int) -> list[str]:
    """Compiler flags for a source of ``size`` characters: -O3 for small models (the batch integrator's loops run
    about 30 % faster than at -O2, with bit-identical results: no fast-math, ISO C so no FMA contraction),
    -O2 for larger ones, -O1 for huge ones (compile time)."""
    opt = "-O3" if size < 100_000 else "-O2" if size < 400_000 else "-O1"
    return [opt, "-fPIC", "-shared", "-fno-math-errno", "-std=c99"]


def digest_of(source: str, cc: str | None, flag_list) -> str:
    return _sha("\0".join([source, cc or "", *flag_list, sys.platform]).encode())[:32]


def _compile(cc: str, flag_list: list[str], source: str, folder: Path, error) -> bytes:
    """Compile ``source`` in a fresh private folder inside ``folder``; the library's bytes."""
    with tempfile.TemporaryDirectory(dir=folder, prefix=".build-") as tmp:
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
        if not _trusted(folder, digest, source):
            lib = _compile(cc, flag_list, source, folder, error)
            for ext, data in ((".c", source.encode()), (".so", lib), (".sha256", _record(digest, lib).encode())):
                path = folder / f"rk_{digest}{ext}"
                try:
                    write_private(path, data)
                except OSError:                           # not ours to replace: use a private copy
                    return _load_private(digest, source, lib, cdef)
            if not _trusted(folder, digest, source):      # replaced under us: load a private copy
                return _load_private(digest, source, lib, cdef)
        return _load(folder / f"rk_{digest}.so", digest, cdef)


def _load_private(digest: str, source: str, lib: bytes, cdef: str):
    folder = private_folder()
    for ext, data in ((".c", source.encode()), (".so", lib), (".sha256", _record(digest, lib).encode())):
        write_private(folder / f"rk_{digest}{ext}", data)
    return _load(folder / f"rk_{digest}.so", digest, cdef)


def _load(path: Path, digest: str, cdef: str):
    import cffi

    ffi = cffi.FFI()
    ffi.cdef(cdef)
    lib = ffi.dlopen(str(path))
    _LOADED[digest] = (ffi, lib)
    return ffi, lib
