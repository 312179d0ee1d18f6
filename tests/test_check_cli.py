"""``rigidkin check``: every bundled example agrees by every law; a wrong --expect exits 1 with the difference."""

import contextlib
import io
import json

import pytest

from rigidkin.cli import main
from rigidkin.examples import names

# the 3D and multi-contact examples take 10 to 70 s each: run by CI's slow pass (pytest -m slow)
SLOW = {"chain", "rolling-disk", "torque-free", "gyroscope", "heavy-top", "collar-rod", "slip-to-roll", "collar-force",
        "disk-in-track", "sphere-on-sphere", "boulder-push", "disk-spring-incline"}


def run(argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(argv)
    return rc, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in names()])
def test_every_bundled_example(name):
    rc, out, err = run(["check", name])
    if name == "bicycle":
        # its closed-form solve is refused by design (five dependent rates): one paragraph, exit 2
        assert rc == 2 and "projected" in err and "Traceback" not in err
        return
    assert rc == 0, out + err
    assert "All agree." in out and "disagrees" not in out
    assert "agrees" in out            # at least one other law was compared


def test_expected_equation_right_and_wrong():
    card = "3/2*m*r**2*ddot(theta) + K*r**2*theta = m*g*r*sin(beta)"
    rc, out, _ = run(["check", "disk-spring-incline", "--laws", "kane", "--expect", card])
    assert rc == 0 and "equivalent to the derived equation of motion" in out
    wrong = "3/2*m*r**2*ddot(theta) + K*r*theta = m*g*r*sin(beta)"
    rc, out, _ = run(["check", "disk-spring-incline", "--laws", "kane", "--expect", wrong])
    assert rc == 1
    assert "NOT equivalent" in out
    assert "the term K·r·θ differs: the derived equation has K·r²·θ" in out
    assert "dimensionally inconsistent" in out and "M·L·T^-2" in out
    # an expression meaning = 0, dimensionally fine but with the wrong inertia
    rc, out, _ = run(["check", "disk-spring-incline", "--laws", "kane", "--expect",
                      "m*r**2*ddot(theta) + K*r**2*theta - m*g*r*sin(beta)"])
    assert rc == 1 and "m·r²·θ̈ differs" in out and "dimensions: consistent" in out


def test_json_and_errors():
    rc, out, _ = run(["check", "rod-impulse", "--format", "json", "--expect", "ddot(theta) = -12*K*theta/(m*l**2)"])
    data = json.loads(out)
    assert rc == 0 and data["ok"] is True
    assert {v["law"] for v in data["verdicts"]} >= {"about-point:O", "work-energy", "lagrange", "kane"}
    assert data["expected"][0]["equivalent"] is True
    rc, _, err = run(["check", "rod-impulse", "--expect", "__import__('os').system('true')"])
    assert rc == 2 and "not allowed" in err
    rc, _, err = run(["check", "rod-impulse", "--laws", "about-point"])
    assert rc == 2 and "needs the point" in err
    rc, _, err = run(["check", "rod-impulse", "--expect", "ddot(theta) = undeclared"])
    assert rc == 2 and "undeclared" in err
