"""The derivation cache: a problem derived once and read back by the next command, safely.

Every test runs the command line in-process with its own cache folder; ``load_system`` is replaced
by one that fails when the test expects the problem to come from the cache, so "read from the cache"
is observed, not assumed.  The tamper cases check that an entry that is not exactly ours is never
unpickled (a pickle that would create a marker file does not) and is derived again.
"""

from __future__ import annotations

import os
import pickle
import shutil
import stat
import warnings

import pytest

from rigidkin.cli import main
from rigidkin.commands import common
from rigidkin.derive.derivation import derivation_of
from rigidkin.io import derivation_cache as dc


@pytest.fixture(scope="module")
def seeded(tmp_path_factory):
    """A cache folder holding the ladder as ``solve`` leaves it (made once for the module)."""
    folder = tmp_path_factory.mktemp("seed") / "cache"
    mp = pytest.MonkeyPatch()
    mp.setenv("RIGIDKIN_CACHE", str(folder))
    mp.delenv("RIGIDKIN_NO_CACHE", raising=False)
    mp.setattr(dc, "_code_fingerprint", lambda: b"fixed for the test")
    try:
        assert main(["solve", "ladder"]) == 0
    finally:
        mp.undo()
    return folder


@pytest.fixture
def cache(seeded, tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    shutil.copytree(seeded, folder)
    monkeypatch.setenv("RIGIDKIN_CACHE", str(folder))
    monkeypatch.delenv("RIGIDKIN_NO_CACHE", raising=False)
    monkeypatch.setattr(dc, "_code_fingerprint", lambda: b"fixed for the test")
    return folder


def _entry(folder):
    return folder / "derivations" / f"{dc.key_of('ladder')}.pkl"


def _loads(monkeypatch) -> list:
    """Count the problems loaded from their file (not from the cache)."""
    calls, real = [], common.load_system
    monkeypatch.setattr(common, "load_system", lambda p: calls.append(getattr(p, "problem", p)) or real(p))
    return calls


def _solve(capsys, *extra) -> str:
    capsys.readouterr()
    assert main(["solve", "ladder", *extra]) == 0
    return capsys.readouterr().out


def test_solve_reads_what_the_first_solve_derived(cache, monkeypatch, capsys):
    entry = _entry(cache)
    assert entry.is_file()
    loads = _loads(monkeypatch)
    cached = _solve(capsys)
    assert loads == []                                       # from the cache
    fresh = _solve(capsys, "--no-cache")
    assert loads == ["ladder"] and cached == fresh           # the same text as a fresh derivation
    assert "acos(2/3)" in cached.replace(" ", "") or "48.19" in cached


def test_the_folder_and_the_files_are_private(cache):
    folder = cache / "derivations"
    assert stat.S_IMODE(folder.stat().st_mode) == 0o700
    for f in folder.iterdir():
        st = os.lstat(f)
        assert stat.S_ISREG(st.st_mode) and stat.S_IMODE(st.st_mode) == 0o600 and st.st_uid == os.getuid()
    assert len((folder / dc.SECRET_NAME).read_bytes()) == 32


def test_no_cache_neither_reads_nor_writes(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("RIGIDKIN_CACHE", str(tmp_path / "c"))
    monkeypatch.delenv("RIGIDKIN_NO_CACHE", raising=False)
    _solve(capsys, "--no-cache", "--no-answers")
    assert not (tmp_path / "c").exists()
    monkeypatch.setenv("RIGIDKIN_NO_CACHE", "1")
    _solve(capsys, "--no-answers")
    assert not (tmp_path / "c").exists()


def test_simulate_and_check_derive_nothing_again(cache, monkeypatch, capsys):
    loads = _loads(monkeypatch)
    capsys.readouterr()
    assert main(["simulate", "ladder", "--t-end", "0.5", "--json"]) == 0
    cached = capsys.readouterr().out
    assert loads == []
    assert main(["simulate", "ladder", "--t-end", "0.5", "--json", "--no-cache"]) == 0
    assert capsys.readouterr().out == cached and loads == ["ladder"]
    assert main(["check", "ladder", "--laws", "lagrange", "--no-dimensions"]) == 0
    assert loads == ["ladder"]
    # what check derived (the Lagrange equations) is in the entry now
    entry = dc.read(cache / "derivations", dc.key_of("ladder"))
    assert any(isinstance(k, tuple) and k[:2] == ("solution", "lagrange")
               for k in derivation_of(entry["system"]).inventory())


def _tamper_then_solve(cache, monkeypatch, capsys, change) -> list:
    entry = _entry(cache)
    change(entry)
    loads = _loads(monkeypatch)
    _solve(capsys, "--no-answers")
    return loads


def _flip_last_byte(entry):
    data = bytearray(entry.read_bytes())
    data[-1] ^= 1
    entry.write_bytes(bytes(data))


def test_a_changed_byte_is_refused_and_the_entry_rebuilt(cache, monkeypatch, capsys):
    assert _tamper_then_solve(cache, monkeypatch, capsys, _flip_last_byte) == ["ladder"]
    assert dc.read(cache / "derivations", dc.key_of("ladder")) is not None     # written anew, valid


class _Marker:
    """A pickle that creates a file when loaded (what an attacker's entry would do)."""

    def __init__(self, path):
        self.path = str(path)

    def __reduce__(self):
        return (open, (self.path, "w"))


@pytest.mark.parametrize("how", ["no-mac", "wrong-key", "group-writable", "link"])
def test_a_planted_pickle_is_never_loaded(cache, tmp_path, monkeypatch, capsys, how):
    marker = tmp_path / "pwned"
    payload = pickle.dumps({"system": _Marker(marker)})
    folder = cache / "derivations"
    key = dc.key_of("ladder")

    def plant(entry):
        if how == "no-mac":
            entry.write_bytes(dc.MAGIC + b"0" * 64 + b"\n" + payload)
        elif how == "wrong-key":
            entry.write_bytes(dc.MAGIC + dc._mac(os.urandom(32), key, payload) + b"\n" + payload)
        elif how == "group-writable":          # correctly signed, but others could have changed it
            entry.write_bytes(dc.MAGIC + dc._mac(dc.secret(folder), key, payload) + b"\n" + payload)
            os.chmod(entry, 0o666)
        else:                                   # a link to a correctly signed file elsewhere
            elsewhere = tmp_path / "elsewhere.pkl"
            elsewhere.write_bytes(dc.MAGIC + dc._mac(dc.secret(folder), key, payload) + b"\n" + payload)
            os.chmod(elsewhere, 0o600)
            entry.unlink()
            entry.symlink_to(elsewhere)

    assert _tamper_then_solve(cache, monkeypatch, capsys, plant) == ["ladder"]
    assert not marker.exists()
    assert not _entry(cache).is_symlink()


def test_a_secret_others_can_read_voids_the_entries(cache, monkeypatch, capsys):
    def expose(entry):
        os.chmod(entry.parent / dc.SECRET_NAME, 0o644)

    assert _tamper_then_solve(cache, monkeypatch, capsys, expose) == ["ladder"]
    assert stat.S_IMODE((cache / "derivations" / dc.SECRET_NAME).stat().st_mode) == 0o600


@pytest.mark.parametrize("mode", [0o777, 0o1777], ids=["0777", "1777-sticky"])
def test_a_world_writable_cache_folder_is_not_used(tmp_path, monkeypatch, capsys, mode):
    shared = tmp_path / "shared"
    shared.mkdir()
    os.chmod(shared, mode)
    monkeypatch.setenv("RIGIDKIN_CACHE", str(shared))
    monkeypatch.delenv("RIGIDKIN_NO_CACHE", raising=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert dc.folder() is None
    assert any("writable by every user" in str(w.message) for w in caught)
    capsys.readouterr()
    assert main(["solve", "ladder", "--no-answers"]) == 0
    assert "the derivation cache is not used" in capsys.readouterr().err
    assert not list(shared.iterdir())


def test_a_changed_file_is_a_new_entry(tmp_path, cache):
    from rigidkin import examples

    card = tmp_path / "ladder.toml"
    card.write_bytes((examples.HERE / "ladder.toml").read_bytes())
    first = dc.key_of(str(card))
    card.write_bytes(card.read_bytes() + b"\n# a comment\n")
    assert dc.key_of(str(card)) != first and dc.key_of("ladder") != first
    assert dc.key_of(str(tmp_path / "missing.toml")) is None


def test_a_repeated_solve_prints_the_kept_output(cache, monkeypatch, capsys):
    outputs = list((cache / "derivations").glob("*.out"))
    assert len(outputs) == 1                                  # written by the first solve (text format)
    monkeypatch.setattr(dc, "read", lambda *a: pytest.fail("the derivation was read"))
    kept = _solve(capsys)
    monkeypatch.undo()
    assert kept == _solve(capsys, "--no-cache")


def test_a_changed_output_is_refused(cache, monkeypatch, capsys):
    (out,) = (cache / "derivations").glob("*.out")
    out.write_bytes(out.read_bytes().replace(b"acos", b"asin"))
    loads = _loads(monkeypatch)
    text = _solve(capsys)
    assert "asin(2/3)" not in text.replace(" ", "") and loads == []    # derived again, from the kept derivation


@pytest.mark.slow
def test_a_report_after_a_check_reads_as_a_fresh_one(cache, tmp_path, capsys):
    # check records its verdicts in the solution's trace; the cache keeps the derivation without them
    assert main(["check", "ladder", "--laws", "lagrange", "--no-dimensions"]) == 0
    cached, fresh = tmp_path / "cached.html", tmp_path / "fresh.html"
    assert main(["report", "ladder", "-o", str(cached), "--no-figures"]) == 0
    assert main(["report", "ladder", "-o", str(fresh), "--no-figures", "--no-cache"]) == 0
    assert cached.read_bytes() == fresh.read_bytes()
