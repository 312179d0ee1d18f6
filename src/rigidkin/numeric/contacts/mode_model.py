"""The numeric functions of one regime of one mode, and the watches whose zero ends it.

A :class:`ModeModel` evaluates, at a state, the rates of (q, q̇), the reactions and the quantities that end
the regime — its :class:`Watch` es: a normal reaction reaching zero, the gap of an open contact closing,
a slip speed dying out, the friction a sticking contact needs reaching ±µN, a regime's sign condition
changing sign — with the constraint gaps, the energies and the friction forces.  Its conditions (the
regime's signs) are checked at a state, or, where one is zero, a short step along the regime's own motion
later (:func:`look_ahead`).  Built by :class:`rigidkin.numeric.contacts.modes.Hybrid`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..rhs import RegimeFunctions
from ..state import StateLayout
from .vocabulary import describe_mode


def look_ahead(t_: float, y: np.ndarray, f: np.ndarray) -> tuple[float, np.ndarray]:
    """(h, y + h f): a short explicit step along the rates ``f`` (of the first len(f) state slots) that moves
    the state by a relative 1e-7, and never more than a microsecond's worth — at rest on a threshold the rates
    are round-off (1e-15), and a step sized by them alone would be years long (a pushed box as it tips)."""
    n = len(f)
    h = min(1e-7 * (1.0 + float(np.max(np.abs(y[:n])))) / max(float(np.max(np.abs(f))), 1e-300),
            1e-6 * (1.0 + abs(float(t_))))
    y2 = np.array(y, dtype=float)
    y2[:n] = y2[:n] + h * f
    return h, y2


@dataclass(frozen=True)
class Watch:
    """A quantity of the state whose zero ends a regime, and what that zero means."""

    kind: str            # "opens", "impact", "sticks", "slips", "reverses", "domain" (the model's geometry ends),
    #                      "slack" (a rope's tension reaches zero), "tightens" (a slack rope's gap closes)
    name: str            # the contact or load
    label: str           # e.g. "contact A opens"
    direction: int       # the sign of the crossing that counts (solve_ivp's convention)
    slip_sign: int = 0   # "slips": the sign σ of the slip that begins
    quantity: str = ""   # the watched quantity, as a person reads it
    detail: str = ""     # "domain": why the model ends where the quantity reaches zero


class _Only:
    """A view of a ModeModel restricted to some of its conditions."""

    def __init__(self, model, conditions):
        self._m, self.conditions = model, conditions

    def __getattr__(self, name):
        return getattr(self._m, name)


@dataclass
class ModeModel:
    """Numeric functions of one regime of one mode (parameters passed at call time).

    ``functions`` (a :class:`RegimeFunctions`) evaluates, at a state, the rates, the reactions and
    the quantities [P_nc, watches…, constraint gaps…, T, U, friction forces and limits…].
    ``conditions`` are the regime's sign conditions: (watch index, ">" or "<").
    """

    system: object
    mode: dict
    regime_index: int
    solution: object
    layout: StateLayout
    functions: RegimeFunctions
    watches: list
    conditions: list
    residual_names: list
    friction_names: list
    conservative: bool
    steady: frozenset = frozenset()   # watches that cannot change: a mode at rest, no explicit time; a reaction
    #                                   identically zero (by symmetry)
    offsets: np.ndarray | None = None  # constants added to the watches (a slack rope's gap: .slack)

    @property
    def regime(self):
        return self.solution.regime(self.regime_index)

    @property
    def description(self) -> str:
        words = describe_mode(self.system, self.mode, getattr(self.solution.setup, "held", ()))
        conds = [f"{self.watches[wi].quantity} {rel} 0" for wi, rel in self.conditions]
        return words + (f" ({', '.join(conds)})" if conds else "")

    def _q(self, t_, y, p):
        return self.functions.evaluate(t_, y, p)

    def rates(self, t_, y, p) -> np.ndarray:
        """dy/dt of (q, q̇) and of the work of non-conservative loads and reactions."""
        dy, _, q = self._q(t_, y, p)
        return np.concatenate([dy, q[:1]])

    def reactions(self, t_, y, p) -> dict:
        return dict(self._q(t_, y, p)[1])

    def watch_values(self, t_, y, p) -> np.ndarray:
        w = self._q(t_, y, p)[2][1:1 + len(self.watches)]
        return w if self.offsets is None else np.asarray(w, dtype=float) + self.offsets

    def residuals(self, t_, y, p) -> dict:
        q = self._q(t_, y, p)[2]
        nw = len(self.watches)
        return dict(zip(self.residual_names, map(float, q[1 + nw:1 + nw + len(self.residual_names)])))

    def energy(self, t_, y, p) -> tuple[float, float]:
        q = self._q(t_, y, p)[2]
        i = 1 + len(self.watches) + len(self.residual_names)
        return float(q[i]), float(q[i + 1])

    def condition_holds(self, t_, y, p, zero: float) -> bool | None:
        """Whether the regime's conditions hold strictly at the state (None: one of them is zero there)."""
        w = self.watch_values(t_, y, p)
        for wi, rel in self.conditions:
            v = float(w[wi])
            if abs(v) <= zero:
                return None
            if (v > 0) != (rel == ">"):
                return False
        return True

    def leaves_zero_consistently(self, t_, y, p, zero: float) -> bool:
        """At a state where some condition is zero: does the motion of this regime make them all hold?

        A short explicit step along this regime's own rates shows the sign each condition takes.
        """
        y = np.asarray(y, dtype=float)
        n = 2 * self.layout.n
        f = self.rates(t_, y, p)[:n]
        h, y2 = look_ahead(t_, y, f)
        w0, w1 = self.watch_values(t_, y, p), self.watch_values(t_ + h, y2, p)
        for wi, rel in self.conditions:
            v = float(w0[wi]) if abs(float(w0[wi])) > zero else float(w1[wi])
            if v == 0.0 or (v > 0) != (rel == ">"):
                return False
        return True

    def evaluate(self, times: np.ndarray, ys: np.ndarray, p) -> dict:
        """The reactions, constraint gaps, T, U and friction forces at many states (arrays), by name."""
        reactions = {k: np.empty(len(times)) for k in self.functions.reaction_names}
        nw, ns = len(self.watches), len(self.residual_names)
        res = np.empty((ns, len(times)))
        T, U = np.empty(len(times)), np.empty(len(times))
        fr = np.empty((len(self.friction_names), len(times)))
        for j, tt in enumerate(times):
            _, r, q = self._q(float(tt), ys[:, j], p)
            for k, v in r.items():
                reactions[k][j] = v
            res[:, j] = q[1 + nw:1 + nw + ns]
            T[j], U[j] = q[1 + nw + ns], q[2 + nw + ns]
            fr[:, j] = q[3 + nw + ns:]
        return {"reactions": reactions, "residuals": dict(zip(self.residual_names, res)), "T": T, "U": U,
                "frictions": dict(zip(self.friction_names, fr))}
