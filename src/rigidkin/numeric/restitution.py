"""The coefficients of restitution a simulation uses: Newton's e of each contact's impacts, and of the jerk
with which each rope or cable that went slack re-tightens (:mod:`.contacts.jerk`)."""

from __future__ import annotations

from collections.abc import Mapping

from ..base.errors import InputError


def restitution_map(system, restitution) -> dict:
    """Name → e for a simulation of ``system``.  ``restitution``: None (each contact's, rope's or cable's
    ``System.restitution``, or 0), a number (e of every contact; the ropes and cables keep theirs), or a dict by
    contact, rope or cable name (the others keep theirs); each e in [0, 1]."""
    kinds = {n: getattr(c, "kind", "") for n, c in system.constraints.items()}
    contacts = [n for n, k in kinds.items() if k == "contact"]
    ropes = [n for n, k in kinds.items() if k in ("rope", "cable")]
    declared = getattr(system, "restitutions", {})
    restitution = {} if restitution is None else restitution      # None: each one's declared e (or 0)
    if isinstance(restitution, Mapping):
        bad = [str(n) for n in restitution if n not in contacts and n not in ropes]
        if bad:
            raise InputError(f"{', '.join(bad)} is not a contact, rope or cable of {system.name}.",
                             where="restitution", hint=f"Contacts: {', '.join(contacts) or 'none'}; ropes and "
                                                       f"cables: {', '.join(ropes) or 'none'}.")
        out = {n: declared.get(n, 0.0) for n in contacts + ropes}
        out.update({n: _number(n, v) for n, v in restitution.items()})
    else:
        out = {n: _number("every contact", restitution) for n in contacts}
        out.update({n: declared.get(n, 0.0) for n in ropes})
    for n, e in out.items():
        if not 0.0 <= e <= 1.0:
            raise InputError(f"the coefficient of restitution of {n} is {e}; it must lie in [0, 1].",
                             where="restitution")
    return out


def _number(name: str, value) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"the coefficient of restitution of {name} must be a number, not {value!r}.",
                         where="restitution", hint="Give e in [0, 1], e.g. restitution={\"floor\": 0.5}.") from None


__all__ = ["restitution_map"]
