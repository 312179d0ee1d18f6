"""Refusals of inconsistent models name the real conflict: the body, the balance law (and its component) and the
contact whose reactions are in it — checked against the free-body diagram by hand for each model.

* A point-mass cart carrying a block off its centre: the contact forces have a moment about the cart's centre,
  which a point mass cannot carry (its Euler's 2nd law reads Σ M = 0 with no inertia): that law is named, with
  the contacts A and C — not Euler's 1st law along Ey.  With the block centred (and no tangential load) the
  moments cancel and the same model solves, so the refusal is about the offset.
* A point mass pushed above its centre, a slider with nothing to hold it up: a balance with no unknown in it,
  named as it is formed (Euler's 2nd law about Ez; Euler's 1st law along Ey).
* A plank with no angle coordinate on one support off its centre: its moment balance (no coordinate lets it turn,
  no constraint carries a couple), with the contact S; centred, it solves with N = m g.
* The cart with no floor either: two conflicts (its vertical balance and its moment balance), both named.
"""

import pytest

import rigidkin as rk

G = 9.81


def carrier(e=0.1, friction=0.5, floor=True):
    """A point-mass cart (x1 only) with a top surface at h1 above its centre carries a block (x2, y2, θ) on
    its two lower corners A and C; the block's centre is e ahead of the cart's."""
    s = rk.System("carrier")
    m1, m2 = s.parameter("m1", "kg", value=3.0), s.parameter("m2", "kg", value=1.0)
    g = s.parameter("g", "m/s^2", value=G)
    b, h, h1 = s.parameter("b", "m", value=0.4), s.parameter("h", "m", value=0.3), s.parameter("h1", "m", value=0.2)
    F = s.inertial
    x1 = s.coordinate("x1", "cart along Ex", kind="length", initial=0, rate=0)
    x2 = s.coordinate("x2", "block along Ex", kind="length", initial=e, rate=0)
    y2 = s.coordinate("y2", "block height", kind="length", initial=0.35, rate=0)
    th = s.coordinate("theta", "block tilt", initial=0, rate=0)
    C1 = s.point("C1", s.origin, x1 * F.x)
    cart = s.body("cart", rk.shapes.PointMass(m1), frame=F, at=C1)
    B = s.frame("B", angle=th)
    G2 = s.point("G2", s.origin, x2 * F.x + y2 * F.y)
    blk = s.body("block", rk.shapes.RectangularPlate(m2, b, h), frame=B, at=G2)
    A = s.point("A", G2, -b / 2 * B.x - h / 2 * B.y, body=blk)
    C = s.point("C", G2, b / 2 * B.x - h / 2 * B.y, body=blk)
    top = s.line(s.point("T", C1, h1 * F.y, body=cart), F.y, body=cart, name="top")
    if floor:
        s.contact("floor", cart, s.line(s.origin, F.y), centre=C1, normal_name="N_floor")
    s.contact("A", blk, top, centre=A, friction=friction, normal_name="N_A", friction_name="F_A")
    s.contact("C", blk, top, centre=C, friction=friction, normal_name="N_C", friction_name="F_C")
    s.gravity(g)
    return s


def refusal(s, mode=None, kind=rk.ConstraintError):
    with pytest.raises(kind) as err:
        s.solve(mode=mode or {})
    return err.value


@pytest.mark.parametrize("mode", [{"A": "slip", "C": "slip"}, {"A": "stick", "C": "stick"}, {"A": "slip",
                                                                                              "C": "open"}])
def test_point_mass_carrying_a_block_off_its_centre_names_its_moment_balance(mode):
    err = refusal(carrier(e=0.1), mode)
    msg = str(err)
    assert "contradict each other: Euler's 2nd law for cart about its mass centre, along Ez cannot hold" in msg
    assert "no rotational inertia (a point mass)" in msg
    assert err.where.startswith("body cart, contact A")
    assert ("contact C" in err.where) == (mode["C"] != "open")
    assert "Euler's 1st law for cart along Ey cannot hold" not in msg


def test_the_same_cart_with_the_block_centred_solves():
    # e = 0: N_A = N_C = m2 g/2 by symmetry, their moments about the cart's centre cancel; the friction sum is 0
    s = carrier(e=0.0)
    r = s.solve(mode={"A": "stick", "C": "stick"}).regimes[0]
    vals = {p.symbol: p.value for p in s.parameter_info.values()}
    assert float(r.reactions["N_A"].subs(vals)) == pytest.approx(1.0 * G / 2, rel=1e-12)
    assert float(r.reactions["N_C"].subs(vals)) == pytest.approx(1.0 * G / 2, rel=1e-12)
    assert float(r.reactions["N_floor"].subs(vals)) == pytest.approx(4.0 * G, rel=1e-12)
    assert r.indeterminate.reactions == ("F_A", "F_C")


def test_point_mass_pushed_above_its_centre_names_the_moment_and_no_contact():
    s = rk.System("pushed-particle")
    m, P, h = s.parameter("m", "kg", value=1.0), s.parameter("P", "N", value=2.0), s.parameter("h", "m", value=0.1)
    x = s.coordinate("x", "along Ex", kind="length", initial=0, rate=0)
    F = s.inertial
    C = s.point("C", s.origin, x * F.x)
    blk = s.body("block", rk.shapes.PointMass(m), frame=F, at=C)
    s.contact("floor", blk, s.line(s.origin, F.y), centre=C, normal_name="N")
    s.force("push", s.point("Q", C, h * F.y, body=blk), P * F.x)
    s.gravity(s.parameter("g", "m/s^2", value=G))
    err = refusal(s, kind=rk.ModelError)         # a balance with no unknown in it: refused as it is formed
    assert "Euler's 2nd law for block about its mass centre, along Ez reads -P*h = 0" in str(err)
    assert err.where == "block"


def test_slider_with_nothing_holding_it_up_names_its_vertical_balance():
    s = rk.System("slider")
    m = s.parameter("m", "kg", value=1.0)
    x = s.coordinate("x", "along Ex", kind="length", initial=0, rate=0)
    F = s.inertial
    s.body("slider", rk.shapes.RectangularPlate(m, 0.2, 0.1), frame=F, at=s.point("C", s.origin, x * F.x))
    s.gravity(s.parameter("g", "m/s^2", value=G))
    err = refusal(s, kind=rk.ModelError)
    assert "Euler's 1st law for slider along Ey reads -g*m = 0" in str(err) and err.where == "slider"


def test_plank_that_cannot_turn_on_one_support_off_its_centre_names_its_moment_balance():
    # no angle coordinate: N = m g from the vertical balance, whose moment N a about G nothing balances
    s = rk.System("plank")
    m, a = s.parameter("m", "kg", value=1.0), s.parameter("a", "m", value=0.3)
    x = s.coordinate("x", "along Ex", kind="length", initial=0, rate=0)
    F = s.inertial
    G_ = s.point("G", s.origin, x * F.x)
    rod = s.body("plank", rk.shapes.SlenderRod(m, 1.0, axis="x"), frame=F, at=G_)
    s.contact("S", rod, s.line(s.origin, F.y), centre=s.point("P", G_, a * F.x, body=rod), normal_name="N",
              friction="rolling")
    s.gravity(s.parameter("g", "m/s^2", value=G))
    err = refusal(s)
    msg = str(err)
    assert "Euler's 2nd law for plank about its mass centre, along Ez cannot hold" in msg
    assert "no coordinate lets the body turn this way" in msg and err.where == "body plank, contact S"
    s2 = rk.System("plank-centred")            # the support under the centre: N = m g, no moment, it solves
    m2 = s2.parameter("m", "kg", value=1.0)
    x2 = s2.coordinate("x", "along Ex", kind="length", initial=0, rate=0)
    G2 = s2.point("G", s2.origin, x2 * s2.inertial.x)
    rod2 = s2.body("plank", rk.shapes.SlenderRod(m2, 1.0, axis="x"), frame=s2.inertial, at=G2)
    s2.contact("S", rod2, s2.line(s2.origin, s2.inertial.y), centre=G2, normal_name="N", friction="rolling")
    s2.gravity(s2.parameter("g", "m/s^2", value=G))
    N = s2.solve().reactions["N"]
    assert float(N.subs({p.symbol: p.value for p in s2.parameter_info.values()})) == pytest.approx(G, rel=1e-12)


def test_cart_without_a_floor_names_both_conflicts():
    err = refusal(carrier(e=0.1, floor=False), {"A": "slip", "C": "slip"})
    msg = str(err)
    assert "Euler's 1st law for cart along Ey cannot hold" in msg
    assert "and Euler's 2nd law for cart about its mass centre, along Ez cannot hold" in msg
    assert err.where == "body cart, contact A, contact C"


def test_two_coincident_pins_name_the_pins_whose_reactions_are_not_separated():
    # a pendulum held at O by two pins: the force at O is determined, its split between the pins is not
    s = rk.System("pendulum")
    m, l, g = s.parameter("m", "kg"), s.parameter("l", "m"), s.parameter("g", "m/s^2")
    th = s.coordinate("theta", "from the downward vertical")
    R = s.frame("R", angle=th)
    rod = s.body("rod", rk.shapes.SlenderRod(m, l, axis="y"), frame=R, at=s.point("G", offset=-l / 2 * R.y))
    s.gravity(g)
    s.pin("O", s.origin, rod)
    s.pin("O2", s.origin, rod)
    err = refusal(s)
    assert "cannot be determined from them (the reactions of O, O2)" in str(err) and err.where == "O, O2"


def stack(e=0.1):
    """Two point masses stacked: the upper one (x2, y2) on the lower one's top surface, h1 above its centre,
    e ahead of it; the lower one (x1) on a rough floor."""
    s = rk.System("stack")
    m1, m2 = s.parameter("m1", "kg", value=3.0), s.parameter("m2", "kg", value=1.0)
    g, h1 = s.parameter("g", "m/s^2", value=G), s.parameter("h1", "m", value=0.2)
    F = s.inertial
    x1 = s.coordinate("x1", "lower along Ex", kind="length", initial=0, rate=0)
    x2 = s.coordinate("x2", "upper along Ex", kind="length", initial=e, rate=0)
    y2 = s.coordinate("y2", "upper height", kind="length", initial=0.2, rate=0)
    C1 = s.point("C1", s.origin, x1 * F.x)
    low = s.body("lower", rk.shapes.PointMass(m1), frame=F, at=C1)
    s.contact("floor", low, s.line(s.origin, F.y), centre=C1, normal_name="N_floor", friction=0.3,
              friction_name="F_floor")
    G2 = s.point("G2", s.origin, x2 * F.x + y2 * F.y)
    up = s.body("upper", rk.shapes.PointMass(m2), frame=F, at=G2)
    top = s.line(s.point("T", C1, h1 * F.y, body=low), F.y, body=low)
    s.contact("top", up, top, centre=G2, normal_name="N", friction=0.5, friction_name="F")
    s.gravity(g)
    return s


@pytest.mark.parametrize("mode", [{}, {"top": "stick", "floor": "slip"}, {"top": "stick", "floor": "stick"}])
def test_point_mass_carrying_a_point_mass_off_its_centre_names_the_lower_ones_moment_balance(mode):
    # the case: the normal force N = m2 g of the upper block acts on the lower point mass e off its
    # centre; before, the refusal blamed "Euler's 1st law for upper along Ey"
    err = refusal(stack(0.1), mode)
    msg = str(err)
    assert "contradict each other: Euler's 2nd law for lower about its mass centre, along Ez cannot hold" in msg
    assert "lower has no rotational inertia (a point mass)" in msg and err.where == "body lower, contact top"
    assert "Euler's 1st law for upper along Ey cannot hold" not in msg
