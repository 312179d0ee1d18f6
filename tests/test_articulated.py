"""The articulated-body route (numeric/tree.py, articulated.py, large.py): the same equations of motion as
the symbolic derivation of the same model, energy kept by the simulation, cost linear in the bodies,
and the automatic switch past the symbolic limit (Python API and CLI)."""

from __future__ import annotations

import importlib
import itertools
import json
import math

import numpy as np
import pytest
from helpers import rigidkin_process

import rigidkin as rk
from rigidkin.commands.common import load_system
from rigidkin.numeric import simulate
from rigidkin.numeric.large.articulated import ArticulatedModel
from rigidkin.numeric.large.route import SYMBOLIC_LIMIT, numeric_route
from rigidkin.numeric.large.tree import NotATree, read_tree
from rigidkin.numeric.rhs import compile_functions
from rigidkin.numeric.state import StateLayout, parameter_vector


def chain(n: int) -> rk.System:
    """The bundled chain of n rods (examples/chain.py), absolute angles."""
    return importlib.import_module("rigidkin.examples.chain").build(n)


def relative_chain(n: int) -> rk.System:
    """Rods in relative angles with torsional springs between them, a damping torque at the top pin and a
    force at the free end that grows with time: every load kind the route takes."""
    s = rk.System(f"relchain{n}")
    m, l = s.parameter("m", "kg", value=1.3), s.parameter("l", "m", value=0.7)
    g, k = s.parameter("g", "m/s^2", value=9.81), s.parameter("k", "N*m", value=2.0)
    F0 = s.parameter("F0", "N", value=0.5)
    top, above, prev = s.origin, None, s.inertial
    for i in range(1, n + 1):
        phi = s.coordinate(f"phi{i}", "angle of rod i from rod i - 1")
        R = s.frame(f"R{i}", parent=prev, angle=phi)
        G = s.point(f"G{i}", top, -l / 2 * R.y)
        rod = s.body(f"rod{i}", rk.shapes.SlenderRod(m * i, l, axis="y"), frame=R, at=G)
        s.pin(f"P{i - 1}", top, rod, above)
        if above is None:
            s.torque(f"T{i}", rod, -k * phi.diff(rk.t) * s.inertial.z)
        else:
            s.torsional_spring(f"k{i}", rod, stiffness=k, angle=phi, body_b=above)
        top, above, prev = s.point(f"P{i}", top, -l * R.y, body=rod), rod, R
    s.force("push", top, F0 * s.inertial.x + F0 * rk.t * prev.y)
    s.gravity(g)
    return s


def symbolic_rates(system):
    """dy/dt from the symbolic mass matrix and forcing of System.solve (M q̈ = f solved numerically)."""
    lay = StateLayout.of(system)
    sol = system.solve()
    reg = sol.regime(0)
    assert tuple(sol.coordinates) == tuple(lay.coordinates)
    fn = compile_functions(lay.arguments(), [lay.to_plain(e) for e in (*reg.mass_matrix, *reg.forcing)])
    n = lay.n

    def rates(t_, y, p):
        v = np.array(fn(t_, *y[:2 * n], *p), dtype=float)
        M = v[:n * n].reshape(n, n)
        if np.linalg.cond(M) > 1e10:
            return None                   # a singular configuration of the coordinates (Euler angles)
        return np.concatenate([y[n:2 * n], np.linalg.solve(M, v[n * n:])])
    return rates


def states(n: int, rng, count: int = 3):
    """Random states, then the special ones: every angle at 0, ±π/2, π (rates random)."""
    out = [rng.uniform(-3, 3, 2 * n) for _ in range(count)]
    for a in (0.0, math.pi / 2, -math.pi / 2, math.pi):
        out.append(np.concatenate([np.full(n, a), rng.uniform(-2, 2, n)]))
    out.append(np.concatenate([np.array([a for a, _ in zip(itertools.cycle((0, math.pi / 2, math.pi)),
                                                             range(n))]), np.zeros(n)]))
    return out


def agree(system, t_=0.3, tol=1e-10):
    am = ArticulatedModel(system)
    p = parameter_vector(system, am.layout)
    ref = symbolic_rates(system)
    n, compared = am.n, 0
    for y in states(n, np.random.default_rng(n)):
        b = ref(t_, y, p)
        if b is None:
            continue
        compared += 1
        a = am.rates(t_, np.concatenate([y, [0.0]]), p)[:2 * n]
        assert np.max(np.abs(a - b)) <= tol * max(1.0, np.max(np.abs(b))), (y, a - b)
    assert compared >= 4
    return am, p


@pytest.mark.parametrize("n", [2, 3, *(pytest.param(n, marks=pytest.mark.slow) for n in (4, 5, 6))])
def test_chain_agrees_with_the_symbolic_eom(n):
    am, p = agree(chain(n))
    # the step in C (gravity only) and in numpy are the same algorithm: they agree to rounding
    slow = ArticulatedModel(chain(n), use_c=False)
    y = np.concatenate([np.random.default_rng(0).uniform(-3, 3, 2 * n), [0.0]])
    assert np.allclose(am.rates(0.0, y, p), slow.rates(0.0, y, p), rtol=1e-12, atol=1e-12)


def test_pin_reactions_and_energy_agree_with_the_symbolic_route():
    s = chain(3)
    am = ArticulatedModel(s)
    p = parameter_vector(s, am.layout)
    from rigidkin.numeric.simulate import hybrid_of

    model = hybrid_of(s).model({}, 0)
    numpy_step = ArticulatedModel(s, use_c=False)
    for y in states(3, np.random.default_rng(1)):
        y = np.concatenate([y, [0.0]])
        r1, r2 = am.reactions(0.0, y, p), model.reactions(0.0, y, p)
        r3, T3, U3 = numpy_step.sample(0.0, y, p)
        assert all(abs(r3[k] - r2[k]) <= 1e-10 * max(1.0, abs(r2[k])) for k in r2)
        assert np.allclose((T3, U3), model.energy(0.0, y, p), rtol=1e-12, atol=1e-12)
        assert set(r1) == set(r2) == {"R_P0x", "R_P0y", "R_P1x", "R_P1y", "R_P2x", "R_P2y"}
        assert all(abs(r1[k] - r2[k]) <= 1e-10 * max(1.0, abs(r2[k])) for k in r2)
        assert np.allclose(am.energy(0.0, y, p), model.energy(0.0, y, p), rtol=1e-12, atol=1e-12)


@pytest.mark.slow
def test_relative_angles_springs_torques_and_forces_agree():
    am, p = agree(relative_chain(3))
    assert not am.conservative          # the damping torque and the pushing force do work
    # the work integrand is their power: dE/dt = P along the motion
    y = np.concatenate([np.random.default_rng(3).uniform(-2, 2, 6), [0.0]])
    r = am.rates(0.4, y, p)
    h = 1e-6
    E = [sum(am.energy(0.4 + s * h, y + s * h * r, p)) for s in (-1, 1)]
    assert (E[1] - E[0]) / (2 * h) == pytest.approx(r[-1], rel=1e-6, abs=1e-8)


@pytest.mark.parametrize("sequence", ["313", pytest.param("123", marks=pytest.mark.slow)])
def test_three_dimensional_top_on_a_ball_joint(sequence):
    """A body on a fixed point with three Euler angles: three rotations in one pin (massless links between)."""
    s = importlib.import_module("rigidkin.examples.heavy_top").build(sequence)
    am, _ = agree(s)
    assert len(am.tree.nodes) == 3 and len(am.tree.joints) == 1


def test_models_outside_the_route_are_refused_with_the_reason():
    for name, words in (("ladder", "not a pin"), ("collar-rod", "not a pin")):
        s, _ = load_system(name)
        with pytest.raises(NotATree, match=words):
            read_tree(s)
        assert numeric_route(s, limit=0) is None
    assert numeric_route(chain(SYMBOLIC_LIMIT)) is None            # small enough: the symbolic route
    assert numeric_route(chain(3), limit=2) is not None


# The cost of one RHS growing linearly with the chain's length (O(n), C and numpy steps) is measured, not
# tested: benchmarks/chain_scaling.py prints it against Pinocchio's ABA (a timing ratio is no unit test).


def test_chain_past_the_limit_simulates_numerically_with_energy_kept():
    s = chain(SYMBOLIC_LIMIT + 2)
    r = simulate(s, 0.2, rtol=1e-10, atol=1e-12, n_points=51)
    assert r.reached_end and "articulated-body algorithm" in r.route and f"{SYMBOLIC_LIMIT + 2} degrees" in r.route
    assert r.energy_balance == "conserved" and r.energy_drift < 1e-8
    assert "R_P0y" in r.reactions and np.all(np.isfinite(r.reactions["R_P0y"]))


@pytest.mark.slow
@pytest.mark.parametrize("n", [30, 50])
def test_chains_of_30_and_50_simulate_with_energy_kept(n):
    r = simulate(chain(n), 0.5, rtol=1e-10, atol=1e-12, n_points=101)
    assert r.reached_end and f"{n} degrees of freedom" in r.route
    assert r.energy_drift < 1e-8


def chain_toml(n: int) -> str:
    lines = ['title = "Chain of rods"', "[parameters]", 'm = { unit = "kg", value = 1 }',
             'l = { unit = "m", value = 1 }', 'g = { unit = "m/s^2", value = 9.81 }', "[coordinates]"]
    lines += [f'theta{i} = {{ sense = "angle of rod {i} from the downward vertical", initial = {0.3 + 0.05 * i} }}'
              for i in range(1, n + 1)]
    lines.append("[frames]")
    lines += [f'R{i} = {{ angle = "theta{i}" }}' for i in range(1, n + 1)]
    lines.append("[points]")
    for i in range(1, n + 1):
        top = "O" if i == 1 else f"P{i - 1}"
        lines.append(f'G{i} = {{ from = "{top}", offset = "-l/2*R{i}.y" }}')
        if i < n:
            lines.append(f'P{i} = {{ from = "{top}", offset = "-l*R{i}.y", body = "rod{i}" }}')
    lines.append("[bodies]")
    lines += [f'rod{i} = {{ shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R{i}", '
              f'at = "G{i}" }}' for i in range(1, n + 1)]
    lines.append("[constraints]")
    for i in range(1, n + 1):
        top = "O" if i == 1 else f"P{i - 1}"
        below = f', body_b = "rod{i - 1}"' if i > 1 else ""
        lines.append(f'J{i} = {{ type = "pin", point = "{top}", body_a = "rod{i}"{below} }}')
    lines += ["[loads]", 'gravity = { type = "gravity", g = "g" }']
    return "\n".join(lines) + "\n"


@pytest.mark.slow
def test_cli_simulates_a_chain_file_past_the_limit(tmp_path):
    path = tmp_path / "chain.toml"
    path.write_text(chain_toml(SYMBOLIC_LIMIT + 3))
    out = rigidkin_process("simulate", path, "--t-end", "0.1", "--json", "--points", "21", timeout=300)
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["reached_end"] and data["energy_drift"] < 1e-8
    assert "articulated-body algorithm" in data["modes"][0]["mode"]
    assert f"{SYMBOLIC_LIMIT + 3} degrees of freedom" in data["modes"][0]["mode"]
