"""Problem files: the safe expression language (``expressions``), the schema (``schema``) and the reader
(``problem``: ``load_problem``, ``parse_problem``, ``system_scope``).  Loaded on first use."""

from __future__ import annotations

import importlib

_EXPORTS = {"load_problem": "problem", "parse_problem": "problem", "build_problem": "problem",
            "system_scope": "problem", "ProblemSpec": "problem"}


def __getattr__(name: str):
    if name in _EXPORTS:
        return getattr(importlib.import_module(f".{_EXPORTS[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = sorted(_EXPORTS)
