"""Markdown of a report, with LaTeX math (``$…$`` inline, ``$$…$$`` displayed).

Figures are written beside the Markdown file (``figures`` maps a figure key to its relative path)
or, without a place for them, embedded as data URIs; the animation is linked as a GIF.  Every piece of
text is escaped (:func:`rigidkin.base.textsafe.markdown_text`): no raw HTML, link or emphasis of a user's
title or description gets through; names inside formulas are escaped by the LaTeX printer.
"""

from __future__ import annotations

import base64

from ..base.textsafe import markdown_text
from .blocks import Animation, Document, Equations, Figure, Math, Paragraph, Step, Table
from .notation import latex, latex_condition


def _tex(m: Math) -> str:
    s = latex_condition(m.obj, m.relation) if m.relation is not None else latex(m.obj)
    return s.replace("|", r"\vert ")


def _cell(c) -> str:
    if isinstance(c, Math):
        return f"${_tex(c)}$"
    return markdown_text(c)


def _display(items) -> str:
    return "\n".join(f"$$\n{_tex(m)}\n$$" for m in items)


def _block(b, files: dict) -> str:
    if isinstance(b, Paragraph):
        return markdown_text(b.text, inline=False)
    if isinstance(b, Equations):
        return _display(b.items)
    if isinstance(b, Step):
        law = f" *({markdown_text(b.law)})*" if b.law else ""
        parts = [f"#### {markdown_text(b.title)}{law}"]
        if b.equations:
            parts.append(_display(b.equations))
        if b.why:
            parts.append(f"*{markdown_text(b.why)}*")
        return "\n\n".join(parts)
    if isinstance(b, Table):
        head = "| " + " | ".join(markdown_text(c) for c in b.columns) + " |\n|" + "---|" * len(b.columns)
        rows = "\n".join("| " + " | ".join(_cell(c) for c in r) + " |" for r in b.rows)
        cap = f"**{markdown_text(b.caption)}**\n\n" if b.caption else ""
        return f"{cap}{head}\n{rows}"
    if isinstance(b, Figure):
        src = files.get(b.key) or "data:image/png;base64," + base64.b64encode(b.png).decode("ascii")
        return f"![{markdown_text(b.alt or b.key)}]({src})\n\n*{markdown_text(b.caption)}*"
    if isinstance(b, Animation):
        src = files.get(f"animation-{b.key}")
        if src:
            return f"![animation]({src})\n\n*{markdown_text(b.caption)}*"
        return f"*{markdown_text(b.caption)} (the animation is in the HTML report).*"
    raise TypeError(f"unknown block {b!r}")


def to_markdown(doc: Document, files: dict | None = None) -> str:
    files = files or {}
    out = [f"# {markdown_text(doc.title)}", f"*{markdown_text(doc.subtitle)}*"]
    for i, s in enumerate(doc.sections):
        out.append(f"## {i + 1}. {markdown_text(s.title)}")
        out.extend(_block(b, files) for b in s.blocks)
    return "\n\n".join(out) + "\n"
