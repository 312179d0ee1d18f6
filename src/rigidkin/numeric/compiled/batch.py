"""Batch integration: one model, many runs (parameter sets and initial states), in compiled C.

Each run is integrated by the explicit Runge–Kutta method of order 8(5,3) of Dormand and Prince
(DOP853), step for step the algorithm of scipy's ``solve_ivp(method="DOP853")`` with scipy's own
coefficients (step-size control, first step, 7th-degree dense output), in C beside the generated
model.  Events are outputs of the model (a reaction, or any expression of the state) crossing zero
in a direction: they are detected at the end of each step and located on the dense output by
Brent's method to 4 ε in time, as solve_ivp does; a terminal event ends the run.  The runs are
split into chunks that threads integrate in parallel (the C call releases the GIL).

Without a compiler the same runs are made by ``solve_ivp`` in a Python loop over the numpy kernel.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

#: Run status codes.
STATUS = {0: "reached the end time", 1: "terminal event", 2: "non-finite state", 3: "singular equations",
          4: "too many steps", 5: "step size too small", 6: "no regime fits the initial state"}


def _dop853_coefficients():
    """scipy's module of DOP853 coefficients, read from its file without importing ``scipy.integrate`` (whose
    package import costs most of a second and is not needed to run compiled code)."""
    import importlib.util
    import sys
    from pathlib import Path

    name = "scipy.integrate._ivp.dop853_coefficients"
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.find_spec("scipy")
    for folder in (spec.submodule_search_locations or []) if spec else []:
        path = Path(folder, "integrate", "_ivp", "dop853_coefficients.py")
        if path.is_file():
            module_spec = importlib.util.spec_from_file_location("rigidkin._scipy_dop853_coefficients", path)
            module = importlib.util.module_from_spec(module_spec)
            module_spec.loader.exec_module(module)
            return module
    import scipy.integrate._ivp.dop853_coefficients as d

    return d


def _coefficients_c() -> str:
    d = _dop853_coefficients()

    def arr(name, a):
        a = np.asarray(a, dtype=float)
        if a.ndim == 1:
            return f"static const double {name}[{a.size}] = {{{', '.join(repr(float(v)) for v in a)}}};"
        rows = ", ".join("{" + ", ".join(repr(float(v)) for v in r) + "}" for r in a)
        return f"static const double {name}[{a.shape[0]}][{a.shape[1]}] = {{{rows}}};"

    return "\n".join([f"#define DP_NS {d.N_STAGES}", f"#define DP_NSX {d.N_STAGES_EXTENDED}",
                      f"#define DP_NI {d.INTERPOLATOR_POWER}", arr("DP_A", d.A), arr("DP_B", d.B),
                      arr("DP_C", d.C), arr("DP_E3", d.E3), arr("DP_E5", d.E5), arr("DP_D", d.D)])


_INTEGRATOR = r"""
/* ---- batch integrator (rigidkin.numeric.compiled.batch): DOP853 as in scipy's solve_ivp, with events ---- */
#include <float.h>
#define RK_EPS DBL_EPSILON

typedef struct {
    double t_old, h, t, rtol, atol, max_step;
    const double *p;
    double y_old[RK_NY], y[RK_NY], f[RK_NY];
    double K[DP_NSX][RK_NY];
    double F[DP_NI][RK_NY];
    long nfev;
    int dense_ready;
} rk_state;

static double rk_rms(const double *v, int n) {
    double s = 0.0;
    for (int i = 0; i < n; i++) s += v[i] * v[i];
    return sqrt(s / n);
}

static double rk_first_step(rk_state *S, double t0, double t_bound) {
    double scale[RK_NY], tmp[RK_NY], y1[RK_NY], f1[RK_NY];
    double interval = fabs(t_bound - t0);
    if (interval == 0.0) return 0.0;
    for (int i = 0; i < RK_NY; i++) scale[i] = S->atol + fabs(S->y[i]) * S->rtol;
    for (int i = 0; i < RK_NY; i++) tmp[i] = S->y[i] / scale[i];
    double d0 = rk_rms(tmp, RK_NY);
    for (int i = 0; i < RK_NY; i++) tmp[i] = S->f[i] / scale[i];
    double d1 = rk_rms(tmp, RK_NY);
    double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    if (h0 > interval) h0 = interval;
    for (int i = 0; i < RK_NY; i++) y1[i] = S->y[i] + h0 * S->f[i];
    rk_eval_rhs(t0 + h0, y1, S->p, f1); S->nfev++;
    for (int i = 0; i < RK_NY; i++) tmp[i] = (f1[i] - S->f[i]) / scale[i];
    double d2 = rk_rms(tmp, RK_NY) / h0;
    double h1 = (d1 <= 1e-15 && d2 <= 1e-15) ? fmax(1e-6, h0 * 1e-3) : pow(0.01 / fmax(d1, d2), 1.0 / 8.0);
    double h = 100 * h0;
    if (h1 < h) h = h1;
    if (interval < h) h = interval;
    if (S->max_step < h) h = S->max_step;
    return h;
}

/* one accepted step (with rejections) from S->t towards t_bound; returns 0, or a status code */
static int rk_step(rk_state *S, double *h_abs, double t_bound) {
    double t = S->t, *y = S->y;
    double min_step = 10 * fabs(nextafter(t, INFINITY) - t);
    double ha = *h_abs;
    double y_new[RK_NY], f_new[RK_NY], dy[RK_NY], scale[RK_NY];
    if (ha > S->max_step) ha = S->max_step; else if (ha < min_step) ha = min_step;
    int rejected = 0;
    for (;;) {
        if (ha < min_step) return 5;
        double h = ha, t_new = t + h;
        if (t_new - t_bound > 0) t_new = t_bound;
        h = t_new - t; ha = fabs(h);
        memcpy(S->K[0], S->f, sizeof(S->f));
        for (int s = 1; s < DP_NS; s++) {
            for (int i = 0; i < RK_NY; i++) {
                double acc = 0.0;
                for (int j = 0; j < s; j++) acc += DP_A[s][j] * S->K[j][i];
                dy[i] = y[i] + acc * h;
            }
            if (rk_eval_rhs(t + DP_C[s] * h, dy, S->p, S->K[s])) return 3;
        }
        for (int i = 0; i < RK_NY; i++) {
            double acc = 0.0;
            for (int j = 0; j < DP_NS; j++) acc += DP_B[j] * S->K[j][i];
            y_new[i] = y[i] + h * acc;
        }
        if (rk_eval_rhs(t + h, y_new, S->p, f_new)) return 3;
        S->nfev += DP_NS;
        memcpy(S->K[DP_NS], f_new, sizeof(f_new));
        double e5 = 0.0, e3 = 0.0;
        int finite = 1;
        for (int i = 0; i < RK_NY; i++) {
            scale[i] = S->atol + fmax(fabs(y[i]), fabs(y_new[i])) * S->rtol;
            double a5 = 0.0, a3 = 0.0;
            for (int j = 0; j <= DP_NS; j++) { a5 += S->K[j][i] * DP_E5[j]; a3 += S->K[j][i] * DP_E3[j]; }
            a5 /= scale[i]; a3 /= scale[i];
            e5 += a5 * a5; e3 += a3 * a3;
            if (!isfinite(y_new[i]) || !isfinite(f_new[i])) finite = 0;
        }
        if (!finite) return 2;
        double err;
        if (e5 == 0.0 && e3 == 0.0) err = 0.0;
        else err = ha * e5 / sqrt((e5 + 0.01 * e3) * RK_NY);
        if (err < 1.0) {
            double factor = (err == 0.0) ? 10.0 : fmin(10.0, 0.9 * pow(err, -1.0 / 8.0));
            if (rejected && factor > 1.0) factor = 1.0;
            *h_abs = ha * factor;
            S->t_old = t; S->h = h;
            memcpy(S->y_old, y, sizeof(S->y_old));
            memcpy(S->y, y_new, sizeof(S->y));
            memcpy(S->f, f_new, sizeof(S->f));
            S->t = t_new;
            S->dense_ready = 0;
            return 0;
        }
        ha *= fmax(0.2, 0.9 * pow(err, -1.0 / 8.0));
        rejected = 1;
    }
}

static int rk_dense_prepare(rk_state *S) {
    double h = S->h, dy[RK_NY];
    for (int s = DP_NS + 1; s < DP_NSX; s++) {
        for (int i = 0; i < RK_NY; i++) {
            double acc = 0.0;
            for (int j = 0; j < s; j++) acc += DP_A[s][j] * S->K[j][i];
            dy[i] = S->y_old[i] + acc * h;
        }
        if (rk_eval_rhs(S->t_old + DP_C[s] * h, dy, S->p, S->K[s])) return 3;
        S->nfev++;
    }
    for (int i = 0; i < RK_NY; i++) {
        double d = S->y[i] - S->y_old[i];
        S->F[0][i] = d;
        S->F[1][i] = h * S->K[0][i] - d;
        S->F[2][i] = 2 * d - h * (S->f[i] + S->K[0][i]);
        for (int r = 0; r < DP_NI - 3; r++) {
            double acc = 0.0;
            for (int j = 0; j < DP_NSX; j++) acc += DP_D[r][j] * S->K[j][i];
            S->F[3 + r][i] = h * acc;
        }
    }
    S->dense_ready = 1;
    return 0;
}

static void rk_dense(const rk_state *S, double t, double *y) {
    double x = (t - S->t_old) / S->h;
    for (int i = 0; i < RK_NY; i++) {
        double v = 0.0;
        for (int k = 0; k < DP_NI; k++) {
            v += S->F[DP_NI - 1 - k][i];
            v *= (k % 2 == 0) ? x : (1 - x);
        }
        y[i] = v + S->y_old[i];
    }
}

static double rk_event_at(const rk_state *S, int idx, double t) {
    double y[RK_NY], o[RK_NO];
    rk_dense(S, t, y);
    if (rk_eval_out(t, y, S->p, o)) return NAN;
    return o[idx];
}

/* Brent's method as scipy's brentq (xtol = rtol = 4 eps) on the dense output */
static double rk_brent(const rk_state *S, int idx, double xa, double xb) {
    const double xtol = 4 * RK_EPS, rtol = 4 * RK_EPS;
    double xpre = xa, xcur = xb, xblk = 0., fblk = 0., spre = 0., scur = 0.;
    double fpre = rk_event_at(S, idx, xpre), fcur = rk_event_at(S, idx, xcur);
    if (fpre == 0) return xpre;
    if (fcur == 0) return xcur;
    for (int it = 0; it < 100; it++) {
        if (fpre != 0 && fcur != 0 && (signbit(fpre) != signbit(fcur))) {
            xblk = xpre; fblk = fpre; spre = scur = xcur - xpre;
        }
        if (fabs(fblk) < fabs(fcur)) {
            xpre = xcur; xcur = xblk; xblk = xpre;
            fpre = fcur; fcur = fblk; fblk = fpre;
        }
        double delta = (xtol + rtol * fabs(xcur)) / 2, sbis = (xblk - xcur) / 2;
        if (fcur == 0 || fabs(sbis) < delta) return xcur;
        if (fabs(spre) > delta && fabs(fcur) < fabs(fpre)) {
            double stry;
            if (xpre == xblk) stry = -fcur * (xcur - xpre) / (fcur - fpre);
            else {
                double dpre = (fpre - fcur) / (xpre - xcur), dblk = (fblk - fcur) / (xblk - xcur);
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre));
            }
            if (2 * fabs(stry) < fmin(fabs(spre), 3 * fabs(sbis) - delta)) { spre = scur; scur = stry; }
            else { spre = sbis; scur = sbis; }
        } else { spre = sbis; scur = sbis; }
        xpre = xcur; fpre = fcur;
        xcur += (fabs(scur) > delta) ? scur : (sbis > 0 ? delta : -delta);
        fcur = rk_event_at(S, idx, xcur);
    }
    return xcur;
}

/* Integrate one run.  Events: output index, direction (+1 rising, -1 falling, 0 both), terminal flag.
   ev_t[e] (NAN when none) and ev_y[e*RK_NY..] receive each event's first occurrence. */
static int rk_run(const double *y0, const double *p, double t0, double t1, double rtol, double atol,
                  double max_step, long max_steps, int ne, const int *ev_out, const int *ev_dir,
                  const int *ev_term, double *ev_t, double *ev_y, double *t_end, double *y_end, long *nfev) {
    rk_state S;
    double g[RK_NO], g_new[RK_NO], roots[RK_NO > 0 ? RK_NO : 1];
    int status = 0;
    double h_abs = 0.0;               /* declared before the first goto: C++ (a GPU's compiler) forbids the jump */
    memset(&S, 0, sizeof(S));
    S.p = p; S.rtol = rtol; S.atol = atol; S.max_step = max_step; S.t = t0;
    memcpy(S.y, y0, sizeof(S.y));
    for (int e = 0; e < ne; e++) { ev_t[e] = NAN; for (int i = 0; i < RK_NY; i++) ev_y[e * RK_NY + i] = NAN; }
    if (rk_eval_rhs(t0, S.y, p, S.f)) { status = 3; goto done; }
    S.nfev = 1;
    for (int i = 0; i < RK_NY; i++) if (!isfinite(S.f[i]) || !isfinite(S.y[i])) { status = 2; goto done; }
    if (ne && rk_eval_out(t0, S.y, p, g)) { status = 3; goto done; }
    h_abs = rk_first_step(&S, t0, t1);
    for (long step = 0; ; step++) {
        if (S.t - t1 >= 0) { status = 0; break; }
        if (step >= max_steps) { status = 4; break; }
        status = rk_step(&S, &h_abs, t1);
        if (status) break;
        if (!ne) continue;
        if (rk_eval_out(S.t, S.y, p, g_new)) { status = 3; break; }
        double t_stop = INFINITY;
        int any = 0;
        for (int e = 0; e < ne; e++) {
            int k = ev_out[e];
            double a = g[k], b = g_new[k];
            int up = (a <= 0 && b >= 0), down = (a >= 0 && b <= 0);
            int active = ev_dir[e] > 0 ? up : (ev_dir[e] < 0 ? down : (up || down));
            roots[e] = NAN;
            if (!active) continue;
            if (!S.dense_ready && rk_dense_prepare(&S)) { status = 3; goto done; }
            roots[e] = rk_brent(&S, k, S.t_old, S.t);
            any = 1;
            if (ev_term[e] && roots[e] < t_stop) t_stop = roots[e];
        }
        if (any) {
            for (int e = 0; e < ne; e++) {
                if (isnan(roots[e]) || roots[e] > t_stop || !isnan(ev_t[e])) continue;
                ev_t[e] = roots[e];
                rk_dense(&S, roots[e], ev_y + e * RK_NY);
            }
            if (isfinite(t_stop)) {
                double yt[RK_NY];
                rk_dense(&S, t_stop, yt);
                S.t = t_stop;
                memcpy(S.y, yt, sizeof(yt));
                status = 1;
                break;
            }
        }
        memcpy(g, g_new, sizeof(g));
    }
done:
    *t_end = S.t;
    memcpy(y_end, S.y, sizeof(S.y));
    *nfev = S.nfev;
    return status;
}

void rk_sweep(long n, const double *y0, const double *p, double t0, double t1, double rtol, double atol,
              double max_step, long max_steps, int ne, const int *ev_out, const int *ev_dir, const int *ev_term,
              double *ev_t, double *ev_y, double *t_end, double *y_end, int *status, long *nfev) {
    for (long r = 0; r < n; r++)
        status[r] = rk_run(y0 + r * RK_NY, p + r * RK_NP, t0, t1, rtol, atol, max_step, max_steps, ne, ev_out,
                           ev_dir, ev_term, ev_t + r * ne, ev_y + r * ne * RK_NY, t_end + r, y_end + r * RK_NY,
                           nfev + r);
}
"""

_LAZY: dict[str, str] = {}


def __getattr__(name: str) -> str:
    """``INTEGRATOR_C``, the integrator's C source (coefficients included), made on first use."""
    if name == "INTEGRATOR_C":
        if name not in _LAZY:
            _LAZY[name] = _coefficients_c() + _INTEGRATOR
        return _LAZY[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

INTEGRATOR_CDEF = """
void rk_sweep(long n, const double *y0, const double *p, double t0, double t1, double rtol, double atol,
              double max_step, long max_steps, int ne, const int *ev_out, const int *ev_dir, const int *ev_term,
              double *ev_t, double *ev_y, double *t_end, double *y_end, int *status, long *nfev);
"""


@dataclass(frozen=True)
class Event:
    """Stop or record when the model's output ``output`` crosses zero in ``direction`` (+1, -1, 0)."""

    name: str
    output: int
    direction: int = -1
    terminal: bool = True


@dataclass
class BatchResult:
    """Per run: event times (NaN: none) and states, the end time and state, the status and RHS count."""

    event_names: tuple[str, ...]
    event_t: np.ndarray        # runs × events
    event_y: np.ndarray        # runs × events × 2n
    t_end: np.ndarray          # runs
    y_end: np.ndarray          # runs × 2n
    status: np.ndarray         # runs (see STATUS)
    nfev: np.ndarray           # runs

    def __len__(self) -> int:
        return len(self.t_end)

    @staticmethod
    def concatenate(parts: Sequence[BatchResult]) -> BatchResult:
        first = parts[0]
        return BatchResult(first.event_names, *(np.concatenate([getattr(p, f) for p in parts]) for f in
                                                ("event_t", "event_y", "t_end", "y_end", "status", "nfev")))


def default_workers() -> int:
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1))


def integrate(model, y0: np.ndarray, params: np.ndarray, t_span, events: Sequence[Event] = (),
              rtol: float = 1e-10, atol: float = 1e-12, max_step: float = np.inf, max_steps: int = 1_000_000,
              workers: int | None = None, chunk: int | None = None) -> BatchResult:
    """Integrate every run (rows of ``y0``: runs × 2n; ``params``: runs × n_p) from t0 to t1."""
    y0 = np.ascontiguousarray(np.atleast_2d(y0), dtype=float)
    n = y0.shape[0]
    P = np.ascontiguousarray(np.broadcast_to(np.asarray(params, dtype=float), (n, model.kernel.np_)))
    t0, t1 = (float(v) for v in t_span)
    if hasattr(model, "integrate_batch"):           # another device (the GPU backend) integrates the runs itself
        return model.integrate_batch(y0, P, t0, t1, events, rtol, atol, max_step, max_steps)
    if model.lib is None:
        return _integrate_scipy(model, y0, P, (t0, t1), events, rtol, atol, max_step)
    workers = workers or default_workers()
    if chunk is None:
        chunk = max(1, -(-n // (4 * workers)))
    pieces = [(i, min(n, i + chunk)) for i in range(0, n, chunk)]
    if workers == 1 or len(pieces) == 1:
        parts = [_run_c(model, y0[a:b], P[a:b], t0, t1, events, rtol, atol, max_step, max_steps) for a, b in pieces]
    else:
        with ThreadPoolExecutor(workers) as pool:
            parts = list(pool.map(lambda ab: _run_c(model, y0[ab[0]:ab[1]], P[ab[0]:ab[1]], t0, t1, events, rtol,
                                                    atol, max_step, max_steps), pieces))
    return BatchResult.concatenate(parts)


def _run_c(model, y0, P, t0, t1, events, rtol, atol, max_step, max_steps) -> BatchResult:
    ffi, lib = model.ffi, model.lib
    n, ny, ne = y0.shape[0], y0.shape[1], len(events)
    ev_out = np.array([e.output for e in events] or [0], dtype=np.intc)
    ev_dir = np.array([e.direction for e in events] or [0], dtype=np.intc)
    ev_term = np.array([int(e.terminal) for e in events] or [0], dtype=np.intc)
    ev_t = np.empty((n, max(ne, 1)))
    ev_y = np.empty((n, max(ne, 1), ny))
    t_end = np.empty(n)
    y_end = np.empty((n, ny))
    status = np.empty(n, dtype=np.intc)
    nfev = np.empty(n, dtype=np.int_ if np.dtype(np.int_).itemsize == ffi.sizeof("long") else np.int64)
    buf = ffi.from_buffer
    lib.rk_sweep(n, buf("double[]", y0), buf("double[]", P), t0, t1, rtol, atol, max_step, max_steps, ne,
                 buf("int[]", ev_out), buf("int[]", ev_dir), buf("int[]", ev_term), buf("double[]", ev_t),
                 buf("double[]", ev_y), buf("double[]", t_end), buf("double[]", y_end), buf("int[]", status),
                 buf("long[]", nfev))
    names = tuple(e.name for e in events)
    return BatchResult(names, ev_t[:, :ne], ev_y[:, :ne], t_end, y_end, status.astype(int), nfev.astype(int))


def _integrate_scipy(model, y0, P, t_span, events, rtol, atol, max_step) -> BatchResult:
    """The fallback without a compiler: solve_ivp (DOP853) run by run on the numpy kernel."""
    from scipy.integrate import solve_ivp

    n, ny, ne = y0.shape[0], y0.shape[1], len(events)
    out = BatchResult(tuple(e.name for e in events), np.full((n, ne), np.nan), np.full((n, ne, ny), np.nan),
                      np.empty(n), np.empty((n, ny)), np.zeros(n, dtype=int), np.zeros(n, dtype=int))
    for r in range(n):
        p = P[r]
        fns = []
        for e in events:
            def g(t_, y, k=e.output, p=p):
                return model.outputs(t_, y, p)[k]
            g.direction, g.terminal = e.direction, e.terminal
            fns.append(g)
        sol = solve_ivp(lambda t_, y, p=p: model.rhs(t_, y, p), t_span, y0[r], method="DOP853", rtol=rtol,
                        atol=atol, max_step=max_step, events=fns or None)
        for k in range(ne):
            if len(sol.t_events[k]):
                out.event_t[r, k] = sol.t_events[k][0]
                out.event_y[r, k] = sol.y_events[k][0]
        out.t_end[r] = sol.t[-1]
        out.y_end[r] = sol.y[:, -1]
        out.status[r] = {0: 0, 1: 1}.get(sol.status, 2)
        out.nfev[r] = sol.nfev
    return out
