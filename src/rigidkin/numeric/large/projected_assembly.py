"""Numeric assembly of the projected equations (``rigidkin.numeric.large.projected``): the dependent speeds,
the partial rates T = [I; −A_d⁻¹ A_i] and Kane's equations (Tᵀ Mf T) u̇_i = Tᵀ (ff − Mf u̇p), in
double precision (numpy) or any precision (mpmath)."""

from __future__ import annotations

import mpmath
import numpy as np
import sympy as sp

from ...base import vectorops


# numeric assembly ----------------------------------------------------------------------------------
def _vec(v, frame) -> sp.Matrix:
    """The components of ``v`` along the basis of ``frame`` (a sympy ReferenceFrame), as a column."""
    return sp.Matrix(vectorops.in_frame(v, frame))


def _solve(kind, A, b):
    if kind == "mpmath":
        return mpmath.lu_solve(A, b)
    return np.linalg.solve(A, b)


def _cols(kind, A, idx):
    if kind == "mpmath":
        return mpmath.matrix([[A[r, c] for c in idx] for r in range(A.rows)])
    return A[:, list(idx)]


def _full_rates(kind, A, b, ui, ind, dep, n):
    u = [0] * n if kind == "mpmath" else np.zeros(n)
    for k, i in enumerate(ind):
        u[i] = ui[k]
    if dep:
        Ai, Ad = _cols(kind, A, ind), _cols(kind, A, dep)
        if kind == "mpmath":
            rhs = -(Ai * mpmath.matrix(list(ui)) + b)
        else:
            rhs = -(Ai @ np.asarray(ui, dtype=float) + np.ravel(b))
        ud = _solve(kind, Ad, rhs)
        for k, i in enumerate(dep):
            u[i] = ud[k]
    return u


def _partials(kind, A, ind, dep, n):
    """T (n × k): the rates of all coordinates per unit independent rate."""
    k = len(ind)
    if kind == "mpmath":
        T = mpmath.matrix(n, k)
        for c, i in enumerate(ind):
            T[i, c] = 1
        if dep:
            X = mpmath.inverse(_cols(kind, A, dep)) * (-_cols(kind, A, ind))
            for r, i in enumerate(dep):
                for c in range(k):
                    T[i, c] = X[r, c]
        return T
    T = np.zeros((n, k))
    T[list(ind), range(k)] = 1.0
    if dep:
        T[list(dep), :] = np.linalg.solve(A[:, list(dep)], -A[:, list(ind)])
    return T


def _project(kind, out, bodies, n, ind, dep):
    """(u̇_i, projected mass matrix) from the evaluated pieces."""
    Q, A, _b, c0 = out[-6], out[-5], out[-4], out[-3]
    if kind == "mpmath":
        Mf = mpmath.matrix(n, n)
        ff = mpmath.matrix(Q) if Q is not None else mpmath.matrix(n, 1)
        for _, s in bodies:
            m, Jv, a0, Jw, JH, h0 = out[s:s + 6]
            m = m[0, 0]
            Mf += m * (Jv.T * Jv) + Jw.T * JH
            ff -= m * (Jv.T * a0) + Jw.T * h0
    else:
        Mf = np.zeros((n, n))
        ff = np.ravel(Q).astype(float).copy()
        for _, s in bodies:
            m, Jv, a0, Jw, JH, h0 = out[s:s + 6]
            m = float(np.ravel(m)[0])
            Mf += m * (Jv.T @ Jv) + Jw.T @ JH
            ff -= m * (Jv.T @ np.ravel(a0)) + Jw.T @ np.ravel(h0)
    if not dep and kind != "mpmath":
        return np.linalg.solve(Mf, ff), Mf
    T = _partials(kind, A, ind, dep, n)
    if dep:
        # particular accelerations: independent part zero, dependent part from A q̈ + c0 = 0
        if kind == "mpmath":
            xd = mpmath.lu_solve(_cols(kind, A, dep), -c0)
            qp = mpmath.matrix(n, 1)
            for r, i in enumerate(dep):
                qp[i] = xd[r]
        else:
            xd = np.linalg.solve(A[:, list(dep)], -np.ravel(c0))
            qp = np.zeros(n)
            qp[list(dep)] = xd
    else:
        qp = mpmath.matrix(n, 1) if kind == "mpmath" else np.zeros(n)
    if kind == "mpmath":
        Mr = T.T * Mf * T
        fr = T.T * (ff - Mf * qp)
        return mpmath.lu_solve(Mr, fr), Mr
    Mr = T.T @ Mf @ T
    fr = T.T @ (ff - Mf @ qp)
    return np.linalg.solve(Mr, fr), Mr
