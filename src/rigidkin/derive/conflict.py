"""Which balance equation a contradiction is in: the body, the law and the contact truly in conflict.

When the balance equations A u = −b have no solution, every equation left out of a square set can look
guilty.  The one named is found by taking each equation out in turn: those without which the rest have a
solution are the candidates (each alone explains the contradiction).  Of them the one that says least
about motion is named first: the moment balance of a body that has no rotational inertia (a point mass
or a massless link: the loads on it must pass through its centre), then a balance with no inertia term
(statics along a direction nothing moves in; a moment balance before a force balance: a body that no
coordinate lets turn, and no constraint holds from turning), then the one with the fewest reactions.  The contacts
whose reactions enter it are named with it.
"""

from __future__ import annotations

import itertools

import numpy as np
import sympy as sp

from ..base.printing import text


def _consistent(nA: np.ndarray, nb: np.ndarray, tol: float) -> bool:
    if nA.shape[0] == 0:
        return True
    return np.linalg.matrix_rank(np.hstack([nA, nb]), tol=tol) == np.linalg.matrix_rank(nA, tol=tol)


def _no_rotational_inertia(setup, eq) -> bool:
    body = setup.system.bodies.get(getattr(eq, "body", None)) if setup is not None else None
    kind = getattr(getattr(body, "shape", None), "kind", "")
    return kind in ("point mass", "massless") and "2nd law" in eq.label


def _without_inertia(eq) -> bool:
    rhs = getattr(eq, "rhs", None)
    return rhs is not None and sp.sympify(rhs) == 0


def _why(setup, eq, nrow, unknowns, tol) -> tuple[str, str, list]:
    """(why the equation cannot hold, a hint, the contacts named) for one equation in conflict."""
    reactions = [unknowns[j] for j in range(len(unknowns)) if abs(nrow[j]) > tol
                 and not isinstance(unknowns[j], sp.Derivative)]
    owner = {}
    for row in getattr(setup, "rows", ()):
        owner.setdefault(row.reaction, row.constraint)
    contacts = sorted({owner[r] for r in reactions if r in owner})
    by = (f" the reactions {', '.join(text(r) for r in reactions)} of {', '.join(contacts)}" if contacts
          else " the loads in it")
    body = getattr(eq, "body", None)
    if _no_rotational_inertia(setup, eq):
        what = "a point mass" if setup.system.bodies[body].shape.kind == "point mass" else "massless"
        why = (f"{body} has no rotational inertia ({what}), so the moment "
               f"about its centre of every load on it must vanish, but{by} act on it off its centre with a moment "
               "the other balances do not let vanish")
        hint = (f"Let the loads on {body} pass through its centre (place the contact points on its centre's "
                f"line of action), give {body} a rotational inertia (a rigid shape) and an angle, or hold it "
                "from turning with a constraint that carries a couple.")
    else:
        where = f" on {body}" if body else ""
        why = (f"the other balances already fix{by}, and with those values the loads{where} in it do not balance"
               + ((" (it has no inertia term: no coordinate lets the body turn this way, and no constraint carries "
                   "a couple)" if "2nd law" in eq.label else " (it has no inertia term: no coordinate lets the body "
                   "move this way)") if _without_inertia(eq) else ""))
        hint = ("The coordinates hold back a motion that no constraint enforces: a constraint (with its reaction) "
                "is missing, or a load has no reaction to carry it; see the geometry and free-body diagrams "
                "with 'rigidkin draw FILE'.")
    return why, hint, contacts


def explain(setup, equations, nA: np.ndarray, nb: np.ndarray, unknowns) -> tuple[str, str, str] | None:
    """(message, hint, where) naming the equations in conflict (one, else two), or None when no one or two
    equations explain it."""
    scale = max(1.0, float(np.abs(nA).max()) if nA.size else 1.0, float(np.abs(nb).max()) if nb.size else 1.0)
    tol = 1e-9 * scale
    m = nA.shape[0]
    if m > 24:
        return None
    for k in (1, 2):
        sets = [c for c in itertools.combinations(range(m), k)
                if _consistent(np.delete(nA, c, axis=0), np.delete(nb, c, axis=0), tol)]
        if sets:
            break
    else:
        return None

    def key(i):
        return (not _no_rotational_inertia(setup, equations[i]), not _without_inertia(equations[i]),
                "2nd law" not in equations[i].label, int(np.sum(np.abs(nA[i]) > tol)), i)

    flagged = [c for c in sets if any(key(i)[0] is False or key(i)[1] is False for i in c)]
    if len(sets) == len(list(itertools.combinations(range(m), k))) and m > k and not flagged:
        return None                 # every equation alike: the contradiction is spread over all of them
    best = min(sets, key=lambda c: sorted(key(i) for i in c))
    parts, hints, contacts, bodies = [], [], [], []
    for i in best:
        why, hint, named = _why(setup, equations[i], nA[i], unknowns, tol)
        parts.append(f"{equations[i].label} cannot hold: {why}")
        hints.append(hint) if hint not in hints else None
        contacts += [c for c in named if c not in contacts]
        body = getattr(equations[i], "body", None)
        bodies += [body] if body and body not in bodies else []
    others = [equations[c[0]].label for c in sets if c != best and k == 1]
    also = (f" (without {'; or '.join(others[:3])}{' or others' if len(others) > 3 else ''} instead, the rest "
            "would hold too)" if others else "")
    msg = (f"the balance laws give {m} equations for {len(unknowns)} unknowns "
           f"({', '.join(text(u) for u in unknowns)}), and they contradict each other: {'; and '.join(parts)}"
           f"{also}.")
    where = ", ".join([f"body {b}" for b in bodies] + [f"contact {c}" for c in contacts])
    return msg, " ".join(hints), where
