"""``rigidkin report PROBLEM -o out.html|out.md|out.tex [--simulate T]``: the derivation as a document.

The format follows the output's extension.  The HTML page is one self-contained file (MathML,
inline figures, an inline animation player); Markdown and LaTeX put their figures in a folder
``<name>_files/`` beside the document.
"""

from __future__ import annotations

from ..base.errors import InputError, RigidkinError
from ..base.outfile import OutputError, check_outputs, check_target, writing
from ..base.textsafe import terminal_safe
from ..io.load import value
from ..report.blocks import Animation
from .common import guarded, open_problem, problem_inputs, progress, with_file
from .options import add_no_cache, add_timeout, end_time
from .quantities import checked_values, units_of
from .solve import answer_questions, check_declared_start


def register(sub) -> None:

    p = sub.add_parser("report", help="write the step-by-step derivation as HTML, Markdown or LaTeX",
                       description="Write the derivation of a problem (frames, kinematics, free-body diagrams, "
                                   "balance laws, solving, answers, checks) as a document; with --simulate, add "
                                   "time histories, a phase portrait and an animation of the motion.")
    p.add_argument("problem", help="a problem file (.toml) or a bundled example name")
    p.add_argument("-o", "--output", required=True, help="output file: .html, .md or .tex")
    p.add_argument("--simulate", type=end_time, metavar="T",
                   help="simulate from t = 0 to T (seconds, or a time with its unit: '500 ms') and show it")
    p.add_argument("--method", default="newton-euler", help="the balance law (default newton-euler)")
    p.add_argument("--mode", nargs="+", action="extend", default=[], metavar="CONTACT=STATE",
                   help="state of a contact (open, slip, stick) for the derivation")
    p.add_argument("--at", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="coordinate value of the configuration the free-body diagrams show (default: initial)")
    p.add_argument("--gif", metavar="PATH", help="also write the animation as a GIF (needs --simulate)")
    p.add_argument("--initial", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="initial coordinate or rate for the simulation (theta=0.1, dot(theta)=0; units allowed)")
    p.add_argument("--set", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="parameter value for the simulation and the figures (units allowed: beta=30 deg)")
    p.add_argument("--no-figures", action="store_true", help="leave out the figures and the animation")
    p.add_argument("--no-animation", action="store_true", help="leave out the animation")
    p.add_argument("--no-checks", action="store_true", help="do not run the cross-check by other laws")
    p.add_argument("--no-answers", action="store_true", help="do not answer the problem file's questions")
    add_no_cache(p)
    add_timeout(p)
    p.set_defaults(func=run)


def _pairs(items, what: str) -> dict:
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name.strip() or not value.strip():
            raise InputError(f"'{item}' is not of the form NAME=VALUE.", where=what,
                             hint="Write, e.g., --at theta=0.6 or --mode A=open.")
        out[name.strip()] = value.strip()
    return out


def _numbers(pairs: dict, what: str) -> dict:

    return {k: v if isinstance(v, float) else value(v, f"{what} {k}") for k, v in pairs.items()}


def run(args) -> int:
    from ..report.document import build_document
    from ..report.output import format_of, write_document

    fmt = format_of(args.output)
    check_target(args.output, "the report")
    if args.gif:
        check_target(args.gif, "the animation", (".gif",))
    check_outputs({"-o": args.output, "--gif": args.gif}, problem_inputs(args))
    if args.gif and args.simulate is None:
        raise InputError("--gif needs a simulation to animate.", where="report --gif",
                         hint="Add --simulate T (seconds).")
    if args.simulate is not None and not args.simulate > 0:
        raise InputError(f"--simulate needs a positive end time, not {args.simulate}.", where="report --simulate")
    if args.initial and args.simulate is None:
        raise InputError("--initial sets the start of a simulation.", where="report --initial",
                         hint="Add --simulate T (seconds).")
    mode = _pairs(args.mode, "report --mode")
    at = _pairs(args.at, "report --at")
    params = _pairs(args.set, "report --set")
    initial = _pairs(args.initial, "report --initial")
    with progress(f"Reading {args.problem}"):
        derived = guarded(args, open_problem, args)
    system, spec = derived.system, derived.spec
    units = units_of(system)
    at = _numbers(checked_values(at, units, "report --at"), "report --at")
    initial = checked_values(initial, units, "report --initial")
    try:
        with progress(f"Deriving the equations of motion ({args.method})"):
            solution = guarded(args, system.solve, method=args.method, mode=mode)
        check_declared_start(args, system, spec, mode)     # the declared start, by simulate's rule
        answers, _ = answer_questions(system, spec, args, derived)
        result = None
        if args.simulate is not None:
            from ..numeric.simulate import simulate

            with progress(f"Simulating to t = {args.simulate:g} s"):
                result = guarded(args, simulate, system, (0.0, args.simulate), initial_state=initial or None,
                                 params=params or None)
        figures = not args.no_figures
        with progress("Writing the report (figures, cross-check, animation)"):
            doc = guarded(args, build_document, solution, simulation=result, answers=answers, figures=figures,
                          animation=figures and not args.no_animation, checks=not args.no_checks,
                          values=at or None, gif=fmt != "html" or bool(args.gif),
                          parameters=_numbers(params, "report --set") or None)
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    derived.save()
    try:
        path = write_document(doc, args.output)
    except OSError as exc:
        raise OutputError(f"cannot write the report to {args.output}: {exc.strerror or exc}.") from None
    print(terminal_safe(f"wrote {path}"))
    if args.gif:
        gifs = [b.gif for s in doc.sections for b in s.blocks if isinstance(b, Animation) and b.gif]
        if not gifs:
            raise InputError("there is no animation to write as a GIF.", where="report --gif",
                             hint="Leave out --no-figures and --no-animation.")
        with writing(args.gif, "the animation", binary=True) as f:
            f.write(gifs[0])
        print(terminal_safe(f"wrote {args.gif}"))
    return 0
