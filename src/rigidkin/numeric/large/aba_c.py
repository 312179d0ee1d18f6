"""The articulated-body algorithm of ``numeric.articulated`` in C, for trees whose only load is gravity.

One fixed C source (not generated per model: the tree comes in as arrays) is compiled once through
``numeric.cache.build`` (cached, checked) and loaded with cffi.  It does, per call, what
``ArticulatedModel.dynamics`` does in numpy — orientations of the elementary frames, pin and mass-centre
positions, spatial velocities, the inward and outward passes — and then q̈ from ψ̈ = C q̈ by the
substitution plan (each joint brings one new coordinate); without a plan the LU solve stays in Python.
Without a compiler or cffi, ``compiled(...)`` returns None and the numpy version is used.
"""

from __future__ import annotations

import numpy as np

from ..compiled.cache import build, compiler

CDEF = """
typedef struct {
  int E, nb, nn, n, ne, nnz, plan;
  const int *eparent, *erow, *ecol, *jparent, *fb, *pnode, *nbody, *before, *ncolr, *nrowr, *attach;
  const int *pk, *pi, *pptr, *pidx;
  const double *K, *K2, *evals, *econst, *to_pin, *to_centre, *mass, *Ib, *naxis, *nval, *g, *pdiag, *pval;
  double *work;
} rk_tree;
int rk_aba(const rk_tree *T, const double *q, const double *u, double *qdd, double *jf, double *TU);
"""

SOURCE = r"""
#include <math.h>
#include <string.h>
typedef struct {
  int E, nb, nn, n, ne, nnz, plan;
  const int *eparent, *erow, *ecol, *jparent, *fb, *pnode, *nbody, *before, *ncolr, *nrowr, *attach;
  const int *pk, *pi, *pptr, *pidx;
  const double *K, *K2, *evals, *econst, *to_pin, *to_centre, *mass, *Ib, *naxis, *nval, *g, *pdiag, *pval;
  double *work;
} rk_tree;

static void mm3(const double *a, const double *b, double *c) {
  for (int i = 0; i < 3; i++) for (int j = 0; j < 3; j++)
    c[3*i+j] = a[3*i]*b[j] + a[3*i+1]*b[3+j] + a[3*i+2]*b[6+j];
}
static void mv3(const double *a, const double *v, double *o) {
  for (int i = 0; i < 3; i++) o[i] = a[3*i]*v[0] + a[3*i+1]*v[1] + a[3*i+2]*v[2];
}
static void cr3(const double *a, const double *b, double *o) {
  o[0] = a[1]*b[2] - a[2]*b[1]; o[1] = a[2]*b[0] - a[0]*b[2]; o[2] = a[0]*b[1] - a[1]*b[0];
}
static void crm(const double *v, const double *m, double *o) {     /* v x_m m */
  double t[3]; cr3(v, m, o); cr3(v, m+3, o+3); cr3(v+3, m, t);
  o[3] += t[0]; o[4] += t[1]; o[5] += t[2];
}
static void crf(const double *v, const double *f, double *o) {     /* v x* f */
  double t[3]; cr3(v, f, o); cr3(v+3, f+3, t); cr3(v, f+3, o+3);
  o[0] += t[0]; o[1] += t[1]; o[2] += t[2];
}

int rk_aba(const rk_tree *T, const double *q, const double *u, double *qdd, double *jf, double *TU) {
  const int E = T->E, nb = T->nb, nn = T->nn, n = T->n;
  double *W = T->work, *alpha = W + 9*(E+1), *rG = alpha + E, *rJ = rG + 3*nb, *S = rJ + 3*nb;
  double *V = S + 6*nn, *C = V + 6*nn, *IA = C + 6*nn, *pA = IA + 36*nn, *U = pA + 6*nn, *D = U + 6*nn;
  double *uu = D + nn, *A = uu + nn, *pd = A + 6*nn, *pdd = pd + nn;
  for (int e = 0; e < E; e++) alpha[e] = T->econst[e];
  for (int r = 0; r < T->ne; r++) alpha[T->erow[r]] += T->evals[r] * q[T->ecol[r]];
  double *WF = W + 9*E;
  memset(WF, 0, 9*sizeof(double)); WF[0] = WF[4] = WF[8] = 1.0;
  for (int e = 0; e < E; e++) {
    double s = sin(alpha[e]), c1 = 1.0 - cos(alpha[e]), R[9];
    for (int i = 0; i < 9; i++) R[i] = (i % 4 == 0 ? 1.0 : 0.0) + s*T->K[9*e+i] + c1*T->K2[9*e+i];
    int par = T->eparent[e] < 0 ? E : T->eparent[e];
    mm3(W + 9*par, R, W + 9*e);
  }
  memset(pd, 0, nn*sizeof(double));
  for (int r = 0; r < T->nnz; r++) pd[T->nrowr[r]] += T->nval[r] * u[T->ncolr[r]];
  for (int j = 0; j < nb; j++) {
    int par = T->jparent[j];
    double t[3];
    if (par < 0) { for (int i = 0; i < 3; i++) rJ[3*j+i] = T->to_pin[3*j+i]; }
    else { mv3(W + 9*T->fb[par], T->to_pin + 3*j, t); for (int i = 0; i < 3; i++) rJ[3*j+i] = rG[3*par+i] + t[i]; }
    mv3(W + 9*T->fb[j], T->to_centre + 3*j, t);
    for (int i = 0; i < 3; i++) rG[3*j+i] = rJ[3*j+i] + t[i];
  }
  for (int k = 0; k < nn; k++) {
    int bf = T->before[k] < 0 ? E : T->before[k], par = T->pnode[k];
    double *Sk = S + 6*k, vj[6];
    mv3(W + 9*bf, T->naxis + 3*k, Sk);
    cr3(rJ + 3*T->nbody[k], Sk, Sk + 3);
    for (int i = 0; i < 6; i++) { vj[i] = Sk[i]*pd[k]; V[6*k+i] = (par >= 0 ? V[6*par+i] : 0.0) + vj[i]; }
    crm(V + 6*k, vj, C + 6*k);
  }
  memset(IA, 0, 36*nn*sizeof(double)); memset(pA, 0, 6*nn*sizeof(double));
  double Tk = 0.0, Ug = 0.0;
  for (int b = 0; b < nb; b++) {
    int a = T->attach[b];
    if (a < 0) continue;
    const double *Wb = W + 9*T->fb[b], *r = rG + 3*b;
    double m = T->mass[b], tmp[9], Wt[9], Iw[9], X[9] = {0, -r[2], r[1], r[2], 0, -r[0], -r[1], r[0], 0};
    for (int i = 0; i < 3; i++) for (int j = 0; j < 3; j++) Wt[3*i+j] = Wb[3*j+i];
    mm3(Wb, T->Ib + 9*b, tmp); mm3(tmp, Wt, Iw);
    double I6[36], *v = V + 6*a, h[6], p[6];
    for (int i = 0; i < 3; i++) for (int j = 0; j < 3; j++) {
      double xx = 0; for (int k = 0; k < 3; k++) xx += X[3*i+k]*X[3*j+k];
      I6[6*i+j] = Iw[3*i+j] + m*xx; I6[6*i+3+j] = m*X[3*i+j]; I6[6*(3+i)+j] = m*X[3*j+i];
      I6[6*(3+i)+3+j] = (i == j) ? m : 0.0;
    }
    for (int i = 0; i < 6; i++) { h[i] = 0; for (int j = 0; j < 6; j++) h[i] += I6[6*i+j]*v[j]; }
    crf(v, h, p);
    for (int i = 0; i < 6; i++) Tk += 0.5*v[i]*h[i];
    Ug -= m*(T->g[0]*r[0] + T->g[1]*r[1] + T->g[2]*r[2]);
    for (int i = 0; i < 36; i++) IA[36*a+i] += I6[i];
    for (int i = 0; i < 6; i++) pA[6*a+i] += p[i];
  }
  for (int k = nn - 1; k >= 0; k--) {
    double *Ik = IA + 36*k, *Sk = S + 6*k, *Uk = U + 6*k;
    double d = 0, w = 0;
    for (int i = 0; i < 6; i++) { Uk[i] = 0; for (int j = 0; j < 6; j++) Uk[i] += Ik[6*i+j]*Sk[j]; }
    for (int i = 0; i < 6; i++) { d += Sk[i]*Uk[i]; w -= Sk[i]*pA[6*k+i]; }
    D[k] = d; uu[k] = w;
    int par = T->pnode[k];
    if (par < 0) continue;
    double Ia[36], Iac[6];
    for (int i = 0; i < 6; i++) for (int j = 0; j < 6; j++) Ia[6*i+j] = Ik[6*i+j] - Uk[i]*Uk[j]/d;
    for (int i = 0; i < 6; i++) { Iac[i] = 0; for (int j = 0; j < 6; j++) Iac[i] += Ia[6*i+j]*C[6*k+j]; }
    for (int i = 0; i < 36; i++) IA[36*par+i] += Ia[i];
    for (int i = 0; i < 6; i++) pA[6*par+i] += pA[6*k+i] + Iac[i] + Uk[i]*w/d;
  }
  double base[6] = {0, 0, 0, -T->g[0], -T->g[1], -T->g[2]};
  for (int k = 0; k < nn; k++) {
    int par = T->pnode[k];
    double a[6], s = 0;
    for (int i = 0; i < 6; i++) { a[i] = (par >= 0 ? A[6*par+i] : base[i]) + C[6*k+i]; s += U[6*k+i]*a[i]; }
    pdd[k] = (uu[k] - s) / D[k];
    for (int i = 0; i < 6; i++) A[6*k+i] = a[i] + S[6*k+i]*pdd[k];
  }
  if (TU) { TU[0] = Tk; TU[1] = Ug; }
  if (jf) for (int k = 0; k < nn; k++) for (int i = 0; i < 6; i++) {   /* the force each joint transmits */
    double f = pA[6*k+i];
    for (int j = 0; j < 6; j++) f += IA[36*k+6*i+j]*A[6*k+j];
    jf[6*k+i] = f;
  }
  if (!T->plan) { for (int k = 0; k < n; k++) qdd[k] = pdd[k]; return 0; }
  for (int k = 0; k < n; k++) {
    double acc = pdd[T->pk[k]];
    for (int r = T->pptr[k]; r < T->pptr[k+1]; r++) acc -= T->pval[r]*qdd[T->pidx[r]];
    qdd[T->pi[k]] = acc / T->pdiag[k];
  }
  return 0;
}
"""

_LIB: list = []


def _library():
    if not _LIB:
        try:
            import cffi  # noqa: F401

            _LIB.append(build(SOURCE, CDEF) if compiler() is not None else None)
        except Exception:          # no compiler, no cffi, a cache that refuses: the numpy version is used
            _LIB.append(None)
    return _LIB[0]


class CompiledTree:
    """q̈(q, q̇) of one tree at one parameter set, in C."""

    def __init__(self, num: dict, n: int, ffi, lib):
        self.ffi, self.lib, self.n = ffi, lib, n
        keep = self._keep = []

        def ints(a):
            a = np.ascontiguousarray(np.asarray(a, dtype=np.int32).ravel() if len(a) else np.zeros(1, np.int32))
            keep.append(a)
            return ffi.cast("const int *", ffi.from_buffer("int[]", a))

        def dbl(a):
            a = np.ascontiguousarray(np.asarray(a, dtype=float).ravel() if np.size(a) else np.zeros(1))
            keep.append(a)
            return ffi.cast("const double *", ffi.from_buffer("double[]", a))

        E, nb, nn = len(num["parent"]), len(num["fb"]), len(num["pnode"])
        T = self.T = ffi.new("rk_tree *")
        T.E, T.nb, T.nn, T.n, T.ne, T.nnz = E, nb, nn, n, len(num["erow"]), len(num["nrow"])
        T.eparent, T.erow, T.ecol = ints(num["parent"]), ints(num["erow"]), ints(num["ecol"])
        T.jparent, T.fb, T.pnode = ints(num["jparent"]), ints(num["fb"]), ints(num["pnode"])
        T.nbody, T.before, T.attach = ints(num["nbody"]), ints(num["before"]), ints(num["attach"])
        T.nrowr, T.ncolr = ints(num["nrow"]), ints(num["ncol"])
        T.K, T.K2, T.evals, T.econst = dbl(num["K"]), dbl(num["K2"]), dbl(num["eval"]), dbl(num["econst"])
        T.to_pin, T.to_centre = dbl(num["to_pin"]), dbl(num["to_centre"])
        T.mass, T.Ib = dbl(num["mass"]), dbl(num["Ib"])
        T.naxis, T.nval, T.g = dbl(num["naxis"]), dbl(num["nval"]), dbl(num["g"])
        plan = num.get("plan")
        T.plan = 1 if plan else 0
        if plan:
            ptr = np.cumsum([0] + [len(rest) for *_, rest in plan])
            T.pk, T.pi = ints([k for k, *_ in plan]), ints([i for _, i, *_ in plan])
            T.pdiag = dbl([c for _, _, c, _ in plan])
            T.pptr = ints(ptr)
            T.pidx = ints([j for *_, rest in plan for j, _ in rest])
            T.pval = dbl([c for *_, rest in plan for _, c in rest])
        self._work = np.zeros(9 * (E + 1) + E + 6 * nb + 6 * nn * 4 + 36 * nn + 6 * nn + 4 * nn + 6 * nn + 16)
        T.work = ffi.cast("double *", ffi.from_buffer("double[]", self._work))
        self._lu = None if plan else num["solve"]

    def qdd(self, q, u) -> np.ndarray:
        return self._call(q, u, None, None)

    def sample(self, q, u) -> tuple[np.ndarray, np.ndarray, float, float]:
        """(q̈, the spatial force each joint degree of freedom transmits (nodes × 6), T, U)."""
        jf, TU = np.empty((self.T.nn, 6)), np.empty(2)
        qdd = self._call(q, u, jf, TU)
        return qdd, jf, float(TU[0]), float(TU[1])

    def _call(self, q, u, jf, TU) -> np.ndarray:
        ffi = self.ffi
        q = np.ascontiguousarray(q, dtype=float)
        u = np.ascontiguousarray(u, dtype=float)
        out = np.empty(self.n)
        self.lib.rk_aba(self.T, ffi.cast("const double *", ffi.from_buffer("double[]", q)),
                        ffi.cast("const double *", ffi.from_buffer("double[]", u)),
                        ffi.cast("double *", ffi.from_buffer("double[]", out)),
                        ffi.NULL if jf is None else ffi.cast("double *", ffi.from_buffer("double[]", jf)),
                        ffi.NULL if TU is None else ffi.cast("double *", ffi.from_buffer("double[]", TU)))
        return out if self._lu is None else self._lu(out)


def compiled(num: dict, n: int) -> CompiledTree | None:
    """The C version of the tree's forward dynamics, or None where C cannot be compiled here."""
    lib = _library()
    if lib is None:
        return None
    return CompiledTree(num, n, *lib)
