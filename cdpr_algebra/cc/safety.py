"""Second criterion of seed 002 (Sec. II-C, IV-B): is there, near the pose, an equilibrium of a cable
configuration with fewer than 6 cables taken from the current 6-cable CC?  (A small disturbance could then take the
robot from the CC to that sub-configuration.)

"Near" is the ball of radius R around the pose X = (G, R0) in the paper's pose coordinates (position in length
units, orientation in radians): d(X, X') = sqrt(|G' - G|^2 + theta^2), theta the angle of R0^T R'.

**Interval exclusion (rigorous, fast).**  If a sub-configuration S (a proper subset of the CC) balanced the load at
a pose X', then the square statics of the full CC at X', M(X') lam = -Q (d ; 0) (columns (A_i - B_i ;
(B_i - G) x (A_i - B_i)), moments about G), would have a solution with lam_j = 0 for the cables j not in S; when
M(X') is nonsingular that solution is THE solution.  So if every lam_j is proven > 0 for every pose of a box
containing the ball, no sub-configuration (whatever its cable lengths) has an equilibrium there.  The box is
G +- R per coordinate and Rodrigues parameters e in [-tan(R/2), tan(R/2)]^3 (R' = R0 R(e), seed 004 eq. 20 with
e0 = 1), which contains every rotation of angle <= R; on each box the tensions are enclosed by the Krawczyk test of
:mod:`cdpr_algebra.intervals.balls` on the linear system (interval matrix from arb arithmetic), and boxes that fail are bisected.

**DGP search (the paper's statement, slower).**  For every proper subset S of the CC, the direct geometrico-static
problem of the CC's cables with the lengths of the pose (:func:`cdpr_algebra.dgp.solve_taut_set`; cables outside the CC are
slack by control and left out) gives every admissible equilibrium with exactly S taut; the nearest one is reported.
It is run when the exclusion fails (to decide) or on request (``nearest=True``).

**What the result proves** (``safe``, ``method``, ``status``):

* ``safe = True``, method "interval exclusion proof": proven, no sub-configuration equilibrium within the radius.
* ``safe = False``, method "homotopy search": a verified counterexample -- an equilibrium of a sub-configuration
  certified by its interval certificate (:mod:`cdpr_algebra.certificates.equilibria`: existence, uniqueness, positive tensions, slack cables)
  whose distance to the pose, bounded from above in ball arithmetic over the certified box, is <= the radius.
* ``safe = None`` otherwise: the homotopy search found no sub-configuration equilibrium within the radius (not a
  proof: the homotopy is a floating-point search), or found one it could not verify; ``status`` says which.
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass

import numpy as np

from .configurations import check_pose, configuration_tensions
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.report.jsonable import jsonable

__all__ = ["SafetyResult", "pose_distance", "exclusion_proof", "exclusion_radius", "sub_configuration_equilibria", "safety",
           "distance_upper_bound", "PROOF", "SEARCH"]

PROOF = "interval exclusion proof"
SEARCH = "homotopy search"


def pose_distance(G0, R0, G1, R1) -> tuple[float, float, float]:
    """(d, |G1 - G0|, theta): d = sqrt(|dG|^2 + theta^2), theta the rotation angle of R0^T R1 (radians)."""
    dp = float(np.linalg.norm(np.asarray(G1, float) - np.asarray(G0, float)))
    c = (np.trace(np.asarray(R0, float).T @ np.asarray(R1, float)) - 1.0) / 2.0
    th = float(np.arccos(np.clip(c, -1.0, 1.0)))
    return float(np.hypot(dp, th)), dp, th


# ------------------------------------------------------------------------------------------ interval exclusion


def _wrench_box(robot, cables, R0, lo, hi):
    """arb 6x6 wrench matrix over the pose box (lo, hi) = (G (3), e (3)) and its midpoint float matrix."""
    from flint import arb, arb_mat

    mid = 0.5 * (lo + hi)
    rad = 0.5 * (hi - lo)
    G = [arb(float(m), float(r)) for m, r in zip(mid[:3], rad[:3])]
    e = [arb(float(m), float(r)) for m, r in zip(mid[3:], rad[3:])]
    n2 = 1 + e[0] * e[0] + e[1] * e[1] + e[2] * e[2]
    E = [[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]]
    EE = [[sum(E[i][k] * E[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    Re = [[(1 if i == j else 0) + 2 * (E[i][j] + EE[i][j]) / n2 for j in range(3)] for i in range(3)]
    R = [[sum(float(R0[i, k]) * Re[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    M = arb_mat(6, 6)
    for j, i in enumerate(cables):
        bp = robot.platform[i] - robot.com
        c = [sum(R[a][k] * float(bp[k]) for k in range(3)) for a in range(3)]
        s = [float(robot.base[i][k]) - G[k] - c[k] for k in range(3)]
        col = s + [c[1] * s[2] - c[2] * s[1], c[2] * s[0] - c[0] * s[2], c[0] * s[1] - c[1] * s[0]]
        for a in range(6):
            M[a, j] = col[a]
    # float midpoint matrix (the point pose at the box centre)
    from cdpr_algebra.model.pose import matrix_from_rodrigues

    Rm = np.asarray(R0) @ matrix_from_rodrigues(*mid[3:])
    c = (robot.platform[list(cables)] - robot.com) @ Rm.T
    s = robot.base[list(cables)] - (mid[:3] + c)
    Mm = np.vstack([s.T, np.cross(c, s).T])
    return M, Mm


def _positive_on_box(robot, cables, R0, rhs, lo, hi):
    """True: every lam_j > 0 proven on the box; False: a point of the box (its centre) has some lam_j <= 0 or a
    singular matrix; None: undecided (bisect)."""
    from cdpr_algebra.intervals.balls import krawczyk_certify

    M, Mm = _wrench_box(robot, cables, R0, lo, hi)
    try:
        lam = np.linalg.solve(Mm, rhs)
    except np.linalg.LinAlgError:
        return False
    if not np.all(lam > 0):
        return False

    def F(x):
        return [sum(M[i, j] * x[j] for j in range(6)) - float(rhs[i]) for i in range(6)]

    def J(x):
        return [[M[i, j] for j in range(6)] for i in range(6)]

    res = krawczyk_certify(F, J, lam, np.abs(lam), max_rel_width=4.0, F_float=lambda x: Mm @ x - rhs,
                           J_float=lambda x: Mm)
    if res.proven and all(v > 0 for v in res.enclosure):
        return True
    return None


def exclusion_proof(robot, position, cables, rotation=None, radius: float = 0.03, max_boxes: int = 20000):
    """Interval proof that no proper subset of the 6-cable CC ``cables`` (0-based) balances the load at any pose
    within ``radius`` (see the module doc).  Returns (proven: bool | None, boxes, witness): proven True, or False
    with a witness pose (G, e) where some tension of the CC is <= 0, or None when ``max_boxes`` ran out."""
    G, R0 = check_pose(robot, position, rotation)
    rhs = -robot.load * np.concatenate([robot.load_direction, np.zeros(3)])
    te = np.tan(radius / 2)
    stack = [(np.concatenate([G - radius, [-te] * 3]), np.concatenate([G + radius, [te] * 3]))]
    weights = np.array([1, 1, 1, 2, 2, 2.0])  # e ~ theta / 2: compare widths in pose units
    boxes = 0
    while stack:
        lo, hi = stack.pop()
        boxes += 1
        if boxes > max_boxes:
            return None, boxes, None
        ok = _positive_on_box(robot, cables, R0, rhs, lo, hi)
        if ok is True:
            continue
        if ok is False:
            return False, boxes, 0.5 * (lo + hi)
        k = int(np.argmax((hi - lo) * weights))
        m = 0.5 * (lo[k] + hi[k])
        hi1, lo2 = hi.copy(), lo.copy()
        hi1[k], lo2[k] = m, m
        stack += [(lo2, hi), (lo, hi1)]
    return True, boxes, None


def exclusion_radius(robot, position, cables, rotation=None, start: float = 0.01, rel_tol: float = 0.1,
                     max_boxes: int = 5000) -> float:
    """The largest radius (within ``rel_tol``) for which :func:`exclusion_proof` succeeds: a proven lower bound of
    the distance from the pose to any sub-configuration equilibrium (0.0 if even ``start`` fails)."""
    lo, hi, r = 0.0, None, float(start)
    while hi is None and r < 10 * robot.size:
        if exclusion_proof(robot, position, cables, rotation, r, max_boxes)[0] is True:
            lo, r = r, 2 * r
        else:
            hi = r
    if hi is None:
        return lo
    while hi - lo > rel_tol * max(lo, start):
        mid = 0.5 * (lo + hi)
        if exclusion_proof(robot, position, cables, rotation, mid, max_boxes)[0] is True:
            lo = mid
        else:
            hi = mid
    return lo


# ------------------------------------------------------------------------------------------------- DGP search


def sub_configuration_equilibria(robot, position, cables, rotation=None, sizes=range(1, 6), seed: int = 0,
                                 progress=None) -> tuple[list, list]:
    """Every admissible equilibrium of every proper subset of the CC ``cables`` (0-based), with the CC's cables at
    their lengths at the pose (others left out: slack by control).  Returns ([(d, dpos, theta, S, DGPSolution)]
    sorted by d, [DGPSubproblem]); S and the solutions' ``taut`` are 1-based robot cable numbers."""
    from cdpr_algebra.dgp.solve import solve_taut_set

    G, R0 = check_pose(robot, position, rotation)
    cables = tuple(cables)
    sub = robot.subset(cables)
    c = (sub.platform - sub.com) @ R0.T
    rho = np.linalg.norm(sub.base - (G + c), axis=1)
    sub = sub.with_lengths(rho)
    found, subproblems = [], []
    sets = [S for m in sizes for S in itertools.combinations(range(len(cables)), m)]
    for k, S in enumerate(sets):
        sp_, sols = solve_taut_set(sub, rho, S, seed=seed)
        subproblems.append(sp_)
        for s in sols:
            G1 = s.position + s.rotation @ sub.com
            d, dp, th = pose_distance(G, R0, G1, s.rotation)
            found.append((d, dp, th, tuple(cables[i] + 1 for i in S), s))
        if progress is not None:
            progress(k + 1, len(sets), S, sp_)
    found.sort(key=lambda f: f[0])
    return found, subproblems


def distance_upper_bound(G0, R0, certificate, com) -> float | None:
    """An upper bound (ball arithmetic) of the pose distance d of :func:`pose_distance` from (G0, R0) to every pose in
    the certified box of a DGP certificate (``position_lower/upper``: platform origin p, ``rotation_lower/upper``: R;
    G = p + R com), or None without enclosures.  The angle theta of R0^T R is bounded by
    theta = 2 asin(|R - R0|_F / (2 sqrt 2)) (for rotations |R - R0|_F^2 = 4 (1 - cos theta) = 8 sin^2(theta / 2))."""
    from flint import arb

    from cdpr_algebra.intervals.balls import upper

    if certificate is None or not getattr(certificate, "exists_unique", False):
        return None
    plo, phi = np.asarray(certificate.position_lower, float), np.asarray(certificate.position_upper, float)
    Rlo, Rhi = np.asarray(certificate.rotation_lower, float), np.asarray(certificate.rotation_upper, float)
    if not (np.all(np.isfinite(plo)) and np.all(np.isfinite(Rlo))):
        return None

    def ball(lo, hi):
        return arb(0.5 * (float(lo) + float(hi)), 0.5 * (float(hi) - float(lo))) + arb(0, abs(float(hi)) * 1e-15 + 1e-300)

    p = [ball(plo[k], phi[k]) for k in range(3)]
    R = [[ball(Rlo[i, j], Rhi[i, j]) for j in range(3)] for i in range(3)]
    G1 = [p[i] + sum((R[i][j] * float(com[j]) for j in range(3)), arb(0)) for i in range(3)]
    dp2 = sum(((G1[k] - float(G0[k])) ** 2 for k in range(3)), arb(0))
    fro2 = sum(((R[i][j] - float(R0[i, j])) ** 2 for i in range(3) for j in range(3)), arb(0))
    s_hi = upper(fro2.sqrt() / (2 * arb(2).sqrt()))
    if not s_hi < 1:
        return None
    theta = 2 * arb(s_hi).asin()
    return upper((dp2 + theta * theta).sqrt())


@dataclass(frozen=True)
class SafetyResult:
    """Second criterion for one 6-cable CC (cables 0-based; 1-based in ``to_dict``).

    ``safe``: True only when proven (no sub-configuration equilibrium within ``radius``: interval exclusion), False
    only with a verified counterexample, None otherwise (see the module docstring); ``method``: the method that
    decided, :data:`PROOF` ("interval exclusion proof") or :data:`SEARCH` ("homotopy search"); ``status``: the
    result in words; ``boxes`` of the exclusion; ``nearest``: the nearest sub-configuration equilibrium found by the
    DGP search (None if not run or none found), with ``verified`` and ``distance_upper_bound``; ``subproblems``
    solved by the DGP search."""

    cables: tuple
    position: np.ndarray
    radius: float
    safe: bool | None
    method: str
    boxes: int
    nearest: dict | None
    subproblems: int
    failed_paths: int
    seconds: float
    status: str = ""
    counterexample_verified: bool | None = None

    @property
    def proven(self) -> bool:
        """The answer is proven (safe by the exclusion, or unsafe with a verified counterexample)."""
        return self.safe is not None

    def to_dict(self) -> dict:
        return jsonable({"cables": [c + 1 for c in self.cables], "radius": self.radius, "safe": self.safe,
                         "method": self.method, "proven": self.proven, "status": self.status,
                         "counterexample_verified": self.counterexample_verified, "boxes": self.boxes,
                         "nearest": self.nearest, "subproblems": self.subproblems, "failed_paths": self.failed_paths,
                         "seconds": self.seconds})


def safety(robot, position, cables, rotation=None, radius: float = 0.03, nearest: bool = False, seed: int = 0,
           max_boxes: int = 20000, progress=None) -> SafetyResult:
    """Seed 002 Sec. II-C for the 6-cable CC ``cables`` (0-based) at the pose: interval exclusion first; the DGP
    search when the exclusion fails or ``nearest`` is asked for (see the module docstring for what is proven)."""
    t0 = time.perf_counter()
    if not (np.isfinite(radius) and radius > 0):
        raise CdprInputError("radius", f"expected a radius > 0, got {radius}")
    G, R0 = check_pose(robot, position, rotation)
    cables = tuple(cables)
    if len(cables) != 6:
        raise CdprInputError("configuration", f"the second criterion is for 6-cable configurations, got {len(cables)}")
    if not configuration_tensions(robot, G, cables, R0).valid:
        raise CdprInputError("configuration", f"cables {[c + 1 for c in cables]} are not a valid CC at the pose")
    proven, boxes, _ = exclusion_proof(robot, G, cables, R0, radius, max_boxes)
    safe = True if proven else None
    method = PROOF if proven else SEARCH
    status = (f"proven safe: no sub-configuration equilibrium within {radius:g} ({PROOF}, {boxes} boxes)"
              if proven else "")
    verified = None
    near, nsub, failed = None, 0, 0
    if nearest or not proven:
        found, subs = sub_configuration_equilibria(robot, G, cables, R0, seed=seed, progress=progress)
        nsub = len(subs)
        failed = sum(getattr(s, "failed_paths", 0) for s in subs)
        if found:
            d, dp, th, S, s = found[0]
            bound = distance_upper_bound(G, R0, s.certificate, robot.com) if s.certified else None
            near = {"cables": list(S), "distance": d, "position_distance": dp, "rotation_angle": th,
                    "position": s.position + s.rotation @ robot.com, "angles": s.angles,
                    "tensions": [float(s.tensions[i]) for i in range(len(cables))], "stable": s.stable,
                    "certified": bool(s.certified), "distance_upper_bound": bound}
        if not proven:
            within = [f for f in found if f[0] <= radius]
            if within:
                # a verified counterexample: any equilibrium within the radius that is certified, with its distance
                # bounded by the radius over the certified box
                for d, dp, th, S, s in within:
                    bound = distance_upper_bound(G, R0, s.certificate, robot.com) if s.certified else None
                    if bound is not None and bound <= radius:
                        verified = True
                        safe = False
                        status = (f"unsafe: verified counterexample, cables {list(S)} in equilibrium at distance "
                                  f"<= {bound:.6g} (certified; {SEARCH})")
                        break
                else:
                    verified = False
                    status = (f"not proven: the {SEARCH} found a sub-configuration equilibrium at distance "
                              f"{within[0][0]:.6g} <= {radius:g} that its certificate does not verify")
            else:
                status = (f"not proven: no sub-configuration equilibrium found within {radius:g} by the {SEARCH} "
                          f"(a floating-point search, not a proof; the exclusion proof failed)"
                          + (f"; {failed} failed path(s)" if failed else ""))
    return SafetyResult(cables, G, float(radius), safe, method, boxes, near, nsub, failed, time.perf_counter() - t0,
                        status, verified)
