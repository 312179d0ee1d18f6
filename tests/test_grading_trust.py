"""Grading an instructor can trust (issue 30): the stated motion fixes the friction regime, an answer is
judged against the quantity asked, problem sets keep every question, a path on disk means that file.

References: the sliding regime of the cylinder from its slip speed (ẋ − r φ̇ > 0 down the slope, friction
µ N up it); the sphere leaving a fixed sphere at cos φ = 10/17 (energy m g (R + r)(1 − cos φ) = 7/10 m v²
with N = 0: g cos φ = v²/(R + r)); the disk on a spring: θ_eq = m g sin β/(K r), ω_n² = K r²/(3/2 m r²).
"""

from __future__ import annotations

import json
import math
import os
import xml.etree.ElementTree as ET

import pytest

from rigidkin.base.errors import InputError
from rigidkin.cli import main
from rigidkin.grading import grade, parse_worksheet


def _ws(problem, steps, motion=""):
    out = [f"problem = {json.dumps(problem)}"] + ([f"motion = {json.dumps(motion)}"] if motion else [])
    for s in steps:
        out.append("[[step]]")
        out += [f"{k} = {json.dumps(v)}" for k, v in s.items()]
    return "\n".join(out) + "\n"


def graded(problem, steps, path, motion=""):
    return grade(parse_worksheet(_ws(problem, steps, motion), path / "ws.toml"))


@pytest.fixture(scope="module")
def slip_card(tmp_path_factory):
    from rigidkin import examples

    d = tmp_path_factory.mktemp("slip")
    card = (examples.HERE / "slip-to-roll.toml").read_text(encoding="utf-8").split("[[ask.question]]")[0]
    (d / "slip.toml").write_text(card, encoding="utf-8")
    return d


DOWN = [{"kind": "balance", "law": "force", "direction": "es", "claim": "m*g*sin(beta) - mu*N = m*ddot(x)"},
        {"kind": "balance", "law": "force", "direction": "es", "claim": "m*g*sin(beta) + mu*N = m*ddot(x)"},
        {"kind": "fbd", "claim": "-m*g*Ey at C; N*en at ground; mu*N*es at ground"}]


def test_stated_motion_fixes_the_regime(slip_card):
    rep = graded("slip.toml", DOWN, slip_card, motion="dot(x) - r*dot(phi) > 0")
    assert [s.verdict for s in rep.steps] == ["correct", "incorrect", "incorrect"]
    for s in rep.steps[1:]:
        assert len(s.feedback) == 1 and s.feedback[0].startswith("friction drawn along the motion")
    # the other motion: the other regime is the right one
    rep = graded("slip.toml", DOWN, slip_card, motion="dot(x) - r*dot(phi) < 0")
    assert [s.verdict for s in rep.steps] == ["incorrect", "correct", "correct"]


def test_open_regime_is_the_students_choice_carried(slip_card):
    rep = graded("slip.toml", [DOWN[2], DOWN[0], DOWN[1]], slip_card)
    assert [s.verdict for s in rep.steps] == ["correct", "incorrect", "correct"]
    assert "your choice in step 1" in rep.steps[0].feedback[0]
    assert "your step 1 took" in rep.steps[1].feedback[0]


def test_motion_that_selects_no_regime_is_refused(slip_card):
    with pytest.raises(InputError, match="does not select one sliding regime"):
        graded("slip.toml", DOWN[:1], slip_card, motion="dot(x) > 0")
    with pytest.raises(InputError, match="the motion cannot be read"):
        graded("slip.toml", DOWN[:1], slip_card, motion="dot(x) >> 0")


def test_sphere_event_judged_against_the_quantity_asked(tmp_path):
    phi = math.acos(10 / 17)
    steps = [{"kind": "answer", "question": "leaves_sphere", "claim": c} for c in
             ("acos(10/17)", f"{math.degrees(phi):.2f} deg", f"{phi:.4f}", "phi = acos(10/17)", "0.8411 kg",
              f"{math.degrees(phi):.2f}")]
    steps.append({"kind": "answer", "question": "leaves_sphere", "quantity": "phi", "claim": "(R + r)*acos(10/17)/r"})
    rep = graded("sphere-on-sphere", steps, tmp_path)
    assert [s.verdict for s in rep.steps] == ["correct"] * 4 + ["incorrect", "unreadable", "incorrect"]
    assert "dimension M" in rep.steps[4].feedback[0]
    assert "ambiguous" in rep.steps[5].feedback[0]
    assert rep.steps[6].feedback[0].startswith("wrong quantity: this is θ")


def test_equilibrium_kinds_are_distinct(tmp_path):
    wn = math.sqrt(2 * 50 / (3 * 2))            # K = 50, m = 2 in the card
    steps = [{"kind": "answer", "question": "equilibrium", "quantity": "frequency", "claim": c}
             for c in ("0", "pi", f"{wn:.4f}", f"{wn:.4f} rad/s")]
    steps += [{"kind": "answer", "question": "equilibrium", "claim": "omega_n = 0"},
              {"kind": "answer", "question": "equilibrium", "claim": "sqrt(2*K/(3*m))"},
              {"kind": "answer", "question": "equilibrium", "quantity": "stability", "claim": "unstable"}]
    rep = graded("disk-spring-incline", steps, tmp_path)
    assert [s.verdict for s in rep.steps] == ["incorrect", "incorrect", "correct", "correct", "incorrect", "correct",
                                              "incorrect"]


def test_unknown_quantity_is_unreadable(tmp_path):
    rep = graded("sphere-on-sphere", [{"kind": "answer", "question": "leaves_sphere", "quantity": "psi",
                                       "claim": "1"}], tmp_path)
    assert rep.steps[0].verdict == "unreadable" and "states no quantity 'psi'" in rep.steps[0].feedback[0]


# problem sets --------------------------------------------------------------------------------------------
def test_variants_keep_every_question(capsys):
    # the equilibrium: position and frequency keys, each equal to the closed form at the variant's values
    assert main(["variants", "disk-spring-incline", "--count", "2", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for v in data["variants"]:
        p = {n: x["value"] for n, x in {**v["parameters"], **v["kept"]}.items()}
        keys = {k["quantity"].split(" — ")[0]: k["value"] for k in v["answers"]}
        beta = p["beta"] if p["beta"] < 1.6 else math.radians(p["beta"])
        assert math.isclose(keys["θ"], p["m"] * p["g"] * math.sin(beta) / (p["K"] * p["r"]), rel_tol=1e-6)
        assert math.isclose(keys["ω_n"], math.sqrt(2 * p["K"] / (3 * p["m"])), rel_tol=1e-6)
    assert data["left_out"] == []


def test_variants_state_function_at_the_start_and_left_out(tmp_path, capsys):
    from rigidkin import examples

    # the ladder's wall reaction along the motion from rest upright, a function of θ, is keyed at the declared
    # θ = 0.3: θ̇² = 3 g (1 − cos θ)/l, θ̈ = 3 g sin θ/(2 l), N_A = m l/2 (θ̈ cos θ − θ̇² sin θ)
    # = 3/4 m g sin θ (3 cos θ − 2)
    assert main(["variants", "ladder", "--count", "1", "--format", "json"]) == 0
    v = json.loads(capsys.readouterr().out)["variants"][0]
    m = v["parameters"]["m"]["value"]
    key = next(k for k in v["answers"] if k["question"] == "wall_reaction")
    assert "along the motion of the question" in key["quantity"]
    assert math.isclose(key["value"], 0.75 * m * 9.81 * math.sin(0.3) * (3 * math.cos(0.3) - 2), rel_tol=1e-6)
    # without a declared start the reaction has no number: named, with why, and exit status 1
    src = (examples.HERE / "ladder.toml").read_text(encoding="utf-8").replace(", initial = 0.3, rate = 0", "")
    (tmp_path / "p.toml").write_text(src, encoding="utf-8")
    assert main(["variants", str(tmp_path / "p.toml"), "--count", "1"]) == 1
    out = capsys.readouterr().out
    assert "Left out of every variant: wall_reaction: its answer" in out and "function of the state" in out


def test_moodle_and_prairielearn_say_what_is_asked(tmp_path, capsys):
    out = tmp_path / "set.xml"
    pl = tmp_path / "pl"
    assert main(["variants", "sphere-on-sphere", "--count", "2", "-o", str(out), "--prairielearn", str(pl)]) == 0
    capsys.readouterr()
    texts = [q.find("questiontext/text").text for q in ET.parse(out).getroot().findall("question[@type='numerical']")]
    assert any("give φ (angle of the line of centres OC from the upward vertical, clockwise), in rad" in x
               for x in texts)
    assert not any("SI units" in x for x in texts)
    folders = sorted(p.name for p in pl.iterdir())
    assert len(folders) == 2
    for f in folders:
        info = json.loads((pl / f / "info.json").read_text(encoding="utf-8"))
        assert info["type"] == "v3" and info["uuid"]
        html = (pl / f / "question.html").read_text(encoding="utf-8")
        assert html.count("<pl-number-input") == 4 and "give φ" in html     # ρ = R + r, ρ̇ = 0: not asked
        ns = {}
        exec(compile((pl / f / "server.py").read_text(encoding="utf-8"), "server.py", "exec"), ns)  # noqa: S102
        data = {"correct_answers": {}}
        ns["generate"](data)
        assert math.isclose(data["correct_answers"]["a2"], math.acos(10 / 17), rel_tol=1e-9)


# a path on disk ------------------------------------------------------------------------------------------
def test_folder_named_like_an_example_does_not_hide_it(tmp_path, capsys):
    (tmp_path / "collar-rod").mkdir()
    (tmp_path / "collar-rod" / "ws.toml").write_text(_ws("collar-rod", [
        {"kind": "eom", "claim": "l/3*ddot(theta) + cos(theta)/2*ddot(x) + g/2*sin(theta) = 0"}]), encoding="utf-8")
    here = os.getcwd()
    os.chdir(tmp_path)
    try:
        assert main(["grade", "collar-rod/ws.toml"]) == 0
        from rigidkin.io.load import load_system

        assert load_system("collar-rod")[0].title == "Collar on a track with a pendulum rod"   # solve collar-rod
        assert main(["list"]) == 0
        assert "a folder 'collar-rod' is here" in capsys.readouterr().out
    finally:
        os.chdir(here)


def test_file_beside_the_worksheet_wins(tmp_path):
    from rigidkin import examples
    from rigidkin.io.locate import resolve_problem

    (tmp_path / "ladder").write_text((examples.HERE / "ladder.toml").read_text(encoding="utf-8"), encoding="utf-8")
    assert resolve_problem("ladder", tmp_path) == ("file", tmp_path / "ladder")
    assert resolve_problem("ladder", tmp_path / "elsewhere") == ("example", "ladder")


def test_template_says_what_each_question_asks(capsys):
    import tomllib

    assert main(["grade", "--template", "sphere-on-sphere"]) == 0
    text = capsys.readouterr().out
    data = tomllib.loads(text)
    assert data["problem"] == "sphere-on-sphere"
    answers = [s for s in data["step"] if s["kind"] == "answer"]
    assert answers and all(s["question"] == "leaves_sphere" for s in answers)
    assert "asks φ (angle of the line of centres OC from the upward vertical, clockwise), in rad" in text
    assert main(["grade"]) == 2


def test_report_says_what_is_asked(tmp_path):
    from rigidkin.grading.report import as_data, as_html

    rep = graded("sphere-on-sphere", [{"kind": "answer", "question": "leaves_sphere", "claim": "acos(10/17)"}],
                 tmp_path)
    assert "φ (angle of the line of centres" in as_data(rep)["steps"][0]["asks"]
    assert "The question asks: " in as_html(rep)
