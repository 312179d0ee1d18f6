"""Grading worksheets (rigidkin grade) and problem sets (rigidkin variants).

Every correct claim below is written by hand from the physics (closed forms derived on paper, noted
beside each problem), never copied from the engine; each typical mistake is graded incorrect with its
cause named.  The problem is derived once per test process (the grader caches it).
"""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET

import pytest

from rigidkin.base.errors import InputError
from rigidkin.cli import main
from rigidkin.grading import grade, parse_worksheet
from rigidkin.grading.report import as_data, as_html


def _toml(problem: str, steps: list[dict]) -> str:
    out = [f"problem = {json.dumps(problem)}"]
    for s in steps:
        out.append("[[step]]")
        out += [f"{k} = {json.dumps(v)}" for k, v in s.items()]
    return "\n".join(out) + "\n"


def graded(problem: str, steps: list[dict], tmp_path=None):
    path = (tmp_path / "ws.toml") if tmp_path is not None else "worksheet.toml"
    return grade(parse_worksheet(_toml(problem, steps), path))


def check(problem: str, correct: list[dict], mistakes: list[tuple[dict, str]], tmp_path=None):
    """Every correct step graded correct; every mistake incorrect with the cause (a phrase) named."""
    rep = graded(problem, correct, tmp_path)
    for st, res in zip(correct, rep.steps):
        assert res.verdict == "correct", (problem, st, res.feedback)
    rep = graded(problem, [m for m, _ in mistakes], tmp_path)
    for (st, cause), res in zip(mistakes, rep.steps):
        assert res.verdict == "incorrect", (problem, st)
        assert any(cause in f for f in res.feedback), (problem, st, cause, res.feedback)


# ladder: theta from the wall, G = (l/2 sin θ, l/2 cos θ), B = (l sin θ, 0), A = (0, l cos θ).
# a_G = l/2 θ̈ (cos θ, −sin θ) − l/2 θ̇² (sin θ, cos θ); M_B = m g l/2 sin θ − N_A l cos θ;
# about B (moving, a_B = (l cos θ θ̈ − l sin θ θ̇², 0)): M_B = m l²/3 θ̈ + r_BG × m a_B;
# T = m l² θ̇²/6, V = m g l/2 cos θ; θ̈ = 3 g sin θ/(2 l); leaves the wall at cos θ = 2/3.
LADDER_OK = [
    {"kind": "kinematics", "claim": "a_G = l/2*ddot(theta)*(cos(theta)*Ex - sin(theta)*Ey) "
                                    "- l/2*dot(theta)**2*(sin(theta)*Ex + cos(theta)*Ey)"},
    {"kind": "kinematics", "claim": "v_B = l*cos(theta)*dot(theta)*Ex"},
    {"kind": "kinematics", "claim": "omega_rod = dot(theta)*Ez"},
    {"kind": "fbd", "claim": "-m*g*Ey at G; N_A*Ex at A; N_B*Ey at B"},
    {"kind": "balance", "law": "force", "direction": "Ex",
     "claim": "N_A = m*l/2*(ddot(theta)*cos(theta) - dot(theta)**2*sin(theta))"},
    {"kind": "balance", "law": "moment", "point": "G",
     "claim": "-N_A*l/2*cos(theta) + N_B*l/2*sin(theta) = m*l**2/12*ddot(theta)"},
    {"kind": "balance", "law": "moment", "point": "B",
     "claim": "m*g*l/2*sin(theta) - N_A*l*cos(theta) = m*l**2/3*ddot(theta) "
              "- m*l**2/2*cos(theta)*(cos(theta)*ddot(theta) - sin(theta)*dot(theta)**2)"},
    {"kind": "balance", "law": "energy", "claim": "m*l**2/6*dot(theta)**2 + m*g*l/2*cos(theta) = m*g*l/2"},
    {"kind": "balance", "law": "energy", "question": "leaves_wall",
     "claim": "m*l**2/6*dot(theta)**2 + m*g*l/2*cos(theta) = m*g*l/2"},
    {"kind": "eom", "claim": "2*l*ddot(theta) = 3*g*sin(theta)"},
    {"kind": "eom", "claim": "-4*l*ddot(theta)/g + 6*sin(theta) = 0"},           # another factor and arrangement
    {"kind": "answer", "question": "leaves_wall", "claim": "acos(2/3)"},
    {"kind": "answer", "question": "leaves_wall", "claim": "48.19 deg"},
]
LADDER_BAD = [
    ({"kind": "kinematics", "claim": "v_B = l/2*dot(theta)*(cos(theta)*Ex - sin(theta)*Ey)"},
     "transport term missing: the term ω × r_GB"),
    ({"kind": "kinematics", "claim": "a_G = l/2*ddot(theta)*(cos(theta)*Ex - sin(theta)*Ey)"},
     "only the rates were differentiated"),
    ({"kind": "fbd", "claim": "-m*g*Ey at G; N_B*Ey at B"}, "missing from the diagram: normal reaction N_A"),
    ({"kind": "fbd", "claim": "-m*g*Ey at G; N_A*Ex at A; N_B*Ey at B; N_B*Ex at B"}, "extra in the diagram"),
    ({"kind": "fbd", "claim": "m*g*Ey at G; N_A*Ex at A; N_B*Ey at B"}, "sign: weight of rod"),
    ({"kind": "fbd", "claim": "-m*g*Ey at G; N_A*Ex at G; N_B*Ey at B"}, "wrong point: normal reaction N_A"),
    ({"kind": "balance", "law": "moment", "point": "G",
      "claim": "-N_A*l/2*cos(theta) + N_B*l/2*sin(theta) = m*l**2/3*ddot(theta)"},
     "moment of inertia about B was used for moments about the mass centre G"),
    ({"kind": "balance", "law": "moment", "point": "B",
      "claim": "m*g*l/2*sin(theta) - N_A*l*cos(theta) = m*l**2/3*ddot(theta)"},
     "inertial-moment term missing"),
    ({"kind": "balance", "law": "moment", "point": "G",
      "claim": "N_A*l/2*cos(theta) + N_B*l/2*sin(theta) = m*l**2/12*ddot(theta)"},
     "sign: the term N_A·l·cos(θ)/2"),
    ({"kind": "balance", "law": "moment", "point": "G",
      "claim": "-N_A*l/2*cos(theta) + N_B*sin(theta) = m*l**2/12*ddot(theta)"}, "dimension: the term N_B·sin(θ)"),
    ({"kind": "balance", "law": "force", "direction": "Ey", "claim": "N_B - m*g = 0"},
     "the inertia term m ā is missing"),
    ({"kind": "eom", "claim": "2*l*ddot(theta) = -3*g*sin(theta)"}, "sign: the term 3·g·sin(θ)"),
    ({"kind": "eom", "claim": "N_A = 0"}, "free of the unknown reactions"),
    ({"kind": "answer", "question": "leaves_wall", "claim": "acos(1/3)"}, "θ = acos(2/3)"),
    ({"kind": "answer", "question": "leaves_wall", "claim": "-acos(2/3)"}, "sign"),
    ({"kind": "balance", "law": "energy", "question": "leaves_wall",          # released from rest upright
      "claim": "m*l**2/6*dot(theta)**2 + m*g*l/2*cos(theta) = 0"}, "constant: the integral does not hold"),
]


@pytest.mark.slow
def test_ladder_correct_and_mistakes():
    check("ladder", LADDER_OK, LADDER_BAD)


def test_ladder_carried_errors():
    steps = [
        {"kind": "balance", "law": "moment", "point": "B",
         "claim": "m*g*l/2*sin(theta) - N_A*l*cos(theta) = m*l**2/3*ddot(theta)"},
        {"kind": "balance", "law": "force", "direction": "Ex",
         "claim": "N_A = m*l/2*(ddot(theta)*cos(theta) - dot(theta)**2*sin(theta))"},
        # correct elimination of N_A from the two: a consequence of the wrong moment equation
        {"kind": "eom", "claim": "m*g*l/2*sin(theta) - l*cos(theta)*m*l/2*(ddot(theta)*cos(theta) "
                                 "- dot(theta)**2*sin(theta)) = m*l**2/3*ddot(theta)"},
        {"kind": "eom", "claim": "5*l*ddot(theta) = 3*g*sin(theta)"},       # wrong, and not from step 1
    ]
    rep = graded("ladder", steps)
    assert [s.verdict for s in rep.steps] == ["incorrect", "correct", "incorrect", "incorrect"]
    assert rep.steps[2].carried_from == (1,)
    assert any("carried error" in f for f in rep.steps[2].feedback)
    assert rep.steps[3].carried_from == ()
    # a kinematics error carried into the force balance
    rep = graded("ladder", [
        {"kind": "kinematics", "claim": "a_G = l/2*ddot(theta)*(cos(theta)*Ex - sin(theta)*Ey)"},
        {"kind": "balance", "law": "force", "direction": "Ex", "claim": "N_A = m*l/2*ddot(theta)*cos(theta)"},
    ])
    assert rep.steps[1].verdict == "incorrect" and rep.steps[1].carried_from == (1,)


# collar-rod: G = (x + l/2 sin θ, −l/2 cos θ); about the pin P (a_P = ẍ Ex):
# −m2 g l/2 sin θ = m2 l²/3 θ̈ + m2 l/2 cos θ ẍ; x-momentum of both: (m1 + m2) ẍ + m2 l/2 (θ̈ cos θ − θ̇² sin θ) = 0.
COLLAR_OK = [
    {"kind": "kinematics", "claim": "v_G = dot(x)*Ex + l/2*dot(theta)*R.x"},
    {"kind": "kinematics", "claim": "a_G = (ddot(x) + l/2*(ddot(theta)*cos(theta) - dot(theta)**2*sin(theta)))*Ex"
                                    " + l/2*(ddot(theta)*sin(theta) + dot(theta)**2*cos(theta))*Ey"},
    {"kind": "fbd", "body": "rod", "claim": "-m2*g*Ey at G; R_Px*Ex + R_Py*Ey at P"},
    {"kind": "balance", "law": "moment", "point": "P", "body": "rod",
     "claim": "-m2*g*l/2*sin(theta) = m2*l**2/3*ddot(theta) + m2*l/2*cos(theta)*ddot(x)"},
    {"kind": "eom", "claim": "(m1 + m2)*ddot(x) + m2*l/2*(ddot(theta)*cos(theta) - dot(theta)**2*sin(theta)) = 0"},
    {"kind": "eom", "claim": "l/3*ddot(theta) + cos(theta)/2*ddot(x) + g/2*sin(theta) = 0"},
]
COLLAR_BAD = [
    ({"kind": "kinematics", "claim": "v_G = dot(x)*Ex"}, "transport term missing: the term ω × r_PG"),
    ({"kind": "balance", "law": "moment", "point": "P", "body": "rod",
      "claim": "-m2*g*l/2*sin(theta) = m2*l**2/3*ddot(theta)"}, "inertial-moment term missing"),
    ({"kind": "fbd", "body": "rod", "claim": "-m2*g*Ey at G; R_Px*Ex at P"},
     "missing from the diagram: pin reaction R_Py"),
    ({"kind": "eom", "claim": "(m1 + m2)*ddot(x) + m2*l/2*(ddot(theta)*cos(theta) + dot(theta)**2*sin(theta)) = 0"},
     "sign: the term l·m₂·θ̇²·sin(θ)/2"),
]


@pytest.mark.slow
def test_collar_rod_correct_and_mistakes():
    check("collar-rod", COLLAR_OK, COLLAR_BAD)


# collar-force: massless collar at C = x Ex pushed by P, rod pinned at C; the collar carries no inertia, so
# P = R_Ox and the rod's x-balance gives P = m (ẍ + l/2 (θ̈ cos θ − θ̇² sin θ)); about C (a_C = ẍ Ex):
# −m g l/2 sin θ = m l²/3 θ̈ + m l/2 cos θ ẍ.
FORCE_OK = [
    {"kind": "fbd", "body": "rod", "claim": "-m*g*Ey at G; R_Ox*Ex + R_Oy*Ey at C"},
    {"kind": "fbd", "body": "collar", "claim": ["P*Ex at C", "N*Ey at C", "-R_Ox*Ex - R_Oy*Ey at C", "M_track*Ez"]},
    {"kind": "balance", "law": "force", "body": "collar", "direction": "Ex", "claim": "P - R_Ox = 0"},
    {"kind": "eom", "claim": "P = m*(ddot(x) + l/2*(ddot(theta)*cos(theta) - dot(theta)**2*sin(theta)))"},
    {"kind": "balance", "law": "moment", "point": "C", "body": "rod",
     "claim": "-m*g*l/2*sin(theta) = m*l**2/3*ddot(theta) + m*l/2*cos(theta)*ddot(x)"},
]
FORCE_BAD = [
    ({"kind": "balance", "law": "moment", "point": "C", "body": "rod",
      "claim": "-m*g*l/2*sin(theta) = m*l**2/3*ddot(theta)"}, "inertial-moment term missing"),
    ({"kind": "fbd", "body": "collar", "claim": "N*Ey at C; -R_Ox*Ex - R_Oy*Ey at C; M_track*Ez"},
     "missing from the diagram: applied force P"),
    ({"kind": "eom", "claim": "P = m*ddot(x)"}, "both rotation terms missing"),
]


@pytest.mark.slow
def test_collar_force_correct_and_mistakes():
    check("collar-force", FORCE_OK, FORCE_BAD)


# disk-spring-incline: rolling x = r θ, spring force −K x es, gravity along es m g sin β;
# about the contact point (a_P ∥ r_PC): (m g sin β − K x) r = 3/2 m r² θ̈; equilibrium θ = m g sin β/(K r).
DISK_OK = [
    {"kind": "kinematics", "claim": "v_C = r*dot(theta)*es"},
    {"kind": "kinematics", "claim": "omega_disk = -dot(theta)*Ez"},
    {"kind": "fbd", "claim": "-K*x*es at C; -m*g*Ey at C; N*en - F*es at P"},
    {"kind": "balance", "law": "force", "direction": "es", "claim": "m*g*sin(beta) - K*x - F = m*ddot(x)"},
    {"kind": "balance", "law": "moment", "point": "C", "claim": "F*r = m*r**2/2*ddot(theta)"},
    {"kind": "balance", "law": "moment", "point": "P", "claim": "m*g*r*sin(beta) - K*r*x = 3*m*r**2/2*ddot(theta)"},
    {"kind": "eom", "claim": "3/2*m*r**2*ddot(theta) + K*r**2*theta = m*g*r*sin(beta)"},
    {"kind": "answer", "question": "equilibrium", "claim": "m*g*sin(beta)/(K*r)"},
    {"kind": "answer", "question": "equilibrium", "claim": "sqrt(2*K/(3*m))"},   # 3/2 m r² θ̈ + K r² θ = 0
]
DISK_BAD = [
    ({"kind": "balance", "law": "moment", "point": "P", "claim": "m*g*r*sin(beta) - K*r*x = m*r**2/2*ddot(theta)"},
     "parallel-axis term m·d² is missing"),
    ({"kind": "balance", "law": "moment", "point": "C", "claim": "F*r = 3*m*r**2/2*ddot(theta)"},
     "moment of inertia about P was used for moments about the mass centre C"),
    ({"kind": "fbd", "claim": "-K*x*es at C; N*en - F*es at P"}, "missing from the diagram: weight of disk"),
    ({"kind": "eom", "claim": "3/2*m*r**2*ddot(theta) + K*r*theta = m*g*r*sin(beta)"}, "dimension: the term K·r·θ"),
    ({"kind": "eom", "claim": "3/2*m*r**2*ddot(theta) + K*r**2*theta = m*g*r*cos(beta)"}, "missing term"),
]


@pytest.mark.slow
def test_disk_spring_incline_correct_and_mistakes():
    check("disk-spring-incline", DISK_OK, DISK_BAD)


def test_disk_spring_incline_carried_from_diagram():
    rep = graded("disk-spring-incline", [
        {"kind": "fbd", "claim": "-K*x*es at C; N*en - F*es at P"},        # the weight left off
        {"kind": "eom", "claim": "3/2*m*r**2*ddot(theta) + K*r**2*theta = 0"},
    ])
    assert rep.steps[1].verdict == "incorrect" and rep.steps[1].carried_from == (1,)


# slip-to-roll, sliding down (slip speed ẋ − r φ̇ > 0, friction µ N up the slope):
# N = m g cos β, m ẍ = m g sin β − µ N, m r²/2 φ̈ = µ N r.
SLIP_OK = [
    {"kind": "fbd", "claim": "-m*g*Ey at C; N*en at ground; -mu*N*es at ground"},
    {"kind": "balance", "law": "force", "direction": "en", "claim": "N - m*g*cos(beta) = 0"},
    {"kind": "balance", "law": "force", "direction": "es", "claim": "m*g*sin(beta) - mu*N = m*ddot(x)"},
    {"kind": "balance", "law": "moment", "point": "C", "claim": "mu*N*r = m*r**2/2*ddot(phi)"},
    {"kind": "eom", "claim": "ddot(x) = g*sin(beta) - mu*g*cos(beta)"},
    {"kind": "eom", "claim": "r*ddot(phi) = 2*mu*g*cos(beta)"},
]
SLIP_BAD = [
    ({"kind": "balance", "law": "moment", "point": "C", "claim": "mu*N*r = m*r**2*ddot(phi)"},
     "coefficient"),
    ({"kind": "eom", "claim": "ddot(x) = g*sin(beta) - mu*g"}, "missing term: -g·µ·cos(β)"),
    ({"kind": "fbd", "claim": "-m*g*Ey at C; N*en at ground"}, "missing from the diagram: sliding friction"),
]


def test_slip_to_roll_correct_and_mistakes(tmp_path):
    from rigidkin import examples

    # the card's model without its questions (the phases are not graded here)
    card = (examples.HERE / "slip-to-roll.toml").read_text(encoding="utf-8").split("[[ask.question]]")[0]
    (tmp_path / "slip.toml").write_text(card, encoding="utf-8")
    check("slip.toml", SLIP_OK, SLIP_BAD, tmp_path)


# rod-impulse: pivot at the centre O (I_O = m l²/12), torsional spring −K θ, gravity through O:
# m l²/12 θ̈ = −K θ; just after the blow F̂ l/2 = m l²/12 θ̇ → θ̇ = 6 F̂/(m l);
# largest angle from ½ I θ̇² = ½ K θ²: θ = √3 F̂/√(K m).
ROD_OK = [
    {"kind": "fbd", "claim": "-m*g*Ey at O; R_Ox*Ex + R_Oy*Ey at O; -K*theta*Ez"},
    {"kind": "balance", "law": "moment", "point": "O", "claim": "-K*theta = m*l**2/12*ddot(theta)"},
    {"kind": "eom", "claim": "m*l**2*ddot(theta) + 12*K*theta = 0"},
    {"kind": "answer", "question": "after_blow", "claim": "6*F_hat/(m*l)"},
    {"kind": "answer", "question": "after_blow", "claim": 3.0},
    {"kind": "answer", "question": "largest_angle", "claim": "sqrt(3)*F_hat/sqrt(K*m)"},
    {"kind": "balance", "law": "impulse", "claim": "F_hat*l/2 = m*l**2/12*dot(theta)"},   # angular, about O
    {"kind": "balance", "law": "impulse", "claim": "F_hat + R_Ox_hat = 0"},                # linear: G stays at O
]
ROD_BAD = [
    ({"kind": "eom", "claim": "m*l**2/3*ddot(theta) + K*theta = 0"},
     "moment of inertia about B was used for moments about the mass centre O"),
    ({"kind": "fbd", "claim": "-m*g*Ey at O; R_Ox*Ex + R_Oy*Ey at O"}, "missing from the diagram: torsional spring"),
    ({"kind": "answer", "question": "after_blow", "claim": "3*F_hat/(2*m*l)"}, "= 6·F̂/(l·m)"),
    ({"kind": "eom", "claim": "m*l**2/12*ddot(theta) - K*theta = 0"}, "sign: the term -K·θ"),
    ({"kind": "balance", "law": "impulse", "claim": "F_hat*l/2 = m*l**2/3*dot(theta)"},
     "it does not hold just after the blow, where θ̇ = 6·F̂/(l·m)"),
    ({"kind": "balance", "law": "impulse", "claim": "F_hat*l/2 = m*l/12*dot(theta)"}, "dimension"),
]


def test_rod_impulse_correct_and_mistakes():
    check("rod-impulse", ROD_OK, ROD_BAD)


# disk-in-track: C = (R − r)(sin θ, −cos θ); a_C = (R − r) θ̈ et + (R − r) θ̇² er_in (towards O);
# rolling r φ̇ = (R − r) θ̇, T = ¾ m (R − r)² θ̇²; radial N − m g cos θ = m (R − r) θ̇²;
# looping: N ≥ 0 at the top needs v_top² ≥ g (R − r), so v_bottom² ≥ 11 g (R − r)/3.
TRACK_OK = [
    {"kind": "kinematics", "claim": "a_C = (R - r)*ddot(theta)*et + (R - r)*dot(theta)**2*er_in"},
    {"kind": "kinematics", "claim": "omega_disk = -(R - r)/r*dot(theta)*Ez"},
    {"kind": "balance", "law": "force", "direction": "er_in", "claim": "N - m*g*cos(theta) = m*(R - r)*dot(theta)**2"},
    {"kind": "balance", "law": "energy", "claim": "3/4*m*(R - r)**2*dot(theta)**2 - m*g*(R - r)*cos(theta) = 0"},
    {"kind": "eom", "claim": "3/2*(R - r)*ddot(theta) + g*sin(theta) = 0"},
    {"kind": "answer", "question": "speed_to_loop", "claim": "11*g*(R - r)/3"},
]
TRACK_BAD = [
    ({"kind": "kinematics", "claim": "a_C = (R - r)*ddot(theta)*et"}, "only the rates were differentiated"),
    # follows from the a_C of the step before (its radial component left out): carried, one cause
    ({"kind": "balance", "law": "force", "direction": "er_in", "claim": "N - m*g*cos(theta) = 0"},
     "carried error: it follows correctly from your step 1"),
    ({"kind": "eom", "claim": "(R - r)*ddot(theta) + g*sin(theta) = 0"}, "rotational inertia missing"),
    ({"kind": "balance", "law": "energy", "claim": "m*(R - r)**2*dot(theta)**2/2 - m*g*(R - r)*cos(theta) = 0"},
     "rotational inertia missing"),
    ({"kind": "answer", "question": "speed_to_loop", "claim": "5*g*(R - r)"}, "11·g·(R - r)/3"),
]


def test_disk_in_track_correct_and_mistakes():
    check("disk-in-track", TRACK_OK, TRACK_BAD)


# the minimal form, unreadable claims, reports ---------------------------------------------------------
def test_unreadable_claim_and_reports(tmp_path):
    rep = graded("ladder", [{"kind": "eom", "claim": "2*l*ddot(theta) = 3*g*sin(theta) +"},
                            {"kind": "eom", "claim": "2*l*ddot(theta) = 3*g*sin(phi)"},
                            {"kind": "eom", "claim": "2*l*ddot(theta) = 3*g*sin(theta)"}], tmp_path)
    assert [s.verdict for s in rep.steps] == ["unreadable", "unreadable", "correct"]
    assert "not valid syntax" in rep.steps[0].feedback[0] and "'phi' is not declared" in rep.steps[1].feedback[0]
    data = as_data(rep)
    assert data["problem"] == "ladder" and data["score"] == pytest.approx(1 / 3, abs=1e-3)
    assert {"index", "kind", "verdict", "feedback"} <= set(data["steps"][0])
    page = as_html(rep)
    assert "<script" not in page and "Content-Security-Policy" in page


def test_html_escapes_user_text(tmp_path):
    ws = tmp_path / "w.toml"
    ws.write_text('problem = "ladder"\nstudent = "<script>alert(1)</script>"\n[[step]]\nkind = "eom"\n'
                  'claim = "<b>ddot(theta)</b> = 0"\n', encoding="utf-8")
    out = tmp_path / "r.html"
    assert main(["grade", str(ws), "--format", "html", "-o", str(out)]) == 1
    page = out.read_text(encoding="utf-8")
    assert "<script>alert" not in page and "&lt;script&gt;" in page and "&lt;b&gt;" in page


def test_cli_exit_status_and_json(tmp_path, capsys):
    ws = tmp_path / "w.toml"
    ws.write_text(_toml("ladder", LADDER_OK[8:10]), encoding="utf-8")
    assert main(["grade", str(ws), "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["score"] == 1.0 and [s["verdict"] for s in data["steps"]] == ["correct", "correct"]
    ws.write_text(_toml("ladder", [LADDER_BAD[11][0]]), encoding="utf-8")
    assert main(["grade", str(ws)]) == 1
    assert "sign" in capsys.readouterr().out


def test_problem_file_relative_to_worksheet(tmp_path):
    from rigidkin import examples

    (tmp_path / "mine.toml").write_text((examples.HERE / "rod-impulse.toml").read_text(encoding="utf-8"),
                                        encoding="utf-8")
    rep = grade(parse_worksheet(_toml("mine.toml", ROD_OK[2:3]), tmp_path / "ws.toml"))
    assert rep.steps[0].verdict == "correct"


# hostile and malformed worksheets: refused, exit status 2, one paragraph --------------------------------
HOSTILE = [
    ('problem = "ladder"\n[[step]]\nkind = "eom"\nclaim = "__import__(\'os\').system(\'id\')"\n', "starting with '_'"),
    ('problem = "ladder"\n[[step]]\nkind = "eom"\nclaim = "x\\u001b[2J = 0"\n', "control character"),
    ('problem = "ladder"\n[[step]]\nkind = "shell"\nclaim = "x = 0"\n', "is not a kind of step"),
    ('problem = "ladder"\n[[step]]\nkind = "eom"\nclaim = "' + "x" * 2000 + '"\n', "characters long"),
    ('problem = "ladder"\n[[step]]\nkind = "eom"\n', "has no claim"),
    ('problem = "ladder"\nrun = "rm -rf /"\n[[step]]\nkind = "eom"\nclaim = "x = 0"\n', "unknown field 'run'"),
    ('problem = "/etc/passwd"\n[[step]]\nkind = "eom"\nclaim = "x = 0"\n', "neither a bundled example"),
    ('problem = "../../nothing.toml"\n[[step]]\nkind = "eom"\nclaim = "x = 0"\n', "there is no problem file"),
    ('problem = "ladder"\n' + "[[step]]\nkind = \"eom\"\nclaim = \"x = 0\"\n" * 300, "steps (at most"),
    ("problem = \"ladder\"\nstep = [" * 30 + "]" * 30 + "\n", "nested"),
    ('problem = "ladder"\n[[step]]\nkind = "answer"\nquestion = "nope"\nclaim = "1"\n', "no question named 'nope'"),
    ('problem = "ladder"\n[[step]]\nkind = "balance"\npoint = "Z"\nlaw = "moment"\nclaim = "N_A = 0"\n',
     "no point named 'Z'"),
    ("problem = [1, 2]\n", "expected a string"),
    ("problem = \"ladder\"\n[[step]\n", "TOML syntax error"),
]


@pytest.mark.parametrize("text,message", HOSTILE)
def test_hostile_worksheets_refused(tmp_path, capsys, text, message):
    ws = tmp_path / "w.toml"
    ws.write_text(text, encoding="utf-8")
    assert main(["grade", str(ws)]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and err.count("\n") == 1


def test_worksheet_not_utf8(tmp_path, capsys):
    ws = tmp_path / "w.toml"
    ws.write_bytes(b'problem = "\xff"\n')
    assert main(["grade", str(ws)]) == 2
    assert "not UTF-8" in capsys.readouterr().err


def test_parse_errors_name_line_and_field(tmp_path):
    with pytest.raises(InputError) as exc:
        parse_worksheet('problem = "ladder"\n\n[[step]]\nkind = "eom"\nclaim = "x = 0"\n\n[[step]]\nkind = "fbd"\n'
                        'claim = 3\n', tmp_path / "w.toml")
    assert "line 9" in str(exc.value) and "step[1].claim" in str(exc.value)


# problem sets -------------------------------------------------------------------------------------------
@pytest.mark.slow
def test_variants_keys_checked_and_moodle_xml(tmp_path, capsys):
    out = tmp_path / "set.xml"
    assert main(["variants", "rod-impulse", "--count", "3", "--seed", "7", "--vary", "m=1:3",
                 "--vary", "F_hat=0.5:2", "--format", "json", "-o", str(out)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["variants"]) == 3
    for v in data["variants"]:
        m, F = v["parameters"]["m"]["value"], v["parameters"]["F_hat"]["value"]
        assert 1 <= m <= 3 and 0.5 <= F <= 2
        keys = {k["question"]: k for k in v["answers"]}
        # by hand: θ̇ = 6 F̂/(m l) with l = 1 m; θ_max = √3 F̂/√(K m) with K = 20 N·m/rad
        assert keys["after_blow"]["value"] == pytest.approx(6 * F / m, rel=1e-9)
        assert keys["largest_angle"]["value"] == pytest.approx(math.sqrt(3) * F / math.sqrt(20 * m), rel=1e-9)
        assert keys["after_blow"]["tolerance"] == pytest.approx(0.01 * 6 * F / m)
    root = ET.parse(out).getroot()
    qs = root.findall("question[@type='numerical']")
    assert len(qs) == 6
    assert float(qs[0].find("answer/text").text) == pytest.approx(data["variants"][0]["answers"][0]["value"])
    # the same seed gives the same set
    assert main(["variants", "rod-impulse", "--count", "3", "--seed", "7", "--vary", "m=1:3",
                 "--vary", "F_hat=0.5:2", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out) == data


def test_variants_escape_problem_text(tmp_path):
    from rigidkin import examples

    src = (examples.HERE / "rod-impulse.toml").read_text(encoding="utf-8")
    src = src.replace('title = "Rod on a central pivot struck by an impulse"',
                      'title = "Rod ]]> <b>&amp; </questiontext>"')
    (tmp_path / "p.toml").write_text(src, encoding="utf-8")
    out = tmp_path / "set.xml"
    assert main(["variants", str(tmp_path / "p.toml"), "--count", "1", "--vary", "m=1:2", "-o", str(out)]) == 0
    root = ET.parse(out).getroot()           # well-formed
    name = root.find("question[@type='numerical']/name/text").text
    assert "</questiontext>" in name          # read back as the text it was, not as markup


@pytest.mark.parametrize("args,message", [
    (["--vary", "nope=1:2"], "no parameter named 'nope'"),
    (["--vary", "m=3:1"], "LOW must be below HIGH"),
    (["--vary", "m=-1:2"], "must be above 0"),
    (["--vary", "m"], "NAME=LOW:HIGH"),
    (["--count", "0"], "out of range"),
])
def test_variants_bad_input(capsys, args, message):
    assert main(["variants", "rod-impulse", *args]) == 2
    assert message in capsys.readouterr().err


def test_claim_that_would_expand_hugely_is_graded():
    """A claim whose expansion would be huge is graded without expanding it (its time: benchmarks/grading.py)."""
    rep = graded("ladder", [{"kind": "balance", "claim": CLAIM_12}])
    assert rep.steps[0].verdict == "incorrect"


CLAIM_12 = "N_A*(m + l + g + theta + dot(theta) + sin(theta) + cos(theta))**12 = ddot(theta)"


def test_worksheet_mode_rolling(tmp_path):
    from rigidkin import examples

    card = (examples.HERE / "slip-to-roll.toml").read_text(encoding="utf-8").split("[[ask.question]]")[0]
    (tmp_path / "slip.toml").write_text(card, encoding="utf-8")
    # rolling (r φ̇ = ẋ): m ẍ = m g sin β − F, m r²/2 φ̈ = F r → 3/2 ẍ = g sin β
    text = ('problem = "slip.toml"\nmode = { ground = "stick" }\n[[step]]\nkind = "eom"\n'
            'claim = "3/2*ddot(x) = g*sin(beta)"\n[[step]]\nkind = "eom"\nclaim = "ddot(x) = g*sin(beta)"\n')
    rep = grade(parse_worksheet(text, tmp_path / "ws.toml"))
    assert [s.verdict for s in rep.steps] == ["correct", "incorrect"]
    assert "rotational inertia missing" in rep.steps[1].feedback[0]


# a top with Euler parameters and body angular speeds (issue-18 speeds): the engine's equations are in
# ẇ; a hand derivation writes Euler's equations on |e| = 1, I1 ẇ1 + (I3 − I1) w2 w3 = M1 with the gravity
# moment M1 = m g l (b2·Ez) = 2 m g l (e0 e1 + e2 e3).  Graded on unit Euler parameters; a wrong equation
# is never graded correct (the accelerations ẇ are the unknowns, not a quasi-coordinate's q̈).
@pytest.mark.slow
def test_quaternion_top_euler_equations(tmp_path):
    import re
    from pathlib import Path

    src = (Path(__file__).parent / "test_speeds_quaternion.py").read_text(encoding="utf-8")
    (tmp_path / "top.toml").write_text(re.search(r'TOP_FILE = """(.*?)"""', src, re.S).group(1), encoding="utf-8")
    euler = "I1*ddot(w1_int) + (I3 - I1)*dot(w2_int)*dot(w3_int)"
    check("top.toml",
          [{"kind": "eom", "claim": f"{euler} = 2*m*g*l*(e0*e1 + e2*e3)"},
           {"kind": "eom", "claim": "I3*ddot(w3_int) = 0"},
           # the speeds by their own names: w, and dot(w) for its rate
           {"kind": "eom", "claim": "I1*dot(w1) + (I3 - I1)*w2*w3 = 2*m*g*l*(e0*e1 + e2*e3)"},
           {"kind": "kinematics", "claim": "omega_B = w1*b1 + w2*b2 + w3*b3"}],
          [({"kind": "eom", "claim": f"{euler} = 0"}, "missing term"),
           ({"kind": "eom", "claim": f"{euler} = -2*m*g*l*(e0*e1 + e2*e3)"}, "has the wrong sign"),
           ({"kind": "eom", "claim": "I1*ddot(w1_int) = 5*m*g*l"}, ""),
           ({"kind": "kinematics", "claim": "omega_B = w1*b1 + w2*b2"}, "component along b3")],
          tmp_path)
    rep = graded("top.toml", [{"kind": "eom", "claim": "I1*ddot(w1) = 0"}], tmp_path)
    assert rep.steps[0].verdict == "unreadable" and "dot(w1) is already its rate" in rep.steps[0].feedback[0]
