"""The package tree is the layer diagram, and the imports keep it (docs/architecture.md).

The import graph of ``src/rigidkin`` is read from the source (every ``import``, those inside functions
included) and must be one-way:

* no import circle, once the listed doors are set aside;
* no import from a lower layer to a higher one except through a door listed in :data:`DOORS`;
* an import inside a function only where it is allowed (:func:`_inner_allowed`): a door, or an import
  that keeps a heavy third-party library (:data:`HEAVY`: sympy, numpy, matplotlib, dask, ...) out of the
  importing module's start-up — the imported module loads one that the importer does not (so
  ``rigidkin --help`` imports no sympy and a repeated sweep no sympy).  Heavy libraries themselves may be
  imported inside functions anywhere; this test reads rigidkin's own imports;
* no module over 500 lines.
"""

from __future__ import annotations

import ast
import collections
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1] / "src" / "rigidkin"
MAX_LINES = 500

#: The layers from the bottom up; a module belongs to the first layer one of whose prefixes it starts with.
LAYERS = [
    ("base", ["rigidkin.base"]),
    ("model", ["rigidkin.model"]),
    ("derive", ["rigidkin.derive"]),
    ("numeric", ["rigidkin.numeric"]),
    ("analysis", ["rigidkin.analysis"]),
    ("report", ["rigidkin.report"]),
    ("facade", ["rigidkin"]),                 # the package root: rigidkin/__init__.py, lazy public names
    ("examples", ["rigidkin.examples"]),
    ("io", ["rigidkin.io"]),
    ("grading", ["rigidkin.grading"]),
    ("commands", ["rigidkin.commands"]),
    ("cli", ["rigidkin.cli", "rigidkin.__main__"]),
]

#: The only imports that run up a layer (or close a circle inside one): importer, imported, why.  Each is
#: written inside the one function that needs it.
DOORS = [
    ("rigidkin.model.system", "rigidkin.derive.laws",
     "System.solve derives the equations of motion: the description asks the laws for them"),
    ("rigidkin.derive.solution", "rigidkin.derive.laws.crosscheck",
     "Solution.check compares the solution with every other law (the laws build Solutions)"),
    ("rigidkin.derive.solution", "rigidkin.derive.laws.consistency",
     "Solution.warnings checks dE/dt = ΣP_nc on the solution (the laws build Solutions)"),
    ("rigidkin.derive.to_sympy", "rigidkin.derive.laws.mechanics_model",
     "Solution.to_sympy_system builds sympy's System from the bodies and loads of the Kane cross-check"),
    ("rigidkin.base.display", "rigidkin.report.views",
     "the display methods of System, Solution and SimulationResult (str, HTML, LaTeX) are rendered by "
     "report/; every one goes through base.display"),
]

#: Third-party libraries slow to import: kept out of start-up by importing them (or a rigidkin module that
#: loads them) inside the function that needs them.
HEAVY = {"sympy", "numpy", "scipy", "matplotlib", "dask", "distributed", "pint", "pyarrow", "cffi", "cloudpickle",
         "pydantic", "rich", "IPython", "ipywidgets", "mpmath", "jsonschema", "PIL"}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {_module_name(p): p for p in sorted(ROOT.rglob("*.py"))}


def _resolve(module: str, node: ast.ImportFrom) -> str | None:
    if not node.level:
        return node.module
    base = module.split(".")
    if MODULES[module].name != "__init__.py":
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _known(name: str) -> str:
    while name not in MODULES and "." in name:
        name = name.rsplit(".", 1)[0]
    return name


class Import(collections.namedtuple("Import", "target line inner leaf typing")):
    """One module an import statement runs: ``target`` (the imported module, or a package above it that
    runs first), ``leaf`` (the module the statement names), ``typing``: under ``if TYPE_CHECKING`` (for
    type checkers only: it never runs, so it may name anything below)."""


def _imports(module: str):
    """(imported module, line, inside a function) for every rigidkin import of ``module``; the heavy
    libraries it imports at load time go to :data:`LOADS_HEAVY`."""
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    found = []
    heavy = LOADS_HEAVY.setdefault(module, set())

    def visit(node, inner, typing_only):
        for child in ast.iter_child_nodes(node):
            deeper = inner or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            for_types = typing_only or (isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test))
            names = []
            if isinstance(child, ast.Import):
                names = [a.name for a in child.names]
            elif isinstance(child, ast.ImportFrom):
                base = _resolve(module, child)
                if base:
                    names = [f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base for a in child.names]
            for name in names:
                if name.split(".")[0] in HEAVY and not inner and not typing_only:
                    heavy.add(name.split(".")[0])
                if name.split(".")[0] == "rigidkin" and _known(name) != module:
                    # an import for type checkers only runs at no time: it counts as one inside a function;
                    # importing a.b.c runs the packages a and a.b first: they are imported too
                    target = _known(name).split(".")
                    for i in range(2, len(target) + 1):
                        if ".".join(target[:i]) != module and not module.startswith(".".join(target[:i]) + "."):
                            found.append(Import(".".join(target[:i]), child.lineno, inner or typing_only,
                                                _known(name), typing_only))
            visit(child, deeper, for_types)

    visit(tree, False, False)
    return found


LOADS_HEAVY: dict[str, set[str]] = {}
GRAPH = {m: _imports(m) for m in MODULES}


def _heavy_closure() -> dict[str, frozenset[str]]:
    """The heavy libraries each module loads at import, through its load-time rigidkin imports too (a
    package's ``__init__`` included)."""
    out = {}

    def visit(m, seen):
        if m in out:
            return out[m]
        if m in seen:
            return frozenset(LOADS_HEAVY[m])
        seen = seen | {m}
        acc = set(LOADS_HEAVY[m])
        parts = m.split(".")
        for i in range(1, len(parts)):
            parent = ".".join(parts[:i])
            if parent in MODULES:
                acc |= visit(parent, seen)
        for t, _, inner, _, _ in GRAPH[m]:
            if not inner:
                acc |= visit(t, seen)
        out[m] = frozenset(acc)
        return out[m]

    for m in MODULES:
        visit(m, frozenset())
    return out


HEAVY_AT_LOAD = _heavy_closure()
#: a door's import runs the packages above the imported module too (importing a.b.c runs a and a.b)
DOOR_EDGES = {(a, ".".join(b.split(".")[:i])) for a, b, _ in DOORS for i in range(2, b.count(".") + 2)}


def layer(module: str) -> int:
    best = None
    for i, (_, prefixes) in enumerate(LAYERS):
        for p in prefixes:
            if (module == p or module.startswith(p + ".")) and (best is None or len(p) > best[1]):
                best = (i, len(p))
    return best[0]


def _inner_allowed(importer: str, imported: str) -> bool:
    """A door, or an import that keeps a heavy library out of the importer's start-up."""
    return (importer, imported) in DOOR_EDGES or bool(HEAVY_AT_LOAD[imported] - HEAVY_AT_LOAD[importer])


def test_every_module_has_a_layer():
    assert all(layer(m) is not None for m in MODULES)


def test_doors_are_real_imports():
    """A listed door is an import that exists (a stale list hides nothing)."""
    for a, b, _ in DOORS:
        assert any(i.target == b for i in GRAPH.get(a, [])), f"door {a} -> {b} is not imported"


def test_no_upward_import():
    upward = [f"{m}:{line} imports {t} ({LAYERS[layer(m)][0]} -> {LAYERS[layer(t)][0]})"
              for m, edges in GRAPH.items() for t, line, _, _, _ in edges
              if layer(t) > layer(m) and (m, t) not in DOOR_EDGES]
    assert not upward, "imports up a layer:\n" + "\n".join(sorted(upward))


def test_imports_inside_functions_only_where_allowed():
    inner = sorted({f"{m}:{i.line} imports {i.leaf} inside a function (it loads nothing heavy that {m} does not)"
                    for m, edges in GRAPH.items() for i in edges
                    if i.inner and not i.typing and not _inner_allowed(m, i.leaf)})
    assert not inner, "imports inside functions:\n" + "\n".join(sorted(inner))


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            strong(v)
    return out


def test_no_import_circle():
    edges = collections.defaultdict(set)
    for m, found in GRAPH.items():
        edges[m] |= {i.target for i in found if (m, i.target) not in DOOR_EDGES}
    circles = _cycles(edges)
    assert not circles, "import circles:\n" + "\n".join(" ⇄ ".join(c) for c in circles)


@pytest.mark.parametrize("module", sorted(MODULES))
def test_module_size(module):
    lines = MODULES[module].read_text(encoding="utf-8").count("\n")
    assert lines <= MAX_LINES, f"{module} has {lines} lines (at most {MAX_LINES}: split it by concept)"


def test_package_root_is_the_facade():
    """Only the public facade, the command line and ``__main__`` lie at the package root."""
    loose = sorted(p.name for p in ROOT.glob("*.py"))
    assert loose == ["__init__.py", "__main__.py", "cli.py"]


def test_old_import_paths_give_the_moved_modules():
    import importlib

    import rigidkin
    from rigidkin.base import errors

    assert importlib.import_module("rigidkin.errors") is errors
    for old, new in rigidkin._MOVED.items():
        if old.startswith(("numeric.", "derivation_cache")) or old in ("laws",):
            continue                          # heavy; the mechanism is the same
        assert importlib.import_module(f"rigidkin.{old}") is importlib.import_module(f"rigidkin.{new}")
    from rigidkin.numeric import codegen
    from rigidkin.numeric.compiled import codegen as moved

    assert codegen is moved
    assert importlib.import_module("rigidkin.laws.energy").__name__ == "rigidkin.derive.laws.energy"


def test_the_route_answers_at_its_old_module_path():
    """``rigidkin.numeric.large`` (once the route's module, now the package of large systems)."""
    from rigidkin.numeric.large import SYMBOLIC_LIMIT, numeric_route
    from rigidkin.numeric.large.route import SYMBOLIC_LIMIT as limit

    assert SYMBOLIC_LIMIT == limit == 12 and callable(numeric_route)


def test_moved_modules_answer_as_attributes_of_the_package():
    """``rk.units`` (an attribute, not an import) gives the moved module too."""
    import rigidkin as rk
    from rigidkin.base import units

    assert rk.units is units and rk.units.TIME is units.TIME
