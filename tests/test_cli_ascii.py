"""``--ascii``: results readable in any monospace font.

The text output writes rates with combining dots (θ̇), which DejaVu Sans Mono and other terminal fonts put
over the next glyph.  Under ``--ascii`` (or ``RIGIDKIN_ASCII=1``) nothing printed has a combining mark or a
character outside ASCII, and what is printed still reads back as the same equations (sympy parses it and
compares it with the ladder's closed form θ̈ = 3 g sin θ / (2 l)).
"""

from __future__ import annotations

import contextlib
import io
import unicodedata

import pytest
import sympy as sp

from rigidkin.base.plaintext import to_ascii
from rigidkin.cli import main


def _read(expr: str) -> sp.Expr:
    """An ASCII expression read by sympy, a rate x' as the symbol x_d, x'' as x_dd."""
    return sp.parse_expr(expr.replace("''", "_dd").replace("'", "_d").replace("^", "**"))


@pytest.fixture(scope="module")
def ladder(tmp_path_factory) -> tuple[str, str]:
    """``rigidkin solve ladder`` printed as it is and with ``--ascii`` (derived once: a cache of its own)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.delenv("RIGIDKIN_ASCII", raising=False)
        mp.delenv("RIGIDKIN_NO_CACHE", raising=False)
        mp.setenv("RIGIDKIN_CACHE", str(tmp_path_factory.mktemp("cache")))
        return _run(["solve", "ladder"], mp), _run(["solve", "ladder", "--ascii"], mp)


def _run(argv, monkeypatch, env=None) -> str:
    for k, v in (env or {}).items():
        monkeypatch.setenv(k, v)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(argv) in (0, 1)
    return buf.getvalue()


def test_ascii_output_is_ascii_and_reads_back_as_the_closed_form(ladder):
    out = ladder[1]
    assert out.isascii() and not any(unicodedata.combining(c) for c in out)
    (line,) = [x.strip() for x in out.splitlines() if x.strip().startswith("theta'' =")]
    g, theta, l = sp.symbols("g theta l")
    assert sp.simplify(_read(line.split("=", 1)[1]) - 3 * g * sp.sin(theta) / (2 * l)) == 0
    (na,) = [x.strip() for x in out.splitlines() if x.strip().startswith("N_A = m*")]
    m, w = sp.symbols("m theta_d")
    # the wall pushes the mass centre: N_A = m d²(l sinθ / 2)/dt² with θ̈ = 3 g sin θ / (2 l), by hand
    assert sp.simplify(_read(na.split("=", 1)[1]) - m * sp.sin(theta) * (3 * g * sp.cos(theta) - 2 * l * w**2) / 4) == 0


def test_default_output_keeps_the_dots_and_ascii_is_the_same_text(ladder):
    plain, ascii_ = ladder
    assert "θ̈ = 3·g·sin(θ)/(2·l)" in plain
    assert to_ascii(plain) == ascii_ != plain


@pytest.mark.parametrize("where", ["after", "before", "env"])
def test_ascii_is_asked_for_before_or_after_the_command_or_in_the_environment(where, monkeypatch, tmp_path):
    f = tmp_path / "µ.toml"
    f.write_text("title = 'x'\n")
    argv = {"after": ["validate", str(f), "--ascii"], "before": ["--ascii", "validate", str(f)],
            "env": ["validate", str(f)]}[where]
    monkeypatch.setenv("RIGIDKIN_ASCII", "1" if where == "env" else "0")
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        assert main(argv) == 2                     # no bodies: a refusal that names the file µ.toml
    assert "mu.toml" in err.getvalue() and err.getvalue().isascii()


@pytest.mark.parametrize(("text", "expected"), [
    ("l·θ̇²", "l*theta'^2"), ("θ̈₁ = 3·g", "theta1'' = 3*g"), ("ẍ_B", "x_B''"), ("φ̇₂²", "phi2'^2"),
    ("≈ 48.19°", "~ 48.19 deg"), ("µ·N ≤ 0", "mu*N <= 0"), ("Ω", "Omega"), ("x⁽³⁾", "x^(3)"),
])
def test_to_ascii_by_hand(text, expected):
    assert to_ascii(text) == expected
