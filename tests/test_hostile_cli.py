"""Hostile and careless command lines: every one ends with the exit status that says what happened, one
paragraph and never a traceback, within a time and a memory bound checked here.

Exit statuses: 0 success, 1 an unanswered question (solve), 2 bad input or an output that cannot be
written, 3 a simulation stopped because the model cannot go on, 4 the time limit.  Each case runs
in-process with its wall time and its peak memory measured (the process's peak resident size, reset
before the case; tracemalloc where /proc is not there): under 2 s (a case that draws a figure: 10 s)
and 500 MB.  The time limit itself is checked on a real process, with the hard stops armed.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
import time
import tracemalloc

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rigidkin.cli import main

SECONDS, BYTES = 2.0, 500 * 2**20
#: Cases that do real work (a simulation drawn as a 4-panel figure takes 2–4 s on a loaded machine): 10 s.
WORKING = {"plot-mathtext-title": 10.0, "escape-title-figure": 10.0}

PENDULUM = """\
title = "{title}"
[parameters]
m = {{ unit = "kg", value = 1 }}
l = {{ unit = "m", value = "50 cm" }}
g = {{ unit = "m/s^2", value = 9.81 }}
[coordinates]
theta = {{ sense = "angle from the downward vertical, counter-clockwise", initial = "{initial}" }}
{coordinates}
[frames]
R = {{ angle = "theta" }}
[points]
G = {{ offset = "-l/2*R.y" }}
[bodies]
rod = {{ shape = "slender_rod", mass = "m", length = "l", axis = "y", frame = "R", at = "G" }}
[constraints]
O = {{ type = "pin", point = "O", body_a = "rod" }}
[loads]
gravity = {{ type = "gravity", g = "g" }}
{loads}
"""


def pendulum(title="Pendulum", coordinates="", loads="", initial="10 deg") -> str:
    return PENDULUM.format(title=title, coordinates=coordinates, loads=loads, initial=initial)


def chain(n: int) -> str:
    """A chain of ``n`` rods pinned end to end (its derivation takes long for n = 10)."""
    lines = ['title = "Chain"', "[parameters]", 'm = { unit = "kg", value = 1 }', 'l = { unit = "m", value = 1 }',
             'g = { unit = "m/s^2", value = 9.81 }', "[coordinates]"]
    lines += [f'theta{i} = {{ sense = "angle of rod {i}", initial = "0.{i}" }}' for i in range(1, n + 1)]
    lines += ["[frames]"] + [f'R{i} = {{ angle = "theta{i}" }}' for i in range(1, n + 1)] + ["[points]"]
    for i in range(1, n + 1):
        top = "O" if i == 1 else f"P{i - 1}"
        lines.append(f'G{i} = {{ from = "{top}", offset = "-l/2*R{i}.y" }}')
        if i < n:
            lines.append(f'P{i} = {{ from = "{top}", offset = "-l*R{i}.y", body = "rod{i}" }}')
    lines += ["[bodies]"] + [f'rod{i} = {{ shape = "slender_rod", mass = "m", length = "l", axis = "y", '
                             f'frame = "R{i}", at = "G{i}" }}' for i in range(1, n + 1)]
    lines += ["[constraints]", 'J0 = { type = "pin", point = "O", body_a = "rod1" }']
    lines += [f'J{i - 1} = {{ type = "pin", point = "P{i - 1}", body_a = "rod{i}", body_b = "rod{i - 1}" }}'
              for i in range(2, n + 1)]
    lines += ["[loads]", 'gravity = { type = "gravity", g = "g" }']
    return "\n".join(lines) + "\n"


FILES = {
    "pend.toml": pendulum(),
    "overflow.toml": pendulum(loads='push = { type = "force", point = "G", vector = "m*g*exp(theta**2)*R.x", '
                                   'body = "rod" }', initial="30"),
    "overflow-pow.toml": pendulum(loads='push = { type = "force", point = "G", vector = "m*g*theta**-12*R.x", '
                                       'body = "rod" }', initial="1e-30"),
    "escape-title.toml": pendulum(title=r"\u001b[31mRED\u001b]0;owned\u0007 \u202e"),
    "math-title.toml": pendulum(title=r"$\\frac{unclosed$ and $x^{$"),
    "escape-key.toml": pendulum(coordinates='"bogus\\u001b[2J" = { sense = "x" }'),
    "q-theta.toml": pendulum(coordinates='q_theta = { sense = "a name rigidkin makes itself" }'),
}


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    d = tmp_path_factory.mktemp("hostile")
    for name, text in FILES.items():
        (d / name).write_text(text, encoding="utf-8")
    (d / "a-folder").mkdir()
    # the first run imports the numeric and plotting modules: later runs measure the command, not the imports
    main(["simulate", str(d / "pend.toml"), "--t-end", "0.01", "--points", "2", "--plot", str(d / "warm.png")])
    return d


def fill(argv, folder) -> list[str]:
    return [a.replace("{d}", str(folder)) for a in argv]


class Peak:
    """The peak memory of a block: the process's peak resident size reset before it (Linux: VmHWM, reset
    through /proc/self/clear_refs), or else the peak of tracemalloc (which sees numpy's arrays, but slows)."""

    def __enter__(self):
        self.proc = _hwm() is not None
        if self.proc:
            try:
                with open("/proc/self/clear_refs", "w") as f:
                    f.write("5")
                self.base = _rss()
            except OSError:
                self.proc = False
        if not self.proc:
            tracemalloc.start()
        return self

    def __exit__(self, *exc):
        if self.proc:
            self.bytes = max(_hwm() - self.base, 0)
        else:
            self.bytes = tracemalloc.get_traced_memory()[1]
            tracemalloc.stop()


def _status(key):
    try:
        with open("/proc/self/status") as f:
            m = re.search(rf"{key}:\s+(\d+) kB", f.read())
    except OSError:
        return None
    return int(m.group(1)) * 1024 if m else None


def _hwm():
    return _status("VmHWM")


def _rss():
    return _status("VmRSS")


def run_bounded(capsys, argv):
    """(exit status, stdout, stderr, seconds, peak bytes above the start) of one command line, run in-process."""
    capsys.readouterr()
    with Peak() as peak:
        start = time.monotonic()
        try:
            code = main(argv)
        except SystemExit as exc:                 # argparse refusals
            code = exc.code
        seconds = time.monotonic() - start
    out, err = capsys.readouterr()
    return code, out, err, seconds, peak.bytes


P = "{d}/pend.toml"
SIM = ["simulate", P, "--t-end", "0.01", "--points", "2"]
SWEEP = ["sweep", P, "-o", "{d}/t.csv"]

# (id, argv, expected exit status, words expected in stderr)
CASES = [
    # tolerances, times, counts, limits: refused by the option's kind
    ("rtol-negative", [*SIM, "--rtol", "-1e-8"], 2, "--rtol"),
    ("rtol-zero", [*SIM, "--rtol", "0"], 2, "must be positive"),
    ("rtol-nan", [*SIM, "--rtol", "nan"], 2, "not a finite number"),
    ("rtol-huge", [*SIM, "--rtol", "5"], 2, "not below 1"),
    ("atol-inf", [*SIM, "--atol", "inf"], 2, "--atol"),
    ("atol-text", [*SIM, "--atol", "small"], 2, "not a number"),
    ("t-end-negative", ["simulate", P, "--t-end", "-1"], 2, "--t-end"),
    ("t-end-zero", ["simulate", P, "--t-end", "0"], 2, "not a positive end time"),
    ("t-end-nan", ["simulate", P, "--t-end", "nan"], 2, "not a finite number"),
    ("t-end-inf", ["simulate", P, "--t-end", "inf"], 2, "not a finite number"),
    ("t-end-huge", ["simulate", P, "--t-end", "1e300"], 2, "at most"),
    ("t-start-nan", [*SIM, "--t-start", "nan"], 2, "--t-start"),
    ("t-start-after-end", [*SIM, "--t-start", "5"], 2, "not after the start time"),
    ("points-30M", [*SIM[:-2], "--points", "30000000"], 2, "--points"),
    ("points-5M-memory", [*SIM[:-2], "--points", "5000000"], 2, "of memory; the limit is"),
    ("points-one", [*SIM[:-2], "--points", "1"], 2, "--points"),
    ("points-text", [*SIM[:-2], "--points", "many"], 2, "not a whole number"),
    ("restitution-nan", [*SIM, "--restitution", "nan"], 2, "not a finite number"),
    ("timeout-inf", ["solve", P, "--timeout", "inf"], 2, "--timeout"),
    ("timeout-nan", ["solve", P, "--timeout", "nan"], 2, "--timeout"),
    ("timeout-1e10", ["solve", P, "--timeout", "1e10"], 2, "one day"),
    ("timeout-negative", ["check", P, "--timeout", "-3"], 2, "--timeout"),
    ("timeout-simulate", [*SIM, "--timeout", "nan"], 2, "--timeout"),
    ("timeout-sweep", [*SWEEP, "--param", "theta=0:1:3", "--timeout", "inf"], 2, "--timeout"),
    ("timeout-report", ["report", P, "-o", "{d}/r.html", "--timeout", "1e99"], 2, "--timeout"),
    ("report-simulate-nan", ["report", P, "-o", "{d}/r.html", "--simulate", "nan"], 2, "--simulate"),
    # sweeps bounded by their memory before anything is allocated
    ("sweep-20000x20000", [*SWEEP, "--param", "theta=0.1:1:20000", "l=0.5:2:20000"], 2, "400,000,000 runs"),
    ("sweep-1e7x1e7", [*SWEEP, "--param", "theta=0.1:1:10000000", "l=0.5:2:10000000"], 2,
     "more than one command runs"),
    ("sweep-count-1e8", [*SWEEP, "--param", "theta=0.1:1:100000000"], 2, "between 1 and 10^7"),
    ("sweep-rtol-negative", [*SWEEP, "--param", "theta=0:1:3", "--rtol", "-1"], 2, "--rtol"),
    ("sweep-t-end-nan", [*SWEEP, "--param", "theta=0:1:3", "--t-end", "nan"], 2, "--t-end"),
    ("sweep-threads-zero", [*SWEEP, "--param", "theta=0:1:3", "--threads", "0"], 2, "--threads"),
    ("sweep-workers-huge", [*SWEEP, "--param", "theta=0:1:3", "--workers", "99999999"], 2, "--workers"),
    ("sweep-chunk-negative", [*SWEEP, "--param", "theta=0:1:3", "--chunk", "-5"], 2, "--chunk"),
    ("sweep-value-nan", [*SWEEP, "--param", "theta=nan:1:3"], 2, "quantity 'nan'"),
    ("sweep-value-huge", [*SWEEP, "--param", "theta=1e400:1:3"], 2, "not a finite number"),
    # outputs: checked before any work, written whole or not at all
    ("csv-dev-full", [*SIM, "--csv", "/dev/full"], 2, "no space left on device"),
    ("csv-folder", [*SIM, "--csv", "{d}/a-folder"], 2, "it is a folder"),
    ("plot-missing-folder", [*SIM, "--plot", "{d}/missing/x.png"], 2, "does not exist"),
    ("plot-unknown-extension", [*SIM, "--plot", "{d}/x.figure"], 2, "extension '.figure'"),
    ("plot-folder", [*SIM, "--plot", "{d}/a-folder"], 2, "it is a folder"),
    ("csv-name-too-long", [*SIM, "--csv", "{d}/" + "x" * 300 + ".csv"], 2, "too long"),
    ("csv-nul-in-name", [*SIM, "--csv", "{d}/a\x00b.csv"], 2, "not a usable file name"),
    ("sweep-output-folder", [*SWEEP[:-1], "{d}/a-folder", "--param", "theta=0:1:3"], 2, "it is a folder"),
    ("sweep-plot-extension", [*SWEEP, "--param", "theta=0:1:3", "--plot", "{d}/x.doc"], 2, "extension '.doc'"),
    ("report-missing-folder", ["report", P, "-o", "{d}/missing/r.html"], 2, "does not exist"),
    ("report-gif-folder", ["report", P, "-o", "{d}/r.md", "--simulate", "1", "--gif", "{d}/a-folder"], 2,
     "it is a folder"),
    ("plot-mathtext-title", ["simulate", "{d}/math-title.toml", "--t-end", "0.01", "--points", "2",
                             "--plot", "{d}/math.png"], 0, ""),
    # text from the file shown with its control characters escaped
    ("escape-title", ["validate", "{d}/escape-title.toml"], 0, ""),
    ("escape-key", ["validate", "{d}/escape-key.toml"], 2, "\\x1b[2J"),
    ("escape-title-figure", ["simulate", "{d}/escape-title.toml", "--t-end", "0.01", "--points", "2", "--plot",
                             "{d}/esc.png"], 0, ""),
    ("escape-argument", ["simulate", "\x1b[31mred.toml", "--t-end", "1"], 2, "\\x1b[31m"),
    ("escape-unknown-option", ["solve", P, "--\x1b]0;x\x07"], 2, "\\x1b"),
    # the model cannot go on, names that clash
    ("overflow-in-a-load", ["simulate", "{d}/overflow.toml", "--t-end", "1", "--points", "2"], 3,
     "non-finite rate at t = 0 (theta = 30, dot(theta) = 0)"),
    ("overflow-in-a-power", ["simulate", "{d}/overflow-pow.toml", "--t-end", "1", "--points", "2"], 3,
     "the model cannot go on"),
    ("q-theta", ["validate", "{d}/q-theta.toml"], 2, "q_theta"),
]


@pytest.mark.parametrize("case, argv, code, words", CASES, ids=[c[0] for c in CASES])
def test_hostile_command_line(capsys, folder, case, argv, code, words):
    got, out, err, seconds, peak = run_bounded(capsys, fill(argv, folder))
    assert got == code, err
    assert words in err
    assert "Traceback" not in err and "\x1b" not in out + err and "\x07" not in out + err and "\u202e" not in out
    if code == 2:
        assert err.count("\n") == 1, err             # one paragraph
    assert seconds < WORKING.get(case, SECONDS), f"{seconds:.2f} s"
    assert peak < BYTES, f"{peak / 2**20:.0f} MB"


def test_outputs_are_whole_or_absent(capsys, folder):
    """A failed write leaves neither the target nor a temporary file; a good one leaves exactly the target."""
    before = set(os.listdir(folder))
    assert main([*fill(SIM, folder), "--csv", "/dev/full"]) == 2
    assert set(os.listdir(folder)) == before
    target = folder / "h.csv"
    assert main([*fill(SIM, folder), "--csv", str(target)]) == 0
    assert set(os.listdir(folder)) == before | {"h.csv"}
    rows = target.read_text().splitlines()
    assert rows[0].startswith("t,mode,theta,dot(theta)") and len(rows) == 3
    mask = os.umask(0)
    os.umask(mask)
    assert target.stat().st_mode & 0o777 == 0o666 & ~mask        # as any new file, not private to the user
    (folder / "math.png").unlink(missing_ok=True)
    assert main(["simulate", str(folder / "math-title.toml"), "--t-end", "0.01", "--points", "2", "--plot",
                 str(folder / "math.png")]) == 0
    assert (folder / "math.png").read_bytes()[:4] == b"\x89PNG"
    capsys.readouterr()


def test_escaped_title_is_shown_readably(capsys, folder):
    assert main(["validate", str(folder / "escape-title.toml")]) == 0
    out = capsys.readouterr().out
    assert "\\x1b[31mRED\\x1b]0;owned\\x07" in out and "\\u202e" in out


# hypothesis over the command line: options from the vocabulary, values good and bad --------------------------
_VALUES = st.sampled_from(["0", "-1", "1e-9", "nan", "inf", "-inf", "1e308", "2", "x", "", "1e10", "3000000",
                           "10", "0.5", "1:2:3", "theta=0.1", "theta=nan", "theta", "\x1b[2J", "--", "=",
                           "/dev/full", "/nonexistent/x.png", "a.figure"])
_OPTIONS = {
    "simulate": ["--t-end", "--t-start", "--rtol", "--atol", "--points", "--timeout", "--restitution", "--set",
                 "--initial", "--csv", "--plot", "--mode", "--method"],
    "sweep": ["--t-end", "--rtol", "--atol", "--threads", "--workers", "--chunk", "--timeout", "--param", "--set",
              "--initial", "-o", "--plot", "--stop-at"],
    "solve": ["--timeout", "--method", "--format"],
    "check": ["--timeout", "--expect", "--method", "--mode"],
    "report": ["--timeout", "--simulate", "-o", "--gif", "--at", "--set"],
    "validate": ["--timeout"],
}


@st.composite
def command_lines(draw):
    command = draw(st.sampled_from(sorted(_OPTIONS)))
    argv = [command, draw(st.sampled_from(["ladder", "nope", "missing.toml"]))]
    for _ in range(draw(st.integers(1, 4))):
        argv += [draw(st.sampled_from(_OPTIONS[command])), draw(_VALUES)]
    return argv + ["--timeout", "1"]           # the last --timeout counts: no example runs long


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(argv=command_lines())
def test_hypothesis_command_lines_end_with_a_known_status(capsys, tmp_path, argv):
    argv = [str(tmp_path / "out.csv") if a == "out" else a for a in argv]
    cwd = os.getcwd()
    os.chdir(tmp_path)                          # relative outputs land in the test's folder
    try:
        code, out, err, seconds, _ = run_bounded(capsys, argv)
    finally:
        os.chdir(cwd)
    assert code in (0, 1, 2, 3, 4), (argv, code, err)
    assert "Traceback" not in err and "\x1b" not in out + err, (argv, err)
    assert seconds < 10, (argv, seconds)       # 1 s of limit, the grace of a step, a loaded machine


# the time limit bounds the whole command, in a real process --------------------------------------------------
RUNNER = textwrap.dedent("""
    import sys, time
    from rigidkin.cli import main
    sys.argv = ["rigidkin", *sys.argv[1:]]
    sys.stderr.write(f"@@start {time.monotonic()!r}\\n")
    sys.stderr.flush()
    sys.exit(main())
""")


def test_timeout_bounds_the_whole_command(tmp_path):
    """A chain of 10 rods takes far longer than 2 s to derive and print; --timeout 2 stops it by 4 s."""
    problem = tmp_path / "chain10.toml"
    problem.write_text(chain(10))
    res = subprocess.run([sys.executable, "-c", RUNNER, "solve", str(problem), "--timeout", "2"],
                         capture_output=True, text=True, timeout=60)
    seconds = time.monotonic() - float(res.stderr.split("@@start ", 1)[1].split()[0])    # one clock for both
    assert res.returncode == 4, res.stderr
    assert "time limit reached" in res.stderr and "--timeout 2" in res.stderr and "Traceback" not in res.stderr
    assert seconds < 2 + 2, seconds


LAYER = textwrap.dedent("""
    import sys, time
    from rigidkin.commands.deadline import deadline
    sys.stderr.write(f"@@start {time.monotonic()!r}\\n")
    sys.stderr.flush()
    with deadline(1, hard_stop=True):
        if sys.argv[1] == "swallow":        # a library that catches everything, even the time limit
            while True:
                try:
                    time.sleep(5)
                except BaseException:
                    pass
        else:                               # one long call of compiled code that never lets other threads run
            sum(range(10**12))
""")


@pytest.mark.parametrize("how, status, words, bound", [
    ("swallow", 4, "time limit reached", 1 + 1 + 1.5),     # the watchdog thread, a second after the limit
    ("compiled", -9, "(killed)", 1 + 3 + 1.5),             # the watchdog process, three seconds after it
])
def test_the_hard_stops_of_the_time_limit(how, status, words, bound):
    res = subprocess.run([sys.executable, "-c", LAYER, how], capture_output=True, text=True, timeout=60)
    seconds = time.monotonic() - float(res.stderr.split("@@start ", 1)[1].split()[0])
    assert res.returncode == status, res.stderr
    assert words in res.stderr and "Traceback" not in res.stderr
    assert seconds < bound, seconds


def test_solve_exits_1_when_a_question_is_left_unanswered(monkeypatch, capsys, folder):
    """A question the engine cannot answer is said in the output, and the status says so (1, not 0)."""
    import rigidkin.analysis.answers as answers
    from rigidkin.base.errors import RigidkinError

    problem = folder / "asks.toml"
    problem.write_text(pendulum() + '[[ask.question]]\nkind = "event"\nname = "swing"\nwhen = "theta = 0"\n'
                                    'start = { theta = 0.1, "dot(theta)" = 0 }\n')
    assert main(["solve", str(problem)]) == 0
    assert "swing" in capsys.readouterr().out

    def cannot(*a, **kw):
        raise RigidkinError("no closed form and no simulation for this question.")

    monkeypatch.setattr(answers, "answer", cannot)
    assert main(["solve", str(problem)]) == 1
    assert "no closed form and no simulation" in capsys.readouterr().out
