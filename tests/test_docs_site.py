"""The documentation site (``mkdocs.yml``): its navigation lists every page in ``docs/`` and every bundled example
has a gallery page, the gallery hook draws an example, and (slow) the site builds with ``--strict``."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

from rigidkin import examples

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
HOOKS = DOCS / "hooks"


def _nav_pages(entries) -> list[str]:
    out = []
    for e in entries:
        if isinstance(e, str):
            out.append(e)
        elif isinstance(e, dict):
            for v in e.values():
                out.extend(_nav_pages(v) if isinstance(v, list) else [v])
    return out


def _config() -> dict:
    return yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))


def _hook(name: str):
    spec = importlib.util.spec_from_file_location(f"_docs_{name}", HOOKS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_nav_lists_every_page():
    """Every Markdown page under docs/ is in the navigation, and every page the navigation names exists (or is
    a gallery page the hook draws)."""
    nav = _nav_pages(_config()["nav"])
    assert len(nav) == len(set(nav)), f"pages listed twice: {sorted(p for p in nav if nav.count(p) > 1)}"
    pages = {p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md") if HOOKS not in p.parents}
    assert pages - set(nav) == set(), f"pages in docs/ missing from mkdocs.yml's nav: {sorted(pages - set(nav))}"
    generated = {f"gallery/{n}.md" for n in examples.names()}
    assert set(nav) - pages - generated == set(), "nav entries with no page"


def test_every_example_has_a_gallery_entry():
    """A new bundled example (``rigidkin list``) needs its line in the Gallery section of mkdocs.yml."""
    nav = _nav_pages(_config()["nav"])
    listed = {p.removeprefix("gallery/").removesuffix(".md") for p in nav
              if p.startswith("gallery/") and p != "gallery/index.md"}
    missing = sorted(set(examples.names()) - listed)
    assert not missing, f"bundled examples with no gallery entry in mkdocs.yml: {missing}"
    assert listed <= set(examples.names()), f"gallery entries of no example: {sorted(listed - set(examples.names()))}"


def test_gallery_draws_an_example(tmp_path):
    """The hook draws an example's free-body diagram and simulation as SVG and its page shows them."""
    gallery = _hook("gallery")
    meta = gallery.draw("rod-impulse", tmp_path)
    for fig in ("fbd.svg", "sim.svg"):
        root = ET.parse(tmp_path / fig).getroot()
        assert root.tag.endswith("svg"), fig
        assert (tmp_path / fig).stat().st_size > 5000, fig
    assert meta["title"] == examples.build("rod-impulse").title
    assert "Equations of motion" in meta["derivation"]
    md = gallery.page(meta)
    assert "![Free-body diagram of rod-impulse](rod-impulse-fbd.svg)" in md
    assert "![Simulation of rod-impulse](rod-impulse-sim.svg)" in md
    assert "rigidkin report rod-impulse -o rod-impulse.html --simulate 3" in md
    assert "[`rod-impulse`](rod-impulse.md)" in gallery.index_table({"rod-impulse": meta})


def test_docstrings_read_as_markdown():
    """Sphinx roles become code and a doctest session a fenced block (its brackets are not links)."""
    md = _hook("griffe_docstrings").markdown
    assert md("See :func:`rigidkin.report.fbd.free_body_diagram`.") == "See `rigidkin.report.fbd.free_body_diagram`."
    assert md(":class:`~rigidkin.derive.solution.Solution`") == "`Solution`"
    text = "Example:\n\n>>> xs = [1, 2, 3]\n>>> xs[:2]\n[1, 2]\n\nAfter."
    assert md(text) == "Example:\n\n```pycon\n>>> xs = [1, 2, 3]\n>>> xs[:2]\n[1, 2]\n```\n\nAfter."


@pytest.mark.slow
def test_site_builds_strictly(tmp_path):
    """``mkdocs build --strict``: no warning (broken link, page left out of the nav, docstring mkdocstrings cannot
    read, example that cannot be drawn), and the gallery's figures in the built site."""
    if shutil.which("mkdocs") is None and importlib.util.find_spec("mkdocs") is None:
        pytest.skip("mkdocs is not installed (pip install -e '.[docs]')")
    site = tmp_path / "site"
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    run = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-d", str(site)], cwd=ROOT,
                         capture_output=True, text=True, timeout=1800, env=env)
    assert run.returncode == 0, run.stderr[-4000:]
    for name in examples.names():
        assert (site / "gallery" / name / "index.html").exists(), name
        assert (site / "gallery" / f"{name}-sim.svg").exists(), name
    assert (site / "gallery" / "ladder-fbd.svg").exists()
    api = (site / "api" / "model" / "index.html").read_text(encoding="utf-8")
    assert "rigidkin.model.system.System.solve" in api
    for inherited in ("pin", "contact", "rope", "gravity", "spring"):       # from the System's mixins
        assert f'id="rigidkin.model.system.System.{inherited}"' in api, inherited


def test_readme_says_how_to_serve_the_site():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "pip install -e '.[docs]' && mkdocs serve" in readme
    import tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]
    named = {d.split(">")[0].split("~")[0] for d in extras["docs"]}
    assert {"mkdocs", "mkdocs-material", "mkdocstrings[python]"} <= named


def _documented_classes() -> list[str]:
    """The classes a ``::: path`` directive of docs/api puts on a page."""
    import importlib
    import inspect

    out = []
    for page in sorted((DOCS / "api").glob("*.md")):
        for line in page.read_text(encoding="utf-8").splitlines():
            if line.startswith("::: "):
                module, _, name = line[4:].strip().rpartition(".")
                try:
                    obj = getattr(importlib.import_module(module), name)
                except (ImportError, AttributeError):
                    continue
                if inspect.isclass(obj):
                    out.append(line[4:].strip())
    return out


def test_api_reference_shows_inherited_methods():
    """Every public method of every documented class is on its page, the ones it inherits from rigidkin's
    mixins included (System's pin, contact, rope, gravity, spring ...): the handler is told to show inherited
    members, no page turns that off, and griffe (what mkdocstrings reads) finds every method Python's own
    method resolution finds."""
    griffe = pytest.importorskip("griffe")
    import importlib
    import inspect

    options = _config()["plugins"][1]["mkdocstrings"]["handlers"]["python"]["options"]
    assert options.get("inherited_members") is True
    for page in (DOCS / "api").glob("*.md"):
        assert "inherited_members: false" not in page.read_text(encoding="utf-8"), page.name
    loader = griffe.GriffeLoader(search_paths=[str(ROOT / "src")])
    package = loader.load("rigidkin")
    loader.resolve_aliases(implicit=False, external=False)
    classes = _documented_classes()
    assert "rigidkin.model.system.System" in classes
    for path in classes:
        module, _, name = path.rpartition(".")
        cls = getattr(importlib.import_module(module), name)
        ours = {n for k in cls.__mro__ if k.__module__.startswith("rigidkin") for n, v in vars(k).items()
                if not n.startswith("_") and (inspect.isfunction(v) or isinstance(v, property | classmethod))}
        shown = {n for n in package[path.removeprefix("rigidkin.")].all_members if not n.startswith("_")}
        assert ours <= shown, f"{path}: methods missing from its API page: {sorted(ours - shown)}"
    system = set(package["model.system.System"].all_members)
    assert {"pin", "contact", "rope", "gravity", "spring", "solve"} <= system
