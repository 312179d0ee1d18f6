"""The batch integrator's C source for a GPU: the same generated model and the same DOP853 with events,
one run per thread.

:func:`device_source` takes the C file a sweep compiles (:func:`rigidkin.numeric.compiled.csource.c_source`
followed by :data:`rigidkin.numeric.compiled.batch.INTEGRATOR_C`) and changes only qualifiers: its static
functions become device functions (``RK_DEV``), its coefficient tables device constants (``RK_CONST``), its host
entry points (``rk_rhs``, ``rk_out``, their batch forms and ``rk_sweep``) are left out, and a kernel
``rk_sweep_dev`` integrates run number ``RK_THREAD``.  A fixed shim in front says what those names are: for
CUDA (NVRTC defines ``__CUDACC__``) device qualifiers and the few C library names NVRTC has no header for; for
any other compiler plain C, with ``rk_sweep_host`` running the kernel body for every run in a loop — so the
very text sent to the GPU is compiled and run on the CPU in the tests, against the C backend.
"""

from __future__ import annotations

_SHIM = r"""/* rigidkin device shim: CUDA (NVRTC) or plain C on the host */
#ifdef __CUDACC__
#define RK_DEV static __device__
#define RK_CONST static __device__ const
#define RK_KERNEL extern "C" __global__
#define RK_THREAD ((long)blockIdx.x * (long)blockDim.x + (long)threadIdx.x)
#define NAN __longlong_as_double(0x7ff8000000000000LL)
#define INFINITY __longlong_as_double(0x7ff0000000000000LL)
#define DBL_EPSILON 2.220446049250313e-16
#define DBL_MAX 1.7976931348623157e308
#define isnan(x) ((x) != (x))
#define isfinite(x) (fabs(x) <= DBL_MAX)
#define signbit(x) (__double_as_longlong(x) < 0)
static __device__ void rk_copy(void *d, const void *s, unsigned long n) {
    char *a = (char *)d; const char *b = (const char *)s;
    for (unsigned long i = 0; i < n; i++) a[i] = b[i];
}
static __device__ void rk_zero(void *d, int v, unsigned long n) {
    char *a = (char *)d;
    for (unsigned long i = 0; i < n; i++) a[i] = (char)v;
}
#define memcpy rk_copy
#define memset rk_zero
#else
#include <math.h>
#include <string.h>
#include <float.h>
#define RK_DEV static
#define RK_CONST static const
#define RK_KERNEL static
static long rk_thread_index;
#define RK_THREAD rk_thread_index
#endif
#ifndef M_PI
#define M_E 2.718281828459045235360287471352662498
#define M_LOG2E 1.442695040888963407359924681001892137
#define M_LOG10E 0.434294481903251827651128918916605082
#define M_LN2 0.693147180559945309417232121458176568
#define M_LN10 2.302585092994045684017991454684364208
#define M_PI 3.141592653589793238462643383279502884
#define M_PI_2 1.570796326794896619231321691639751442
#define M_PI_4 0.785398163397448309615660845819875721
#define M_1_PI 0.318309886183790671537767526745028724
#define M_2_PI 0.636619772367581343075535053490057448
#define M_2_SQRTPI 1.128379167095512573896158903121545172
#define M_SQRT2 1.414213562373095048801688724209698079
#define M_SQRT1_2 0.707106781186547524400844362104849039
#endif
"""

_KERNEL = r"""
RK_KERNEL void rk_sweep_dev(long n, const double *y0, const double *p, double t0, double t1, double rtol,
                            double atol, double max_step, long max_steps, int ne, const int *ev_out,
                            const int *ev_dir, const int *ev_term, double *ev_t, double *ev_y, double *t_end,
                            double *y_end, int *status, long *nfev) {
    long r = RK_THREAD;
    if (r >= n) return;
    status[r] = rk_run(y0 + r * RK_NY, p + r * RK_NP, t0, t1, rtol, atol, max_step, max_steps, ne, ev_out, ev_dir,
                       ev_term, ev_t + r * (ne > 0 ? ne : 1), ev_y + r * (ne > 0 ? ne : 1) * RK_NY, t_end + r,
                       y_end + r * RK_NY, nfev + r);
}
#ifndef __CUDACC__
void rk_sweep_host(long n, const double *y0, const double *p, double t0, double t1, double rtol, double atol,
                   double max_step, long max_steps, int ne, const int *ev_out, const int *ev_dir, const int *ev_term,
                   double *ev_t, double *ev_y, double *t_end, double *y_end, int *status, long *nfev) {
    for (rk_thread_index = 0; rk_thread_index < n; rk_thread_index++)
        rk_sweep_dev(n, y0, p, t0, t1, rtol, atol, max_step, max_steps, ne, ev_out, ev_dir, ev_term, ev_t, ev_y,
                     t_end, y_end, status, nfev);
}
#endif
"""

#: What cffi needs to call the host form of the device source (the tests run it on the CPU).
HOST_CDEF = """
void rk_sweep_host(long n, const double *y0, const double *p, double t0, double t1, double rtol, double atol,
                   double max_step, long max_steps, int ne, const int *ev_out, const int *ev_dir, const int *ev_term,
                   double *ev_t, double *ev_y, double *t_end, double *y_end, int *status, long *nfev);
"""

#: The host entry points of the C file, left out of the device source.
_HOST = ("int rk_rhs(", "int rk_out(", "int rk_rhs_batch(", "int rk_out_batch(", "void rk_sweep(")


def device_source(c_text: str) -> str:
    """The device form of a sweep's C file (``c_source(kernel) + INTEGRATOR_C``): see the module's docstring.

    Only qualifiers change; every line of the model and of the integrator is kept as it is.  Raises
    ValueError when the text is not such a file (no ``rk_run``, or a line this function does not know)."""
    if "static int rk_run(" not in c_text or "static int rk_eval_rhs(" not in c_text:
        raise ValueError("not a sweep's C file: it has no rk_run or rk_eval_rhs")
    out, skipping = [_SHIM], False
    for line in c_text.splitlines():
        if skipping:
            skipping = line != "}"
            continue
        if line.startswith(_HOST):
            skipping = not line.rstrip().endswith("}")
            continue
        if line.startswith("#include"):
            continue
        if line.startswith("static const double "):
            line = "RK_CONST double " + line[len("static const double "):]
        elif line.startswith("static ") and "(" in line:
            line = "RK_DEV " + line[len("static "):]
        elif line.startswith("static"):
            raise ValueError(f"a static line this function does not know: {line[:60]}")
        out.append(line)
    out.append(_KERNEL)
    return "\n".join(out)
