"""The same problem gives the same output bytes in every run, under any hash seed.

Each example is solved by the command line in fresh interpreters with different PYTHONHASHSEED values
(the order of sets of symbols changes with it, and sympy's factoring draws random numbers), and the
JSON outputs, answers included, must be byte-for-byte equal.
"""

from __future__ import annotations

import os

import pytest
from helpers import rigidkin_process

SEEDS = ("0", "1", "12345")


def solve_json(name: str, seed: str) -> bytes:
    done = rigidkin_process("solve", name, "--format", "json", env={**os.environ, "PYTHONHASHSEED": seed},
                            text=False, timeout=300)
    assert done.returncode == 0, done.stderr.decode()
    return done.stdout


@pytest.mark.slow
@pytest.mark.parametrize("name", ["ladder", pytest.param("disk-in-track", marks=pytest.mark.slow),
                                  pytest.param("collar-rod", marks=pytest.mark.slow)])
def test_same_bytes_under_every_hash_seed(name):
    outputs = [solve_json(name, seed) for seed in SEEDS]
    assert len(outputs[0]) > 100
    assert outputs[1] == outputs[0] and outputs[2] == outputs[0]
