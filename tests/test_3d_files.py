"""The 3D examples' problem files build the same models as their Python versions.

Compared: titles and statements, parameters (units, values, descriptions), coordinates (senses,
kinds, initial state), frames (rotation matrices), points (positions), bodies (mass, inertia about
the mass centre), constraints (kinds, reactions, constraint rows) and loads — numerically at random
configurations, which is how two models of one system are told apart.
"""

from __future__ import annotations

import random

import pytest
import sympy as sp

from rigidkin.derive.kinematics import Kinematics
from rigidkin.examples import HERE, build
from rigidkin.io.problem import load_problem

EXAMPLES = ["heavy-top", "torque-free", "rolling-disk", "gyroscope"]


def _numbers(system, seed):
    rng = random.Random(seed)
    vals = {p: rng.uniform(0.5, 1.5) for p in system.parameters.values()}
    for q in system.coordinates:
        vals[q.diff()] = rng.uniform(-1, 1)
    for q in system.coordinates:
        vals[q] = rng.uniform(-1, 1)
    return vals


def _num(expr, vals):
    e = sp.sympify(expr)
    e = e.xreplace({k: v for k, v in vals.items() if isinstance(k, sp.Derivative)})
    return complex(e.xreplace(vals).evalf())


@pytest.mark.parametrize("name", EXAMPLES)
def test_problem_file_builds_the_python_model(name):
    f, _ = load_problem(HERE / f"{name}.toml")
    p = build(name)
    assert (f.name, f.title, f.statement) == (p.name, p.title, p.statement)
    assert list(f.parameter_info) == list(p.parameter_info)
    for k, a in f.parameter_info.items():
        b = p.parameter_info[k]
        assert (a.symbol, a.unit, a.description) == (b.symbol, b.unit, b.description)
        assert a.value == pytest.approx(b.value, rel=1e-15)
    assert f.coordinates == p.coordinates
    for k, a in f.coordinate_info.items():
        b = p.coordinate_info[k]
        assert (a.sense, a.kind, a.initial, a.rate) == (b.sense, b.kind, b.initial, b.rate)
    assert list(f.frames) == list(p.frames) and list(f.bodies) == list(p.bodies)
    assert list(f.constraints) == list(p.constraints) and list(f.loads) == list(p.loads)
    kf, kp = Kinematics(f), Kinematics(p)
    for seed in (1, 2):
        vals = _numbers(p, seed)
        for name_ in f.frames:
            if f.frames[name_].parent is None:
                continue
            Df = f.frames[name_].ref.dcm(f.inertial.ref)
            Dp = p.frames[name_].ref.dcm(p.inertial.ref)
            assert all(abs(_num(x - y, vals)) < 1e-12 for x, y in zip(Df, Dp)), name_
        for name_, pt in p.points.items():
            a, b = kf.position(f.points[name_]), kp.position(pt)
            assert all(abs(_num(x - y, vals)) < 1e-12
                       for x, y in zip(a.to_matrix(f.inertial.ref), b.to_matrix(p.inertial.ref))), name_
        for name_, body in p.bodies.items():
            bf = f.bodies[name_]
            assert bf.shape.kind == body.shape.kind and bf.centre.name == body.centre.name
            assert abs(_num(bf.mass - body.mass, vals)) < 1e-12
            If = bf.inertia.to_matrix(f.inertial.ref)
            Ip = body.inertia.to_matrix(p.inertial.ref)
            assert all(abs(_num(x - y, vals)) < 1e-12 for x, y in zip(If, Ip)), name_
        for name_, c in p.constraints.items():
            cf = f.constraints[name_]
            assert type(cf) is type(c) and cf.reactions() == c.reactions()
            st = c.default_state(kp)
            rows_f, rows_p = cf.rows(kf, st), c.rows(kp, st)
            assert [r.reaction for r in rows_f] == [r.reaction for r in rows_p]
            for rf, rp in zip(rows_f, rows_p):
                assert abs(_num(rf.velocity - rp.velocity, vals)) < 1e-12, rf.label
