"""The rigidkin side of the new Siconos side-by-side cases (benchmarks/contacts_vs_siconos.py), against
references of their own: a rocking block with rough corners (Housner's ω⁺/ω⁻ = 1 − (3/2) sin²α, the impact
times from the one-degree-of-freedom equation about the pivot corner integrated by scipy, ω⁻ from energy,
the new corner's impulse by impulse–momentum by hand) and a level rod bouncing on two supports at unequal
distances, smooth and rough (impact times and speeds of a ball dropped h, the lever rule P_A/P_B = b/a,
P_A + P_B = m Δẏ).  Siconos itself is never needed here."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rigidkin.numeric import simulate

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from contacts_vs_siconos import ROCK, TWO, rocking_system, two_supports_system  # noqa: E402


def pivot_impacts(p, n):
    """(t, ω⁻) of the first n impacts: θ̈ = −p² sgn θ sin(α − |θ|) about the corner on the floor
    (p² = m g R / I_O = 3g/(4R)), ω multiplied by Housner's ratio whenever θ reaches 0."""
    R, alpha = math.hypot(p["b"], p["h"]), math.atan2(p["b"], p["h"])
    p2, ratio = 3 * p["g"] / (4 * R), 1 - 1.5 * math.sin(alpha) ** 2

    def rhs(_t, s):
        return [s[1], -p2 * math.copysign(1.0, s[0]) * math.sin(alpha - abs(s[0]))]

    def level(_t, s):
        return s[0]

    level.terminal = True
    t, state, out = 0.0, [p["tilt"], 0.0], []
    for _ in range(n):
        # leave θ = 0 by a hair on the new corner's side, then run to the next θ = 0
        sol = solve_ivp(rhs, (t, t + 5.0), state, events=level, rtol=1e-12, atol=1e-14, method="DOP853")
        t, w = float(sol.t_events[0][0]), float(sol.y_events[0][0][1])
        out.append((t, w))
        w1 = ratio * w
        state = [math.copysign(1e-300, w1), w1]
    return out


@pytest.mark.slow                   # ≈ 9 CPU s, 20–35 s on the shared machine (the derivation); CI's slow pass
def test_rocking_block_impacts_follow_housner_and_the_pivot_equation():
    p = ROCK
    n = 3
    res = simulate(rocking_system(p), 1.2, restitution=p["e"], max_events=50)
    assert res.stop_reason == "completed"
    imp = res.events_of("impact")
    assert len(imp) == n
    alpha = math.atan2(p["b"], p["h"])
    ratio = 1 - 1.5 * math.sin(alpha) ** 2
    assert ratio == pytest.approx(0.85, rel=1e-14)             # b/h = 1/3: sin²α = 1/10
    p2 = 3 * p["g"] / (4 * math.hypot(p["b"], p["h"]))          # m g R / I_O, I_O = 4/3 m R²
    amp = p["tilt"]
    for ev, (t_ref, w_ref) in zip(imp, pivot_impacts(p, n)):
        w0, w1 = ev.state["dot(theta)"], ev.after["dot(theta)"]
        assert w1 / w0 == pytest.approx(ratio, rel=1e-10)
        assert ev.t == pytest.approx(t_ref, abs=1e-9)
        assert w0 == pytest.approx(w_ref, rel=1e-9)
        # energy about the pivot from the last amplitude: ω⁻² = 2p²(cos(α − amp) − cos α)
        assert abs(w0) == pytest.approx(math.sqrt(2 * p2 * (math.cos(alpha - amp) - math.cos(alpha))), rel=1e-10)
        amp = alpha - math.acos(math.cos(alpha) + w1**2 / (2 * p2))
        # the new corner (C when ω < 0) takes the whole impulse: m Δv_G with v_G = ω ẑ × (G − pivot) at θ = 0
        new, old, s = ("C", "A", 1) if w0 < 0 else ("A", "C", -1)
        nums = ev.impact["contacts"]
        assert nums[new]["normal_impulse"] == pytest.approx(-s * p["b"] * p["m"] * (w1 + w0), rel=1e-9)
        assert abs(nums[new]["tangential_impulse"]) == pytest.approx(p["m"] * p["h"] * abs(w1 - w0), rel=1e-9)
        assert abs(nums[new]["tangential_impulse"]) < p["mu"] * nums[new]["normal_impulse"]
        assert nums[new]["state"] == "stick" and abs(nums[old]["normal_impulse"]) < 1e-12
    assert all("slip" not in seg.mode.values() for seg in res.segments)


@pytest.mark.parametrize("mu", [0.0, 0.5])
def test_rod_on_two_supports_bounces_with_the_lever_rule(mu):
    p = TWO | {"mu": mu}
    n, g, e, m = 6, p["g"], p["e"], p["m"]
    res = simulate(two_supports_system(p), 0.6, restitution=e, max_events=200)
    imp = res.events_of("impact")
    assert len(imp) >= n
    v0 = math.sqrt(2 * g * p["h"])
    t = math.sqrt(2 * p["h"] / g)
    for k, ev in enumerate(imp[:n]):
        vb = v0 * e**k                                  # the k-th fall ends at the speed the bounce left with
        assert ev.t == pytest.approx(t, abs=1e-12)
        assert ev.state["dot(y)"] == pytest.approx(-vb, rel=1e-12)
        assert ev.after["dot(y)"] == pytest.approx(e * vb, rel=1e-12)
        assert ev.after["dot(theta)"] == pytest.approx(0.0, abs=1e-12)
        nums = ev.impact["contacts"]
        pa, pb = nums["A"]["normal_impulse"], nums["B"]["normal_impulse"]
        assert pa + pb == pytest.approx(m * (1 + e) * vb, rel=1e-12)
        assert pa / pb == pytest.approx(p["b"] / p["a"], rel=1e-12)
        if mu:
            assert abs(nums["A"]["tangential_impulse"]) < 1e-12 and abs(nums["B"]["tangential_impulse"]) < 1e-12
        t += 2 * e * vb / g
    assert np.max(np.abs(res["x"])) < 1e-12
