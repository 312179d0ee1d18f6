"""A figure of a simulation: coordinates, rates, reactions, the inputs u(t) (when it had any) and energy
against time, events marked.

Each mode is a shaded band named in a legend; each event a dotted vertical line numbered at the top
and listed under the plots.  matplotlib's Agg backend draws it, so no display is needed.
"""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np

from ..base.errors import InputError
from ..base.outfile import OutputError, check_target, writing
from ..base.textsafe import terminal_safe
from ..base.units import from_si

_UNITS = {"angle": ("rad", "rad/s"), "length": ("m", "m/s"), "other": ("", "1/s")}


_GREEK = dict(zip(("alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa", "lambda",
                   "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega"),
                  "αβγδεζηθικλμνξπρστυφχψω"))


def greek(name: str) -> str:
    """``theta`` → θ, ``phi_1`` → φ_1 (names as written by hand)."""
    head, sep, tail = name.partition("_")
    return _GREEK.get(head, head) + sep + tail


def _label(name: str, unit: str) -> str:
    return f"{name} [{unit}]" if unit else name


def plot_result(result, path=None, title: str | None = None):
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure


    inputs = dict(getattr(result, "inputs", None) or {})
    fig = Figure(figsize=(10, 13.5 if inputs else 11), layout="constrained")
    axes = fig.subplots(5 if inputs else 4, 1, sharex=True)
    t = result.t
    names = result.layout.names
    seg_idx = result.segment

    def lines(ax, series, ylabel, styles=None):
        cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        for j, (lab, arr) in enumerate(series):
            style = (styles or {}).get(lab, {"color": cycle[j % len(cycle)], "lw": 1.4})
            for s in np.unique(seg_idx):           # one line per segment: no line across a jump
                m = seg_idx == s
                ax.plot(t[m], arr[m], label=lab if s == seg_idx[0] else None, **style)
        ax.set_ylabel(ylabel)
        if series:
            ax.legend(loc="best", fontsize=8, framealpha=0.85)
        ax.grid(True, alpha=0.3)

    q = result.q
    r = result.rates
    kinds = result.kinds
    lines(axes[0], [(_label(greek(n), _UNITS.get(kinds.get(n, "other"), ("", ""))[0]), q[n]) for n in names],
          "coordinates")
    lines(axes[1], [(_label(f"d{greek(n)}/dt", _UNITS.get(kinds.get(n, "other"), ("", ""))[1]), r[f"dot({n})"])
                    for n in names], "rates")
    lines(axes[2], [(greek(k), v) for k, v in result.reactions.items()], "reactions [N, N·m]")
    limits = {k: v for k, v in result.limits.items() if np.any(v != 0)}
    for k, v in limits.items():               # ± the friction limit µN, dashed
        for s in np.unique(seg_idx):
            m = seg_idx == s
            for sgn in (1, -1):
                axes[2].plot(t[m], sgn * v[m], color="0.45", lw=0.9, ls="--",
                             label=f"±µ{k[3:]} (friction limit)" if (s == seg_idx[0] and sgn > 0)
                             else None)
    if limits:
        axes[2].legend(loc="best", fontsize=8, framealpha=0.85)
    E0 = result.energy["E"][0]
    e_series = [("T kinetic", result.energy["T"]), ("U potential", result.energy["U"]),
                ("E = T + U", result.energy["E"])]
    if np.any(result.energy["W"] != 0):
        e_series.append(("E0 + W (work done on the system)", E0 + result.energy["W"]))
    lines(axes[3], e_series, "energy [J]",
          {"E = T + U": {"color": "black", "lw": 2.2, "ls": "--"},
           "E0 + W (work done on the system)": {"color": "tab:red", "lw": 1.0, "ls": "-."}})
    if inputs:                                # the inputs u(t) as the equations saw them, in their declared units
        lines(axes[4], [(_label(greek(k), _unit(result, k)), _in_unit(v, _unit(result, k)))
                        for k, v in inputs.items()], "inputs")
    axes[-1].set_xlabel("t [s]")
    if not result.reactions and not limits:
        axes[2].text(0.5, 0.5, "no reactions (every contact open)", transform=axes[2].transAxes, ha="center",
                     va="center", color="0.3")
    # modes as shaded bands
    shades = ["#f2f2f2", "#dde8f5", "#f7e6d5", "#e2f0dc", "#efe0f0", "#f5f1d0"]
    desc = []
    for s in result.segments:
        if s.description not in desc:
            desc.append(s.description)
    for s in result.segments:
        c = shades[desc.index(s.description) % len(shades)]
        for ax in axes:
            ax.axvspan(s.t0, s.t1, color=c, zorder=0, lw=0)
    # events
    last_label = -np.inf
    span = max(t[-1] - t[0], 1e-300)
    for i, e in enumerate(result.events, 1):
        for ax in axes:
            ax.axvline(e.t, color="0.25", ls=":", lw=1.0)
        if e.t - last_label < 0.03 * span:      # too close to the previous label to be read
            continue
        last_label = e.t
        axes[0].annotate(f"[{i}]", (e.t, 1.0), xycoords=("data", "axes fraction"), xytext=(0, 3),
                         textcoords="offset points", ha="center", va="bottom", fontsize=9, color="0.15")
        if len(result.events) <= 6:        # the event's name along its line, inside the top panel
            axes[0].annotate(e.name, (e.t, 0.97), xycoords=("data", "axes fraction"), xytext=(3, 0),
                             textcoords="offset points", rotation=90, ha="left", va="top", fontsize=8,
                             color="0.2", bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                                                "alpha": 0.7})
    head = title or f"{result.title} — simulated to t = {result.t_final:.4g} s"
    fig.suptitle(terminal_safe(head, newlines=False), fontsize=12)     # a title's control characters shown
    notes = [f"[{i}] t = {e.t:.6g} s: {e.name}" for i, e in enumerate(result.events, 1)] or ["no events"]
    modes = [f"mode {j + 1} (band {['grey', 'blue', 'orange', 'green', 'violet', 'yellow'][j % 6]}): {d}"
             for j, d in enumerate(desc)]
    foot = modes + notes[:12] + ([f"… and {len(notes) - 12} more events"] if len(notes) > 12 else [])
    foot.append(f"energy drift {result.energy_drift:.2g} (relative, {result.energy_balance}); "
                f"largest constraint residual {result.max_residual:.2g}; {result.status}: {result.message}")
    fig.text(0.01, 0.0, "\n".join(foot), fontsize=8, va="top", ha="left", family="monospace", wrap=True)
    if path is not None:
        save_figure(fig, path, dpi=110, bbox_inches="tight")
    return fig


def _in_unit(si_values, unit: str):
    """Samples held in SI shown in ``unit`` (a declared unit such as kN or N*m)."""
    return si_values * from_si(1.0, unit) if unit else si_values


def _series_name(result, key) -> str:
    """The history a key names: ``'theta'``, ``'dot(theta)'``, a reaction, ``'energy: E'`` (``'E'`` where no
    reaction has that name), or the sympy symbol of one."""
    from ..derive.keyed import key_name

    n = key_name(key)
    if n is not None and n[1] in (0, 1):
        name = n[0] if n[1] == 0 else f"dot({n[0]})"
        if name in result.columns():
            return name
        if f"energy: {name}" in result.columns():     # a bare T, U, E, W: the energy (no reaction has the name)
            return f"energy: {name}"
    known = [k for k in result.columns() if k != "t"]
    raise InputError(f"{key!r} is no history of this simulation.", where="plot(quantities=...)",
                     hint=f"Choose among: {', '.join(known)}.")


def _unit(result, name: str) -> str:
    kinds = result.kinds
    if name in result.q:
        return _UNITS.get(kinds.get(name, "other"), ("", ""))[0]
    if name in result.rates:
        return _UNITS.get(kinds.get(name[4:-1], "other"), ("", ""))[1]
    if name in result.energy or (name.startswith("energy: ") and name[8:] in result.energy):
        return "J"
    if name in getattr(result, "inputs", {}):
        return getattr(result, "input_units", {}).get(name, "")
    return "N or N·m" if name in result.reactions else ""


def plot_quantities(result, quantities=None, ax=None, path=None, title: str | None = None):
    """The histories named in ``quantities`` (default: the coordinates) against time, in ``ax`` if given.

    Modes are shaded and events drawn as dotted lines, as in the full figure; returns the figure.
    """
    from matplotlib.figure import Figure

    names = [_series_name(result, k) for k in (quantities if quantities is not None else result.layout.names)]
    if ax is None:
        fig = Figure(figsize=(8, 4.5), layout="constrained")
        ax = fig.subplots()
    else:
        fig = ax.figure
    cols, seg_idx, t = result.columns(), result.segment, result.t
    for j, n in enumerate(names):
        values = _in_unit(cols[n], _unit(result, n)) if n in result.inputs else cols[n]
        for s in np.unique(seg_idx):           # one line per segment: no line across a jump
            m = seg_idx == s
            lab = _label(greek(n) if not n.startswith("dot(") else f"d{greek(n[4:-1])}/dt", _unit(result, n))
            ax.plot(t[m], values[m], color=f"C{j % 10}", lw=1.4, label=lab if s == seg_idx[0] else None)
    units = {_unit(result, n) for n in names}
    ax.set_ylabel(f"[{units.pop()}]" if len(units) == 1 and "" not in units else "value")
    ax.set_xlabel("t [s]")
    shades = ["#f2f2f2", "#dde8f5", "#f7e6d5", "#e2f0dc", "#efe0f0", "#f5f1d0"]
    desc = list(dict.fromkeys(s.description for s in result.segments))
    if len(desc) > 1:
        for s in result.segments:
            ax.axvspan(s.t0, s.t1, color=shades[desc.index(s.description) % len(shades)], zorder=0, lw=0)
    for e in result.events:
        ax.axvline(e.t, color="0.25", ls=":", lw=1.0)
    ax.legend(loc="best", fontsize=8, framealpha=0.85)
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(terminal_safe(title, newlines=False))
    if path is not None:
        save_figure(fig, path, dpi=110, bbox_inches="tight")
    return fig


def figure_formats() -> tuple[str, ...]:
    """The extensions a figure can be written with (``.png``, ``.pdf``, ``.svg``, ...; not ``.pgf``, which needs
    LaTeX)."""
    from matplotlib.backend_bases import FigureCanvasBase

    return tuple(sorted(f".{k}" for k in FigureCanvasBase.get_supported_filetypes() if k != "pgf"))


def save_figure(fig, path, what: str = "the figure", **savefig_kw) -> Path:
    """Draw ``fig`` and write it to ``path`` whole or not at all; the format follows the extension.

    Text that matplotlib's mathtext cannot typeset (a title with unmatched ``$`` or ``\\frac{``) is
    drawn as plain text instead.  A path that cannot be written is an OutputError naming the reason.
    """

    formats = figure_formats()
    p = check_target(path, what, formats)
    _plain_text(fig, only_unparsable=True)
    buf = io.BytesIO()
    try:
        try:
            fig.savefig(buf, format=p.suffix[1:].lower() or "png", **savefig_kw)
        except ValueError:                   # text that mathtext cannot parse after all: show every text as written
            _plain_text(fig)
            buf = io.BytesIO()
            fig.savefig(buf, format=p.suffix[1:].lower() or "png", **savefig_kw)
    except (ValueError, RuntimeError, OverflowError) as exc:
        reason = " ".join(str(exc).split())[:300]
        raise OutputError(f"cannot draw {what} for {p}: {reason}.",
                          hint="Try another format (.png, .svg, .pdf) or simpler titles and names.") from None
    with writing(p, what, binary=True, suffixes=formats) as f:
        f.write(buf.getvalue())
    return p


_DOLLAR = re.compile(r"(?<!\\)\$")


def _plain_text(fig, only_unparsable: bool = False) -> None:
    """The texts of ``fig`` (every one, or ``only_unparsable`` those mathtext cannot typeset) as plain text:
    each unescaped ``$`` escaped, so mathtext is never entered."""
    from matplotlib.cbook import is_math_text
    from matplotlib.mathtext import MathTextParser
    from matplotlib.text import Text

    parser = MathTextParser("path") if only_unparsable else None
    for text in fig.findobj(Text):
        raw = text.get_text()
        if "$" not in raw:
            continue
        if parser is not None:
            if not is_math_text(raw):
                continue
            try:
                parser.parse(raw)
                continue
            except (ValueError, RuntimeError):
                pass
        text.set_text(_DOLLAR.sub(r"\\$", raw))
