"""``rigidkin solve PROBLEM``: equations of motion, reactions and the answers a problem file asks for."""

from __future__ import annotations

import json
import warnings

from ..base.errors import RigidkinError
from ..base.textsafe import terminal_safe
from ..derive.laws import METHODS
from ..io.derivation_cache import read_output, write_output
from .common import guarded, json_safe, open_problem, progress, source_of, with_file
from .options import EXIT_UNANSWERED, add_no_cache, add_timeout, parse_modes


def register(sub) -> None:

    p = sub.add_parser("solve", help="derive the equations of motion, reactions and answers")
    p.add_argument("problem", help="a problem file (.toml) or a bundled example name (see 'rigidkin list')")
    p.add_argument("--method", default="newton-euler",
                   help=f"the balance law to derive with: {', '.join(METHODS)} (about-point:POINT names the point; "
                        "default newton-euler)")
    p.add_argument("--format", default="text", choices=("text", "latex", "markdown", "json"),
                   help="output format: latex and markdown say all the text does (accelerations, conditions, numbers)")
    p.add_argument("--no-answers", action="store_true", help="skip the questions in the file's [ask]")
    p.add_argument("--mode", nargs="+", action="extend", default=[], metavar="CONTACT=STATE",
                   help="the state of a contact: open, slip or stick (repeatable); a mode at rest (every "
                        "contact sticking) gives the reactions of statics, and names those that statics leaves "
                        "indeterminate (two supports that both hold a body from slipping share their friction: "
                        "only the sum is given)")
    add_no_cache(p)
    add_timeout(p)
    p.set_defaults(func=run)


def answer_questions(system, spec, args, derived=None) -> tuple[dict, list[str]]:
    """Answer the file's questions in order; a question that cannot be answered gets its reason.

    With ``derived`` (a :class:`rigidkin.io.derivation_cache.CachedProblem`) the answers are read from it when
    cached, and kept in it when every question was answered."""

    questions = spec.questions if spec is not None else ()
    if not questions or args.no_answers:
        return {}, []
    if derived is not None and derived.answers is not None:
        return dict(derived.answers), []
    try:
        from ..analysis.answers import answer
    except ImportError:
        return {}, ["Answers are not available in this version of rigidkin; the questions in [ask] were read "
                    "and checked but not answered."]
    answers, context = {}, {}
    for q in questions:
        try:
            with progress(f"Answering {q.name}"):
                a = guarded(args, answer, system, q, context)
        except RigidkinError as exc:
            answers[q.name] = str(exc)
            continue
        context[q.name] = a
        answers[q.name] = a
    if derived is not None and not any(isinstance(a, str) for a in answers.values()):
        derived.answers = dict(answers)        # a failed answer (a time limit, say) is not kept
    return answers, []


def run(args) -> int:
    """Exit status 0, or 1 (EXIT_UNANSWERED) when a question of the file could not be answered.

    A solve printed before for the same file and options is printed again from the cache at once."""

    use = not args.no_cache
    options = ("solve", args.method, args.format, bool(args.no_answers), tuple(args.mode))
    kept = read_output(source_of(args), options, use)
    if kept is not None:
        print(kept["text"])
        return kept["status"]
    shown = []
    show = warnings.showwarning
    warnings.showwarning = lambda *a, **kw: (shown.append(a[0]), show(*a, **kw))
    try:
        text, status = _solve(args)
    finally:
        warnings.showwarning = show
    print(text)
    if status == 0 and not shown:       # a warning, or a question left unanswered, is said again next time
        write_output(source_of(args), options, text, status, use)
    return status


def _solve(args) -> tuple[str, int]:
    from ..io.results import solution_data
    from ..report.text import problem_text

    with progress(f"Reading {args.problem}"):
        derived = guarded(args, open_problem, args)
    system, spec = derived.system, derived.spec
    try:
        with progress(f"Deriving the equations of motion ({args.method})"):
            sol = guarded(args, system.solve, method=args.method, mode=parse_modes(args.mode))
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    check_declared_start(args, system, spec, parse_modes(args.mode))
    answers, notes = answer_questions(system, spec, args, derived)
    try:
        with progress("Writing the solution"):
            if args.format == "json":
                text = json_safe(json.dumps(guarded(args, solution_data, sol, spec, answers, notes), indent=2,
                                            ensure_ascii=False))
            elif args.format in ("latex", "markdown"):
                from . import solve_formats

                write = solve_formats.to_latex if args.format == "latex" else solve_formats.to_markdown
                text = terminal_safe(guarded(args, write, sol, spec, answers, notes))
            else:
                text = terminal_safe(guarded(args, problem_text, sol, spec, answers, notes))
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    derived.save()              # after the text: what writing it computed (the power check) is kept too
    unanswered = [name for name, a in answers.items() if isinstance(a, str)]
    return text, EXIT_UNANSWERED if unanswered else 0


def check_declared_start(args, system, spec, mode=None) -> None:
    """The declared starting state put onto the constraints (numeric.starts), or the one-paragraph refusal."""
    from ..numeric.starts import declared_start

    try:
        moved = guarded(args, declared_start, system, mode)
    except RigidkinError as exc:
        raise with_file(exc, spec) from None
    if moved:                   # a warning: said on stderr, and the output is not kept for a repeat
        warnings.warn("the declared starting state is not on the constraints; it is assembled onto them (Newton's "
                      "method from the declared values): " + ", ".join(
                          f"{nm} = {b:.10g} (declared {a:.10g})" for nm, (a, b) in moved.items()), RuntimeWarning,
                      stacklevel=2)
