"""A coordinate driven by a law of t in a problem file: ``prescribed`` (or ``prescribed_rate``) in [coordinates]."""

from __future__ import annotations

from ..base.errors import InputError


def build_prescribed(builder, name: str, c) -> None:
    """Prescribe the coordinate ``name`` by its law of t (``System.prescribe``), with its effort ``drive_effort``."""
    path = ("coordinates", name)
    if c.prescribed is None and c.prescribed_rate is None:
        if c.drive_effort is not None:
            raise InputError("drive_effort names the effort of a prescribed coordinate.", where=builder.where(*path),
                             hint="Add prescribed = \"...\" (a law of t), or remove drive_effort.")
        return
    if c.prescribed is not None and c.prescribed_rate is not None:
        raise InputError("give the law of the coordinate (prescribed) or of its rate (prescribed_rate), not both.",
                         where=builder.where(*path))
    key = "prescribed" if c.prescribed is not None else "prescribed_rate"
    law = builder.scalar(getattr(c, key), path + (key,))
    q = builder.scope.coordinates[name]
    if c.prescribed is not None:
        builder.call(path, builder.s.prescribe, q, law, None, c.drive_effort)
    else:
        builder.call(path, builder.s.prescribe, q, None, law, c.drive_effort)
