"""First criterion of seed 002 (Sec. II-B.1): how far the platform can translate from a pose, at constant
orientation, before a 6-cable configuration (CC) stops being valid.

For each cable i of the CC the radius r_i is the distance from the pose to the surface {tau_i = 0}, i.e.
{|J_i^{-T}| = 0} (Cramer's numerator: column i of the wrench matrix replaced by the load wrench); r_d is the
distance to the singularity surface {|J^{-T}| = 0}; r_min = min(r_i, r_d).  The CC is valid in the open ball of
radius r_min (the tensions are continuous and keep their sign there) and not beyond.

**Polynomials.**  With constant orientation, B_i = x + c_i (x the position of G, c_i = R (b_i' - g')), every column
(A_i - B_i ; c_i x (A_i - B_i)) of the wrench matrix M (moments about G, unnormalized; the 1/rho_i factors do not
change the zero sets, seed 002 Sec. II-B.1) is affine in x, and the load column is (d ; 0).  In a Laplace expansion
along the three force rows, a 3x3 force minor is affine in x (det(a - x, b - x, e - x) loses its x-quadratic and
cubic terms) and a 3x3 moment minor det(c_j x (a_j - x), ...) is at most quadratic (its cubic part
det(c_1 x x, c_2 x x, c_3 x x) vanishes: three vectors orthogonal to x).  So |M| and every |M_i| are polynomials of
total degree <= 3 in x (the constant-orientation singularity surface is a cubic).  They are computed exactly (up to
rounding) by tensor-product interpolation of the determinant on 4 x 4 x 4 Chebyshev nodes around the pose
(degree <= 3 in each variable), in the scaled coordinate y = (x - x0) / h; the monomials of total degree > 3 must
come out zero, which is checked.  No symbolic work: all polynomials of all CCs of a pose cost one batch of
6x6 determinants.

**Distances: all critical points.**  Seed 002's Lagrangian (eqs. 3-4), H = r + alpha P(x0 + r u) + beta (|u|^2 - 1),
has as critical points exactly the points z = x0 + r u of {P = 0} where u is parallel to grad P, i.e. the critical
points of the distance on the smooth part of the surface.  We solve the equivalent (same critical points,
fewer paths) Lagrange system of min |y|^2 s.t. P(x0 + h y) = 0:

    y_k - lam dP/dy_k (y) = 0  (k = 1, 2, 3),   P(y) = 0,

homogenized in (y0 : y) and in (mu : lam) (on random affine charts): mu y0 y_k - lam dP^h/dy_k = 0,
P^h(y0, y) = 0.  In P^3 x P^1 every solution is a finite chart point: y0 = 0 are solutions at infinity (dropped);
mu = 0 are the singular points of the surface (grad P = 0 on P = 0), which are candidates too (the Lagrange
condition does not hold there); the rest are the critical points.  Since the minimum of the distance to a closed
set is attained, it is at a smooth critical point or at a singular point, so the smallest real candidate is the
global minimum.  A generic cubic has 21 critical points (the Euclidean distance degree d (1 + (d-1) + (d-1)^2)).

**Homotopy.**  The family (parameters: the 20 coefficients of a cubic) is solved once for random complex
coefficients c1 with the engine (:func:`cdpr_algebra.homotopy.endgame.track_paths`) from a 2-homogeneous linear-product start
system (36 paths: 21 solutions, 15 paths end on the spurious component y0 = lam = 0 at infinity), then every
polynomial of interest is reached by the parameter homotopy c(t) = t c1 + (1 - t) c0 (coefficient-parameter
homotopy: every isolated solution of the target in P^3 x P^1 is the end of one of the 21 paths).  All the
polynomials of a computation are tracked in ONE vectorized run: each path carries the index of its polynomial as
an extra coordinate k / 1024 that the homotopy keeps constant (equation k - round(k), dH/dt = 0), because the
tracker evaluates subsets of paths without their indices.  Evaluation is hand-written numpy over monomial tables
(the equations are linear in the coefficients, so dH/dt = dF/dc (c1 - c0) costs one contraction).

Real critical points are polished by Newton in real arithmetic.  With ``certify=True`` r_min gets two separate
proofs (``CCRadii.radius_certificate``):

* **critical point** (:func:`certify_radius`): the cubic's coefficients enclosed by arb determinants, then the
  Krawczyk test of :mod:`cdpr_algebra.intervals.balls` on the Lagrange system: a true critical point of the true surface exists at a
  distance in ``radius_enclosure`` -- so r_min <= its upper end;
* **nearest** (:func:`prove_nearest`): the homotopy's minimum alone is a floating-point search (a failed or jumped
  path could hide a nearer point), so every one of the seven enclosed cubics is shown, by an interval branch and
  bound, to have no critical point of the distance (nor singular point) in the open ball of radius
  (1 - ``NEAREST_REL_GAP``) times the certified lower end -- so r_min >= that radius.

``certified`` is True only when both hold: r_min then lies in ``proven_interval`` (relative width ~1e-9).  When the
exclusion does not finish (``NEAREST_MAX_BOXES``), ``nearest`` is reported as "float search" and ``certified`` is
False.  The other per-cable radii are floating-point values.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .configurations import check_pose, parse_cables, wrench_columns
from .cubic_distances import MONOMIALS, _GRID, _VINV, distance_to_cubics, evaluate_cubic
from .radius_proofs import NEAREST_MAX_BOXES, NEAREST_REL_GAP, arb_cubic, certify_radius, prove_nearest
from cdpr_algebra.report.jsonable import jsonable

__all__ = ["MONOMIALS", "CCPolynomials", "CCRadii", "cc_polynomials", "cc_radii",
           "cc_radii_many", "distance_to_cubics", "certify_radius", "arb_cubic", "evaluate_cubic"]


# ---------------------------------------------------------------------------------------------------------------
# the polynomials of a CC and its radii


@dataclass(frozen=True)
class CCPolynomials:
    """|M| (row 0) and |M_i| (rows 1..6, cable order of ``cables``) as cubics in y = (x - x0) / h."""

    cables: tuple  # 0-based
    position: np.ndarray  # x0 (G)
    rotation: np.ndarray
    scale: float  # h
    coefficients: np.ndarray  # (7, 20)
    truncation: float  # largest dropped coefficient (degree > 3) relative to the largest kept


def _interpolate(values):
    """Tensor-product interpolation on the 4x4x4 Chebyshev grid: (..., 64) values -> (..., 4, 4, 4) coefficients
    of y1^i y2^j y3^k."""
    T = values.reshape(values.shape[:-1] + (4, 4, 4))
    return np.einsum("ai,bj,ck,...ijk->...abc", _VINV, _VINV, _VINV, T)


def polynomials_batch(robot, positions, rotations, cable_sets, scale):
    """Coefficients (K, 7, 20) of |M| and the six |M_i| for K (pose, CC) pairs, and the truncation check."""
    K = len(cable_sets)
    mats = []
    d6 = np.concatenate([robot.load_direction, np.zeros(3)])
    for x0, R, S in zip(positions, rotations, cable_sets):
        W, _, _ = wrench_columns(robot, x0 + scale * _GRID, R)  # (64, 6, n)
        M = W[:, :, list(S)]
        stack = [M]
        for i in range(6):
            Mi = M.copy()
            Mi[:, :, i] = d6
            stack.append(Mi)
        mats.append(np.stack(stack))  # (7, 64, 6, 6)
    D = np.linalg.det(np.stack(mats))  # (K, 7, 64)
    T = _interpolate(D)  # (K, 7, 4, 4, 4)
    coef = np.stack([T[..., i, j, k] for (i, j, k) in MONOMIALS], axis=-1)
    mask = np.ones((4, 4, 4), bool)
    for (i, j, k) in MONOMIALS:
        mask[i, j, k] = False
    dropped = np.abs(T[..., mask]).max(axis=-1) / np.maximum(np.abs(coef).max(axis=-1), 1e-300)
    return coef, dropped.reshape(K, 7)


def cc_polynomials(robot, position, cables, rotation=None, scale: float | None = None) -> CCPolynomials:
    """The seven cubics of a 6-cable CC (0-based ``cables``) around the pose (see the module doc)."""
    G, R = check_pose(robot, position, rotation)
    h = _default_scale(robot) if scale is None else float(scale)
    coef, dropped = polynomials_batch(robot, [G], [R], [tuple(cables)], h)
    return CCPolynomials(tuple(cables), G, R, h, coef[0], float(dropped[0].max()))


def _default_scale(robot) -> float:
    return robot.size / 10.0


def radii_by_number(radii: dict, singular) -> dict:
    """{"<cable number>": r, ..., "singular": r} from {0-based cable: r} and the distance to the singularity (the
    JSON contract of radii at a pose and along a path)."""
    d = {str(c + 1): float(r) for c, r in radii.items()}
    d["singular"] = float(singular)
    return d


@dataclass(frozen=True)
class CCRadii:
    """Radii of the first criterion for one 6-cable CC at one pose (cables 0-based; 1-based in ``to_dict``).

    ``radii[i]`` distance to {tau_i = 0} for cable i of the CC, ``singular`` distance to {|J^-T| = 0},
    ``rmin`` their minimum and ``limiting`` what attains it (a cable index or 'singular'); ``nearest`` the point of
    the limiting surface nearest to the pose (world frame); ``points`` the nearest point of every surface;
    ``failed_paths`` paths that did not finish; ``certified``: r_min proven (its critical point certified and no
    point of the seven surfaces nearer, see the module docstring; None when not run); ``radius_certificate`` says
    which part is proven: {"critical_point": "certified" | "not certified", "nearest": "proven" | "float search",
    "radius_enclosure", "proven_interval", "proven_lower_bound", "homotopy_failed_paths"}."""

    cables: tuple
    position: np.ndarray
    rotation: np.ndarray
    tensions: np.ndarray
    radii: dict
    singular: float
    rmin: float
    limiting: object
    nearest: np.ndarray
    points: dict
    failed_paths: int
    seconds: float
    certified: bool | None = None
    certificate: dict | None = field(default=None, compare=False)
    radius_certificate: dict | None = field(default=None, compare=False)
    seed: int = 0  # of the generic instance and the homotopies (with the robot and pose: what reproduces it)

    def radii_by_number(self) -> dict:
        """{"<cable number>": r, ..., "singular": r} (the JSON contract)."""
        return radii_by_number(self.radii, self.singular)

    @property
    def status(self) -> str:
        """'certified' (r_min proven: critical point and nearest-ness), 'critical point certified' (nearest-ness a
        float search), 'incomplete' (homotopy paths failed, r_min not certified) or 'float search'."""
        if self.certified:
            return "certified"
        if self.failed_paths:
            return "incomplete"
        rc = self.radius_certificate or {}
        return "critical point certified" if rc.get("critical_point") == "certified" else "float search"

    def to_dict(self) -> dict:
        return jsonable({"status": self.status, "cables": [c + 1 for c in self.cables], "position": self.position,
                         "tensions": self.tensions, "radii": self.radii_by_number(), "rmin": self.rmin,
                         "limiting": self.limiting + 1 if isinstance(self.limiting, (int, np.integer)) else self.limiting,
                         "nearest": self.nearest, "failed_paths": self.failed_paths, "certified": self.certified,
                         "radius_certificate": self.radius_certificate, "certificate": self.certificate,
                         "seconds": self.seconds, "seed": self.seed})


def cc_radii_many(robot, requests, scale: float | None = None, seed: int = 0, certify: bool = False,
                  nearest_max_boxes: int = NEAREST_MAX_BOXES) -> list[CCRadii]:
    """Radii of many (position, 0-based cables[, rotation]) requests in one batched homotopy run; ``certify``: the
    interval certificate of each r_min, the proof of nearest-ness giving up after ``nearest_max_boxes`` boxes per
    cubic (then "float search")."""
    t0 = time.perf_counter()
    h = _default_scale(robot) if scale is None else float(scale)
    Gs, Rs, Ss = [], [], []
    for req in requests:
        pos, cables = req[0], req[1]
        rot = req[2] if len(req) > 2 else None
        G, R = check_pose(robot, pos, rot)
        S = tuple(cables)
        if len(S) != 6:
            from cdpr_algebra.model.errors import CdprInputError

            raise CdprInputError("cables", f"the radii are defined for 6-cable configurations, got {len(S)} cables")
        Gs.append(G)
        Rs.append(R)
        Ss.append(S)
    coef, dropped = polynomials_batch(robot, Gs, Rs, Ss, h)
    if np.any(dropped > 1e-8):
        raise ArithmeticError(f"determinant not a cubic in the position (relative dropped terms {dropped.max():.1e})")
    crit = distance_to_cubics(coef.reshape(-1, 20), seed=seed)
    out = []
    shared = (time.perf_counter() - t0) / max(1, len(requests))
    for q, (G, R, S) in enumerate(zip(Gs, Rs, Ss)):
        cd = crit[7 * q:7 * q + 7]
        from .configurations import configuration_tensions

        tau = configuration_tensions(robot, G, S, R).tensions
        radii = {S[i]: h * cd[i + 1].minimum for i in range(6)}
        sing = h * cd[0].minimum
        points = {S[i]: (G + h * cd[i + 1].points[0]) if len(cd[i + 1].points) else None for i in range(6)}
        points["singular"] = (G + h * cd[0].points[0]) if len(cd[0].points) else None
        which = min(list(radii) + ["singular"], key=lambda k: radii[k] if k != "singular" else sing)
        rmin = sing if which == "singular" else radii[which]
        res = CCRadii(S, G, R, tau, radii, sing, rmin, which, points[which], points,
                      sum(c.failed for c in cd), shared, seed=seed)
        if certify:
            res = _with_certificate(res, robot, h, nearest_max_boxes)
        out.append(res)
    return out


def cc_radii(robot, position, cables, rotation=None, scale: float | None = None, seed: int = 0,
             certify: bool = False, nearest_max_boxes: int = NEAREST_MAX_BOXES) -> CCRadii:
    """Merlet Sec. II-B.1 for one 6-cable CC given by 1-based cable numbers (e.g. [1, 2, 3, 4, 5, 6])."""
    S = parse_cables(robot, cables, "configuration", size=6)
    return cc_radii_many(robot, [(position, S, rotation)], scale, seed, certify, nearest_max_boxes)[0]




def _with_certificate(res: CCRadii, robot, h: float, max_boxes: int = NEAREST_MAX_BOXES) -> CCRadii:
    """Certify the minimizing critical point (Krawczyk) and prove that it is the nearest (interval exclusion, within a
    relative ``NEAREST_REL_GAP`` of the certified distance); ``certified`` when both are proven."""
    from dataclasses import replace

    which = res.limiting
    column = None if which == "singular" else res.cables.index(which)
    cert = certify_radius(robot, res.position, res.rotation, res.cables, column, h, res.nearest)
    base = cert["radius_enclosure"][0] if cert["proven"] else float(res.rmin)
    near = prove_nearest(robot, res.position, res.rotation, res.cables, h, (1.0 - NEAREST_REL_GAP) * base, max_boxes)
    cert["method"] = ("critical point: Krawczyk (arb) on the Lagrange system of the enclosed cubic; nearest: interval "
                      "exclusion of every critical point of the distance to the seven enclosed cubics within the "
                      "proven lower bound")
    cert["failed_paths"] = res.failed_paths
    cert["nearest_proof"] = near
    rc = {"critical_point": "certified" if cert["proven"] else "not certified",
          "nearest": "proven" if near["proven"] else "float search",
          "radius_enclosure": cert["radius_enclosure"],
          "proven_interval": ([near["lower_bound"], cert["radius_enclosure"][1]]
                              if near["proven"] and cert["proven"] else None),
          "proven_lower_bound": near["lower_bound"],
          "homotopy_failed_paths": res.failed_paths}
    return replace(res, certified=bool(cert["proven"] and near["proven"]), certificate=cert, radius_certificate=rc)
