"""``rigidkin simulate``: figure, histories, JSON, parameters and initial values from the command line."""

import json

import numpy as np
import pytest

from rigidkin.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_simulate_ladder_writes_figure_and_histories(capsys, tmp_path):
    png, csv = tmp_path / "out.png", tmp_path / "out.csv"
    code, out, err = run(capsys, "simulate", "ladder", "--t-end", "3", "--plot", str(png), "--csv", str(csv))
    assert code == 0, err
    assert png.read_bytes()[:4] == b"\x89PNG" and png.stat().st_size > 20_000
    head = csv.read_text().splitlines()[0]
    assert head.startswith("t,mode,theta,x,dot(theta),dot(x)")
    assert "A closed, A_floor open, B closed" in out and "Final state: theta = " in out
    assert "Traceback" not in err


def test_simulate_json_reports_the_wall_leaving_event(capsys):
    code, out, _ = run(capsys, "simulate", "ladder", "--t-end", "6", "--json", "--points", "50",
                       "--initial", "theta=1e-6")       # card (b): released from rest upright
    assert code == 0
    d = json.loads(out)
    ev = d["events"][0]      # then, at t ≈ 5.5 s, the upper end comes down onto the floor
    assert [e["name"] for e in d["events"]][:1] == ["contact A opens"]
    assert ev["name"] == "contact A opens" and abs(ev["state"]["theta"] - np.arccos(2 / 3)) < 1e-8
    assert set(d["final_state"]) == {"theta", "x", "dot(theta)", "dot(x)"}
    assert d["energy_drift"] < 1e-9


def test_simulate_set_with_units_and_initial_values(capsys):
    beta, mu = np.radians(20), 0.3
    vB = np.sqrt(2 * 9.81 * np.sin(beta))
    code, out, err = run(capsys, "simulate", "slip-to-roll", "--t-end", "1", "--json", "--set", "beta=20 deg",
                         f"mu={mu}", "--initial", "x=1", f"dot(x)={float(vB)!r}", "dot(phi)=0")
    assert code == 0, err
    (ev,) = json.loads(out)["events"]
    assert abs(ev["t"] - vB / (9.81 * (3 * mu * np.cos(beta) - np.sin(beta)))) < 1e-8


@pytest.mark.parametrize("argv, words", [
    (["--set", "nope=1"], "'nope' is not a parameter"),
    (["--set", "beta=3 kg"], "not in units of"),
    (["--initial", "theta"], "is not NAME=VALUE"),
    (["--initial", "dot(psi)=1"], "is not a coordinate or a rate"),
    (["--restitution", "2"], "must lie in [0, 1]"),
    (["--mode", "ground=flying"], "is not open, slip or stick"),
])
def test_simulate_input_errors_are_one_paragraph(capsys, argv, words):
    code, out, err = run(capsys, "simulate", "slip-to-roll", "--t-end", "1", *argv)
    assert code == 2
    assert words in err and "Traceback" not in err and err.count("\n") == 1


def test_simulate_reports_where_the_model_cannot_follow(capsys):
    code, out, err = run(capsys, "simulate", "disk-in-track", "--t-end", "3", "--initial", "theta=0",
                         f"dot(theta)={float(np.sqrt(2 * 9.81 * 0.9) / 0.9)!r}", "--json")
    assert code == 3                    # stopped early: the model cannot go on (reason and state given)
    d = json.loads(out)
    assert d["status"] == "stopped" and "no coordinate that lets P leave its surface" in d["message"]
    assert d["reached_end"] is False and d["stop_reason"] == "mode-unavailable"
