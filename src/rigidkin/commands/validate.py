"""``rigidkin validate PROBLEM``: check a problem file (schema, names, expressions, model, kinematics)
without deriving the equations of motion."""

from __future__ import annotations

from ..base.errors import RigidkinError
from ..base.textsafe import terminal_safe
from .common import guarded, load_system, progress, with_file
from .options import add_timeout


def register(sub) -> None:

    p = sub.add_parser("validate", help="check a problem file without solving it")
    p.add_argument("problem", help="a problem file (.toml) or a bundled example name")
    add_timeout(p, 120)
    p.set_defaults(func=run)


def run(args) -> int:

    with progress(f"Reading {args.problem}"):
        system, spec = guarded(args, load_system, args.problem)
    from ..derive.mode import setup_mode

    try:
        with progress("Checking the kinematics and constraints"):
            setup = guarded(args, setup_mode, system)
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    red = setup.reduction
    source = str(spec.path) if spec is not None else f"bundled example {args.problem}"
    indep = ", ".join(q.func.__name__ for q in red.independent) or "none"
    dep = ", ".join(q.func.__name__ for q in red.dependent)

    print(terminal_safe(f"{source}: valid. {system.title}: {len(system.bodies)} bodies, {len(system.coordinate_info)} "
          f"coordinates (independent: {indep}{'; dependent: ' + dep if dep else ''}), "
          f"{len(system.constraints)} constraints, {len(system.loads)} loads"
          + (f", {len(spec.questions)} questions." if spec is not None else ".")))
    return 0
