"""Forward dynamics of a tree of pinned rigid bodies in O(n): Featherstone's articulated-body algorithm.

The model is read once as a tree (``tree.read_tree``: elementary rotations, joints, offsets, loads);
at a state every quantity is numeric.  Spatial vectors are written in the inertial frame about the
fixed origin O (Plücker coordinates, angular part first), so no transform is needed between bodies:

* motion of joint degree of freedom k, a rotation about the unit axis s_k through the pin J:
  S_k = [s_k; r_J × s_k]; spatial velocities v_k = v_parent + S_k ψ̇_k, velocity-product
  accelerations c_k = v_k ×ₘ S_k ψ̇_k;
* spatial inertia of a body about O: [[Ī + m C Cᵀ, m C], [m Cᵀ, m 1]] with C = [r_G ×], and bias
  force p = v ×* (I v) − f_ext (f_ext the loads' wrenches about O);
* inward pass: articulated inertias I^A = I + Σ (I^A − U Uᵀ/D), bias forces p^A = p + Σ (p^A + I^a c + U u/D)
  with U = I^A S, D = Sᵀ U, u = −Sᵀ p^A;
* outward pass from the base's acceleration −g (gravity as a fictitious base acceleration):
  ψ̈_k = (u_k − Uᵀ (a_parent + c_k)) / D_k.

Each step costs the same for every degree of freedom, so one evaluation grows linearly with the
number of bodies.  The accelerations of the model's coordinates follow from ψ̈ = C q̈ (C constant):
by substitution where each joint brings one new coordinate (a chain in absolute or relative angles),
otherwise by one LU factorisation made once per parameter set.  The pin reactions are the spatial
forces the joints transmit, f = I^A a + p^A.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ..rhs import compile_functions
from ..state import StateLayout
from .aba_c import compiled
from .tree import NotATree, Tree, node_coefficients, read_tree

t = dynamicsymbols._t


def _inertia_matrix(body):
    """The central inertia of ``body`` as a 3×3 matrix in its own frame (read term by term when every
    term is written in that frame, as the shapes write them; otherwise through sympy's to_matrix)."""
    I, ref = body.inertia, body.frame.ref
    M = sp.zeros(3, 3)
    for c, v1, v2 in I.args:
        if len(v1.args) != 1 or len(v2.args) != 1 or v1.args[0][1] != ref or v2.args[0][1] != ref:
            return list(I.to_matrix(ref))
        M += c * v1.args[0][0] * v2.args[0][0].T
    return list(M)


def _skew(v):
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _terms(vec, frame_index):
    """A sympy Vector as [(elementary frame, [x, y, z] expressions)]."""
    out = []
    for comps, frame in vec.args:
        if frame not in frame_index:
            raise NotATree(f"a vector is written in frame {frame}, which is not a frame of the model")
        out.append((frame_index[frame], list(comps)))
    return out


class ArticulatedModel:
    """dy/dt, energy and pin reactions of ``system`` by the articulated-body algorithm (NotATree otherwise)."""

    #: evaluate the step in C where the tree's only load is gravity and a compiler is available
    use_c = True

    def __init__(self, system, tree: Tree | None = None, layout: StateLayout | None = None, use_c: bool = True):
        self.system = system
        self.use_c = use_c
        self.tree = tr = tree or read_tree(system)
        self.layout = lay = layout or StateLayout.of(system)
        if tuple(lay.coordinates) != tr.coordinates:
            raise NotATree("the state's coordinates are not the model's")
        self.n = lay.n
        fi = tr.frame_index
        # every expression the algorithm needs, in one compiled function of (t, q, q̇, p) ------------------
        exprs, self._slots = [], {}
        qs, us = lay.plain_symbols()
        plain = {c.diff(t): v for c, v in zip(lay.coordinates, us)}
        plain.update(zip(lay.coordinates, qs))

        def to_plain(e):
            return sp.sympify(e).xreplace(plain)

        def put(key, items):
            self._slots[key] = (len(exprs), len(items))
            exprs.extend(to_plain(e) for e in items)

        E = len(tr.edges)
        put("axes", [a for e in tr.edges for a in e.axis])
        self._ecoef = [(k, i) for k, e in enumerate(tr.edges) for i in e.coeffs]
        put("ecoef", [tr.edges[k].coeffs[i] for k, i in self._ecoef])
        put("econst", [e.offset for e in tr.edges])
        self._ncoef = [(k, i, c) for k in range(len(tr.nodes)) for i, c in node_coefficients(tr, k).items()]
        put("ncoef", [c for _, _, c in self._ncoef])
        put("mass", [b.mass for b in tr.bodies])
        put("inertia", [c for b in tr.bodies for c in _inertia_matrix(b)])
        self._vec_terms = {}
        for j, jt in enumerate(tr.joints):
            for what in ("to_pin", "to_centre"):
                terms = _terms(getattr(jt, what), fi)
                self._vec_terms[(what, j)] = [f for f, _ in terms]
                put((what, j), [c for _, cs in terms for c in cs])
        gterms = []
        for g, d in tr.gravity:
            for f, cs in _terms(d, fi):
                gterms.append(f)
                exprs_g = [g * c for c in cs]
                put(("gravity", len(gterms) - 1), exprs_g)
        self._gframes = gterms
        for a, (_, arm, _, _) in enumerate(tr.applications):
            if arm is not None:
                terms = _terms(arm, fi)
                self._vec_terms[("arm", a)] = [f for f, _ in terms]
                put(("arm", a), [c for _, cs in terms for c in cs])
        self._geometry = compile_functions(lay.arguments(), exprs)
        # loads and potentials: the part that changes with the state
        lexprs, self._lslots = [], []
        for _, _, vec, _ in tr.applications:
            terms = _terms(vec, fi)
            self._lslots.append((len(lexprs), [f for f, _ in terms]))
            lexprs.extend(to_plain(c) for _, cs in terms for c in cs)
        self._n_load = len(lexprs)
        lexprs.extend(to_plain(u) for u in tr.potentials)
        self._loads = compile_functions(lay.arguments(), lexprs) if lexprs else None
        self._E = E
        self._cache: dict = {}
        self.conservative = all(kind == "torsional spring" for *_, kind in tr.applications)
        planar = _planar(tr)
        self.reaction_names = []
        self._react = []                  # (joint, sign, frame comps 3×k)
        for j, jt in enumerate(tr.joints):
            pin = system.constraints[jt.pin]
            syms = pin._symbols(2 if planar else 3)
            self.reaction_names += [str(s) for s in syms]
            sign = 1.0 if pin.body_a is tr.bodies[jt.body] else -1.0
            self._react.append((j, sign, pin.basis_frame or system.inertial, len(syms)))

    # numbers that depend only on the parameters ---------------------------------------------------------
    def numbers(self, p) -> dict:
        key = tuple(float(v) for v in p)
        if key not in self._cache:
            if len(self._cache) > 64:
                self._cache.clear()
            self._cache[key] = self._numbers(np.asarray(p, dtype=float))
        return self._cache[key]

    def _numbers(self, p) -> dict:
        tr, n, E = self.tree, self.n, self._E
        rng = np.random.default_rng(7)
        states = [np.concatenate([[0.3], rng.uniform(-1.5, 1.5, 2 * n)]) for _ in range(2)]
        vals = [np.array(self._geometry(*s, *p), dtype=float) for s in states]
        if not np.allclose(vals[0][:self._slots["ncoef"][0] + self._slots["ncoef"][1]],
                           vals[1][:self._slots["ncoef"][0] + self._slots["ncoef"][1]]):
            raise NotATree("a joint axis or angle coefficient changes with the state")

        def get(v, key):
            i, k = self._slots[key]
            return v[i:i + k]

        g = vals[0]
        axes = get(g, "axes").reshape(E, 3)
        K = np.array([_skew(a) for a in axes]).reshape(E, 3, 3)
        num = {"K": K, "K2": K @ K, "parent": np.array([e.parent for e in tr.edges], dtype=int)}
        num["erow"] = np.array([k for k, _ in self._ecoef], dtype=int)
        num["ecol"] = np.array([i for _, i in self._ecoef], dtype=int)
        num["eval"] = get(g, "ecoef")
        num["econst"] = get(g, "econst")
        C = np.zeros((n, n))
        for (k, i, _), c in zip(self._ncoef, get(g, "ncoef")):
            C[k, i] = c
        num["nrow"] = np.array([k for k, _, _ in self._ncoef], dtype=int)
        num["ncol"] = np.array([i for _, i, _ in self._ncoef], dtype=int)
        num["nval"] = get(g, "ncoef")
        if abs(np.linalg.det(C)) < 1e-12 * max(1.0, float(np.max(np.abs(C)))) ** n:
            raise NotATree("the joint angles do not determine the coordinates")
        num["solve"], num["plan"] = self._substitution(C)
        # geometry in the body frames, checked constant at two states
        Ws = [self._orientations(num, s[1:1 + n]) for s in states]

        def local(key, frame, v_all):
            out = []
            for v, W in zip(v_all, Ws):
                cs = get(v, key).reshape(-1, 3)
                world = sum((W[f] @ c for f, c in zip(self._vec_terms[key], cs)), np.zeros(3))
                out.append(W[frame].T @ world)
            scale = max(1.0, float(np.max(np.abs(out[0]))))
            if not np.allclose(out[0], out[1], atol=1e-10 * scale, rtol=0):
                raise NotATree("a point the algorithm needs is not fixed in its body (" + str(key[0]) + ")")
            return out[0]

        fb = np.array([self.tree.frame_index[b.frame.ref] for b in tr.bodies], dtype=int)
        num["fb"] = fb
        num["to_pin"] = np.array([local(("to_pin", j), -1 if jt.parent < 0 else fb[jt.parent], vals)
                                  for j, jt in enumerate(tr.joints)])
        num["to_centre"] = np.array([local(("to_centre", j), fb[jt.body], vals) for j, jt in enumerate(tr.joints)])
        num["arm"] = {a: local(("arm", a), fb[b], vals) for a, (b, arm, _, _) in enumerate(tr.applications)
                      if arm is not None}
        num["mass"] = get(g, "mass")
        Ib = get(g, "inertia").reshape(-1, 3, 3)
        if not np.allclose(Ib, get(vals[1], "inertia").reshape(-1, 3, 3)):
            raise NotATree("an inertia is not constant in its body frame")
        num["Ib"] = Ib
        gvec = np.zeros(3)
        for i, f in enumerate(self._gframes):
            gvec += Ws[0][f] @ get(g, ("gravity", i))
        num["g"] = gvec
        # joint degrees of freedom: parent node, the body they carry
        parent_node, attach = [], []
        last_of_body: dict = {}
        for jt in tr.joints:
            above = last_of_body.get(jt.parent, -1) if jt.parent >= 0 else -1
            for k in jt.nodes:
                parent_node.append(above)
                above = k
            last_of_body[jt.body] = above
            attach.append(above)
        num["pnode"], num["attach"] = parent_node, np.array(attach, dtype=int)
        num["jparent"] = [jt.parent for jt in tr.joints]
        num["nbody"] = np.array([tr.nodes[k].body for k in range(len(tr.nodes))], dtype=int)
        num["before"] = np.array([tr.nodes[k].before for k in range(len(tr.nodes))], dtype=int)
        num["naxis"] = np.array([[float(c) for c in tr.nodes[k].axis] for k in range(len(tr.nodes))])
        num["first"] = {jt.nodes[0]: j for j, jt in enumerate(tr.joints) if jt.nodes}
        num["c"] = None
        if self.use_c and not tr.applications:      # gravity only: the whole step in C (numeric/aba_c.py)
            num["c"] = compiled(num, n)
        return num

    @staticmethod
    def _substitution(C):
        """q̈ from ψ̈ = C q̈: in order where each row brings one new coordinate (O(nonzeros)), else by LU."""
        n = C.shape[0]
        seen, plan = set(), []
        for k in range(n):
            cols = [i for i in np.nonzero(C[k])[0]]
            new = [i for i in cols if i not in seen]
            if len(new) != 1:
                import scipy.linalg as sla  # here: importing the route (and simulate) loads no scipy

                lu = sla.lu_factor(C)
                return (lambda psi_dd, lu=lu: sla.lu_solve(lu, psi_dd)), None
            i = new[0]
            seen.add(i)
            plan.append((k, i, C[k, i], [(j, C[k, j]) for j in cols if j != i]))

        def solve(psi_dd):
            out = np.empty(n)
            for k, i, cii, rest in plan:
                out[i] = (psi_dd[k] - sum(c * out[j] for j, c in rest)) / cii
            return out
        return solve, plan

    def _orientations(self, num, q):
        """World orientation of every elementary frame (index −1, the last row: the inertial frame)."""
        alpha = num["econst"] + np.bincount(num["erow"], num["eval"] * q[num["ecol"]], minlength=self._E)
        s, c = np.sin(alpha), np.cos(alpha)
        R = np.eye(3) + s[:, None, None] * num["K"] + (1.0 - c)[:, None, None] * num["K2"]
        W = np.empty((self._E + 1, 3, 3))
        W[-1] = np.eye(3)
        parent = num["parent"]
        for e in range(self._E):
            W[e] = W[parent[e]] @ R[e]
        return W

    # the state ------------------------------------------------------------------------------------
    def _kinematics(self, t_, y, p):
        num = self.numbers(p)
        n, tr = self.n, self.tree
        q, u = np.asarray(y[:n], dtype=float), np.asarray(y[n:2 * n], dtype=float)
        W = self._orientations(num, q)
        psi_d = np.bincount(num["nrow"], num["nval"] * u[num["ncol"]], minlength=len(tr.nodes))
        nb = len(tr.bodies)
        rG, rJ = np.empty((nb, 3)), np.empty((nb, 3))
        fb, to_pin, to_centre = num["fb"], num["to_pin"], num["to_centre"]
        for j, par in enumerate(num["jparent"]):
            rJ[j] = to_pin[j] if par < 0 else rG[par] + W[fb[par]] @ to_pin[j]
            rG[j] = rJ[j] + W[fb[j]] @ to_centre[j]
        s = np.einsum("kij,kj->ki", W[num["before"]], num["naxis"])
        S = np.concatenate([s, np.cross(rJ[num["nbody"]], s)], axis=1)
        vj = S * psi_d[:, None]
        V = np.empty_like(vj)
        zero = np.zeros(6)
        for k, par in enumerate(num["pnode"]):
            V[k] = (V[par] if par >= 0 else zero) + vj[k]
        cacc = _crm(V, vj)
        att = num["attach"]
        Vb = np.where((att >= 0)[:, None], V[att], 0.0)
        loads = np.array(self._loads(t_, *y[:2 * n], *p), dtype=float) if self._loads is not None else np.zeros(0)
        return num, W, rG, rJ, S, V, cacc, Vb, loads

    def _inertias(self, num, W, rG):
        """Spatial inertias of the bodies about O in the inertial frame, (bodies, 6, 6)."""
        m = num["mass"]
        Wb = W[num["fb"]]
        Iw = Wb @ num["Ib"] @ np.swapaxes(Wb, 1, 2)
        Cx = _skew_many(rG)
        mC = m[:, None, None] * Cx
        out = np.empty((len(m), 6, 6))
        out[:, :3, :3] = Iw - mC @ Cx
        out[:, :3, 3:] = mC
        out[:, 3:, :3] = -mC
        out[:, 3:, 3:] = m[:, None, None] * np.eye(3)
        return out

    def _wrenches(self, num, W, rG, Vb, loads):
        """Spatial forces of the loads about O on each body, and their power where they are not conservative."""
        f = np.zeros((len(self.tree.bodies), 6))
        power = 0.0
        for a, (b, arm, _, kind) in enumerate(self.tree.applications):
            i, frames = self._lslots[a]
            cs = loads[i:i + 3 * len(frames)].reshape(-1, 3)
            vec = sum((W[fr] @ c for fr, c in zip(frames, cs)), np.zeros(3))
            w, v0 = Vb[b][:3], Vb[b][3:]
            if arm is None:
                f[b, :3] += vec
                pw = vec @ w
            else:
                r = rG[b] + W[num["fb"][b]] @ num["arm"][a]
                f[b] += np.concatenate([_cross(r, vec), vec])
                pw = vec @ (v0 + _cross(w, r))
            if kind != "torsional spring":
                power += pw
        return f, power

    def dynamics(self, t_, y, p):
        """(q̈, ψ̈, pin reactions, power of the non-conservative loads, kinematics) at the state."""
        num, W, rG, rJ, S, V, cacc, Vb, loads = self._kinematics(t_, y, p)
        tr = self.tree
        nn = len(tr.nodes)
        Ibody = self._inertias(num, W, rG)
        fext, power = self._wrenches(num, W, rG, Vb, loads)
        IA = np.zeros((nn, 6, 6))
        pA = np.zeros((nn, 6))
        pb = _crf(Vb, np.einsum("bij,bj->bi", Ibody, Vb)) - fext
        for b, a in enumerate(num["attach"]):
            if a >= 0:
                IA[a] += Ibody[b]
                pA[a] += pb[b]
        U, D, u = np.empty((nn, 6)), np.empty(nn), np.empty(nn)
        for k in range(nn - 1, -1, -1):
            U[k] = IA[k] @ S[k]
            D[k] = S[k] @ U[k]
            u[k] = -S[k] @ pA[k]
            par = num["pnode"][k]
            if par >= 0:
                Ia = IA[k] - np.outer(U[k], U[k]) / D[k]
                IA[par] += Ia
                pA[par] += pA[k] + Ia @ cacc[k] + U[k] * (u[k] / D[k])
        A = np.empty((nn, 6))
        base = np.concatenate([np.zeros(3), -num["g"]])
        psi_dd = np.empty(nn)
        for k in range(nn):
            par = num["pnode"][k]
            a = (A[par] if par >= 0 else base) + cacc[k]
            psi_dd[k] = (u[k] - U[k] @ a) / D[k]
            A[k] = a + S[k] * psi_dd[k]
        qdd = num["solve"](psi_dd)
        return qdd, (IA, pA, A, W), power, (num, W, rG, Vb, loads)

    def accelerations(self, t_, y, p) -> np.ndarray:
        """q̈ of every coordinate at (t, y = (q, q̇)) with parameters p."""
        return self.dynamics(t_, y, p)[0]

    def rates(self, t_, y, p) -> np.ndarray:
        """dy/dt of (q, q̇) and of the work of the non-conservative loads (the simulation's state)."""
        n = self.n
        fast = self.numbers(p)["c"]
        if fast is not None:                  # gravity only: no load does work
            return np.concatenate([y[n:2 * n], fast.qdd(y[:n], y[n:2 * n]), [0.0]])
        qdd, _, power, _ = self.dynamics(t_, y, p)
        return np.concatenate([y[self.n:2 * self.n], qdd, [power]])

    def reactions(self, t_, y, p) -> dict:
        """The pin reactions (force on body_a, along the pin's basis) from the forces the joints transmit."""
        return self.sample(t_, y, p)[0]

    def energy(self, t_, y, p) -> tuple[float, float]:
        """(T, U): kinetic energy and the potential of gravity and of the torsional springs."""
        num, W, rG, _, _, _, _, Vb, loads = self._kinematics(t_, y, p)
        return self._energy(num, W, rG, Vb, loads)

    def sample(self, t_, y, p) -> tuple[dict, float, float]:
        """(pin reactions, T, U) at the state from one evaluation of the algorithm."""
        tr, n = self.tree, self.n
        fast = self.numbers(p)["c"]
        if fast is not None and all(frame is self.system.inertial for _, _, frame, _ in self._react):
            _, jf, T, U = fast.sample(y[:n], y[n:2 * n])
            W, energy = None, (T, U)
        else:
            _, (IA, pA, A, _), _, (num, W, rG, Vb, loads) = self.dynamics(t_, y, p)
            jf = np.array([IA[k] @ A[k] + pA[k] for k in range(len(tr.nodes))])
            energy = self._energy(num, W, rG, Vb, loads)
        out = {}
        names = iter(self.reaction_names)
        for j, sign, frame, k in self._react:
            nodes = tr.joints[j].nodes
            if nodes:
                force = sign * jf[nodes[0]][3:]
            else:
                force = np.full(3, np.nan)       # a welded body: its joint force is not computed here
            Wf = W[tr.frame_index[frame.ref]] if W is not None and frame.ref in tr.frame_index else np.eye(3)
            comp = Wf.T @ force
            for i in range(k):
                out[next(names)] = float(comp[i])
        return (out, *energy)

    def _energy(self, num, W, rG, Vb, loads) -> tuple[float, float]:
        Ibody = self._inertias(num, W, rG)
        T = 0.5 * float(np.einsum("bi,bij,bj->", Vb, Ibody, Vb))
        U = -float(num["mass"] @ (rG @ num["g"]))
        U += float(np.sum(loads[self._n_load:]))
        return T, U


def _planar(tr: Tree) -> bool:
    """Motion in the Ex–Ey plane: every rotation about Ez, no offset, gravity or force along it, no torque
    across it (then a pin has two reaction components, as the symbolic route names them)."""
    if any(sp.simplify(e.axis[0]) != 0 or sp.simplify(e.axis[1]) != 0 for e in tr.edges):
        return False

    def along_z(v, which=(2,)):
        return all(sp.simplify(sum((m[i] for m, _ in v.args), sp.Integer(0))) == 0 for i in which)

    vecs = [jt.to_pin for jt in tr.joints] + [jt.to_centre for jt in tr.joints] + [d for _, d in tr.gravity]
    if not all(along_z(v) for v in vecs):
        return False
    return all(along_z(vec, (0, 1) if arm is None else (2,)) for _, arm, vec, _ in tr.applications) and \
        all(arm is None or along_z(arm) for _, arm, _, _ in tr.applications)


def _cross(a, b):
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def _skew_many(r):
    out = np.zeros((len(r), 3, 3))
    out[:, 0, 1], out[:, 0, 2], out[:, 1, 2] = -r[:, 2], r[:, 1], -r[:, 0]
    out[:, 1, 0], out[:, 2, 0], out[:, 2, 1] = r[:, 2], -r[:, 1], r[:, 0]
    return out


def _crm(v, m):
    """Spatial motion cross products v ×ₘ m, row by row."""
    w, v0 = v[:, :3], v[:, 3:]
    return np.concatenate([np.cross(w, m[:, :3]), np.cross(w, m[:, 3:]) + np.cross(v0, m[:, :3])], axis=1)


def _crf(v, f):
    """Spatial force cross products v ×* f, row by row."""
    w, v0 = v[:, :3], v[:, 3:]
    return np.concatenate([np.cross(w, f[:, :3]) + np.cross(v0, f[:, 3:]), np.cross(w, f[:, 3:])], axis=1)
