"""The caches under faults and tampering: nothing unpickled or loaded that this user's rigidkin did not write,
no entry for other equations, and every fault run uncached with one line on stderr (issue 28).

The reference for every command's output is the same command with ``--no-cache``.
"""

from __future__ import annotations

import errno
import os
import pickle
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import pytest
from helpers import rigidkin_env

from rigidkin.base import cache_folder, signing, unit_cache
from rigidkin.cli import main
from rigidkin.examples import HERE as EXAMPLES
from rigidkin.io import derivation_cache as dc
from rigidkin.io.load import load_system, read_source
from rigidkin.numeric.compiled import cache as compiled

LADDER = (EXAMPLES / "ladder.toml").read_bytes()


@pytest.fixture
def problem(tmp_path):
    p = tmp_path / "p.toml"
    p.write_bytes(LADDER)
    return p


def _run(capsys, argv) -> tuple[int, str, str]:
    capsys.readouterr()
    status = main(argv)
    out, err = capsys.readouterr()
    return status, out, err


class _Planted:
    """A pickle that, if ever unpickled, leaves a file behind."""

    def __init__(self, marker: Path):
        self.marker = marker

    def __reduce__(self):
        return (Path.touch, (self.marker,))


# pint's definitions ---------------------------------------------------------------------------------------
def test_a_planted_pickle_in_pint_s_cache_is_never_given_to_pint(cache, tmp_path):
    import pint

    with unit_cache.staged() as first:
        pint.UnitRegistry(cache_folder=first)
    folder = cache / "pint"
    pickles = sorted(folder.glob("*.pickle"))
    assert pickles and all((p.stat().st_mode & 0o077) == 0 for p in pickles)
    marker = tmp_path / "ran"
    planted = pickle.dumps(_Planted(marker))
    for p in pickles:
        p.write_bytes(planted)                  # the manifest's hashes no longer match
    (folder / "extra.pickle").write_bytes(planted)      # nor is this file listed
    with unit_cache.staged() as staged:
        given = sorted(x.name for x in staged.iterdir())
        reg = pint.UnitRegistry(cache_folder=staged)
    assert not marker.exists() and "extra.pickle" not in given and not any(n.endswith(".pickle") for n in given)
    assert reg("200 cm").to("m").magnitude == pytest.approx(2.0)
    # a manifest recomputed with plain hashes of the planted files (no key): still refused
    import hashlib
    import json

    listed = json.dumps({p.name: hashlib.sha256(planted).hexdigest() for p in pickles}).encode()
    (folder / "manifest").write_bytes(unit_cache.MAGIC + hashlib.sha256(listed).hexdigest().encode() + b"\n" + listed)
    for p in pickles:
        p.write_bytes(planted)
    with unit_cache.staged() as staged:
        assert not any(x.name.endswith(".pickle") for x in staged.iterdir())
        pint.UnitRegistry(cache_folder=staged)
    assert not marker.exists()


def test_pint_s_definitions_signed_are_used_again(cache):
    import pint

    with unit_cache.staged() as first:
        pint.UnitRegistry(cache_folder=first)
    with unit_cache.staged() as again:
        names = {x.name for x in again.iterdir()}
    listed = {p.name for p in (cache / "pint").iterdir()} - {"manifest"}
    assert names == listed and any(n.endswith(".pickle") for n in names)


# the compiled library -------------------------------------------------------------------------------------
SOURCE = "double twice(double x) { return 2.0 * x; }\n"
CDEF = "double twice(double x);"


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler")
def test_a_library_record_recomputed_without_the_key_is_not_trusted(cache, monkeypatch):
    monkeypatch.setattr(compiled, "_LOADED", {})
    ffi, lib = compiled.build(SOURCE, CDEF)
    assert lib.twice(1.5) == 3.0
    folder = compiled.checked_folder()
    digest = compiled.digest_of(SOURCE, compiled.compiler(), compiled.flags(len(SOURCE)))
    assert compiled._trusted(folder, digest, SOURCE) is not None
    rec = folder / f"rk_{digest}.sha256"
    so = (folder / f"rk_{digest}.so").read_bytes()
    rec.write_text(f"{digest}\n{compiled._sha(so)}\n")            # the old, unkeyed record of the same bytes
    assert compiled._trusted(folder, digest, SOURCE) is None
    other = compiled._record(os.urandom(32), digest, SOURCE, so)  # a MAC under another key
    rec.write_text(other)
    assert compiled._trusted(folder, digest, SOURCE) is None
    rec.write_text(compiled._record(signing.secret(folder), digest, SOURCE, so))
    assert compiled._trusted(folder, digest, SOURCE) == so


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler")
def test_a_cache_folder_that_is_a_file_builds_privately(tmp_path, monkeypatch, recwarn):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("RIGIDKIN_CACHE", str(blocker))
    monkeypatch.setattr(compiled, "_LOADED", {})
    cache_folder.new_run()
    ffi, lib = compiled.build(SOURCE, CDEF)
    assert lib.twice(2.0) == 4.0 and blocker.read_text() == "not a folder"
    assert sum("running without the cache" in str(w.message) for w in recwarn) == 1


# the derivation cache ------------------------------------------------------------------------------------
def test_a_file_changed_while_a_command_runs_never_gives_an_entry_for_other_equations(cache, problem):
    """The key is made from the bytes parsed: an edit after the read is a new file, with its own entry."""
    source = read_source(str(problem))
    problem.write_bytes(LADDER.replace(b"value = 10 }", b"value = 30 }"))      # m = 30 kg, saved by an editor
    derived = dc.CachedProblem(source, lambda: load_system(source))
    assert derived.system.parameter_info["m"].value == 10                 # built from the bytes read
    derived.system.solve()
    assert derived.save()
    entry = dc.read(dc.folder(), dc.key_of(source))
    assert entry is not None and entry["system"].parameter_info["m"].value == 10
    assert dc.key_of(str(problem)) != dc.key_of(source)
    assert dc.read(dc.folder(), dc.key_of(str(problem))) is None       # the edited file has no entry yet
    again = dc.CachedProblem(read_source(str(problem)), lambda: load_system(str(problem)))
    assert not again.hit and again.system.parameter_info["m"].value == 30


@pytest.mark.parametrize("fault", ["cache is a file", "secret.key is a folder", "disk full", "entry is a folder"])
def test_a_cache_fault_runs_uncached_with_one_line(cache, problem, capsys, monkeypatch, fault):
    status, fresh, _ = _run(capsys, ["solve", str(problem), "--no-cache"])
    assert status == 0
    if fault == "cache is a file":
        shutil.rmtree(cache, ignore_errors=True)        # pint's definitions may have been kept by the run above
        cache.write_text("x")
    else:
        assert _run(capsys, ["solve", str(problem)])[1] == fresh        # a cache made
        where = cache / "derivations"
        for entry in where.iterdir():
            if entry.name != "secret.key":
                entry.unlink()
        if fault == "secret.key is a folder":
            (where / "secret.key").unlink()
            (where / "secret.key").mkdir()
        elif fault == "entry is a folder":
            (where / f"{dc.key_of(str(problem))}.pkl").mkdir()
        else:
            def full(path, data):
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

            monkeypatch.setattr(dc, "write_private", full)
    status, out, err = _run(capsys, ["solve", str(problem)])
    assert status == 0 and out == fresh
    lines = [x for x in err.splitlines() if "cache" in x]
    assert len(lines) == 1 and "running without the cache" in lines[0], err
    assert "internal error" not in err


@pytest.mark.parametrize("action", ["default", "always", "ignore", "record"])
def test_a_cache_fault_is_one_line_in_every_command_whatever_the_warnings_filter(cache, problem, capsys, action):
    """``default`` hid the line in a second command of the same process, ``always`` (or a thread) could say it
    twice, a ``catch_warnings`` around the work (simulate records its RuntimeWarnings) swallowed it."""
    cache.write_text("x")
    with warnings.catch_warnings(record=action == "record"):
        warnings.simplefilter("always" if action == "record" else action)
        for argv in (["solve", str(problem)], ["solve", str(problem)], ["check", str(problem)],
                     ["simulate", str(problem), "--t-end", "0.05", "--points", "5"]):
            status, out, err = _run(capsys, argv)
            lines = [x for x in err.splitlines() if "running without the cache" in x]
            assert status == 0 and len(lines) == 1 and lines[0].startswith("rigidkin: warning: the cache at "), \
                (argv, err)
    assert cache.read_text() == "x"


def test_outside_a_command_a_cache_fault_is_a_warning_once_per_run(cache):
    cache.write_text("x")
    cache_folder.new_run()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert dc.folder() is None and dc.folder() is None
    assert ["running without the cache" in str(w.message) for w in caught] == [True]
    cache_folder.new_run()
    with pytest.warns(RuntimeWarning, match="running without the cache"):
        dc.folder()


def test_a_cache_folder_removed_while_running_is_no_error(cache, problem):
    derived = dc.CachedProblem(read_source(str(problem)), lambda: load_system(str(problem)))
    derived.system.solve()
    shutil.rmtree(cache)
    assert derived.save() is False                     # nothing kept, nothing raised


# concurrent runs ----------------------------------------------------------------------------------------
@pytest.mark.slow
def test_concurrent_runs_on_the_same_and_on_different_files(cache, problem, tmp_path, capsys):
    other = tmp_path / "q.toml"
    other.write_bytes(LADDER.replace(b"value = 2 }", b"value = 3 }"))      # l = 3 m
    expected = {}
    for p in (problem, other):
        status, expected[p], _ = _run(capsys, ["solve", str(p), "--no-cache", "--format", "json"])
        assert status == 0
    assert expected[problem] != expected[other]
    env = rigidkin_env(RIGIDKIN_CACHE=str(cache))
    env.pop("RIGIDKIN_NO_CACHE", None)
    for _ in range(2):                                     # a fresh cache, then one full of entries
        procs = [(p, subprocess.Popen([sys.executable, "-m", "rigidkin", "solve", str(p), "--format", "json"],
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env))
                 for p in (problem, problem, other, other)]
        for p, proc in procs:
            out, err = proc.communicate(timeout=600)
            assert proc.returncode == 0, err
            assert out == expected[p] and "cache" not in err
    assert not [x for x in (cache / "derivations").iterdir() if x.name.startswith(".tmp-")]
