"""The tree of pinned rigid bodies a model describes, read for the articulated-body algorithm.

Every frame of the model is a chain of *elementary rotations* from its parent (one about an axis, or
three for a body-fixed angle sequence such as 3-1-3).  A body hangs from its parent body (or the
ground) at a pin J; the rotation from the parent's frame to the body's frame is the path of
elementary rotations between the two frames in the frame tree: up from the parent's frame (each
rotation undone) and down to the body's.  Consecutive rotations about the same axis merge (absolute
angles θ_i, θ_{i−1} of a chain make one joint angle θ_i − θ_{i−1}); a rotation whose angle depends on
the coordinates is a joint degree of freedom ψ_k = c_k·q + d_k (c_k constant), one that does not is
a fixed turn.  The joint rates are ψ̇ = C q̇ with C square and constant, so q̈ = C⁻¹ ψ̈.

Only what the algorithm needs is built symbolically, and it is small: each rotation's axis and
angle, the offsets J − G_parent and G − J (point-tree paths), masses, inertias in the body frames,
and the load vectors.  Anything outside this class of models (contacts, collars, ropes, springs
between points, dampers, friction, points sliding on a body) raises :class:`NotATree` with the
reason, and the symbolic route is used as before.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ...model.definitions import expand

t = dynamicsymbols._t
_AXIS = {"1": (1, 0, 0), "2": (0, 1, 0), "3": (0, 0, 1)}
#: loads the articulated route evaluates (gravity as a base acceleration, the others as body wrenches)
LOAD_KINDS = ("gravity", "force", "torque", "torsional spring")


class NotATree(Exception):
    """The model is not a tree of pinned bodies the articulated-body algorithm handles; the message says why."""


@dataclass
class Edge:
    """One elementary rotation: from elementary frame ``parent`` (−1: the inertial frame F) by ``angle``
    about ``axis`` (a constant unit vector in the parent's coordinates)."""

    parent: int
    axis: tuple
    angle: sp.Expr
    coeffs: dict = field(default_factory=dict)    # coordinate index → constant coefficient of the angle
    offset: sp.Expr = sp.Integer(0)               # the angle's constant part


@dataclass
class Node:
    """One joint degree of freedom: rotation about ``axis`` (coordinates of elementary frame ``before``)
    through the pin of ``body``; its angle is Σ sign·angle of the merged ``steps`` (edge, sign)."""

    body: int
    before: int
    axis: tuple
    steps: list


@dataclass
class Joint:
    """Body ``body`` pinned at point ``pin_point`` to body ``parent`` (−1: the ground) by pin ``pin``."""

    body: int
    parent: int
    pin: str
    to_pin: Vector          # J − G_parent (from the fixed origin O where the parent is the ground)
    to_centre: Vector       # G − J
    nodes: list             # indices into Tree.nodes


@dataclass
class Tree:
    """The model read as a tree (see the module docstring); ``describe()`` says what it is in words."""

    system: object
    coordinates: tuple
    edges: list
    frame_index: dict       # sympy ReferenceFrame → elementary frame index (F: −1)
    bodies: list            # model bodies, parents before children
    joints: list            # one per body, same order
    nodes: list
    gravity: list           # (g expression, direction Vector)
    applications: list      # (body index, point offset from G or None for a torque, vector, load kind)
    potentials: list        # potential energies of the conservative loads other than gravity

    def describe(self) -> str:
        n = len(self.coordinates)
        return f"{len(self.bodies)} bodies on {len(self.joints)} pins, {n} degree{'s' * (n != 1)} of freedom"


def read_tree(system) -> Tree:
    """The tree of ``system``, or NotATree with the reason it is not one the algorithm handles."""
    coords = tuple(c.symbol for c in system.coordinate_info.values())
    cindex = {q: i for i, q in enumerate(coords)}
    params = {p.symbol for p in system.parameter_info.values()}
    edges, frame_index = _edges(system, cindex, params)
    # constraints: pins only, each a point shared by the two bodies
    pins = []
    for name, c in system.constraints.items():
        if getattr(c, "kind", "") != "pin":
            raise NotATree(f"constraint {name} is a {getattr(c, 'kind', 'constraint')}, not a pin")
        if c.point_b is not None and c.point_b is not c.point:
            raise NotATree(f"pin {name} joins two different points")
        pins.append(c)
    bodies = list(system.bodies.values())
    for b in bodies:
        if b.is_massless:
            raise NotATree(f"body {b.name} is massless")
    if len(pins) != len(bodies):
        raise NotATree(f"{len(bodies)} bodies on {len(pins)} pins is not a tree hanging from the ground")
    order, joints_of = [], {}
    parent_of: dict = {None: None}
    frontier = [None]
    while frontier:
        nxt = []
        for above in frontier:
            for pin in pins:
                ends = (pin.body_a, pin.body_b)
                if above not in ends or pin.name in joints_of:
                    continue
                child = pin.body_a if pin.body_b is above else pin.body_b
                if child is None or child in parent_of:
                    raise NotATree(f"pin {pin.name} closes a loop")
                parent_of[child] = above
                joints_of[pin.name] = child
                order.append((child, above, pin))
                nxt.append(child)
        frontier = nxt
    if len(order) != len(bodies):
        loose = [b.name for b in bodies if b not in parent_of]
        raise NotATree(f"{', '.join(loose)} {'is' if len(loose) == 1 else 'are'} not pinned to the ground "
                       "through other bodies")
    bodies = [b for b, _, _ in order]
    bidx = {id(b): i for i, b in enumerate(bodies)}
    nodes: list[Node] = []
    joints: list[Joint] = []
    for child, above, pin in order:
        fb = _frame_of(child, frame_index)
        fa = -1 if above is None else _frame_of(above, frame_index)
        first = len(nodes)
        nodes += _nodes(bidx[id(child)], _path(edges, fa, fb), edges)
        to_pin = _between(pin.point, above.centre if above is not None else None)
        joints.append(Joint(bidx[id(child)], -1 if above is None else bidx[id(above)], pin.name, to_pin,
                            _between(child.centre, pin.point), list(range(first, len(nodes)))))
        if getattr(pin, "axis", None) and len(joints[-1].nodes) > 1:
            raise NotATree(f"hinge {pin.name} turns about {len(joints[-1].nodes)} axes")
    if len(nodes) != len(coords):
        raise NotATree(f"the joints have {len(nodes)} rotation degrees of freedom for {len(coords)} coordinates "
                       "(a coordinate that is not a joint angle, such as a length, or angles that repeat)")
    gravity, apps, pots = [], [], []
    for name, ld in system.loads.items():
        kind = getattr(ld, "kind", "load")
        if kind not in LOAD_KINDS:
            raise NotATree(f"load {name} is a {kind}")
        if kind == "gravity":
            gravity.append((expand(ld.g), expand(ld.direction)))
            continue
        if kind == "torsional spring":
            pots.append(expand(ld.potential(None)))
        for app in ld.applications(None):
            if app.location is not None or app.reaction is not None:
                raise NotATree(f"load {name} acts at a moving location")
            if id(app.body) not in bidx:
                raise NotATree(f"load {name} acts on something that is not a body of the tree")
            arm = None if app.point is None else _between(app.point, app.body.centre)
            apps.append((bidx[id(app.body)], arm, expand(app.vector), kind))
    return Tree(system, coords, edges, frame_index, bodies, joints, nodes, gravity, apps, pots)


def _linear(angle, cindex, params, where):
    """(coordinate index → coefficient, constant part) of an angle linear in the coordinates."""
    angle = expand(sp.sympify(angle))
    coeffs, rest = {}, angle
    for q, i in cindex.items():
        if angle.has(q):
            c = sp.diff(angle, q)
            if c.free_symbols - params or c.has(t) or any(c.has(qq) for qq in cindex):
                raise NotATree(f"the angle {angle} of {where} is not linear in the coordinates")
            coeffs[i] = c
            rest = rest - c * q
    rest = sp.expand(rest)
    if rest.free_symbols - params or rest.has(t):
        raise NotATree(f"the angle {angle} of {where} depends on time or on something other than the coordinates")
    return coeffs, rest


def _edges(system, cindex, params):
    edges: list[Edge] = []
    index = {system.inertial.ref: -1}
    if getattr(system, "speed_groups", None):
        raise NotATree("the model has generalised speeds other than the coordinates' rates")
    for name, fr in system.frames.items():
        if fr.parent is None:
            continue
        if getattr(fr, "quaternion", None) is not None or getattr(fr, "speeds", None) is not None:
            raise NotATree(f"frame {name} is oriented by a quaternion or has its own speeds")
        parent = index.get(fr.parent.ref)
        if parent is None:
            raise NotATree(f"frame {name} turns from a frame defined after it")
        if fr.sequence is not None:
            steps = [(_AXIS.get(ch), ang) for ch, ang in zip(fr.sequence, fr.angles)]
            if any(a is None for a, _ in steps):
                raise NotATree(f"frame {name}'s sequence {fr.sequence} is not made of 1, 2, 3")
        else:
            ax = fr.axis.to_matrix(fr.parent.ref)
            ax = [sp.nsimplify(c) if c.is_number else c for c in expand(ax) / sp.sqrt((ax.T * ax)[0])]
            if any(sp.sympify(c).free_symbols - params for c in ax):
                raise NotATree(f"frame {name}'s axis is not fixed in its parent frame")
            steps = [(tuple(ax), fr.angle)]
        for ax, ang in steps:
            coeffs, const = _linear(ang, cindex, params, f"frame {name}")
            edges.append(Edge(parent, tuple(sp.sympify(a) for a in ax), expand(sp.sympify(ang)), coeffs, const))
            parent = len(edges) - 1
        index[fr.ref] = parent
    return edges, index


def _frame_of(body, frame_index) -> int:
    try:
        return frame_index[body.frame.ref]
    except KeyError:
        raise NotATree(f"body {body.name}'s frame is not a frame of the model") from None


def _ancestors(edges, e) -> list:
    out = []
    while e != -1:
        out.append(e)
        e = edges[e].parent
    return out


def _path(edges, a, b) -> list:
    """(edge, sign) from elementary frame ``a`` to ``b``: up from a (sign −1), then down to b (+1)."""
    up, down = _ancestors(edges, a), _ancestors(edges, b)
    common = set(up) & set(down)
    up = [e for e in up if e not in common]
    down = [e for e in down if e not in common]
    return [(e, -1) for e in up] + [(e, +1) for e in reversed(down)]


def _nodes(body, path, edges) -> list:
    """The joint's degrees of freedom along ``path``: turning steps, consecutive ones about one axis merged."""
    out: list[Node] = []
    last = None
    for e, sign in path:
        edge = edges[e]
        if not edge.coeffs:
            last = None          # a fixed turn between two degrees of freedom
            continue
        before = e if sign < 0 else edge.parent
        if last is not None and all(sp.simplify(a - b) == 0 for a, b in zip(last.axis, edge.axis)):
            last.steps.append((e, sign))
            continue
        last = Node(body, before, edge.axis, [(e, sign)])
        out.append(last)
    # merged steps whose angles cancel (two frames turned by the same coordinate) are fixed turns
    kept = []
    for nd in out:
        total: dict = {}
        for e, sign in nd.steps:
            for i, c in edges[e].coeffs.items():
                total[i] = sp.simplify(total.get(i, 0) + sign * c)
        if any(v != 0 for v in total.values()):
            kept.append(nd)
    return kept


def _point_chain(p) -> list:
    out = []
    while p is not None:
        out.append(p)
        p = p.parent
    return out


def _between(to, frm) -> Vector:
    """The vector from point ``frm`` (None: the origin) to point ``to`` along the tree of point offsets."""
    a = _point_chain(to)
    b = _point_chain(frm) if frm is not None else []
    common = {id(p) for p in a} & {id(p) for p in b}
    v = Vector(0)
    for p in a:
        if id(p) in common:
            break
        v = v + p.offset
    for p in b:
        if id(p) in common:
            break
        v = v - p.offset
    return expand(v)


def node_coefficients(tree: Tree, k: int) -> dict:
    """ψ̇_k = Σ c_i q̇_i: coordinate index → coefficient (sympy) of node ``k``."""
    total: dict = {}
    for e, sign in tree.nodes[k].steps:
        for i, c in tree.edges[e].coeffs.items():
            total[i] = total.get(i, 0) + sign * c
    return {i: c for i, c in total.items() if sp.simplify(c) != 0}
