"""Algebra helpers: readable simplification keeps values; time limits nest."""

import time

import pytest
import sympy as sp

from rigidkin.base import algebra
from rigidkin.base.algebra import readable, time_limit, trig_reduce


class Outer(Exception):
    pass


def test_inner_limit_fires_and_outer_is_restored():
    with pytest.raises(Outer), time_limit(0.6, Outer):
        with pytest.raises(TimeoutError), time_limit(0.1):
            time.sleep(0.5)
        time.sleep(1.0)           # the outer limit, restored less the time spent, still fires


def test_outer_limit_that_comes_first_is_left_to_fire():
    # a longer inner limit must not cancel the outer one
    with pytest.raises(Outer), time_limit(0.2, Outer), time_limit(5.0):
        time.sleep(1.0)


def test_a_swallowed_limit_fires_again():
    """Python ignores an exception raised in a gc callback or a __del__; the limit fires again 0.1 s later."""
    swallowed = []
    t0 = time.monotonic()
    with pytest.raises(TimeoutError), time_limit(0.2):
        try:
            time.sleep(2.0)
        except TimeoutError:
            swallowed.append(time.monotonic() - t0)       # ignored, as in a gc callback
        time.sleep(2.0)
    assert len(swallowed) == 1 and 0.15 < swallowed[0] < 0.6 and time.monotonic() - t0 < 1.0
    time.sleep(0.3)                                        # and nothing fires once the block is left


def test_trig_reduce_and_readable_keep_the_value():
    th, ph, m, g = sp.symbols("theta phi m g", real=True)
    e = (m * g * sp.sin(th) ** 2 + m * g * sp.cos(th) ** 2) / (sp.cos(ph) ** 2 + sp.sin(ph) ** 2) \
        + sp.sqrt(4 - m**2) / sp.sqrt(1 - m**2 / 4)
    r = trig_reduce(e)
    assert sp.simplify(r - (m * g + 2)) == 0
    assert algebra.is_zero(readable(e) - e)
