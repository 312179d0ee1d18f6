"""Acceptance: ``rigidkin report examples/ladder.toml -o ladder.html --simulate 3`` opened in headless Chromium.

The page must open with no network (every request other than the file itself is refused and
recorded), show every section, render its formulas as MathML laid out by the browser (no raw
TeX), play its animation, and log no console error.  Screenshots go to ``test-artifacts/``.
Skipped, with the reason, where Chromium (Debian's ``chromium``) or Playwright is not installed.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import pytest

from rigidkin.cli import main
from rigidkin.report import REPORT_SECTIONS

ROOT = Path(__file__).resolve().parents[1]
ARTIFACTS = ROOT / "test-artifacts"
CHROMIUM = next((p for p in ("/usr/bin/chromium", shutil.which("chromium") or "") if p and Path(p).exists()), None)
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--no-first-run"]

playwright = pytest.importorskip("playwright.sync_api", reason="Playwright (pip install playwright) is not installed")
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (apt-get install chromium)")


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
