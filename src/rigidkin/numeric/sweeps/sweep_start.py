"""The starting state of every run of a sweep, under the same rule as ``simulate``'s.

Each run's coordinates are put onto the mode's bilateral position constraints by Newton's method from the
values given (:func:`rigidkin.numeric.state.assemble`), or the sweep is refused naming the run, the
constraint and its residual.  A unilateral contact the mode holds closed must touch: a run that starts with
it inside its surface is refused (as ``simulate`` refuses it), and one that starts with it apart is refused
too, since the sweep integrates the one mode in which it is closed (``simulate`` would start it open).
"""

from __future__ import annotations

import numpy as np

from ...base.errors import InputError
from ...derive.derivation import derivation_of
from ..contacts.modes import Hybrid
from ..contacts.vocabulary import OPEN
from ..state import StateLayout, assemble


def _run_text(layout: StateLayout, y, p) -> str:
    return ", ".join(f"{k} = {v:.6g}" for k, v in zip(layout.labels, y[:2 * layout.n]))


def _hybrid_and_mode(system, mode):
    hyb = derivation_of(system).hybrid(lambda: Hybrid(system))
    mode = dict(mode or {})
    return hyb, {name: mode.get(name) or c.default_state(hyb.kin) for name, c in hyb.contacts.items()}  # setup_mode's


def start_gaps(system, mode, layout: StateLayout) -> list:
    """The gaps (plain sympy expressions of the layout's arguments) that vanish at every start the mode accepts:
    its bilateral position constraints and its closed unilateral contacts (what a sweep's record checks)."""
    hyb, full = _hybrid_and_mode(system, mode)
    red = hyb.solution(full).setup.reduction
    gaps = [r.gap for r in red.relating if r.gap is not None and r.gap != 0 and not r.unilateral]
    gaps += [c.gap(hyb.kin) for name, c in hyb.contacts.items() if full[name] != OPEN and c.unilateral]
    return [layout.to_plain(g) for g in gaps]


def _columns(fn, Y: np.ndarray, P: np.ndarray, n: int, count: int) -> np.ndarray | None:
    """The function's values at every run at once (runs × count), or None where it does not vectorise."""
    try:
        with np.errstate(all="ignore"):
            vals = fn(0.0, *Y[:, :2 * n].T, *P.T)
        out = np.column_stack([np.broadcast_to(np.asarray(v, dtype=float), (len(Y),)) for v in vals][:count])
    except (TypeError, ValueError):
        return None
    return out if out.shape == (len(Y), count) else None


def assemble_runs(system, mode, layout: StateLayout, Y: np.ndarray, P: np.ndarray, where: str = "sweep",
                  first: int = 0) -> bool:
    """Assemble each run's start (rows of ``Y``, parameters ``P``) in place; True when a coordinate moved (the
    dependent rates are then to be completed again).  InputError for a run that cannot start in the mode
    (runs are numbered from ``first`` + 1: a chunk of a streamed sweep)."""
    hyb, full = _hybrid_and_mode(system, mode)
    cons = hyb.position_constraints(full)
    n = layout.n
    tol = 1e-9 * np.maximum(1.0, np.max(np.abs(Y[:, :n]), axis=1)) if n else np.full(len(Y), 1e-9)
    moved = False
    if cons.labels:
        vals = _columns(cons.function, Y, P, n, len(cons.labels))
        todo = range(len(Y)) if vals is None else np.flatnonzero(~np.all(np.abs(vals) <= tol[:, None], axis=1))
        for r in todo:                      # Newton for the runs off their constraints only
            y, p = Y[r], P[r]
            try:
                y2 = assemble(cons, layout, 0.0, y, p, f"{where}, run {first + r + 1}")
            except InputError as exc:
                raise InputError(f"run {first + r + 1} ({_run_text(layout, y, p)}): {exc.message}", where=where,
                                 hint=exc.hint) from None
            if np.any(y2[:n] != y[:n]):
                Y[r, :n] = y2[:n]
                moved = True
    for name, c in hyb.contacts.items():
        if full.get(name, OPEN) == OPEN or not c.unilateral:
            continue
        fn, count = hyb.contact_functions(name)
        vals = _columns(fn, Y, P, n, count)
        gaps = vals[:, 0] if vals is not None else np.array([hyb.contact_state(name, 0.0, y, p)[0]
                                                               for y, p in zip(Y, P)])
        inside, apart = np.flatnonzero(gaps < -tol), np.flatnonzero(gaps > tol)
        if len(inside):
            r = int(inside[0])
            raise InputError(f"run {first + r + 1} ({_run_text(layout, Y[r], P[r])}) puts contact {name} "
                             f"{-gaps[r]:.6g} into its surface.", where=where,
                             hint="Give starting values that keep the bodies outside the surfaces they touch.")
        if len(apart):
            r = int(apart[0])
            raise InputError(f"run {first + r + 1} ({_run_text(layout, Y[r], P[r])}) starts with contact {name} "
                             f"apart (gap {gaps[r]:.6g}), but the sweep integrates the mode in which it is closed.",
                             where=where, hint=f"Sweep the mode with it open (--mode {name}=open), or "
                                               "start the runs with it touching.")
    return moved
