"""Accessibility of the HTML report, checked by axe-core (Deque's engine, bundled by axe-playwright-python) in
headless Chromium: ``rigidkin report ladder --simulate 3`` — formulas, tables, free-body diagrams and the
animation player — has no violation of the WCAG rules axe-core tests (labels, contrast, header scopes, alt
text, ...).  Skipped, with the reason, where Chromium, Playwright or axe-playwright-python is missing."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import pytest

from rigidkin.cli import main

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = next((p for p in ("/usr/bin/chromium", shutil.which("chromium") or "") if p and Path(p).exists()), None)
playwright = pytest.importorskip("playwright.sync_api", reason="Playwright (pip install playwright) is not installed")
axe_sync = pytest.importorskip("axe_playwright_python.sync_playwright",
                               reason="axe-playwright-python (pip install axe-playwright-python) is not installed")
pytestmark = [pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (apt-get install chromium)"),
              pytest.mark.slow]


def test_report_has_no_axe_violation(tmp_path):
    out = tmp_path / "ladder.html"
    assert main(["report", "ladder", "-o", str(out), "--simulate", "3"]) == 0
    with playwright.sync_playwright() as p, tempfile.TemporaryDirectory() as profile:
        ctx = p.chromium.launch_persistent_context(profile, executable_path=CHROMIUM, headless=True,
                                                   args=["--headless", "--no-sandbox", "--disable-gpu"])
        try:
            page = ctx.new_page()
            page.route("http*://**", lambda route: route.abort())       # no network: the report stands alone
            page.goto(out.as_uri())
            result = axe_sync.Axe().run(page)
        finally:
            ctx.close()
    assert result.response["passes"], "axe-core ran no rule at all"
    found = [(v["id"], v["impact"], [n["target"] for n in v["nodes"]][:3]) for v in result.response["violations"]]
    assert found == [], found
