"""Reading a problem file: TOML → schema check → a ``rigidkin.System`` built through its public methods.

``load_problem(path)`` returns ``(system, spec)``; ``spec`` (a :class:`ProblemSpec`) keeps what the
file asks (``[ask]``: the equations of motion, reactions, and questions as
:class:`rigidkin.analysis.questions.Question` objects) and can say where any field is written.
Every problem is reported as an :class:`~rigidkin.errors.InputError` (or the model's own
``ModelError``) naming the file, the line, the field path and what to do.
"""

from __future__ import annotations

import difflib
import re
import tomllib
import typing
from dataclasses import dataclass, field
from pathlib import Path

import sympy as sp
from pydantic import BaseModel, ValidationError
from sympy.physics.vector import Vector

from ..analysis.questions import Question
from ..errors import InputError, ModelError, RigidkinError
from ..model.checks import NONNEGATIVE, REAL, check_problem_name, generated_clash, problem_name, require
from ..model.constraints import Contact
from ..model.loads import V as DAMPER_SPEED
from ..model.shapes import SHAPES
from ..model.system import System
from ..units import LENGTH, ONE, TIME, to_si, unit_dimension
from . import schema as S
from .expressions import (
    Scope,
    check_name,
    default_scope,
    parse_condition,
    parse_equation,
    parse_scalar,
    parse_vector,
    slip,
)
from .locate import Locator, dotted
from .prescan import check_tree, prescan

#: Larger files are refused before they are read (a problem description is a few kilobytes).
MAX_FILE_BYTES = 1_000_000
_UNIT_QUANTITY = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*[A-Za-z°µ]")
_NUMBER = re.compile(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*")
_FRICTION_WORDS = ("smooth", "rolling", "no-slip", "no_slip")


@dataclass
class ProblemSpec:
    """What a problem file says beyond the system: its source, and what it asks."""

    path: Path
    name: str
    title: str
    statement: str
    eom: bool = True
    reactions: tuple[str, ...] | None = None
    questions: tuple[Question, ...] = ()
    scope: Scope = field(default_factory=default_scope, repr=False)
    locator: Locator | None = field(default=None, repr=False)
    data: S.ProblemFile | None = field(default=None, repr=False)

    def where(self, *path) -> str:
        """``"file.toml, line 12, bodies.rod.at"`` for a field path."""
        return self.locator.where(path) if self.locator else str(self.path)


# reading ------------------------------------------------------------------------------------------------
def read_toml(path: Path | str) -> tuple[str, dict]:
    """The text and parsed TOML of a file (size-limited; syntax errors with their line)."""
    path = Path(path)
    try:
        size = path.stat().st_size
    except OSError as exc:
        raise InputError(f"cannot read the problem file ({exc.strerror or exc}).", where=str(path),
                         hint="Check the path; 'rigidkin list' shows the bundled examples.") from None
    if not path.is_file():
        raise InputError("is not a file.", where=str(path), hint="Give the path of a .toml problem file.")
    if size > MAX_FILE_BYTES:
        raise InputError(f"the problem file is {size} bytes long (at most {MAX_FILE_BYTES}).", where=str(path),
                         hint="A problem file describes one system in a few kilobytes; check that this is the "
                              "right file.")
    try:
        raw = path.read_bytes()
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"the file is not UTF-8 text (byte {exc.start}).", where=str(path),
                         hint="Save it as UTF-8.") from None
    except OSError as exc:
        raise InputError(f"cannot read the problem file ({exc.strerror or exc}).", where=str(path)) from None
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


# building -----------------------------------------------------------------------------------------------
class _Builder:
    def __init__(self, spec: S.ProblemFile, locator: Locator, name: str):
        self.spec, self.loc = spec, locator
        self.s = System(name, statement=spec.statement, title=spec.title)
        self.scope = default_scope().with_max_derivative(1)     # the model: no accelerations in loads
        F = self.s.inertial
        self.scope.add_frame("F", F.basis, (F.x, F.y, F.z))
        self.reactions: dict[str, sp.Symbol] = {}
        self.owners: dict[str, str] = {}          # expression name → what declared it

    # helpers ------------------------------------------------------------------------------------------
    def where(self, *path) -> str:
        return self.loc.where(path)

    def call(self, path: tuple, fn, *args, **kwargs):
        """Call a System method; its errors are reported at ``path`` in the file."""
        try:
            return fn(*args, **kwargs)
        except RigidkinError as exc:
            inner = f"{exc.where}: " if exc.where else ""
            raise type(exc)(inner + exc.message, where=self.where(*path), hint=exc.hint) from None
        except (TypeError, ValueError, AttributeError, ZeroDivisionError, ArithmeticError) as exc:
            raise InputError(f"this cannot be built ({type(exc).__name__}: {exc}).", where=self.where(*path),
                             hint="Check the expressions and names in this table.") from None

    def scalar(self, value, path, scope=None) -> sp.Expr:
        """A scalar expression, real and finite once the parameters' values are put in."""
        where = self.where(*path)
        return require(parse_scalar(value, scope or self.scope, where), REAL, "value", where,
                       self.s.parameter_values(), InputError)

    def vector(self, value, path, scope=None) -> Vector:
        where = self.where(*path)
        vec = parse_vector(value, scope or self.scope, where)
        for measure, _frame in vec.args:
            for comp in measure:
                require(comp, REAL, "vector component", where, self.s.parameter_values(), InputError)
        return vec

    def value(self, value, path, dimension=None) -> sp.Expr:
        """A number, a quantity with a unit ('30 deg', converted to SI; of ``dimension`` if given) or an
        expression."""
        if isinstance(value, str) and _UNIT_QUANTITY.match(value):
            return sp.Float(to_si(value, None, self.where(*path), dimension))
        return self.scalar(value, path, self._question_scope())

    def _lookup(self, table: dict, kind: str, name: str | None, path, optional=False):
        if name is None:
            if optional:
                return None
            raise InputError(f"a {kind} is required here.", where=self.where(*path))
        if name not in table:
            known = ", ".join(table) or "none yet"
            close = difflib.get_close_matches(name, list(table), n=1)
            hint = (f"Did you mean '{close[0]}'? " if close else "") + f"Known {kind}s: {known}."
            if kind == "point":
                hint += " O is the origin; points are declared in [points] or are bodies' mass centres."
                if name in self.spec.points:
                    raise ModelError(f"the point '{name}' cannot be placed: {self._chain(name)}.",
                                     where=self.where(*path), hint="Locate each point from O or from a point that "
                                                                   "can be placed ('from = ...').")
            raise ModelError(f"there is no {kind} named '{name}'.", where=self.where(*path), hint=hint)
        return table[name]

    def _chain(self, name) -> str:
        chain, cur = [name], name
        while cur in self.spec.points and cur not in self.s.points:
            cur = self.spec.points[cur].from_
            if cur in chain:
                return "its 'from' points form a cycle (" + " → ".join(chain + [cur]) + ")"
            chain.append(cur)
        if cur in self.s.points:
            return "it is located from " + " → ".join(chain[1:]) + ", which is not placed yet"
        return f"it is located (through {' → '.join(chain)}) from '{cur}', which is not a point"

    def point(self, name, path, optional=False):
        return self._lookup(self.s.points, "point", name, path, optional)

    def body(self, name, path, optional=False):
        return self._lookup(self.s.bodies, "body", name, path, optional)

    def frame(self, name, path, optional=False):
        return self._lookup(self.s.frames, "frame", name, path, optional)

    def declared(self, name: str, kind: str, path, vectors: bool = True) -> str:
        check_name(name, kind, self.where(*path))
        sc = self.scope
        if name in sc.names or vectors and (name in sc.vectors or name in sc.ambiguous):
            raise InputError(f"the {kind} name '{name}' is already used by {self.owners.get(name, 'another name')}.",
                             where=self.where(*path),
                             hint="Give every parameter, coordinate, basis vector and reaction a name of its own.")
        self.owners.setdefault(name, f"{kind} {name}")
        return name

    # the system -----------------------------------------------------------------------------------------
    def build(self) -> System:
        sp_ = self.spec
        for name, p in sp_.parameters.items():
            self.parameter(name, p)
        for name, d in sp_.definitions.items():
            self.definition(name, d)
        for name, c in sp_.coordinates.items():
            self.coordinate(name, c)
        self.frames()
        pending = self.points(dict(sp_.points))
        for name, b in sp_.bodies.items():
            self.add_body(name, b)
        pending = self.points(pending)
        if pending:
            for name, p in pending.items():
                if p.from_ not in pending:
                    self.point(p.from_, ("points", name, "from"))        # raises: unknown point
            name = next(iter(pending))
            raise InputError(f"the points {', '.join(pending)} are located from each other in a cycle.",
                             where=self.where("points", name, "from"),
                             hint="Locate one of them from O or another point.")
        for name, p in sp_.points.items():
            if p.body is not None:
                self.fix_point(name, p)
        for name, c in sp_.constraints.items():
            self.constraint(name, c)
        owner: dict[str, str] = {}
        for cname, c in self.s.constraints.items():
            for r in c.reactions():
                if r.name in owner or r.name in self.scope.names:
                    other = owner.get(r.name) or self.owners.get(r.name, r.name)
                    raise ModelError(f"the reaction name '{r.name}' of {c.kind} {cname} is already used by {other}.",
                                     where=self.where("constraints", cname),
                                     hint="Name the reactions apart (normal_name, friction_name, couple_name, "
                                          "prefix).")
                owner[r.name] = f"{c.kind} {cname}"
                self.reactions[r.name] = r
        for name, ld in sp_.loads.items():
            self.load(name, ld)
        self.generated_names()
        return self.s

    def generated_names(self) -> None:
        """Refuse a parameter or coordinate named as the engine names something it makes (R_Ox_hat, theta_dot_end)."""
        coords = list(self.s.coordinate_info)
        for table in ("parameters", "coordinates"):
            for name in getattr(self.spec, table):
                clash = generated_clash(name, coords, self.reactions)
                if clash:
                    raise InputError(f"the name '{name}' is {clash}.", where=self.where(table, name),
                                     hint="Choose another name.")

    def parameter(self, name, p: S.ParameterSpec):
        path = ("parameters", name)
        self.declared(name, "parameter", path)
        value = p.value
        if p.unit is not None:
            unit_dimension(p.unit, self.where(*path, "unit"))
        if value is not None:
            where = self.where(*path, "value")
            if isinstance(value, str) and not (_UNIT_QUANTITY.match(value) or _NUMBER.fullmatch(value)):
                raise InputError(f"the value {value!r} is neither a number nor a quantity with a unit.",
                                 where=where, hint="Write a number (in the parameter's unit) or a string such as "
                                                   "\"30 deg\".")
            unit = p.unit if p.unit is not None and p.unit.strip() not in ("", "1", "-") else None
            to_si(value, unit, where)             # checked here to name the field; System converts it
        sym = self.call(path, self.s.parameter, name, p.unit, p.description, value, p.dimension, p.positive)
        self.scope.names[name] = sym

    def definition(self, name, d):
        """A derived quantity of the parameters (and earlier definitions): a name in every expression."""
        path = ("definitions", name)
        self.declared(name, "definition", path)
        spec = d if isinstance(d, S.DefinitionSpec) else S.DefinitionSpec(value=d)
        expr_path = path + ("value",) if isinstance(d, S.DefinitionSpec) else path
        expr = parse_scalar(spec.value, self.scope, self.where(*expr_path))
        self.scope.names[name] = self.call(path, self.s.define, name, expr, spec.unit, spec.description)

    def coordinate(self, name, c: S.CoordinateSpec):
        path = ("coordinates", name)
        self.declared(name, "coordinate", path)
        dim = unit_dimension(c.unit, self.where(*path, "unit")) if c.unit else LENGTH if c.kind == "length" else ONE
        for key, d in (("initial", dim), ("rate", dim / TIME)):
            v = getattr(c, key)
            if v is not None:
                to_si(v, None, self.where(*path, key), d)   # finite, of the coordinate's dimension
        q = self.call(path, self.s.coordinate, name, c.sense, c.kind, c.unit, c.initial, c.rate, c.description,
                      c.positive)
        self.scope.names[name] = q
        self.scope.coordinates[name] = q

    def frames(self):
        pending = dict(self.spec.frames)
        while pending:
            ready = [n for n, f in pending.items() if f.parent in self.s.frames]
            if not ready:
                name, f = next(iter(pending.items()))
                if f.parent in pending:
                    raise InputError(f"the frames {', '.join(pending)} are rotated from each other in a cycle.",
                                     where=self.where("frames", name, "parent"),
                                     hint="Rotate one of them from F or another frame.")
                self.frame(f.parent, ("frames", name, "parent"))
            for name in ready:
                self.add_frame(name, pending.pop(name))

    def add_frame(self, name, f: S.FrameSpec):
        path = ("frames", name)
        check_name(name, "frame", self.where(*path))
        parent = self.s.frames[f.parent]
        basis = None
        if f.basis is not None:
            basis = tuple(f.basis)
            for i, b in enumerate(basis):
                self.declared(b, "basis vector", path + ("basis", i), vectors=False)
        if f.sequence is not None:
            if f.angle is not None:
                raise InputError("give either angle (with axis) or sequence (with angles), not both.",
                                 where=self.where(*path))
            if f.angles is None:
                raise InputError("a rotation sequence needs three angles.", where=self.where(*path, "sequence"),
                                 hint='Add angles = ["psi", "theta", "phi"].')
            angles = tuple(self.scalar(a, path + ("angles", i)) for i, a in enumerate(f.angles))
            fr = self.call(path, self.s.frame, name, parent, basis=basis, description=f.description,
                           sequence=f.sequence, angles=angles)
        else:
            if f.angles is not None:
                raise InputError("angles are for a rotation sequence; give sequence = \"313\" (or another) too.",
                                 where=self.where(*path, "angles"))
            angle = 0 if f.angle is None else self.scalar(f.angle, path + ("angle",))
            axis = f.axis
            if not (isinstance(axis, str) and re.fullmatch(r"\s*[+-]?\s*[A-Za-z_]\w*\s*", axis)
                    and self._is_unit(parent, axis)):
                axis = self.vector(axis, path + ("axis",))
            fr = self.call(path, self.s.frame, name, parent, angle, axis, basis, f.description)
        if basis is None:
            for b in fr.basis:
                self.declared(b, "basis vector", path, vectors=False)
        self.scope.add_frame(name, fr.basis, (fr.x, fr.y, fr.z))

    @staticmethod
    def _is_unit(frame, spec) -> bool:
        try:
            frame.unit(spec)
            return True
        except ModelError:
            return False

    def points(self, pending: dict) -> dict:
        pending = dict(pending)
        progress = True
        while pending and progress:
            progress = False
            for name in list(pending):
                p = pending[name]
                if p.from_ in self.s.points:
                    path = ("points", name)
                    offset = self.vector(p.offset, path + ("offset",))
                    self.call(path, self.s.point, name, self.s.points[p.from_], offset, description=p.description)
                    del pending[name]
                    progress = True
        return pending

    def fix_point(self, name, p: S.PointSpec):
        path = ("points", name, "body")
        body = self.body(p.body, path)
        pt = self.s.points[name]
        if pt.body is not None and pt.body is not body:
            raise ModelError(f"point {name} is already fixed in body {pt.body.name}.", where=self.where(*path),
                             hint="A point belongs to one body; declare another point at the same place.")
        pt.body = body

    def add_body(self, name, b):
        path = ("bodies", name)
        cls = SHAPES[b.shape]
        kwargs = {}
        data = b.model_dump(exclude={"shape", "frame", "at", "description", "centre_name"})
        for key, v in data.items():
            if v is None:
                if self._required_dimension(cls, key):
                    raise InputError(f"the {b.shape} shape needs its '{key}'.", where=self.where(*path),
                                     hint=f"Add {key} = ... (an expression such as \"l\").")
                continue
            if key in S._WORD_FIELDS:
                kwargs[key] = v
            elif key == "centre":
                kwargs[key] = tuple(self.scalar(c, path + ("centre", i)) for i, c in enumerate(v))
            else:
                kwargs[key] = self.scalar(v, path + (key,))
        shape = self.call(path, cls, **kwargs)
        frame = self.frame(b.frame, path + ("frame",))
        at = self.point(b.at, path + ("at",))
        self.call(path, self.s.body, name, shape, frame, at, b.description, b.centre_name)

    @staticmethod
    def _required_dimension(cls, key) -> bool:
        import inspect

        p = inspect.signature(cls).parameters.get(key)
        if p is None:
            return False
        return p.default is inspect.Parameter.empty or (isinstance(p.default, sp.Basic) and p.default == 1)

    # constraints ----------------------------------------------------------------------------------------
    def friction(self, value, path):
        if isinstance(value, S.FrictionCoefficients):   # { static = µs, kinetic = µk }: one alone means both
            if value.static is None and value.kinetic is None:
                raise InputError("a friction table needs 'static' (µs), 'kinetic' (µk) or both.",
                                 where=self.where(*path), hint="Write friction = { static = 0.5, kinetic = 0.4 }.")
            k = self.scalar(value.kinetic if value.kinetic is not None else value.static, path + ("kinetic",))
            st = self.scalar(value.static if value.static is not None else value.kinetic, path + ("static",))
            if k == 0 and st == 0:
                return "smooth"
            return {"static": st, "kinetic": k}
        if isinstance(value, str) and value.strip() in _FRICTION_WORDS:
            return value.strip()
        if isinstance(value, str) and value.strip().isidentifier() and value.strip() not in self.scope.names:
            raise InputError(f"friction must be \"smooth\", \"rolling\" or a coefficient µ, not '{value}'.",
                             where=self.where(*path),
                             hint="Write friction = \"rolling\" (no slip), \"smooth\", a number or a parameter "
                                  "such as \"mu\".")
        mu = self.scalar(value, path)
        return "smooth" if mu == 0 else mu

    def names(self, c, path):
        for key in ("normal_name", "friction_name", "couple_name", "tension_name"):
            v = getattr(c, key, None)
            if v is not None:
                check_name(v, "reaction", self.where(*path, key))

    def constraint(self, name, c):
        path = ("constraints", name)
        self.names(c, path)
        if isinstance(c, S.PinSpec):
            basis = self.frame(c.basis, path + ("basis",), optional=True)
            if c.axis is not None:
                self.call(path + ("axis",), self.s.axis_of, c.axis, f"pin {name}")
            self.call(path, self.s.pin, name, self.point(c.point, path + ("point",)),
                      self.body(c.body_a, path + ("body_a",)), self.body(c.body_b, path + ("body_b",), True),
                      self.point(c.point_b, path + ("point_b",), True), basis, c.axis, c.prefix, c.description)
        elif isinstance(c, S.ContactSpec):
            surface = self.surface(c.surface, path + ("surface",))
            arc = c.arc if not isinstance(c.arc, S.ArcSpec) else (
                self.vector(c.arc.toward, path + ("arc", "toward")), self.scalar(c.arc.half_angle,
                                                                                 path + ("arc", "half_angle")))
            if arc is True:
                arc = None
            self.call(path, self.s.contact, name, self.body(c.body, path + ("body",)), surface,
                      self.point(c.centre, path + ("centre",), True), self.scalar(c.radius, path + ("radius",)),
                      self.friction(c.friction, path + ("friction",)), c.unilateral, c.normal_name,
                      c.friction_name, c.description, arc=arc)
        elif isinstance(c, S.DiskContactSpec):
            self._needs("disk_contact", path)
            surface = self.surface(c.surface, path + ("surface",))
            self.call(path, self.s.disk_contact, name, self.body(c.body, path + ("body",)), surface,
                      self.vector(c.axis, path + ("axis",)), self.scalar(c.radius, path + ("radius",)),
                      self.point(c.centre, path + ("centre",), True), self.friction(c.friction, path + ("friction",)),
                      c.unilateral, c.normal_name, c.friction_name, c.description)
        elif isinstance(c, S.CableSpec):
            self._needs("cable", path)
            points = [self.point(p, path + ("points", i)) for i, p in enumerate(c.points)]
            bodies = None
            if c.bodies is not None:
                bodies = [self.body(b, path + ("bodies", i), optional=True) if b else None
                          for i, b in enumerate(c.bodies)]
            self.call(path, self.s.cable, name, points, self.scalar(c.length, path + ("length",)), bodies,
                      c.tension_name, c.description)
        elif isinstance(c, S.RopeSpec):
            from ..model.ropes import Wrap

            stations = []
            for i, st in enumerate(c.path):
                here = path + ("path", i)
                if isinstance(st, S.WrapSpec):
                    mu = None if st.mu is None else self.scalar(st.mu, here + ("mu",))
                    stations.append(Wrap(self.body(st.pulley, here + ("pulley",)),
                                         self.scalar(st.radius, here + ("radius",)), st.sense,
                                         self.point(st.centre, here + ("centre",), True), mu))
                else:
                    stations.append(self.point(st, here))
            self.call(path, self.s.rope, name, stations, c.tensions, c.description)
        else:
            self.call(path, self.s.collar, name, self.body(c.body, path + ("body",)),
                      self.vector(c.along, path + ("along",)), self.point(c.through, path + ("through",), True),
                      self.point(c.point, path + ("point",), True),
                      self.body(c.track_body, path + ("track_body",), True),
                      self.friction(c.friction, path + ("friction",)), c.normal_name, c.couple_name, c.description)

    def _needs(self, method: str, path) -> None:
        if not hasattr(self.s, method):
            raise InputError(f"this version of rigidkin has no '{method}' constraint.", where=self.where(*path))

    def surface(self, f, path):
        body = self.body(f.body, path + ("body",), True)
        if isinstance(f, S.LineSpec):
            return self.call(path, self.s.line, self.point(f.point, path + ("point",)),
                             self.vector(f.normal, path + ("normal",)), body, f.name)
        normal = None if f.normal is None else self.vector(f.normal, path + ("normal",))
        return self.call(path, self.s.circle, self.point(f.centre, path + ("centre",)),
                         self.scalar(f.radius, path + ("radius",)), f.inside, body, f.name, normal)

    # loads ------------------------------------------------------------------------------------------------
    def load(self, name, ld):
        path = ("loads", name)
        s = self.s
        P = lambda key, opt=False: self.point(getattr(ld, key), path + (key,), opt)  # noqa: E731
        B = lambda key, opt=False: self.body(getattr(ld, key), path + (key,), opt)  # noqa: E731
        sc = lambda key: self.scalar(getattr(ld, key), path + (key,))  # noqa: E731
        vec = lambda key: None if getattr(ld, key) is None else self.vector(getattr(ld, key), path + (key,))  # noqa: E731
        if isinstance(ld, S.GravitySpec):
            self.call(path, s.gravity, sc("g"), vec("direction"), name=name)
        elif isinstance(ld, S.ForceSpec):
            self.call(path, s.force, name, P("point"), vec("vector"), B("body", True), ld.description,
                      on=B("on", True))
        elif isinstance(ld, S.TorqueSpec):
            self.call(path, s.torque, name, B("body"), vec("vector"), B("reaction_body", True), ld.description)
        elif isinstance(ld, S.SpringSpec):
            self.call(path, s.spring, name, P("point_a"), P("point_b"), sc("stiffness"), sc("natural_length"),
                      B("body_a", True), B("body_b", True), ld.description, on_a=B("on_a", True), on_b=B("on_b", True))
        elif isinstance(ld, S.TorsionalSpringSpec):
            self.call(path, s.torsional_spring, name, B("body_a"), sc("stiffness"), sc("angle"),
                      sc("natural_angle"), B("body_b", True), vec("axis"), ld.description)
        elif isinstance(ld, S.DamperSpec):
            if "v" in self.scope.names:
                raise InputError("a damper law is written in the speed v, but 'v' is also declared (a parameter "
                                 "or coordinate).", where=self.where(*path, "law"), hint="Rename that 'v'.")
            law = self.scalar(ld.law, path + ("law",), self.scope.with_names({"v": DAMPER_SPEED}))
            self.call(path, s.damper, name, P("point_a"), law, vec("along"), P("point_b", True),
                      B("body_a", True), B("body_b", True), ld.description, on_a=B("on_a", True), on_b=B("on_b", True))
        elif isinstance(ld, S.FrictionSpec):
            normal_force = self.scalar(ld.normal_force, path + ("normal_force",),
                                       self.scope.with_names(self.reactions))
            self.call(path, s.friction, name, B("body"), P("centre"), vec("normal"), sc("mu"), normal_force,
                      sc("radius"), B("against_body", True), P("against_point", True), ld.description)
        else:
            self.call(path, s.impulse, name, P("point"), vec("vector"), B("body", True), ld.description,
                      on=B("on", True))

    # questions --------------------------------------------------------------------------------------------
    def _question_scope(self) -> Scope:
        return self.scope.with_names(self.reactions).with_functions({"slip": _slip_handler(self.s)}) \
            .with_max_derivative(2)

    def state(self, table: dict, path) -> dict:
        out = {}
        sc = self.scope
        for key, v in table.items():
            kpath = path + (key,)
            target = parse_scalar(key, sc, self.where(*kpath))
            coords = set(sc.coordinates.values())
            ok = target in coords or (isinstance(target, sp.Derivative) and target.expr in coords
                                      and target.derivative_count == 1)
            if not ok:
                raise InputError(f"'{key}' is not a coordinate or the rate of one.", where=self.where(*kpath),
                                 hint="A state gives coordinates and their rates, e.g. "
                                      "{ theta = 0, \"dot(theta)\" = 0 }.")
            c = self.s.coordinate_of(target if target in coords else target.expr)
            out[target] = self.value(v, kpath, c.dimension if target in coords else c.dimension / TIME)
        return out

    def mode(self, table: dict, path) -> dict:
        for cname, state in table.items():
            c = self._lookup(self.s.constraints, "constraint", cname, path + (cname,))
            if state not in c.states:
                raise InputError(f"'{state}' is not a state of {c.kind} {cname}.", where=self.where(*path, cname),
                                 hint=f"States: {', '.join(c.states)}.")
        return dict(table)

    def substitutions(self, table: dict, path) -> dict:
        out = {}
        for pname, v in table.items():
            sym = self._lookup(self.s.parameters, "parameter", pname, path + (pname,))
            info = self.s.parameter_info[pname]
            where = self.where(*path, pname)
            value = self.value(v, path + (pname,), info.dimension if info.unit or info.dimension != ONE else None)
            # zero is allowed for a positive parameter here: a limiting case (µ = 0 on a frictionless stretch)
            out[sym] = require(value, NONNEGATIVE if sym.is_positive else REAL, f"value of the parameter {pname}",
                               where, self.s.parameter_values(), InputError)
        return out

    def questions(self, ask: S.AskSpec) -> tuple[Question, ...]:
        out, seen = [], {}
        for name in ask.reactions or ():
            if name not in self.reactions:
                self._lookup(self.reactions, "reaction", name, ("ask", "reactions"))
        kinds = [q.kind for q in ask.question]
        for i, q in enumerate(ask.question):
            path = ("ask", "question", i)
            qname = q.name or (q.kind if kinds.count(q.kind) == 1 else f"{q.kind}_{i + 1}")
            if qname in seen:
                raise InputError(f"two questions are named '{qname}'.", where=self.where(*path, "name"),
                                 hint="Give each question a name of its own.")
            seen[qname] = i
            fields = self.question_fields(q, path, seen)
            out.append(Question(q.kind, qname, fields, self.where(*path)))
        return tuple(out)

    def question_fields(self, q, path, seen) -> dict:
        qs = self._question_scope()
        f: dict = {}
        for key in type(q).model_fields:
            v = getattr(q, key)
            if key in ("kind", "name") or v is None:
                continue
            kpath = path + (key,)
            if key == "description":
                if v:
                    f[key] = v
            elif key == "mode":
                f[key] = self.mode(v, kpath)
            elif key == "set":
                f[key] = self.substitutions(v, kpath)
            elif key == "after":
                if v not in seen or seen[v] >= path[-1]:
                    raise InputError(f"'after = \"{v}\"' names no earlier question.", where=self.where(*kpath),
                                     hint=f"Earlier questions: {', '.join(n for n in seen if seen[n] < path[-1])}.")
                f[key] = v
            elif key in ("start", "at"):
                f[key] = self.state(v, kpath)
            elif key in ("when", "until"):
                f[key] = parse_equation(v, qs, self.where(*kpath))
            elif key in ("holds", "regime"):
                f[key] = parse_condition(v, qs, self.where(*kpath))
            elif key == "reaction":
                self._lookup(self.reactions, "reaction", v, kpath)
                f[key] = v
            elif key == "coordinate":
                f[key] = self._lookup(self.scope.coordinates, "coordinate", v, kpath)
            elif key in ("duration", "expression"):
                f[key] = parse_scalar(v, qs, self.where(*kpath))
            elif key == "over":
                f[key] = tuple(self.value(x, kpath + (i,)) for i, x in enumerate(v))
            elif key == "phase":
                f[key] = [self.phase(p, kpath + (j,)) for j, p in enumerate(v)]
            else:  # a field the schema knows and this reader does not: keep it as written
                f[key] = v
        if q.kind == "interval" and "duration" not in f and "until" not in f:
            raise InputError("an interval question needs 'duration' or 'until'.", where=self.where(*path),
                             hint="Add duration = \"dt\" or until = \"slip(ground) = 0\".")
        return f

    def phase(self, p: S.PhaseSpec, path) -> dict:
        out = {"name": p.name or f"phase {path[-1] + 1}", "mode": self.mode(p.mode, path + ("mode",)),
               "set": self.substitutions(p.set, path + ("set",))}
        out["until"] = None if p.until is None else parse_equation(p.until, self._question_scope(),
                                                                    self.where(*path, "until"))
        return out


def _slip_handler(system):
    """``slip(contact)`` in conditions: the slip speed at a contact of ``system``."""

    def slip_of(args, node, parser):
        if len(args) != 1 or not hasattr(args[0], "id"):
            raise parser.fail("slip() takes the name of one contact, e.g. slip(ground)", node)
        cname = args[0].id
        c = system.constraints.get(cname)
        if not isinstance(c, Contact):
            contacts = [n for n, k in system.constraints.items() if isinstance(k, Contact)]
            raise parser.fail(f"'{cname}' is not a contact, so slip({cname}) is not defined", node,
                              hint=f"Contacts: {', '.join(contacts) or 'none'}.")
        return slip(sp.Symbol(cname))

    return slip_of


def system_scope(system, reactions: bool = True) -> Scope:
    """The names an expression about ``system`` may use, whether it was built in Python or from a file.

    Parameters, coordinates (with ``dot``/``ddot``), ``t``, ``pi``, every frame's basis vectors and,
    with ``reactions``, the reaction names and ``slip(contact)``.  For example, to read an expected
    equation of motion: ``parse_equation("ddot(theta) = 3*g*sin(theta)/(2*l)", system_scope(system))``.
    """
    sc = default_scope()
    sc.names.update(system.parameters)
    sc.names.update({n: d.quantity for n, d in system.definitions.items()})
    for name, c in system.coordinate_info.items():
        sc.names[name] = c.symbol
        sc.coordinates[name] = c.symbol
    for name, fr in system.frames.items():
        sc.add_frame(name, fr.basis, (fr.x, fr.y, fr.z))
    if reactions:
        for c in system.constraints.values():
            for r in c.reactions():
                sc.names.setdefault(r.name, r)
        sc = sc.with_functions({"slip": _slip_handler(system)})
    return sc


# entry points ---------------------------------------------------------------------------------------------
def load_problem(path: Path | str) -> tuple[System, ProblemSpec]:
    """Read, check and build a problem file: returns ``(system, spec)``."""
    path = Path(path)
    text, data = read_toml(path)
    return build_problem(data, text, path)


def parse_problem(text: str, filename: str = "<problem>") -> tuple[System, ProblemSpec]:
    """A problem from TOML text (as if read from ``filename``): returns ``(system, spec)``."""
    if len(text) > MAX_FILE_BYTES:
        raise InputError(f"the problem text is {len(text)} characters long (at most {MAX_FILE_BYTES}).",
                         where=filename)
    return build_problem(_parse_toml(text, filename), text, Path(filename))


def build_problem(data: dict, text: str = "", path: Path | str = "<problem>") -> tuple[System, ProblemSpec]:
    """A problem from parsed TOML ``data`` (``text``, if given, lets errors name lines)."""
    path = Path(path)
    check_tree(data, str(path))
    locator = Locator(text, str(path))
    spec = validate_schema(data, locator)
    if spec.name is not None:
        name = check_problem_name(spec.name, locator.where(("name",)), InputError)
    else:
        name = problem_name(path.stem)
    builder = _Builder(spec, locator, name)
    system = builder.build()
    questions = builder.questions(spec.ask)
    ps = ProblemSpec(path, name, spec.title, spec.statement, spec.ask.eom,
                     None if spec.ask.reactions is None else tuple(spec.ask.reactions), questions,
                     builder._question_scope(), locator, spec)
    return system, ps


def where_in(spec: ProblemSpec | None, *path) -> str | None:
    """The location of a field path in a problem file (None without a file)."""
    return spec.where(*path) if spec is not None else None


__all__ = ["ProblemSpec", "load_problem", "parse_problem", "build_problem", "read_toml", "validate_schema",
           "system_scope", "where_in", "dotted"]
