"""Bundled examples: Python models (``build()`` returns a System) and problem files (``*.toml``)."""

from __future__ import annotations

import importlib
from pathlib import Path

HERE = Path(__file__).parent


def names() -> list[str]:
    """The names of the bundled examples (card names, e.g. ``collar-rod``)."""
    found = {p.stem.replace("_", "-") for p in HERE.glob("*.py") if p.stem != "__init__"}
    found |= {p.stem for p in HERE.glob("*.toml")}
    return sorted(found)


def build(name: str):
    """Build the Python model of the example ``name``."""
    module = importlib.import_module(f"{__name__}.{name.replace('-', '_')}")
    return module.build()
