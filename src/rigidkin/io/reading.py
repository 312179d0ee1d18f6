"""Reading a problem file's text: size and structure bounded, TOML parsed, the schema checked.

Every failure is an :class:`~rigidkin.base.errors.InputError` naming the file, the line and the field path.
"""

from __future__ import annotations

import difflib
import re
import tomllib
import typing
from pathlib import Path

from pydantic import BaseModel, ValidationError

from ..base.errors import InputError
from ..model.shapes import SHAPES
from . import schema as S
from .locate import Locator
from .prescan import check_tree, prescan
from .source import MAX_FILE_BYTES, read_bytes  # noqa: F401  (MAX_FILE_BYTES public here too)


# reading ------------------------------------------------------------------------------------------------
def read_toml(path: Path | str) -> tuple[str, dict]:
    """The text and parsed TOML of a file (read once, size-limited; syntax errors with their line)."""
    return parse_bytes(read_bytes(path), path)


def parse_bytes(raw: bytes, path: Path | str) -> tuple[str, dict]:
    """The text and parsed TOML of the bytes ``raw`` read from ``path`` (exactly these bytes: the file is not
    read again)."""
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"the file is not UTF-8 text (byte {exc.start}).", where=str(path),
                         hint="Save it as UTF-8.") from None
    return text, _parse_toml(text, str(path))


def _parse_toml(text: str, filename: str) -> dict:
    """TOML text → data, its structure bounded before and after ``tomllib`` reads it."""
    prescan(text, filename)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise _toml_error(exc, filename) from None
    except (RecursionError, MemoryError):
        raise InputError("the TOML is nested too deeply to read.", where=filename) from None
    check_tree(data, filename)
    return data


def _toml_error(exc: Exception, filename: str) -> InputError:
    msg = str(exc)
    m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
    where = f"{filename}, line {m.group(1)}, column {m.group(2)}" if m else filename
    detail = re.sub(r"\s*\(at line \d+, column \d+\)", "", msg) if m else msg
    return InputError(f"TOML syntax error: {detail}.", where=where,
                      hint="Fix the TOML syntax (strings in double quotes, one 'key = value' per line, each key once "
                           "per table; see https://toml.io).")


def validate_schema(data: dict, locator: Locator) -> S.ProblemFile:
    """The schema check; the first problem is reported with its line and field path."""
    try:
        return S.ProblemFile.model_validate(data)
    except ValidationError as exc:
        errors = exc.errors(include_url=False)
        raise _schema_error(errors[0], len(errors) - 1, data, locator) from None
    except RecursionError:
        raise InputError("the file is nested too deeply.", where=locator.filename) from None


def _clean_loc(loc: tuple, data) -> tuple:
    """Drop pydantic's union tags from a location by walking the data along it."""
    out, cur = [], data
    for part in loc:
        if (isinstance(cur, dict) and part in cur
                or isinstance(cur, list) and isinstance(part, int) and 0 <= part < len(cur)):
            out.append(part)
            cur = cur[part]
        elif isinstance(cur, dict) and isinstance(part, str):
            # a tag (the union member chosen), or a missing key: keep missing keys, drop tags
            if part in ("str", "int", "float", "bool") or "[" in part or _is_tag(cur, part):
                continue
            out.append(part)
            cur = None
        else:
            out.append(part)
            cur = None
    return tuple(out)


def _is_tag(table: dict, part: str) -> bool:
    return any(table.get(k) == part for k in ("type", "kind", "shape"))


def _model_at(loc: tuple):
    """The pydantic model a (raw, tagged) location points into, for 'did you mean' hints."""
    tp: typing.Any = S.ProblemFile
    for part in loc:
        tp = _unwrap(tp, part)
        if tp is None:
            return None
    return tp


def _unwrap(tp, part):
    origin = typing.get_origin(tp)
    if origin is typing.Annotated:
        return _unwrap(typing.get_args(tp)[0], part)
    if isinstance(tp, type) and issubclass(tp, BaseModel):
        f = tp.model_fields.get(part)
        if f is None:
            for fi in tp.model_fields.values():
                if fi.alias == part:
                    f = fi
                    break
        return f.annotation if f is not None else None
    if origin is dict:
        return typing.get_args(tp)[1]
    if origin is list:
        return typing.get_args(tp)[0]
    if origin in (typing.Union, __import__("types").UnionType):
        for member in typing.get_args(tp):
            if isinstance(member, type) and issubclass(member, BaseModel):
                for key in ("type", "kind", "shape"):
                    f = member.model_fields.get(key)
                    if f is not None and part in typing.get_args(f.annotation):
                        return member
        return None
    return None


def _schema_error(err: dict, more: int, data: dict, locator: Locator) -> InputError:
    raw_loc = tuple(err["loc"])
    loc = _clean_loc(raw_loc, data)
    where = locator.where(loc)
    kind, msg = err["type"], err["msg"].removeprefix("Value error, ")
    key = loc[-1] if loc else ""
    hint = None
    if kind == "missing":
        message = f"the required field '{key}' is missing"
        hint = f"Add {key} = ... to this table."
        if key == "sense":
            hint = "Say where the coordinate is measured from and which way it is positive: sense = \"...\"."
    elif kind == "extra_forbidden":
        message = f"unknown field '{key}'"
        model = _model_at(raw_loc[:-1])
        if isinstance(model, type) and issubclass(model, BaseModel):
            known = [f.alias or n for n, f in model.model_fields.items()]
            close = difflib.get_close_matches(str(key), known, n=1)
            hint = (f"Did you mean '{close[0]}'? " if close else "") + f"Fields here: {', '.join(known)}."
    elif kind in ("union_tag_invalid", "union_tag_not_found"):
        message = msg[0].lower() + msg[1:]
        hint = "Give the table's 'type' (constraints, loads, surfaces), 'shape' (bodies) or 'kind' (questions)."
        if "shape" in msg:
            hint = f"Shapes: {', '.join(SHAPES)}."
    else:
        got = err.get("input")
        shown = repr(got) if not isinstance(got, dict | list) else type(got).__name__
        if len(shown) > 60:
            shown = shown[:57] + "..."
        message = f"{msg[0].lower() + msg[1:]} (got {shown})"
    if hint is None:
        hint = "The fields and their types are listed in rigidkin.io.schema; 'rigidkin list' shows bundled examples."
    if more:
        message += f" ({more} more problem{'s' if more > 1 else ''} in the file; fix this one first)"
    return InputError(message + ".", where=where, hint=hint)
