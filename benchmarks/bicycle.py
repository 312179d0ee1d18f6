"""Whipple bicycle: rigidkin's derivation against sympy.physics.mechanics' own bicycle model, and RHS speed.

    python benchmarks/bicycle.py            # everything (sympy's linearisation may take minutes)
    python benchmarks/bicycle.py --quick    # skip sympy's linearisation

The sympy model is the one of sympy's own test ``physics/mechanics/tests/test_kane3.py`` (a port of
an Autolev model of Meijaard et al. 2007): frames yaw–roll–pitch–steer, generalised speeds u1…u6,
KanesMethod with the front contact's three velocity constraints and the holonomic pitch constraint,
built here with the same numbers.  Measured (CPU seconds of this process; medians where repeated):

* derivation — rigidkin: ``examples.bicycle.projected()`` (the model, its kinematics, partial
  velocities, remainder accelerations, constraint rows and their derivatives, the workless check);
  sympy: building the model and ``KanesMethod.kanes_equations``.  Their ratio.
* linearisation — rigidkin: ``lean_steer_matrices`` (two linearisations in 40-digit arithmetic);
  sympy: ``KanesMethod.linearize`` at the upright operating point (as in its test).
* RHS speed — one call of the right-hand side from Python: rigidkin's projected equations with numpy
  (lambdify + CSE) and with generated C (``numeric.codegen``); sympy's mass matrix and forcing
  lambdified (with CSE) and solved by numpy.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import sympy as sp
from common import CLOCK, TimeLimit, machine, per_call, table, time_limit

from rigidkin.examples import bicycle


def sympy_bicycle():
    """sympy's Kane model of the benchmark bicycle (test_kane3's formulation); returns (KM, values, speeds)."""
    from sympy.physics.mechanics import KanesMethod, Point, ReferenceFrame, RigidBody, dot, dynamicsymbols, inertia

    q1, q2, q4, q5 = dynamicsymbols("q1 q2 q4 q5")
    q1d, q2d, q4d, q5d = dynamicsymbols("q1 q2 q4 q5", 1)
    u1, u2, u3, u4, u5, u6 = dynamicsymbols("u1 u2 u3 u4 u5 u6")
    WFrad, WRrad, htangle, forkoffset = sp.symbols("WFrad WRrad htangle forkoffset")
    forklength, framelength, forkcg1 = sp.symbols("forklength framelength forkcg1")
    forkcg3, framecg1, framecg3, Iwr11 = sp.symbols("forkcg3 framecg1 framecg3 Iwr11")
    Iwr22, Iwf11, Iwf22, Iframe11 = sp.symbols("Iwr22 Iwf11 Iwf22 Iframe11")
    Iframe22, Iframe33, Iframe31, Ifork11 = sp.symbols("Iframe22 Iframe33 Iframe31 Ifork11")
    Ifork22, Ifork33, Ifork31, g = sp.symbols("Ifork22 Ifork33 Ifork31 g")
    mframe, mfork, mwf, mwr = sp.symbols("mframe mfork mwf mwr")
    N = ReferenceFrame("N")
    Y = N.orientnew("Y", "Axis", [q1, N.z])
    R = Y.orientnew("R", "Axis", [q2, Y.x])
    Frame = R.orientnew("Frame", "Axis", [q4 + htangle, R.y])
    WR = ReferenceFrame("WR")
    TempFrame = Frame.orientnew("TempFrame", "Axis", [-htangle, Frame.y])
    Fork = Frame.orientnew("Fork", "Axis", [q5, Frame.x])
    TempFork = Fork.orientnew("TempFork", "Axis", [-htangle, Fork.y])
    WF = ReferenceFrame("WF")
    WR_cont = Point("WR_cont")
    WR_mc = WR_cont.locatenew("WR_mc", WRrad * R.z)
    Steer = WR_mc.locatenew("Steer", framelength * Frame.z)
    Frame_mc = WR_mc.locatenew("Frame_mc", -framecg1 * Frame.x + framecg3 * Frame.z)
    Fork_mc = Steer.locatenew("Fork_mc", -forkcg1 * Fork.x + forkcg3 * Fork.z)
    WF_mc = Steer.locatenew("WF_mc", forklength * Fork.x + forkoffset * Fork.z)
    WF_cont = WF_mc.locatenew("WF_cont", WFrad * (dot(Fork.y, Y.z) * Fork.y - Y.z).normalize())
    Y.set_ang_vel(N, u1 * Y.z)
    R.set_ang_vel(Y, u2 * R.x)
    WR.set_ang_vel(Frame, u3 * Frame.y)
    Frame.set_ang_vel(R, u4 * Frame.y)
    Fork.set_ang_vel(Frame, u5 * Fork.x)
    WF.set_ang_vel(Fork, u6 * Fork.y)
    WR_cont.set_vel(N, 0)
    WR_mc.v2pt_theory(WR_cont, N, WR)
    Steer.v2pt_theory(WR_mc, N, Frame)
    Frame_mc.v2pt_theory(WR_mc, N, Frame)
    Fork_mc.v2pt_theory(Steer, N, Fork)
    WF_mc.v2pt_theory(Steer, N, Fork)
    WF_cont.v2pt_theory(WF_mc, N, WF)
    bodies = [
        RigidBody("Frame", Frame_mc, Frame, mframe,
                  (inertia(TempFrame, Iframe11, Iframe22, Iframe33, 0, 0, Iframe31), Frame_mc)),
        RigidBody("Fork", Fork_mc, Fork, mfork, (inertia(TempFork, Ifork11, Ifork22, Ifork33, 0, 0, Ifork31), Fork_mc)),
        RigidBody("WR", WR_mc, WR, mwr, (inertia(Frame, Iwr11, Iwr22, Iwr11), WR_mc)),
        RigidBody("WF", WF_mc, WF, mwf, (inertia(Fork, Iwf11, Iwf22, Iwf11), WF_mc)),
    ]
    loads = [(Frame_mc, -mframe * g * Y.z), (Fork_mc, -mfork * g * Y.z), (WF_mc, -mwf * g * Y.z),
             (WR_mc, -mwr * g * Y.z)]
    KM = KanesMethod(N, q_ind=[q1, q2, q5], q_dependent=[q4],
                     configuration_constraints=[WF_cont.pos_from(WR_cont) & Y.z],
                     u_ind=[u2, u3, u5], u_dependent=[u1, u4, u6],
                     velocity_constraints=[WF_cont.vel(N) & Y.x, WF_cont.vel(N) & Y.y, WF_cont.vel(N) & Y.z],
                     kd_eqs=[q1d - u1, q2d - u2, q4d - u4, q5d - u5], constraint_solver="CRAMER")
    KM.kanes_equations(bodies, loads)
    # the benchmark's Table 1 in this model's parameters (as in the test)
    rr, rf, HTA, trail, wb = 0.3, 0.35, float(sp.pi / 2 - sp.pi / 10), 0.08, 1.02
    rake = -(trail * np.sin(HTA) - rf * np.cos(HTA))
    frame_length = wb * np.sin(HTA) - (rake - (rf - rr) * np.cos(HTA))
    fcg_norm = (0.9 - rr - (0.3 / np.sin(HTA)) * np.cos(HTA)) * np.sin(HTA)
    fcg_par = 0.3 / np.sin(HTA) + (0.9 - rr - 0.3 / np.sin(HTA) * np.cos(HTA)) * np.cos(HTA)
    ta, tb = 0.7 - rf, wb - 0.9
    tc = np.hypot(ta, tb)
    fork_l = wb * np.cos(HTA) - (rf - rr) * np.sin(HTA)
    kcg_norm = rake + tc * np.sin(np.pi / 2 - HTA - np.arccos(ta / tc))
    kcg_par = tc * np.cos(np.pi / 2 - HTA - np.arccos(ta / tc)) - fork_l
    values = {WFrad: rf, WRrad: rr, htangle: HTA, forkoffset: rake, forklength: fork_l, framelength: frame_length,
              forkcg1: kcg_par, forkcg3: kcg_norm, framecg1: fcg_norm, framecg3: fcg_par, Iwr11: 0.0603,
              Iwr22: 0.12, Iwf11: 0.1405, Iwf22: 0.28, Ifork11: 0.05892, Ifork22: 0.06, Ifork33: 0.00708,
              Ifork31: 0.00756, Iframe11: 9.2, Iframe22: 11, Iframe33: 2.8, Iframe31: -2.4, mfork: 4, mframe: 85,
              mwf: 3, mwr: 2, g: 9.81}
    return KM, values, (q1, q2, q4, q5), (u1, u2, u3, u4, u5, u6)


def sympy_linearise(KM, values, qs, us, v):
    q1, q2, q4, q5 = qs
    u1, u2, u3, u4, u5, u6 = us
    op = {u.diff(): 0 for u in us}
    op.update({u1: 0, u2: 0, u3: v / 0.3, u4: 0, u5: 0, u6: v / 0.35, q1: 0, q2: 0, q4: 0, q5: 0})
    A, _, _ = KM.linearize(A_and_B=True, op_point=op, linear_solver="CRAMER")
    return np.array(A.xreplace(values).evalf(), dtype=float)[np.ix_([1, 2, 3, 5], [1, 2, 3, 5])]


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="skip sympy's linearisation (minutes)")
    ap.add_argument("--limit", type=float, default=900.0, help="time limit of each sympy step, seconds")
    args = ap.parse_args(argv)
    print(f"Whipple bicycle benchmark — {machine()}")

    t0 = CLOCK()
    model = bicycle.projected()
    t_rk = CLOCK() - t0
    t0 = CLOCK()
    q0 = bicycle.upright(model)          # the first numeric use: lambdify (numpy) and the workless check
    model.accelerations(q0, [0.0, 0.0, -5 / 0.3])
    t_rk_np = CLOCK() - t0
    t0 = CLOCK()
    mats = bicycle.lean_steer_matrices(model)
    t_rk_lin = CLOCK() - t0
    t0 = CLOCK()
    try:
        with time_limit(args.limit):
            KM, values, qs, us = sympy_bicycle()
        t_sp = CLOCK() - t0
    except TimeLimit:
        KM, t_sp = None, None
    rows = [["rigidkin (numeric.projected)", t_rk, t_rk_np, t_rk_lin],
            ["sympy KanesMethod (test_kane3 model)", t_sp, None, None]]
    t_sp_lin, A_sp = None, None
    if KM is not None and not args.quick:
        t0 = CLOCK()
        try:
            with time_limit(args.limit):
                A_sp = sympy_linearise(KM, values, qs, us, 5.0)
            t_sp_lin = CLOCK() - t0
        except TimeLimit:
            t_sp_lin = None
        rows[1][3] = t_sp_lin
    ratio = f"rigidkin / sympy derivation time: {t_rk / t_sp:.3g}" if t_sp else "sympy did not finish"
    print(table("Derivation (CPU s)", ["model", "derive", "numpy functions + check", "lean-steer linearisation"], rows,
                note=ratio))
    # agreement with the benchmark and with sympy's linearisation
    pub_M = np.array([[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]])
    g, v = 9.81, 5.0
    A_rk = np.block([[np.zeros((2, 2)), np.eye(2)],
                     [-np.linalg.solve(mats["M"], g * mats["K0"] + v**2 * mats["K2"]),
                      -np.linalg.solve(mats["M"], v * mats["C1"])]])
    lines = [f"max |M − M_published| = {np.abs(mats['M'] - pub_M).max():.2e}"]
    if A_sp is not None:
        lines.append(f"max |A_rigidkin − A_sympy| at v = 5 m/s (lean, steer, rates) = {np.abs(A_rk - A_sp).max():.2e}")
    print("\n".join(lines))
    # RHS speed
    f_np = model.rhs()
    y = np.concatenate([q0, [0.01, 0.02, -5 / 0.3]])
    y[0], y[1] = 0.05, 0.03
    y[:8] = model.configuration(list(y[:8]))
    rhs_rows = [["rigidkin projected, numpy", per_call(lambda: f_np(0.0, y))]]
    try:
        f_c = model.rhs(backend="c")
        d_np, d_c = f_np(0.0, y), f_c(0.0, y)
        assert np.allclose(d_np, d_c, rtol=1e-9, atol=1e-12), "C and numpy right-hand sides differ"
        rhs_rows.append(["rigidkin projected, generated C", per_call(lambda: f_c(0.0, y))])
    except Exception as exc:  # noqa: BLE001 - report what happened, keep benchmarking
        rhs_rows.append([f"rigidkin projected, generated C ({type(exc).__name__})", None])
    if KM is not None:
        t0 = time.perf_counter()
        Mfull = KM.mass_matrix_full.xreplace(values)
        ffull = KM.forcing_full.xreplace(values)
        syms = list(KM.q) + list(KM.u)
        plain = {s: sp.Symbol(f"_s{i}") for i, s in enumerate(syms)}
        fM = sp.lambdify(list(plain.values()), Mfull.xreplace(plain), "numpy", cse=True)
        ff = sp.lambdify(list(plain.values()), ffull.xreplace(plain), "numpy", cse=True)
        x = np.array([0.0, 0.05, 0.01, 0.03, 0.0, 0.01, -5 / 0.3, 0.0, 0.02, 5 / 0.35])
        xs = x[: len(syms)]

        def sympy_rhs():
            return np.linalg.solve(fM(*xs), np.ravel(ff(*xs)))

        sympy_rhs()
        rhs_rows.append(["sympy mass_matrix_full \\ forcing_full, numpy", per_call(sympy_rhs)])
        print(f"(sympy's numeric functions took {time.perf_counter() - t0:.1f} s wall to make)")
    print(table("Right-hand side, one call from Python (s)", ["model", "time per call"], rhs_rows))


if __name__ == "__main__":
    main()
