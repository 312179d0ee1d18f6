"""Griffe extension for the API reference: the package's docstrings, written for reading in a terminal (reST
roles, doctest sessions), read as Markdown.

* ``:func:`name``` and the other Sphinx roles become inline code (``~`` dropped: the last part shown);
* a doctest session (lines from ``>>>`` to the next blank line) becomes a fenced ``pycon`` block, so that
  its brackets are not read as links and its ``>>>`` not as quotes.
"""

from __future__ import annotations

import re

try:                                   # the docs extra; markdown() itself needs nothing
    import griffe
except ImportError:                    # pragma: no cover - without the docs extra
    griffe = None

ROLE = re.compile(r":(?:func|class|mod|meth|attr|data|obj|exc):`~?([^`]+)`")


def _role(m: re.Match) -> str:
    target = m[1]
    return f"`{target.rsplit('.', 1)[-1]}`" if m[0].count("~") else f"`{target}`"


def markdown(text: str) -> str:
    """The docstring ``text`` with its roles as code and its doctest sessions fenced."""
    text = ROLE.sub(_role, text)
    out: list[str] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.lstrip().startswith(">>>"):
            indent = line[: len(line) - len(line.lstrip())]
            out.append(f"{indent}```pycon")
            while i < len(lines) and lines[i].strip():
                out.append(lines[i])
                i += 1
            out.append(f"{indent}```")
            continue
        out.append(line)
        i += 1
    return "\n".join(out)


if griffe is not None:
    class DocstringsAsMarkdown(griffe.Extension):
        """Each object's docstring through :func:`markdown`, once the object tree is complete."""

        def on_object(self, *, obj, loader, **kwargs) -> None:
            if not obj.is_alias and obj.docstring is not None:
                obj.docstring.value = markdown(obj.docstring.value)
