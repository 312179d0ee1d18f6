"""One read-only mapping for every result keyed by a coordinate, a rate or a reaction.

A result is found by its own key (``theta`` as rigidkin made it, ``θ(t)`` real), by its name
(``'theta'``, ``'N'``, ``'dot(phi)'``), or by the symbol a user of sympy.physics.mechanics writes for it:
``me.dynamicsymbols('theta')`` (a function of t without assumptions), its derivative, or
``sp.Symbol('N')``.  These are the same quantity by name, so they find the same entry; a key that names
nothing in the mapping is a ``KeyError`` that lists the keys there are — never a silent miss.

:func:`to_ours` does the same for the keys of a substitution (a state or parameter values given with
sympy's own symbols or with names), and :func:`as_ours` for the symbols inside an expression.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.physics.vector import dynamicsymbols

from ..base.errors import InputError
from ..base.printing import text

t = dynamicsymbols._t

_DOT = re.compile(r"^\s*(dot|ddot)\(\s*([A-Za-z_]\w*)\s*\)\s*$")


class KeyLookupError(KeyError):
    """A key that names no entry of a result (a KeyError, so ``in`` and ``.get`` work as for a dict)."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


def key_name(key) -> tuple[str, int] | None:
    """(name, order of time derivative) of a key: ``theta`` / θ(t) → ('theta', 0), ``dot(theta)`` / θ̇ → 1."""
    if isinstance(key, str):
        m = _DOT.match(key)
        if m:
            return m.group(2), 1 if m.group(1) == "dot" else 2
        return (key.strip(), 0) if key.strip().isidentifier() else None
    if isinstance(key, sp.Derivative) and isinstance(key.expr, AppliedUndef) and key.variables \
            and all(v == t for v in key.variables):
        return key.expr.func.__name__, len(key.variables)
    if isinstance(key, AppliedUndef) and key.args == (t,):
        return key.func.__name__, 0
    if isinstance(key, sp.Symbol):
        return key.name, 0
    return None


def _describe(key) -> str:
    return f"'{key}'" if isinstance(key, str) else str(key)


class Keyed(Mapping):
    """A read-only mapping (possibly computed on first use) found by key, by name or by sympy's own symbol.

    ``sol.accelerations[theta]``, ``sol.accelerations['theta']`` and
    ``sol.accelerations[me.dynamicsymbols('theta')]`` are the same entry; ``sol.reactions['N']`` and
    ``sol.reactions[sp.Symbol('N')]`` too; rates by ``'dot(phi)'``.
    """

    what = "result"

    def __init__(self, data=None, compute=None, what: str | None = None):
        self._data = None if data is None else dict(data)
        self._compute = compute if data is None else None
        if what:
            self.what = what
        self._names: dict | None = None

    def _get(self) -> dict:
        if self._data is None:
            self._data = dict(self._compute())
            self._compute = None
        return self._data

    @property
    def computed(self) -> bool:
        return self._data is not None

    def _by_name(self) -> dict:
        if self._names is None:
            names: dict = {}
            for k in self._get():
                n = key_name(k)
                if n is not None:
                    names.setdefault(n, []).append(k)
            self._names = names
        return self._names

    def resolve(self, key):
        """The mapping's own key for ``key`` (itself, or the entry of the same name and derivative order)."""
        data = self._get()
        try:
            if key in data:
                return key
        except TypeError:            # an unhashable key: a list, a Matrix
            raise KeyLookupError(f"{self.what}: a key is a name, a coordinate q(t) or a symbol, not "
                                 f"{type(key).__name__}.") from None
        n = key_name(key)
        found = self._by_name().get(n, []) if n is not None else []
        if len(found) == 1:
            return found[0]
        if n is not None and n[1] == 0 and not found:
            # 'phi' in a mapping keyed by rates (φ̇ → ...): the one rate of that coordinate
            rates = [k for (name, order), ks in self._by_name().items() if name == n[0] and order == 1 for k in ks]
            if len(rates) == 1 and isinstance(key, str):
                return rates[0]
        keys = ", ".join(_describe(_show(k)) for k in data) or "none"
        hint = ""
        if isinstance(key, str) and key_name(key) is None:
            hint = " A name is an identifier ('theta'), or 'dot(theta)' for a rate."
        raise KeyLookupError(f"{self.what}: no entry for {_describe(key)}; the entries are {keys}.{hint}")

    def __getitem__(self, key):
        return self._get()[self.resolve(key)]

    def __contains__(self, key) -> bool:
        try:
            self.resolve(key)
        except KeyError:
            return False
        return True

    def __iter__(self):
        return iter(self._get())

    def __len__(self):
        return len(self._get())

    def by_name(self) -> dict:
        """The entries keyed by their names: ``{'theta': ..., 'dot(phi)': ...}``."""
        return {_show(k): v for k, v in self._get().items()}

    def __eq__(self, other):
        if isinstance(other, Mapping):
            return dict(self._get()) == dict(other.items())
        return NotImplemented

    __hash__ = None

    def __repr__(self) -> str:
        return repr(self._get())

    def __str__(self) -> str:
        """What ``print`` shows: one entry a line, ``name = expression`` (computed first when it is not yet)."""
        entries = self._get()
        if not entries:
            return f"{self.what}: none"
        return "\n".join([f"{self.what}:"] + [f"  {_show(k)} = {text(v)}" for k, v in entries.items()])


def _show(key) -> str:
    n = key_name(key)
    if n is None:
        return str(key)
    name, order = n
    return name if order == 0 else (f"dot({name})" if order == 1 else f"ddot({name})")


def history_name(key) -> str:
    """The name of a history a key means: θ(t) or ``dynamicsymbols('theta')`` → ``'theta'``, θ̇ → ``'dot(theta)'``."""
    if isinstance(key, str):
        return key
    if key_name(key) is None:
        raise KeyLookupError(f"a history is found by a name, a coordinate q(t), its rate or a symbol, not {key!r}.")
    return _show(key)


def keyed(mapping, what: str) -> Keyed:
    """``mapping`` as a :class:`Keyed` (kept as it is when it is one already)."""
    if isinstance(mapping, Keyed):
        if "what" not in mapping.__dict__:
            mapping.what = what
        return mapping
    return Keyed(mapping, what=what)


# substitutions ------------------------------------------------------------------------------------
def _ours(system) -> dict:
    """(name, order) → rigidkin's own symbol: coordinates, their rates and accelerations, parameters."""
    out: dict = {}
    for c in system.coordinate_info.values():
        q = c.symbol
        out[(c.name, 0)] = q
        out[(c.name, 1)] = q.diff(t)
        out[(c.name, 2)] = q.diff(t, 2)
    for p in system.parameter_info.values():
        out[(p.name, 0)] = p.symbol
    return out


def to_ours(system, values: Mapping | None, where: str = "the values") -> dict:
    """A substitution's keys as rigidkin's symbols: names (``'theta'``, ``'dot(theta)'``, ``'m'``), sympy's
    own ``dynamicsymbols('theta')`` and ``symbols('m')`` included; a key that names nothing is an InputError."""
    if not values:
        return {}
    ours = _ours(system)
    mine = set(ours.values())
    out = {}
    for k, v in values.items():
        if k in mine:
            out[k] = v
            continue
        n = key_name(k)
        if n is not None and n in ours:
            out[ours[n]] = v
            continue
        if isinstance(k, sp.Symbol) and not isinstance(k, sp.Dummy):
            out[k] = v                       # a symbol of the model that is no parameter (a reaction, an input)
            continue
        known = ", ".join(sorted({name for name, order in ours if order == 0}))
        raise InputError(f"{_describe(k)} in {where} is no coordinate, rate or parameter of {system.name}.",
                         where=system.name,
                         hint=f"Use a name ({known}), 'dot(name)' for a rate, or the symbols the system returned.")
    return out


def as_ours(system, expr):
    """``expr`` (written with sympy's own ``dynamicsymbols`` and ``symbols``) in rigidkin's symbols, by name.

    A function of t or a symbol whose name is a coordinate or parameter of the system becomes rigidkin's
    (real) one, so that ``sol.subs(expr, {...})`` and comparisons with rigidkin's results hold.
    """
    ours = _ours(system)
    e = sp.sympify(expr)
    rep = {}
    for a in e.atoms(sp.Derivative, AppliedUndef, sp.Symbol):
        n = key_name(a)
        if n is not None and n in ours and ours[n] != a and (n[1] == 0 or isinstance(a, sp.Derivative)):
            rep[a] = ours[n]
    derivs = {k: v for k, v in rep.items() if isinstance(k, sp.Derivative)}
    rest = {k: v for k, v in rep.items() if not isinstance(k, sp.Derivative)}
    return e.xreplace(derivs).xreplace(rest) if rep else e
