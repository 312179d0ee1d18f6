"""The blocks a report is made of — a formula, a paragraph, displayed equations, a recorded step of the
derivation, a table, a figure, an animation — and the document: titled sections of blocks.  Every
renderer (Markdown, LaTeX, HTML, a notebook) reads these; :mod:`rigidkin.report.document` lays a
solution out in them.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Math:
    """A formula: an expression, vector or dyadic, an equation (lhs, rhs), or ``expr relation 0``."""

    obj: object
    relation: str | None = None


@dataclass(frozen=True)
class Paragraph:
    text: str


@dataclass(frozen=True)
class Equations:
    """Displayed formulas, one per line."""

    items: tuple[Math, ...]


@dataclass(frozen=True)
class Step:
    """One recorded step of the derivation: title, formulas, why, and the law that recorded it."""

    title: str
    equations: tuple[Math, ...]
    why: str = ""
    law: str = ""


@dataclass(frozen=True)
class Table:
    """A table whose cells are text (str) or ``Math``."""

    columns: tuple[str, ...]
    rows: tuple[tuple, ...]
    caption: str = ""


@dataclass(frozen=True)
class Figure:
    key: str
    png: bytes
    caption: str
    alt: str = ""


@dataclass(frozen=True)
class Animation:
    key: str
    html: str              # an HTML5 player (matplotlib's to_jshtml: frames and script, no network)
    gif: bytes | None
    caption: str


@dataclass
class Section:
    key: str
    title: str
    blocks: list = field(default_factory=list)


@dataclass
class Document:
    title: str
    subtitle: str
    sections: list[Section]

    def section(self, key: str) -> Section:
        for s in self.sections:
            if s.key == key:
                return s
        raise KeyError(key)
