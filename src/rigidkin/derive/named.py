"""M and f with named common sub-expressions: the structured form of a large system, made readable.

Where the closed-form accelerations would be too large to read (derive/closed_forms.py), a regime is
given as M q̈ = f.  Its entries share sub-expressions (sin θ₁ l m, the products of the link lengths
and masses); ``sympy.cse`` names each shared one once — x₀ = cos θ₁, x₁ = l m, x₂ = 5/2 x₀ x₁ … — and M and
f are written with the names.  Each name is defined from the state, the parameters and the names before
it, so evaluating the definitions in order and then M and f gives M and f exactly, at any state (and
q̈ = M⁻¹f from them).  The names use a letter that no symbol of the model starts with.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from ..base import algebra
from ..base.printing import text

#: Letters tried for the names, in order (the first that no symbol or coordinate of the model starts with).
LETTERS = ("x", "ξ", "c", "w", "k")

NOTE = ("the sub-expressions are defined in order from the state, the parameters and the names before "
        "them; put in M and f they give M and f exactly, so the numbers are exact at any state")


@dataclass(frozen=True)
class NamedForm:
    """M q̈ = f written with named sub-expressions: ``names`` are (symbol, definition) in order."""

    names: tuple
    mass_matrix: sp.Matrix
    forcing: sp.Matrix

    def substituted(self) -> tuple[sp.Matrix, sp.Matrix]:
        """M and f with every name replaced by its definition (the last first)."""
        M, f = self.mass_matrix, self.forcing
        for s, e in reversed(self.names):
            M, f = M.xreplace({s: e}), f.xreplace({s: e})
        return M, f


def _letter(exprs, taken=()) -> str:
    used = set(taken)
    for e in exprs:
        for a in algebra.atoms_of([e], (sp.Symbol,)):
            used.add(a.name)
        used |= {f.func.__name__ for f in algebra.functions_of_time(e)}
    for letter in LETTERS:
        if not any(n.startswith(letter) for n in used):
            return letter
    return "x_cse"


def named_form(M: sp.Matrix, f: sp.Matrix, taken=()) -> NamedForm:
    """M and f with their common sub-expressions named (sympy.cse on the plain state, names in order);
    ``taken``: more names the letter must not begin (the model's parameters and coordinates)."""
    exprs = list(M) + list(f)
    plain, back = algebra.plain_state(sp.Matrix(exprs)) if exprs else (sp.Matrix([]), {})
    letter = _letter(exprs, taken)
    subs, reduced = sp.cse(list(plain), symbols=sp.numbered_symbols(letter), order="none")
    names = tuple((s, e.xreplace(back)) for s, e in subs)
    reduced = [e.xreplace(back) for e in reduced]
    n = M.rows * M.cols
    return NamedForm(names, sp.Matrix(M.rows, M.cols, reduced[:n]), sp.Matrix(f.rows, f.cols, reduced[n:]))


def of_regime(regime, system=None) -> NamedForm:
    """The named form of a regime's M and f as printed (made once per regime; ``system``: its parameters and
    coordinates are names the letter avoids, e.g. a coordinate x)."""
    kept = regime.__dict__.get("_named_form")
    if kept is None:
        taken = () if system is None else [*map(str, system.parameters),
                                           *(q.func.__name__ for q in system.coordinates)]
        kept = regime.__dict__["_named_form"] = named_form(regime.mass_matrix, regime.forcing, taken)
    return kept


def rows(form: NamedForm) -> list[tuple[sp.Symbol, sp.Expr]]:
    """What a reader is shown: the names with their definitions in order, then every non-zero entry of M
    (M_ij) and every entry of f (f_i), written with the names."""
    M, f = form.mass_matrix, form.forcing
    sep = "" if max(M.rows, M.cols) < 10 else "_"
    out = list(form.names)
    out += [(sp.Symbol(f"M_{i + 1}{sep}{j + 1}"), M[i, j]) for i in range(M.rows) for j in range(M.cols)
            if M[i, j] != 0]
    out += [(sp.Symbol(f"f_{i + 1}"), f[i]) for i in range(f.rows)]
    return out


def heading(coordinates) -> str:
    """The sentence above the rows: the order of q̈ in M q̈ = f and what the names give."""
    return (f"M q̈ = f with q = ({', '.join(text(q) for q in coordinates)}), written with named common "
            f"sub-expressions; {NOTE}.")
