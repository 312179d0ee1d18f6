"""Grading the steps that are not balance equations: kinematics, free-body diagrams and answers.

* ``kinematics``: ``claim = "v_A = ..."``, ``"a_G = ..."``, ``"omega_R = ..."`` or ``"alpha_rod = ..."``
  (a point, or a frame or body for ω and α; a body's name as a point means its mass centre), the right
  side a vector in any of the problem's bases.  Compared with the engine's vector at random states; a
  wrong one is matched against the common mistakes (a transport term missing ...), else each component
  along the basis the student wrote in is named.
* ``fbd``: ``claim = "-m*g*Ey at G; N_A*Ex at A; N_B*Ey at B"`` (``@`` for ``at``; an item without a point
  is a couple), ``body`` naming the body (optional with one body).  Each load is matched with the
  engine's diagram: same vector, and a point on the same line of action; the rest is named (missing,
  extra, wrong sign, wrong point).
* ``answer``: in :mod:`rigidkin.grading.answers`.
"""

from __future__ import annotations

import re

import numpy as np
from sympy.physics.vector import Vector, dynamicsymbols

from ..base.errors import InputError
from ..base.printing import text
from ..derive.laws.newton_euler import body_loads
from ..io.expressions import parse_vector
from . import space
from .claims import Unreadable, read
from .engine import Reference
from .mistakes import kinematic_variants
from .verdicts import CORRECT, INCORRECT, Carried, StepResult
from .worksheet import Step

t = dynamicsymbols._t
_LHS = re.compile(r"^\s*(v|a|omega|w|alpha)_([A-Za-z][A-Za-z0-9_]*)\s*=")
ANSWER_RTOL = 5e-3


def _vector_values(ref: Reference, v: Vector, regime=None) -> np.ndarray:
    F = ref.F
    comps = [space.to_plain(ref.scalar(v.dot(e), regime)) for e in (F.x, F.y, F.z)] if v != Vector(0) else []
    if not comps:
        return np.zeros((ref.sampler.n, 3))
    return ref.sampler.evaluate(comps)


def same_vector(ref: Reference, a: Vector, b: Vector, regime=None) -> bool:
    va, vb = _vector_values(ref, a, regime), _vector_values(ref, b, regime)
    return bool(space.vanishes(va - vb, np.abs(va) + np.abs(vb)))


def _basis_of(ref: Reference, v: Vector):
    frames = [fr for fr in ref.system.frames.values()
              if v != Vector(0) and any(f is fr.ref for _, f in v.args)]
    fr = frames[0] if frames else ref.system.inertial
    axes = [(fr.x, fr.basis[0]), (fr.y, fr.basis[1]), (fr.z, fr.basis[2])]
    return axes[:2] if ref.kin.planar else axes


def grade_kinematics(ref: Reference, st: Step, carried: Carried) -> StepResult:
    m = _LHS.match(st.claim)
    if not m:
        raise _unreadable("a kinematics claim reads 'v_P = ...', 'a_P = ...', 'omega_R = ...' or 'alpha_R = ...' "
                          "(P a point or a body, R a frame or a body)")
    what, name = m.group(1), m.group(2)
    rhs = st.claim[m.end():]
    student = read("vector", parse_vector, rhs, ref.scope, st.where)
    kin = ref.kin
    res = StepResult(st.index, st.kind, INCORRECT)
    body = None
    if what in ("v", "a"):
        P = ref.point_of(name)
        if P is None:
            raise _unreadable(f"the problem has no point or body named '{name}' (points: "
                              f"{', '.join(ref.system.points)}; bodies: {', '.join(ref.system.bodies)})")
        engine = ref.setup.vector(kin.velocity(P) if what == "v" else kin.acceleration(P))
        body = next((b for b in ref.system.bodies.values() if b.centre is P), None)
        label = f"{what}_{name}"
    else:
        frame = ref.system.frames.get(name) or (ref.system.bodies[name].frame if name in ref.system.bodies else None)
        if frame is None:
            raise _unreadable(f"the problem has no frame or body named '{name}' (frames: "
                              f"{', '.join(ref.system.frames)}; bodies: {', '.join(ref.system.bodies)})")
        engine = ref.setup.vector(kin.omega(frame) if what in ("omega", "w") else kin.alpha(frame))
        body = next((b for b in ref.system.bodies.values() if b.frame is frame), None)
        label = f"{'ω' if what in ('omega', 'w') else 'α'}_{name}"
    res.expected = f"{label} = {_vec_text(ref, engine, student)}"
    if same_vector(ref, student, engine):
        res.verdict = CORRECT
        return res
    if body is not None:
        if what == "a":
            carried.accel[body] = (st.index, student)
        elif what == "alpha":
            carried.alpha[body] = (st.index, student)
    if what in ("v", "a"):
        for why, v in kinematic_variants(ref, P, what):
            if same_vector(ref, student, ref.setup.vector(v)):
                res.feedback.append(why)
                break
    if not res.feedback and same_vector(ref, student, -engine):
        res.feedback.append("sign: the whole vector has the wrong sign")
    one = bool(res.feedback)                   # one cause: the named mistake or the sign, else the components
    axes = _basis_of(ref, student)
    if what not in ("v", "a") and len(axes) == 2:          # a planar ω or α lies along the third axis
        fr = next(f for f in ref.system.frames.values() if f.x == axes[0][0])
        axes = axes + [(fr.z, fr.basis[2])]
    for e, ename in axes:
        a, b = ref.scalar(student.dot(e)), ref.scalar(engine.dot(e))
        va, vb = ref.sampler.evaluate([space.to_plain(a), space.to_plain(b)]).T
        if not space.vanishes((va - vb)[:, None], np.abs(np.stack([va, vb], 1))):
            sa, sb = kin.simplify_expr(a), kin.simplify_expr(b)
            if not one:
                res.feedback.append(f"component along {ename}: you wrote {text(sa)}, it is {text(sb)}")
            res.differences.append((text(sa), text(sb)))
    if len(res.feedback) > 1:
        more = len(res.feedback) - 1
        res.feedback = [res.feedback[0] + f" (and {more} more component{'s' if more > 1 else ''}: see the differences)"]
    if not res.feedback:
        res.feedback.append(f"{label} differs from the engine's")
    return res


def _vec_text(ref: Reference, v: Vector, like: Vector) -> str:
    parts = []
    axes = _basis_of(ref, like)
    if len(axes) == 2:
        fr = next(f for f in ref.system.frames.values() if f.x == axes[0][0])
        axes = axes + [(fr.z, fr.basis[2])]
    for e, name in axes:
        c = ref.kin.simplify_expr(ref.scalar(v.dot(e)))
        if c != 0:
            parts.append(f"({text(c)}) {name}")
    return " + ".join(parts) or "0"


def _unreadable(msg: str):
    return Unreadable(f"unreadable: {msg}")


# free-body diagrams -----------------------------------------------------------------------------------
_AT = re.compile(r"\s+at\s+|@")


def _items(st: Step) -> list[str]:
    raw = [st.claim] if isinstance(st.claim, str) else list(st.claim)
    out = []
    for r in raw:
        out += [s.strip() for s in r.split(";") if s.strip()]
    return out


def grade_fbd(ref: Reference, st: Step, carried: Carried, scope=None, rc=None) -> StepResult:
    """A diagram compared in the regime the motion fixes (``scope``); one valid only in another regime is
    wrong for one cause, the friction's direction."""
    bodies = ref.system.bodies
    if st.body is None and len(bodies) > 1:
        raise InputError("a free-body diagram names its body (body = \"NAME\") when the problem has several.",
                         where=st.where, hint=f"Bodies: {', '.join(bodies)}.")
    body = bodies.get(st.body) if st.body else next(iter(bodies.values()))
    if body is None:
        raise InputError(f"the problem has no body named '{st.body}'.", where=st.where,
                         hint=f"Bodies: {', '.join(bodies)}.")
    kin = ref.kin
    student = []
    for item in _items(st):
        parts = _AT.split(item)
        if len(parts) > 2:
            raise _unreadable(f"'{item[:60]}' names more than one point")
        vec = read("load", parse_vector, parts[0], ref.scope, st.where)
        loc, pname = None, None
        if len(parts) == 2:
            pname = parts[1].strip()
            P = ref.point_of(pname)
            if P is None:
                raise _unreadable(f"'{pname[:40]}' is not a point of the problem "
                                  f"(points: {', '.join(ref.system.points)})")
            loc = kin.position(P)
        student.append((ref.setup.vector(vec), loc, item))
    _, _, apps = body_loads(ref.setup, body)
    engine = [(ref.setup.vector(a.vector), None if a.is_torque else
               (a.location if a.location is not None else kin.position(a.point)), a.label) for a in apps]
    res = StepResult(st.index, st.kind, INCORRECT)
    res.expected = "; ".join(f"{a[2]}: {_vec_text(ref, a[0], a[0])}" + ("" if a[1] is None else
                                                                       f" at {_where(ref, a[1])}") for a in engine)
    allowed = scope.for_step() if scope is not None else ref.regimes()
    every = {id(reg): _compare_loads(ref, student, engine, body, reg) for reg in ref.regimes()}
    best = min((every[id(r)] for r in allowed), key=lambda fd: len(fd[0]))
    res.feedback, res.differences = best
    holds = [r for r in ref.regimes() if not every[id(r)][0]]
    if not res.feedback:
        res.verdict = CORRECT
        if scope is not None and len(holds) == 1 and len(ref.regimes()) > 1:
            if rc is not None and scope is rc:
                rc.holds_in(holds[0], st.index)
            res.feedback = [scope.note()] if scope.note() else []
        return res
    if scope is not None and holds:
        res.feedback, res.differences = [scope.wrong_regime(holds[0])], []
    elif len(res.feedback) > 1:                 # one cause; every difference stays listed
        res.differences = res.differences + [(f, "") for f in res.feedback[1:]]
        more = len(res.feedback) - 1
        res.feedback = [res.feedback[0] + f" (and {more} more difference{'s' if more > 1 else ''})"]
    carried.loads[body] = (st.index, [(s[0], s[1]) for s in student])
    return res


def _compare_loads(ref: Reference, student, engine, body, reg):
    left_s, left_e = list(range(len(student))), list(range(len(engine)))
    fb, diffs = [], []

    def same(a, b):
        return same_vector(ref, a, b, reg)

    def on_line(s, e):
        if (s[1] is None) != (e[1] is None):
            return False
        return s[1] is None or same((s[1] - e[1]).cross(e[0]), Vector(0))

    for sign, how in ((1, None), (-1, "sign")):
        for i in list(left_s):
            s = student[i]
            for j in left_e:
                e = engine[j]
                if same(s[0], sign * e[0]):
                    if not on_line(s, e):
                        fb.append(f"wrong point: {e[2]} acts at {_where(ref, e[1])}, not where you put it "
                                  f"({s[2]})" if e[1] is not None else f"{e[2]} is a couple, not a force")
                    elif how:
                        fb.append(f"sign: {e[2]} points the other way ({s[2]})")
                    left_s.remove(i)
                    left_e.remove(j)
                    break
    # one arrow for two loads at the same point (a contact force as N + F)
    for i in list(left_s):
        s = student[i]
        for j, k in [(j, k) for j in left_e for k in left_e if j < k]:
            if same(s[0], engine[j][0] + engine[k][0]) and on_line(s, engine[j]) and on_line(s, engine[k]):
                left_s.remove(i)
                left_e.remove(j)
                left_e.remove(k)
                break
    for j in left_e:
        e = engine[j]
        fb.append(f"missing from the diagram: {e[2]} ({_vec_text(ref, e[0], e[0])}"
                  + ("" if e[1] is None else f" at {_where(ref, e[1])}") + ")")
        diffs.append(("", e[2]))
    for i in left_s:
        fb.append(f"extra in the diagram: {student[i][2]} (no such load acts on {body.name})")
        diffs.append((student[i][2], ""))
    return fb, diffs


def _where(ref: Reference, loc: Vector) -> str:
    for p in list(ref.system.points.values()) + ref.contact_spots():
        if same_vector(ref, ref.kin.position(p), loc):
            return p.name
    return text(ref.kin.simplify_vector(loc)) if hasattr(ref.kin, "simplify_vector") else str(loc)
