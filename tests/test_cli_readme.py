"""The README's quick start and its problem-file example work as written."""

import re
from pathlib import Path

from rigidkin.cli import main

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text()


def test_quick_start_solves_a_bundled_problem_file(capsys, monkeypatch):
    block = re.search(r"## Quick start.*?```bash\n(.*?)\n```", README, re.S).group(1)
    install, solve = block.split(" && ")
    assert install == "pip install ."
    argv = solve.split()
    assert argv[:2] == ["rigidkin", "solve"] and argv[2].endswith(".toml")
    monkeypatch.chdir(ROOT)
    assert main(argv[1:]) == 0
    out = capsys.readouterr().out
    assert "θ\u0308 = 3·g·sin(θ)/(2·l)" in out and "acos(2/3)" in out      # what the README says it prints


def test_problem_file_example(tmp_path, capsys):
    toml = re.search(r"```toml\n(.*?)\n```", README, re.S).group(1)
    f = tmp_path / "pendulum.toml"
    f.write_text(toml)
    assert main(["solve", str(f)]) == 0
    out = capsys.readouterr().out
    # energy from rest at theta = pi/2: (m l²/3) θ̇²/2 = m g (l/2) cos θ
    assert "θ\u0307² = 3·g·cos(θ)/l" in out
    assert "θ\u0308 = -3·g·sin(θ)/(2·l)" in out
    bad = f.read_text().replace('at = "G"', 'at = "Q"')
    f.write_text(bad)
    assert main(["validate", str(f)]) == 2
    err = capsys.readouterr().err
    quoted = re.search(r"\(`(pendulum\.toml, line \d+, [^`]*)`\)", README).group(1)   # the README's example error
    assert quoted in err
