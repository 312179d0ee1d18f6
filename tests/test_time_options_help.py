"""The help of the options that take a time (``--t-end``, ``--t-start``, ``--simulate``) says what they take:
seconds, or a time with its unit ("500 ms"), as the readers of those options do."""

import pytest

from rigidkin.cli import main
from rigidkin.commands.options import end_time, start_time


def _help(capsys, command) -> str:
    capsys.readouterr()
    assert main([command, "--help"]) == 0
    return " ".join(capsys.readouterr().out.split())          # argparse wraps the lines: read as one text


@pytest.mark.parametrize("command, option", [("simulate", "--t-end T"), ("simulate", "--t-start T0"),
                                             ("sweep", "--t-end T"), ("report", "--simulate T")])
def test_the_help_says_a_time_with_its_unit(capsys, command, option):
    text = _help(capsys, command)
    said = text[text.rindex(option + " "):][:160]          # its line in the options, after the usage
    assert "seconds" in said and "with its unit" in said and "ms'" in said, said
    assert "[s]" not in said


def test_what_the_help_says_is_what_is_read():
    assert end_time("500 ms") == pytest.approx(0.5) and end_time("5") == 5.0 and end_time("2 min") == 120.0
    assert start_time("20 ms") == pytest.approx(0.02)
