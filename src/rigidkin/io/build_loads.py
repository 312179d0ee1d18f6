"""Building a problem file's constraints and loads (a part of the file reader's builder).
"""

from __future__ import annotations

from ..base.errors import InputError
from ..model.loads import V as DAMPER_SPEED
from ..model.ropes import Wrap
from . import schema as S
from .build_restitution import restitution_value
from .expressions import (
    check_name,
)

_FRICTION_WORDS = ("smooth", "rolling", "no-slip", "no_slip")


class ConstraintsAndLoads:
    """Builder steps for ``[constraints]`` and ``[loads]`` (mixed into the file reader's builder)."""

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
        for key in ("normal_name", "friction_name", "couple_name", "tension_name", "reaction_name"):
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
        elif isinstance(c, S.KnifeEdgeSpec):
            self.call(path, self.s.knife_edge, name, self.body(c.body, path + ("body",)),
                      self.point(c.point, path + ("point",)), self.vector(c.direction, path + ("direction",)),
                      c.reaction_name, c.description)
        elif isinstance(c, S.VelocityConstraintSpec):
            self.call(path, self.s.velocity_constraint, name, self.scalar(c.expression, path + ("expression",)),
                      c.reaction_name, c.description)
        else:
            self.call(path, self.s.collar, name, self.body(c.body, path + ("body",)),
                      self.vector(c.along, path + ("along",)), self.point(c.through, path + ("through",), True),
                      self.point(c.point, path + ("point",), True),
                      self.body(c.track_body, path + ("track_body",), True),
                      self.friction(c.friction, path + ("friction",)), c.normal_name, c.couple_name, c.description)

        if getattr(c, "restitution", None) is not None:    # Newton's law: a contact's impacts, a rope's jerk
            self.call(path + ("restitution",), self.s.restitution, name, restitution_value(self, name, c, path))

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
        elif isinstance(ld, S.RotationalSpringSpec):
            angle = None if ld.angle is None else sc("angle")
            self.call(path, s.rotational_spring, name, B("body_a"), sc("stiffness"), B("body_b", True),
                      sc("natural_angle"), vec("axis"), angle, ld.description)
        elif isinstance(ld, S.RotationalDamperSpec):
            self.call(path, s.rotational_damper, name, B("body_a"), sc("coefficient"), B("body_b", True),
                      vec("axis"), ld.description)
        else:
            self.call(path, s.impulse, name, P("point"), vec("vector"), B("body", True), ld.description,
                      on=B("on", True))
