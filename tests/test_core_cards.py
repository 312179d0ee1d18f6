"""Core acceptance: each card's EOM against the card, each named reaction against an independent
derivation with sympy.physics.mechanics' LagrangesMethod (multipliers) built here from T − V."""

import pytest
import sympy as sp
from helpers import solve_accels, values_match
from sympy import cos, sin
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from rigidkin.examples import build

t = dynamicsymbols._t


@pytest.fixture(scope="module")
def solved():
    cache = {}

    def get(name):
        if name not in cache:
            s = build(name)
            cache[name] = (s, s.solve())
        return cache[name]

    return get


def P(s, name):
    return s.parameters[name]


def lagrange(L, qs, hol=(), nonhol=(), forces=None, frame=None):
    """Accelerations and multipliers from LagrangesMethod; returns (dict q→q̈, list of λ)."""
    LM = LagrangesMethod(L, qs, hol_coneqs=list(hol), nonhol_coneqs=list(nonhol), forcelist=forces, frame=frame)
    LM.form_lagranges_equations()
    rhs = LM.rhs()
    n = len(qs)
    acc = {q: rhs[n + i] for i, q in enumerate(qs)}
    lams = list(rhs[2 * n:])
    return acc, lams


def test_ladder(solved):
    s, sol = solved("ladder")
    m, l, g = P(s, "m"), P(s, "l"), P(s, "g")
    th = s.coordinates[0]
    card = [sol.system.coordinates[0].diff(t, 2) - 3 * g / (2 * l) * sin(th)]
    assert sol.coordinates == (th,)
    assert values_match(sol.accelerations[th], solve_accels(card, [th])[th], [th])
    assert sp.simplify(sol.accelerations[th] - 3 * g * sin(th) / (2 * l)) == 0
    # independent: mass-centre coordinates with wall and floor constraints, multipliers = N_A, N_B
    xg, yg, q = dynamicsymbols("xg yg q")
    T = m * (xg.diff() ** 2 + yg.diff() ** 2) / 2 + m * l**2 / 12 * q.diff() ** 2 / 2
    L = T - m * g * yg
    acc, (lam_wall, lam_floor) = lagrange(L, [xg, yg, q], hol=[xg - l / 2 * sin(q), yg - l / 2 * cos(q)])
    on = {xg: l / 2 * sin(th), yg: l / 2 * cos(th), q: th, xg.diff(): l / 2 * cos(th) * th.diff(),
          yg.diff(): -l / 2 * sin(th) * th.diff(), q.diff(): th.diff()}
    to_state = lambda e: e.subs({k: v for k, v in on.items() if isinstance(k, sp.Derivative)}).subs(on)  # noqa: E731
    assert values_match(sol.accelerations[th], to_state(acc[q]), [th], ranges={"theta": (0.1, 1.2)})
    assert values_match(sol.reactions["N_A"], to_state(lam_wall), [th])
    assert values_match(sol.reactions["N_B"], to_state(lam_floor), [th])
    # and the card's contact-loss condition: N_A = 0 where cos θ = 2/3 when θ̇² = 3g(1 − cos θ)/l
    NA = sol.reactions["N_A"].subs(th.diff(), sp.sqrt(3 * g * (1 - cos(th)) / l))
    assert sp.simplify(NA.subs(th, sp.acos(sp.Rational(2, 3)))) == 0


def test_collar_rod(solved):
    s, sol = solved("collar-rod")
    m1, m2, l, g = (P(s, n) for n in ("m1", "m2", "l", "g"))
    x, th = s.coordinates
    card = [(m1 + m2) * x.diff(t, 2) + m2 * l / 2 * (th.diff(t, 2) * cos(th) - th.diff() ** 2 * sin(th)),
            x.diff(t, 2) * cos(th) + 2 * l / 3 * th.diff(t, 2) + g * sin(th)]
    ref = solve_accels(card, [x, th])
    for q in (x, th):
        assert values_match(sol.accelerations[q], ref[q], [x, th])
    # the two EOM rows are the card's rows up to a constant factor each
    for mine, theirs in zip(sol.eom, card):
        assert values_match(mine, theirs, [x, th], factor=True)
    # independent: collar (xc, yc), rod mass centre (xg, yg), angle q; track and pin constraints
    xc, yc, xg, yg, q = dynamicsymbols("xc yc xg yg q")
    T = m1 * (xc.diff() ** 2 + yc.diff() ** 2) / 2 + m2 * (xg.diff() ** 2 + yg.diff() ** 2) / 2 \
        + m2 * l**2 / 24 * q.diff() ** 2
    L = T - m2 * g * yg - m1 * g * yc
    acc, (lam_track, lam_px, lam_py) = lagrange(
        L, [xc, yc, xg, yg, q], hol=[yc, xg - l / 2 * sin(q) - xc, yg + l / 2 * cos(q) - yc])
    on_d = {xc.diff(): x.diff(), yc.diff(): 0, xg.diff(): x.diff() + l / 2 * cos(th) * th.diff(),
            yg.diff(): l / 2 * sin(th) * th.diff(), q.diff(): th.diff()}
    on = {xc: x, yc: 0, xg: x + l / 2 * sin(th), yg: -l / 2 * cos(th), q: th}
    to_state = lambda e: e.subs(on_d).subs(on)  # noqa: E731
    assert values_match(sol.reactions["N"], to_state(lam_track), [x, th])
    assert values_match(sol.reactions["R_Px"], to_state(lam_px), [x, th])
    assert values_match(sol.reactions["R_Py"], to_state(lam_py), [x, th])
    assert sol.reactions["M_track"] == 0


def test_collar_force(solved):
    s, sol = solved("collar-force")
    m, l, g, Pf = (P(s, n) for n in ("m", "l", "g", "P"))
    x, th = s.coordinates
    card = [m * x.diff(t, 2) + m * l / 2 * (th.diff(t, 2) * cos(th) - th.diff() ** 2 * sin(th)) - Pf,
            m * x.diff(t, 2) * cos(th) + 2 * m * l / 3 * th.diff(t, 2) + m * g * sin(th)]
    ref = solve_accels(card, [x, th])
    for q in (x, th):
        assert values_match(sol.accelerations[q], ref[q], [x, th])
    # independent: the massless collar's coordinates are fixed by the track and pin constraints
    xc, yc, xg, yg, q = dynamicsymbols("xc yc xg yg q")
    T = m * (xg.diff() ** 2 + yg.diff() ** 2) / 2 + m * l**2 / 24 * q.diff() ** 2
    L = T - m * g * yg
    from sympy.physics.mechanics import Point, ReferenceFrame
    N = ReferenceFrame("N")
    C = Point("C")
    C.set_vel(N, xc.diff() * N.x + yc.diff() * N.y)
    # reduce to x, θ for the track force: Lagrange on (x, θ) gives EOM; N from the rod's vertical balance
    acc, lams = lagrange(L.subs({xg: xc + l / 2 * sin(q), yg: yc - l / 2 * cos(q)}).doit(), [xc, yc, q],
                         hol=[yc], forces=[(C, Pf * N.x)], frame=N)
    on = {xc.diff(): x.diff(), yc.diff(): 0, q.diff(): th.diff(), xc: x, yc: 0, q: th}
    assert values_match(sol.reactions["N"], lams[0].subs(on), [x, th])
    assert values_match(sol.accelerations[th], acc[q].subs(on), [x, th])


def test_sphere_on_sphere(solved):
    s, sol = solved("sphere-on-sphere")
    m, r, R, g = (P(s, n) for n in ("m", "r", "R", "g"))
    th, phi, rho = s.coordinates
    assert sol.coordinates == (th,)
    assert sol.relations[rho] == R + r
    assert sp.simplify(sol.relations[phi] - r * th / (R + r)) == 0
    card = th.diff(t, 2) - 5 * g / (7 * r) * sin(r * th / (R + r))
    assert values_match(sol.accelerations[th], solve_accels([card], [th])[th], [th])
    # independent: polar coordinates of the centre, constraints ρ = R + r and ρ φ̇ = r θ̇
    q, f, p = dynamicsymbols("q f p")
    T = m * (p.diff() ** 2 + p**2 * f.diff() ** 2) / 2 + m * r**2 / 5 * q.diff() ** 2
    L = T - m * g * p * cos(f)
    acc, (lam_gap, lam_roll) = lagrange(L, [q, f, p], hol=[p - R - r],
                                        nonhol=[p * f.diff() - r * q.diff()])
    on = {q.diff(): th.diff(), f.diff(): r * th.diff() / (R + r), p.diff(): 0,
          q: th, f: r * th / (R + r), p: R + r}
    assert values_match(sol.reactions["N"], lam_gap.subs(on), [th])
    assert values_match(sol.accelerations[th], acc[q].subs(on), [th])


def test_disk_in_track(solved):
    s, sol = solved("disk-in-track")
    m, r, R, g = (P(s, n) for n in ("m", "r", "R", "g"))
    th, phi = s.coordinates
    assert sp.simplify(sol.relations[phi] - (R - r) * th / r) == 0
    card = sp.Rational(3, 2) * m * (R - r) * th.diff(t, 2) + m * g * sin(th)
    rng = {"R": (2.0, 4.0), "r": (0.2, 1.0)}
    assert values_match(sol.accelerations[th], solve_accels([card], [th])[th], [th], ranges=rng)
    assert values_match(sol.eom[0], card, [th], ranges=rng, factor=True)
    # independent: polar coordinates (ρ, θ) of the centre and the disk angle φ; gap ρ − (R − r)
    q, f, p = dynamicsymbols("q f p")
    T = m * (p.diff() ** 2 + p**2 * q.diff() ** 2) / 2 + m * r**2 / 4 * f.diff() ** 2
    L = T + m * g * p * cos(q)
    acc, (lam_gap, lam_roll) = lagrange(L, [q, f, p], hol=[p - (R - r)],
                                        nonhol=[r * f.diff() - p * q.diff()])
    on = {q.diff(): th.diff(), f.diff(): (R - r) * th.diff() / r, p.diff(): 0, q: th, p: R - r}
    # the track pushes towards O: N = −λ (λ is the force along +ρ)
    assert values_match(sol.reactions["N"], -lam_gap.subs(on), [th], ranges=rng)


def test_disk_spring_incline(solved):
    s, sol = solved("disk-spring-incline")
    m, r, K, beta, g = (P(s, n) for n in ("m", "r", "K", "beta", "g"))
    th = s.coordinates[0]
    card = sp.Rational(3, 2) * m * r**2 * th.diff(t, 2) + K * r**2 * th - m * g * r * sin(beta)
    assert values_match(sol.accelerations[th], solve_accels([card], [th])[th], [th])
    assert values_match(sol.eom[0], card, [th], factor=True)


def test_boulder_push_regimes(solved):
    s, sol = solved("boulder-push")
    m, g, beta, Pf, mu = (P(s, n) for n in ("m", "g", "beta", "P", "mu"))
    x = s.coordinates[0]
    assert len(sol.regimes) == 2
    up = sol.regime_at({x.diff(): 1.0})
    down = sol.regime_at({x.diff(): -1.0})
    assert up is not down
    assert [str(c.expr) for c in up.conditions] == [str(x.diff())] and up.conditions[0].relation == ">"
    card_up = sp.Rational(7, 5) * m * x.diff(t, 2) + m * g * sin(beta) - Pf * (1 - mu)
    card_down = sp.Rational(7, 5) * m * x.diff(t, 2) + m * g * sin(beta) - Pf * (1 + mu)
    assert values_match(up.accelerations[x], solve_accels([card_up], [x])[x], [x])
    assert values_match(down.accelerations[x], solve_accels([card_down], [x])[x], [x])
    assert not values_match(up.accelerations[x], down.accelerations[x], [x])
    with pytest.raises(Exception, match="2 regimes"):
        _ = sol.eom


def test_mass_matrix_consistent(solved):
    for name in ("collar-rod", "collar-force", "ladder"):
        s, sol = solved(name)
        M, f = sol.mass_matrix, sol.forcing
        a = sp.Matrix([sol.accelerations[q] for q in sol.coordinates])
        for e in M * a - f:
            assert values_match(e, 0, list(s.coordinates))
