"""Contact complementarity problems, solved exactly by enumeration in a fixed order.

Every contact that touches its surface is decided together with the others, never one at a time.
Each contact takes one of a few *states*; a choice of state for every contact is a candidate, and
a candidate is a solution when the linear equations it implies give numbers that satisfy its
inequalities.  The candidates are tried in a fixed order (contacts in declaration order; per contact
``stick`` before ``slide +`` before ``slide −`` before ``inactive``), so the same input gives the same
answer, bit for bit.  With few contacts (the problems of a dynamics course have one to four) the
enumeration is small (at most 4ᵏ linear solves) and needs no pivoting rules; where no candidate or
more than one is a solution the caller is told so (Painlevé's paradox).

Impulse problem (:func:`impulse_problem`), at an impact, over every contact that is closed or closing.
With M the mass matrix in the rates u of the mode in which those contacts are open, and for contact i
the normal row v_n = J_n u + b_n and (rough contacts) the tangential row v_t = J_t u + b_t:

    M (u⁺ − u⁻) = Σ J_nᵀ Λ_n + J_tᵀ Λ_t

* normal, Newton's law of restitution on the normal velocity of each contact:
  Λ_n ≥ 0,  v_n⁺ + e v_n⁻ ≥ 0,  Λ_n (v_n⁺ + e v_n⁻) = 0   (a closed contact has v_n⁻ = 0);
* tangential, Coulomb's law for impulses: either the contact sticks through the impact (v_t⁺ = 0 and
  |Λ_t| ≤ µs Λ_n), or it slides with Λ_t = −σ µk Λ_n against the slip σ = sign(v_t⁺) it leaves with.

Newton's law with friction can, for some multi-contact impacts, return more kinetic energy than it
had; that is checked in code (:func:`impulse_problem` reports T⁺ − T⁻ and the caller falls back to a
plastic impact, e = 0, which with Coulomb friction never creates energy).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

STICK, SLIDE_POS, SLIDE_NEG, INACTIVE = "stick", "slide+", "slide-", "inactive"


@dataclass(frozen=True)
class ContactRows:
    """One contact in an impulse problem: its normal row, its tangential row (rough contacts) and its law."""

    name: str
    Jn: np.ndarray
    bn: float
    Jt: np.ndarray | None = None      # None: smooth (no tangential impulse)
    bt: float = 0.0
    mu_s: float = 0.0
    mu_k: float = 0.0
    rolling: bool = False              # no slip ever (infinite friction)
    restitution: float = 0.0
    extra: tuple = ()                  # further no-slip rows (J, b) of a rolling contact in 3D


@dataclass(frozen=True)
class ImpulseSolution:
    """u⁺, the impulses (Λ_n, Λ_t) per contact, the state each contact took, and every solution found."""

    u: np.ndarray
    normal: dict
    tangential: dict
    states: dict
    normal_after: dict              # v_n⁺ per contact
    slip_after: dict                # v_t⁺ per rough contact
    energy_change: float            # ½u⁺ᵀMu⁺ − ½u⁻ᵀMu⁻ (the rates' part of T)
    count: int                      # how many candidates were solutions (1: unique)


class NoImpulseSolution(Exception):
    """No choice of contact states satisfies the impulse problem."""


def _options(c: ContactRows) -> tuple[str, ...]:
    if c.Jt is None:
        return (STICK, INACTIVE)             # smooth: "stick" stands for active (no tangential row)
    if c.rolling:
        return (STICK, INACTIVE)
    return (STICK, SLIDE_POS, SLIDE_NEG, INACTIVE)


def _solve_candidate(M, u0, contacts, states):
    """The linear equations of one candidate: unknowns u⁺ and the impulses of the active contacts."""
    n = len(u0)
    cols, eqs = [], []                   # impulse directions, and the extra rows
    for c, st in zip(contacts, states):
        if st == INACTIVE:
            continue
        vn0 = float(c.Jn @ u0 + c.bn)
        target = -c.restitution * min(vn0, 0.0)
        if c.Jt is None:
            cols.append(c.Jn)
            eqs.append((c.Jn, target - c.bn))
        elif st == STICK:
            cols.extend([c.Jn, c.Jt, *(J for J, _ in c.extra)])
            eqs.append((c.Jn, target - c.bn))
            eqs.append((c.Jt, -c.bt))
            eqs.extend((J, -b_) for J, b_ in c.extra)
        else:
            sigma = 1.0 if st == SLIDE_POS else -1.0
            cols.append(c.Jn - sigma * c.mu_k * c.Jt)       # Λ_t = −σ µk Λ_n: one unknown
            eqs.append((c.Jn, target - c.bn))
    k = len(cols)
    A = np.zeros((n + k, n + k))
    b = np.zeros(n + k)
    A[:n, :n] = M
    b[:n] = M @ u0
    for j, d in enumerate(cols):
        A[:n, n + j] = -d
    for i, (row, val) in enumerate(eqs):
        A[n + i, :n] = row
        b[n + i] = val
    try:
        x = np.linalg.solve(A, b)
        if not np.all(np.isfinite(x)):
            raise np.linalg.LinAlgError
    except np.linalg.LinAlgError:
        # impulses that the velocities do not determine (a rod flat on two rough supports: how the
        # friction impulse splits between them): the smallest that fit, when the equations are consistent
        x = np.linalg.lstsq(A, b, rcond=None)[0]
        if np.max(np.abs(A @ x - b)) > 1e-9 * max(1.0, float(np.max(np.abs(b)))):
            raise
    return x[:n], x[n:]


def impulse_problem(M: np.ndarray, u0: np.ndarray, contacts: list[ContactRows], tol: float = 1e-10,
                    plastic: bool = False) -> ImpulseSolution:
    """Solve the impact of every contact in ``contacts`` at once (see the module docstring)."""
    if plastic:
        contacts = [ContactRows(c.name, c.Jn, c.bn, c.Jt, c.bt, c.mu_s, c.mu_k, c.rolling, 0.0, c.extra)
                    for c in contacts]
    speed = max(1.0, float(np.max(np.abs(u0))) if len(u0) else 1.0)
    first, count = None, 0
    for states in itertools.product(*[_options(c) for c in contacts]):
        try:
            u, lam = _solve_candidate(M, u0, contacts, states)
        except np.linalg.LinAlgError:
            continue
        ok, j = True, 0
        normal, tangential, vn_after, vt_after = {}, {}, {}, {}
        imp = max(1e-300, float(np.max(np.abs(lam))) if len(lam) else 0.0)
        for c, st in zip(contacts, states):
            vn0 = float(c.Jn @ u0 + c.bn)
            vn = float(c.Jn @ u + c.bn)
            vt = float(c.Jt @ u + c.bt) if c.Jt is not None else None
            vn_after[c.name] = vn
            if vt is not None:
                vt_after[c.name] = vt
            if st == INACTIVE:
                normal[c.name], tangential[c.name] = 0.0, 0.0
                ok &= vn + c.restitution * min(vn0, 0.0) >= -tol * speed
                continue
            ln = float(lam[j])
            ok &= ln >= -tol * imp
            if c.Jt is None:
                normal[c.name], tangential[c.name] = ln, 0.0
                j += 1
            elif st == STICK:
                lt = float(lam[j + 1])
                normal[c.name], tangential[c.name] = ln, lt
                ok &= c.rolling or abs(lt) <= c.mu_s * ln + tol * imp
                j += 2 + len(c.extra)
            else:
                sigma = 1.0 if st == SLIDE_POS else -1.0
                normal[c.name], tangential[c.name] = ln, -sigma * c.mu_k * ln
                ok &= sigma * vt > tol * speed           # it does slide (zero slip is sticking)
                j += 1
            if not ok:
                break
        if ok:
            count += 1
            if first is None:
                dT = 0.5 * float(u @ M @ u) - 0.5 * float(u0 @ M @ u0)
                first = ImpulseSolution(u, normal, tangential, dict(zip([c.name for c in contacts], states)),
                                        vn_after, vt_after, dT, 0)
    if first is None:
        raise NoImpulseSolution(", ".join(c.name for c in contacts))
    return ImpulseSolution(first.u, first.normal, first.tangential, first.states, first.normal_after,
                           first.slip_after, first.energy_change, count)
