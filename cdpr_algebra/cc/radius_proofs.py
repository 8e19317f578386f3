"""Interval proofs for a robustness radius (Merlet): the minimizing critical point certified by Krawczyk (arb) on the
Lagrange system of the enclosed cubic, and its nearest-ness proven by interval exclusion of every other critical
point within the proven lower bound."""

from __future__ import annotations

import itertools
import numpy as np

from cdpr_algebra.generated.cubic_distance import CRITICAL_SET_ROWS, MONOMIALS, lagrange_system
from .cubic_distances import _NODES


# ---------------------------------------------------------------------------------------------------------------
# interval certificate of the minimizing critical point


def arb_cubic(robot, position, rotation, cables, column, scale) -> list:
    """Rigorous enclosures (arb balls) of the 20 coefficients of |M| (``column`` None) or |M_column| in
    y = (x - x0) / scale, from arb determinants on the 4x4x4 grid and an arb inverse Vandermonde matrix (the
    doubles of the robot file, the pose and the nodes are taken as exact; the degree bound 3 is a theorem)."""
    from flint import arb, arb_mat

    G = [arb(float(v)) for v in position]
    R = np.asarray(rotation, dtype=float)
    Rm = arb_mat(R.tolist())
    h = arb(float(scale))
    cols_data = []
    for i in cables:
        c = Rm * arb_mat([[float(v)] for v in (robot.platform[i] - robot.com)])
        # c_i = R (b_i' - g'): b' - g' rounded to a double first (the value the float code uses too)
        cols_data.append(([arb(float(v)) for v in robot.base[i]], [c[k, 0] for k in range(3)]))
    d = [arb(float(v)) for v in robot.load_direction] + [arb(0)] * 3
    V = arb_mat([[float(n) ** p for p in range(4)] for n in _NODES]).inv()
    D = np.empty((4, 4, 4), dtype=object)
    for a_, b_, c_ in itertools.product(range(4), repeat=3):
        x = [G[0] + h * float(_NODES[a_]), G[1] + h * float(_NODES[b_]), G[2] + h * float(_NODES[c_])]
        M = arb_mat(6, 6)
        for j, (A, c) in enumerate(cols_data):
            if column is not None and j == column:
                col = d
            else:
                s_ = [A[k] - x[k] - c[k] for k in range(3)]
                col = s_ + [c[1] * s_[2] - c[2] * s_[1], c[2] * s_[0] - c[0] * s_[2], c[0] * s_[1] - c[1] * s_[0]]
            for i in range(6):
                M[i, j] = col[i]
        D[a_, b_, c_] = M.det()
    out = []
    for (i, j, k) in MONOMIALS:
        acc = arb(0)
        for a_, b_, c_ in itertools.product(range(4), repeat=3):
            acc += V[i, a_] * V[j, b_] * V[k, c_] * D[a_, b_, c_]
        out.append(acc)
    return out


def _lagrange_evaluators(c):
    """F(y, lam) = (y - lam grad P(y), P(y)) and its Jacobian (4 rows) for P = sum c_m y^m, from the generated
    :func:`cdpr_algebra.generated.cubic_distance.lagrange_system` (plain arithmetic: floats or arb balls)."""
    c = list(c)

    def F(x):
        return list(lagrange_system(x[0], x[1], x[2], x[3], *c)[:4])

    def J(x):
        v = lagrange_system(x[0], x[1], x[2], x[3], *c)[4:]
        return [list(v[4 * r:4 * r + 4]) for r in range(4)]

    return F, J


def certify_radius(robot, position, rotation, cables, column, scale, point) -> dict:
    """Interval certificate of a radius: Krawczyk (:func:`cdpr_algebra.intervals.balls.krawczyk_certify`) on the Lagrange system of
    the rigorously enclosed cubic (:func:`arb_cubic`) around the critical point ``point`` (world frame).

    Returns {"proven": bool, "radius_enclosure": [lo, hi] or None, "reason": str or None}: proven means there is
    exactly one critical point of the distance to the TRUE surface in a tiny box around ``point`` and its
    distance to the pose lies in the enclosure.  (That no other point is nearer: :func:`prove_nearest`.)"""
    from flint import arb

    from cdpr_algebra.intervals.balls import krawczyk_certify, lower, upper

    cb = arb_cubic(robot, position, rotation, cables, column, scale)
    y = (np.asarray(point, dtype=float) - np.asarray(position, dtype=float)) / scale
    cf = np.array([float(v) for v in cb])
    Ff, Jf = _lagrange_evaluators(cf)
    G = -np.array(Jf(list(y) + [0.0]), dtype=float)[:3, 3]  # the last column of J is -grad P
    lam = float(y @ G / (G @ G))
    x0 = np.concatenate([y, [lam]])
    F, J = _lagrange_evaluators(cb)
    res = krawczyk_certify(F, J, x0, np.array([1.0, 1.0, 1.0, max(abs(lam), 1e-300)]) * 1.0,
                           max_rel_width=1e-8, F_float=lambda x: np.array(Ff(list(x)), dtype=float),
                           J_float=lambda x: np.array(Jf(list(x)), dtype=float))
    if not res.proven:
        return {"proven": False, "radius_enclosure": None, "reason": res.reason}
    enc = res.enclosure
    r = (enc[0] * enc[0] + enc[1] * enc[1] + enc[2] * enc[2]).sqrt() * arb(float(scale))
    return {"proven": True, "radius_enclosure": [lower(r), upper(r)], "reason": None}


# ---------------------------------------------------------------------------------------------------------------
# proof that no point of the seven surfaces is nearer (interval exclusion of the distance's critical points)

NEAREST_REL_GAP = 1e-9  # the proven lower bound is (1 - this) times the lower end of the certified distance
NEAREST_MAX_BOXES = 200_000  # boxes per cubic before giving up (then nearest-ness stays a float search)


def critical_set_coefficients(coef_lo, coef_hi):
    """Rigorous (mid, rad) coefficient rows (16, 20) over MONOMIALS of the polynomials of the critical set
    C = {P = 0, y x grad P = 0} and their derivatives (:data:`cdpr_algebra.generated.cubic_distance.CRITICAL_SET_ROWS`,
    integer maps of the cubic's coefficients), for every cubic with coefficients in [coef_lo, coef_hi]."""
    from cdpr_algebra.intervals.arithmetic import Interval
    from cdpr_algebra.intervals.operators import midrad, mr_matmul

    L = np.array(CRITICAL_SET_ROWS, dtype=float)  # (16, 20, 20), small integers: exact
    cm, cr = midrad(Interval(np.asarray(coef_lo, dtype=float), np.asarray(coef_hi, dtype=float)))
    rows = mr_matmul(L.reshape(-1, L.shape[-1]), None, cm[:, None], cr[:, None])
    return midrad(Interval(rows.lo.reshape(L.shape[:2]), rows.hi.reshape(L.shape[:2])))


_MONO_INDEX = {e: k for k, e in enumerate(MONOMIALS)}
_MONO = np.array(MONOMIALS)


def _monomials(lo, hi):
    """Enclosures of the 20 monomials over n boxes (lo, hi of shape (n, 3)): an Interval of shape (n, 20)."""
    from cdpr_algebra.intervals.arithmetic import Interval

    n = len(lo)
    plo, phi = np.ones((n, 3, 4)), np.ones((n, 3, 4))
    Y = Interval(lo, hi)
    Y2 = Y.sqr()
    Y3 = Y2 * Y
    for p, Yp in ((1, Y), (2, Y2), (3, Y3)):
        plo[:, :, p], phi[:, :, p] = Yp.lo, Yp.hi
    parts = [Interval(plo[:, v, _MONO[:, v]], phi[:, v, _MONO[:, v]]) for v in range(3)]
    out = parts[0]
    for v in (1, 2):
        exact = _MONO[:, v] == 0  # factor 1: no widening
        prod = out * parts[v]
        out = Interval(np.where(exact, out.lo, prod.lo), np.where(exact, out.hi, prod.hi))
    return out


def exclude_critical_points(coef_lo, coef_hi, radius: float, max_boxes: int | None = None):
    """Interval proof that the cubic P (coefficients in [coef_lo, coef_hi], MONOMIALS order, any cubic of the box)
    has no point of C = {P(y) = 0, y x grad P(y) = 0} with |y| < ``radius``.  Returns (proven, boxes).

    Why this bounds the distance: the distance from 0 to the closed set {P = 0} is attained at some y*; where
    grad P(y*) != 0 the surface is smooth there and y* is parallel to grad P(y*) (Lagrange), otherwise y* is a
    singular point; either way y* is in C (and y* != 0 when P(0) != 0).  So C empty in the open ball means
    dist(0, {P = 0}) >= ``radius``.  Branch and bound over the cube [-radius, radius]^3 in outward-rounded interval
    arithmetic (:mod:`cdpr_algebra.intervals.arithmetic`; the four functions and their gradients as interval coefficient matrices on
    the monomials, products by :func:`cdpr_algebra.intervals.arithmetic.mr_matmul`): a box is discarded when it misses the open ball,
    or when the enclosure of P or of a component of y x grad P excludes 0 (each enclosure is the intersection of the
    natural and the mean-value forms); other boxes are bisected along their widest side."""
    from cdpr_algebra.intervals.arithmetic import Interval, up
    from cdpr_algebra.intervals.operators import midrad, mr_matmul

    max_boxes = NEAREST_MAX_BOXES if max_boxes is None else max_boxes
    if not np.isfinite(radius):  # no finite radius to prove (e.g. the float search failed): nothing proven
        return False, 0
    Cm, Cr = critical_set_coefficients(coef_lo, coef_hi)  # 4 functions, then d/dy_v of each
    CmT, CrT = np.ascontiguousarray(Cm.T), np.ascontiguousarray(Cr.T)
    nf = 4
    r2 = float(up(radius * radius))
    lo = np.full((1, 3), -float(radius))
    hi = np.full((1, 3), float(radius))
    boxes = 0
    while len(lo):
        boxes += len(lo)
        if boxes > max_boxes or np.max(hi - lo) < 1e-13 * radius:
            return False, boxes
        c = 0.5 * (lo + hi)
        MY = _monomials(lo, hi)
        Mm, Mr = midrad(MY)
        vals = mr_matmul(Mm, Mr, CmT, CrT)  # (n, 16): the functions and their derivatives over the boxes
        Mcm, Mcr = midrad(_monomials(c, c))
        fc = mr_matmul(Mcm, Mcr, CmT[:, :nf], CrT[:, :nf])
        mv = fc
        for v in range(3):
            dv = Interval(lo[:, v], hi[:, v]) - c[:, v]
            mv = mv + vals[:, nf * (v + 1):nf * (v + 2)] * Interval(dv.lo[:, None], dv.hi[:, None])
        enc = vals[:, :nf].intersect(mv)
        sq = (MY[:, _MONO_INDEX[(2, 0, 0)]] + MY[:, _MONO_INDEX[(0, 2, 0)]]) + MY[:, _MONO_INDEX[(0, 0, 2)]]
        keep = (sq.lo < r2) & ~np.any((enc.lo > 0) | (enc.hi < 0), axis=1)
        lo, hi = lo[keep], hi[keep]
        if not len(lo):
            break
        k = np.argmax(hi - lo, axis=1)
        idx = np.arange(len(lo))
        mid = 0.5 * (lo[idx, k] + hi[idx, k])
        hi1, lo2 = hi.copy(), lo.copy()
        hi1[idx, k] = mid
        lo2[idx, k] = mid
        lo, hi = np.vstack([lo, lo2]), np.vstack([hi1, hi])
    return True, boxes


def prove_nearest(robot, position, rotation, cables, scale, radius, max_boxes: int | None = None) -> dict:
    """Interval proof that none of the seven surfaces of the 6-cable CC ``cables`` ({|M_i| = 0} for each cable and
    {|M| = 0}) comes within ``radius`` (world units) of the pose: :func:`exclude_critical_points` on each rigorously
    enclosed cubic (:func:`arb_cubic`).  Returns {"proven", "lower_bound" (a double <= the proven radius), "boxes",
    "reason"}."""
    from cdpr_algebra.intervals.balls import lower, upper

    from cdpr_algebra.intervals.arithmetic import down

    rs = float(radius) / float(scale)
    lower_bound = float(down(rs * float(scale)))
    total = 0
    for column in [None] + list(range(6)):
        cb = arb_cubic(robot, position, rotation, cables, column, scale)
        ok, nb_ = exclude_critical_points(np.array([lower(v) for v in cb]), np.array([upper(v) for v in cb]), rs,
                                          max_boxes)
        total += nb_
        if not ok:
            what = "the singularity surface" if column is None else f"the surface tau_{cables[column] + 1} = 0"
            return {"proven": False, "lower_bound": None, "boxes": total,
                    "reason": f"interval exclusion inconclusive for {what} within {radius:.10g} ({nb_} boxes)"}
    return {"proven": True, "lower_bound": max(lower_bound, 0.0), "boxes": total, "reason": None}
