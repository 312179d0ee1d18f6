"""The HTML report reads for everyone: text contrast at WCAG 2 level AA, table headers with their scope, an
animation with a text alternative.

The contrast is computed here by WCAG 2.1's own definition (relative luminance of sRGB, (L1 + 0.05)/(L2 + 0.05))
for every rule of the page's style sheet that sets a text colour, against the background it is drawn on.
(tests/test_report_browser.py renders the page in Chromium; an axe-core run would need npm and the network.)
"""

from __future__ import annotations

import re

import pytest

from rigidkin.report.blocks import Animation, Math, Table
from rigidkin.report.html import STYLE, block_html

WHITE, PAGE, HEADER, TH = "#ffffff", "#fafafa", "#1f3b5c", "#eef2f7"
# the background each rule's text is drawn on (sections are white on the page's #fafafa)
ON = {"body": PAGE, "header": HEADER, "nav a": HEADER, "h2": WHITE, ".law": WHITE, ".why": WHITE,
      "figcaption": WHITE, "th": TH}


def _luminance(colour: str) -> float:
    colour = {"white": "#ffffff", "black": "#000000"}.get(colour, colour).lstrip("#")
    if len(colour) == 3:
        colour = "".join(c * 2 for c in colour)
    channels = [int(colour[i:i + 2], 16) / 255 for i in (0, 2, 4)]
    lin = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in channels]
    return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]


def contrast(a: str, b: str) -> float:
    la, lb = sorted((_luminance(a), _luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


def test_the_contrast_formula_by_hand():
    assert contrast("#000", "#fff") == pytest.approx(21.0)
    assert contrast("#777777", "#ffffff") == pytest.approx(4.48, abs=0.01)      # the old grey tag: just under
    assert contrast("#767676", "#ffffff") == pytest.approx(4.54, abs=0.01)      # the lightest grey that passes


def test_every_text_colour_of_the_report_passes_aa():
    rules = dict(re.findall(r"([^{}]+?)\s*\{([^}]*)\}", STYLE))
    checked = 0
    for selector, body in rules.items():
        m = re.search(r"(?<![-\w])color:\s*(#[0-9a-fA-F]{3,6}|white|black)", body)
        if not m:
            continue
        selector = selector.strip()
        assert selector in ON, f"say what {selector!r} is drawn on"
        assert contrast(m.group(1), ON[selector]) >= 4.5, (selector, m.group(1), contrast(m.group(1), ON[selector]))
        checked += 1
    assert checked >= 6


def test_table_headers_have_their_scope_and_the_animation_its_text():
    import sympy as sp

    html = block_html(Table(("quantity", "value"), (("N_A", Math(sp.Symbol("x"))),), "Reactions"))
    assert html.count('<th scope="col">') == 2 and "<th>" not in html
    player = '<div class="animation"><img id="_anim_img1"><div class="anim-buttons"></div></div>'
    html = block_html(Animation("sim", player, None, "The ladder slides down the wall and leaves it."))
    alt = re.search(r'<img alt="([^"]+)" id="_anim_img1">', html)
    assert alt and "ladder slides down the wall" in alt.group(1)
