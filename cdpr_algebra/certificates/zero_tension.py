"""Exact zero tensions of the IGP with assigned position: the three-force plane (seed 004 Sec. 4, Appendix B).

An IGP root whose tension tau_k encloses 0 is a 'boundary' case for :mod:`.equilibria`: intervals cannot prove
that a value is exactly zero.  Seed 004 Table 4 is such a case by construction (the robot behaves as a 2-2 robot,
tau_3 = 0), and so is any robot where the other two cables i, l can hold the load alone at the assigned G.

Why it can be proven.  Three forces in equilibrium (the two cable forces and the load) are coplanar and concurrent.
With G assigned, that plane Pi contains A_i, A_l, G and the load direction d; the platform points b'_i, b'_l, g'
must lie in one plane of the platform that the pose maps onto Pi.  Both are decided exactly, in rationals from the
doubles of the robot file (:func:`three_force_plane`).  The 2-cable equilibria with the platform in Pi are then a
square planar system (:func:`planar_system`): unknowns (c, s, lam_i, lam_l), R = W P(c, s) F^T with W, F
orthonormal frames of Pi and of the platform plane and P a turn (or a turn and a flip, ``sigma`` = -1) about their
normals:

    c^2 + s^2 - 1 = 0,   sum_q lam_q (a_q - P2 b_q) + f = 0 (2 rows),   sum_q lam_q (P2 b_q) x a_q = 0,

in the plane's coordinates (a_q: A_q - G, b_q: b'_q - g', f: the load; 2-vectors).  Its out-of-plane components (the
force along the normal, the moments about in-plane axes) are zero exactly, since every point and force lies in Pi.

Proof (:func:`prove_zero_tension`).  (1) The Krawczyk test proves a unique root of the planar system in a small box
for every value of its coefficients in their balls (W, F are irrational: enclosed from the exact data), hence for
the exact ones.  (2) That root, as (R, lam) with lam_k = 0, is an exact root of the 12 IGP equations (rotation and
balance).  (3) The Krawczyk test proves the IGP root unique in a box X of (u, v, w, lam); the planar root, mapped,
lies inside X.  So the IGP root is that root, and tau_k = lam_k rho_k = 0 exactly.  When a step fails the tension
stays 'boundary' (nothing is guessed).  Over the planar root's enclosure, the class of H_r of cables i, l alone
(cable k at its length, unloaded) is proven too (the bordered matrix of :mod:`.equilibria`): seed 004 Table 4
prints that class.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction

import numpy as np
from flint import arb

from cdpr_algebra.intervals.balls import krawczyk_certify, krawczyk_operator, symmetric_inertias

from .equilibria import (BOX_RTOL, FLINT, _bordered_matrix, _cross, _dot, _hessian_class, _robot_data, _vec_sub,
                         boundary_reason, igp_position_scales, igp_position_system)

__all__ = ["ZeroTension", "three_force_plane", "planar_system", "prove_zero_tension", "with_zero_tensions"]

ZERO = "zero"  # tension sign proven exactly 0 (Certificate.tension_signs)


@dataclass(frozen=True)
class ZeroTension:
    """A proof that tension ``cable`` (1-based) is exactly 0, the other two ``holding`` the load, and the class of
    the reduced Hessian of those two cables alone (cable ``cable`` at its length, unloaded: seed 004 Table 4
    prints this class), proven over the planar root's enclosure ('proven', '>' | '<' | '<>') or 'undecided'."""

    cable: int
    holding: tuple
    hessian: str
    hessian_class: str | None

    @property
    def text(self) -> str:
        i, l = self.holding
        return (f"tau_{self.cable} = 0 exactly: cables {i}, {l} hold the load in the plane through A_{i}, A_{l}, G and "
                f"the load (three-force equilibrium, proven by a planar Krawczyk test); H_r of cables {i}, {l} alone: "
                + (f"{self.hessian_class} (proven)" if self.hessian == "proven" else "undecided"))

    def to_dict(self) -> dict:
        return {"cable": self.cable, "holding": list(self.holding), "proof": self.text,
                "hessian_of_the_others": self.hessian_class if self.hessian == "proven" else "undecided"}


def _exact(v):
    return [Fraction(float(c)) for c in v]


def three_force_plane(robot, com_position, k: int):
    """The exact geometry of the three-force plane of the cables other than ``k`` (0-based) of a 3-cable robot with
    G at ``com_position``, or None when it does not exist: (i, l, A_i - G, A_l - G, d, b_i, b_l) in Fractions
    (b_q = b'_q - g'), where A_i, A_l, G and the load direction d span one plane (d not along A_l - A_i) and
    b_i, b_l are not parallel (the platform plane through b'_i, b'_l, g')."""
    i, l = (j for j in range(3) if j != k)
    G = _exact(com_position)
    Ai, Al = _vec_sub(_exact(robot.base[i]), G), _vec_sub(_exact(robot.base[l]), G)
    d = _exact(robot.load_direction)
    normal = _cross(_vec_sub(Al, Ai), d)
    if not any(normal) or _dot(Ai, normal) != 0:
        return None
    g = _exact(robot.com)
    bi, bl = _vec_sub(_exact(robot.platform[i]), g), _vec_sub(_exact(robot.platform[l]), g)
    if not any(_cross(bi, bl)):
        return None
    return i, l, Ai, Al, d, bi, bl


def _ball(q: Fraction):
    return arb(q.numerator) / q.denominator


def _frame(u, w):
    """Orthonormal (e1, e2, e3) as balls: e1 along u, e3 along u x w (u, w exact, not parallel)."""
    u = [_ball(c) for c in u]
    n = _cross(u, [_ball(c) for c in w])
    e1 = [c / _dot(u, u).sqrt() for c in u]
    e3 = [c / _dot(n, n).sqrt() for c in n]
    return e1, _cross(e3, e1), e3


def _in_plane(v, e1, e2):
    return [_dot(v, e1), _dot(v, e2)]


def _turn(c, s, sigma):
    """P2 (2 x 2) and its derivatives by c and s: a turn (sigma = 1) or a turn and a flip (sigma = -1)."""
    if sigma > 0:
        return [[c, -s], [s, c]], [[1, 0], [0, 1]], [[0, -1], [1, 0]]
    return [[c, s], [s, -c]], [[1, 0], [0, -1]], [[0, 1], [1, 0]]


def _mul2(M, v):
    return [M[0][0] * v[0] + M[0][1] * v[1], M[1][0] * v[0] + M[1][1] * v[1]]


def _cross2(a, b):
    return a[0] * b[1] - a[1] * b[0]


def planar_system(a, b, f, sigma: int):
    """The planar 2-cable equilibrium (module doc) as ``system(x) -> (F, J)`` for x = (c, s, lam_i, lam_l):
    ``a``, ``b``: the two cables' a_q and b_q (2-vectors), ``f``: the load (2-vector), in any arithmetic."""
    def system(x, jacobian=True):
        c, s, lam = x[0], x[1], x[2:4]
        P, Pc, Ps = _turn(c, s, sigma)
        r = [_mul2(P, bq) for bq in b]
        F = [c * c + s * s - 1]
        F += [lam[0] * (a[0][k] - r[0][k]) + lam[1] * (a[1][k] - r[1][k]) + f[k] for k in range(2)]
        F.append(lam[0] * _cross2(r[0], a[0]) + lam[1] * _cross2(r[1], a[1]))
        if not jacobian:
            return F, None
        rc, rs = [_mul2(Pc, bq) for bq in b], [_mul2(Ps, bq) for bq in b]
        J = [[2 * c, 2 * s, 0 * c, 0 * c]]
        J += [[-(lam[0] * rc[0][k] + lam[1] * rc[1][k]), -(lam[0] * rs[0][k] + lam[1] * rs[1][k]),
               a[0][k] - r[0][k], a[1][k] - r[1][k]] for k in range(2)]
        J.append([lam[0] * _cross2(rc[0], a[0]) + lam[1] * _cross2(rc[1], a[1]),
                  lam[0] * _cross2(rs[0], a[0]) + lam[1] * _cross2(rs[1], a[1]),
                  _cross2(r[0], a[0]), _cross2(r[1], a[1])])
        return F, J
    return system


def _unique_igp_root(robot, G, y0, mapped) -> bool:
    """True when the Krawczyk test proves that the 12 x 12 IGP system with assigned position (unknowns (u, v, w,
    lam), platform frame at G) has exactly one zero in the box X = y0 +- (2 ``BOX_RTOL`` scale + 2 rad) around the
    reported root ``y0``, which contains the balls ``mapped`` (their midpoints within ``BOX_RTOL`` scale of y0, else
    False) and the box in which :func:`.equilibria.certify_igp_positions` proved the reported root (half-width <=
    BOX_RTOL / 2 scale around y0's Newton step, itself <= BOX_RTOL / 2 scale).  So the zero in X is the certified
    root, and it is ``mapped``'s."""
    make = igp_position_system(robot, G)
    sa, sf = make(arb), make(float)
    mid = np.array([float(v.mid()) for v in mapped])
    rad = np.array([float(v.rad()) for v in mapped])
    scale = igp_position_scales(robot, y0)
    if np.any(np.abs(mid - y0) > BOX_RTOL * scale):  # not the reported root: it was certified within that of y0
        return False
    r = 2 * BOX_RTOL * scale + 2 * rad
    try:
        C = np.linalg.inv(np.asarray(sf(y0.tolist(), True)[1], float))
    except np.linalg.LinAlgError:
        return False
    if not np.all(np.isfinite(C)):
        return False
    K, X = krawczyk_operator(lambda y: sa(y, False)[0], lambda y: sa(y, True)[1], y0, r, C)
    return (all(Xi.contains(v) for Xi, v in zip(X, mapped))
            and all(Xi.contains_interior(Ki) for Xi, Ki in zip(X, K)))


def prove_zero_tension(robot, com_position, rotation, tensions, lengths, k: int) -> ZeroTension | None:
    """A proof that tension ``k`` (0-based) of the IGP root with assigned G = ``com_position`` (``rotation``, the
    3 ``tensions`` and ``lengths``) is exactly 0 (module doc), with the class of H_r of the other two cables over
    the planar root's enclosure; None when not proven."""
    plane = three_force_plane(robot, com_position, k)
    if plane is None:
        return None
    i, l, Ai, Al, d, bi, bl = plane
    with FLINT:
        W = _frame(d, _vec_sub(Al, Ai))  # e1 along d, e3 the plane's normal
        Fr = _frame(bi, bl)
        a = [_in_plane([_ball(c) for c in A], W[0], W[1]) for A in (Ai, Al)]
        b = [_in_plane([_ball(c) for c in B], Fr[0], Fr[1]) for B in (bi, bl)]
        f = _in_plane([arb(robot.load) * float(c) for c in robot.load_direction], W[0], W[1])
        Wm = np.array([[float(v.mid()) for v in e] for e in W]).T  # columns e1, e2, e3
        Fm = np.array([[float(v.mid()) for v in e] for e in Fr]).T
        P0 = Wm.T @ np.asarray(rotation, float) @ Fm
        if abs(abs(P0[2, 2]) - 1) > 1e-6:  # the root's platform plane is not on Pi
            return None
        sigma = 1 if P0[2, 2] > 0 else -1
        lam = np.asarray(tensions, float) / np.asarray(lengths, float)
        x0 = np.array([P0[0, 0], P0[1, 0], lam[i], lam[l]])
        floats = planar_system([[float(v.mid()) for v in q] for q in a], [[float(v.mid()) for v in q] for q in b],
                               [float(v.mid()) for v in f], sigma)
        balls = planar_system(a, b, f, sigma)
        scale = np.array([1.0, 1.0] + [max(robot.load / robot.cable_scale, abs(lam[i]), abs(lam[l]))] * 2)
        kr = krawczyk_certify(lambda x: balls(x, False)[0], lambda x: balls(x, True)[1], x0, scale, BOX_RTOL,
                              F_float=lambda x: floats(x.tolist(), False)[0],
                              J_float=lambda x: floats(x.tolist(), True)[1])
        if not kr.proven:
            return None
        c, s, li, ll = kr.enclosure
        P2 = _turn(c, s, sigma)[0]
        P = [[P2[0][0], P2[0][1], arb(0)], [P2[1][0], P2[1][1], arb(0)], [arb(0), arb(0), arb(sigma)]]
        # R = W P F^T, entries R[r][q] = sum W[r][u] P[u][v] F[q][v]
        R = [[sum((W[u][r] * P[u][v] * Fr[v][q] for u in range(3) for v in range(3)), arb(0)) for q in range(3)]
             for r in range(3)]
        lam_all = [arb(0)] * 3
        lam_all[i], lam_all[l] = li, ll
        mapped = [R[r][q] for q in range(3) for r in range(3)] + lam_all  # (u, v, w, lam): columns of R
        y0 = np.concatenate([np.asarray(rotation, float).T.ravel(), lam])  # the certified root, as certified
        if not _unique_igp_root(robot, com_position, y0, mapped):
            return None
        A, bp, _, _ = _robot_data(robot, (i, l), arb, com_at_origin=True)
        Gb = [arb(float(v)) for v in com_position]
        B = [[Gb[r] + sum((R[r][q] * bq[q] for q in range(3)), arb(0)) for r in range(3)] for bq in bp]
        K = _bordered_matrix(A, B, Gb, [li, ll], robot.cable_scale, robot.load)
        (inertia,) = symmetric_inertias([K])
    hessian, cls = _hessian_class(inertia, (2, False))
    return ZeroTension(k + 1, (i + 1, l + 1), hessian, cls)


def with_zero_tensions(robot, solutions) -> list:
    """The IGP (assigned position) solutions whose certificate has exactly one 'boundary' tension and everything
    else proven, with that tension proven 0 where :func:`prove_zero_tension` proves it: its sign becomes 'zero',
    its enclosure [0, 0] and its value 0, the proof (:meth:`ZeroTension.to_dict`) is the certificate's
    ``extra['zero_tension']``, and the certificate is complete when nothing else is missing."""
    out = []
    for s in solutions:
        c = s.certificate
        boundary = [j for j, g in enumerate(c.tension_signs) if g == "boundary"] if c is not None else []
        proof = None
        if c is not None and c.exists_unique and len(boundary) == 1 and robot.n == 3:
            proof = prove_zero_tension(robot, np.real(s.com_position), np.real(s.rotation), np.real(s.tensions),
                                       np.real(s.lengths), boundary[0])
        if proof is None:
            out.append(s)
            continue
        k = boundary[0]
        reasons = [r for r in (c.reason or "").split("; ") if r and r != boundary_reason(k)]
        signs = list(c.tension_signs)
        signs[k] = ZERO
        lo, hi = np.array(c.tension_lower, float), np.array(c.tension_upper, float)
        lo[k] = hi[k] = 0.0
        cert = replace(c, certified=not reasons, reason="; ".join(reasons) or None, tension_signs=tuple(signs),
                       tension_lower=lo, tension_upper=hi, extra={**c.extra, "zero_tension": proof.to_dict()})
        tensions = np.array(s.tensions)
        tensions[k] = 0  # the proven value (the float one was within rounding of it)
        out.append(replace(s, tensions=tensions, certified=cert.certified, certificate=cert))
    return out
