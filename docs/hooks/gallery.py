"""MkDocs hook: the gallery of the bundled examples, drawn at build time by rigidkin itself.

For every bundled example (``rigidkin.examples.names()``, what ``rigidkin list`` prints) the site gets a
page ``gallery/NAME.md``: the statement, the derivation as ``rigidkin solve`` prints it, the free-body
diagram (:func:`rigidkin.report.fbd.free_body_diagram`) and the simulation figure
(:func:`rigidkin.numeric.figure.plot_result` of ``T_END`` seconds from the example's own start), both as SVG,
and the problem file or Python model itself.  Nothing of it is committed: pages and figures exist only in
the built site.

Each example is drawn in a process of its own (``python docs/hooks/gallery.py NAME FOLDER``), a bounded time
each, two at a time; a failure is a warning, which ``mkdocs build --strict`` turns into a failed build.  The
drawings are kept in a cache folder keyed by a hash of the package's source, so ``mkdocs serve`` redraws them
only after the package changes.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SOURCE = ROOT / "src" / "rigidkin"
T_END = 3.0                 # seconds simulated: what `rigidkin report NAME --simulate 3` shows
POINTS = 400                # samples of the simulation figure
TIME_LIMIT = 300            # seconds for one example's drawings
WORKERS = max(1, min(2, os.cpu_count() or 1))
MAX_EVENTS = 20            # rows of a page's events table

log = logging.getLogger("mkdocs.plugins.gallery")


# --------------------------------------------------------------------------------------------------------------
# drawing one example (run in its own process)

def draw(name: str, folder: Path) -> dict:
    """Draw the example ``name`` into ``folder`` (fbd.svg, sim.svg) and return what its page shows."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rigidkin import examples
    from rigidkin.commands.common import load_system
    from rigidkin.numeric.figure import plot_result
    from rigidkin.numeric.simulate import simulate
    from rigidkin.report.fbd import free_body_diagram

    folder.mkdir(parents=True, exist_ok=True)
    system, spec = load_system(name)
    toml = examples.HERE / f"{name}.toml"
    source = toml if toml.exists() else examples.HERE / f"{name.replace('-', '_')}.py"
    meta = {"name": name, "title": system.title, "statement": getattr(spec, "statement", None)
            or getattr(system, "statement", "") or "", "form": source.suffix[1:], "file": source.name,
            "source": source.read_text(encoding="utf-8"), "derivation": None, "events": [], "notes": [],
            "figures": {}, "shows": ["free-body diagram", "simulation"]}
    module = None if toml.exists() else __import__(f"rigidkin.examples.{name.replace('-', '_')}", fromlist=["_"])
    if module is not None and getattr(module, "SYMBOLIC_SETUP", True) is False:
        meta["notes"].append(_projected(module, system, folder, meta))
        return meta
    solution = system.solve()
    meta["derivation"] = str(solution)
    fbd = free_body_diagram(solution)
    fbd.figure.savefig(folder / "fbd.svg")
    fbd.close()
    meta["figures"]["fbd.svg"] = "Free-body diagram at the start"
    result = simulate(system, T_END, n_points=POINTS)
    fig = plot_result(result, folder / "sim.svg")
    plt.close(fig)
    meta["figures"]["sim.svg"] = f"Simulated for {T_END:g} s from the example's own start"
    meta["events"] = [(float(e.t), e.name) for e in result.events]
    meta["status"] = f"{result.status}: {result.message}"
    return meta


def _projected(module, system, folder: Path, meta: dict) -> str:
    """A model too large for the closed-form derivation (the Whipple bicycle): its lean–steer eigenvalues
    against speed, from the projected equations, in place of the free-body diagram and the simulation."""
    import numpy as np
    from matplotlib.figure import Figure

    meta["shows"] = ["lean–steer eigenvalues"]
    model = module.projected(system)
    matrices = module.lean_steer_matrices(model)
    speeds = np.linspace(0.0, 10.0, 201)
    roots = np.array([np.sort_complex(module.eigenvalues(matrices, v)) for v in speeds])
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.subplots()
    for k in range(roots.shape[1]):
        ax.plot(speeds, roots[:, k].real, ".", ms=2.5, color="tab:blue", label="real part" if k == 0 else None)
        ax.plot(speeds, np.abs(roots[:, k].imag), ".", ms=2.5, color="tab:orange",
                label="|imaginary part|" if k == 0 else None)
    ax.axhline(0.0, color="0.3", lw=0.8)
    ax.set_ylim(-10, 10)
    ax.set_xlabel("forward speed v [m/s]")
    ax.set_ylabel("eigenvalue [1/s]")
    ax.set_title("Lean–steer eigenvalues of the linearised equations (upright, straight ahead)")
    ax.legend(loc="lower left")
    ax.grid(True, alpha=0.3)
    fig.savefig(folder / "sim.svg")
    meta["figures"]["sim.svg"] = ("Eigenvalues of the lean–steer motion against speed (stable where every real "
                                  "part is negative)")
    return (f"The closed-form derivation ({system.title}: five dependent rates through the front wheel's "
            "contact) does not finish in useful time, so this page shows no free-body diagram and no "
            "simulation; the equations of motion are projected numerically on the independent rates "
            f"(`rigidkin.examples.{module.__name__.rsplit('.', 1)[-1]}.projected()`) and linearised about "
            "upright straight running.")


# --------------------------------------------------------------------------------------------------------------
# the cache and the processes

def source_key() -> str:
    """A hash of everything the drawings depend on: the package's source, the drawing functions of this file and
    their settings, the libraries' versions (editing a page's layout here redraws nothing)."""
    import inspect
    from importlib.metadata import version

    h = hashlib.sha256()
    for p in sorted([*SOURCE.rglob("*.py"), *SOURCE.rglob("*.toml")]):
        h.update(str(p.relative_to(ROOT)).encode())
        h.update(p.read_bytes())
    h.update(f"{inspect.getsource(draw)}{inspect.getsource(_projected)}{T_END}/{POINTS}".encode())
    for lib in ("sympy", "numpy", "scipy", "matplotlib"):
        h.update(f"{lib}={version(lib)}".encode())
    return h.hexdigest()[:16]


def cache_folder() -> Path:
    return Path(tempfile.gettempdir()) / f"rigidkin-docs-gallery-{os.getuid() if hasattr(os, 'getuid') else 0}"


def prune(keep: Path, count: int = 3) -> None:
    """Remove the cache's older drawings (other versions of the package), keeping ``count`` folders."""
    import shutil

    if not keep.parent.is_dir():
        return
    others = sorted((p for p in keep.parent.iterdir() if p.is_dir() and p != keep), key=lambda p: p.stat().st_mtime)
    for old in others[: max(0, len(others) - (count - 1))]:
        shutil.rmtree(old, ignore_errors=True)


def _drawn(name: str, folder: Path) -> dict | None:
    meta = folder / "meta.json"
    if not meta.exists():
        return None
    data = json.loads(meta.read_text(encoding="utf-8"))
    return data if all((folder / f).exists() for f in data["figures"]) else None


def _draw_in_process(name: str, folder: Path) -> dict:
    cached = _drawn(name, folder)
    if cached is not None:
        return cached
    path = os.pathsep.join(filter(None, [str(ROOT / "src"), os.environ.get("PYTHONPATH")]))
    env = {**os.environ, "PYTHONPATH": path, "MPLBACKEND": "Agg"}
    try:
        run = subprocess.run([sys.executable, __file__, name, str(folder)], capture_output=True, text=True,
                             timeout=TIME_LIMIT, env=env, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return {"name": name, "error": f"drawing took more than {TIME_LIMIT} s"}
    if run.returncode != 0:
        return {"name": name, "error": (run.stderr.strip() or run.stdout.strip())[-2000:]}
    return _drawn(name, folder) or {"name": name, "error": "the drawing process wrote no meta.json"}


def draw_all(names: list[str], folder: Path) -> dict[str, dict]:
    """Draw every example (cached ones are read back), ``WORKERS`` processes at a time; the slow ones first."""
    order = sorted(names, key=lambda n: n != "bicycle")
    with ThreadPoolExecutor(WORKERS) as pool:
        found = dict(zip(order, pool.map(lambda n: _draw_in_process(n, folder / n), order)))
    return {n: found[n] for n in names}


# --------------------------------------------------------------------------------------------------------------
# the pages

def page(meta: dict) -> str:
    """The Markdown of one example's gallery page."""
    name = meta["name"]
    out = [f"# {meta['title']}", ""]
    if meta.get("statement"):
        out += [meta["statement"], ""]
    out += [f"Bundled example `{name}` (`{meta['file']}`). The same, as a report with the whole derivation and an "
            "animation:", "", "```console", f"$ rigidkin report {name} -o {name}.html --simulate {T_END:g}", "```",
            ""]
    for note in meta["notes"]:
        out += ["!!! note", "", f"    {note}", ""]
    if "fbd.svg" in meta["figures"]:
        out += ["## Free-body diagram", "", f"![Free-body diagram of {name}]({name}-fbd.svg)", "",
                f"*{meta['figures']['fbd.svg']}: applied loads in blue start at their point; reactions (the "
                "unknowns) in red end at theirs.*", ""]
    if meta.get("derivation"):
        out += ["## Equations of motion and reactions", "", "```text", meta["derivation"].rstrip(), "```", ""]
    if "sim.svg" in meta["figures"]:
        out += ["## Simulation" if meta.get("derivation") else "## Linearised motion", "",
                f"![Simulation of {name}]({name}-sim.svg)", "", f"*{meta['figures']['sim.svg']}.*", ""]
    if meta.get("events"):
        shown = meta["events"][:MAX_EVENTS]
        out += ["| event | t [s] |", "| --- | --- |"]
        out += [f"| {e.replace('|', '&#124;')} | {t:.6g} |" for t, e in shown]
        if len(meta["events"]) > MAX_EVENTS:
            out.append(f"| … and {len(meta['events']) - MAX_EVENTS} more | |")
        out.append("")
    if meta.get("status"):
        out += [f"Simulation {meta['status']}", ""]
    lang = "toml" if meta["form"] == "toml" else "python"
    out += [f'??? example "The {"problem file" if lang == "toml" else "Python model"} {meta["file"]}"', "",
            f"    ```{lang}"] + [f"    {line}".rstrip() for line in meta["source"].splitlines()] + ["    ```", ""]
    return "\n".join(out)


def index_table(drawn: dict[str, dict]) -> str:
    """The gallery's table of contents: every example with its title and what its page shows."""
    rows = ["| example | title | shows | |", "| --- | --- | --- | --- |"]
    for name, meta in drawn.items():
        shown = ", ".join(meta.get("shows", [])) or "(could not be drawn)"
        first = next(iter(meta.get("figures", {})), None)
        thumb = (f'[![{name}]({name}-{first.removesuffix(".svg")}.svg){{ width="150" loading="lazy" }}]({name}.md)'
                 if first else "")
        rows.append(f"| [`{name}`]({name}.md) | {meta.get('title', name)} | {shown} | {thumb} |")
    return "\n".join(rows)


# --------------------------------------------------------------------------------------------------------------
# MkDocs events

_DRAWN: dict[str, dict] = {}
MARK = "<!-- gallery: every example -->"


def on_files(files, config):
    from mkdocs.structure.files import File

    sys.path.insert(0, str(ROOT / "src"))
    from rigidkin import examples

    names = examples.names()
    folder = cache_folder() / source_key()
    cached = sum(_drawn(n, folder / n) is not None for n in names)
    start = time.perf_counter()
    _DRAWN.clear()
    _DRAWN.update(draw_all(names, folder))
    prune(folder)
    cpu = sum(m.get("cpu_seconds", 0.0) for m in _DRAWN.values())
    log.info("gallery: %d examples drawn in %.1f s (%d from the cache %s; %.0f s of processor time when drawn)",
             len(names), time.perf_counter() - start, cached, folder, cpu)
    for name, meta in _DRAWN.items():
        if "error" in meta:
            log.warning("gallery: example '%s' could not be drawn: %s", name, meta["error"])
            continue
        files.append(File.generated(config, f"gallery/{name}.md", content=page(meta)))
        for fig in meta["figures"]:
            stem = fig.removesuffix(".svg")
            files.append(File.generated(config, f"gallery/{name}-{stem}.svg", abs_src_path=str(folder / name / fig)))
    return files


def on_page_markdown(markdown, page, config, files):
    if page.file.src_uri == "gallery/index.md":
        if MARK not in markdown:
            log.warning("gallery: docs/gallery/index.md has lost its mark %s", MARK)
        return markdown.replace(MARK, index_table(_DRAWN))
    return markdown


def main(argv: list[str]) -> int:
    name, folder = argv
    meta = draw(name, Path(folder))
    meta["cpu_seconds"] = time.process_time()          # with the imports: what one example costs a build
    (Path(folder) / "meta.json").write_text(json.dumps(meta, ensure_ascii=False), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
