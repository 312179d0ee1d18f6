"""Contact complementarity problems, solved exactly by enumeration in a fixed order.

Every contact that touches its surface is decided together with the others, never one at a time.
Each contact takes one of a few *states*; a choice of state for every contact is a candidate, and
a candidate is a solution when the linear equations it implies give numbers that satisfy its
inequalities.  The candidates are tried in a fixed order (contacts in declaration order; per contact
``stick`` before ``slide +`` before ``slide −`` before ``inactive``), so the same input gives the same
answer, bit for bit.  With few contacts (the problems of a dynamics course have one to four) the
enumeration is small (at most 4ᵏ linear solves) and needs no pivoting rules; where no candidate or
more than one is a solution the caller is told so (Painlevé's paradox).

Degenerate contact sets (a rod flat on two supports: its two no-slip rows are the same row) make a
candidate's equations singular.  They are solved by the singular value decomposition: the velocities
after are determined, the impulses only up to the null space (how the friction splits between the
supports).  The smallest impulses that fit are taken when they satisfy the inequalities, else a
point of the solution set that does (a linear program, scipy's HiGHS); the impulses that move in the
null space are named *indeterminate*.  A candidate is rejected only when no point of its solution set
satisfies its inequalities, so a degenerate set never gives a spurious paradox.

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
import math
from dataclasses import dataclass, field, replace

import numpy as np

STICK, SLIDE_POS, SLIDE_NEG, INACTIVE = "stick", "slide+", "slide-", "inactive"


@dataclass(frozen=True)
class ContactRows:
    """One contact in an impulse problem: its normal row, its tangential row (rough contacts) and its law.

    ``Cn``, ``Ct``, ``Cextra``: the columns its unit impulses give in the momentum equations (None: the
    rows' transposes, as in the reduced form M Δu = Σ Jᵀ Λ).  ``held``: a contact the coordinates keep
    closed (it cannot open, so it is always active; its normal row may vanish identically)."""

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
    Cn: np.ndarray | None = None
    Ct: np.ndarray | None = None
    Cextra: tuple = ()
    held: bool = False
    labels: tuple = ()                 # names of its impulses: normal, tangential, further


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
    indeterminate: tuple = ()       # impulses the impact does not determine (their split is a choice)
    bilateral: dict = field(default_factory=dict)   # impulses of the other constraints (unreduced form)
    further: dict = field(default_factory=dict)     # 3D: the second tangential impulse per contact


class NoImpulseSolution(Exception):
    """No choice of contact states satisfies the impulse problem."""


def _options(c: ContactRows) -> tuple[str, ...]:
    if c.Jt is None or c.rolling:
        opts = (STICK, INACTIVE)             # smooth: "stick" stands for active (no tangential row)
    elif _cone(c):
        opts = (STICK, SLIDE_POS, INACTIVE)  # 3D: sliding against the direction of the slip after
    else:
        opts = (STICK, SLIDE_POS, SLIDE_NEG, INACTIVE)
    return tuple(o for o in opts if o != INACTIVE) if c.held else opts


def _cone(c: ContactRows) -> bool:
    """A rough contact in 3D: two tangential rows, Coulomb's cone |Λ_t| ≤ µ Λ_n."""
    return c.Jt is not None and not c.rolling and len(c.extra) > 0


def _label(c: ContactRows, i: int) -> str:
    if i < len(c.labels) and c.labels[i]:
        return str(c.labels[i])
    return f"{c.name}:{('normal', 'tangential')[i] if i < 2 else f'tangential {i}'}"


def _least_norm(A: np.ndarray, b: np.ndarray, rtol: float = 1e-10):
    """The smallest solution of A x = b and a basis of A's null space (SVD; singular values below
    ``rtol`` times the largest count as zero: redundant rows such as two supports' no-slip rows are
    recognised as such, never solved to 10¹⁵).  None when the equations are inconsistent."""
    if A.size == 0:
        return np.zeros(A.shape[1]), np.zeros((A.shape[1], 0))
    U, s, Vt = np.linalg.svd(A)
    r = int(np.sum(s > rtol * s[0])) if s.size and s[0] > 0 else 0
    x = Vt[:r].T @ ((U[:, :r].T @ b) / s[:r])
    if np.max(np.abs(A @ x - b)) > 1e-9 * max(1.0, float(np.max(np.abs(b)))):
        return None
    return x, Vt[r:].T


def _candidate(E, u0, R, contacts, states, dirs=None):
    """The linear equations of one candidate: unknowns u⁺, the other constraints' impulses and the
    impulses of the active contacts; with the impulses' labels and the inequalities G x ≥ h they must meet."""
    n, k, mr = len(u0), E.shape[0], R.shape[1]
    cols, labels, eqs, ineq = [], [], [], []
    for c, st in zip(contacts, states):
        if st == INACTIVE:
            continue
        vn0 = float(c.Jn @ u0 + c.bn)
        target = -c.restitution * min(vn0, 0.0)
        Cn = c.Jn if c.Cn is None else c.Cn
        Ct = c.Jt if c.Ct is None else c.Ct
        j0 = len(cols)
        eqs.append((c.Jn, target - c.bn))
        if c.Jt is None:
            cols.append(Cn)
            labels.append(_label(c, 0))
            ineq.append(({j0: 1.0}, 0.0))                            # Λ_n ≥ 0
        elif st == STICK:
            extra_cols = c.Cextra if c.Cextra else tuple(J for J, _ in c.extra)
            cols.extend([Cn, Ct, *extra_cols])
            labels.extend(_label(c, i) for i in range(2 + len(c.extra)))
            eqs.append((c.Jt, -c.bt))
            eqs.extend((J, -b_) for J, b_ in c.extra)
            ineq.append(({j0: 1.0}, 0.0))
            if not c.rolling and not _cone(c):                        # |Λ_t| ≤ µs Λ_n (3D: checked after)
                ineq.append(({j0: c.mu_s, j0 + 1: -1.0}, 0.0))
                ineq.append(({j0: c.mu_s, j0 + 1: 1.0}, 0.0))
        else:
            if _cone(c):                       # Λ_t = −µk Λ_n d, d the slip direction after (iterated)
                d1, d2 = dirs[c.name]
                Ce = c.Cextra[0] if c.Cextra else c.extra[0][0]
                cols.append(Cn - c.mu_k * (d1 * Ct + d2 * Ce))
                labels.append(_label(c, 0))
                ineq.append(({j0: 1.0}, 0.0))
                continue
            sigma = 1.0 if st == SLIDE_POS else -1.0
            cols.append(Cn - sigma * c.mu_k * Ct)                     # Λ_t = −σ µk Λ_n: one unknown
            labels.append(_label(c, 0))
            ineq.append(({j0: 1.0}, 0.0))
    A = np.zeros((k + len(eqs), n + mr + len(cols)))
    b = np.zeros(k + len(eqs))
    A[:k, :n] = E
    b[:k] = E @ u0
    A[:k, n:n + mr] = -R
    for j, d in enumerate(cols):
        A[:k, n + mr + j] = -d
    for i, (row, val) in enumerate(eqs):
        A[k + i, :n] = row
        b[k + i] = val
    G = np.zeros((len(ineq), A.shape[1]))
    for i, (coef, _) in enumerate(ineq):
        for j, v in coef.items():
            G[i, n + mr + j] = v
    return A, b, G, np.array([h for _, h in ineq]), labels


def _within(G, h, x, N, tol):
    """x, or x + N w chosen among the solutions of the equations so that G x ≥ h: the one farthest from
    its limits (max t with G x − h ≥ t, a linear program, scipy's HiGHS); None when no solution of the
    equations meets the inequalities."""
    if G.shape[0] == 0 or np.all(G @ x - h >= -tol):
        return x
    if N.shape[1] == 0:
        return None
    from scipy.optimize import linprog

    k = N.shape[1]
    scale = max(1.0, float(np.max(np.abs(x))))
    GN = G @ N
    A_ub = np.hstack([-GN, np.ones((G.shape[0], 1))])        # t − G N w ≤ G x − h
    res = linprog(np.r_[np.zeros(k), -1.0], A_ub=A_ub, b_ub=G @ x - h, bounds=[(None, None)] * k + [(None, scale)],
                  method="highs")
    if res.status != 0 or res.x[-1] < -max(tol, 1e-9 * scale):
        return None
    return x + N @ res.x[:k]


def _within_cones(contacts, states, offset, x, x0, N, G, h, tol):
    """Where a 3D contact sticks and the impulses are indeterminate (four corners), a split inside every
    friction cone when the one found is not: the cones replaced by inscribed octagons (linear, so the
    linear program finds such a split if the octagons admit one).  Otherwise ``x`` unchanged."""
    if N.shape[1] == 0:
        return x
    rows, j, bad = [], offset, False
    for c, st in zip(contacts, states):
        if st == INACTIVE:
            continue
        if st == STICK and _cone(c):
            bad |= math.hypot(x[j + 1], x[j + 2]) > c.mu_s * x[j] + tol
            for k in range(8):
                r = np.zeros(len(x))
                r[j], r[j + 1], r[j + 2] = c.mu_s * math.cos(math.pi / 8), -math.cos(k * math.pi / 4), \
                    -math.sin(k * math.pi / 4)
                rows.append(r)
        j += (2 + len(c.extra)) if st == STICK and c.Jt is not None else 1
    if not bad:
        return x
    x1 = _within(np.vstack([G, *rows]), np.concatenate([h, np.zeros(len(rows))]), x0, N, tol)
    return x if x1 is None else x1


def _solve_with_directions(E, u0, R, contacts, states, iterations: int = 60):
    """Solve one candidate; a 3D contact that slides does so against the direction of its slip after the
    impact, found by iterating from the slip before (for a sphere it does not turn: one step)."""
    n = len(u0)
    dirs = {}
    for c, st in zip(contacts, states):
        if st == SLIDE_POS and _cone(c):
            s = np.array([c.Jt @ u0 + c.bt, c.extra[0][0] @ u0 + c.extra[0][1]], dtype=float)
            if not np.linalg.norm(s) > 0:
                return None
            dirs[c.name] = tuple(s / np.linalg.norm(s))
    for _ in range(iterations if dirs else 1):
        A, b, G, h, labels = _candidate(E, u0, R, contacts, states, dirs)
        solved = _least_norm(A, b)
        if solved is None:
            return None
        x, N = solved
        if not dirs:
            return x, N, G, h, labels, dirs
        u, moved = x[:n], 0.0
        for c in contacts:
            if c.name in dirs:
                # the slip after with its change along d taken back: parallel to d at the solution, and
                # (unlike the slip after itself) a stable iteration; for a sphere it is the slip before
                d0 = np.array(dirs[c.name])
                s0 = np.array([c.Jt @ u0 + c.bt, c.extra[0][0] @ u0 + c.extra[0][1]], dtype=float)
                s = np.array([c.Jt @ u + c.bt, c.extra[0][0] @ u + c.extra[0][1]], dtype=float)
                s = s + float(d0 @ (s0 - s)) * d0
                if not np.linalg.norm(s) > 0:
                    return None
                d = s / np.linalg.norm(s)
                moved = max(moved, float(np.max(np.abs(d - d0))))
                dirs[c.name] = tuple(d)
        if moved <= 1e-13:
            break
    A, b, G, h, labels = _candidate(E, u0, R, contacts, states, dirs)
    solved = _least_norm(A, b)
    return None if solved is None else (*solved, G, h, labels, dirs)


def impulse_problem(M: np.ndarray, u0: np.ndarray, contacts: list[ContactRows], tol: float = 1e-10,
                    plastic: bool = False, momentum: np.ndarray | None = None,
                    bilateral: tuple | None = None) -> ImpulseSolution:
    """Solve the impact of every contact in ``contacts`` at once (see the module docstring).

    ``momentum`` (E) and ``bilateral`` ((R, labels)): the unreduced impulse–momentum equations
    E (u⁺ − u⁻) = R r + Σ C Λ of every body, with r the impulses of the other constraints; without
    them the reduced form M (u⁺ − u⁻) = Σ Jᵀ Λ."""
    if plastic:
        contacts = [replace(c, restitution=0.0) for c in contacts]
    E = M if momentum is None else momentum
    R, rlabels = bilateral if bilateral is not None else (np.zeros((E.shape[0], 0)), ())
    n, mr = len(u0), R.shape[1]
    speed = max(1.0, float(np.max(np.abs(u0))) if len(u0) else 1.0)
    first, count = None, 0
    for states in itertools.product(*[_options(c) for c in contacts]):
        solved = _solve_with_directions(E, u0, R, contacts, states)
        if solved is None:
            continue
        x, N, G, h, labels, dirs = solved
        if N.shape[1] and np.max(np.abs(N[:n])) > 1e-9:
            continue                         # the velocities after are not determined by this candidate
        imp = max(1e-300, float(np.max(np.abs(x[n:]))) if len(x) > n else 0.0)
        x0 = x
        x = _within(G, h, x, N, tol * max(imp, speed))
        if x is None:
            continue
        x = _within_cones(contacts, states, n + mr, x, x0, N, G, h, tol * max(imp, speed))
        u, lam = x[:n], x[n + mr:]
        ok, j = True, 0
        normal, tangential, vn_after, vt_after, further = {}, {}, {}, {}, {}
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
            if c.Jt is None:
                normal[c.name], tangential[c.name] = ln, 0.0
                j += 1
            elif st == STICK:
                normal[c.name], tangential[c.name] = ln, float(lam[j + 1])
                further[c.name] = tuple(float(v) for v in lam[j + 2:j + 2 + len(c.extra)])
                if _cone(c):                             # Coulomb's cone: |Λ_t| ≤ µs Λ_n
                    ok &= math.hypot(tangential[c.name], *further[c.name]) <= c.mu_s * ln + tol * imp
                j += 2 + len(c.extra)
            elif _cone(c):
                d1, d2 = dirs[c.name]
                normal[c.name], tangential[c.name] = ln, -c.mu_k * ln * d1
                further[c.name] = (-c.mu_k * ln * d2,)
                ve = float(c.extra[0][0] @ u + c.extra[0][1])
                ok &= d1 * vt + d2 * ve > tol * speed and abs(d2 * vt - d1 * ve) <= 1e-9 * speed
                j += 1
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
                nz = np.max(np.abs(N), axis=1) > 1e-9 if N.shape[1] else np.zeros(len(x), dtype=bool)
                names = list(rlabels) + labels
                indet = tuple(names[i] for i in range(len(names)) if nz[n + i])
                first = ImpulseSolution(u, normal, tangential, dict(zip([c.name for c in contacts], states)),
                                        vn_after, vt_after, dT, 0, indet,
                                        {str(lb): float(v) for lb, v in zip(rlabels, x[n:n + mr])}, further)
    if first is None:
        raise NoImpulseSolution(", ".join(c.name for c in contacts))
    return replace(first, count=count)
