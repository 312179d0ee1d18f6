"""An interactive view for Jupyter: a slider for each parameter; moving one re-simulates the system and
redraws its time histories and the animation of its motion.

>>> view = rigidkin.jupyter.explore(system, t_final=3)     # doctest: +SKIP
>>> view                           # shows the sliders, the plot, the animation  # doctest: +SKIP

``explore`` takes a System or a Solution (its system); ``start=["theta"]`` adds sliders for the
start of coordinates or rates (``"dot(theta)"``).  Sliders run from a quarter to four times each
parameter's value (0 to 1 for a parameter whose value is 0; ``ranges={"m": (1, 20)}`` to choose),
and act on release, so a drag simulates once.  A value the model refuses (a contact that cannot
start, a parameter out of its range) is said in one line above the plot, and the last good figures
stay.  Needs ipywidgets: ``pip install 'rigidkin[jupyter]'``.
"""

from __future__ import annotations

import base64
import html
from collections.abc import Mapping

from ..base.errors import RigidkinError
from ..base.units import si_unit


class MissingExtra(RigidkinError, ImportError):
    """An optional dependency is not installed (its extra names it)."""


def _ipywidgets():
    try:
        import ipywidgets
    except ImportError:
        raise MissingExtra("the interactive view needs ipywidgets, which is not installed.",
                           where="rigidkin.jupyter.explore",
                           hint="Install it with: pip install 'rigidkin[jupyter]' (or pip install ipywidgets), "
                                "then restart the kernel.") from None
    return ipywidgets


def _range(value: float) -> tuple[float, float]:
    if value > 0:
        return value / 4, value * 4
    if value < 0:
        return value * 4, value / 4
    return 0.0, 1.0


def _png_output(png: bytes, text: str) -> dict:
    return {"output_type": "display_data", "metadata": {},
            "data": {"image/png": base64.b64encode(png).decode("ascii"), "text/plain": text}}


def _html_output(source: str, text: str) -> dict:
    return {"output_type": "display_data", "metadata": {}, "data": {"text/html": source, "text/plain": text}}


class Explorer:
    """Sliders over a system's parameters, the last simulation and its figures.

    ``widget`` is the ipywidgets box a notebook shows; ``sliders`` maps each parameter's name to its
    slider (``start_sliders``: those of the start); ``result`` is the latest ``SimulationResult``,
    ``values`` the parameters it ran with and ``started`` its start;
    ``figure`` the matplotlib figure of its time histories (also shown as a PNG in ``plot_output``);
    ``animation_output`` holds the animation's player.  ``runs`` counts the simulations.
    """

    def __init__(self, system, t_final: float = 3.0, *, initial_state: Mapping | None = None,
                 parameters=None, start=(), ranges: Mapping | None = None, animation: bool = True,
                 frames: int = 40, simulate_options: Mapping | None = None):
        ipw = _ipywidgets()
        self.system = system
        self.t_final = float(t_final)
        self.initial_state = dict(initial_state or {})
        self.animation = animation
        self.frames = int(frames)
        self.simulate_options = dict(simulate_options or {})
        info = system.parameter_info
        names = [n for n in (parameters if parameters is not None else info) if info[n].value is not None]
        unknown = [n for n in (parameters or ()) if n not in info]
        if unknown:
            raise RigidkinError(f"{', '.join(unknown)} is not a parameter of {system.name}.", where="explore",
                                hint=f"Parameters: {', '.join(info) or 'none'}.")
        ranges = dict(ranges or {})
        self.sliders = {}
        for name in names:
            p = info[name]
            lo, hi = ranges.get(name, _range(float(p.value)))
            unit = f" ({si_unit(p.dimension)})" if si_unit(p.dimension) else ""     # the sliders are in SI
            self.sliders[name] = ipw.FloatSlider(
                value=float(p.value), min=float(lo), max=float(hi), step=(float(hi) - float(lo)) / 200,
                description=name, readout_format=".4g", continuous_update=False,
                tooltip=f"{p.description or name}{unit}", style={"description_width": "initial"})
        self.start_sliders = {}
        for key in start:
            self.start_sliders[key] = self._start_slider(ipw, key, ranges.get(key))
        self.status = ipw.HTML()
        self.plot_output = ipw.Output()
        self.animation_output = ipw.Output()
        self.runs = 0
        self.result = None
        self.values: dict = {}
        self.started: dict = {}
        self.figure = None
        for s in (*self.sliders.values(), *self.start_sliders.values()):
            s.observe(self._changed, names="value")
        views = [self.plot_output] + ([self.animation_output] if animation else [])
        self.widget = ipw.VBox([ipw.HTML(f"<b>{html.escape(system.title)}</b>: parameters (SI units)"),
                                ipw.GridBox([*self.sliders.values(), *self.start_sliders.values()],
                                            layout=ipw.Layout(grid_template_columns="repeat(2, 50%)")),
                                self.status, ipw.HBox(views)])
        self.update()

    def _start_slider(self, ipw, key: str, span):
        """A slider for a coordinate's start value (``theta``) or its rate's (``dot(theta)``)."""
        rate = key.startswith("dot(") and key.endswith(")")
        name = key[4:-1] if rate else key
        info = self.system.coordinate_info.get(name)
        if info is None:
            raise RigidkinError(f"'{key}' names no coordinate of {self.system.name}.", where="explore(start=...)",
                                hint=f"Coordinates: {', '.join(self.system.coordinate_info)}; a rate is "
                                     "'dot(NAME)'.")
        given = self.initial_state.get(key, info.rate if rate else info.initial)
        value = float(given) if given is not None else 0.0
        if span is None:
            width = 4 * abs(value) if value else 1.0
            span = (-3.2, 3.2) if info.kind == "angle" and not rate else (value - width, value + width)
        lo, hi = float(span[0]), float(span[1])
        return ipw.FloatSlider(value=value, min=lo, max=hi, step=(hi - lo) / 200, description=f"{key} at start",
                               readout_format=".4g", continuous_update=False, style={"description_width": "initial"})

    def start(self) -> dict:
        """The start the next simulation takes: the given ``initial_state`` with the start sliders' values."""
        return {**self.initial_state, **{k: float(s.value) for k, s in self.start_sliders.items()}}

    def parameters(self) -> dict:
        """The sliders' values, name → number (SI)."""
        return {name: float(s.value) for name, s in self.sliders.items()}

    def _changed(self, change) -> None:
        self.update()

    def update(self) -> None:
        """Simulate with the sliders' values and redraw the plot and the animation."""
        from ..numeric.simulate import simulate
        from .plots import png

        values, begin = self.parameters(), self.start()
        try:
            result = simulate(self.system, self.t_final, begin or None, values, **self.simulate_options)
        except RigidkinError as exc:
            self.status.value = f'<span style="color:#a00">{html.escape(str(exc))}</span>'
            return
        self.runs += 1
        self.result, self.values, self.started = result, values, begin
        self.status.value = html.escape(f"simulated to t = {result.t_final:.4g} s ({result.status}); "
                                        + (f"{len(result.events)} event(s)" if result.events else "no event"))
        self.figure = result.plot()
        self.plot_output.outputs = (_png_output(png(self.figure), f"time histories, run {self.runs}"),)
        if self.animation:
            from .animate import animate

            anim = animate(self.system, result, frames=self.frames)
            try:
                self.animation_output.outputs = (_html_output(anim.to_jshtml(), f"animation, run {self.runs}"),)
            finally:
                anim.close()

    def _repr_mimebundle_(self, include=None, exclude=None):
        return self.widget._repr_mimebundle_(include=include, exclude=exclude)

    def __repr__(self) -> str:
        return f"Explorer({self.system.name}: {', '.join(self.sliders) or 'no parameters'}; {self.runs} run(s))"


def explore(obj, t_final: float = 3.0, **kwargs) -> Explorer:
    """Sliders for the parameters of ``obj`` (a System or a Solution) that re-simulate and redraw.

    ``t_final``: the simulated time (s); ``initial_state``: the start (``{"theta": 0.3}``, as
    ``simulate`` takes it); ``parameters``: the names to give sliders (default: every parameter with a
    value); ``start``: coordinates and rates whose start gets a slider too (``["theta", "dot(theta)"]``);
    ``ranges``: name → (min, max); ``animation``: draw the motion too (``frames`` frames).
    """
    system = getattr(obj, "system", obj)
    return Explorer(system, t_final, **kwargs)
