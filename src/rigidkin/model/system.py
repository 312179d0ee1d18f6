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

from ..errors import ModelError
from ..units import NAMED, ONE, Dimension, to_si, unit_dimension
from . import constraints as C
from . import loads as L
from .bodies import Body
from .chains import remember, shallow
from .checks import NONNEGATIVE, POSITIVE, REAL, check_identifier, require
from .definitions import Defined, Definition
from .definitions import define as define_quantity
from .frames import Frame, make_reference_frame
from .points import Point
from .profiles import arc_for
from .quantities import Coordinate, Parameter
from .shapes import Shape
from .surfaces import Circle, Line

t = dynamicsymbols._t

_GREEK_LATEX = {"theta": r"\theta", "phi": r"\phi", "psi": r"\psi", "beta": r"\beta", "alpha": r"\alpha"}


def _latex_basis(basis):
    out = []
    for b in basis:
        head, tail = b[0], b[1:]
        tail_tex = _GREEK_LATEX.get(tail, tail.replace("θ", r"\theta").replace("φ", r"\phi"))
        out.append(rf"\mathbf{{{head}}}_{{{tail_tex}}}" if tail else rf"\mathbf{{{head}}}")
    return tuple(out)


class System:
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
        self._cache: dict = {}
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
        self._cache.clear()

    # parameters and coordinates ---------------------------------------------------------------
    def parameter(self, name: str, unit: str | None = None, description: str = "", value=None,
                  dimension: str | Dimension | None = None, positive: bool = True) -> sp.Symbol:
        """Declare a parameter; returns its positive real sympy Symbol.

        ``value`` is a number in ``unit`` (``unit="cm", value=50`` is 0.5 m) or a quantity string
        (``"30 deg"``); it is stored in SI.
        """
        where = f"parameter {name}"
        if unit is not None:
            dim = unit_dimension(unit, where)
        elif isinstance(dimension, Dimension):
            dim = dimension
        elif dimension is not None:
            if dimension not in NAMED:
                raise ModelError(f"unknown dimension '{dimension}'.", where=where,
                                 hint=f"Use a unit (kg, m, N/m ...) or one of: {', '.join(sorted(NAMED))}.")
            dim = NAMED[dimension]
        else:
            dim = ONE
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

        ``sense`` says where it is measured from and which way is positive.  Coordinates declared
        first are kept as independent; later ones are eliminated first by the constraints.
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
              sequence: str | None = None, angles=None) -> Frame:
        """A frame rotated from ``parent`` (default: the inertial frame) by ``angle`` about ``axis``.

        ``axis`` is a basis vector name of the parent (``"z"``, ``"-y"``) or a vector fixed in the
        parent.  For 3D, ``sequence="313"`` (or "321", ...) with three ``angles`` gives a body-fixed
        rotation sequence.
        """
        self._claim(name, "frame", "frame")
        parent = parent or self.inertial
        self._check_frame(parent, f"frame {name}")
        basis = tuple(basis) if basis else (f"{name.lower()}x", f"{name.lower()}y", f"{name.lower()}z")
        if len(basis) != 3 or len(set(basis)) != 3:
            raise ModelError("a basis needs three distinct names.", where=f"frame {name}")
        ref = make_reference_frame(name, basis, _latex_basis(basis))
        if sequence is not None:
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

    # constraints --------------------------------------------------------------------------------
    def _add_constraint(self, c):
        self.constraints[c.name] = c
        return c

    def pin(self, name: str, point: Point | str, body_a, body_b=None, point_b=None, basis: Frame | None = None,
            axis: str | None = None, prefix: str | None = None, description: str = "") -> C.Pin:
        """Hold ``point`` of ``body_a`` at ``point_b`` of ``body_b`` (fixed in the ground if None)."""
        self._claim(name, "constraint", "constraint")
        where = f"pin {name}"
        p = self._check_point(point, where)
        a = self._check_body(body_a, where)
        b = self._check_body(body_b, where, allow_none=True)
        pb = self._check_point(point_b, where) if point_b is not None else None
        if basis is not None:
            self._check_frame(basis, where)
        con = C.Pin(name, point=p, body_a=a, body_b=b, point_b=pb, basis_frame=basis, axis=axis, prefix=prefix,
                    description=description)
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"pin {name}")
        return self._add_constraint(con)

    def contact(self, name: str, body, surface, centre: Point | str | None = None, radius=0,
                friction="smooth", unilateral: bool = True, normal_name: str | None = None,
                friction_name: str | None = None, description: str = "", arc=None) -> C.Contact:
        """A contact of ``body`` with ``surface`` through a profile (point, circle or sphere of ``radius``).

        ``arc``: the part of the profile that exists, ``(toward, half_angle)`` with ``toward`` fixed in the
        body (a half cylinder's curved face: its ``toward``, π/2 — the default for half shapes touching by
        their curved face); ``False``: the whole circle.  Leaving the arc ends the contact's validity.

        ``friction``: ``"smooth"``, ``"rolling"`` (no slip), or a coefficient µ (Coulomb friction), or
        ``{"static": µs, "kinetic": µk}`` (sticks while |F| ≤ µs N, slides with µk N).
        """
        self._claim(name, "constraint", "constraint")
        where = f"contact {name}"
        b = self._check_body(body, where)
        c = self._check_point(centre, where) if centre is not None else b.centre
        if not isinstance(surface, (Line, Circle)):
            raise ModelError("surface must be a line/plane or circle/sphere (System.line, System.circle).",
                             where=where)
        fr = self._friction(friction, where)
        rad = self._value(radius, where, NONNEGATIVE, "radius")
        con = C.Contact(name, body=b, centre=c, radius=rad,
                        surface=surface, friction=fr,
                        unilateral=unilateral, normal_name=normal_name, friction_name=friction_name,
                        description=description, arc=arc_for(arc, b, c, rad, where))
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"contact {name}")
        return self._add_constraint(con)

    def disk_contact(self, name: str, body, surface, axis: Vector, radius, centre: Point | str | None = None,
                     friction="smooth", unilateral: bool = True, normal_name: str | None = None,
                     friction_name: str | None = None, description: str = ""):
        """A thin disk (wheel, coin) of ``radius`` and unit ``axis`` (fixed in ``body``) touching a plane
        at its rim, in 3D: see :mod:`rigidkin.model.rolling3d`."""
        from .rolling3d import DiskContact

        self._claim(name, "constraint", "constraint")
        where = f"contact {name}"
        b = self._check_body(body, where)
        c = self._check_point(centre, where) if centre is not None else b.centre
        con = DiskContact(name, body=b, centre=c, radius=self._value(radius, where, POSITIVE, "radius"),
                          surface=surface, friction=self._friction(friction, where), unilateral=unilateral,
                          normal_name=normal_name,
                          friction_name=friction_name, description=description,
                          axis=self._check_vector(axis, where))
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"contact {name}")
        return self._add_constraint(con)

    def collar(self, name: str, body, along: Vector, through: Point | str | None = None,
               point: Point | str | None = None, track_body=None, friction="smooth",
               normal_name: str | None = None, couple_name: str | None = None, description: str = "") -> C.Collar:
        """A collar: ``body`` slides along a straight track (through ``through``, direction ``along``)."""
        self._claim(name, "constraint", "constraint")
        where = f"collar {name}"
        b = self._check_body(body, where)
        p = self._check_point(point, where) if point is not None else b.reference
        thr = self._check_point(through, where) if through is not None else self.origin
        con = C.Collar(name, body=b, point=p, through=thr, along=self._check_vector(along, where),
                       track_body=self._check_body(track_body, where, True), friction=self._friction(friction, where),
                       normal_name=normal_name, couple_name=couple_name, description=description)
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"collar {name}")
        return self._add_constraint(con)

    def cable(self, name: str, points, length, bodies=None, tension_name: str | None = None,
              description: str = "") -> C.Cable:
        """An inextensible cable through ``points`` (ends and pulleys), taut with tension T ≥ 0.

        ``bodies`` gives the body of each point (default: the body each point is fixed in, or the
        ground); ``length`` is the cable's length between its ends.
        """
        self._claim(name, "constraint", "constraint")
        where = f"cable {name}"
        pts = tuple(self._check_point(p, where) for p in points)
        if len(pts) < 2:
            raise ModelError("a cable needs at least its two ends.", where=where)
        if bodies is None:
            bs = tuple(p.body for p in pts)
        else:
            if len(bodies) != len(pts):
                raise ModelError(f"give one body (or None) for each of the {len(pts)} points.", where=where)
            bs = tuple(self._check_body(b, where, allow_none=True) for b in bodies)
        con = C.Cable(name, points=pts, bodies=bs, length=self._value(length, where, POSITIVE, "length"),
                      tension_name=tension_name,
                      description=description)
        self._claim(con.T.name, "reaction", owner=f"cable {name}")
        return self._add_constraint(con)

    def rope(self, name: str, path, tensions=None, description: str = ""):
        """A rope over pulleys with inertia that it does not slip on: ``path`` = end, Wrap(pulley, radius,
        "cw"|"ccw"), …, end (see :mod:`rigidkin.model.ropes`); one tension per straight segment, each ≥ 0."""
        from .ropes import build_rope

        self._claim(name, "constraint", "constraint")
        con = build_rope(self, name, path, tensions, description)
        for sym in con.reactions():
            self._claim(sym.name, "reaction", owner=f"rope {name}")
        return self._add_constraint(con)

    # loads -------------------------------------------------------------------------------------
    def _add_load(self, load):
        self._claim(load.name, "load", "load")
        self.loads[load.name] = load
        return load

    def _body_of(self, point: Point, body, where):
        if body is not None:
            return self._check_body(body, where)
        if point.body is None:
            raise ModelError(f"point {point.name} is not fixed in a body, so it is not clear which body the "
                             "load acts on.", where=where, hint="Give the body explicitly (body=...).")
        return point.body

    def gravity(self, g, direction: Vector | None = None, name: str = "gravity") -> None:
        """Uniform gravity of magnitude ``g`` along the unit vector ``direction`` (default −Ey)."""
        d = -self.inertial.y if direction is None else self._check_vector(direction, f"load {name}")
        self._add_load(L.Gravity(name, g=self._value(g, f"load {name}", NONNEGATIVE, "gravitational acceleration"),
                                 direction=d))

    def force(self, name: str, point: Point | str, vector: Vector, body=None, description: str = "",
              on=None) -> L.Force:
        """A known force at ``point`` (of ``body``; default: the body the point is fixed in).

        At a point that moves over the body (``on=body``, the same as ``body=``), the force acts on the
        material point of the body momentarily there; its power uses that material point's velocity.
        """
        where = f"force {name}"
        p = self._check_point(point, where)
        return self._add_load(L.Force(name, body=self._body_of(p, on if on is not None else body, where), point=p,
                                      vector=self._check_vector(vector, where), description=description))

    def torque(self, name: str, body, vector: Vector, reaction_body=None, description: str = "") -> L.Torque:
        """A known torque on ``body`` (and its reaction on ``reaction_body``)."""
        where = f"torque {name}"
        return self._add_load(L.Torque(name, body=self._check_body(body, where),
                                       vector=self._check_vector(vector, where),
                                       reaction_body=self._check_body(reaction_body, where, True),
                                       description=description))

    def spring(self, name: str, point_a: Point | str, point_b: Point | str, stiffness, natural_length=0,
               body_a=None, body_b=None, description: str = "", on_a=None, on_b=None) -> L.Spring:
        """A linear spring between two points; ends not fixed in a body are anchored in the ground.

        ``on_a``/``on_b``: the body whose material point momentarily at ``point_a``/``point_b`` the
        spring pulls (for an end that moves over the body, such as the top of a rolling wheel).
        """
        where = f"spring {name}"
        pa, pb = self._check_point(point_a, where), self._check_point(point_b, where)
        ba = self._body_of(pa, on_a if on_a is not None else body_a, where)
        bb = self._check_body(on_b if on_b is not None else body_b, where, True) \
            if (body_b is not None or on_b is not None) else pb.body
        ref = self.inertial.ref
        ma = L.check_end(name, "spring", pa, ba, on_a is not None, ref)
        mb = L.check_end(name, "spring", pb, bb, on_b is not None, ref)
        return self._add_load(L.Spring(name, point_a=pa, body_a=ba, point_b=pb, body_b=bb, moving_a=ma, moving_b=mb,
                                       stiffness=self._value(stiffness, where, NONNEGATIVE, "stiffness"),
                                       natural_length=self._value(natural_length, where, NONNEGATIVE, "natural length"),
                                       description=description))

    def torsional_spring(self, name: str, body_a, stiffness, angle, natural_angle=0, body_b=None,
                         axis: Vector | None = None, description: str = "") -> L.TorsionalSpring:
        """A torsional spring: torque −K (angle − angle0) about ``axis`` (default Ez) on ``body_a``."""
        where = f"torsional spring {name}"
        return self._add_load(L.TorsionalSpring(
            name, body_a=self._check_body(body_a, where), body_b=self._check_body(body_b, where, True),
            stiffness=self._value(stiffness, where, NONNEGATIVE, "stiffness"), angle=_expr(angle, where),
            natural_angle=_expr(natural_angle, where),
            axis=self.inertial.z if axis is None else self._check_vector(axis, where), description=description))

    def damper(self, name: str, point_a: Point | str, law, along: Vector | None = None,
               point_b: Point | str | None = None, body_a=None, body_b=None, description: str = "",
               on_a=None, on_b=None) -> L.Damper:
        """A damper of any force law f(v) (``law`` in the symbol ``rigidkin.v`` or a callable).

        ``on_a``/``on_b`` as for :meth:`spring`: v then uses the material velocity of that body there.
        """
        where = f"damper {name}"
        pa = self._check_point(point_a, where)
        pb = self._check_point(point_b, where) if point_b is not None else None
        ob = on_b if on_b is not None else body_b
        bb = self._check_body(ob, where, True) if ob is not None else (pb.body if pb else None)
        ba = self._body_of(pa, on_a if on_a is not None else body_a, where)
        ref = self.inertial.ref
        ma = L.check_end(name, "damper", pa, ba, on_a is not None, ref)
        mb = pb is not None and L.check_end(name, "damper", pb, bb, on_b is not None, ref)
        return self._add_load(L.Damper(name, point_a=pa, body_a=ba, law=law,
                                       along=None if along is None else self._check_vector(along, where),
                                       point_b=pb, body_b=bb, moving_a=ma, moving_b=mb, description=description))

    def impulse(self, name: str, point: Point | str, vector: Vector, body=None, description: str = "",
                on=None) -> L.Impulse:
        """An impulse F̂ applied at ``point`` (used by the impulse–momentum law); ``on`` as for :meth:`force`."""
        where = f"impulse {name}"
        p = self._check_point(point, where)
        return self._add_load(L.Impulse(name, body=self._body_of(p, on if on is not None else body, where), point=p,
                                        vector=self._check_vector(vector, where), description=description))

    def friction(self, name: str, body, centre: Point | str, normal: Vector, mu, normal_force, radius=0,
                 against_body=None, against_point: Point | str | None = None,
                 description: str = "") -> L.SlidingFriction:
        """Coulomb sliding friction at a contact whose normal force is known (or a named reaction)."""
        where = f"friction {name}"
        return self._add_load(L.SlidingFriction(
            name, body=self._check_body(body, where), centre=self._check_point(centre, where),
            radius=self._value(radius, where, NONNEGATIVE, "radius"), normal=self._check_vector(normal, where),
            mu=self._value(mu, where, NONNEGATIVE, "friction coefficient µ"),
            normal_force=_expr(normal_force, where), against_body=self._check_body(against_body, where, True),
            against_point=self._check_point(against_point, where) if against_point is not None else None,
            description=description))

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

        ``mode`` maps contact names to ``"slip"``, ``"stick"`` or ``"open"``;
        ``independent`` lists the coordinates to keep (others are eliminated by the constraints);
        ``substitutions`` replaces parameters (e.g. ``{mu: 0}`` on a frictionless stretch);
        ``integrate=False`` keeps the coordinates whose relation comes from integrating a rate relation
        (a constant of integration) as coordinates of their own, as a simulation entering the mode needs.
        """
        from ..laws import solve_with

        for sym, value in (substitutions or {}).items():
            if isinstance(value, (int, float, sp.Basic)) and not isinstance(value, bool):
                require(value, NONNEGATIVE if getattr(sym, "is_positive", False) else REAL, f"value given for {sym}",
                        "solve(substitutions=...)", self.parameter_values())
        return solve_with(self, method, mode=mode or {}, independent=independent,
                          substitutions=substitutions or {}, integrate=integrate)

    def _repr_html_(self) -> str:
        from ..report.jupyter import system_html

        return system_html(self)

    def _repr_latex_(self) -> str:
        from ..report.jupyter import system_latex

        return system_latex(self)

    def __repr__(self) -> str:
        return (f"System({self.name}: {len(self.bodies)} bodies, {len(self._coordinates)} coordinates, "
                f"{len(self.constraints)} constraints, {len(self.loads)} loads)")


def _expr(value, where: str = "") -> sp.Expr:
    """A number or sympy expression given to the Python API (a string is refused: no sympify on text)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, sp.Basic)):
        kind = "the string " + repr(value)[:40] if isinstance(value, str) else type(value).__name__
        raise ModelError(f"expected a number or a sympy expression, got {kind}.", where=where or None,
                         hint="In Python, build expressions from the symbols System.parameter and "
                              "System.coordinate return (l/2, m*g); text expressions belong in problem files.")
    return sp.sympify(value)


def _friction(friction, where):
    if friction in (None, "smooth", 0):
        return C.SMOOTH
    if friction in ("rolling", "no-slip", "no_slip"):
        return C.ROLLING
    if isinstance(friction, C.Coulomb):
        return friction
    if isinstance(friction, dict) and set(friction) <= {"static", "kinetic"} and friction:
        # static and kinetic coefficients (µs, µk); one alone means both
        mu_k = friction.get("kinetic", friction.get("static"))
        mu_s = friction.get("static", mu_k)
        if mu_k in (0, None) and mu_s in (0, None):
            return C.SMOOTH
        return C.Coulomb(_expr(mu_k, where), _expr(mu_s, where))
    if isinstance(friction, (int, float, sp.Basic)):
        return C.Coulomb(_expr(friction, where))
    raise ModelError(f"friction must be 'smooth', 'rolling', a coefficient µ or {{'static': µs, 'kinetic': µk}}, "
                     f"not {friction!r}.", where=where)
