"""Every question kind against bundled problems, with and without contact modes: each is answered or
refused in one clear paragraph (a RigidkinError), never an internal error; every example's JSON
output (all its questions answered, in under 10 s of CPU) validates against the schema shipped with
the package.

The questions are written as TOML and read by the problem-file reader, as a user's would be; their
fields come from the problem itself (its first coordinate, its reactions, its contacts).
"""

from __future__ import annotations

import json
import time
from importlib import resources

import jsonschema
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rigidkin import examples
from rigidkin.analysis.answers import answer
from rigidkin.analysis.questions import KINDS, Answer
from rigidkin.base import algebra
from rigidkin.base.errors import RigidkinError
from rigidkin.io.problem import load_problem, parse_problem
from rigidkin.io.results import solution_data

#: Seconds one answer may take before it counts as a stall.
ANSWER_SECONDS = 60


def _questions(system, q: str, reaction: str, mode: str) -> list[str]:
    """TOML for one question of every kind (``mode``: a TOML inline table or "")."""
    m = f"mode = {mode}\n" if mode else ""
    start = f'start = {{ {q} = 0.3, "dot({q})" = 0.5 }}\n'
    out = {
        "eom": "",
        "reaction": f'reaction = "{reaction}"\n',
        "reaction_along": f'reaction = "{reaction}"\n{start}',
        "integral": start,
        "event": f'when = "{reaction} = 0"\n{start}',
        "event_rate": f'when = "dot({q}) = 0"\n{start}',
        "extreme": f'coordinate = "{q}"\n{start}',
        "threshold": f'holds = "{reaction} >= 0"\nstart = {{ {q} = 0 }}\n',
        "equilibrium": "",
        "impulse": start,
        "interval": f"duration = 0.1\n{start}",
        "phases": f'{start}[[ask.question.phase]]\nname = "one"\nuntil = "{q} = 1"\n',
        "value": f'expression = "{reaction}"\nat = {{ {q} = 0.3, "dot({q})" = 0.5 }}\n',
    }
    texts = []
    for name, body in out.items():
        kind = name.split("_")[0]
        texts.append(f'[[ask.question]]\nkind = "{kind}"\nname = "{name}"\n{m}{body}')
    return texts


def _problem_without_questions(name: str) -> str:
    text = (examples.HERE / f"{name}.toml").read_text()
    cut = text.find("[[ask.question]]")
    return text if cut < 0 else text[:cut]


def _mode_variants(system) -> list[str]:
    contacts = [c for c in system.constraints.values() if getattr(c, "kind", "") == "contact"]
    variants = [""]
    for c in contacts[:1]:
        variants += [f'{{ {c.name} = "{s}" }}' for s in ("stick", "slip", "open")]
    return variants


CASES = ["ladder", "slip-to-roll", "collar-rod", "disk-in-track"]


def check_answer(system, question, context) -> str:
    """Answer; a refusal must be one paragraph; anything else is a failure (the exception propagates)."""
    try:
        with algebra.time_limit(ANSWER_SECONDS):
            a = answer(system, question, context)
    except RigidkinError as exc:
        message = str(exc)
        assert message and "\n" not in message.strip(), message
        assert "internal error" not in message, message
        return "refused"
    assert isinstance(a, Answer) and a.text, question
    context[question.name] = a
    return "answered"


@pytest.mark.slow
@pytest.mark.parametrize("name", CASES)
def test_every_question_kind_answers_or_refuses(name):
    base = _problem_without_questions(name)
    system, _ = parse_problem(base, f"{name}.toml")
    sol = system.solve()
    q = sol.coordinates[0].func.__name__
    reaction = next(iter(sol.regimes[0].reactions), "N")
    seen = {}
    for mode in _mode_variants(system):
        try:
            system, spec = parse_problem(base + "\n" + "\n".join(_questions(system, q, reaction, mode)),
                                         f"{name}.toml")
        except RigidkinError:
            continue            # a mode this problem cannot take is refused by the reader: fine
        context = {}
        for question in spec.questions:
            seen[(question.kind, bool(mode))] = check_answer(system, question, context)
    assert {k for k, _ in seen} == set(KINDS)


def test_value_and_threshold_under_friction_without_mode():
    """The reported failures: a value and a threshold question on a problem with a coefficient of
    friction and no mode (two regimes): one is answered, the other refused in one sentence."""
    base = _problem_without_questions("slip-to-roll")
    text = base + '''
[[ask.question]]
kind = "value"
name = "normal"
expression = "N"
at = { x = 0.5, "dot(x)" = 1 }

[[ask.question]]
kind = "threshold"
name = "t"
holds = "N >= 0"
'''
    system, spec = parse_problem(text, "slip-to-roll.toml")
    value, threshold = spec.questions
    a = answer(system, value, {})
    m, g, beta = (system.parameter_info[n].symbol for n in ("m", "g", "beta"))
    assert sp.simplify(a.value - m * g * sp.cos(beta)) == 0
    with pytest.raises(RigidkinError, match="one degree of freedom"):
        answer(system, threshold, {})


def test_event_that_is_the_simulators_own_switch():
    """The slip speed reaching zero is exactly the switch the simulator makes (slip → roll): the event
    happens, with its time and every coordinate and rate, and the contact rolls from there."""
    base = _problem_without_questions("slip-to-roll")
    text = base + '''
[[ask.question]]
kind = "event"
name = "rolls"
when = "slip(ground) = 0"
start = { x = 0, "dot(x)" = 1, phi = 0, "dot(phi)" = 0 }
'''
    system, spec = parse_problem(text, "slip-to-roll.toml")
    a = answer(system, spec.questions[0], {})
    assert a.details["happens"] and a.details["time"] > 0
    state = a.details["end_state"]
    names = {str(k) for k in state}
    assert {"x(t)", "phi(t)", "Derivative(x(t), t)", "Derivative(phi(t), t)"} <= names
    x_dot = next(v for k, v in state.items() if str(k) == "Derivative(x(t), t)")
    phi_dot = next(v for k, v in state.items() if str(k) == "Derivative(phi(t), t)")
    r = system.parameter_info["r"].value
    assert abs(float(x_dot) - r * float(phi_dot)) < 1e-6          # no slip there
    # the slip speed s = ẋ − r φ̇ changes uniformly: ṡ = g sin β − µ g cos β (centre) − 2 µ g cos β (spin of a
    # solid cylinder, r φ̈ = µ m g cos β r² / (m r²/2)); from s = 1 it reaches 0 at t = 1/(3 µ g cos β − g sin β)
    mu, g, beta = (system.parameter_info[n].value for n in ("mu", "g", "beta"))
    import math
    slip_rate = 3 * mu * g * math.cos(beta) - g * math.sin(beta)
    assert a.details["time"] == pytest.approx(1 / slip_rate, rel=1e-6)


def _schema():
    return json.loads(resources.files("rigidkin.io").joinpath("results.schema.json").read_text())


def _answers(system, spec):
    out, context = {}, {}
    for q in (spec.questions if spec is not None else ()):
        try:
            with algebra.time_limit(ANSWER_SECONDS):
                a = answer(system, q, context)
        except RigidkinError as exc:
            out[q.name] = str(exc)
            continue
        context[q.name] = out[q.name] = a
    return out


SCHEMA_NAMES = [n if n not in ("chain", "slip-to-roll", "paper-pull", "boulder-push", "gyroscope")
                else pytest.param(n, marks=pytest.mark.slow) for n in examples.names() if n != "bicycle"]


@pytest.mark.parametrize("name", SCHEMA_NAMES)
def test_json_output_validates_against_the_schema(name):
    toml = examples.HERE / f"{name}.toml"
    system, spec = load_problem(toml) if toml.exists() else (examples.build(name), None)
    start = time.process_time()
    sol = system.solve()
    data = json.loads(json.dumps(solution_data(sol, spec, _answers(system, spec)), ensure_ascii=False))
    spent = time.process_time() - start
    assert spent < 10, f"{name}: solving and answering took {spent:.1f} s of CPU"   # the bound
    jsonschema.validate(data, _schema())
    for a in data["answer_data"].values():
        if a["answered"] and a["kind"] == "event" and a["happens"]:
            coords = set(data["coordinates"])
            assert coords <= set(a["state"]) and {f"dot({c})" for c in coords} <= set(a["state"])
        if a["answered"] and a["value"] is not None and a["value"]["numeric"] is not None:
            names = {n: sp.Symbol(n) for n in [*data["parameters"], *data["coordinates"], "t"]}
            parsed = sp.parse_expr(a["value"]["exact"], local_dict=names)
            if not parsed.free_symbols:
                assert float(parsed) == pytest.approx(a["value"]["numeric"], rel=1e-9, abs=1e-12)


def test_schema_refuses_a_malformed_answer():
    schema = {"$defs": _schema()["$defs"], "$ref": "#/$defs/answer"}
    good = {"answered": True, "kind": "event", "text": "x", "exact": True, "tolerance": None, "note": None,
            "value": {"exact": "1", "numeric": 1.0}, "happens": True,
            "state": {"x": {"exact": "1", "numeric": 1.0}}}
    jsonschema.validate(good, schema)
    bad = {k: v for k, v in good.items() if k != "state"}      # an event that happens must give the state
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(bad, schema)
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate({"answered": False}, schema)        # a refusal must give its reason


def test_event_located_by_simulation_is_the_contact_opening_itself():
    """N_A = 0 asked of the ladder through the simulation path: the simulator's own 'contact A opens' is the
    event (it happens, at the closed-form angle acos(2/3)), not 'never ... first contact A opens'."""
    from rigidkin.analysis.events import event_by_simulation

    system, _ = load_problem(examples.HERE / "ladder.toml")
    sol = system.solve()
    th = sol.coordinates[0]
    ev = event_by_simulation(sol, sp.Eq(sp.Symbol("N_A"), 0), {th: sp.Rational(1, 10)}, name="leaves_wall")
    assert ev.happens and ev.time > 0, ev.notes
    # from θ0 at rest: N_A = 0 where cos θ = (2/3) cos θ0
    assert float(ev.value) == pytest.approx(float(sp.acos(sp.Rational(2, 3) * sp.cos(sp.Rational(1, 10)))), abs=1e-6)
    names = {str(k) for k in ev.state}
    assert {"theta(t)", "x(t)", "Derivative(theta(t), t)", "Derivative(x(t), t)"} <= names


@pytest.mark.slow
@settings(max_examples=8, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_hypothesis_questions_over_the_vocabulary(data):
    """Random questions from the vocabulary (kind, reaction or coordinate, start, mode) on two problems."""
    name = data.draw(st.sampled_from(["ladder", "collar-rod"]))
    base = _problem_without_questions(name)
    system, _ = parse_problem(base, f"{name}.toml")
    sol = system.solve()
    q = data.draw(st.sampled_from([c.func.__name__ for c in sol.coordinates]))
    reaction = data.draw(st.sampled_from(sorted(sol.regimes[0].reactions) or ["N"]))
    mode = data.draw(st.sampled_from(_mode_variants(system)))
    texts = _questions(system, q, reaction, mode)
    chosen = data.draw(st.lists(st.sampled_from(texts), min_size=1, max_size=3, unique=True))
    try:
        system, spec = parse_problem(base + "\n" + "\n".join(chosen), f"{name}.toml")
    except RigidkinError:
        return
    context = {}
    for question in spec.questions:
        check_answer(system, question, context)


def test_value_at_rest_on_a_rough_incline_is_a_legal_start():
    """At rest on the rough incline no slip starts (µ = 0.4 > tan β / 3): the cylinder rolls from rest, so the
    friction is the one rolling needs, F = m g sin β / 3 (its magnitude), and N = m g cos β."""
    base = _problem_without_questions("slip-to-roll")
    text = base + '''
[[ask.question]]
kind = "value"
name = "friction"
expression = "F"
at = { x = 0, "dot(x)" = 0, phi = 0, "dot(phi)" = 0 }
'''
    system, spec = parse_problem(text, "slip-to-roll.toml")
    a = answer(system, spec.questions[0], {})
    m, g, beta = (system.parameter_info[n].symbol for n in ("m", "g", "beta"))
    assert sp.simplify(abs(a.value) - m * g * sp.sin(beta) / 3) == 0 or \
        sp.simplify(a.value**2 - (m * g * sp.sin(beta) / 3) ** 2) == 0
    assert "stick" in a.note
