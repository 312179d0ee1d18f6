"""Right-hand side speed: generated C against plain lambdify, rigidkin's lambdify+CSE, numpy, hand-written C.

    python benchmarks/rhs.py

Two figures per model: the time of one call ``rhs(t, y)`` from Python (what scipy's solve_ivp
pays), and the time of one evaluation inside C over a batch of 10⁴ states (what the batch
integrator pays).  The hand-written C right-hand sides are written below from the closed-form
equations of motion (ladder: θ̈ = 3 g sin θ / (2 l); chain: the n-link mass matrix and forcing,
solved by LU), compiled with the same compiler and flags, and called the same way; each is checked
against the generated code before it is timed.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from common import machine, per_call, table

HAND_LADDER = r"""
#include <math.h>
int hand_rhs(double t, const double *y, const double *p, double *dy) {
    double th = y[0], w = y[2], l = p[1], g = p[2];
    double s = sin(th), c = cos(th);
    double dd = 1.5 * g / l * s;
    dy[0] = w; dy[1] = l * c * w; dy[2] = dd; dy[3] = l * (c * dd - s * w * w);
    return 0;
}
"""

HAND_CHAIN = r"""
#include <math.h>
#define N %(n)d
int hand_rhs(double t, const double *y, const double *p, double *dy) {
    double m = p[0], l = p[1], g = p[2], M[N][N], f[N], s[N], c[N];
    for (int i = 0; i < N; i++) { s[i] = sin(y[i]); c[i] = cos(y[i]); dy[i] = y[N + i]; }
    for (int i = 0; i < N; i++) {
        f[i] = -m * g * l * (N - i - 0.5) * s[i];
        for (int j = 0; j < N; j++) {
            double k = (i == j) ? (N - i - 1) + 1.0 / 3.0 : (N - (i > j ? i : j) - 0.5);
            double cij = c[i] * c[j] + s[i] * s[j], sij = s[i] * c[j] - c[i] * s[j];
            M[i][j] = m * l * l * k * cij;
            if (i != j) f[i] -= m * l * l * k * sij * y[N + j] * y[N + j];
        }
    }
    for (int k = 0; k < N; k++) {           /* M is symmetric positive definite: no pivoting */
        for (int i = k + 1; i < N; i++) {
            double r = M[i][k] / M[k][k];
            for (int j = k; j < N; j++) M[i][j] -= r * M[k][j];
            f[i] -= r * f[k];
        }
    }
    for (int i = N - 1; i >= 0; i--) {
        double a = f[i];
        for (int j = i + 1; j < N; j++) a -= M[i][j] * dy[N + j];
        dy[N + i] = a / M[i][i];
    }
    return 0;
}
"""

_BATCH = r"""
int hand_rhs_batch(long n, const double *t, const double *y, const double *p, double *dy) {
    int bad = 0;
    for (long i = 0; i < n; i++) bad |= hand_rhs(t[i], y + i * NY, p + i * NP, dy + i * NY);
    return bad;
}
"""


def hand_model(source: str, ny: int, np_: int):
    from rigidkin.numeric.compiled.codegen import _build

    src = source + f"\n#define NY {ny}\n#define NP {np_}\n" + _BATCH
    return _build(src, "int hand_rhs(double, const double *, const double *, double *);\n"
                       "int hand_rhs_batch(long, const double *, const double *, const double *, double *);")


def measure(name: str, system, hand_source: str, states: np.ndarray, params: np.ndarray, form: str = "auto"):
    from rigidkin.numeric.compiled.codegen import compile_model, fast_rhs, kernel
    from rigidkin.numeric.state import StateLayout

    k = kernel(system, form=form)
    lay = StateLayout.of(system)
    # plain lambdify of the rates (accelerations substituted), no CSE
    if k.A is None:
        sub = dict(zip(k.unknowns, k.b))
        exprs = [sp.sympify(e).xreplace(sub) for e in k.rates]
        plain = sp.lambdify(lay.arguments(), exprs, "numpy")

        def lam(t, y, p=tuple(params)):
            return np.array(plain(t, *y, *p), dtype=float)
        from rigidkin.numeric.rhs import make_rhs

        rk_lambdify = make_rhs(system)
    else:                  # mass-matrix (or implicit) form: lambdify M, f and the rates; numpy solves M q̈ = f
        mat, vec = (k.M, k.f) if k.M is not None else (k.A, k.b)
        Ab = sp.lambdify(lay.arguments(), [list(mat), list(vec)], "numpy")
        nx = mat.rows
        rates = sp.lambdify(lay.arguments() + list(k.unknowns[:nx]), list(k.rates), "numpy")

        def lam(t, y, p=tuple(params)):
            A, b = Ab(t, *y, *p)
            x = np.linalg.solve(np.array(A, dtype=float).reshape(nx, nx), np.array(b, dtype=float))
            return np.array(rates(t, *y, *p, *x), dtype=float)
        rk_lambdify = None
    fast = fast_rhs(system, form=form)
    fast_np = fast_rhs(system, form=form, backend="numpy")
    ffi, hlib = hand_model(hand_source, k.ny, k.np_)
    pbuf = np.ascontiguousarray(params, dtype=float)
    pptr = ffi.from_buffer("double[]", pbuf)

    def hand(t, y):
        dy = np.empty(k.ny)
        hlib.hand_rhs(t, ffi.from_buffer("double[]", y), pptr, ffi.from_buffer("double[]", dy))
        return dy

    y0 = np.ascontiguousarray(states[0])
    for y in states[:20]:                      # every path gives the same numbers
        ref = hand(0.0, np.ascontiguousarray(y))
        for f in (fast, fast_np, lambda t, y: lam(t, y)) + ((rk_lambdify,) if rk_lambdify else ()):
            np.testing.assert_allclose(f(0.0, np.ascontiguousarray(y)), ref, rtol=1e-9, atol=1e-9)
    t_plain = per_call(lambda: lam(0.0, y0))
    t_rk = per_call(lambda: rk_lambdify(0.0, y0)) if rk_lambdify else None
    t_np = per_call(lambda: fast_np(0.0, y0))
    t_c = per_call(lambda: fast(0.0, y0))
    t_hand = per_call(lambda: hand(0.0, y0))
    # inside C, over a batch of states
    model = compile_model(system, form=form)
    Y = np.ascontiguousarray(states)
    P = np.ascontiguousarray(np.tile(params, (len(Y), 1)))
    T = np.zeros(len(Y))
    out = np.empty_like(Y)
    buf = ffi.from_buffer
    hargs = (len(Y), buf("double[]", T), buf("double[]", Y), buf("double[]", P), buf("double[]", out))
    b_c = per_call(lambda: model.rhs_batch(0.0, Y, P)) / len(Y)
    b_hand = per_call(lambda: hlib.hand_rhs_batch(*hargs)) / len(Y)
    return [name + f" ({k.form})", t_plain, t_rk, t_np, t_c, t_hand, t_plain / t_c, t_c / t_hand, b_c, b_hand,
            b_c / b_hand]


def main() -> None:
    import rigidkin as rk
    from rigidkin.examples import chain

    print(f"# Right-hand side speed ({machine()})", flush=True)
    rng = np.random.default_rng(0)
    rows = []
    ladder = rk.examples.build("ladder")
    th = rng.uniform(0.05, 1.3, 10_000)
    w = rng.uniform(-2, 2, 10_000)
    states = np.column_stack([th, 2 * np.sin(th), w, 2 * np.cos(th) * w])
    rows.append(measure("ladder", ladder, HAND_LADDER, states, np.array([10.0, 2.0, 9.81])))
    n = 5
    states = np.column_stack([rng.uniform(-1, 1, (10_000, n)), rng.uniform(-2, 2, (10_000, n))])
    rows.append(measure(f"chain {n}", chain.build(n), HAND_CHAIN % {"n": n}, states, np.array([1.0, 1.0, 9.81]),
                        form="auto"))
    print(table("One RHS evaluation (seconds; median of 5 timed loops)",
                ["model", "lambdify", "rk lambdify+cse", "numpy backend", "generated C", "hand C", "lambdify/C",
                 "C/hand", "in-C gen", "in-C hand", "in-C gen/hand"], rows,
                "lambdify: plain sympy.lambdify of the rates called as f(t, *y, *p) → array (the baseline);\n"
                "rk lambdify+cse: rigidkin.numeric.rhs.make_rhs (the simulator's RHS);\n"
                "generated C / hand C: rhs(t, y) through cffi from Python; in-C: per state over a batch of 10⁴ "
                "states (no Python).\nTargets: lambdify/C ≥ 20; C/hand ≤ 3."), flush=True)


if __name__ == "__main__":
    main()
