"""Errors rigidkin raises: one clear paragraph that names the problem, where it is, and what to do.

Every error carries ``where`` (a file and line, a field path such as ``bodies.rod.center``, or the
name of a body, constraint or load) and ``hint`` (what the user can do about it).  ``str(error)``
joins them into a single paragraph; the command line prints that paragraph and never a traceback.
"""

from __future__ import annotations


class RigidkinError(Exception):
    """Base of every error rigidkin raises on purpose."""

    def __init__(self, message: str, *, where: str | None = None, hint: str | None = None):
        self.message = message.strip()
        self.where = where
        self.hint = hint
        super().__init__(str(self))

    def __str__(self) -> str:
        text = f"{self.where}: {self.message}" if self.where else self.message
        if self.hint:
            text += f" {self.hint.strip()}"
        return text


class ModelError(RigidkinError):
    """The description of the system is inconsistent (unknown name, wrong kind of object, bad value)."""


class ConstraintError(ModelError):
    """The constraints leave the system over- or under-determined, or the unknowns cannot be solved."""


class RegimeError(RigidkinError):
    """A question needs one regime (friction direction, contact state) but the solution has several."""


class InputError(RigidkinError):
    """A problem file or an expression in it is malformed or unsafe."""
