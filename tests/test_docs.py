"""Every code block in ``docs/`` runs.

Per document, in order, in a fresh working folder: a fenced block marked by the comment
``<!-- file: NAME -->`` on the line before it is written to NAME; ``python`` blocks run one after
another in one namespace (a later block uses what an earlier one defined); ``console`` blocks run
each ``$ rigidkin ...`` line through ``rigidkin.cli.main`` and expect exit status 0, and every
output line shown under a command must appear in what it printed (``...`` skips lines).
"""

from __future__ import annotations

import re
import runpy
import shlex
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
FENCE = re.compile(r"(?:<!--\s*file:\s*(?P<file>[\w.\-/]+)\s*-->\n)?```(?P<lang>[\w+-]*)\n(?P<body>.*?)```", re.S)
# pages whose code takes over ~10 s on 2 shared cores: run by CI's slow pass (pytest -m slow)
SLOW = {"tutorial.md", "simulation.md", "reports.md", "file-format.md", "bodies.md", "answers.md", "gallery/index.md",
        "constraints.md", "grading.md"}


def blocks(path: Path) -> list[tuple[str, str, str | None]]:
    return [(m["lang"], m["body"], m["file"]) for m in FENCE.finditer(path.read_text(encoding="utf-8"))]


def documents() -> list:
    out = []
    for p in sorted(DOCS.rglob("*.md")):
        marks = [pytest.mark.slow] if p.name in SLOW or p.relative_to(DOCS).as_posix() in SLOW else []
        out.append(pytest.param(p, id=str(p.relative_to(DOCS)), marks=marks))
    return out


def _run_console(body: str, capsys) -> None:
    from rigidkin.cli import main

    lines = body.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.startswith("$ "):
            i += 1
            continue
        argv = shlex.split(line[2:], comments=True)
        assert argv[0] == "rigidkin", f"only rigidkin commands are run from the docs: {line}"
        expected = []
        i += 1
        while i < len(lines) and not lines[i].startswith("$ "):
            if lines[i].strip() and lines[i].strip() != "...":
                expected.append(lines[i].strip())
            i += 1
        capsys.readouterr()
        code = main(argv[1:])
        out = capsys.readouterr()
        assert code == 0, f"{line} exited {code}: {out.err}"
        printed = " ".join(out.out.split())
        for e in expected:
            assert " ".join(e.split()) in printed, f"{line}: the docs show '{e}', which it did not print"


@pytest.mark.parametrize("path", documents())
def test_doc_code_runs(path, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    found = blocks(path)
    namespace: dict = {"__name__": "__docs__"}
    for n, (lang, body, fname) in enumerate(found):
        if fname:
            target = tmp_path / fname
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(body, encoding="utf-8")
        if lang == "python" and not fname:
            script = tmp_path / f"_block{n}.py"
            script.write_text(body, encoding="utf-8")
            namespace = runpy.run_path(str(script), init_globals=namespace, run_name="__docs__")
        elif lang == "console":
            _run_console(body, capsys)


def test_docs_have_code():
    """The tutorial and every guide show code (a document without a runnable block is not tested)."""
    for p in [DOCS / "tutorial.md", *sorted((DOCS / "guide").glob("*.md"))]:
        langs = {lang for lang, _, _ in blocks(p)}
        assert langs & {"python", "console"}, p.name


def test_file_format_reference_names_every_field():
    """Each table of the problem-file schema has every field named in the reference."""
    from rigidkin.io import schema

    text = (DOCS / "file-format.md").read_text(encoding="utf-8")
    models = [schema.ProblemFile, schema.ParameterSpec, schema.CoordinateSpec, schema.FrameSpec, schema.PointSpec,
              schema.LineSpec, schema.CircleSpec, schema.PinSpec, schema.ContactSpec, schema.CollarSpec,
              *schema.LoadSpec.__origin__.__args__, *schema.QUESTION_MODELS, schema.PhaseSpec, schema.AskSpec]
    missing = []
    for model in models:
        for name, f in model.model_fields.items():
            key = f.alias or name
            if f"`{key}`" not in text:
                missing.append(f"{model.__name__}.{key}")
    assert not missing, f"fields not in docs/file-format.md: {missing}"
    for shape in schema.BODY_MODELS:
        assert f"`{shape}`" in text, shape
