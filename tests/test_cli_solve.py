"""The command line: every bundled problem file solves from ``rigidkin solve`` and its JSON equations of
motion agree with the Python model's accelerations; answers, text, LaTeX, list, validate, python -m."""

import json
import random

import pytest
import sympy as sp
from helpers import rigidkin_process

from rigidkin.cli import main
from rigidkin.examples import HERE, build

CARDS = ["boulder-push", "collar-force", "collar-rod", "disk-in-track", "disk-spring-incline", "ladder",
         "paper-pull", "rod-impulse", "slip-to-roll", "sphere-on-sphere"]


def run_cli(capsys, *argv) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def read_back(data: dict, text: str):
    """sympy.parse_expr of a JSON expression, with the problem's names as symbols and functions of t.

    (Names such as beta or N are sympy functions in parse_expr's default namespace.)"""
    local = {"t": sp.Symbol("t")}
    local.update({p: sp.Symbol(p) for p in data["parameters"]})
    local.update({q: sp.Function(q) for q in data["coordinates"]})
    return sp.parse_expr(text, local_dict=local)


def plain(expr):
    """q(t), q̇, q̈ → symbols q, q_d1, q_d2; every symbol by its name (assumptions dropped)."""
    repl = {}
    for d in expr.atoms(sp.Derivative):
        repl[d] = sp.Symbol(f"{d.expr.func.__name__}_d{d.derivative_count}")
    expr = expr.xreplace(repl)
    funcs = {f: sp.Symbol(f.func.__name__) for f in expr.atoms(sp.Function)
             if isinstance(f.func, sp.core.function.UndefinedFunction)}
    expr = expr.xreplace(funcs)
    return expr.xreplace({s: sp.Symbol(s.name) for s in expr.free_symbols})


def agree(a, b, n=12, seed=1) -> bool:
    """Numerical agreement of two expressions at random values of every name (parameters positive)."""
    a, b = plain(sp.sympify(a)), plain(sp.sympify(b))
    names = sorted(a.free_symbols | b.free_symbols, key=str)
    rng = random.Random(seed)
    for _ in range(n):
        vals = {s: sp.Float(rng.uniform(0.3, 1.3)) for s in names}
        va, vb = complex(a.xreplace(vals).evalf()), complex(b.xreplace(vals).evalf())
        if abs(va - vb) > 1e-9 * max(1.0, abs(va), abs(vb)):
            return False
    return True


@pytest.fixture(scope="module")
def python_solutions():
    cache = {}

    def get(card):
        if card not in cache:
            cache[card] = build(card).solve()
        return cache[card]

    return get


@pytest.mark.parametrize("card", CARDS)
def test_every_problem_file_solves_and_matches_the_python_model(card, capsys, python_solutions):
    code, out, err = run_cli(capsys, "solve", str(HERE / f"{card}.toml"), "--format", "json", "--no-answers")
    assert code == 0, err
    data = json.loads(out)
    ref = python_solutions(card)
    assert data["name"] == card and len(data["regimes"]) == len(ref.regimes)
    assert [n for n, c in data["coordinates"].items() if c["independent"]] == [q.func.__name__ for q in ref.coordinates]
    for reg, r in zip(data["regimes"], ref.regimes):
        # the same regime conditions (slip senses), accelerations and reactions
        assert len(reg["conditions"]) == len(r.conditions)
        for c, rc in zip(reg["conditions"], r.conditions):
            assert c["relation"] == rc.relation and agree(read_back(data, c["expression"]), rc.expr)
        for q, a in r.accelerations.items():
            assert agree(read_back(data, reg["accelerations"][q.func.__name__]), a), (card, q)
        assert set(reg["reactions"]) == set(r.reactions)
        for k, v in r.reactions.items():
            assert agree(read_back(data, reg["reactions"][k]), v), (card, k)
        # each JSON equation of motion vanishes with the Python model's accelerations substituted
        assert len(reg["eom"]) == len(r.eom)
        for e in reg["eom"]:
            expr = read_back(data, e)
            subs = {}
            for d in expr.atoms(sp.Derivative):
                if d.derivative_count == 2:
                    q = next(q for q in r.accelerations if q.func.__name__ == d.expr.func.__name__)
                    subs[d] = plain(r.accelerations[q])
            residual = plain(expr).xreplace({plain(k): v for k, v in subs.items()})
            assert agree(residual, 0), (card, e)
    # the top-level keys are the first regime
    assert data["eom"] == data["regimes"][0]["eom"]
    assert data["accelerations"] == data["regimes"][0]["accelerations"]
    # the card's parameters with their SI values
    for name, p in ref.system.parameter_info.items():
        assert data["parameters"][name]["value"] == pytest.approx(p.value)


def test_json_answers_match_the_cards(capsys):
    code, out, _ = run_cli(capsys, "solve", "ladder", "--format", "json")
    assert code == 0
    data = json.loads(out)
    # card ladder (b): released from rest at theta = 0 it leaves the wall at arccos(2/3)
    assert sp.simplify(read_back(data, data["answers"]["leaves_wall"]) - sp.acos(sp.Rational(2, 3))) == 0
    th = sp.Function("theta")(sp.Symbol("t"))
    m, g = sp.symbols("m g")
    # the wall reaction along the motion from rest, from the energy integral θ̇² = (3g/l)(1 − cos θ)
    expect = 3 * m * g * sp.sin(th) * (3 * sp.cos(th) - 2) / 4
    assert sp.simplify(read_back(data, data["answers"]["wall_reaction"]) - expect) == 0
    assert "acos(2/3)" in data["answer_text"]["leaves_wall"]


def test_text_output_is_for_people(capsys):
    code, out, _ = run_cli(capsys, "solve", str(HERE / "ladder.toml"))
    assert code == 0
    assert "θ\u0308 = 3·g·sin(θ)/(2·l)" in out
    assert "angle between the rod and the wall" in out              # the senses restated
    assert "x = l·sin(θ)" in out                                      # the dependent coordinate
    assert any(line.lstrip().startswith("x (") and line.endswith("[dependent]") for line in out.splitlines())
    assert "N_A: normal force of contact A" in out and "N_B" in out    # reactions named
    assert "leaves_wall" in out and "acos(2/3)" in out and "48.19°" in out
    # one equation per block: blank lines around each numbered equation
    lines = out.splitlines()
    i = next(k for k, line in enumerate(lines) if line.strip().startswith("(1)"))
    assert lines[i - 1] == "" and lines[i + 1] == ""


def test_regimes_are_labelled(capsys):
    code, out, _ = run_cli(capsys, "solve", "boulder-push", "--no-answers")
    assert code == 0
    xdot = "x\u0307"            # x with a combining dot above, as rigidkin prints rates
    assert f"Regime 1 of 2: while {xdot} > 0" in out and f"Regime 2 of 2: while {xdot} < 0" in out


def test_latex_output(capsys):
    code, out, _ = run_cli(capsys, "solve", "collar-rod", "--format", "latex")
    assert code == 0
    assert r"\ddot{\theta}" in out and r"\[ " in out and r"\section*{Collar on a track" in out


def test_unavailable_answers_are_said_not_hidden(capsys, monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_answers(name, *args, **kwargs):
        if name.endswith("analysis.answers"):
            raise ImportError("no answers module")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_answers)
    code, out, _ = run_cli(capsys, "solve", "ladder")
    assert code == 0 and "Answers are not available" in out


def test_validate_and_list(capsys):
    code, out, _ = run_cli(capsys, "validate", str(HERE / "sphere-on-sphere.toml"))
    assert code == 0 and "valid" in out and "independent: theta" in out and "1 questions" in out
    code, out, _ = run_cli(capsys, "list")
    assert code == 0
    lines = {line.split()[0]: line for line in out.splitlines()}
    for card in CARDS:
        assert card in lines and "toml" in lines[card]
    assert "Ladder sliding on a frictionless wall and floor" in lines["ladder"]


def test_list_titles_are_the_built_systems_titles(capsys):
    """``rigidkin list`` reads titles from the files without building; each is the title of the system
    that ``solve`` would build from the same name."""
    from rigidkin import examples
    from rigidkin.commands.common import load_system

    code, out, _ = run_cli(capsys, "list")
    assert code == 0
    listed = {line.split()[0]: line.split(None, 2)[2] for line in out.splitlines()}
    assert sorted(listed) == examples.names()
    for name in examples.names():
        system, _ = load_system(name)
        assert listed[name] == system.title, name


def test_unknown_problem_exits_2(capsys):
    code, _, err = run_cli(capsys, "solve", "no-such-card")
    assert code == 2 and "neither a problem file nor a bundled example" in err and "ladder" in err


@pytest.mark.slow
def test_python_dash_m(tmp_path):
    res = rigidkin_process("validate", HERE / "ladder.toml", timeout=120)
    assert res.returncode == 0, res.stderr
    assert "valid" in res.stdout
    bad = tmp_path / "bad.toml"
    bad.write_text("title = \n")
    res = rigidkin_process("validate", bad, timeout=120)
    assert res.returncode == 2 and "Traceback" not in res.stderr
    assert "bad.toml, line 1" in res.stderr and "TOML syntax error" in res.stderr


def test_ask_eom_false_leaves_out_the_equations(capsys, tmp_path):
    f = tmp_path / "ladder.toml"
    f.write_text((HERE / "ladder.toml").read_text().replace("eom = true", "eom = false"))
    code, out, _ = run_cli(capsys, "solve", str(f))
    assert code == 0
    assert "Equations of motion" not in out and "Accelerations" not in out
    assert "N_A = " in out and "leaves_wall" in out


def test_time_limit_stops_a_long_step():
    import time

    from rigidkin.commands.common import TimeLimit, time_limit

    start = time.perf_counter()
    with pytest.raises(TimeLimit, match="took longer than 0.2 s"), time_limit(0.2, "the busy loop"):
        while time.perf_counter() - start < 5:
            sum(range(1000))
    assert time.perf_counter() - start < 2
    with time_limit(0, "no limit"):      # 0: no limit
        pass


def test_json_impulse_answers_read_back(capsys):
    """rod-impulse: ω' = 6 F̂/(m l) just after the blow (card a), θ_max = F̂ sqrt(3/(m K)) (card b)."""
    code, out, _ = run_cli(capsys, "solve", "rod-impulse", "--format", "json")
    assert code == 0
    data = json.loads(out)
    F, m, l, K = sp.symbols("F_hat m l K")
    th = sp.Function("theta")(sp.Symbol("t"))
    after = read_back(data, data["answers"]["after_blow"])
    assert isinstance(after, dict) and agree(after[th.diff(sp.Symbol("t"))], 6 * F / (m * l))
    assert agree(read_back(data, data["answers"]["largest_angle"]), F * sp.sqrt(3 / (m * K)))


def test_method_option_reaches_the_law(capsys):
    """--method lagrange derives the ladder's equation of motion by Lagrange's method: the card's θ̈."""
    code, out, _ = run_cli(capsys, "solve", "ladder", "--method", "lagrange", "--format", "json", "--no-answers")
    assert code == 0
    data = json.loads(out)
    g, l = sp.symbols("g l")
    th = sp.Function("theta")(sp.Symbol("t"))
    assert data["method"] == "lagrange"
    assert agree(read_back(data, data["accelerations"]["theta"]), 3 * g * sp.sin(th) / (2 * l))
    code, _, err = run_cli(capsys, "solve", "ladder", "--method", "guesswork")
    assert code == 2 and "unknown method 'guesswork'" in err and "ladder.toml" in err
