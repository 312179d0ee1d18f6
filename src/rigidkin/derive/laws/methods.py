"""The names of the balance laws, and what a law says when it does not apply.

The vocabulary every law module and the dispatcher share: ``METHODS`` (newton-euler, about-point:P,
work-energy, lagrange, kane), ``parse_method`` (a method as written → its law and the point for the
moments), and ``NotApplicable`` (this law does not give the equations of motion of this system or mode,
for the reason it states; another law may).  It imports no law, so each law imports it without running
the dispatcher.
"""

from __future__ import annotations

from ...base.errors import ModelError

METHODS = ("newton-euler", "about-point", "work-energy", "lagrange", "kane")


class NotApplicable(ModelError):
    """A law does not apply to this system or mode (the message says why); other laws may."""


def parse_method(method: str, options: dict | None = None) -> tuple[str, dict]:
    """``"about-point:O"`` → ("about-point", {"point": "O"}); other names pass through."""
    options = dict(options or {})
    name = str(method).strip()
    if ":" in name:
        name, _, arg = name.partition(":")
        name = name.strip()
        if name != "about-point":
            raise ModelError(f"the method '{name}' takes no argument (':{arg}').", where="method",
                             hint=f"Use one of: {', '.join(METHODS)} (about-point:POINT).")
        options["point"] = arg.strip()
    if name not in METHODS:
        raise ModelError(f"unknown method '{method}'.", where="method",
                         hint=f"Use one of: {', '.join(METHODS)} (about-point takes a point: about-point:O).")
    if name == "about-point" and not options.get("point"):
        raise ModelError("the about-point law needs the point to take moments about.", where="method",
                         hint="Write about-point:NAME with a point, pin, collar or contact name.")
    return name, options
