"""Generated code: the equations of one regime of one mode as compiled C, or numpy without a compiler.

``kernel`` reads the :class:`~rigidkin.numeric.compiled.kernel.Kernel` of a regime from a system: its
unknowns (the independent accelerations and the reactions), explicit (the Solution's solved expressions),
in mass-matrix form (M q̈ = f) or implicit (the balance equations A·X = b), its rates and named outputs.

``compile_kernel`` turns it into one C file (:mod:`rigidkin.numeric.compiled.csource`: common subexpressions
eliminated with ``sympy.cse``, small integer powers as products, our own names only — no user text),
compiled once with the machine's C compiler and loaded through cffi; the shared library is cached on
disk by a hash of the generated source in ``$RIGIDKIN_CACHE`` (default ``~/.cache/rigidkin``), a
private folder whose every file is checked before it is loaded (:mod:`rigidkin.numeric.compiled.cache`).  The
same file holds the batch integrator of :mod:`rigidkin.numeric.compiled.batch`.  Without a compiler (or cffi)
the same kernel is evaluated by numpy (``lambdify`` with CSE, on our own argument names), so every
caller keeps working, only slower.
"""

from __future__ import annotations

import itertools
import warnings
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import sympy as sp
from sympy.physics.vector import dynamicsymbols

from ...base.trace import Trace
from ...derive.derivation import derivation_of
from ...derive.kinematics import linear_form
from ...derive.laws import newton_euler
from ...derive.mode import setup_mode
from ...derive.solution import _determinacy
from ..rhs import SimulationError
from ..state import StateLayout, parameter_vector
from .batch import INTEGRATOR_C, INTEGRATOR_CDEF
from .cache import _LOADED, build, cache_dir, compiler  # noqa: F401  (cache_dir, _LOADED: public through here)
from .codesafe import safe_lambdify
from .csource import _CDEF, c_source  # noqa: F401  (c_source, _CDEF: public through here)
from .kernel import CODE_VERSION, CodegenError, Kernel, check_free  # noqa: F401  (public through here)

t = dynamicsymbols._t

BACKENDS = ("auto", "c", "numpy")
FORMS = ("auto", "explicit", "mass-matrix", "implicit")


def kernel(system, mode: Mapping | None = None, regime: int = 0, form: str = "auto") -> Kernel:
    """The kernel of ``system`` in ``mode`` (regime ``regime``), from the solved or the unsolved equations.

    ``form="explicit"`` uses the Solution's solved accelerations and reactions; ``"mass-matrix"`` the
    Solution's mass matrix and forcing (M q̈ = f solved by LU at each call; the reactions from the
    balance equations, by LU too); ``"implicit"`` the Newton–Euler balance equations A·X = b without
    any symbolic solve.  ``"auto"``: the mass-matrix form when the Solution keeps M q̈ = f unsolved
    (no reaction does work) and there are more than two degrees of freedom (long chains, whose
    solved expressions grow without bound), the explicit form otherwise.
    """
    if form not in FORMS:
        raise CodegenError(f"unknown form '{form}'.", hint=f"Use one of: {', '.join(FORMS)}.")
    mode = dict(mode or {})
    key = (tuple(sorted(mode.items())), regime, form)
    if (kept := derivation_of(system).kernel(key)) is not None:
        return kept
    setup = setup_mode(system, mode)
    if form == "auto":
        reg = system.solve(mode=mode).regime(regime)
        lazy = hasattr(reg.accelerations, "computed")      # the Solution left M q̈ = f unsolved
        form = "mass-matrix" if lazy and len(setup.reduction.independent) > 2 else "explicit"
    if form == "explicit":
        k = _explicit(system, setup, mode, regime)
    elif form == "mass-matrix":
        k = _mass_matrix(system, setup, mode, regime)
    else:
        k = _implicit(system, setup, regime)
    return derivation_of(system).keep_kernel(key, k)


def _rates(layout: StateLayout, red, accel_symbols: Mapping) -> list:
    """dy/dt of every coordinate: q̇ then q̈ (dependent ones from the reduction's relations)."""
    qdot, udot = [], []
    for q in layout.coordinates:
        if q in red.independent:
            qdot.append(q.diff(t))
            udot.append(accel_symbols[q])
        else:
            qdot.append(red.rate_map[q.diff(t)])
            acc = {p.diff(t, 2): accel_symbols[p] for p in red.independent}
            udot.append(sp.sympify(red.accel_map[q.diff(t, 2)]).xreplace(acc).xreplace(red.rate_map))
    return [layout.to_plain(e) for e in (*qdot, *udot)]


def _unknown_symbols(red, reaction_names):
    names = [f"ddot({q.func.__name__})" for q in red.independent] + list(reaction_names)
    return [sp.Symbol(f"X{i}", real=True) for i in range(len(names))], names


def _explicit(system, setup, mode, regime) -> Kernel:
    sol = system.solve(mode=mode)
    reg = sol.regime(regime)
    layout = StateLayout.of(system)
    red = setup.reduction
    X, names = _unknown_symbols(red, list(reg.reactions))
    accel = dict(zip(red.independent, X))
    b = [layout.to_plain(reg.accelerations[q]) for q in red.independent]
    b += [layout.to_plain(v) for v in reg.reactions.values()]
    rates = _rates(layout, red, accel)
    outputs = X[len(red.independent):]
    k = Kernel(layout, tuple(X), tuple(names), None, tuple(b), tuple(rates), tuple(outputs),
               tuple(names[len(red.independent):]), label=system.name)
    check_free(k, [*b, *rates])
    return k


def _mass_matrix(system, setup, mode, regime) -> Kernel:
    sol = system.solve(mode=mode)
    reg = sol.regime(regime)
    red = setup.reduction
    layout = StateLayout.of(system)
    present = set().union(*[e.expr.free_symbols for e in sol.equations]) if sol.equations else set()
    reactions = [r for r in setup.reactions if r in present]
    absent = [r for r in setup.reactions if r not in present]
    unknowns = [q.diff(t, 2) for q in red.independent] + reactions
    A, b = linear_form([e.expr.xreplace(dict(reg.signs)) for e in sol.equations], unknowns)
    keep = _determinacy(A, b, unknowns, [e.label for e in sol.equations])
    A, b = A.extract(keep, list(range(len(unknowns)))), -b.extract(keep, [0])
    X, names = _unknown_symbols(red, [str(r) for r in reactions])
    rates = _rates(layout, red, dict(zip(red.independent, X)))
    n_acc = len(red.independent)
    k = Kernel(layout, tuple(X), tuple(names), A.applyfunc(layout.to_plain), tuple(layout.to_plain(e) for e in b),
               tuple(rates), tuple(X[n_acc:]) + (sp.Integer(0),) * len(absent),
               tuple(names[n_acc:]) + tuple(str(r) for r in absent), label=system.name,
               M=reg.mass_matrix.applyfunc(layout.to_plain), f=tuple(layout.to_plain(e) for e in reg.forcing))
    check_free(k, [*k.A, *k.b, *rates, *k.M, *k.f])
    return k


def _implicit(system, setup, regime) -> Kernel:
    red = setup.reduction
    saved, setup.trace = setup.trace, Trace(law="codegen")
    try:
        equations = newton_euler.equations(setup)
    finally:
        setup.trace = saved
    present = set().union(*[e.expr.free_symbols for e in equations]) if equations else set()
    reactions = [r for r in setup.reactions if r in present]
    absent = [r for r in setup.reactions if r not in present]
    choices = [c for c in setup.sign_choices if c.symbol in present]
    combos = list(itertools.product((1, -1), repeat=len(choices)))
    if not 0 <= regime < len(combos):
        raise CodegenError(f"regime {regime} does not exist: this mode has {len(combos)}.", where=system.name)
    signs = {c.symbol: s for c, s in zip(choices, combos[regime])}
    unknowns = [q.diff(t, 2) for q in red.independent] + reactions
    A, b = linear_form([e.expr.xreplace(signs) for e in equations], unknowns)
    keep = _determinacy(A, b, unknowns, [e.label for e in equations])
    A = A.extract(keep, list(range(len(unknowns))))
    b = -b.extract(keep, [0])
    layout = StateLayout.of(system)
    X, names = _unknown_symbols(red, [str(r) for r in reactions])
    rates = _rates(layout, red, dict(zip(red.independent, X)))
    n_acc = len(red.independent)
    outputs = list(X[n_acc:]) + [sp.Integer(0)] * len(absent)
    k = Kernel(layout, tuple(X), tuple(names) + tuple(str(r) for r in absent),
               A.applyfunc(layout.to_plain), tuple(layout.to_plain(e) for e in b), tuple(rates), tuple(outputs),
               tuple(names[n_acc:]) + tuple(str(r) for r in absent), label=system.name)
    check_free(k, [*k.A, *k.b, *rates])
    return k


# ---------------------------------------------------------------------------------------------------
# compiling and caching (rigidkin.numeric.compiled.cache: a private, checked cache)
def c_available() -> bool:
    """True when C code can be compiled and loaded here (a compiler and cffi)."""
    try:
        import cffi  # noqa: F401
    except ImportError:
        return False
    return compiler() is not None


def _build(source: str, cdef: str):
    """Compile our generated ``source`` (cached, checked) and load it with cffi; returns (ffi, lib)."""
    return build(source, cdef, CodegenError)


# ---------------------------------------------------------------------------------------------------
# the compiled model
class CompiledModel:
    """The functions of a kernel, compiled (``backend == "c"``) or in numpy (``"numpy"``).

    ``rhs(t, y, p)`` → dy/dt; ``outputs(t, y, p)`` → the named outputs; ``rhs_batch`` /
    ``outputs_batch`` over rows of arrays.  For the batch integrator, ``ffi``/``lib`` hold the C
    library (None with numpy).
    """

    def __init__(self, kernel: Kernel, backend: str = "auto"):
        if backend not in BACKENDS:
            raise CodegenError(f"unknown backend '{backend}'.", hint=f"Use one of: {', '.join(BACKENDS)}.")
        self.kernel = kernel
        self.ffi = self.lib = None
        if backend in ("auto", "c"):
            if c_available():
                self.ffi, self.lib = _build(c_source(kernel) + INTEGRATOR_C, _CDEF + INTEGRATOR_CDEF)
            elif backend == "c":
                raise CodegenError("no C compiler (or the cffi package) is available here.",
                                   hint="Install gcc and cffi, or use backend='numpy'.")
        self.backend = "c" if self.lib is not None else "numpy"
        if self.lib is None:
            self._np = _numpy_functions(kernel)

    @property
    def ny(self) -> int:
        return self.kernel.ny

    def _ptr(self, a: np.ndarray):
        return self.ffi.from_buffer("double[]", a)

    def rhs(self, t_: float, y, p) -> np.ndarray:
        y = np.ascontiguousarray(y, dtype=float)
        p = np.ascontiguousarray(p, dtype=float)
        if self.lib is None:
            return self._np.rhs(t_, y, p)
        dy = np.empty(self.ny)
        code = self.lib.rk_rhs(t_, self._ptr(y), self._ptr(p), self._ptr(dy))
        if code:
            dy[:] = np.nan
        return dy

    def outputs(self, t_: float, y, p) -> np.ndarray:
        y = np.ascontiguousarray(y, dtype=float)
        p = np.ascontiguousarray(p, dtype=float)
        if self.lib is None:
            return self._np.outputs(t_, y, p)
        o = np.empty(max(len(self.kernel.outputs), 1))
        if self.lib.rk_out(t_, self._ptr(y), self._ptr(p), self._ptr(o)):
            o[:] = np.nan
        return o[:len(self.kernel.outputs)]

    def rhs_batch(self, t_, Y, P) -> np.ndarray:
        """dy/dt for every row of Y (runs × 2n) with parameters P (runs × n_p)."""
        Y = np.ascontiguousarray(Y, dtype=float)
        n = Y.shape[0]
        P = np.ascontiguousarray(np.broadcast_to(P, (n, self.kernel.np_)), dtype=float)
        T = np.ascontiguousarray(np.broadcast_to(np.asarray(t_, dtype=float), (n,)))
        if self.lib is None:
            return np.array([self._np.rhs(T[i], Y[i], P[i]) for i in range(n)]).reshape(n, self.ny)
        dy = np.empty((n, self.ny))
        self.lib.rk_rhs_batch(n, self._ptr(T), self._ptr(Y), self._ptr(P), self._ptr(dy))
        return dy

    def outputs_batch(self, t_, Y, P) -> np.ndarray:
        Y = np.ascontiguousarray(Y, dtype=float)
        n = Y.shape[0]
        no = len(self.kernel.outputs)
        P = np.ascontiguousarray(np.broadcast_to(P, (n, self.kernel.np_)), dtype=float)
        T = np.ascontiguousarray(np.broadcast_to(np.asarray(t_, dtype=float), (n,)))
        if self.lib is None:
            return np.array([self._np.outputs(T[i], Y[i], P[i]) for i in range(n)]).reshape(n, no)
        o = np.empty((n, max(no, 1)))
        self.lib.rk_out_batch(n, self._ptr(T), self._ptr(Y), self._ptr(P), self._ptr(o))
        return o[:, :no]


class _NumpyFunctions:
    """The kernel through lambdify (with CSE); implicit kernels solved by numpy.linalg."""

    def __init__(self, kernel: Kernel):
        self.kernel = kernel
        args = kernel.args
        X = list(kernel.unknowns)
        if kernel.A is None:
            sub = dict(zip(X, kernel.b))
            self._rates = safe_lambdify(args, [sp.sympify(e).xreplace(sub) for e in kernel.rates])
            self._outs = safe_lambdify(args, [sp.sympify(e).xreplace(sub) for e in kernel.outputs])
        else:
            self._Ab = safe_lambdify(args, [list(kernel.A), list(kernel.b)])
            if kernel.M is not None:
                self._Mf = safe_lambdify(args, [list(kernel.M), list(kernel.f)])
            self._rates = safe_lambdify(args + X, list(kernel.rates))
            self._outs = safe_lambdify(args + X, list(kernel.outputs))

    def _x(self, t_, y, p):
        if self.kernel.A is None:
            return ()
        A, b = self._Ab(t_, *y, *p)
        n = len(self.kernel.unknowns)
        try:
            return tuple(np.linalg.solve(np.array(A, dtype=float).reshape(n, n), np.array(b, dtype=float)))
        except np.linalg.LinAlgError:
            return (np.nan,) * n

    def rhs(self, t_, y, p):
        with np.errstate(all="ignore"):
            if self.kernel.M is not None:
                M, f = self._Mf(t_, *y, *p)
                n = self.kernel.M.rows
                try:
                    acc = np.linalg.solve(np.array(M, dtype=float).reshape(n, n), np.array(f, dtype=float))
                except np.linalg.LinAlgError:
                    acc = np.full(n, np.nan)
                x = (*acc, *[np.nan] * (len(self.kernel.unknowns) - n))
            else:
                x = self._x(t_, y, p)
            return np.array(self._rates(t_, *y, *p, *x), dtype=float)

    def outputs(self, t_, y, p):
        with np.errstate(all="ignore"):
            return np.array(self._outs(t_, *y, *p, *self._x(t_, y, p)), dtype=float).reshape(-1)


def _numpy_functions(kernel: Kernel) -> _NumpyFunctions:
    if "numpy" not in kernel._cache:
        kernel._cache["numpy"] = _NumpyFunctions(kernel)
    return kernel._cache["numpy"]


def compile_kernel(kernel: Kernel, backend: str = "auto") -> CompiledModel:
    """The compiled model of a kernel (C when a compiler is present, numpy otherwise); cached."""
    key = ("compiled", backend)
    if key not in kernel._cache:
        kernel._cache[key] = CompiledModel(kernel, backend)
    return kernel._cache[key]


def compile_model(system, mode: Mapping | None = None, regime: int = 0, form: str = "auto",
                  backend: str = "auto") -> CompiledModel:
    """``compile_kernel(kernel(system, mode, regime, form), backend)``."""
    return compile_kernel(kernel(system, mode, regime, form), backend)


# ---------------------------------------------------------------------------------------------------
# what the simulator plugs in
class FastRHS:
    """rhs(t, y) → dy/dt for y = (q, q̇) with the parameters bound: a drop-in for scipy's solve_ivp.

    Raises :class:`rigidkin.numeric.rhs.SimulationError` on a non-finite rate (a singular
    configuration), like the lambdified RHS of :mod:`rigidkin.numeric.rhs`.
    """

    def __init__(self, model: CompiledModel, params: np.ndarray):
        self.model = model
        self.params = np.ascontiguousarray(params, dtype=float)
        self.calls = 0
        self.layout = model.kernel.layout
        self._ny = model.kernel.ny
        if model.lib is not None:
            self._p = model.ffi.from_buffer("double[]", self.params)
            self._f = model.lib.rk_rhs
            self._buf = model.ffi.from_buffer

    def __call__(self, t_: float, y) -> np.ndarray:
        self.calls += 1
        m = self.model
        if m.lib is not None:
            y = y if (type(y) is np.ndarray and y.dtype == np.float64 and y.flags.c_contiguous) \
                else np.ascontiguousarray(y, dtype=float)
            dy = np.empty(self._ny)
            code = self._f(t_, self._buf("double[]", y), self._p, self._buf("double[]", dy))
        else:
            dy = m.rhs(t_, y, self.params)
            code = not np.all(np.isfinite(dy))
        if code:
            state = ", ".join(f"{k} = {v:.6g}" for k, v in self.layout.as_dict(y).items())
            raise SimulationError(f"the equations of motion give a non-finite rate at t = {t_:.10g} ({state}).",
                                  where=m.kernel.label or "simulation",
                                  hint="The motion reached a singular configuration of the coordinates or of "
                                       "the mass matrix; check the model and the initial state.")
        return dy


def fast_rhs(system, mode: Mapping | None = None, regime: int = 0, params: Mapping | None = None,
             form: str = "auto", backend: str = "auto") -> FastRHS:
    """The compiled rhs(t, y) of ``system`` in ``mode``: same state layout and parameters as ``make_rhs``.

    >>> from rigidkin import examples
    >>> from rigidkin.numeric.compiled.codegen import fast_rhs
    >>> f = fast_rhs(examples.build("ladder"))
    >>> [round(float(v), 6) for v in f(0.0, [0.5, 1.0, 0.0, 0.0])]    # θ, x, θ̇, ẋ
    [0.0, 0.0, 3.527373, 6.191123]
    """
    model = compile_model(system, mode, regime, form, backend)
    return FastRHS(model, parameter_vector(system, model.kernel.layout, params))


def c_backend(args: Sequence[sp.Symbol], exprs: Sequence[sp.Expr]) -> Callable:
    """A backend for :func:`rigidkin.numeric.rhs.use_backend`: ``f(*args)`` → the values of ``exprs``, in C.

    ``args`` are the simulator's (t, q…, q̇…, parameters…); any symbols may be used.
    """
    args = list(args)
    exprs = [sp.sympify(e) for e in exprs]
    if not c_available() or len(args) < 2 or not exprs:
        return sp.lambdify(args, exprs, modules="numpy", cse=True)
    T = args[0]
    rest = args[1:]
    ys = [sp.Symbol(f"_a{i}", real=True) for i in range(len(rest))]
    sub = dict(zip(rest, ys))
    # a generic kernel: all arguments but t in y, no parameters, outputs = exprs
    fake = _GenericLayout(len(rest), T, ys)
    k = Kernel(fake, (), (), None, (), (), tuple(e.xreplace(sub) for e in exprs),
               tuple(f"o{i}" for i in range(len(exprs))), label="backend")
    model = compile_kernel(k, "c")
    n_out = len(exprs)
    ffi, lib = model.ffi, model.lib

    n_y = len(rest)

    def f(*values):
        if all(isinstance(v, (float, int, np.floating, np.integer)) for v in values):
            y = np.array(values[1:], dtype=float)
            o = np.empty(max(n_out, 1))
            lib.rk_out(float(values[0]), ffi.from_buffer("double[]", y), ffi.NULL, ffi.from_buffer("double[]", o))
            return o[:n_out]
        arrays = np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in values])   # vectorised call
        shape = arrays[0].shape
        T = np.ascontiguousarray(arrays[0].ravel())
        Y = np.ascontiguousarray(np.stack([a.ravel() for a in arrays[1:]], axis=1)) if n_y else np.zeros((T.size, 1))
        O = np.empty((T.size, max(n_out, 1)))
        P = np.zeros((T.size, 1))
        lib.rk_out_batch(T.size, ffi.from_buffer("double[]", T), ffi.from_buffer("double[]", Y),
                         ffi.from_buffer("double[]", P), ffi.from_buffer("double[]", O))
        return [O[:, i].reshape(shape) for i in range(n_out)]

    return f


class _GenericLayout(StateLayout):
    """A layout whose state is any list of plain symbols (``c_backend``)."""

    def __init__(self, size: int, time, symbols):
        object.__setattr__(self, "names", tuple(f"a{i}" for i in range(size)))
        object.__setattr__(self, "coordinates", ())
        object.__setattr__(self, "parameters", ())
        object.__setattr__(self, "parameter_symbols", ())
        object.__setattr__(self, "_time", time)
        object.__setattr__(self, "_symbols", list(symbols))

    @property
    def n(self) -> int:
        return len(self._symbols) // 2

    def arguments(self) -> list:
        return [self._time, *self._symbols]


def operation_count(kernel: Kernel) -> int:
    """Operations in the kernel's expressions after common-subexpression elimination (sympy.count_ops)."""
    exprs = list(kernel.rates) + list(kernel.outputs) + list(kernel.b) + list(kernel.f)
    for mat in (kernel.A, kernel.M):
        exprs += list(mat) if mat is not None else []
    subs, reduced = sp.cse(exprs, order="none")
    return int(sum(sp.count_ops(e) for _, e in subs) + sum(sp.count_ops(e) for e in reduced))


def warn_numpy_fallback(model: CompiledModel) -> None:
    if model.backend != "c":
        warnings.warn("no C compiler here: rigidkin evaluates the generated code with numpy (slower).",
                      RuntimeWarning, stacklevel=3)
