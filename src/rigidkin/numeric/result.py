"""The result of a simulation: time histories, events, modes, and the energy and constraint monitors.

Histories are sampled from each mode's dense output on a uniform grid plus the ends of every
segment (so a jump in the rates at an impact shows as two samples at the same time).  The energy
monitor compares E = T + U with its initial value plus the work W done by non-conservative loads
and reactions (integrated with the motion) and by impulses: E − E0 − W is the drift of the
integration, whether or not energy is conserved.  The constraint monitor reports the largest gap
of every closed constraint (position level).
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..base import display
from ..base.outfile import unique_columns, write_text, writing
from ..base.textsafe import safe_csv_cell
from ..base.units import shown_unit
from ..derive.keyed import Keyed, history_name
from ..model.inputs import inputs_of
from .figure import plot_quantities, plot_result
from .inputs import histories as input_histories
from .rhs import SimulationError
from .state import StateLayout, rate_name

#: The prefix of the energy columns (kinetic T, potential U, E = T + U, work W), apart from the user's names.
ENERGY = "energy: "


@dataclass(frozen=True)
class Event:
    """Something that ended a mode: its name, time, the state before and after, and the modes."""

    name: str
    kind: str                # "opens", "impact", "sticks", "slips", "reverses", "slack", "tightens", "phase", "stop"
    contact: str
    t: float
    state: dict              # the state at the event (before any jump)
    after: dict              # the state the next mode starts from
    mode_before: str
    mode_after: str
    detail: str = ""
    impact: dict | None = None  # an impact's numbers: impulses per contact, velocity jump, energy change

    def to_dict(self) -> dict:
        d = {"name": self.name, "t": self.t, "state": dict(self.state), "kind": self.kind,
             "mode_before": self.mode_before, "mode_after": self.mode_after}
        if any(abs(self.after[k] - self.state[k]) > 0 for k in self.state):
            d["state_after"] = dict(self.after)
        if self.detail:
            d["detail"] = self.detail
        if self.impact is not None:
            d["impact"] = self.impact
        return d

    def __str__(self) -> str:
        return f"t = {self.t:.10g}: {self.name}" + (f" ({self.detail})" if self.detail else "")


@dataclass
class Segment:
    """A stretch of the motion in one regime of one mode."""

    t0: float
    t1: float
    mode: dict
    regime: int
    description: str
    phase: int
    dense: object = field(repr=False)
    model: object = field(repr=False)
    params: np.ndarray = field(repr=False)
    rhs_calls: int = 0

    def state(self, t_) -> np.ndarray:
        return np.asarray(self.dense(t_), dtype=float)


@dataclass
class SimulationResult:
    """Time histories (``t``, ``q``, ``rates``, ``reactions``, ``energy``), ``events``, ``segments`` and monitors."""

    system: str
    title: str
    layout: StateLayout
    t: np.ndarray
    y: np.ndarray                      # (samples, 2n): q then q̇
    segment: np.ndarray                # segment index of each sample
    reactions: dict                    # name → array (0 where the constraint is open)
    energy: dict                       # "T", "U", "E", "W" (work of non-conservative loads and impulses)
    residuals: dict                    # constraint row → largest |gap| while closed
    events: list
    segments: list
    status: str                        # "completed" or "stopped"
    message: str
    energy_drift: float                # max |E − E0 − W| / energy scale
    energy_balance: str                # "conserved" or "with the work of non-conservative loads"
    warnings: list = field(default_factory=list)
    kinds: dict = field(default_factory=dict)
    limits: dict = field(default_factory=dict)   # "mu*N": the friction limit µN of each Coulomb contact
    #: why the run ended: "completed" (reached the end time), or why it stopped early: "mode-unavailable"
    #: (the model cannot represent the next mode), "no-consistent-mode" (the contact problem has no
    #: solution, Painlevé), "ambiguous" (several), "accumulation" (events pile up), "max-events",
    #: "relation-mismatch" (a mode entered with another constant of integration), "outside-domain" (a contact
    #: leaves the configurations its geometry describes: a disk lying flat), "constraint-drift" / "energy-drift"
    #: (a constraint or the energy balance left its tolerance: the histories end there)
    stop_reason: str = "completed"
    inputs: dict = field(default_factory=dict)   # name → the input u(t) at each sample (as the equations saw it)
    input_units: dict = field(default_factory=dict)  # name → the unit it was declared in (the samples are SI)

    @property
    def reached_end(self) -> bool:
        """Whether the simulation reached its end time (otherwise ``stop_reason`` and ``message`` say why)."""
        return self.status == "completed"

    # access ------------------------------------------------------------------------------------
    @property
    def q(self) -> Keyed:
        """Coordinate histories by name (``'theta'``), by q(t) or by sympy's own dynamicsymbol."""
        return Keyed({n: self.y[:, i] for i, n in enumerate(self.layout.names)}, what="coordinates")

    @property
    def rates(self) -> Keyed:
        """Rate histories by ``'dot(theta)'``, by q̇(t) or by sympy's own derivative."""
        n = self.layout.n
        return Keyed({rate_name(nm): self.y[:, n + i] for i, nm in enumerate(self.layout.names)}, what="rates")

    def __getitem__(self, name) -> np.ndarray:
        """A history by name: ``theta``, ``dot(theta)``, a reaction, an input, ``energy: T`` (kinetic),
        ``energy: U``, ``energy: E``, ``energy: W`` (a bare ``T``, ``U``, ``E``, ``W`` when no reaction has that
        name); or by symbol: q(t), q̇(t), sympy's own ``dynamicsymbols`` of the same name, ``Symbol('N')``."""
        if not isinstance(name, str):
            name = history_name(name)
        if name in self.inputs:
            return self.inputs[name]
        if name in self.reactions:
            return self.reactions[name]
        if name.startswith(ENERGY) and name[len(ENERGY):] in self.energy:
            return self.energy[name[len(ENERGY):]]
        if name in self.energy:
            return self.energy[name]
        return self.y[:, self.layout.index(name)]

    @property
    def final_state(self) -> dict:
        return self.layout.as_dict(self.y[-1])

    @property
    def t_final(self) -> float:
        return float(self.t[-1])

    @property
    def max_residual(self) -> float:
        return max(self.residuals.values(), default=0.0)

    def at(self, t_: float) -> dict:
        """The state at time ``t_`` from the dense output (after any event at exactly that time)."""
        seg = self.segment_at(t_)
        return self.layout.as_dict(seg.state(t_))

    def segment_at(self, t_: float) -> Segment:
        if not self.segments[0].t0 <= t_ <= self.segments[-1].t1:
            raise ValueError(f"t = {t_} is outside the simulated interval "
                             f"[{self.segments[0].t0}, {self.segments[-1].t1}].")
        for seg in reversed(self.segments):
            if seg.t0 <= t_:
                return seg
        return self.segments[0]

    def events_of(self, kind: str) -> list:
        return [e for e in self.events if e.kind == kind]

    # output --------------------------------------------------------------------------------------
    def to_dict(self) -> dict:
        """``{"events": [...], "final_state", "energy_drift", ...}`` (what ``--json`` prints)."""
        return {"system": self.system, "status": self.status, "message": self.message,
                "reached_end": self.reached_end, "stop_reason": self.stop_reason,
                "t_final": self.t_final, "events": [e.to_dict() for e in self.events],
                "final_state": self.final_state, "energy_drift": self.energy_drift,
                "energy_balance": self.energy_balance, "max_constraint_residual": self.max_residual,
                "modes": [{"t0": s.t0, "t1": s.t1, "mode": s.description} for s in self.segments],
                "warnings": list(self.warnings)}

    def to_json(self, indent: int | None = 2) -> str:
        return json.dumps(self.to_dict(), indent=indent, allow_nan=False)

    def columns(self) -> dict:
        """The histories by column name: ``t``, the coordinates, the rates, the reactions (the user's names), the
        inputs, and the energies namespaced ``energy: T``, ``energy: U``, ``energy: E``, ``energy: W``, so that no
        user's name (a tension called T) can replace another column; a name that would still appear twice is
        refused."""
        return unique_columns([("t", self.t), *self.q.items(), *self.rates.items(), *self.reactions.items(),
                               *self.inputs.items(), *((ENERGY + k, v) for k, v in self.energy.items())],
                              reserved=("mode",))

    def to_csv(self, path=None) -> str:
        """The histories as CSV (t, mode, coordinates, rates, reactions, inputs, ``energy: T``, ``energy: U``,
        ``energy: E``, ``energy: W``); written to ``path`` if given.

        Text cells (the mode) are made safe for spreadsheets (no formulas).  For long histories
        :meth:`write_csv` streams the rows to the file instead of building the text first.
        """
        buf = io.StringIO()
        for chunk in self._csv_chunks():
            buf.write(chunk)
        text = buf.getvalue()
        if path is not None:
            write_text(path, text, "the histories")
        return text

    def write_csv(self, path) -> Path:
        """Write the histories as CSV to ``path``, chunk by chunk, whole or not at all (an OutputError says why)."""

        with writing(path, "the histories") as f:
            for chunk in self._csv_chunks():
                f.write(chunk)
        return Path(path)

    def _csv_chunks(self, rows: int = 20_000):

        cols = self.columns()
        names = list(cols)
        modes = [safe_csv_cell(s.description) for s in self.segments] or ["(no mode: stopped at the start)"]
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow([safe_csv_cell(n) for n in (names[0], "mode", *names[1:])])
        for start in range(0, len(self.t), rows):
            for j in range(start, min(start + rows, len(self.t))):
                w.writerow([repr(float(cols["t"][j])), modes[int(self.segment[j])],
                            *(repr(float(cols[k][j])) for k in names[1:])])
            yield buf.getvalue()
            buf.seek(0)
            buf.truncate()
        if buf.tell():
            yield buf.getvalue()

    def plot(self, path=None, title: str | None = None, *, ax=None, quantities=None):
        """A figure of coordinates, rates, reactions, energy (and the inputs u(t), where the run had any) with the
        events marked; saved to ``path``.

        ``quantities`` (names such as ``'theta'``, ``'dot(theta)'``, ``'N'``, ``'E'``, or their sympy symbols)
        draws only those, in one panel; ``ax`` draws into a matplotlib Axes of the caller's figure."""

        if ax is None and quantities is None:
            return plot_result(self, path, title)
        return plot_quantities(self, quantities, ax, path, title)

    def to_pandas(self):
        """The histories as a pandas DataFrame indexed by t: mode, coordinates, rates, reactions, energy: T, U, E, W
        (an event time appears twice: before and after the jump)."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("to_pandas() needs pandas, which is not installed: pip install 'pandas>=2.1' "
                              "(or to_csv() writes the same table without it).") from None
        cols = self.columns()
        modes = [s.description for s in self.segments]
        data = {"mode": [modes[int(i)] for i in self.segment], **{k: v for k, v in cols.items() if k != "t"}}
        return pd.DataFrame(data, index=pd.Index(np.asarray(self.t), name="t"))

    def _repr_html_(self) -> str:
        return display.render(self, "html")

    def __str__(self) -> str:
        lines = [f"{self.title}: simulated to t = {self.t_final:.6g} ({self.status}: {self.message})"]
        for s in self.segments:
            lines.append(f"  {s.t0:12.6g} – {s.t1:<12.6g} {s.description}")
        if self.events:
            lines.append("Events:")
            lines += [f"  {e}" for e in self.events]
        lines.append(f"Energy drift {self.energy_drift:.3g} (relative; {self.energy_balance}); "
                     f"largest constraint residual {self.max_residual:.3g}")
        lines += [f"Warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def build_result(system, layout: StateLayout, segments: list, events: list, status: str, message: str,
                 n_points: int = 1001, energy_tol: float = 1e-6, residual_tol: float = 1e-6,
                 notes: list | None = None) -> SimulationResult:
    """Sample every segment and assemble the histories and monitors."""
    n = layout.n
    t_start, t_end = segments[0].t0, segments[-1].t1
    grid = np.linspace(t_start, t_end, max(2, int(n_points)))
    input_parts: list = []
    ts, ys, segs, react_parts, res_parts, T_parts, U_parts, limit_parts = [], [], [], [], [], [], [], []
    for i, seg in enumerate(segments):
        last = i == len(segments) - 1
        inside = grid[(grid > seg.t0) & ((grid < seg.t1) | (last & (grid <= seg.t1)))]
        times = np.unique(np.concatenate([[seg.t0], inside, [seg.t1]]))
        Y = np.asarray(seg.dense(times), dtype=float).reshape(2 * n + 1, len(times))
        vals = seg.model.evaluate(times, Y, seg.params)
        ts.append(times)
        ys.append(Y)
        segs.append(np.full(len(times), i))
        input_parts.append(input_histories(system, layout, times, Y, seg.params))
        forces = dict(vals["reactions"])
        forces.update({k: v for k, v in vals["frictions"].items() if not k.startswith("mu*")})
        react_parts.append(forces)
        limit_parts.append({k: v for k, v in vals["frictions"].items() if k.startswith("mu*")})
        res_parts.append(vals["residuals"])
        T_parts.append(vals["T"])
        U_parts.append(vals["U"])
    t = np.concatenate(ts)
    Y = np.concatenate(ys, axis=1)
    names: list[str] = []
    for part in react_parts:
        names += [k for k in part if k not in names]
    reactions = {k: np.concatenate([part.get(k, np.zeros(len(tt))) for part, tt in zip(react_parts, ts)])
                 for k in names}
    lnames: list[str] = []
    for part in limit_parts:
        lnames += [k for k in part if k not in lnames]
    limits = {k: np.concatenate([part.get(k, np.zeros(len(tt))) for part, tt in zip(limit_parts, ts)])
              for k in lnames}
    residuals: dict = {}
    for part in res_parts:
        for k, v in part.items():
            residuals[k] = max(residuals.get(k, 0.0), float(np.max(np.abs(v))) if len(v) else 0.0)
    inputs = {k: np.concatenate([part[k] for part in input_parts]) for k in (input_parts[0] if input_parts else {})}
    res_hist = {k: np.concatenate([np.abs(part[k]) if k in part else np.zeros(len(tt))
                                   for part, tt in zip(res_parts, ts)]) for k in residuals}
    T, U = np.concatenate(T_parts), np.concatenate(U_parts)
    W = Y[2 * n]
    E = T + U
    for label, arr in [("state", Y), ("reactions", np.array(list(reactions.values()) or [[0.0]])), ("energy", E)]:
        if not np.all(np.isfinite(arr)):
            bad = np.nonzero(~np.all(np.isfinite(np.atleast_2d(arr)), axis=0))[0]
            j = int(bad[0]) if len(bad) else 0
            raise SimulationError(f"the {label} is not finite at t = {t[min(j, len(t) - 1)]:.10g}.",
                                  where=system.name, hint="The motion reached a singular configuration.")
    scale = max(abs(E[0]), float(np.max(np.abs(T))), float(np.max(np.abs(U - U[0]))), 1e-300)
    drift = float(np.max(np.abs(E - E[0] - W)) / scale)
    conserved = bool(np.all(W == 0.0)) and all(s.model.conservative for s in segments)
    balance = "conserved" if conserved else "with the work of non-conservative loads and impulses"
    warns = list(notes or [])
    qscale = max(1.0, float(np.max(np.abs(Y[:n]))) if n else 1.0)
    # a run that cannot keep its constraints or its energy balance stops where it first fails (exit 3)
    failed = _first_failure(t, np.abs(E - E[0] - W) / scale, energy_tol, balance, res_hist, residual_tol * qscale)
    stop_reason, seg_of = "completed", np.concatenate(segs)
    if failed is not None:
        j, stop_reason, what = failed
        keep = slice(0, j + 1)
        t, Y, seg_of = t[keep], Y[:, keep], seg_of[keep]
        reactions = {k: v[keep] for k, v in reactions.items()}
        limits = {k: v[keep] for k, v in limits.items()}
        inputs = {k: v[keep] for k, v in inputs.items()}
        T, U, E, W = T[keep], U[keep], E[keep], W[keep]
        events = [e for e in events if e.t <= t[-1]]
        drift = float(np.max(np.abs(E - E[0] - W)) / scale)            # the monitors up to the stop
        residuals = {k: float(np.max(v[keep])) for k, v in res_hist.items()}
        status, message = "stopped", what
    result = SimulationResult(system.name, system.title, layout, t, Y[:2 * n].T.copy(), seg_of,
                              reactions, {"T": T, "U": U, "E": E, "W": W}, residuals, list(events),
                              list(segments), status, message, drift, balance, warns,
                              {c.name: c.kind for c in system.coordinate_info.values()}, limits)
    result.stop_reason = stop_reason
    result.inputs = inputs
    result.input_units = {k: shown_unit(i.unit, i.dimension) for k, i in inputs_of(system).items() if k in inputs}
    return result


def _first_failure(t, drift, energy_tol, balance, res_hist, res_tol):
    """(sample, stop reason, message) where the energy balance or a constraint first leaves its tolerance."""
    first = None
    bad = np.flatnonzero(drift > energy_tol)
    if len(bad):
        j = int(bad[0])
        first = (j, "energy-drift", f"the energy balance ({balance}) drifts by {drift[j]:.3g} (relative) at t = "
                 f"{t[j]:.10g}, beyond the tolerance {energy_tol:g}: the integration is not accurate enough "
                 "(tighten rtol/atol) or the model does work the monitor does not see; the simulation stops there")
    for k, v in res_hist.items():
        bad = np.flatnonzero(v > res_tol)
        if len(bad) and (first is None or int(bad[0]) < first[0]):
            j = int(bad[0])
            first = (j, "constraint-drift", f"the constraint '{k}' is violated by {v[j]:.3g} at t = {t[j]:.10g} "
                     f"(tolerance {res_tol:.3g}): the motion leaves the constraint; the simulation stops there")
    return first
