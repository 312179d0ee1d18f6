"""A self-contained HTML page of a report: native MathML, inline figures, an inline animation player.

Everything the page shows is inside the one file: formulas are presentation MathML (rendered by the
browser itself, no script), figures are PNG data URIs, the animation is matplotlib's HTML5 player
with its frames embedded.  A content security policy forbids every fetch, so the page cannot reach
the network even by accident, and forbids every script unless the page holds the animation player.
Every piece of text is escaped (:func:`rigidkin.base.textsafe.html_text`), formulas' text too
(:mod:`rigidkin.report.notation`).
"""

from __future__ import annotations

import base64
import re
from functools import cache
from importlib import resources

from ..base.textsafe import html_text
from .blocks import Animation, Document, Equations, Figure, Math, Paragraph, Step, Table
from .notation import mathml, mathml_condition

CSP = "default-src 'none'; img-src data:; font-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'"
#: The policy of a page without an animation: no script at all.
CSP_NO_SCRIPT = "default-src 'none'; img-src data:; font-src data:; style-src 'unsafe-inline'"
#: The math font the page embeds (a subset of STIX Two Math, OFL; see report/assets/README.md).
MATH_FONT = "STIXTwoMath-subset.woff2"

STYLE = """
body { font-family: "DejaVu Serif", Georgia, serif; margin: 0; color: #1b1b1b; background: #fafafa; }
header { background: #1f3b5c; color: white; padding: 1.2em 2em; }
header h1 { margin: 0 0 .2em 0; font-size: 1.7em; }
header .subtitle { margin: 0; opacity: .85; }
nav { font-family: "DejaVu Sans", sans-serif; font-size: .9em; margin-top: .8em; }
nav a { color: #d6e4f5; margin-right: 1em; text-decoration: none; white-space: nowrap; display: inline-block; }
main { max-width: 60em; margin: 0 auto; padding: 1em 2em 4em 2em; }
section { background: white; border: 1px solid #e2e2e2; border-radius: 6px; padding: .6em 1.4em 1em 1.4em;
          margin: 1.2em 0; }
h2 { color: #1f3b5c; border-bottom: 2px solid #c9d6e8; padding-bottom: .2em; }
h3 { font-size: 1.05em; margin: 1.1em 0 .3em 0; }
.law { font-family: "DejaVu Sans", sans-serif; font-size: .7em; color: #5c5c5c; font-weight: normal;
       margin-left: .6em; }
.step { border-left: 3px solid #c9d6e8; padding-left: .9em; margin: .6em 0 1em 0; }
.why { color: #444; font-style: italic; margin: .3em 0; }
.eqs { overflow-x: auto; }
math[display="block"] { margin: .35em 0; font-size: 1.08em; }
td math { font-size: 1.1em; }
math { font-family: "RigidkinMath", math; }
table { border-collapse: collapse; margin: .8em 0; font-size: .95em; }
caption { text-align: left; font-weight: bold; padding: .3em 0; }
th, td { border: 1px solid #d4d4d4; padding: .3em .6em; vertical-align: top; text-align: left; }
th { background: #eef2f7; }
figure { margin: 1em 0; text-align: center; }
figure img { max-width: 100%; }
figcaption { font-size: .9em; color: #444; margin-top: .3em; }
.animation { display: inline-block; }
.anim-buttons button { font-size: 1em; min-width: 2.2em; }
"""

# matplotlib's player names Font Awesome icons; the page draws them as characters instead (no fetch)
_ICONS = {"fa-minus": "\u2212", "fa-fast-backward": "\u21e4", "fa-step-backward": "\u25c1",
          "fa-play fa-flip-horizontal": "\u25c0", "fa-pause": "\u2016", "fa-play": "\u25b6",
          "fa-step-forward": "\u25b7", "fa-fast-forward": "\u21e5", "fa-plus": "+"}


def offline_player(player: str) -> str:
    """matplotlib's HTML5 animation player without its stylesheet link to a CDN (icons as characters)."""
    player = re.sub(r"<link[^>]*font-awesome[^>]*>", "", player)
    for cls, ch in _ICONS.items():
        player = player.replace(f'<i class="fa {cls}"></i>', f'<span class="icon">{ch}</span>')
    # its frame slider and its loop-mode buttons named for a screen reader (axe-core: form elements need labels)
    player = re.sub(r'<input(?![^>]*aria-label)(?=[^>]*id="_anim_slider)', '<input aria-label="animation frame"',
                    player)
    return player


@cache
def math_font_css() -> str:
    """An ``@font-face`` rule that embeds the bundled math font as a ``data:`` URI.

    Browsers place an accent (θ̇, θ̈, x̂, x̄) above its letter by the font's OpenType MATH table; with
    no math font installed, Chromium draws the dots into the letter or not at all.
    """
    data = resources.files("rigidkin.report").joinpath("assets", MATH_FONT).read_bytes()
    b64 = base64.b64encode(data).decode("ascii")
    return f'@font-face {{ font-family: "RigidkinMath"; src: url(data:font/woff2;base64,{b64}) format("woff2"); }}'


def animation_alt(b: Animation) -> str:
    """The text alternative of an animation's frames (what a screen reader says): its caption."""
    return f"Animation, one frame at a time: {b.caption}".strip()


def _esc(s: str) -> str:
    return html_text(s)


def _math(m: Math, display: bool) -> str:
    if m.relation is not None:
        inner = mathml_condition(m.obj, m.relation)
        return inner.replace("<math ", '<math display="block" ', 1) if display else inner
    return mathml(m.obj, display=display)


def block_html(b, math=None, heading: str = "h3", anchors: bool = True) -> str:
    """One block of a document as HTML; ``math(m, display)`` writes a formula (MathML by default),
    ``heading`` is the step titles' element, ``anchors`` gives figures an id to link to."""
    math = math or _math

    def cell(c) -> str:
        return math(c, False) if isinstance(c, Math) else _esc(c)

    if isinstance(b, Paragraph):
        return f"<p>{_esc(b.text)}</p>"
    if isinstance(b, Equations):
        return '<div class="eqs">' + "".join(math(m, True) for m in b.items) + "</div>"
    if isinstance(b, Step):
        law = f'<span class="law">{_esc(b.law)}</span>' if b.law else ""
        eqs = '<div class="eqs">' + "".join(math(m, True) for m in b.equations) + "</div>" if b.equations else ""
        why = f'<p class="why">{_esc(b.why)}</p>' if b.why else ""
        return f'<div class="step"><{heading}>{_esc(b.title)}{law}</{heading}>{eqs}{why}</div>'
    if isinstance(b, Table):
        head = "".join(f'<th scope="col">{_esc(c)}</th>' for c in b.columns)
        rows = "".join("<tr>" + "".join(f"<td>{cell(c)}</td>" for c in r) + "</tr>" for r in b.rows)
        cap = f"<caption>{_esc(b.caption)}</caption>" if b.caption else ""
        return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>"
    if isinstance(b, Figure):
        data = base64.b64encode(b.png).decode("ascii")
        fid = f' id="fig-{_esc(b.key)}"' if anchors else ""
        return (f'<figure{fid}><img src="data:image/png;base64,{data}" alt="{_esc(b.alt)}">'
                f"<figcaption>{_esc(b.caption)}</figcaption></figure>")
    if isinstance(b, Animation):
        aid = f' id="animation-{_esc(b.key)}" class="animation-figure"' if anchors else ""
        player = offline_player(b.html).replace("<img id=", f'<img alt="{_esc(animation_alt(b))}" id=', 1)
        return f"<figure{aid}>{player}<figcaption>{_esc(b.caption)}</figcaption></figure>"
    raise TypeError(f"unknown block {b!r}")


def to_html(doc: Document) -> str:
    """The whole page as a string."""
    nav = "".join(f'<a href="#{_esc(s.key)}">{i + 1}. {_esc(s.title)}</a>' for i, s in enumerate(doc.sections))
    body = []
    for i, s in enumerate(doc.sections):
        blocks = "\n".join(block_html(b) for b in s.blocks)
        body.append(f'<section id="{_esc(s.key)}"><h2>{i + 1}. {_esc(s.title)}</h2>\n{blocks}\n</section>')
    scripts = any(isinstance(b, Animation) for s in doc.sections for b in s.blocks)
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f'<meta http-equiv="Content-Security-Policy" content="{CSP if scripts else CSP_NO_SCRIPT}">'
            '<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{_esc(doc.title)}</title><style>{math_font_css()}{STYLE}</style></head>\n<body>"
            f'<header><h1>{_esc(doc.title)}</h1><p class="subtitle">{_esc(doc.subtitle)}</p><nav>{nav}</nav></header>'
            f"<main>\n" + "\n".join(body) + "\n</main></body></html>\n")
