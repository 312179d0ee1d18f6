"""3D drawing and animation: rims where the kinematics put them, animations of simulated and sampled motion."""

from __future__ import annotations

import numpy as np
import pytest

import rigidkin as rk
from rigidkin.examples import bicycle, rolling_disk
from rigidkin.report.animate3d import Scene3D, animate3d


def test_leaning_coin_rim_touches_the_ground():
    s = rolling_disk.build()
    scene = Scene3D(s)
    a = s.parameter_values()[s.parameters["a"]]
    th = 0.4
    q = {c: 0.0 for c in s.coordinates}
    psi, theta, phi, x, y, z = s.coordinates
    q.update({theta: th, z: a * np.cos(th), psi: 0.7, x: 0.1, y: -0.2})
    rim = scene.rim("disk", q)
    C = scene.point("C", q)
    axis = scene.axes("disk", q)[:, 1]
    assert np.allclose(np.linalg.norm(rim - C, axis=1), a, rtol=1e-12)
    assert np.allclose((rim - C) @ axis, 0, atol=1e-15)
    assert rim[:, 2].min() == pytest.approx(0.0, abs=a * 2e-3)        # sampled rim: within a chord's sag
    assert rim[:, 2].min() >= -1e-15


def test_bicycle_wheels_stand_on_the_ground_upright():
    s = bicycle.build()
    scene = Scene3D(s)
    q = [0.0] * len(s.coordinates)
    for wheel, r in (("rear_wheel", 0.3), ("front_wheel", 0.35)):
        rim = scene.rim(wheel, q, n=400)
        assert rim[:, 2].max() == pytest.approx(0.0, abs=1e-4)        # Ez points down: the lowest point at z = 0
        assert rim[:, 2].min() == pytest.approx(-2 * r, abs=1e-4)
    assert scene.point("C_F", q)[0] == pytest.approx(1.02, abs=1e-12)  # the wheelbase w
    assert len(scene.segments(q)) > 4


@pytest.mark.slow
def test_animation_of_sampled_and_simulated_motion():
    # sampled: the bicycle running straight at 4 m/s
    s = bicycle.build()
    ts = np.linspace(0, 0.5, 11)
    names = [c.func.__name__ for c in s.coordinates]
    states = np.zeros((len(ts), len(names)))
    states[:, names.index("x")] = 4 * ts
    states[:, names.index("theta_R")] = -4 * ts / 0.3
    states[:, names.index("theta_F")] = -4 * ts / 0.35
    anim = animate3d(s, times=ts, states=states, frames=6, z_down=True, dpi=30, size=3)
    try:
        assert len(anim.times) == 6
        assert anim.gif_bytes()[:4] == b"GIF8"
    finally:
        anim.close()
    with pytest.raises(rk.InputError, match="one row per time"):
        animate3d(s, times=ts, states=states[:, :3])
    # simulated: a rotor on a hinge about Ex, through rigidkin's simulate and its result object
    from rigidkin.numeric.simulate import simulate

    r = rk.System("rotor")
    m, a = r.parameter("m", "kg", value=1.0), r.parameter("a", "m", value=0.2)
    ph = r.coordinate("phi", "rotor angle about Ex", rate=3.0)
    R = r.frame("R", angle=ph, axis="x")
    rotor = r.body("rotor", rk.shapes.Disk(m, a, axis="x"), frame=R, at=r.origin)
    r.pin("hub", r.origin, rotor, axis="R.x")
    res = simulate(r, 1.0)
    anim = animate3d(r, res, frames=5, dpi=30, size=3)
    try:
        assert len(anim.times) == 5 and anim.times[-1] == pytest.approx(1.0)
        assert anim.gif_bytes()[:4] == b"GIF8"
    finally:
        anim.close()
