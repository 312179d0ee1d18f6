"""Every example in a docstring of the package (``>>>``) prints what it says: each module whose source holds
one is run through :mod:`doctest`, so a doc comment that drifts from the code's output fails here.

The modules are found by reading the sources, so a new example is tested without being listed.  All of them
together take about 7 s on a shared 2-core machine (the derivations come from the cache after the first run)."""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

SRC = Path(__file__).parents[1] / "src" / "rigidkin"


def _modules() -> list[str]:
    out = []
    for path in sorted(SRC.rglob("*.py")):
        if ">>> " in path.read_text(encoding="utf-8"):
            parts = path.relative_to(SRC.parent).with_suffix("").parts
            out.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return out


MODULES = _modules()


def test_the_examples_are_found():
    assert "rigidkin.model.system" in MODULES and len(MODULES) >= 5


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE, verbose=False,
                             report=True)
    found = sum(len(t.examples) for t in doctest.DocTestFinder().find(module))
    assert found > 0, f"{name}: its '>>>' lines are not in a docstring doctest reads"
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples print something else"
