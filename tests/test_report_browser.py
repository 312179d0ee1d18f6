"""Acceptance: ``rigidkin report examples/ladder.toml -o ladder.html --simulate 3`` opened in headless Chromium.

The page must open with no network (every request other than the file itself is refused and
recorded), show every section, render its formulas as MathML laid out by the browser (no raw
TeX), play its animation, and log no console error.  Screenshots go to ``test-artifacts/``.
Skipped, with the reason, where Chromium (Debian's ``chromium``) or Playwright is not installed.
"""

from __future__ import annotations

import io
import shutil
import tempfile
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from rigidkin.cli import main
from rigidkin.report import REPORT_SECTIONS
from rigidkin.report.html import CSP_NO_SCRIPT, STYLE, math_font_css
from rigidkin.report.notation import mathml

ROOT = Path(__file__).resolve().parents[1]
ARTIFACTS = ROOT / "test-artifacts"
CHROMIUM = next((p for p in ("/usr/bin/chromium", shutil.which("chromium") or "") if p and Path(p).exists()), None)
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--no-first-run"]

playwright = pytest.importorskip("playwright.sync_api", reason="Playwright (pip install playwright) is not installed")
# a report rendered in Chromium takes half a minute on 2 shared cores: CI's slow pass runs it (pytest -m slow)
pytestmark = [pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (apt-get install chromium)"),
              pytest.mark.slow]


@pytest.fixture(scope="module")
def ladder_page(tmp_path_factory):
    out = tmp_path_factory.mktemp("report") / "ladder.html"
    problem = ROOT / "examples" / "ladder.toml"
    assert main(["report", str(problem if problem.exists() else "ladder"), "-o", str(out), "--simulate", "3"]) == 0
    return out


def test_ladder_report_in_chromium(ladder_page):
    ARTIFACTS.mkdir(exist_ok=True)
    console, requests = [], []
    with playwright.sync_playwright() as p, tempfile.TemporaryDirectory() as profile:
        ctx = p.chromium.launch_persistent_context(profile, executable_path=CHROMIUM, headless=True, args=FLAGS,
                                                   viewport={"width": 1100, "height": 1300})
        try:
            page = ctx.new_page()
            page.on("console", lambda m: console.append((m.type, m.text)))
            page.on("pageerror", lambda e: console.append(("pageerror", str(e))))

            def refuse(route):
                if route.request.url != ladder_page.as_uri():
                    requests.append(route.request.url)
                    return route.abort()
                return route.continue_()

            page.route("**/*", refuse)
            page.goto(ladder_page.as_uri(), wait_until="load")
            page.screenshot(path=str(ARTIFACTS / "report-ladder-top.png"))

            # every section, in order
            ids = page.eval_on_selector_all("main > section", "els => els.map(e => e.id)")
            assert ids == [k for k, _ in REPORT_SECTIONS]
            for key, title in REPORT_SECTIONS:
                assert title in page.inner_text(f"section#{key} h2")

            # formulas are MathML the browser lays out as math, not TeX source
            n_math = page.eval_on_selector_all("math", "els => els.length")
            assert n_math > 30
            display = page.evaluate("getComputedStyle(document.querySelector('math[display=block]')).display")
            assert "math" in display, display
            frac_height = page.evaluate("document.querySelector('mfrac').getBoundingClientRect().height")
            line_height = page.evaluate("document.querySelector('mi').getBoundingClientRect().height")
            assert frac_height > 1.5 * line_height > 0          # a fraction is stacked, two lines tall
            text = page.inner_text("main")
            assert "\\frac" not in text and "$$" not in text and "\\dot" not in text

            # figures decoded, animation present and playing
            for fig in ("fig-fbd", "fig-time-histories", "fig-phase-portrait"):
                w = page.evaluate(f"document.querySelector('#{fig} img').naturalWidth")
                assert w > 200, fig
            anim = page.locator("figure.animation-figure")
            assert anim.count() == 1
            slider = anim.locator("input[type=range]")
            assert int(slider.get_attribute("max")) >= 10
            first = anim.locator("img").first.get_attribute("src")
            assert first.startswith("data:image/png;base64,")
            anim.locator("button[title='Play']").click()
            page.wait_for_timeout(600)
            assert int(slider.input_value()) > 0
            assert anim.locator("img").first.get_attribute("src") != first
            anim.scroll_into_view_if_needed()
            page.locator("section#simulation").screenshot(path=str(ARTIFACTS / "report-ladder-simulation.png"))
            page.screenshot(path=str(ARTIFACTS / "report-ladder-full.png"), full_page=True)
        finally:
            ctx.close()
    assert requests == [], f"the page tried to reach: {requests}"
    errors = [c for c in console if c[0] in ("error", "pageerror", "warning")]
    assert errors == [], errors


# accents drawn above their letters ----------------------------------------------------------------
_t = dynamicsymbols._t
_theta, _theta1 = dynamicsymbols("theta theta1")
#: (plain, accented, marks expected above the letter) — each pair printed by the report's own MathML
ACCENT_PAIRS = {
    "dot": (_theta, _theta.diff(_t), 1),
    "ddot": (_theta, _theta.diff(_t, 2), 2),
    "hat": (sp.Symbol("e"), sp.Symbol("e_hat"), 1),
    "bar": (sp.Symbol("x"), sp.Symbol("x_bar"), 1),
    "dot1": (_theta1, _theta1.diff(_t), 1),
}


def _accent_page(size_px: int) -> str:
    rows = "".join(f'<p id="{k}"><span class="plain">{mathml(a)}</span> <span class="acc">{mathml(b)}</span></p>'
                   for k, (a, b, _) in ACCENT_PAIRS.items())
    return ('<!DOCTYPE html><html><head><meta charset="utf-8">'
            f'<meta http-equiv="Content-Security-Policy" content="{CSP_NO_SCRIPT}">'
            f"<style>{math_font_css()}{STYLE} p {{ font-size: {size_px}px; margin: .2em 1em; }}</style></head>"
            f"<body>{rows}</body></html>")


def _runs(flags) -> list[tuple[int, int]]:
    """Runs of consecutive True entries as (first, last) indices."""
    out, start = [], None
    for i, f in enumerate(list(flags) + [False]):
        if f and start is None:
            start = i
        elif not f and start is not None:
            out.append((start, i - 1))
            start = None
    return out


def _ink(png: bytes) -> np.ndarray:
    from PIL import Image
    img = np.asarray(Image.open(io.BytesIO(png)).convert("L"), dtype=float)
    return img < 140


def accent_shots(html: str, artifact: str | None = None) -> dict:
    """For each pair: the ink of its line (as rendered by Chromium) and the columns of the two symbols."""
    with playwright.sync_playwright() as p, tempfile.TemporaryDirectory() as profile:
        ctx = p.chromium.launch_persistent_context(profile, executable_path=CHROMIUM, headless=True, args=FLAGS,
                                                   viewport={"width": 700, "height": 900})
        try:
            page = ctx.new_page()
            console = []
            page.on("console", lambda m: console.append((m.type, m.text)))
            page.set_content(html, wait_until="load")
            page.evaluate("document.fonts.ready")
            fonts = page.evaluate("[...document.fonts].filter(f => f.status === 'loaded').map(f => f.family)")
            if artifact:
                page.screenshot(path=str(ARTIFACTS / artifact))
            shots = {}
            for key in ACCENT_PAIRS:
                row = page.locator(f"p#{key}")
                box = row.bounding_box()
                plain = page.locator(f"p#{key} .plain math").bounding_box()
                acc = page.locator(f"p#{key} .acc math").bounding_box()
                shots[key] = (_ink(row.screenshot()), [int(round(b["x"] - box["x"])) for b in (plain, acc)],
                              [int(round(b["x"] + b["width"] - box["x"])) for b in (plain, acc)])
        finally:
            ctx.close()
    assert not [c for c in console if c[0] in ("error", "warning")], console
    return {"fonts": fonts, "shots": shots}


def check_marks_above(shots: dict) -> None:
    """Above the letter's top (the plain letter's, on the same baseline) there is ink, separated from the
    letter by blank rows; θ̈ has two dots side by side; θ̇₁'s dot stands over the θ, not the subscript."""
    for key, (ink, x0, x1) in shots.items():
        marks = ACCENT_PAIRS[key][2]
        plain, acc = ink[:, x0[0]:x1[0]], ink[:, x0[1]:x1[1]]
        plain_rows = _runs(plain.any(axis=1))
        acc_rows = _runs(acc.any(axis=1))
        assert len(plain_rows) >= 1, key
        letter_top = plain_rows[0][0]
        assert len(acc_rows) >= 2, (key, acc_rows)                 # a mark, blank rows, then the letter
        mark = acc_rows[0]
        assert mark[1] < letter_top - 1, (key, mark, letter_top)   # wholly above the plain letter's top
        assert abs(acc_rows[1][0] - letter_top) <= 2, (key, acc_rows, letter_top)   # the letter where it was
        mark_cols = _runs(acc[mark[0]:mark[1] + 1].any(axis=0))
        assert len(mark_cols) == marks, (key, mark_cols)
        if key == "dot1":       # over the θ, left of the whole symbol's middle (the subscript is right)
            cols = np.nonzero(acc.any(axis=0))[0]
            centre = (mark_cols[0][0] + mark_cols[-1][1]) / 2
            assert centre < (cols[0] + cols[-1]) / 2, (mark_cols, cols[0], cols[-1])


def test_accents_are_marks_above_their_letters():
    """θ̇, θ̈, ê, x̄ and θ̇₁ as the report writes them, in Chromium with the page's embedded math font:
    each accent a separate mark above its letter (in the pixels), at 64 px; a 17 px page is kept to look at."""
    ARTIFACTS.mkdir(exist_ok=True)
    big = accent_shots(_accent_page(64), "accents-64px.png")
    assert "RigidkinMath" in " ".join(big["fonts"]), big["fonts"]
    check_marks_above(big["shots"])
    accent_shots(_accent_page(17), "accents-17px.png")


FIREFOX = shutil.which("firefox-esr") or shutil.which("firefox")


def _placed_page(size_px: int = 64, row: int = 110) -> str:
    """The accent pairs at fixed places (rows at fixed heights, each pair on one baseline in 200 px wide
    boxes from x = 20), for a browser screenshot taken without a driver."""
    box = '<span style="display:inline-block;width:200px">{}</span>'
    cells = "".join(
        f'<div style="position:absolute;top:{20 + row * i}px;left:20px;font-size:{size_px}px;white-space:nowrap">'
        f"{box.format(mathml(a))}{box.format(mathml(b))}</div>" for i, (a, b, _) in enumerate(ACCENT_PAIRS.values()))
    return ('<!DOCTYPE html><html><head><meta charset="utf-8">'
            f'<meta http-equiv="Content-Security-Policy" content="{CSP_NO_SCRIPT}">'
            f"<style>{math_font_css()}{STYLE} body {{ background: white; }}</style></head>"
            f"<body>{cells}</body></html>")


@pytest.mark.skipif(FIREFOX is None, reason="Firefox is not installed (apt-get install firefox-esr)")
def test_accents_are_marks_above_their_letters_in_firefox(tmp_path):
    """The same pixel check in headless Firefox (its own --screenshot, no driver), where it is installed."""
    import subprocess

    page = tmp_path / "accents.html"
    page.write_text(_placed_page(), encoding="utf-8")
    png = ARTIFACTS / "accents-firefox.png"
    ARTIFACTS.mkdir(exist_ok=True)
    env = {"HOME": str(tmp_path), "PATH": "/usr/bin:/bin", "MOZ_HEADLESS": "1"}
    subprocess.run([FIREFOX, "--headless", "--no-remote", "--profile", str(tmp_path), "--window-size=700,700",
                    "--screenshot", str(png), page.as_uri()], env=env, timeout=120, capture_output=True)
    assert png.exists(), "Firefox wrote no screenshot"
    ink = _ink(png.read_bytes())
    shots = {key: (ink[20 + 110 * i:20 + 110 * (i + 1)], [20, 220], [215, 415])
             for i, key in enumerate(ACCENT_PAIRS)}
    check_marks_above(shots)
