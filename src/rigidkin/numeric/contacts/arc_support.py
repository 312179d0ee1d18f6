"""The hybrid model's view of a profile that is an arc with edges at its ends (:mod:`rigidkin.model.arc_edges`).

While the arc touches (its contact closed) the edges cannot reach the surface anywhere but at the arc's
end, where the arc's own watch (the arc margin m = (−n)·toward − cos(half angle) reaching zero) hands the
contact over; so an edge left open by a closed arc has no watch, and is left out of the mode's words.

An open arc contact is measured by the gap of the part of the circle that exists.  For a half circle
(half angle π/2) on a straight surface the nearest point of the arc, when m < 0, is an end, whose gap
is g + r(1 − √(1 − m²)) ≤ g + r|m| (g the gap of the whole circle); the hybrid model uses

    g_arc = g + r (|m| − m)         (= g where m ≥ 0; above every end's gap where m < 0)

which reaches zero only where the arc itself touches, or at its very end together with the edge there;
its rate is the arc's normal speed.  Lying on the flat face g_arc = r > 0, so the flat face never reads
as the arc touching.  At the very end (m = 0 within round-off) the arc counts as touching only while the
motion brings it back onto the arc (ṁ > 0); leaving, or at rest there, the edge has the contact.  While an
edge touches, the arc can come back only through its end: the margin rising through zero (the watch
``arc-back``) with the edge on the surface hands the contact back.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...derive.derivation import derivation_of
from ...derive.mode import _check_fixed_points, _check_model  # the checks every derivation of kinematics runs
from ...model.arc_edges import with_edges
from ..rhs import compile_functions
from .vocabulary import OPEN

t = dynamicsymbols._t


def extended(system):
    """(the system the hybrid model works with, {arc contact: (edge names)}): the edges of half shapes' curved
    faces added where planar motion on a straight surface has them (model.arc_edges)."""
    if not any(getattr(c, "arc", None) is not None for c in system.constraints.values()):
        return system, {}
    kin = derivation_of(system).kinematics(checks=lambda k: (_check_model(system, k), _check_fixed_points(system, k)))
    if not kin.planar:
        return system, {}
    ext, edges = with_edges(system, kin.F.z)
    if edges:
        derivation_of(ext)._kinematics = kin          # the same bodies, frames and coordinates
    return ext, edges


def parent_of(hyb) -> dict:
    """Edge name → its arc contact's name."""
    return {e: a for a, es in hyb.edges.items() for e in es}


def dormant(hyb, mode: dict, name: str) -> bool:
    """An edge that is open while its arc contact is closed: it cannot touch (no watch, no words)."""
    parent = parent_of(hyb).get(name)
    return parent is not None and mode.get(name) == OPEN and mode.get(parent) != OPEN


def arc_gap(c, kin):
    """(g_arc, its rate) of an arc contact with edges (see the module's docstring)."""
    g = c.gap(kin)
    m = c.arc.margin(c, kin)
    r = sp.sympify(c.radius)
    vn = c.rows(kin, "slip")[0].velocity
    dm = sp.diff(m, t)
    return g + r * (sp.Abs(m) - m), vn + r * (sp.sign(m) - 1) * dm


def arc_watches(hyb, mode: dict, name: str, kin, watch, Watch) -> None:
    """The watches of an open arc contact that has edges: while an edge touches, the margin rising through zero
    (the arc comes back); else g_arc reaching zero (an impact on the arc)."""
    c = hyb.contacts[name]
    if any(mode[e] != OPEN for e in hyb.edges[name]):
        watch(Watch("arc-back", name, f"the arc of {name} comes back to the surface", +1,
                    quantity=f"arc margin of {name}"), c.arc.margin(c, kin))
    else:
        watch(Watch("arc-impact", name, f"impact at {name}", -1, quantity=f"gap of {name}"), arc_gap(c, kin)[0])


def off_arc(hyb, t_, y, p) -> dict:
    """{arc contact: open} for every arc contact with edges that does not touch at the state (g_arc > 0)."""
    scale = max(1.0, float(max(abs(v) for v in y[:2 * hyb.layout.n])))
    return {a: OPEN for a in hyb.edges if hyb.contact_state(a, t_, y, p)[0] > 1e-9 * scale}


def end_values(hyb, name, t_, y, p) -> tuple[float, float, float]:
    """(arc margin m, its rate ṁ, the whole circle's gap g) of an arc contact at a state."""
    key = ("arc end", name)
    if key not in hyb._contact_fns:
        c, kin, lay = hyb.contacts[name], hyb.kin, hyb.layout
        m = c.arc.margin(c, kin)
        hyb._contact_fns[key] = compile_functions(lay.arguments(), [lay.to_plain(e) for e in
                                                                    (m, sp.diff(m, t), c.gap(kin))])
    m, dm, g = (float(v) for v in hyb._contact_fns[key](t_, *y[:2 * hyb.layout.n], *p))
    return m, dm, g


def leaving_end(hyb, name, t_, y, p) -> bool:
    """At the end of the arc (m = 0 within round-off) and not coming back onto it (ṁ ≤ 0)."""
    m, dm, _ = end_values(hyb, name, t_, y, p)
    return abs(m) <= 1e-9 and dm <= 0
