"""Reading a worksheet: the student's steps of a derivation, in a TOML file.

::

    problem = "ladder"              # a bundled example, or a problem file relative to the worksheet
    student = "A. Student"          # optional
    motion = "dot(x) > 0"           # optional: the motion that fixes a sliding regime

    [[step]]
    kind = "kinematics"             # kinematics | fbd | balance | eom | answer
    claim = "a_G = l/2*ddot(theta)*ex - l/2*dot(theta)**2*ey + ..."

    [[step]]
    kind = "balance"
    law = "moment"                  # force | moment | energy (optional)
    point = "B"                     # for moments (optional)
    claim = "m*g*l/2*sin(theta) - ... = m*l**2/3*ddot(theta)"

The file is read through the same bounded machinery as a problem file (size, TOML structure pre-scan,
value count, depth) and every field is checked before anything is derived; a mistake in the file is
one paragraph naming the file, line and field.  The claims are read later by the restricted expression
parser (:mod:`rigidkin.io.expressions`) — nothing is evaluated by Python; a claim the parser cannot
read is graded *unreadable*, but a claim that is hostile rather than mistaken (names starting with
``_``, control characters, beyond the size limits) makes the whole worksheet refused.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from .. import examples
from ..base.errors import InputError
from ..base.textsafe import is_identifier
from ..io.expressions import MAX_LENGTH
from ..io.locate import Locator, resolve_problem
from ..io.reading import _parse_toml

MAX_BYTES = 200_000        # a worksheet is a page of steps
MAX_STEPS = 200
MAX_FBD_ITEMS = 40
KINDS = ("kinematics", "fbd", "balance", "eom", "answer")
LAWS = {"force": "force", "euler1": "force", "newton": "force", "momentum": "force",
        "moment": "moment", "moments": "moment", "euler2": "moment", "angular-momentum": "moment",
        "energy": "energy", "work-energy": "energy", "power": "energy", "impulse": "impulse"}
_TOP = {"problem", "student", "title", "step", "mode", "motion"}
_STEP = {"kind", "claim", "body", "point", "law", "direction", "question", "tolerance", "note", "quantity"}
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f\u202a-\u202e\u2066-\u2069]")
_HINT = ("A worksheet has problem = \"NAME or FILE.toml\" and [[step]] tables with kind (kinematics, fbd, balance, "
         "eom, answer) and claim; see docs/guide/grading.md.")


@dataclass(frozen=True)
class Step:
    """One step as the student wrote it."""

    index: int                      # 1-based, in the worksheet's order
    kind: str
    claim: str | tuple[str, ...]    # fbd: one string with items separated by ';', or several strings
    where: str                      # file, line and field, for messages
    body: str | None = None
    point: str | None = None
    law: str | None = None
    direction: str | None = None
    question: str | None = None
    tolerance: float | None = None
    note: str = ""
    quantity: str | None = None     # answer: which quantity of the question (phi, dot(phi), N, frequency ...)


@dataclass(frozen=True)
class Worksheet:
    path: Path
    problem: str                    # the name or path as written
    problem_ref: str                # what the loader reads: a bundled name or a resolved file path
    steps: tuple[Step, ...]
    student: str = ""
    title: str = ""
    mode: dict = field(default_factory=dict)
    motion: str = ""                # the motion that fixes the sliding regime, e.g. "dot(x) - r*dot(phi) > 0"
    motion_where: str = ""


def load_worksheet(path: Path | str) -> Worksheet:
    """Read and check a worksheet file (size-bounded, UTF-8, TOML pre-scanned)."""
    path = Path(path)
    try:
        size = path.stat().st_size
    except OSError as exc:
        raise InputError(f"cannot read the worksheet ({exc.strerror or exc}).", where=str(path)) from None
    if not path.is_file():
        raise InputError("is not a file.", where=str(path), hint="Give the path of a worksheet (.toml).")
    if size > MAX_BYTES:
        raise InputError(f"the worksheet is {size} bytes long (at most {MAX_BYTES}).", where=str(path), hint=_HINT)
    try:
        text = path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"the worksheet is not UTF-8 text (byte {exc.start}).", where=str(path),
                         hint="Save it as UTF-8.") from None
    return parse_worksheet(text, path)


def parse_worksheet(text: str, path: Path | str = "<worksheet>") -> Worksheet:
    """A worksheet from TOML text, as if read from ``path`` (relative problem files are found beside it)."""
    path = Path(path)
    where = str(path)
    if len(text) > MAX_BYTES:
        raise InputError(f"the worksheet is {len(text)} characters long (at most {MAX_BYTES}).", where=where)
    data = _parse_toml(text, where)   # bounded before and after tomllib, as a problem file
    loc = Locator(text, where)
    return _build(data, loc, path)


def _at(loc: Locator, *path) -> str:
    return loc.where(path)


def _string(value, loc, *path, identifier: bool = False, limit: int = MAX_LENGTH) -> str:
    if not isinstance(value, str):
        raise InputError(f"expected a string, not {type(value).__name__}.", where=_at(loc, *path), hint=_HINT)
    if len(value) > limit:
        raise InputError(f"the text is {len(value)} characters long (at most {limit}).", where=_at(loc, *path))
    if _CONTROL.search(value):
        raise InputError("the text contains a control character.", where=_at(loc, *path),
                         hint="Write plain text: no control characters or direction overrides.")
    if identifier and not is_identifier(value):
        raise InputError(f"{value[:40]!r} is not a name (letters, digits and '_', starting with a letter).",
                         where=_at(loc, *path))
    return value


def _claim_text(value, loc, *path) -> str:
    s = _string(value, loc, *path)
    if not s.strip():
        raise InputError("the claim is empty.", where=_at(loc, *path), hint="Write what the step says.")
    if "__" in s or re.search(r"(?<![A-Za-z0-9])_", s):
        raise InputError("the claim contains a name starting with '_' (such as a dunder name), which is refused.",
                         where=_at(loc, *path), hint="Claims use the problem's names, numbers and operators.")
    return s


def _problem_ref(problem: str, path: Path, where: str) -> str:
    """A file beside the worksheet (or at an absolute path) first; a bundled example only when no such file
    exists (a folder named like an example never hides it)."""
    how, found = resolve_problem(problem, path.parent)
    if how == "example":
        toml = examples.HERE / f"{problem}.toml"
        return str(toml) if toml.is_file() else problem
    if found.is_file() and problem.endswith(".toml"):
        return str(found)
    if not problem.endswith(".toml"):
        raise InputError(f"'{problem}' is neither a bundled example nor a problem file (.toml).", where=where,
                         hint=f"Bundled examples: {', '.join(examples.names())}.")
    p = Path(problem)
    if not p.is_absolute():
        p = path.parent / p
    if not p.is_file():
        raise InputError(f"there is no problem file {problem} (looked for {p}).", where=where,
                         hint="A relative path is read from the worksheet's folder.")
    return str(p)


def _build(data: dict, loc: Locator, path: Path) -> Worksheet:
    unknown = sorted(set(data) - _TOP)
    if unknown:
        raise InputError(f"unknown field '{unknown[0][:40]}'.", where=_at(loc, unknown[0]),
                         hint=f"A worksheet has: {', '.join(sorted(_TOP))}.")
    if "problem" not in data:
        raise InputError("the worksheet names no problem.", where=str(path), hint=_HINT)
    problem = _string(data["problem"], loc, "problem", limit=500)
    ref = _problem_ref(problem, path, _at(loc, "problem"))
    student = _string(data.get("student", ""), loc, "student", limit=200)
    title = _string(data.get("title", ""), loc, "title", limit=200)
    mode = data.get("mode", {})
    if not isinstance(mode, dict) or any(not isinstance(v, str) for v in mode.values()):
        raise InputError("mode is a table CONTACT = \"open\"|\"slip\"|\"stick\".", where=_at(loc, "mode"))
    for k, v in mode.items():
        _string(k, loc, "mode", k, identifier=True)
        _string(v, loc, "mode", k, identifier=True)
    steps_raw = data.get("step", [])
    if not isinstance(steps_raw, list) or not steps_raw:
        raise InputError("the worksheet has no [[step]] tables.", where=_at(loc, "step") if "step" in data
                         else str(path), hint=_HINT)
    if len(steps_raw) > MAX_STEPS:
        raise InputError(f"the worksheet has {len(steps_raw)} steps (at most {MAX_STEPS}).", where=str(path))
    steps = tuple(_step(s, i, loc) for i, s in enumerate(steps_raw))
    motion = _claim_text(data["motion"], loc, "motion") if "motion" in data else ""
    return Worksheet(path, problem, ref, steps, student, title, dict(mode), motion, _at(loc, "motion"))


def _step(raw, i: int, loc: Locator) -> Step:
    base = ("step", i)
    if not isinstance(raw, dict):
        raise InputError("a step is a table with kind and claim.", where=_at(loc, *base), hint=_HINT)
    unknown = sorted(set(raw) - _STEP)
    if unknown:
        raise InputError(f"unknown field '{unknown[0][:40]}' in a step.", where=_at(loc, *base, unknown[0]),
                         hint=f"A step has: {', '.join(sorted(_STEP))}.")
    for req in ("kind", "claim"):
        if req not in raw:
            raise InputError(f"the step has no {req}.", where=_at(loc, *base), hint=_HINT)
    kind = _string(raw["kind"], loc, *base, "kind", limit=40)
    if kind not in KINDS:
        raise InputError(f"'{kind}' is not a kind of step.", where=_at(loc, *base, "kind"),
                         hint=f"Kinds: {', '.join(KINDS)}.")
    claim_raw = raw["claim"]
    if kind == "fbd" and isinstance(claim_raw, list):
        if not claim_raw or len(claim_raw) > MAX_FBD_ITEMS:
            raise InputError(f"a diagram lists 1 to {MAX_FBD_ITEMS} loads.", where=_at(loc, *base, "claim"))
        claim = tuple(_claim_text(c, loc, *base, "claim", k) for k, c in enumerate(claim_raw))
    elif kind == "answer" and isinstance(claim_raw, int | float) and not isinstance(claim_raw, bool):
        claim = repr(claim_raw)
    else:
        claim = _claim_text(claim_raw, loc, *base, "claim")
    names = {}
    for key in ("body", "point", "question"):
        if key in raw:
            names[key] = _string(raw[key], loc, *base, key, identifier=True)
    law = None
    if "law" in raw:
        w = _string(raw["law"], loc, *base, "law", limit=40).strip().lower().replace("_", "-").replace("–", "-")
        w = w.replace("impulse-momentum", "impulse")
        if w not in LAWS:
            raise InputError(f"'{w}' is not a law the grader knows.", where=_at(loc, *base, "law"),
                             hint="Laws: force (Euler's 1st law), moment (2nd law about a point), energy "
                                  "(work–energy), impulse (impulse–momentum).")
        law = LAWS[w]
    direction = _claim_text(raw["direction"], loc, *base, "direction") if "direction" in raw else None
    tol = raw.get("tolerance")
    if tol is not None and (isinstance(tol, bool) or not isinstance(tol, int | float) or not 0 < tol < 1):
        raise InputError("tolerance is a relative tolerance between 0 and 1 (e.g. 0.01).",
                         where=_at(loc, *base, "tolerance"))
    note = _string(raw.get("note", ""), loc, *base, "note", limit=500)
    if kind == "answer" and "question" not in names:
        raise InputError("an answer step names the question it answers (question = \"NAME\").",
                         where=_at(loc, *base), hint="The questions are the [[ask.question]] names of the problem.")
    quantity = _claim_text(raw["quantity"], loc, *base, "quantity") if "quantity" in raw else None
    return Step(i + 1, kind, claim, _at(loc, *base), names.get("body"), names.get("point"), law, direction,
                names.get("question"), None if tol is None else float(tol), note, quantity)
