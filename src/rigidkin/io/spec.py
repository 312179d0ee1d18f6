"""What a problem file says beyond the system (its source, its questions): :class:`ProblemSpec`.

Kept apart from the reader (:mod:`rigidkin.io.problem`, which loads the schema and pydantic) so that a
problem read back from the derivation cache needs neither.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from ..analysis.questions import Question
from .expressions import Scope, default_scope
from .locate import Locator

if TYPE_CHECKING:
    from . import schema as S


@dataclass
class ProblemSpec:
    """What a problem file says beyond the system: its source, and what it asks."""

    path: Path
    name: str
    title: str
    statement: str
    eom: bool = True
    reactions: tuple[str, ...] | None = None
    questions: tuple[Question, ...] = ()
    scope: Scope = field(default_factory=default_scope, repr=False)
    locator: Locator | None = field(default=None, repr=False)
    data: S.ProblemFile | None = field(default=None, repr=False)
    #: The warnings said while the file was read (a parameter with no unit ...): said again when the problem is
    #: read back from the derivation cache.
    reading_warnings: tuple[str, ...] = ()

    def where(self, *path) -> str:
        """``"file.toml, line 12, bodies.rod.at"`` for a field path."""
        return self.locator.where(path) if self.locator else str(self.path)


# building -----------------------------------------------------------------------------------------------
