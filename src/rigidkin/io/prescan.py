"""Bounds on the structure of a problem file, checked on the raw text before ``tomllib`` reads it.

A problem file describes one system in a few kilobytes.  ``tomllib`` is correct but not bounded:
tens of thousands of dotted keys, nested table headers or one enormous header line make it (and the
line locator) run for a minute or take gigabytes.  ``prescan`` reads the text once with one regular
expression (strings and comments skipped, so their content does not count) and refuses, with the
line where a limit is passed, a file that has

* a line longer than ``MAX_LINE`` characters,
* more than ``MAX_KEYS`` keys, ``MAX_TABLES`` table headers or ``MAX_DOTTED`` dotted keys,
* a key path (header or dotted key) of more than ``MAX_KEY_PARTS`` parts,
* brackets or braces nested more than ``MAX_DEPTH`` deep.

``check_tree`` bounds the parsed data as well (number of values, depth), for data that does not come
from a file.
"""

from __future__ import annotations

import re

from ..base.errors import InputError

MAX_BYTES = 1_000_000      # the whole file
MAX_LINE = 10_000          # characters in one line
MAX_KEYS = 10_000          # 'key = value' pairs, inline tables' keys included
MAX_TABLES = 2_000         # [table] and [[array]] headers
MAX_DOTTED = 2_000         # keys written with dots (a.b = 1)
MAX_KEY_PARTS = 8          # parts of one key path ([a.b.c] has 3)
MAX_DEPTH = 16             # nested [ ] and { } in values
MAX_VALUES = 50_000        # values in the parsed data
_HINT = ("A problem file describes one system in a few kilobytes: parameters, coordinates, frames, points, bodies, "
         "constraints, loads and questions; check that this is the right file.")

# one token: a string (skipped), a comment (skipped), a bracket, '=', '.', a newline
_TOKEN = re.compile(r'"""(?:[^"\\]|\\.|"(?!""))*"""|\'\'\'(?:[^\']|\'(?!\'\'))*\'\'\'|"(?:[^"\\\n]|\\.)*"|'
                    r"'[^'\n]*'|#[^\n]*|[\[\]{}=.,\n]", re.S)


_LINE_KEY = re.compile(r"\s*([A-Za-z0-9_.\- ]{1,200}?)\s*=")
_LINE_HEADER = re.compile(r"\s*\[\[?\s*([A-Za-z0-9_.\- ]{1,200}?)\s*\]")


def _field(lines: list[str], lineno: int) -> str:
    """The key path written at ``lineno`` (table header above it + the key), or '' when not plain."""
    m = _LINE_KEY.match(lines[lineno - 1][:300])
    if not m:
        return ""
    table = ""
    for back in range(lineno - 2, max(lineno - 2000, -1), -1):
        h = _LINE_HEADER.match(lines[back][:300])
        if h:
            table = h.group(1).replace(" ", "") + "."
            break
    return table + m.group(1).replace(" ", "")


def _refuse(what: str, where: str, line: int | None, field: str = "") -> InputError:
    at = f"{where}, line {line}" if line else where
    return InputError(what, where=at + (f", {field}" if field else ""), hint=_HINT)


def prescan(text: str, where: str) -> None:
    """Refuse a TOML text whose structure is out of bounds, before it is parsed (linear time)."""
    if len(text) > MAX_BYTES:
        raise _refuse(f"the problem text is {len(text)} characters long (at most {MAX_BYTES}).", where, None)
    lines = text.split("\n")
    longest = max(map(len, lines), default=0)
    if longest > MAX_LINE:
        lineno = next(i for i, s in enumerate(lines, start=1) if len(s) == longest)
        raise _refuse(f"the line is {longest} characters long (at most {MAX_LINE}).", where, lineno,
                      _field(lines, lineno))
    line, depth, keys, tables, dotted = 1, 0, 0, 0, 0
    at_line_start = True          # no value or key seen yet on this line (outside brackets)
    parts = 1                     # parts of the key being written
    header = False                # inside a [table] header
    for m in _TOKEN.finditer(text):
        tok = m.group()
        c = tok[0]
        if c in "\"'#":
            line += tok.count("\n")
            if c != "#":
                at_line_start = False
            continue
        if c == "\n":
            line += 1
            at_line_start, parts, header = depth == 0, 1, False
            continue
        if header and c in "[]":        # '[[' and ']]' of an array of tables
            continue
        if c in "[{":
            if c == "[" and depth == 0 and at_line_start:
                header, parts = True, 1
                tables += 1
                if tables > MAX_TABLES:
                    raise _refuse(f"the file has more than {MAX_TABLES} table headers.", where, line)
                continue
            depth += 1
            if depth > MAX_DEPTH:
                raise _refuse(f"brackets and braces are nested more than {MAX_DEPTH} deep.", where, line)
            at_line_start = c == "{"
        elif c in "]}":
            depth = max(depth - 1, 0)
            at_line_start = False
        elif c == ",":
            at_line_start = depth > 0
            parts = 1
        elif c == ".":
            parts += 1
            if parts > MAX_KEY_PARTS:
                raise _refuse(f"a key path has more than {MAX_KEY_PARTS} parts.", where, line)
        elif c == "=":
            keys += 1
            if keys > MAX_KEYS:
                raise _refuse(f"the file has more than {MAX_KEYS} keys.", where, line)
            if parts > 1:
                dotted += 1
                if dotted > MAX_DOTTED:
                    raise _refuse(f"the file has more than {MAX_DOTTED} dotted keys (a.b = ...).", where, line)
            parts = 1
            at_line_start = False


def check_tree(data, where: str) -> None:
    """Refuse parsed data with more than ``MAX_VALUES`` values or nested more than ``MAX_DEPTH`` deep."""
    count, stack = 0, [(data, 0)]
    while stack:
        node, d = stack.pop()
        count += 1
        if count > MAX_VALUES:
            raise InputError(f"the problem has more than {MAX_VALUES} values.", where=where, hint=_HINT)
        if d > MAX_DEPTH + MAX_KEY_PARTS:
            raise InputError(f"the problem's tables are nested more than {MAX_DEPTH + MAX_KEY_PARTS} deep.",
                             where=where, hint=_HINT)
        if isinstance(node, dict):
            stack.extend((v, d + 1) for v in node.values())
        elif isinstance(node, list):
            stack.extend((v, d + 1) for v in node)
