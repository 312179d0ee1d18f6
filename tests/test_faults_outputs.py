"""Outputs, caches and signals under faults: nothing the user had is lost, nothing they did not write runs,
and no answer comes from another file (issue 28).

Each probe states its exit status and checks what is on disk afterwards: the problem file, the old output,
the special file, the absence of temporary files.  The reference for every output written is the same
command writing to a plain new file (or with ``--no-cache``): the bytes must be the same.
"""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest
from helpers import rigidkin_env, rigidkin_process

from rigidkin.base import outfile, tempfiles
from rigidkin.cli import main
from rigidkin.examples import HERE as EXAMPLES

LADDER = (EXAMPLES / "ladder.toml").read_bytes()
SIM = ["--t-end", "0.3", "--points", "31"]


def _parts(folder: Path) -> list[Path]:
    return [p for p in folder.iterdir() if p.name.startswith((".rigidkin-", ".tmp-"))]


@pytest.fixture
def problem(tmp_path):
    p = tmp_path / "p.toml"
    p.write_bytes(LADDER)
    return p


@pytest.fixture
def reference(problem, tmp_path):
    """The histories written to a plain new file: what every other target must receive."""
    ref = tmp_path / "ref.csv"
    assert main(["simulate", str(problem), *SIM, "--csv", str(ref)]) == 0
    return ref.read_bytes()


# output paths ------------------------------------------------------------------------------------------
def test_an_output_over_the_problem_file_is_refused_before_anything_runs(problem, tmp_path, capsys):
    link = tmp_path / "alias.csv"
    link.symlink_to(problem)
    hard = tmp_path / "hard.csv"
    os.link(problem, hard)
    for argv in (["simulate", str(problem), *SIM, "--csv", str(problem)],
                 ["simulate", str(problem), *SIM, "--csv", str(link)],
                 ["simulate", str(problem), *SIM, "--plot", str(tmp_path / "p.png"), "--csv", str(hard)],
                 ["sweep", str(problem), "--param", "theta=0.1:0.2:2", "-o", str(problem)],
                 ["variants", str(problem), "--count", "1", "-o", str(tmp_path / "x.xml"), "--vary", "m=1:2"]):
        if argv[0] == "variants":                                   # a .xml link to the problem file
            (tmp_path / "x.xml").symlink_to(problem)
        assert main(argv) == 2, argv
        err = capsys.readouterr().err
        assert "an input of this command" in err and "Nothing was run" in err
        assert problem.read_bytes() == LADDER and link.is_symlink()
    assert not (tmp_path / "p.png").exists() and not _parts(tmp_path)


def test_grade_never_writes_over_the_worksheet_or_its_problem(problem, tmp_path, capsys):
    ws = tmp_path / "ws.toml"
    text = 'problem = "p.toml"\n[[step]]\nkind = "answer"\nquestion = "leaves_wall"\nclaim = "theta = 0.84"\n'
    ws.write_text(text)
    assert main(["grade", str(ws), "-o", str(ws)]) == 2
    assert main(["grade", str(ws), "-o", str(problem)]) == 2
    assert "an input of this command" in capsys.readouterr().err
    assert ws.read_text() == text and problem.read_bytes() == LADDER


def test_two_outputs_on_one_file_are_refused(problem, tmp_path, capsys):
    (tmp_path / "x.png").write_bytes(b"mine")
    (tmp_path / "y.png").symlink_to(tmp_path / "x.png")
    for other in ("x.png", "y.png"):
        argv = ["simulate", str(problem), *SIM, "--csv", str(tmp_path / "x.png"), "--plot", str(tmp_path / other)]
        assert main(argv) == 2
        assert "are the same file" in capsys.readouterr().err
    assert (tmp_path / "x.png").read_bytes() == b"mine"
    assert main(["simulate", str(problem), *SIM, "--csv", "/dev/null", "--plot", "/dev/null"]) == 0   # a device: fine


def test_dev_stdout_is_written_through_and_never_replaced(problem, tmp_path, reference, capfd):
    before = os.lstat("/dev/stdout")
    capfd.readouterr()
    assert main(["simulate", str(problem), *SIM, "--csv", "/dev/stdout"]) == 0
    out = capfd.readouterr().out
    assert out.startswith(reference.decode())                      # the table, then the summary lines
    after = os.lstat("/dev/stdout")
    assert stat.S_ISLNK(after.st_mode) and after.st_ino == before.st_ino


def test_dev_stdout_appended_by_the_shell_keeps_what_was_there(problem, tmp_path, reference):
    log = tmp_path / "log.csv"
    log.write_text("kept line\n")
    with open(log, "a") as f:
        run = rigidkin_process("simulate", problem, *SIM, "--csv", "/dev/stdout", stdout=f, stderr=subprocess.PIPE,
                               text=False)
    assert run.returncode == 0, run.stderr
    text = log.read_text()
    assert text.startswith("kept line\n" + reference.decode())
    assert not _parts(tmp_path)


def test_a_fifo_is_written_through(problem, tmp_path, reference):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    try:
        assert main(["simulate", str(problem), *SIM, "--csv", str(fifo)]) == 0
    finally:
        reader.join(60)
    assert got == [reference] and stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_link_to_a_file_stays_a_link_and_its_target_is_replaced_whole(problem, tmp_path, reference):
    target = tmp_path / "data" / "h.csv"
    target.parent.mkdir()
    target.write_text("old")
    os.chmod(target, 0o640)
    link = tmp_path / "h.csv"
    link.symlink_to(target)
    assert main(["simulate", str(problem), *SIM, "--csv", str(link)]) == 0
    assert link.is_symlink() and target.read_bytes() == reference
    assert stat.S_IMODE(target.stat().st_mode) == 0o640                   # the file keeps its permissions
    assert not _parts(tmp_path) and not _parts(target.parent)


def test_a_missing_device_is_refused():
    with pytest.raises(outfile.OutputError, match="no such device"):
        outfile.check_target("/dev/rigidkin-no-such-device", "the histories")


def test_a_write_that_fails_leaves_the_old_report_whole(problem, tmp_path):
    """A file-size limit stops the write (EFBIG): exit 2, the old report as it was, no temporary file."""
    old = tmp_path / "r.html"
    old.write_bytes(b"<html>the old report</html>\n" * 10)
    script = textwrap.dedent(f"""
        import resource, sys
        from rigidkin.cli import main
        resource.setrlimit(resource.RLIMIT_FSIZE, (4096, resource.RLIM_INFINITY))
        sys.exit(main(["report", {str(problem)!r}, "-o", {str(old)!r}, "--no-figures", "--no-checks",
                       "--no-answers"]))
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=rigidkin_env(),
                         timeout=600)
    assert run.returncode == 2, run.stderr
    assert "cannot write the report" in run.stderr and "too large" in run.stderr.lower()
    assert old.read_bytes() == b"<html>the old report</html>\n" * 10
    assert not _parts(tmp_path)


@pytest.mark.parametrize("sig", ["SIGTERM", "SIGHUP", "SIGINT"])
def test_a_signal_during_a_write_leaves_no_temporary_file(tmp_path, sig):
    target = tmp_path / "out.csv"
    target.write_text("old\n")
    script = textwrap.dedent(f"""
        import sys, time
        from rigidkin.base.outfile import writing
        with writing({str(target)!r}, "the table") as f:
            f.write("half a table\\n")
            f.flush()
            print("writing", flush=True)
            time.sleep(60)
    """)
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=rigidkin_env())
    assert proc.stdout.readline().strip() == "writing"
    assert len(_parts(tmp_path)) == 1                                      # the temporary file, while writing
    proc.send_signal(getattr(signal, sig))
    proc.wait(60)
    assert proc.returncode != 0
    if sig != "SIGINT":
        assert proc.returncode == -getattr(signal, sig)                    # ended by the signal, as without us
    assert target.read_text() == "old\n" and not _parts(tmp_path)


def test_the_signal_handlers_chain_to_the_programs_own(tmp_path):
    seen = []
    previous = signal.signal(signal.SIGHUP, lambda s, f: seen.append(s))
    saved = dict(tempfiles._PREVIOUS)
    others = tempfiles.live()                          # what the rest of this process registered: kept
    for p in others:
        tempfiles.release(p)
    tempfiles._PREVIOUS.pop(signal.SIGHUP, None)
    try:
        tmp = tmp_path / ".rigidkin-x.part"
        tmp.write_text("x")
        tempfiles.register(str(tmp))
        os.kill(os.getpid(), signal.SIGHUP)
        time.sleep(0.1)
        assert not tmp.exists() and seen == [signal.SIGHUP]
    finally:
        signal.signal(signal.SIGHUP, previous)
        tempfiles._PREVIOUS.clear()
        tempfiles._PREVIOUS.update(saved)
        for p in others:
            tempfiles.register(p)


# columns and keys ---------------------------------------------------------------------------------------
def test_a_reaction_named_T_keeps_its_column_beside_the_kinetic_energy(tmp_path, capsys):
    """The wall reaction renamed T: its column equals N_A of the same simulation, and the kinetic energy
    (namespaced) is m l² θ̇²/6 while the rod touches the wall (v_G = l θ̇/2, I_G = m l²/12)."""
    renamed = tmp_path / "t.toml"
    import re

    renamed.write_bytes(re.sub(rb"\bN_A\b", b"T", LADDER))
    plain = tmp_path / "plain.toml"
    plain.write_bytes(LADDER)
    assert main(["simulate", str(renamed), *SIM, "--csv", str(tmp_path / "t.csv")]) == 0
    assert main(["simulate", str(plain), *SIM, "--csv", str(tmp_path / "n.csv")]) == 0
    import csv

    rows_t = list(csv.DictReader((tmp_path / "t.csv").open()))
    rows_n = list(csv.DictReader((tmp_path / "n.csv").open()))
    head = next(csv.reader((tmp_path / "t.csv").open()))
    assert len(head) == len(set(head)) and {"T", "energy: T", "energy: U", "energy: E", "energy: W"} <= set(head)
    checked = 0
    for a, b in zip(rows_t, rows_n, strict=True):
        assert float(a["T"]) == pytest.approx(float(b["N_A"]), rel=1e-12, abs=1e-9)
        if "A closed" in a["mode"]:
            assert float(a["energy: T"]) == pytest.approx(10 * 2**2 * float(a["dot(theta)"]) ** 2 / 6, rel=1e-9,
                                                          abs=1e-12)
            checked += 1
    assert checked > 10


def test_an_output_column_named_twice_is_refused():
    with pytest.raises(outfile.OutputError, match="'status'"):
        outfile.unique_columns([("run", 1), ("status", 2), ("status", 3)])
    with pytest.raises(outfile.OutputError, match="'mode'"):
        outfile.unique_columns([("t", 1), ("mode", 2)], reserved=("mode",))


def test_json_labels_every_regime_and_names_the_top_level_one(capsys):
    import json
    from importlib import resources

    import jsonschema

    assert main(["solve", "slip-to-roll", "--format", "json", "--no-cache"]) in (0, 1)
    data = json.loads(capsys.readouterr().out)
    regimes = data["regimes"]
    assert len(regimes) == 2 and [r["index"] for r in regimes] == [0, 1]
    assert data["regime"] == {"index": 0, "label": regimes[0]["label"], "of": 2}
    assert regimes[0]["label"] != regimes[1]["label"]
    assert data["eom"] == regimes[0]["eom"] and data["reactions"] == regimes[0]["reactions"]
    jsonschema.validate(data, json.loads(resources.files("rigidkin.io").joinpath("results.schema.json").read_text()))


# quantities ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("argv, where", [
    (["simulate", "{p}", *SIM, "--initial", "theta=0.5 kg"], "--initial theta"),
    (["simulate", "{p}", *SIM, "--initial", "dot(theta)=1 m/s"], "--initial dot(theta)"),
    (["simulate", "{p}", *SIM, "--initial", "theta=nan"], "theta"),
    (["simulate", "{p}", *SIM, "--initial", "theta=inf deg"], "theta"),
    (["report", "{p}", "-o", "{d}/r.html", "--at", "theta=0.5 kg"], "--at theta"),
    (["sweep", "{p}", "--param", "theta=0.1:0.2:2", "--stop-at", "theta=nan", "-o", "{d}/s.csv"], "--stop-at theta"),
    (["sweep", "{p}", "--param", "theta=0.1:0.2:2", "--stop-at", "theta=1 kg", "-o", "{d}/s.csv"], "--stop-at"),
    (["sweep", "{p}", "--param", "theta=0.1 kg:0.2:2", "-o", "{d}/s.csv"], "--param theta"),
    (["sweep", "{p}", "--param", "x=1 s,2 s", "-o", "{d}/s.csv"], "--param x"),
    (["variants", "{p}", "--vary", "m=1 s:2 s", "--count", "1"], "--vary m"),
    (["variants", "{p}", "--vary", "m=1:inf", "--count", "1"], "--vary m"),
])
def test_a_quantity_of_the_wrong_dimension_or_not_finite_is_refused(problem, tmp_path, capsys, argv, where):
    argv = [a.format(p=problem, d=tmp_path) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert where in err and ("dimension" in err or "finite" in err or "cannot be read" in err)
    assert not (tmp_path / "s.csv").exists() and not (tmp_path / "r.html").exists()


def test_a_quantity_with_its_unit_gives_the_same_run_as_its_si_value(problem, tmp_path, capsys):
    """30 deg is π/6 rad: the histories are the same bytes."""
    import math

    assert main(["simulate", str(problem), *SIM, "--initial", "theta=30 deg", "--csv", str(tmp_path / "a.csv")]) == 0
    assert main(["simulate", str(problem), *SIM, "--initial", f"theta={math.pi / 6!r}",
                 "--csv", str(tmp_path / "b.csv")]) == 0
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()


@pytest.mark.skipif(not os.path.isdir("/dev/shm"), reason="no /dev/shm")
def test_an_ordinary_file_in_dev_shm_is_written_whole(tmp_path):
    target = Path("/dev/shm") / f"rigidkin-test-{os.getpid()}.csv"
    try:
        outfile.write_text(target, "a,b\n1,2\n", "the table")
        assert target.read_text() == "a,b\n1,2\n" and not outfile.through(target)
        assert not [p for p in target.parent.iterdir() if p.name.startswith(".rigidkin-")]
    finally:
        target.unlink(missing_ok=True)
