"""The system model: the one description of a mechanical system that every law reads.

``System`` collects parameters, coordinates, frames and bases, points, bodies, constraints and
loads, each under a unique name.  It checks what it is given as it is given (an unknown point, a
vector that is not a vector, a point declared fixed in a body that moves relative to it) and raises
``ModelError`` with the name of the object involved.  ``System.solve`` derives the equations of
motion and reactions with a chosen law.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..base import display
from ..base.errors import ModelError
from ..base.units import NAMED, ONE, Dimension, to_si, unit_dimension
from . import constraints as C
from . import loads as L
from .bodies import Body
from .chains import remember, shallow
from .checks import NONNEGATIVE, POSITIVE, REAL, check_identifier, require
from .definitions import Defined, Definition
from .definitions import define as define_quantity
from .frames import Frame, make_reference_frame
from .points import Point
from .quantities import Coordinate, Parameter, declared_dimension
from .shapes import Shape
from .speeds import angular_group, quasi_coordinate, quaternion_dcm, quaternion_group
from .surfaces import Circle, Line
from .system_constraints import ConstraintMethods
from .system_drive import DriveMethods
from .system_loads import LoadMethods
from .values import _expr, _friction

t = dynamicsymbols._t

_GREEK_LATEX = {"theta": r"\theta", "phi": r"\phi", "psi": r"\psi", "beta": r"\beta", "alpha": r"\alpha"}


def _latex_basis(basis):
    out = []
    for b in basis:
        head, tail = b[0], b[1:]
        tail_tex = _GREEK_LATEX.get(tail, tail.replace("θ", r"\theta").replace("φ", r"\phi"))
        out.append(rf"\mathbf{{{head}}}_{{{tail_tex}}}" if tail else rf"\mathbf{{{head}}}")
    return tuple(out)


class System(ConstraintMethods, LoadMethods, DriveMethods):
    """A system of rigid bodies: build it with the methods below, then call :meth:`solve`.

    >>> import rigidkin as rk
    >>> s = rk.System("pendulum")
    >>> m, l, g = s.parameter("m", "kg"), s.parameter("l", "m"), s.parameter("g", "m/s^2")
    >>> th = s.coordinate("theta", "angle of the rod from the downward vertical, counter-clockwise")
    >>> R = s.frame("R", angle=th)
    >>> G = s.point("G", offset=-l / 2 * R.y)
    >>> rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=G)
    >>> _ = s.pin("O", s.origin, rod)
    >>> s.gravity(g)
    >>> s.solve().accelerations[th]
    -3*g*sin(theta(t))/(2*l)
    """

    def __init__(self, name: str = "system", statement: str = "", title: str | None = None):
        self.name = name
        self.title = title or name
        self.statement = statement
        self._parameters: dict[str, Parameter] = {}
        self._coordinates: dict[str, Coordinate] = {}
        self.frames: dict[str, Frame] = {}
        self.points: dict[str, Point] = {}
        self.bodies: dict[str, Body] = {}
        self.constraints: dict[str, C.Constraint] = {}
        self.loads: dict[str, L.Load] = {}
        self.definitions: dict[str, Definition] = {}     # derived quantities (System.define)
        self._names: dict[str, str] = {}
        self._derived = self._kinematic_equations = None     # what was derived from this description
        self.speed_groups: dict = {}                     # frame name → SpeedGroup (model/speeds.py)
        basis = ("Ex", "Ey", "Ez")
        ref = make_reference_frame("F", basis, _latex_basis(basis))
        self.inertial = Frame("F", ref, basis, description="the inertial frame (the ground)")
        self.frames["F"] = self.inertial
        self.origin = Point("O", description="fixed origin")
        self.points["O"] = self.origin
        self._names["frame:F"] = "the inertial frame F"
        self._names["point:O"] = "the fixed origin O"

    # names ---------------------------------------------------------------------------------------
    def _claim(self, name: str, kind: str, namespace: str = "symbol", owner: str | None = None) -> None:
        check_identifier(name, kind, owner or f"{kind} {name}")
        key = f"{namespace}:{name}"
        if key in self._names:
            of = f" of {owner}" if owner else ""
            raise ModelError(f"the name '{name}'{of} is already used by {self._names[key]}.",
                             where=owner or f"{kind} {name}", hint="Give each object a name of its own.")
        self._names[key] = owner or f"{kind} {name}"
        self._derived = self._kinematic_equations = None     # the description changed: void what was derived

    # parameters and coordinates ---------------------------------------------------------------
    def parameter(self, name: str, unit: str | None = None, description: str = "", value=None,
                  dimension: str | Dimension | None = None, positive: bool = True) -> sp.Symbol:
        """Declare a parameter; returns its positive real sympy Symbol.

        ``value`` is a number in ``unit`` (``unit="cm", value=50`` is 0.5 m) or a quantity string
        (``"30 deg"``); it is stored in SI.
        """
        where = f"parameter {name}"
        dim = declared_dimension(unit, dimension, where)
        si_unit = unit if unit is not None and str(unit).strip() not in ("", "1", "-") else None
        val = None if value is None else to_si(value, si_unit, where, None if si_unit else dim)
        if positive and val is not None and val <= 0:
            raise ModelError(f"the value {value!r} of a positive parameter is {val:g}.", where=where,
                             hint="Give a positive value, or declare the parameter with positive=False (in a "
                                  "problem file: positive = false) if it may be zero or negative.")
        sym = sp.Symbol(name, positive=True) if positive else sp.Symbol(name, real=True)
        self._claim(name, "parameter")
        self._parameters[name] = Parameter(name, sym, description, unit or "", dim, val)
        return sym

    def coordinate(self, name: str, sense: str = "", kind: str = "angle", unit: str | None = None,
                   initial=None, rate=None, description: str = "", positive: bool = False) -> sp.Function:
        """Declare a generalised coordinate; returns the dynamicsymbol q(t).

        ``sense`` says where it is measured from and which way is positive.  Coordinates declared first are
        kept as independent; later ones are eliminated first by the constraints.
        """
        self._claim(name, "coordinate")
        if kind not in ("angle", "length", "other"):
            raise ModelError(f"kind must be 'angle', 'length' or 'other', not '{kind}'.",
                             where=f"coordinate {name}")
        dim = unit_dimension(unit) if unit else (NAMED["length"] if kind == "length" else ONE)
        assumptions = {"positive": True} if positive else {"real": True}
        sym = dynamicsymbols(name, **assumptions)
        where = f"coordinate {name}"
        q0 = None if initial is None else to_si(initial, None, f"{where}, initial value", dim)
        u0 = None if rate is None else to_si(rate, None, f"{where}, initial rate", dim / NAMED["time"])
        self._coordinates[name] = Coordinate(name, sym, sense, kind, dim, q0, u0, description)
        return sym

    def define(self, name: str, expression, unit: str | None = None, description: str = "") -> Defined:
        """A derived quantity ``name`` = ``expression`` (of parameters and earlier definitions).

        Returns a quantity that prints as ``name`` in every result and means its definition in every
        number (simulation, generated code); checked for dimensions (against ``unit`` if given) and for
        being real with the parameters' values (positive when its value is).  E.g.
        ``a = s.define("a", sp.sqrt(R**2 - l**2), "m", "distance of the chord from the centre")``.
        """
        where = f"definition {name}"
        d = define_quantity(self, name, _expr(expression, where), unit, description, where)
        self._claim(name, "definition")
        self.definitions[name] = d
        return d.quantity

    @property
    def parameters(self) -> dict[str, sp.Symbol]:
        """Parameter name → sympy Symbol."""
        return {k: p.symbol for k, p in self._parameters.items()}

    @property
    def parameter_info(self) -> dict[str, Parameter]:
        return dict(self._parameters)

    @property
    def coordinates(self) -> tuple:
        """The generalised coordinates (dynamicsymbols), in declaration order."""
        return tuple(c.symbol for c in self._coordinates.values())

    @property
    def coordinate_info(self) -> dict[str, Coordinate]:
        return dict(self._coordinates)

    def coordinate_of(self, symbol) -> Coordinate:
        for c in self._coordinates.values():
            if c.symbol == symbol:
                return c
        raise KeyError(symbol)

    def parameter_values(self) -> dict[sp.Symbol, float]:
        """Numeric values of the parameters that have one."""
        return {p.symbol: p.value for p in self._parameters.values() if p.value is not None}

    # frames and points -----------------------------------------------------------------------
    def frame(self, name: str, parent: Frame | None = None, angle=None, axis: str | Vector = "z",
              basis: tuple[str, str, str] | None = None, description: str = "",
              sequence: str | None = None, angles=None, quaternion=None, speeds=None, initial=None,
              rates=None) -> Frame:
        """A frame rotated from ``parent`` (default: the inertial frame) by ``angle`` about ``axis``.

        ``axis`` is a basis vector name of the parent (``"z"``, ``"-y"``) or a vector fixed in the
        parent.  For 3D, ``sequence="313"`` (or "321", ...) with three ``angles`` gives a body-fixed
        rotation sequence.  ``quaternion=("e0", "e1", "e2", "e3")`` (or ``True`` for names made from
        the frame's) orients it by Euler parameters instead, declared here as coordinates (``initial``:
        their four values, default (1, 0, 0, 0)); its angular-velocity components along its own basis
        relative to ``parent`` are then its generalised speeds (``speeds``: their names, default
        ``w_<basis>``; ``rates``: their initial values).  ``speeds=`` with a ``sequence`` asks for the same
        speeds for Euler angles (Kane's choice; the default there is u = q̇).  See ``rigidkin.model.speeds``.
        """
        if quaternion is not None and quaternion is not False:
            return self._quaternion_frame(name, parent, basis, description, quaternion, speeds, initial, rates,
                                          sequence, angles, angle)
        if (initial is not None or rates is not None) and speeds is None:
            raise ModelError("initial and rates are for a frame oriented by a quaternion (or with speeds).",
                             where=f"frame {name}", hint="Give the angles' initial values with their coordinates.")
        fr = self._plain_frame(name, parent, angle, axis, basis, description, sequence, angles)
        if speeds is not None:
            if sequence is None:
                raise ModelError("angular speeds need a frame oriented by a rotation sequence or a quaternion.",
                                 where=f"frame {name}", hint="Use System.angular_speeds(frame, coordinates=...) for "
                                                             "a chain of frames.")
            self.angular_speeds(fr, speeds, fr.angles, rates)
        return fr

    def _plain_frame(self, name, parent, angle, axis, basis, description, sequence, angles, orient=None) -> Frame:
        self._claim(name, "frame", "frame")
        parent = parent or self.inertial
        self._check_frame(parent, f"frame {name}")
        basis = tuple(basis) if basis else (f"{name.lower()}x", f"{name.lower()}y", f"{name.lower()}z")
        if len(basis) != 3 or len(set(basis)) != 3:
            raise ModelError("a basis needs three distinct names.", where=f"frame {name}")
        ref = make_reference_frame(name, basis, _latex_basis(basis))
        if orient is not None:
            fr = orient(ref, parent, basis)
        elif sequence is not None:
            if angles is None or len(angles) != 3:
                raise ModelError("a rotation sequence needs three angles.", where=f"frame {name}")
            ref.orient_body_fixed(parent.ref, tuple(angles), sequence)
            remember(ref, parent.ref, None, None)
            fr = Frame(name, ref, basis, parent, None, None, sequence, tuple(angles), description)
        else:
            ang = _expr(0 if angle is None else angle, f"frame {name}")
            ax = parent.unit(axis) if isinstance(axis, str) else axis
            if not isinstance(ax, Vector):
                raise ModelError(f"axis must be a basis name or a vector, not {axis!r}.", where=f"frame {name}")
            ref.orient_axis(parent.ref, ax, ang)
            remember(ref, parent.ref, ax.express(parent.ref).normalize().to_matrix(parent.ref), ang)
            fr = Frame(name, ref, basis, parent, ang, ax, None, None, description)
        self.frames[name] = fr
        return fr

    def _quaternion_frame(self, name, parent, basis, description, quaternion, speeds, initial, rates,
                          sequence, angles, angle) -> Frame:
        """A frame oriented by Euler parameters, its angular-velocity components as speeds."""

        where = f"frame {name}"
        if sequence is not None or angles is not None or angle is not None:
            raise ModelError("give either a quaternion or angles (angle, or sequence with angles), not both.",
                             where=where)
        basis_t = tuple(basis) if basis else (f"{name.lower()}x", f"{name.lower()}y", f"{name.lower()}z")
        names = tuple(f"{name}_e{i}" for i in range(4)) if quaternion is True else tuple(quaternion)
        if len(names) != 4 or not all(isinstance(n, str) for n in names):
            raise ModelError("a quaternion needs the names of its four Euler parameters (e0, e1, e2, e3).",
                             where=where, hint='Write quaternion=("e0", "e1", "e2", "e3"), scalar part first.')
        snames = tuple(f"w_{b}" for b in basis_t) if speeds is None or speeds is True else tuple(speeds)
        if len(snames) != 3 or not all(isinstance(n, str) for n in snames):
            raise ModelError("the angular speeds of a frame need three names.", where=where)
        init = (1, 0, 0, 0) if initial is None else tuple(initial)
        w0 = (None, None, None) if rates is None else tuple(rates)
        if len(init) != 4 or len(w0) != 3:
            raise ModelError("a quaternion's initial value has four numbers and its speeds' rates three.",
                             where=where)
        vals = []
        for i, v in enumerate(init):
            vals.append(self._number(v, f"{where}, initial {names[i]}"))
        norm = sum(v * v for v in vals) ** 0.5
        if not norm > 0:
            raise ModelError("the initial quaternion is zero, which is no rotation.", where=where,
                             hint="Give (1, 0, 0, 0) for the frame aligned with its parent.")
        w0 = tuple(None if v is None else self._number(v, f"{where}, initial rate") for v in w0)
        holder = {}

        def orient(ref, par, basis_):
            for n in snames:
                self._claim(n, "speed", owner=f"speed {n} of frame {name}")
            e = tuple(self.coordinate(n, f"Euler parameter {i} of frame {name} (scalar part first)", kind="other",
                                      initial=vals[i] / norm) for i, n in enumerate(names))
            ref.orient_explicit(par.ref, quaternion_dcm(e).T)
            fr = Frame(name, ref, basis_, par, None, None, None, e, description, quaternion=e)
            group = quaternion_group(fr, e, snames)
            group.initial = w0
            ref.set_ang_vel(par.ref, sum((w * b for w, b in zip(group.speeds, (fr.x, fr.y, fr.z))), Vector(0)))
            remember(ref, par.ref, None, None)
            fr.speeds = group.speeds
            holder["group"] = group
            return fr

        fr = self._plain_frame(name, parent, None, "z", basis_t, description, None, None, orient)
        group = holder["group"]
        self._quasi_coordinates(group)
        self.speed_groups[name] = group
        self._derived = self._kinematic_equations = None     # the description changed: void what was derived
        return fr

    def _quasi_coordinates(self, group) -> None:
        """For each speed w, a quasi-coordinate ``<w>_int`` with π̇ = w: the symbolic core's coordinate
        whose rate is the speed (initial rate: the speed's initial value).  It locates nothing."""

        quasi = []
        for n, w, w0 in zip(group.names, group.speeds, group.initial):
            name = f"{n}_int"
            self._claim(name, "coordinate", owner=f"quasi-coordinate {name} of frame {group.frame.name}")
            sym = quasi_coordinate(name, w)
            self._coordinates[name] = Coordinate(
                name, sym, f"quasi-coordinate: the integral of the speed {n} (its rate {n} is the component of the "
                           f"angular velocity of {group.frame.name} along its basis; it locates nothing)",
                "angle", ONE, 0.0, w0, extra={"quasi": True, "speed": n})
            quasi.append(sym)
        group.quasi = tuple(quasi)

    def angular_speeds(self, frame: Frame | str, names=None, coordinates=None, rates=None) -> tuple:
        """Kane's choice for a frame oriented by angles: the components of its angular velocity (in the
        inertial frame) along its own basis become generalised speeds in place of the rates of
        ``coordinates`` (default: the frame's sequence angles).  Returns the speeds w(t)."""

        fr = self._lookup("frame", self.frames, Frame, frame, "angular speeds")
        where = f"frame {fr.name}"
        coords = tuple(fr.angles or ()) if coordinates is None else tuple(coordinates)
        known = set(self.coordinates)
        if len(coords) != 3 or any(q not in known for q in coords):
            raise ModelError("angular speeds replace the rates of three coordinates of the system.", where=where)
        taken = {q for g in self.speed_groups.values() for q in g.coordinates}
        if taken & set(coords) or fr.name in self.speed_groups:
            raise ModelError("these coordinates already have speeds of their own.", where=where)
        snames = tuple(f"w_{b}" for b in fr.basis) if names is None or names is True else tuple(names)
        if len(snames) != 3:
            raise ModelError("the angular speeds of a frame need three names.", where=where)
        for n in snames:
            self._claim(n, "speed", owner=f"speed {n} of frame {fr.name}")
        group = angular_group(fr, fr.parent.ref, coords, snames, self.inertial.ref)
        if rates is not None:
            group.initial = tuple(None if v is None else self._number(v, f"{where}, initial rate") for v in rates)
        fr.speeds = group.speeds
        self._quasi_coordinates(group)
        self.speed_groups[fr.name] = group
        self._derived = self._kinematic_equations = None     # the description changed: void what was derived
        return group.speeds

    def _number(self, v, where) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float, str, sp.Basic)):
            raise ModelError(f"{v!r} is not a number.", where=where)
        x = float(v) if isinstance(v, (int, float)) else to_si(v, None, where) if isinstance(v, str) \
            else float(_expr(v, where)) if sp.sympify(v).is_number else None
        if x is None:
            raise ModelError(f"{v} is not a number.", where=where)
        if x != x or x in (float("inf"), float("-inf")):
            raise ModelError(f"{v!r} is not a finite number.", where=where)
        return x

    def _check_frame(self, frame, where):
        if not isinstance(frame, Frame) or self.frames.get(frame.name) is not frame:
            raise ModelError(f"{frame!r} is not a frame of this system.", where=where)

    def _lookup(self, kind: str, table: dict, cls, obj, where):
        """An object of this system given itself or by name; a clear error otherwise."""
        if isinstance(obj, str):
            if obj not in table:
                raise ModelError(f"there is no {kind} named '{obj}'.", where=where,
                                 hint=f"Known {kind}s: {', '.join(table) or 'none yet'}.")
            return table[obj]
        if not isinstance(obj, cls) or table.get(obj.name) is not obj:
            raise ModelError(f"{obj!r} is not a {kind} of this system.", where=where)
        return obj

    def _check_point(self, point, where) -> Point:
        return self._lookup("point", self.points, Point, point, where)

    def _check_body(self, body, where, allow_none=False):
        if body is None and allow_none:
            return None
        return self._lookup("body", self.bodies, Body, body, where)

    def _check_vector(self, v, where) -> Vector:
        if isinstance(v, (int, float)) and v == 0 or (isinstance(v, sp.Basic) and v == 0):
            return Vector(0)
        if not isinstance(v, Vector):
            raise ModelError(f"expected a vector (e.g. 'l*R.y'), got {v!r}.", where=where,
                             hint="Multiply a scalar by a basis vector of a frame.")
        return v

    def point(self, name: str, from_: Point | str | None = None, offset=0, body=None,
              description: str = "") -> Point:
        """A point located by ``offset`` from ``from_`` (the origin by default); optionally fixed in ``body``."""
        self._claim(name, "point", "point")
        parent = self._check_point(from_, f"point {name}") if from_ is not None else self.origin
        vec = shallow(self._check_vector(offset, f"point {name}"), self.inertial.ref)
        p = Point(name, parent, vec, None, description)
        self.points[name] = p
        if body is not None:
            p.body = self._check_body(body, f"point {name}")
        return p

    def axis_of(self, spec: str, where: str = ""):
        """Resolve ``"B.z"`` into (frame B, "z")."""
        try:
            fname, ax = spec.split(".")
            fr = self.frames[fname]
        except (ValueError, KeyError):
            raise ModelError(f"'{spec}' does not name a frame axis (write FRAME.x, FRAME.y or FRAME.z).",
                             where=where) from None
        if ax not in ("x", "y", "z"):
            raise ModelError(f"'{spec}': the axis must be x, y or z.", where=where)
        return fr, ax

    # bodies ------------------------------------------------------------------------------------
    def body(self, name: str, shape: Shape, frame: Frame, at: Point | str, description: str = "",
             centre_name: str | None = None) -> Body:
        """A rigid body of ``shape`` with body frame ``frame``, its shape placed at the point ``at``.

        ``at`` is the mass centre for symmetric shapes and the flat-face centre for half shapes; when
        the mass centre is elsewhere a point ``G_<name>`` (or ``centre_name``) is made for it.
        """
        self._claim(name, "body", "body")
        where = f"body {name}"
        if not isinstance(shape, Shape):
            raise ModelError(f"shape must be one of rigidkin.shapes, not {shape!r}.", where=where)
        self._check_frame(frame, where)
        ref = self._check_point(at, where)
        shape.check(self.parameter_values(), where)
        offset = shape.centre_offset(frame)
        if offset == Vector(0):
            centre = ref
        else:
            centre = self.point(centre_name or f"G_{name}", ref, offset, description=f"mass centre of {name}")
        b = Body(name, shape, frame, ref, centre, description)
        self.bodies[name] = b
        for p in {ref, centre}:
            if p.body is None:
                p.body = b
            elif p.body is not b:
                raise ModelError(f"point {p.name} is already fixed in body {p.body.name}.", where=where)
        return b

    # surfaces -------------------------------------------------------------------------------
    def line(self, point: Point | str, normal: Vector, body=None, name: str = "") -> Line:
        """A straight surface through ``point`` whose unit ``normal`` points to the bodies' side."""
        p = self._check_point(point, f"line {name}")
        return Line(p, self._check_vector(normal, f"line {name}"), self._check_body(body, name, True), name)

    def circle(self, centre: Point | str, radius, inside: bool = False, body=None, name: str = "",
               normal: Vector | None = None) -> Circle:
        """A circular (spherical in 3D) surface; the body touches it from ``inside`` or outside."""
        p = self._check_point(centre, f"circle {name}")
        return Circle(p, self._value(radius, f"circle {name}", POSITIVE, "radius"), inside,
                      self._check_body(body, name, True), name, normal)

    plane = line
    sphere = circle

    def _value(self, value, where: str, rule: str, what: str) -> sp.Expr:
        """A number or expression that must obey ``rule`` (with the parameters' numeric values put in)."""
        return require(_expr(value, where), rule, what, where, self.parameter_values())

    def _friction(self, friction, where):
        """``_friction`` with each coefficient µ checked first (real, finite, ≥ 0 with the parameters' values)."""
        given = friction.values() if isinstance(friction, dict) else \
            (friction.mu, friction.mu_s) if isinstance(friction, C.Coulomb) else (friction,)
        for v in given:
            if isinstance(v, (int, float, sp.Basic)) and not isinstance(v, bool):
                require(v, NONNEGATIVE, "friction coefficient µ", where, self.parameter_values())
        return _friction(friction, where)

    # solving -------------------------------------------------------------------------------------
    def solve(self, method: str = "newton-euler", mode: dict[str, str] | None = None,
              independent=None, substitutions: dict | None = None, integrate: bool = True):
        """Derive the equations of motion and reactions; returns a :class:`rigidkin.Solution`.

        ``mode`` maps contact names to ``"slip"``, ``"stick"`` or ``"open"``; ``independent`` lists the coordinates to
        keep (others are eliminated by the constraints); ``substitutions`` replaces parameters (e.g. ``{mu: 0}`` on a
        frictionless stretch); ``integrate=False`` keeps the coordinates whose relation comes from integrating a rate
        relation (a constant of integration) as coordinates of their own, as a simulation entering the mode needs.
        """
        from ..derive.laws import solve_with

        for sym, value in (substitutions or {}).items():
            if isinstance(value, (int, float, sp.Basic)) and not isinstance(value, bool):
                require(value, NONNEGATIVE if getattr(sym, "is_positive", False) else REAL, f"value given for {sym}",
                        "solve(substitutions=...)", self.parameter_values())
        return solve_with(self, method, mode=mode or {}, independent=independent,
                          substitutions=substitutions or {}, integrate=integrate)

    def _repr_html_(self) -> str:
        return display.render(self, "html")

    def _repr_latex_(self) -> str:
        return display.render(self, "latex")

    def __repr__(self) -> str:
        return (f"System({self.name}: {len(self.bodies)} bodies, {len(self._coordinates)} coordinates, "
                f"{len(self.constraints)} constraints, {len(self.loads)} loads)")
