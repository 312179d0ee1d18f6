"""Reports: notation, the document's order and completeness, HTML/Markdown/LaTeX output, the CLI."""

from __future__ import annotations

import re
import shutil
import subprocess
import xml.dom.minidom

import pytest
import sympy as sp
from sympy.physics.vector import dynamicsymbols

import rigidkin as rk
from rigidkin import examples
from rigidkin.base.trace import SECTIONS
from rigidkin.cli import main
from rigidkin.report import REPORT_SECTIONS, build_document, render
from rigidkin.report.blocks import Equations, Step
from rigidkin.report.notation import latex, mathml, split_label

t = dynamicsymbols._t


@pytest.fixture(scope="module")
def ladder():
    return examples.build("ladder").solve()


@pytest.fixture(scope="module")
def ladder_doc(ladder):
    return build_document(ladder, figures=True, checks=False)


# notation -----------------------------------------------------------------------------------------
def _xml(s: str):
    return xml.dom.minidom.parseString(s)


def test_mathml_dots_and_greek_are_well_formed():
    th = dynamicsymbols("theta")
    m = mathml((th.diff(t, 2), 3 * sp.Symbol("g") * sp.sin(th) / (2 * sp.Symbol("l"))), display=True)
    dom = _xml(m)  # well-formed XML (numeric character references only)
    movers = dom.getElementsByTagName("mover")
    assert len(movers) == 1
    assert movers[0].getAttribute("accent") == "false"              # an over-script: the font's gap above θ
    assert movers[0].lastChild.firstChild.data == "\u00a8"          # two dots: θ̈
    assert "θ" in "".join(n.firstChild.data for n in dom.getElementsByTagName("mi"))
    assert dom.getElementsByTagName("mfrac")
    assert "(t)" not in m and "mfenced" not in m                      # MathML Core: no mfenced


def test_vectors_print_with_the_users_basis_names():
    s = rk.System("v")
    th = s.coordinate("theta")
    A = s.frame("A", angle=th, basis=("er", "etheta", "ez"))
    v = 2 * A.er - sp.Symbol("l") * th.diff(t) * A.etheta + s.inertial.Ey
    tex = latex(v)
    assert tex == r"2\,\mathbf{e}_{r} - l \dot{\theta}\,\mathbf{e}_{\theta} + \mathbf{E}_{y}"
    dom = _xml(mathml(v))
    bold = [n for n in dom.getElementsByTagName("mi") if "bold" in n.getAttribute("style")]
    assert [n.firstChild.data for n in bold] == ["e", "e", "E"]
    subs = [n.lastChild.firstChild.data for n in dom.getElementsByTagName("msub")]
    assert subs == ["r", "θ", "y"]


def test_dyadic_latex_and_labels():
    sol = examples.build("ladder").solve()
    step = [s for s in sol.trace.steps if s.title.startswith("Inertia and angular momentum")][0]
    tex = latex(step.equations[0])
    assert r"\frac{m l^{2}}{12}\,\mathbf{e}_{x}\otimes \mathbf{e}_{x}" in tex      # m l², the mass first
    assert split_label("normal_reaction_N_A") == ("normal reaction", "N_A")
    assert split_label("weight_of_rod") == ("weight of rod", "")
    assert split_label("omega_rod") == ("", "omega_rod")
    assert split_label("N_A") == ("", "N_A")
    assert latex(sp.Symbol("normal_reaction_N_A")) == r"\text{normal reaction}\ N_{A}"


# the document ---------------------------------------------------------------------------------------
def test_sections_follow_the_method(ladder_doc):
    titles = [s.title for s in ladder_doc.sections]
    method = [s for s in SECTIONS if s not in ("Answers", "Checks")]
    assert titles == ["Problem", "Parameters and coordinates", *method, "Answers", "Checks", "Simulation"]
    assert [k for k, _ in REPORT_SECTIONS] == [s.key for s in ladder_doc.sections]


def test_every_trace_step_is_in_the_document_once(ladder, ladder_doc):
    steps = [b for s in ladder_doc.sections for b in s.blocks if isinstance(b, Step)]
    in_method_order = sorted(ladder.trace.steps, key=lambda s: SECTIONS.index(s.section))  # stable
    assert [(s.title, s.why) for s in steps] == [(s.title, s.why) for s in in_method_order]
    eqs = sum(len(s.equations) for s in steps)
    assert eqs == sum(len(s.equations) for s in ladder.trace.steps)


def test_answers_hold_the_card_result(ladder_doc):
    """Card ladder (a): θ̈ = 3 g sin θ / (2 l) while both contacts hold."""
    th = examples.build("ladder").coordinates[0]
    g, l = sp.symbols("g l", positive=True)
    found = [m.obj for b in ladder_doc.section("answers").blocks if isinstance(b, Equations) for m in b.items
             if isinstance(m.obj, tuple) and m.obj[0] == th.diff(t, 2)]
    assert len(found) == 1
    assert sp.simplify(found[0][1] - 3 * g * sp.sin(th) / (2 * l)) == 0


def test_parameters_table_has_units_and_values(ladder_doc):
    params, coords = [b for b in ladder_doc.section("inputs").blocks]
    rows = {str(r[0].obj): r for r in params.rows}
    assert rows["g"][2] == "m/s^2" and rows["g"][3] == "9.81"
    crow = {str(r[0].obj): r for r in coords.rows}
    assert crow["theta(t)"][3] == "rad" and crow["theta(t)"][4] == "independent"
    assert crow["x(t)"][3] == "m" and crow["x(t)"][4] == "dependent"
    assert "wall" in crow["theta(t)"][1]


# renderers ------------------------------------------------------------------------------------------
def test_html_is_self_contained(ladder_doc):
    page = render(ladder_doc, "html")
    for key, _ in REPORT_SECTIONS:
        assert f'<section id="{key}">' in page
    urls = set(re.findall(r"https?://[^\s\"'<>)]+", page))
    assert urls <= {"http://www.w3.org/1998/Math/MathML"}, urls
    assert "<link" not in page and 'src="http' not in page
    assert "Content-Security-Policy" in page
    for m in re.findall(r"<math .*?</math>", page, flags=re.S):
        _xml(m)
    assert page.count('class="step"') == len([b for s in ladder_doc.sections for b in s.blocks
                                               if isinstance(b, Step)])
    assert '<img src="data:image/png;base64,' in page


def test_markdown_has_math_and_figure_files(ladder_doc, tmp_path):
    from rigidkin.report import write_document

    out = write_document(ladder_doc, tmp_path / "ladder.md")
    md = out.read_text()
    assert md.count("$$") % 2 == 0 and md.count("$$") >= 20
    assert r"\ddot{\theta} = \frac{3 g \sin{\left(\theta \right)}}{2 l}" in md
    assert (tmp_path / "ladder_files" / "fbd.png").read_bytes()[:4] == b"\x89PNG"
    assert "](ladder_files/fbd.png)" in md


TEX = next((e for e in ("pdflatex", "lualatex", "xelatex") if shutil.which(e)), None)


@pytest.mark.skipif(TEX is None, reason="no TeX engine (pdflatex, lualatex, xelatex) is installed")
@pytest.mark.parametrize("name", ["ladder", "disk-in-track"])
def test_latex_compiles(name, tmp_path):
    from rigidkin.report import write_report

    sol = examples.build(name).solve()
    path = write_report(sol, tmp_path / f"{name}.tex", checks=False)
    run = subprocess.run([TEX, "-interaction=nonstopmode", "-halt-on-error", path.name], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout[-2000:]
    assert (tmp_path / f"{name}.pdf").stat().st_size > 10_000
    assert "Missing character" not in (tmp_path / f"{name}.log").read_text(errors="replace")


# command line ---------------------------------------------------------------------------------------
def test_cli_report_writes_html(tmp_path, capsys):
    out = tmp_path / "collar.html"
    assert main(["report", "collar-rod", "-o", str(out), "--no-checks", "--at", "theta=0.3"]) == 0
    page = out.read_text()
    assert "Free-body diagrams at x = 0, θ = 0.3" in page
    assert page.count("<math") > 20


@pytest.mark.parametrize("argv, words", [
    (["report", "ladder", "-o", "out.pdf"], "extensions .html, .md or .tex"),
    (["report", "ladder", "-o", "x.html", "--at", "theta"], "NAME=VALUE"),
    (["report", "ladder", "-o", "x.html", "--at", "psi=1"], "not a coordinate"),
    (["report", "ladder", "-o", "x.html", "--gif", "a.gif"], "--gif needs a simulation"),
    (["report", "ladder", "-o", "x.html", "--simulate", "-1"], "positive end time"),
    (["report", "ladder", "-o", "/nonexistent-dir/x.html", "--no-figures", "--no-checks"], "cannot write"),
])
def test_cli_report_errors_are_one_paragraph(argv, words, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("rigidkin: ") and words in err
    assert "Traceback" not in err


# cross-check ----------------------------------------------------------------------------------------
def test_check_section_shows_each_verdict_and_a_disagreement_with_both_forms():
    from types import SimpleNamespace

    from rigidkin.report.blocks import Math, Paragraph, Table
    from rigidkin.report.document import check_table

    th = dynamicsymbols("theta")
    good = SimpleNamespace(law="kane", equation="θ̈", status="agrees", how="symbolic: identical", ours=None,
                           reference=None)
    bad = SimpleNamespace(law="lagrange", equation="θ̈", status="disagrees", how="numerical at 24 states",
                          ours=2 * sp.sin(th), reference=3 * sp.sin(th))
    report = SimpleNamespace(verdicts=(good, bad), reference="newton-euler", ok=False, dimensions=(),
                             expectations=(), notes=("a note",))
    blocks = check_table(report)
    assert "DISAGREEMENT" in blocks[0].text
    table = next(b for b in blocks if isinstance(b, Table))
    assert table.rows == (("kane", "θ̈", "agrees", "symbolic: identical"),
                          ("lagrange", "θ̈", "disagrees", "numerical at 24 states"))
    eqs = next(b for b in blocks if isinstance(b, Equations))
    assert eqs.items == (Math(2 * sp.sin(th)), Math(3 * sp.sin(th)))
    assert isinstance(blocks[-1], Paragraph) and blocks[-1].text == "a note"


@pytest.mark.skipif(not hasattr(rk.Solution, "check"), reason="Solution.check (the cross-check) is not available")
def test_check_section_is_the_solutions_cross_check(ladder):
    from rigidkin.report.blocks import Table

    doc = build_document(ladder, figures=False, checks=True)
    tables = [b for b in doc.section("checks").blocks if isinstance(b, Table)]
    verdicts = ladder.check().verdicts
    assert [r[:3] for r in tables[0].rows] == [(v.law, v.equation, v.status) for v in verdicts]
    assert {r[2] for r in tables[0].rows} == {"agrees"}      # every law agrees on the ladder


def test_cli_report_answers_the_files_questions(tmp_path):
    """Card ladder (b): released from rest upright, the rod leaves the wall at θ = arccos(2/3)."""
    from pathlib import Path

    problem = Path(__file__).resolve().parents[1] / "examples" / "ladder.toml"
    out = tmp_path / "ladder.html"
    assert main(["report", str(problem), "-o", str(out), "--no-figures", "--no-checks"]) == 0
    page = out.read_text()
    row = re.search(r"<tr><td>leaves_wall</td>.*?</tr>", page, flags=re.S).group(0)
    math = re.search(r"<math .*?</math>", row, flags=re.S).group(0)
    assert re.sub(r"\s", "", math).count("<mi>arccos</mi>") == 1
    assert "<mfrac><mn>2</mn><mn>3</mn></mfrac>" in math
    assert "48.19°" in row


def test_cli_report_stops_at_its_time_limit(tmp_path, capsys):
    assert main(["report", "collar-rod", "-o", str(tmp_path / "x.html"), "--timeout", "0.001"]) == 4
    err = capsys.readouterr().err
    assert "took longer than 0.001 s" in err and "Traceback" not in err
