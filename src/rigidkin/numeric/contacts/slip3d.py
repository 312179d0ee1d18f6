"""Slipping in three dimensions in the simulator: the slip direction written relative to a reference tangent.

A contact slipping on a surface in 3D has the friction −µk N û with û = v_s/|v_s| (``model.friction3d``).
The slip speed |v_s| reaches zero when the contact starts to roll, but it touches zero without changing
sign and û is not defined there, so neither |v_s| nor the symbolic û serves an event locator.  Written
relative to a reference tangent, with s1, s2 the slip velocity's components,

    û = σ (t1 + λ t2)/√(1 + λ²),  λ = s2/s1,  σ = sign(s1)        (reference t1, κ = +1)
    û = σ (µ t1 + t2)/√(1 + µ²),  µ = s1/s2,  σ = sign(s2)        (reference t2, κ = −1)

is the same vector wherever the reference component is nonzero, and analytic through |v_s| = 0 when the
slip dies out along a direction with a nonzero reference component (the motion beyond is the analytic
continuation, so the integrator's error control and the dense output stay exact there).  So each
slipping 3D contact splits a mode's regime into numeric regimes:

* fast (|v_s| > SLOW): û = v_s/|v_s| itself; one watch, |v_s|² − SLOW² reaching zero (bookkeeping);
* slow (|v_s| < 2 SLOW), four regimes (κ, σ), with three watches:
  - the reference component s_ref (s1 or s2) reaching zero with κ's condition s_ref² > s_other² holding:
    |v_s| itself reaches zero, transversally in s_ref — the contact may stick (kind ``sticks``);
  - s1² − s2² reaching zero while |v_s| > 0: the slip direction turns past a diagonal of (t1, t2) and the
    other component becomes the reference;
  - |v_s|² − (2 SLOW)² reaching zero: fast again.
  The last two are changes of bookkeeping, not of the motion (kind ``reverses``, listed with the events).

A slip that starts from sticking (``start_direction``, ``nudge``) begins against the friction the cone could
no longer hold, with |v_s| set to 1e-10 of the state's size: the referenced form needs |v_s| > 0, and a slip
that small is below the integrator's tolerances.

Every regime's equations are the symbolic solution's with û1, û2 replaced: nothing is derived again.
"""

from __future__ import annotations

from dataclasses import replace
from itertools import product

import numpy as np
import sympy as sp

from ...derive.regime import Condition, Deferred, LazyMap, Regime
from ...model.friction3d import SlidingFriction3D, referenced_direction, slip_components
from ...model.loads import SignChoice
from ..rhs import compile_functions
from .vocabulary import SLIP

#: Suffixes of the load names under which a contact's bookkeeping choices are sign choices: κ (which
#: tangent is the reference) and ζ (whether the slip is slow enough to need a reference at all).
DIRECTION, SPEED = " slip direction", " slip speed"

#: |v_s| (SI, m/s) below which the slip direction is written relative to a reference tangent (above
#: 2·SLOW again the unit vector v_s/|v_s| itself): a fast-turning slip (a spinning top) is not followed by
#: a change of reference at every diagonal, and a slip that dies out is seen in its reference component.
SLOW = 1e-3


def direction_load(contact: str) -> str:
    return contact + DIRECTION


def contact_of(load: str) -> str | None:
    """The contact whose bookkeeping choice (κ or ζ) ``load`` is (None: not one)."""
    for suffix in (DIRECTION, SPEED):
        if load.endswith(suffix):
            return load[:-len(suffix)]
    return None


def _slipping(setup) -> list:
    held = set(getattr(setup, "held", ()))
    return [ld for ld in setup.loads if isinstance(ld, SlidingFriction3D) and ld.name not in held]


def expand(sol):
    """``sol`` with each regime split into the numeric regimes of its 3D slipping contacts: û = v_s/|v_s| while
    |v_s| > SLOW, and the four referenced forms (κ, σ) while |v_s| < 2 SLOW."""
    setup = sol.setup
    loads = _slipping(setup)
    if not loads:
        return sol
    kin = setup.kin
    per_contact, choices = [], list(setup.sign_choices)
    for ld in loads:
        s1, s2 = (kin.simplify_expr(setup.scalar(s)) for s in ld.slip_components(kin))
        kappa, sigma = sp.Symbol(f"kappa_{ld.name}"), ld.sign_symbol
        u1, u2 = ld.direction()
        zeta_slow, zeta_fast = sp.Symbol(f"zeta_{ld.name}"), sp.Symbol(f"zeta2_{ld.name}")
        speed2 = s1**2 + s2**2
        options = [({zeta_slow: 1}, {u1: s1 / sp.sqrt(speed2), u2: s2 / sp.sqrt(speed2)})]   # û = v_s/|v_s|
        for k, sg in product((1, -1), (1, -1)):
            d1, d2 = referenced_direction(s1, s2, 1 if k > 0 else 2, sg)
            options.append(({zeta_fast: -1, kappa: k, sigma: sg}, {u1: d1, u2: d2}))
        per_contact.append(options)
        ref = (1 + kappa) / 2 * s1 + (1 - kappa) / 2 * s2
        choices.append(SignChoice(sigma, ref, f"slip velocity at {ld.name} along its reference tangent", ld.name))
        choices.append(SignChoice(kappa, s1**2 - s2**2, f"s1² − s2² at {ld.name} (which tangent is the reference)",
                                  direction_load(ld.name)))
        choices.append(SignChoice(zeta_slow, speed2 - SLOW**2, f"|v_s|² − {SLOW:g}² at {ld.name} (a slow slip)",
                                  ld.name + SPEED))
        choices.append(SignChoice(zeta_fast, speed2 - (2 * SLOW)**2,
                                  f"|v_s|² − {2 * SLOW:g}² at {ld.name} (no longer slow)", ld.name + SPEED))
    new_setup = replace(setup, sign_choices=choices)
    new_setup.held = getattr(setup, "held", ())
    regimes = []
    for reg in sol.regimes:
        for combo in product(*per_contact):
            signs, sub = dict(reg.signs), {}
            for sg, d in combo:
                signs.update(sg)
                sub.update(d)
            regimes.append(_regime(reg, signs, sub, new_setup))
    return replace(sol, regimes=tuple(regimes), setup=new_setup)


def _regime(reg, signs: dict, sub: dict, setup) -> Regime:
    conds = list(reg.conditions)
    for sc in setup.sign_choices:
        if sc.symbol in signs and sc.symbol not in reg.signs:
            q = setup.kin.simplify_expr(sp.sympify(sc.quantity).xreplace(signs))
            conds.append(Condition(q, ">" if signs[sc.symbol] > 0 else "<", sc.label))

    def mapped(m):
        if getattr(m, "computed", True):
            return {k: sp.sympify(v).xreplace(sub) for k, v in m.items()}
        return LazyMap(lambda: {k: sp.sympify(v).xreplace(sub) for k, v in m.items()})

    def later(name):
        return Deferred(lambda: sp.sympify(getattr(reg, name)).xreplace(sub))

    return Regime(tuple(conds), Deferred(lambda: reg.validity), {**signs, **sub},
                  Deferred(lambda: tuple(sp.sympify(e).xreplace(sub) for e in reg.eom)),
                  mapped(reg.accelerations), mapped(reg.reactions), later("mass_matrix"), later("forcing"),
                  reg.raw_mass_matrix.xreplace(sub), reg.raw_forcing.xreplace(sub))


def slip_speed(hyb, name: str, t_, y, p) -> float:
    """|v_s| at contact ``name`` of a 3D model, in the full state (every coordinate and rate)."""
    key = ("slip3d", name)
    if key not in hyb._contact_fns:
        c, kin = hyb.contacts[name], hyb.kin
        s1, s2 = slip_components(kin, c.relative_velocity(kin), c.normal(kin))
        lay = hyb.layout
        hyb._contact_fns[key] = compile_functions(lay.arguments(), [lay.to_plain(s1), lay.to_plain(s2)])
    s1, s2 = (float(v) for v in hyb._contact_fns[key](t_, *np.asarray(y)[:2 * hyb.layout.n], *p))
    return float(np.hypot(s1, s2))


def friction_needed(c, react: dict) -> float | None:
    """|F| of a sticking 3D contact from its two tangential reactions (None: not such a contact)."""
    names = [f"{c.F.name}{i}" for i in (1, 2)]
    if not all(n in react for n in names):
        return None
    return float(np.hypot(react[names[0]], react[names[1]]))


def _components(hyb, name: str, t_, y, p) -> np.ndarray:
    slip_speed(hyb, name, t_, y, p)              # compiles the components
    return np.array([float(v) for v in hyb._contact_fns[("slip3d", name)](t_, *np.asarray(y)[:2 * hyb.layout.n], *p)])


def start_direction(hyb, mode: dict, name: str, t_, y, p, react: dict) -> dict:
    """The friction directions a sticking 3D contact starts to slip with: against the friction it needed,
    û0 = −F/|F| (the slip grows where the friction cone can no longer hold it), as the signs (σ, κ) of
    its reference regime; the slip's first motion then decides (``regime_at`` checks it)."""
    c = hyb.contacts[name]
    names = [f"{c.F.name}{i}" for i in (1, 2)]
    F = np.array([react.get(n, 0.0) for n in names])
    u0 = -F / max(float(np.hypot(*F)), 1e-300)
    ref = 0 if abs(u0[0]) >= abs(u0[1]) else 1
    start = hyb.__dict__.setdefault("_slip_starts", {})
    start[name] = u0
    return {name: 1 if u0[ref] > 0 else -1, direction_load(name): 1 if ref == 0 else -1}


def nudge(hyb, mode: dict, t_, y, p, scale: float = 1e-10) -> np.ndarray:
    """The state with the slip of each 3D contact that starts to slip here (``start_direction``) set to
    ε û0, ε = ``scale`` × the state's size: the referenced direction is analytic for |v_s| > 0 only, and a
    slip of that size changes the state by less than the integrator's tolerance."""
    starts = hyb.__dict__.get("_slip_starts", {})
    y = np.array(y, dtype=float)
    n = hyb.layout.n
    for name, u0 in list(starts.items()):
        if mode.get(name) != SLIP:
            continue
        sol = hyb.solution(mode)
        slots = [n + hyb.layout.coordinates.index(q) for q in sol.coordinates]
        base = _components(hyb, name, t_, y, p)
        J = np.empty((2, len(slots)))
        for j, s_ in enumerate(slots):
            yy = y.copy()
            yy[s_] += 1.0
            J[:, j] = _components(hyb, name, t_, yy, p) - base
        eps = scale * max(1.0, float(np.max(np.abs(y[:2 * n]))))
        du = np.linalg.lstsq(J, eps * u0 - base, rcond=None)[0]
        y[slots] += du
        y[:2 * n] = hyb.project_rates(mode, t_, y[:2 * n], p)
    starts.clear()
    return y
