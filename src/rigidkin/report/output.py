"""Writing a report to a file: the format from the file's extension (.html, .md, .tex).

Every file is written through :mod:`rigidkin.base.outfile`: whole or not at all (a full disk or a size
limit leaves the previous report as it was), written through to a device or ``/dev/stdout``.

An HTML report is one file.  Markdown and LaTeX reports put their figures (PNG) and the animation
(GIF) in a folder beside the document, ``<name>_files/``, and refer to them by relative path; the
names of those files are plain (letters, digits, ``. _ -``: no folder, no ``..``).
"""

from __future__ import annotations

from pathlib import Path

from ..base.errors import InputError
from ..base.outfile import write_bytes, write_text
from ..base.textsafe import safe_filename
from .blocks import Animation, Document, Figure
from .document import build_document
from .html import to_html
from .latex import to_latex
from .markdown import to_markdown

FORMATS = {".html": "html", ".htm": "html", ".md": "markdown", ".markdown": "markdown", ".tex": "latex"}


def format_of(path) -> str:
    fmt = FORMATS.get(Path(path).suffix.lower())
    if fmt is None:
        raise InputError(f"cannot tell the report format from '{path}'.", where="report output",
                         hint="Name the output file with one of the extensions .html, .md or .tex.")
    return fmt


def render(doc: Document, fmt: str, files: dict | None = None) -> str:
    """The document as text in ``fmt`` ("html", "markdown" or "latex")."""
    if fmt == "html":
        return to_html(doc)
    if fmt == "markdown":
        return to_markdown(doc, files)
    if fmt == "latex":
        return to_latex(doc, files)
    raise InputError(f"unknown report format '{fmt}'.", hint="Use html, markdown or latex.")


def write_document(doc: Document, path) -> Path:
    """Write ``doc`` to ``path`` (and its figures beside it for Markdown and LaTeX)."""
    path = Path(path)
    fmt = format_of(path)
    files: dict = {}
    if fmt != "html":
        assets = path.with_name(safe_filename(path.stem, "report") + "_files")     # named in the document: plain
        for sec in doc.sections:
            for b in sec.blocks:
                if isinstance(b, Figure):
                    assets.mkdir(parents=True, exist_ok=True)
                    name = safe_filename(b.key, "figure") + ".png"
                    write_bytes(assets / name, b.png, "a figure of the report")
                    files[b.key] = f"{assets.name}/{name}"
                elif isinstance(b, Animation) and b.gif:
                    assets.mkdir(parents=True, exist_ok=True)
                    name = "animation-" + safe_filename(b.key, "motion") + ".gif"
                    write_bytes(assets / name, b.gif, "the animation of the report")
                    files[f"animation-{b.key}"] = f"{assets.name}/{name}"
    write_text(path, render(doc, fmt, files), "the report")      # whole or not at all: the old report kept
    return path


def write_report(solution, path, simulation=None, answers=None, figures: bool = True, animation: bool = True,
                 checks: bool = True, values=None) -> Path:
    """Build the report of ``solution`` (see :func:`build_document`) and write it to ``path``."""
    fmt = format_of(path)
    doc = build_document(solution, simulation=simulation, answers=answers, figures=figures, animation=animation,
                         checks=checks, values=values, gif=fmt != "html")
    return write_document(doc, path)
