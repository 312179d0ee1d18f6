"""A level rod that has bounced to rest on two rough supports (benchmarks/contacts_vs_siconos.py, TWO, µ = 0.5)
is told at rest on both: its last segment reads "A sticking, B sticking (friction shared)", never slipping.

At rest the model carries the friction jointly (settle's held alternative: B named ``slip`` inside the
model, its friction carried with A's); the words follow the mechanics, checked here against the rod at
rest by hand: every speed zero, N_A = m g b/(a + b), N_B = m g a/(a + b) (lever rule), no friction."""

import sys
from pathlib import Path

import pytest

from rigidkin.numeric import simulate
from rigidkin.numeric.contacts.vocabulary import describe_mode

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from contacts_vs_siconos import TWO, two_supports_system  # noqa: E402


@pytest.fixture(scope="module")
def at_rest():
    p = TWO | {"mu": 0.5}
    system = two_supports_system(p)
    return p, system, simulate(system, p["T"], restitution=p["e"], max_events=2000)


def test_rod_at_rest_on_two_rough_supports_is_told_sticking(at_rest):
    p, system, res = at_rest
    last = res.segments[-1]
    assert res.reached_end and last.t1 == p["T"] and last.t0 < 0.7   # at rest well before the end
    final = res.final_state
    assert final["dot(x)"] == 0 and final["dot(y)"] == 0 and final["dot(theta)"] == 0
    # the lever rule by hand: the supports carry the weight, A at a, B at b from the centre
    m, g, a, b = p["m"], p["g"], p["a"], p["b"]
    react = last.model.reactions(last.t1, last.state(last.t1), last.params)
    assert react["N_A"] == pytest.approx(m * g * b / (a + b), rel=1e-12)
    assert react["N_B"] == pytest.approx(m * g * a / (a + b), rel=1e-12)
    assert abs(react["F_A"]) < 1e-12
    # the words: both held, none slipping, wherever the mode is shown (segment, result dict, text)
    assert last.description == "A sticking, B sticking (friction shared)"
    assert res.to_dict()["modes"][-1]["mode"] == last.description
    assert "slipping" not in last.description
    assert str(res).splitlines()[len(res.segments)].endswith("A sticking, B sticking (friction shared)")


def test_the_words_come_from_the_held_contacts(at_rest):
    """The model's key still names B ``slip`` (the friction carried jointly); only the held set makes it sticking:
    without it the same key reads slipping, so the test above can fail."""
    _, system, res = at_rest
    last = res.segments[-1]
    assert last.mode == {"A": "stick", "B": "slip"}
    assert describe_mode(system, last.mode) == "A sticking, B slipping"
    assert "B" in last.model.solution.setup.held
