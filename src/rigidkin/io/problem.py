"""Reading a problem file: TOML → schema check → a ``rigidkin.System`` built through its public methods.

``load_problem(path)`` returns ``(system, spec)``; ``spec`` (a :class:`ProblemSpec`) keeps what the
file asks (``[ask]``: the equations of motion, reactions, and questions as
:class:`rigidkin.analysis.questions.Question` objects) and can say where any field is written.
Every problem is reported as an :class:`~rigidkin.base.errors.InputError` (or the model's own
``ModelError``) naming the file, the line, the field path and what to do.
"""

from __future__ import annotations

import difflib
import re
from pathlib import Path

import sympy as sp
from sympy.physics.vector import Vector

from ..base.errors import InputError, ModelError, RigidkinError
from ..base.units import LENGTH, ONE, TIME, to_si, unit_dimension
from ..model.checks import REAL, check_problem_name, generated_clash, problem_name, require
from ..model.shapes import SHAPES
from ..model.system import System
from . import schema as S
from .build_loads import ConstraintsAndLoads
from .build_prescribed import build_prescribed
from .build_questions import Questions, _slip_handler
from .build_units import UnitsAndDimensions
from .expressions import (
    Scope,
    check_name,
    default_scope,
    parse_scalar,
    parse_vector,
)
from .locate import Locator, dotted
from .prescan import check_tree
from .reading import (  # noqa: F401  (public through here)
    MAX_FILE_BYTES,
    _parse_toml,
    _toml_error,
    read_toml,
    validate_schema,
)
from .spec import ProblemSpec

_UNIT_QUANTITY = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*[A-Za-z°µ]")
_QUANTITY_ALONE = re.compile(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*[A-Za-z°µ][\w\s*/^()°µ.-]*")
_NUMBER = re.compile(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*")
_FRICTION_WORDS = ("smooth", "rolling", "no-slip", "no_slip")


class _Builder(ConstraintsAndLoads, Questions, UnitsAndDimensions):
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

    def scalar(self, value, path, scope=None, dimension=None) -> sp.Expr:
        """A scalar expression, real and finite once the parameters' values are put in; quantities with units
        in it are of the field's dimension and are read in SI units."""
        where = self.where(*path)
        return require(self.parsed(value, path, scope, parse_scalar, dimension), REAL, "value", where,
                       self.s.parameter_values(), InputError)

    def vector(self, value, path, scope=None) -> Vector:
        where = self.where(*path)
        vec = self.parsed(value, path, scope, parse_vector)
        for measure, _frame in vec.args:
            for comp in measure:
                require(comp, REAL, "vector component", where, self.s.parameter_values(), InputError)
        return vec

    def value(self, value, path, dimension=None) -> sp.Expr:
        """A number, a quantity with a unit ('30 deg', converted to SI; of ``dimension`` if given) or an
        expression (which may hold quantities: "theta0 + 5 deg")."""
        if isinstance(value, str) and _UNIT_QUANTITY.match(value):
            try:
                return sp.Float(to_si(value, None, self.where(*path), dimension))
            except InputError:
                if _QUANTITY_ALONE.fullmatch(value):
                    raise
        return self.scalar(value, path, self._question_scope(), dimension)

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
        for name, i in sp_.inputs.items():
            self.input(name, i)
        for name, c in sp_.coordinates.items():
            self.coordinate(name, c)
        self.frames()
        if not self.s.coordinates:
            raise InputError("the required field 'coordinates' is missing: nothing can move.",
                             where=self.where("coordinates"),
                             hint="Add a [coordinates] table, or orient a frame by a quaternion "
                                  "(quaternion = [\"e0\", \"e1\", \"e2\", \"e3\"]), which declares its own.")
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
        for name, c in sp_.coordinates.items():
            build_prescribed(self, name, c)
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
        self.check_dimensions()
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
        self.unit_warning(name, p, path)
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

    def input(self, name, i: S.InputSpec):
        """An input u(t) ([inputs]): a name in every expression, printed as name(t)."""
        path = ("inputs", name)
        self.declared(name, "input", path)
        history = None if i.history is None else self.scalar(i.history, path + ("history",))
        self.scope.names[name] = self.call(path, self.s.input, name, i.unit, i.description, history=history)

    def definition(self, name, d):
        """A derived quantity of the parameters (and earlier definitions): a name in every expression."""
        path = ("definitions", name)
        self.declared(name, "definition", path)
        spec = d if isinstance(d, S.DefinitionSpec) else S.DefinitionSpec(value=d)
        expr_path = path + ("value",) if isinstance(d, S.DefinitionSpec) else path
        self.no_quantities(spec.value, expr_path)
        expr = parse_scalar(spec.value, self.scope, self.where(*expr_path))
        self.scope.names[name] = self.call(path, self.s.define, name, expr, spec.unit, spec.description)

    def coordinate(self, name, c: S.CoordinateSpec):
        path = ("coordinates", name)
        self.declared(name, "coordinate", path)
        dim = unit_dimension(c.unit, self.where(*path, "unit")) if c.unit else LENGTH if c.kind == "length" else ONE
        values = {}
        unit = c.unit if c.unit is not None and c.unit.strip() not in ("", "1", "-") else None
        for key, d, u in (("initial", dim, unit), ("rate", dim / TIME, unit and f"({unit})/s")):
            v = getattr(c, key)
            if v is not None:
                to_si(v, None, self.where(*path, key), d)   # finite, of the coordinate's dimension
            plain = isinstance(v, int | float) or isinstance(v, str) and _NUMBER.fullmatch(v)
            # a plain number is in the coordinate's unit (unit = "cm", initial = 5 is 5 cm), as a parameter's value
            values[key] = to_si(v, u, self.where(*path, key)) if u and plain else v
        q = self.call(path, self.s.coordinate, name, c.sense, c.kind, c.unit, values["initial"], values["rate"],
                      c.description, c.positive)
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
        if f.quaternion is not None or f.speeds is not None or f.initial is not None or f.rates is not None:
            fr = self.orientation_frame(name, f, parent, basis, path)
        elif f.sequence is not None:
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

    def orientation_frame(self, name, f: S.FrameSpec, parent, basis, path):
        """A frame oriented by a quaternion, or by a sequence with angular speeds (``rigidkin.model.speeds``)."""
        if f.quaternion is None:
            if f.sequence is None or f.speeds is None:
                field = "initial" if f.initial is not None else "rates" if f.rates is not None else "speeds"
                raise InputError(f"{field} belongs to a frame oriented by a quaternion (or, for speeds and rates, by "
                                 "a sequence with speeds).", where=self.where(*path, field),
                                 hint='Write quaternion = ["e0", "e1", "e2", "e3"], or sequence and angles with '
                                      'speeds = ["w1", "w2", "w3"].')
            if f.initial is not None:
                raise InputError("initial is the quaternion's start; a sequence's angles start with their "
                                 "coordinates.", where=self.where(*path, "initial"))
        else:
            for key in ("angle", "sequence", "angles"):
                if getattr(f, key) is not None:
                    raise InputError(f"give either a quaternion or {key}, not both.", where=self.where(*path, key))
            for i, n in enumerate(f.quaternion):
                self.declared(n, "coordinate", path + ("quaternion", i))
        for i, n in enumerate(f.speeds or ()):
            self.declared(n, "speed", path + ("speeds", i))
        initial = None if f.initial is None else \
            tuple(to_si(v, None, self.where(*path, "initial", i), ONE) for i, v in enumerate(f.initial))
        rates = None if f.rates is None else \
            tuple(to_si(v, None, self.where(*path, "rates", i), ONE / TIME) for i, v in enumerate(f.rates))
        if f.quaternion is not None:
            fr = self.call(path, self.s.frame, name, parent, basis=basis, description=f.description,
                           quaternion=tuple(f.quaternion), speeds=None if f.speeds is None else tuple(f.speeds),
                           initial=initial, rates=rates)
            for q in fr.quaternion:
                self.scope.names[q.func.__name__] = q
                self.scope.coordinates[q.func.__name__] = q
        else:
            angles = tuple(self.scalar(a, path + ("angles", i)) for i, a in enumerate(f.angles or ()))
            fr = self.call(path, self.s.frame, name, parent, basis=basis, description=f.description,
                           sequence=f.sequence, angles=angles, speeds=tuple(f.speeds), rates=rates)
        group = self.s.speed_groups[name]
        self.scope.add_speeds(group.names, group.speeds)
        return fr

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
        data = b.model_dump(exclude={"shape", "frame", "at", "description", "centre_name", "driven", "drive_torque",
                                     "drive_force", "drive_joint", "drive_carrier"})
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
        if b.driven:        # moved by the laws of t in its frame and point, with the effort that drives it
            joint = self.point(b.drive_joint, path + ("drive_joint",)) if b.drive_joint else None
            carrier = self.body(b.drive_carrier, path + ("drive_carrier",)) if b.drive_carrier else None
            self.call(path, self.s.drive, name, frame, at, shape, torque=b.drive_torque, force=b.drive_force,
                      description=b.description, joint=joint, carrier=carrier)
            return
        if b.drive_torque or b.drive_force or b.drive_joint or b.drive_carrier:
            raise InputError("drive_torque, drive_force, drive_joint and drive_carrier are for a driven body.",
                             where=self.where(*path), hint="Add driven = true, or remove them.")
        self.call(path, self.s.body, name, shape, frame, at, b.description, b.centre_name)

    @staticmethod
    def _required_dimension(cls, key) -> bool:
        import inspect

        p = inspect.signature(cls).parameters.get(key)
        if p is None:
            return False
        return p.default is inspect.Parameter.empty or (isinstance(p.default, sp.Basic) and p.default == 1)


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
    for group in getattr(system, "speed_groups", {}).values():     # body angular speeds: w, and dot(w) = ẇ
        sc.add_speeds(group.names, group.speeds)
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
    builder.check_question_dimensions(questions)
    ps = ProblemSpec(path, name, spec.title, spec.statement, spec.ask.eom,
                     None if spec.ask.reactions is None else tuple(spec.ask.reactions), questions,
                     builder._question_scope(), locator, spec, tuple(getattr(builder, "reading_warnings", ())))
    return system, ps


def where_in(spec: ProblemSpec | None, *path) -> str | None:
    """The location of a field path in a problem file (None without a file)."""
    return spec.where(*path) if spec is not None else None


__all__ = ["ProblemSpec", "load_problem", "parse_problem", "build_problem", "read_toml", "validate_schema",
           "system_scope", "where_in", "dotted"]
