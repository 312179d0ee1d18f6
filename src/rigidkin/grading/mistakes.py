"""The common mistakes of a derivation, written out as the wrong equations they lead to.

Kinematics: a velocity differentiated in a turning frame without its transport term ω × r, a rigid-body
relation v_P = v_Q + ω × r_QP without (or with the wrong sign of) its ω × r term, an acceleration
without its centripetal ω × (ω × r) or tangential α × r term.  Moments: about a moving point without
the inertial-moment term −(r̄ − r_P) × m a_P, Ī used about another point (the parallel-axis term
missing), the inertia about an end used about the mass centre.  Each is a :class:`Candidate` with the
cause in words; the grader names the one a wrong step matches.
"""

from __future__ import annotations

from sympy.physics.vector import Vector, dynamicsymbols

from .engine import Candidate, Reference

t = dynamicsymbols._t


def kinematic_variants(ref: Reference, point, quantity: str) -> list[tuple[str, Vector]]:
    """Wrong velocities (``quantity`` "v") or accelerations ("a") of ``point`` with their causes."""
    kin, F = ref.kin, ref.F
    body = ref.point_body(point)
    out = []
    if quantity == "a":
        v = ref.setup.vector(kin.velocity(point))
        rates_only = Vector(0)
        for q in ref.solution.coordinates:
            rates_only += v.diff(q.diff(t), F.ref) * q.diff(t, 2)
        out.append(("terms missing: only the rates were differentiated (the q̈ terms); the terms in the squares "
                    "of the rates, from the turning of the directions (ω × (ω × r), ω × v), are missing", rates_only))
    for fr in ref.system.frames.values():
        if fr.ref is F.ref:
            continue
        w = kin.omega(fr)
        if kin.is_zero_vector(w):
            continue
        if quantity == "v":
            out.append((f"transport term missing: r_O{point.name} was differentiated in frame {fr.name} "
                        f"only; the transport theorem adds ω × r (ω of {fr.name})", kin.position(point).dt(fr.ref)))
        else:
            out.append((f"transport term missing: v_{point.name} was differentiated in frame {fr.name} only; "
                        f"the transport theorem adds ω × v (ω of {fr.name})", kin.velocity(point).dt(fr.ref)))
            out.append((f"transport terms missing: r_O{point.name} was differentiated twice in frame {fr.name} "
                        "only (no ω × terms)", kin.position(point).dt(fr.ref).dt(fr.ref)))
    if body is None:
        return out
    w, a = kin.omega_of(body), kin.alpha(body.frame)
    for Q in ref.body_points(body):
        if Q is point:
            continue
        r = kin.position(point) - kin.position(Q)
        if kin.is_zero_vector(r):
            continue
        tag = f"v_{point.name} = v_{Q.name} + ω × r_{Q.name}{point.name}" if quantity == "v" else \
            f"a_{point.name} = a_{Q.name} + α × r + ω × (ω × r) (r = r_{Q.name}{point.name})"
        if quantity == "v":
            out.append((f"transport term missing: the term ω × r_{Q.name}{point.name} of {tag}", kin.velocity(Q)))
            out.append((f"sign: the term ω × r_{Q.name}{point.name} of {tag} has the wrong sign",
                        kin.velocity(Q) - w.cross(r)))
        else:
            aQ = kin.acceleration(Q)
            out.append((f"centripetal term missing: ω × (ω × r) of {tag}", aQ + a.cross(r)))
            out.append((f"tangential term missing: α × r of {tag}", aQ + w.cross(w.cross(r))))
            out.append((f"both rotation terms missing: α × r and ω × (ω × r) of {tag}", aQ))
    return out


def moment_candidates(ref: Reference, body, points, axes) -> list[Candidate]:
    """Euler's 2nd law about each point (correct), and its common mistaken forms."""
    kin = ref.kin
    out = []
    G = body.centre
    for P in points:
        rP = kin.position(P)
        d = kin.position(G) - rP
        at_centre = kin.is_zero_vector(d)
        for axis, aname in axes:
            lab = f"Euler's 2nd law for {body.name} about {P.name}, along {aname}"
            right = ref.moment_equation(body, P, axis)
            out.append(Candidate(lab, right, body.name, "moment", P.name))
            if body.is_massless:
                continue
            if not kin.is_zero_vector(body.inertia.dot(kin.alpha(body.frame))):
                out.append(Candidate(lab, ref.moment_equation(body, P, axis, rotational=False), body.name, "moment",
                                     P.name, "rotational inertia missing: the term Ī·α of dH̄/dt was left out, as if "
                                             f"{body.name} were a particle", right))
            if not at_centre:
                out.append(Candidate(lab, ref.moment_equation(body, P, axis, inertial=False), body.name, "moment",
                                     P.name, f"inertial-moment term missing: moments about the moving point "
                                             f"{P.name} need −(r̄ − r_{P.name}) × m a_{P.name} (M_P = I_P·α holds "
                                             "only when P is fixed or is the mass centre)", right))
                why = (f"wrong inertia: Ī (about the mass centre) was used for moments about {P.name}; the "
                       f"parallel-axis term m·d² is missing (I_{P.name} = Ī + m d²)")
                out.append(Candidate(lab, _bare(ref, body, P, axis), body.name, "moment", P.name, why, right))
                # Ī about P with the inertial-moment term written with a_P (r_PG × m a_P): the m d² α is lost
                out.append(Candidate(lab, ref.moment_equation(body, P, axis, accel=kin.acceleration(P)), body.name,
                                     "moment", P.name, why, right))
            else:
                for Q in ref.body_points(body) + ref.contact_spots(body):
                    if Q is G or kin.is_zero_vector(kin.position(Q) - kin.position(G)):
                        continue
                    why = (f"wrong inertia: the moment of inertia about {Q.name} was used for moments about the mass "
                           f"centre {G.name} (about {G.name} it is Ī, without m d²)")
                    out.append(Candidate(lab, ref.moment_equation(body, P, axis, inertia_about=Q), body.name,
                                         "moment", P.name, why, right))
    return out


def _bare(ref: Reference, body, P, axis):
    """M_P = dH̄/dt: the mass-centre inertia used about P, nothing else."""
    kin = ref.kin
    w, a = kin.omega_of(body), kin.alpha(body.frame)
    Ibar = body.inertia
    M = ref.moment_vector(body, kin.position(P))
    return ref.scalar(ref.setup.vector(M - Ibar.dot(a) - w.cross(Ibar.dot(w))).dot(axis))


def force_candidates(ref: Reference, body, directions, variants: bool = True) -> list[Candidate]:
    """Euler's 1st law along each direction, and the same with the mass centre's acceleration mistaken."""
    out = []
    wrong = [("the inertia term m ā is missing (written as if in equilibrium; the mass centre accelerates)",
              Vector(0))] + kinematic_variants(ref, body.centre, "a") if variants and not body.is_massless else []
    for e, name in directions:
        lab = f"Euler's 1st law for {body.name} along {name}"
        right = ref.force_equation(body, e)
        out.append(Candidate(lab, right, body.name, "force"))
        for why, a in wrong:
            out.append(Candidate(lab, ref.force_equation(body, e, accel=a), body.name, "force", None,
                                 f"wrong acceleration of the mass centre in m ā: {why}", right))
    return out


def system_candidates(ref: Reference, bodies, directions) -> list[Candidate]:
    """Euler's 1st law for the whole system along each direction: the sum of the bodies' equations (the
    forces between the bodies cancel), so that a whole-system balance is compared with its own kind."""
    out = []
    for e, name in directions:
        expr = sum((ref.force_equation(b, e) for b in bodies), 0)
        out.append(Candidate(f"Euler's 1st law for the whole system along {name}", expr, None, "force"))
    return out
