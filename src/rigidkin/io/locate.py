"""Where a field is written in a TOML file: the line of a key path such as ``bodies.rod.at``.

``tomllib`` gives a line only for syntax errors; schema and model errors name a field path.  The
``Locator`` scans the file text once (table headers, arrays of tables, keys, keys of inline tables)
and answers the line of the longest recorded prefix of a path, so that every error message can say
"ladder.toml, line 31, bodies.rod.at".
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

from .. import examples

_KEY_PART = re.compile(r"[A-Za-z0-9_-]+|\"(?:[^\"\\]|\\.)*\"|'[^']*'")
_KEY = re.compile(r"^\s*((?:[A-Za-z0-9_-]+|\"(?:[^\"\\]|\\.)*\"|'[^']*')"
                  r"(?:\s*\.\s*(?:[A-Za-z0-9_-]+|\"(?:[^\"\\]|\\.)*\"|'[^']*'))*)\s*=")
_INLINE_KEY = re.compile(r"[{,]\s*([A-Za-z0-9_-]+|\"(?:[^\"\\]|\\.)*\"|'[^']*')\s*=")


def _header(line: str) -> tuple[str, str] | None:
    """``("[" or "[[", "a.b")`` for a table header line, else None; one pass over the line (a regular
    expression with ``\\s*(.+?)\\s*`` backtracks for minutes on a long line of spaces)."""
    s = line.lstrip()
    if not s.startswith("["):
        return None
    double = s.startswith("[[")
    body = s[2:] if double else s[1:]
    i, n, quote = 0, len(body), None
    end = body.find("]")
    if end < 0:
        return None
    if '"' not in body[:end] and "'" not in body[:end]:
        i = n = end                         # no quoted key: the header ends at the first ']'
    while i < n:
        ch = body[i]
        if quote:
            if ch == "\\" and quote == '"':
                i += 2
                continue
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
        elif ch == "]":
            break
        i += 1
    if i >= len(body) or body[i] != "]":
        return None
    rest = body[i + 1:]
    if double:
        if not rest.startswith("]"):
            return None
        rest = rest[1:]
    rest = rest.strip()
    if rest and not rest.startswith("#"):
        return None
    key = body[:i].strip()
    return ("[[" if double else "[", key) if key else None


def _parts(dotted: str) -> tuple[str, ...]:
    out = []
    for p in _KEY_PART.findall(dotted):
        if p[:1] in "\"'":
            p = p[1:-1]
        out.append(p)
    return tuple(out)


def dotted(path: Sequence) -> str:
    """``("ask", "question", 0, "when")`` → ``ask.question[0].when``."""
    out = ""
    for p in path:
        if isinstance(p, int):
            out += f"[{p}]"
        else:
            p = str(p)
            if not re.fullmatch(r"[A-Za-z0-9_-]+", p):
                p = '"' + p.replace('"', '\\"') + '"'
            out += ("." if out else "") + p
    return out


class Locator:
    """The lines of the keys of one TOML text, for error messages."""

    def __init__(self, text: str, filename: str):
        self.filename = filename
        self.entries: list[tuple[tuple, int]] = []
        self._scan(text)

    def _resolve(self, parts: tuple[str, ...], arrays: dict) -> tuple:
        out: list = []
        for i, p in enumerate(parts):
            out.append(p)
            if i < len(parts) - 1 and tuple(out) in arrays:
                out.append(arrays[tuple(out)] - 1)
        return tuple(out)

    def _scan(self, text: str) -> None:
        arrays: dict[tuple, int] = {}
        current: tuple = ()
        in_string = None
        for lineno, line in enumerate(text.splitlines(), start=1):
            if in_string:
                if line.count(in_string) % 2 == 1:
                    in_string = None
                continue
            h = _header(line)
            if h and not _KEY.match(line):
                parts = self._resolve(_parts(h[1]), arrays)
                if h[0] == "[[":
                    idx = arrays.get(parts, 0)
                    arrays[parts] = idx + 1
                    current = parts + (idx,)
                else:
                    current = parts
                self.entries.append((current, lineno))
                continue
            m = _KEY.match(line)
            if m:
                path = current + _parts(m.group(1))
                self.entries.append((path, lineno))
                rest = line[m.end():]
                for km in _INLINE_KEY.finditer(rest):
                    self.entries.append((path + _parts(km.group(1)), lineno))
                for quote in ('"""', "'''"):
                    if rest.count(quote) % 2 == 1:
                        in_string = quote
                        break

    def line_of(self, path: Sequence) -> int | None:
        """The line of the longest recorded prefix of ``path`` (None when nothing matches)."""
        target = tuple(path)
        best, best_len = None, -1
        for p, line in self.entries:
            if len(p) > best_len and target[:len(p)] == p:
                best, best_len = line, len(p)
        return best

    def where(self, path: Sequence = ()) -> str:
        """``"ladder.toml, line 31, bodies.rod.at"``."""
        out = self.filename
        if path:
            line = self.line_of(path)
            if line is not None:
                out += f", line {line}"
            out += f", {dotted(path)}"
        return out


# which problem a name means -------------------------------------------------------------------------------
def resolve_problem(problem: str, folder=None) -> tuple[str, object]:
    """What a problem argument means: ``("file", Path)`` or ``("example", NAME)``.

    A path that exists on disk as a file always means that file (relative paths from ``folder``, else
    the working folder); a bundled example's name means the example only when no such file exists —
    a folder of that name (``collar-rod/`` holding worksheets) never hides the example.  A ``.toml``
    path that does not exist stays a file (its reader says it is missing).
    """
    p = Path(problem)
    if folder is not None and not p.is_absolute():
        p = Path(folder) / p
    if p.is_file():
        return "file", p
    if problem in examples.names() and not problem.endswith(".toml"):
        return "example", problem
    return "file", p


def clashes(names, folder=".") -> dict:
    """Bundled names that a file or folder in ``folder`` shares, with what a command given the name reads."""
    out = {}
    for name in names:
        p = Path(folder) / name
        if p.is_file():
            out[name] = f"a file '{name}' is here: a command given '{name}' reads that file, not the example"
        elif p.is_dir():
            out[name] = f"a folder '{name}' is here: '{name}' still means the example (a folder is not a problem)"
    return out
