import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

# Tests derive afresh: the derivation cache (tested in test_derivation_cache.py) would let one test's
# derivation answer another's, and would write to the user's cache folder.
os.environ.setdefault("RIGIDKIN_NO_CACHE", "1")


def pytest_collection_modifyitems(config, items):
    """The modules that hold long cases (marked ``slow``) run first, each module kept together (its fixtures
    are made once): with ``-n 2`` a long case started last would leave the other worker idle at the end."""
    slow_modules = {item.module.__name__ for item in items if item.get_closest_marker("slow")}
    order = {id(item): i for i, item in enumerate(items)}
    items.sort(key=lambda item: (item.module.__name__ not in slow_modules, order[id(item)]))


# fixtures several test files share ------------------------------------------------------------------------
import pytest  # noqa: E402


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """A cache folder of this test's own (``$RIGIDKIN_CACHE``), with the cache on."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("RIGIDKIN_CACHE", str(folder))
    monkeypatch.delenv("RIGIDKIN_NO_CACHE", raising=False)
    return folder


@pytest.fixture
def code_cache(tmp_path_factory, monkeypatch):
    """One compiled-code cache for the whole session (compiled once, not in the user's folder)."""
    monkeypatch.setenv("RIGIDKIN_CACHE", str(tmp_path_factory.getbasetemp() / "rk-cache"))


@pytest.fixture(scope="module")
def ladder():
    """The bundled ladder (rigidkin.examples), built once per test module."""
    from rigidkin import examples

    return examples.build("ladder")
