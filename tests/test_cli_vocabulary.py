"""One vocabulary on the command line: every option that takes NAME=VALUE pairs (``--set``, ``--initial``,
``--mode``, ``--at``, ``--vary``, ``--param``, ``--restitution``) accepts several pairs after one flag and
the flag repeated, in every subcommand, with the same result."""

from __future__ import annotations

import argparse
import json

import pytest

from rigidkin.cli import build_parser, main


def _subparsers(parser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            yield from action.choices.items()


def test_every_name_value_option_takes_several_and_repeats():
    seen = []
    for name, sub in _subparsers(build_parser()):
        for action in sub._actions:
            if action.option_strings and action.metavar and "=" in str(action.metavar):
                seen.append((name, action.option_strings[-1]))
                assert action.nargs == "+" and isinstance(action, argparse._ExtendAction), (name, action.option_strings)
    commands = {c for c, _ in seen}
    assert {"simulate", "sweep", "report", "check", "variants"} <= commands, seen
    # and argparse reads both forms into the same list
    for name, sub in _subparsers(build_parser()):
        if name == "report":
            both = sub.parse_args(["ladder", "-o", "x.md", "--set", "m=5", "l=3", "--set", "g=9.8"])
            assert both.set == ["m=5", "l=3", "g=9.8"]


def test_report_set_and_at_in_both_forms_write_the_same_document(tmp_path):
    a, b = tmp_path / "a.md", tmp_path / "b.md"
    common = ["--no-figures", "--no-checks", "--no-answers"]
    assert main(["report", "ladder", "-o", str(a), *common, "--set", "m=5", "l=3", "--at", "theta=0.4"]) == 0
    assert main(["report", "ladder", "-o", str(b), *common, "--set", "m=5", "--set", "l=3", "--at", "theta=0.4"]) == 0
    assert a.read_text() == b.read_text()
    assert "3" in a.read_text()


@pytest.mark.slow
def test_variants_vary_in_both_forms(capsys):
    base = ["variants", "rod-impulse", "--count", "2", "--seed", "3", "--format", "json"]
    assert main([*base, "--vary", "m=1:3", "F_hat=0.5:2"]) == 0
    one = json.loads(capsys.readouterr().out)
    assert main([*base, "--vary", "m=1:3", "--vary", "F_hat=0.5:2"]) == 0
    two = json.loads(capsys.readouterr().out)
    assert one == two
    for v in one["variants"]:
        assert 1 <= v["parameters"]["m"]["value"] <= 3 and 0.5 <= v["parameters"]["F_hat"]["value"] <= 2


@pytest.mark.parametrize("argv", [["--set", "m=5", "l=3"], ["--set", "m=5", "--set", "l=3"]])
def test_simulate_set_both_forms(argv, capsys):
    assert main(["simulate", "rod-impulse", "--t-end", "0.2", "--json", "--points", "5", *argv]) == 0
    json.loads(capsys.readouterr().out)


@pytest.mark.slow
def test_sweep_stops_at_the_event_simulate_names(capsys, tmp_path):
    """simulate --json names the wall leaving 'contact A opens'; sweep --stop-at takes that name as well as N_A."""
    assert main(["simulate", "ladder", "--t-end", "2", "--json", "--points", "5"]) == 0
    name = json.loads(capsys.readouterr().out)["events"][0]["name"]
    assert name == "contact A opens"
    outs = []
    for i, stop in enumerate((name, "N_A")):
        out = tmp_path / f"s{i}.csv"
        assert main(["sweep", "ladder", "--param", "theta=0.2:0.4:2", "--stop-at", stop, "--t-end", "3",
                     "-o", str(out)]) == 0, capsys.readouterr().err
        outs.append(out.read_text())
    assert outs[0] == outs[1] and "N_A: t" in outs[0]
    import numpy as np

    from rigidkin.examples import build
    from rigidkin.numeric.sweeps.sweep import sweep
    res = sweep(build("ladder"), {"theta": [0.2, 0.4]}, stop_at="contact A opens", record=["N_A"], t_end=3.0)
    assert np.allclose(np.cos(res.event_state("N_A", "theta")) / np.cos([0.2, 0.4]), 2 / 3, rtol=1e-8)
