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

from rigidkin.base.errors import RigidkinError
from rigidkin.numeric.simulate import simulate

T_END = 0.5


def _bundle(obj) -> dict:
    formatter = pytest.importorskip("IPython.core.formatters").DisplayFormatter()
    data, _ = formatter.format(obj)
    return data


def _tex_spans(html_: str) -> list[str]:
    """The TeX of every formula: the alttext of its <math> element."""
    return [html.unescape(a) for a in re.findall(r'<math alttext="([^"]*)"', html_)]


def test_solution_bundle_shows_dots(ladder):
    data = _bundle(ladder.solve())
    assert {"text/html", "text/latex", "text/plain"} <= set(data)
    html_, tex = data["text/html"], data["text/latex"]
    spans = " ".join(_tex_spans(html_))
    assert r"\dot{\theta}" in spans and r"\ddot{\theta}" in spans         # x' = l cos θ θ̇ ; the EOM in θ̈
    assert r"\ddot{\theta}" in tex
    for wrong in ("Derivative", r"\frac{d}{d t}", "theta'", "θ'", r"\theta{\left(t \right)}"):
        assert wrong not in spans and wrong not in tex
    # MathJax leaves the fragment alone; every formula is MathML (its TeX only as the alttext)
    assert 'class="rigidkin tex2jax_ignore mathjax_ignore"' in html_
    assert html_.count("<math ") == len(_tex_spans(html_)) > 5
    assert "\\(" not in html_ and "\\[" not in html_ and "<script" not in html_
    assert not re.search(r"(src|href)=\"https?:", html_)                        # nothing fetched from the network


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


def test_an_exported_notebook_reads_offline(ladder, tmp_path):
    """In headless Chromium with the network cut: the output as nbconvert's HTML export places it (inside
    .jp-RenderedHTMLCommon, on a page whose MathJax from a CDN cannot load) shows every equation as laid-out
    MathML (a θ̈ is a θ with a dot above, a fraction has a numerator above its denominator), and no raw TeX
    is visible."""
    import shutil
    import tempfile
    from pathlib import Path

    sync_api = pytest.importorskip("playwright.sync_api", reason="Playwright is not installed")
    chromium = next((p for p in ("/usr/bin/chromium", shutil.which("chromium") or "") if p and Path(p).exists()),
                    None)
    if chromium is None:
        pytest.skip("Chromium is not installed (apt-get install chromium)")
    fragment = _bundle(ladder.solve())["text/html"]
    cdn = "https://cdnjs.cloudflare.com/ajax/libs/mathjax/2.7.7/MathJax.js?config=TeX-AMS_CHTML-full,Safe"
    page_file = tmp_path / "notebook.html"
    page_file.write_text(f'<!DOCTYPE html><html><head><meta charset="utf-8"><script src="{cdn}"></script></head>'
                         f'<body class="jp-Notebook"><div class="jp-OutputArea-output jp-RenderedHTMLCommon '
                         f'jp-RenderedHTML" data-mime-type="text/html">{fragment}</div></body></html>',
                         encoding="utf-8")
    probe = """() => {
        const maths = [...document.querySelectorAll('math')];
        const box = e => e.getBoundingClientRect();
        const fracs = [...document.querySelectorAll('mfrac')].map(f => box(f.children[0]).bottom
                        <= box(f.children[1]).top + 1);
        const dots = [...document.querySelectorAll('mover')].map(m => box(m.children[1]).bottom
                        <= box(m.children[0]).top + box(m.children[0]).height / 2);
        return {shown: maths.map(m => box(m).width > 5 && box(m).height > 5), fracs, dots,
                text: document.body.innerText};
    }"""
    with sync_api.sync_playwright() as p, tempfile.TemporaryDirectory() as profile:
        ctx = p.chromium.launch_persistent_context(profile, executable_path=chromium, headless=True,
                                                   args=["--headless", "--no-sandbox", "--disable-gpu"])
        try:
            page = ctx.new_page()
            page.route("**/*", lambda route: route.continue_() if route.request.url.startswith("file:")
                       else route.abort())
            page.goto(page_file.as_uri())
            seen = page.evaluate(probe)
        finally:
            ctx.close()
    assert len(seen["shown"]) > 5 and all(seen["shown"])
    assert seen["fracs"] and all(seen["fracs"]) and seen["dots"] and all(seen["dots"])
    for tex in ("\\frac", "\\ddot", "\\theta", "\\[", "\\("):
        assert tex not in seen["text"]
    assert "θ" in seen["text"] or "\U0001d703" in seen["text"]              # θ, drawn as mathematical italic


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
