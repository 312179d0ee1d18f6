"""The command line starts quickly and completes in the shell.

``--help`` and ``import rigidkin`` load none of the heavy libraries (each command imports what it uses
when it runs); argcomplete answers a completion request with the subcommands, a subcommand's options
and the bundled examples' names (its test variables: no shell needed).
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys

import pytest

HEAVY = ("sympy", "numpy", "scipy", "matplotlib", "pydantic", "pint", "dask", "rich", "cloudpickle")


def _modules_after(code: str) -> set[str]:
    out = subprocess.run([sys.executable, "-c", code + "\nimport sys; print(' '.join(sys.modules))"],
                         capture_output=True, text=True, timeout=60, check=True).stdout
    return {m.split(".")[0] for m in out.split()}


def test_help_and_import_load_no_heavy_library():
    loaded = _modules_after("import contextlib, io\nfrom rigidkin.cli import main\n"
                            "with contextlib.redirect_stdout(io.StringIO()): main(['--help'])\n"
                            "with contextlib.redirect_stdout(io.StringIO()): main(['simulate', '--help'])")
    assert not loaded & set(HEAVY), loaded & set(HEAVY)
    assert not _modules_after("import rigidkin") & set(HEAVY)


def test_list_builds_nothing():
    """``rigidkin list`` reads the examples' titles from their files: no sympy, no model built."""
    loaded = _modules_after("import contextlib, io\nfrom rigidkin.cli import main\n"
                            "with contextlib.redirect_stdout(io.StringIO()): main(['list'])")
    assert not loaded & set(HEAVY), loaded & set(HEAVY)


def test_the_public_names_still_load():
    import rigidkin as rk

    assert rk.System.__name__ == "System" and rk.shapes.SlenderRod and str(rk.t) == "t"
    assert {"System", "shapes", "Solution"} <= set(dir(rk))
    with pytest.raises(AttributeError):
        rk.no_such_name  # noqa: B018


def _complete(line: str, tmp_path) -> list[str]:
    out = tmp_path / "completions"
    env = {**os.environ, "_ARGCOMPLETE": "1", "COMP_LINE": line, "COMP_POINT": str(len(line)),
           "_ARGCOMPLETE_STDOUT_FILENAME": str(out), "_ARGCOMPLETE_IFS": "\n"}
    subprocess.run([sys.executable, "-m", "rigidkin"], env=env, cwd=tmp_path, timeout=60, check=True,
                   capture_output=True)
    return [w.strip() for w in out.read_text().split("\n") if w.strip()]


def test_completion_of_subcommands_options_and_examples(tmp_path):
    pytest.importorskip("argcomplete")
    assert set(_complete("rigidkin s", tmp_path)) == {"solve", "simulate", "sweep"}
    assert "--t-end" in _complete("rigidkin simulate ladder --t", tmp_path)
    assert set(_complete("rigidkin solve --format ", tmp_path)) == {"text", "latex", "markdown", "json"}
    (tmp_path / "my_card.toml").write_text("")
    (tmp_path / "notes.txt").write_text("")
    words = _complete("rigidkin solve ", tmp_path)
    assert {"ladder", "collar-rod", "my_card.toml"} <= set(words) and "notes.txt" not in words
    assert _complete("rigidkin check lad", tmp_path) == ["ladder"]


def test_units_load_without_dask_and_keep_pints_definitions(tmp_path):
    """pint's probe for dask is answered 'absent' (0.35 s), dask still imports afterwards where installed,
    and pint's parsed definitions are kept in the private cache folder (the next registry is faster)."""
    env = {**os.environ, "RIGIDKIN_CACHE": str(tmp_path / "cache")}
    env.pop("RIGIDKIN_NO_CACHE", None)
    code = ("import sys, importlib.util\nfrom rigidkin.base.units import registry, to_si\nr = registry()\n"
            "assert abs(to_si('30 cm', 'm', 'x') - 0.3) < 1e-15\n"
            "print('dask' in sys.modules)\n"
            "if importlib.util.find_spec('dask'):\n    import dask\n    print('dask imports', bool(dask.__version__))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env=env,
                         check=True).stdout.split("\n")
    assert out[0] == "False"
    import importlib.util

    if importlib.util.find_spec("dask"):
        assert out[1] == "dask imports True"
    kept = tmp_path / "cache" / "pint"
    assert kept.is_dir() and any(kept.rglob("*")) and (kept.stat().st_mode & 0o077) == 0


def test_version_is_the_installed_metadata_and_loads_no_heavy_library():
    """``rigidkin --version`` prints the version pip installed (importlib.metadata, the independent source)
    and exits 0, importing no heavy library."""
    from importlib.metadata import version

    code = ("import contextlib, io, sys\nfrom rigidkin.cli import main\nbuf = io.StringIO()\n"
            "with contextlib.redirect_stdout(buf): status = main(['--version'])\n"
            "sys.stderr.write(repr((status, buf.getvalue())))")
    res = subprocess.run([sys.executable, "-c", code + "\nimport sys; print(' '.join(sys.modules))"],
                         capture_output=True, text=True, timeout=60, check=True)
    status, printed = ast.literal_eval(res.stderr)
    assert status == 0 and printed.startswith(f"rigidkin {version('rigidkin')} (Python ")
    assert not {m.split(".")[0] for m in res.stdout.split()} & set(HEAVY)
