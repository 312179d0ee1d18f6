"""Jupyter: the mime bundles a notebook receives show rates with dots; the slider view re-simulates.

The bundles are what IPython's display formatter hands a notebook (text/html, text/latex, text/plain).
The slider view is built headless (no kernel, no browser): sliders are moved from Python and the new
simulation, plot and animation are compared with a fresh simulation at the same parameter values.
"""

from __future__ import annotations

import base64
import html
import re
import sys

import numpy as np
import pytest

from rigidkin import examples
from rigidkin.base.errors import RigidkinError
from rigidkin.numeric.simulate import simulate

T_END = 0.5


@pytest.fixture(scope="module")
def ladder():
    return examples.build("ladder")


def _bundle(obj) -> dict:
    formatter = pytest.importorskip("IPython.core.formatters").DisplayFormatter()
    data, _ = formatter.format(obj)
    return data


def _tex_spans(html: str) -> list[str]:
    return re.findall(r'class="rk-tex [^"]*mathjax_process[^"]*">(.*?)</(?:span|div)>', html, flags=re.S)


def test_solution_bundle_shows_dots_for_mathjax(ladder):
    data = _bundle(ladder.solve())
    assert {"text/html", "text/latex", "text/plain"} <= set(data)
    html, tex = data["text/html"], data["text/latex"]
    spans = " ".join(_tex_spans(html))
    assert r"\dot{\theta}" in spans and r"\ddot{\theta}" in spans         # x' = l cos θ θ̇ ; the EOM in θ̈
    assert r"\ddot{\theta}" in tex
    for wrong in ("Derivative", r"\frac{d}{d t}", "theta'", "θ'", r"\theta{\left(t \right)}"):
        assert wrong not in spans and wrong not in tex
    # MathJax typesets the TeX only: the rest of the fragment is marked for it to leave alone
    assert 'class="rigidkin tex2jax_ignore mathjax_ignore"' in html
    # every formula also as MathML (pages without MathJax), hidden inside a Jupyter output
    assert html.count('<span class="rk-mathml">') + html.count('<div class="rk-mathml">') == len(_tex_spans(html))
    assert ".jp-RenderedHTMLCommon .rigidkin .rk-mathml{display:none}" in html


@pytest.mark.slow
def test_system_and_result_bundles(ladder):
    data = _bundle(ladder)
    spans = _tex_spans(data["text/html"])
    assert any(r"\theta" in s for s in spans) and "$" not in "".join(spans)
    assert data["text/latex"].startswith("$\\displaystyle") and r"\theta" in data["text/latex"]
    res = simulate(ladder, T_END)
    html = _bundle(res)["text/html"]
    assert "data:image/png;base64," in html and "mathjax_ignore" in html


def test_a_dollar_in_text_is_not_math():
    from rigidkin.report.blocks import Paragraph
    from rigidkin.report.jupyter import fragment

    html = fragment("costs", [Paragraph("between $5 and $10")])
    assert "mathjax_ignore" in html.split("between")[0] and "$5 and $10" in html


def test_missing_ipywidgets_says_how_to_install(monkeypatch, ladder):
    from rigidkin.report import widgets

    monkeypatch.setitem(sys.modules, "ipywidgets", None)          # import ipywidgets fails
    with pytest.raises(ImportError) as info:
        widgets.explore(ladder)
    assert isinstance(info.value, widgets.MissingExtra)
    assert "pip install 'rigidkin[jupyter]'" in str(info.value) and "ipywidgets" in str(info.value)


def _png(output) -> bytes:
    return base64.b64decode(output.outputs[0]["data"]["image/png"])


def _plotted(fig) -> list[tuple]:
    return [(ln.get_label(), np.asarray(ln.get_xdata()), np.asarray(ln.get_ydata())) for ax in fig.axes
            for ln in ax.lines]


@pytest.mark.slow
def test_sliders_resimulate_and_redraw(ladder):
    pytest.importorskip("ipywidgets")
    import rigidkin as rk

    view = rk.jupyter.explore(ladder, t_final=T_END, frames=4)
    assert set(view.sliders) == {"m", "l", "g"} and view.runs == 1
    first_png, first_anim = _png(view.plot_output), view.animation_output.outputs[0]["data"]["text/html"]
    first_plot = _plotted(view.figure)
    assert view.sliders["l"].min < 2.0 < view.sliders["l"].max and not view.sliders["l"].continuous_update

    view.sliders["l"].value = 3.0                    # as if the user moved the sliders
    view.sliders["g"].value = 5.0
    assert view.runs == 3
    assert view.values == {"m": 10.0, "l": 3.0, "g": 5.0}

    fresh = simulate(ladder, T_END, None, {"m": 10.0, "l": 3.0, "g": 5.0})
    np.testing.assert_allclose(view.result.q["theta"], fresh.q["theta"], rtol=1e-9, atol=1e-12)
    shown, expected = _plotted(view.figure), _plotted(fresh.plot())
    assert [s[0] for s in shown] == [e[0] for e in expected]
    for (label, x, y), (_, xe, ye) in zip(shown, expected):
        np.testing.assert_allclose(x, xe, rtol=1e-9, atol=1e-12, err_msg=label)
        np.testing.assert_allclose(y, ye, rtol=1e-7, atol=1e-9, err_msg=label)
    assert not np.allclose(shown[0][2], first_plot[0][2])       # θ(t) did change with l and g

    png = _png(view.plot_output)                     # the output area holds the new figure, the new animation
    assert png.startswith(b"\x89PNG") and png != first_png
    assert view.plot_output.outputs[0]["data"]["text/plain"] == "time histories, run 3"
    anim = view.animation_output.outputs[0]["data"]["text/html"]
    assert anim != first_anim and view.animation_output.outputs[0]["data"]["text/plain"] == "animation, run 3"
    assert "<script" in anim and "cdnjs" not in anim
    assert "application/vnd.jupyter.widget-view+json" in view._repr_mimebundle_()


def test_a_refused_value_is_said_and_the_figures_stay(ladder):
    pytest.importorskip("ipywidgets")
    from rigidkin.report.widgets import explore

    view = explore(ladder.solve(), t_final=T_END, animation=False, parameters=["l"], ranges={"l": (-1.0, 4.0)})
    assert list(view.sliders) == ["l"] and view.sliders["l"].min == -1.0
    png = _png(view.plot_output)
    view.sliders["l"].value = -0.5                   # a negative length: the simulation refuses the start
    assert view.runs == 1 and _png(view.plot_output) == png
    with pytest.raises(RigidkinError) as refused:
        simulate(ladder, T_END, None, {"l": -0.5})
    assert html.escape(str(refused.value)) in view.status.value and "color:#a00" in view.status.value


def test_stylesheet_shows_tex_in_jupyter_and_mathml_elsewhere(ladder, tmp_path):
    """In headless Chromium: inside a JupyterLab output (.jp-RenderedHTMLCommon) the TeX is shown for
    MathJax and the MathML hidden; on a plain page the other way round."""
    import shutil
    import tempfile
    from pathlib import Path

    sync_api = pytest.importorskip("playwright.sync_api", reason="Playwright is not installed")
    chromium = next((p for p in ("/usr/bin/chromium", shutil.which("chromium") or "") if p and Path(p).exists()),
                    None)
    if chromium is None:
        pytest.skip("Chromium is not installed (apt-get install chromium)")
    fragment = _bundle(ladder.solve())["text/html"]
    page_file = tmp_path / "outputs.html"
    page_file.write_text(f'<!DOCTYPE html><html><head><meta charset="utf-8"></head><body>'
                         f'<div id="lab" class="jp-RenderedHTMLCommon jp-RenderedHTML">{fragment}</div>'
                         f'<div id="plain">{fragment}</div></body></html>', encoding="utf-8")
    count = """([root, cls]) => [...document.querySelectorAll(`#${root} .${cls}`)]
                 .map(e => getComputedStyle(e).display !== 'none')"""
    with sync_api.sync_playwright() as p, tempfile.TemporaryDirectory() as profile:
        ctx = p.chromium.launch_persistent_context(profile, executable_path=chromium, headless=True,
                                                   args=["--headless", "--no-sandbox", "--disable-gpu"])
        try:
            page = ctx.new_page()
            page.route("**/*", lambda route: route.continue_() if route.request.url.startswith("file:")
                       else route.abort())
            page.goto(page_file.as_uri())
            shown = {(root, cls): page.evaluate(count, [root, cls])
                     for root in ("lab", "plain") for cls in ("rk-tex", "rk-mathml")}
        finally:
            ctx.close()
    assert len(shown["lab", "rk-tex"]) > 5 and len(shown["lab", "rk-tex"]) == len(shown["lab", "rk-mathml"])
    assert all(shown["lab", "rk-tex"]) and not any(shown["lab", "rk-mathml"])
    assert not any(shown["plain", "rk-tex"]) and all(shown["plain", "rk-mathml"])


@pytest.mark.slow
def test_start_sliders(ladder):
    pytest.importorskip("ipywidgets")
    from rigidkin.report.widgets import explore

    view = explore(ladder, t_final=T_END, animation=False, parameters=[], start=["theta", "dot(theta)"])
    assert not view.sliders and set(view.start_sliders) == {"theta", "dot(theta)"}
    assert view.start_sliders["theta"].value == pytest.approx(ladder.coordinate_info["theta"].initial)
    view.start_sliders["theta"].value = 0.6
    assert view.runs == 2 and view.started == {"theta": 0.6, "dot(theta)": 0.0}
    fresh = simulate(ladder, T_END, {"theta": 0.6, "dot(theta)": 0.0})
    np.testing.assert_allclose(view.result.q["theta"], fresh.q["theta"], rtol=1e-9, atol=1e-12)
    with pytest.raises(RigidkinError, match="names no coordinate"):
        explore(ladder, animation=False, parameters=[], start=["phi"])
