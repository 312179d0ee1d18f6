"""Building a problem file's questions: starts, modes, substitutions and phases (``[ask]``).
"""

from __future__ import annotations

import sympy as sp

from ..analysis.questions import Question
from ..base.errors import InputError
from ..base.units import ONE, TIME
from ..model.checks import NONNEGATIVE, REAL, require
from ..model.constraints import Contact
from . import schema as S
from .expressions import (
    Scope,
    parse_condition,
    parse_equation,
    parse_scalar,
    slip,
)


class Questions:
    """Builder steps for ``[ask]`` (mixed into the file reader's builder)."""

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
                f[key] = self.parsed(v, kpath, qs, parse_equation)          # "theta = 30 deg": units checked
            elif key in ("holds", "regime"):
                f[key] = self.parsed(v, kpath, qs, parse_condition)
            elif key == "reaction":
                self._lookup(self.reactions, "reaction", v, kpath)
                f[key] = v
            elif key == "coordinate":
                f[key] = self._lookup(self.scope.coordinates, "coordinate", v, kpath)
            elif key == "duration":            # "0.5 s" as well as "dt" or 0.5 (seconds)
                f[key] = self.value(v, kpath, TIME)
            elif key == "expression":
                f[key] = self.parsed(v, kpath, qs, parse_scalar)
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
        out["until"] = None if p.until is None else self.parsed(p.until, path + ("until",), self._question_scope(),
                                                                parse_equation)
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
