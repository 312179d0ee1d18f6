"""The kinds of value a command-line option takes, one rule per kind, checked when the line is read.

Each function is an argparse ``type=``: it turns the text into a value or refuses it with a message
that names what is wrong and what to write instead.  The parser (:class:`Parser`) prints a refusal
as one paragraph (control characters escaped) and exits with status 2.

Exit statuses of every command (README, "Commands"):

====  ==========================================================================================
0     success
1     a question was left unanswered (``solve``), or the laws disagree (``check``)
2     bad input: a problem file, an option value, an output that cannot be written
3     the simulation stopped before its end time because the model cannot go on
4     the time limit (``--timeout``) was reached
130   interrupted (Ctrl-C)
====  ==========================================================================================
"""

from __future__ import annotations

import argparse
import math
import sys

from ..base.errors import InputError
from ..base.textsafe import terminal_safe
from ..base.units import TIME, parse_quantity

EXIT_OK, EXIT_UNANSWERED, EXIT_INPUT, EXIT_STOPPED, EXIT_TIME, EXIT_INTERRUPTED = 0, 1, 2, 3, 4, 130

#: The longest time limit (``--timeout``) accepted: one day.  0 means no limit.
MAX_TIMEOUT = 86_400.0

#: The largest time (``--t-end``, ``--simulate``) accepted, in seconds.
MAX_TIME = 1e9

#: The most samples ``--points`` may ask for (memory is also estimated per model).
MAX_POINTS = 10_000_000


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose refusals are one paragraph on stderr, control characters escaped, status 2."""

    def error(self, message: str):

        text = terminal_safe(message.removeprefix("argument ").rstrip("."), newlines=False)
        sys.stderr.write(f"rigidkin: {text}. See '{terminal_safe(self.prog, newlines=False)} --help'.\n")
        sys.exit(EXIT_INPUT)


def _real(text: str, what: str) -> float:
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise argparse.ArgumentTypeError(f"{_show(text)} is not a number; {what}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{_show(text)} is not a finite number; {what}")
    return value


def _time(text: str, what: str) -> float:
    """A time in seconds: a plain number (seconds) or a quantity with a unit of time ("500 ms", "2 min")."""
    try:
        return _real(text, what)
    except argparse.ArgumentTypeError:
        if not isinstance(text, str) or not any(ch.isalpha() for ch in text) or text.strip().lower().lstrip(
                "+-") in ("nan", "inf", "infinity"):
            raise
    try:                                               # pint: read only when a unit is given
        return parse_quantity(text, None, None, TIME)
    except InputError as exc:
        raise argparse.ArgumentTypeError(f"{_show(text)} is not a time ({exc.message.rstrip('.')}); {what}") from None


def _show(text) -> str:
    text = str(text)
    return repr(text if len(text) <= 40 else text[:37] + "...")


def tolerance(text: str) -> float:
    """A relative or absolute integration tolerance: a finite number > 0 (a relative one below 1)."""
    v = _real(text, "a tolerance is a small positive number such as 1e-10")
    if not v > 0:
        raise argparse.ArgumentTypeError(f"the tolerance {v:g} must be positive; write a small positive number "
                                         "such as 1e-10")
    if v >= 1:
        raise argparse.ArgumentTypeError(f"the tolerance {v:g} is not below 1 and would give no accuracy; write a "
                                         "small positive number such as 1e-10")
    return v


def end_time(text: str) -> float:
    """An end time in seconds (or with a unit of time: ``"500 ms"``): finite, positive and at most MAX_TIME."""
    v = _time(text, "give the end time in seconds or with a unit of time, e.g. 5 or '500 ms'")
    if not 0 < v <= MAX_TIME:
        raise argparse.ArgumentTypeError(f"{v:g} s is not a positive end time of at most {MAX_TIME:g} s")
    return v


def start_time(text: str) -> float:
    """A start time in seconds (or with a unit of time): finite, of magnitude at most MAX_TIME."""
    v = _time(text, "give the start time in seconds or with a unit of time, e.g. 0 or '2 ms'")
    if abs(v) > MAX_TIME:
        raise argparse.ArgumentTypeError(f"the time {v:g} s is beyond ±{MAX_TIME:g} s")
    return v


def timeout(text: str) -> float:
    """A time limit in seconds (or with a unit of time: ``"10 min"``): finite, 0 (no limit) or positive up to
    MAX_TIMEOUT."""
    v = _time(text, f"give the limit in seconds or with a unit of time, e.g. 600 or '10 min' (at most "
                    f"{MAX_TIMEOUT:g} s; 0: no limit)")
    if v < 0 or v > MAX_TIMEOUT:
        raise argparse.ArgumentTypeError(f"the time limit {v:g} s must lie between 0 (no limit) and "
                                         f"{MAX_TIMEOUT:g} s (one day)")
    return v


def whole(low: int, high: int, what: str):
    """An argparse type: a whole number from ``low`` to ``high``."""

    def parse(text: str) -> int:
        try:
            v = int(str(text).strip())
        except ValueError:
            raise argparse.ArgumentTypeError(f"{_show(text)} is not a whole number; give {what} from {low} to "
                                             f"{high}") from None
        if not low <= v <= high:
            raise argparse.ArgumentTypeError(f"{v} is out of range; give {what} from {low} to {high}")
        return v

    parse.__name__ = what          # argparse names the type in its own messages
    return parse


points = whole(2, MAX_POINTS, "a number of samples")
threads = whole(1, 1024, "a number of threads")
workers = whole(1, 1024, "a number of worker processes")
chunk = whole(1, 10_000_000, "a number of runs per task")


def add_timeout(p, default: float = 600) -> None:
    """The ``--timeout`` option: the whole command stops after that many seconds (exit status 4)."""
    p.add_argument("--timeout", type=timeout, default=default, metavar="SECONDS",
                   help=f"stop the whole command after SECONDS, or a time with a unit such as '10 min' (default "
                        f"{default:g}; 0: no limit; at most "
                        f"{MAX_TIMEOUT:g}); exit status 4")


def add_no_cache(p) -> None:
    """The ``--no-cache`` option: derive afresh, neither reading nor writing the derivation cache."""
    p.add_argument("--no-cache", action="store_true",
                   help="derive afresh: neither read nor write the derivation cache (RIGIDKIN_NO_CACHE=1 does the "
                        "same for every command; the cache is in $RIGIDKIN_CACHE or ~/.cache/rigidkin/derivations)")


def parse_modes(items) -> dict:
    """``--mode CONTACT=STATE ...`` → {contact: state} (states: open, slip, stick)."""

    out = {}
    for it in items:
        name, sep, state = it.partition("=")
        if not sep or not name.strip() or not state.strip():
            raise InputError(f"--mode '{it}' is not CONTACT=STATE.", where="--mode",
                             hint="For example --mode ground=stick (states: open, slip, stick).")
        out[name.strip()] = state.strip()
    return out
