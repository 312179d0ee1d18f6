"""Baseline models built in the benchmarks with sympy.physics.mechanics (independent of rigidkin)."""

from __future__ import annotations

import sympy as sp
import sympy.physics.mechanics as me


def kane_chain(n: int):
    """The n-rod chain (uniform rods m, l; absolute angles from the downward vertical) by KanesMethod.

    Returns (KanesMethod, q, u, (m, l, g)); ``km.mass_matrix`` and ``km.forcing`` are filled.
    """
    q = me.dynamicsymbols(f"q1:{n + 1}")
    u = me.dynamicsymbols(f"u1:{n + 1}")
    m, l, g = sp.symbols("m l g", positive=True)
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    bodies, loads, top = [], [], O
    for i in range(n):
        A = N.orientnew(f"A{i}", "Axis", (q[i], N.z))
        A.set_ang_vel(N, u[i] * N.z)
        G = top.locatenew(f"G{i}", -l / 2 * A.y)
        G.v2pt_theory(top, N, A)
        bodies.append(me.RigidBody(f"rod{i}", G, A, m, (me.inertia(A, 0, 0, m * l ** 2 / 12), G)))
        loads.append((G, -m * g * N.y))
        top = top.locatenew(f"P{i}", -l * A.y)
        top.v2pt_theory(G, N, A)
    km = me.KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=[qi.diff() - ui for qi, ui in zip(q, u)])
    km.kanes_equations(bodies, loads)
    return km, q, u, (m, l, g)


def ops_after_cse(exprs) -> int:
    """Operation count (sympy.count_ops) of expressions after common-subexpression elimination."""
    exprs = [sp.sympify(e) for e in exprs]
    subs, reduced = sp.cse(exprs, order="none")
    return int(sum(sp.count_ops(e) for _, e in subs) + sum(sp.count_ops(e) for e in reduced))
