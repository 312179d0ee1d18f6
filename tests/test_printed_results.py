"""What ``print`` shows of a solution's mappings computed on first use (``sol.reactions`` of a LazyMap):
the entries themselves, one a line, not a placeholder."""

import sympy as sp

from rigidkin import examples
from rigidkin.base.printing import text
from rigidkin.base.trace import LazyEquations
from rigidkin.derive.regime import LazyMap


def test_printing_the_reactions_computes_and_shows_them(capsys):
    system = examples.build("ladder")
    sol = system.solve()
    reactions = sol.reactions
    assert isinstance(reactions, LazyMap) and not reactions.computed
    print(reactions)
    shown = capsys.readouterr().out
    assert "not computed" not in shown and "LazyMap" not in shown
    lines = shown.splitlines()
    assert lines[0] == "reactions:"
    assert [ln.split(" = ")[0].strip() for ln in lines[1:]] == list(reactions.by_name())
    # the ladder (uniform, length l, ends on a smooth wall and floor), by hand: the wall's push
    # N_A = m sin θ (3 g cos θ − 2 l θ̇²)/4
    th = system.coordinate_info["theta"].symbol
    m, g, l = (system.parameter_info[n].symbol for n in ("m", "g", "l"))
    by_hand = m * sp.sin(th) * (3 * g * sp.cos(th) - 2 * l * th.diff() ** 2) / 4
    assert sp.simplify(reactions["N_A"] - by_hand) == 0
    assert f"  N_A = {text(reactions['N_A'])}" in lines


def test_repr_of_a_lazy_map_is_its_entries():
    mg = sp.Symbol("m") * sp.Symbol("g")
    lazy = LazyMap(lambda: {"N": mg}, what="reactions")
    assert repr(lazy) == repr({"N": mg})
    assert str(lazy) == f"reactions:\n  N = {text(mg)}" and "·" in str(lazy)
    assert str(LazyMap(dict, what="reactions")) == "reactions: none"


def test_a_step_s_equations_computed_on_first_use_are_printed_as_equations():
    x = sp.Symbol("x")
    eqs = LazyEquations(lambda: [(x, 2 * x)])
    assert repr(eqs) == repr(((x, 2 * x),)) and list(eqs) == [(x, 2 * x)]
