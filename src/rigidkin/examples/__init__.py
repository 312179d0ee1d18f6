"""Bundled examples: Python models (``build()`` returns a System) and problem files (``*.toml``)."""

from __future__ import annotations

import ast
import importlib
import tomllib
from pathlib import Path

HERE = Path(__file__).parent


def names() -> list[str]:
    """The names of the bundled examples (card names, e.g. ``collar-rod``)."""
    found = {p.stem.replace("_", "-") for p in HERE.glob("*.py") if p.stem != "__init__"}
    found |= {p.stem for p in HERE.glob("*.toml")}
    return sorted(found)


def title(name: str) -> str:
    """The title of the example ``name``, read without building it: a problem file's ``title``, a Python
    model's module constant ``TITLE`` (what ``build()`` gives ``System.title`` by default)."""
    toml = HERE / f"{name}.toml"
    if toml.exists():
        with toml.open("rb") as fh:
            found = tomllib.load(fh).get("title")
        return found if isinstance(found, str) else name
    tree = ast.parse((HERE / f"{name.replace('-', '_')}.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and [getattr(t, "id", None) for t in node.targets] == ["TITLE"] \
                and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str):
            return node.value.value
    return build(name).title


def build(name: str):
    """Build the Python model of the example ``name``."""
    module = importlib.import_module(f"{__name__}.{name.replace('-', '_')}")
    return module.build()
