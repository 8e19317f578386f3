"""Uncertainty criterion of seed 002 (Sec. II-D, IV-D): does a 6-cable configuration (CC) stay valid for every real
robot whose geometry and cable lengths lie within given tolerances?

The controller computes the nominal lengths rho_i = |A_i B_i| of the CC's cables at the nominal pose X (G, R0)
from the nominal model; the real robot has exit points A^r in A +- dA, platform anchors b'^r in b' +- dB (platform
frame, the centre of mass g' being the frame's origin as in the paper) and cable lengths rho^r in rho +- drho (each
coordinate in its interval; cables outside the CC are slack by control).  The platform settles at the real
equilibrium X^r near X (seed 002: no change of CC on the way); the CC is valid there iff every tension is > 0.

**Proof (parametric Krawczyk).**  Unknowns z = (G^r, e, lam) (12): the position of G, Rodrigues parameters of
R0^T R^r (seed 004 eq. 20 with e0 = 1) and lam_i = tau_i / rho_i; equations (12): the six cable lengths
|A^r_i - G^r - R^r c^r_i|^2 = (rho^r_i)^2 (c^r_i = b'^r_i - g') and the statics sum lam_i (A^r_i - B^r_i ;
c_i x (A^r_i - B^r_i)) = -Q (d ; 0) (moments about G).  With the 42 parameters as arb balls, the Krawczyk test of
:mod:`cdpr_algebra.intervals.balls` proves that for EVERY parameter value in the box there is exactly one solution in the box found
(the real equilibrium near X and its tensions), and encloses it; if every lam_i of the enclosure is > 0 the CC is
valid for every robot in the ranges.  The mean-value form keeps the correlation between pose and tensions.  When the
test or the sign check fails, the parameter box is bisected (along the parameter with the largest first-order
effect on the weakest tension) up to ``max_boxes`` boxes.

**Counterexample.**  First-order worst case of each tension (parameters at the vertex given by the signs of
d lam_j / dP), followed by a few steps of the same local search; the candidate robot's equilibrium is recomputed
by Newton and, when a tension is <= 0 there, returned as a concrete counterexample (A^r, b'^r, rho^r, pose,
tensions, residual).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .configurations import check_pose, configuration_tensions
from cdpr_algebra.generated.rodrigues_equilibrium import rodrigues_equilibrium, rodrigues_lengths
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.report.jsonable import jsonable
from cdpr_algebra.model.pose import matrix_from_rodrigues, angles_from_matrix

__all__ = ["UncertaintyResult", "uncertainty_check", "equilibrium"]


def _flat(rows) -> list:
    return [v for row in rows for v in row]


def _equilibrium_values(z, A, c, rho, R0, f) -> tuple:
    """The generated 6-cable equilibrium system (:mod:`cdpr_algebra.generated.rodrigues_equilibrium`) at z = (G, e,
    lam): its 12 equations, then dF/dz row by row; plain arithmetic (floats or arb balls), q = 1 / (1 + e.e) formed
    in that arithmetic."""
    e = z[3:6]
    q = 1 / (1 + e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
    return rodrigues_equilibrium(*z, q, *_flat(A), *_flat(c), *rho, *_flat(R0), *f)


class _LengthModel:
    """The six cable-length equations f_i = |A_i - G - R c_i|^2 - rho_i^2 of the pose x = (G, e), their Jacobian
    and the wrench matrix (columns (s_i ; R c_i x s_i)): the first six rows of the generated equilibrium system and
    its statics block d(statics)/d lam (generated together as ``rodrigues_lengths``), for one parameter set.  Balls (lists) by default; with ``floats`` numpy
    arrays of floats (preconditioners and midpoints)."""

    def __init__(self, R0, A, c, rho, floats: bool = False):
        self.R0 = [[float(R0[i][j]) for j in range(3)] for i in range(3)]
        self.A, self.c, self.rho, self.floats = A, c, rho, floats

    def _values(self, x):
        x = [float(v) for v in x[:6]] if self.floats else list(x[:6])
        e = x[3:6]
        q = 1 / (1 + e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
        return rodrigues_lengths(*x, q, *_flat(self.A), *_flat(self.c), *self.rho, *_flat(self.R0))

    def _out(self, rows):
        return np.array(rows, dtype=float) if self.floats else rows

    def F(self, x):
        return self._out(list(self._values(x)[:6]))

    def J(self, x):
        v = self._values(x)
        return self._out([list(v[6 + 6 * r:12 + 6 * r]) for r in range(6)])

    def M(self, x):
        v = self._values(x)
        return self._out([list(v[42 + 6 * a:48 + 6 * a]) for a in range(6)])


def _system(R0, Q, d, A, c, rho):
    """F(z) and J(z) of the 12 equations (module doc; generated, :func:`_equilibrium_values`) for parameters
    A (6x3), c (6x3), rho (6) (floats or balls)."""
    R0 = [[float(R0[i][j]) for j in range(3)] for i in range(3)]
    rhs = [-Q * float(d[k]) for k in range(3)] + [0, 0, 0]

    def F(z):
        return list(_equilibrium_values(list(z), A, c, rho, R0, rhs)[:12])

    def J(z):
        v = _equilibrium_values(list(z), A, c, rho, R0, rhs)
        return [list(v[12 + 12 * r:24 + 12 * r]) for r in range(12)]

    return F, J


def equilibrium(robot, cables, R0, A, c, rho, z0, iters=30):
    """Newton on the 12 equations (floats) from z0; returns (z, residual)."""
    F, J = _system(R0, robot.load, robot.load_direction, A, c, rho)
    z = np.array(z0, dtype=float)
    for _ in range(iters):
        if not np.all(np.isfinite(z)) or np.abs(z[3:6]).max() > 1e3:
            return z, np.inf
        with np.errstate(all="ignore"):
            f = np.array(F(list(z)), dtype=float)
            Jm = np.array(J(list(z)), dtype=float)
        try:
            dz = np.linalg.solve(Jm, -f)
        except np.linalg.LinAlgError:
            break
        z = z + dz
        if np.abs(dz).max() <= 1e-15 * (1 + np.abs(z).max()):
            break
    with np.errstate(all="ignore"):
        res = float(np.abs(np.array(F(list(z)), dtype=float)).max())
    return z, res if np.isfinite(res) else np.inf


def continued_equilibrium(robot, cables, R0, P0, P1, z0, steps: int = 16):
    """The equilibrium of parameters P1 reached by continuation from (P0, z0) along the segment P0 -> P1 (Newton
    at each step, halving failed steps); None if the branch cannot be followed (a fold: the real equilibrium
    would jump, which the criterion excludes)."""
    s, h, z = 0.0, 1.0 / steps, np.array(z0, dtype=float)
    while s < 1.0:
        h = min(h, 1.0 - s)
        P = P0 + (s + h) * (P1 - P0)
        zn, res = equilibrium(robot, cables, R0, *_unpack(P), z, iters=12)
        if res < 1e-9 and np.abs(zn - z)[:6].max() < 0.2 * max(1.0, robot.size / 10):
            s, z = s + h, zn
            h = min(2 * h, 1.0 / steps)
        else:
            h /= 2
            if h < 1e-6:
                return None
    return z


@dataclass(frozen=True)
class UncertaintyResult:
    """Outcome for one 6-cable CC (cables 0-based; 1-based in ``to_dict``).

    ``robust``: True (proven valid for every robot in the ranges), False (``counterexample`` found), None
    (undecided within ``max_boxes``); ``tension_bounds`` (6, 2) proven bounds of the tensions tau_i over all robots
    (when proven); ``equilibrium_box`` the half-widths of the pose box (position, rotation angle bound) in which the
    real equilibrium is unique; ``boxes`` parameter boxes examined."""

    cables: tuple
    position: np.ndarray
    tolerances: dict
    robust: bool | None
    tension_bounds: np.ndarray | None
    equilibrium_box: dict | None
    counterexample: dict | None
    boxes: int
    seconds: float
    reason: str | None = None

    @property
    def status(self) -> str:
        """'robust' (proven), 'not robust' (verified counterexample) or 'undecided'."""
        return {True: "robust", False: "not robust", None: "undecided"}[self.robust]

    def to_dict(self) -> dict:
        return jsonable({"status": self.status, "cables": [c + 1 for c in self.cables], "position": self.position,
                         "tolerances": self.tolerances, "robust": self.robust, "tension_bounds": self.tension_bounds,
                         "equilibrium_box": self.equilibrium_box, "counterexample": self.counterexample,
                         "boxes": self.boxes, "seconds": self.seconds, "reason": self.reason})


def _nominal(robot, G, R0, cables):
    A = robot.base[list(cables)]
    c = robot.platform[list(cables)] - robot.com
    rho = np.linalg.norm(A - (G + c @ R0.T), axis=1)
    return A, c, rho


def _params_vector(A, c, rho):
    return np.concatenate([np.asarray(A).ravel(), np.asarray(c).ravel(), np.asarray(rho).ravel()])


def _unpack(P):
    return P[:18].reshape(6, 3), P[18:36].reshape(6, 3), P[36:42]


def _equilibrium_derivative(robot, cables, R0, P, z):
    """d z / dP (12 x 42) at the equilibrium z = (G, e, lam) of parameters P (implicit function theorem, central
    differences of F in P; only used to steer the search, the bisection and the size of the pose region)."""
    A, c, rho = _unpack(P)
    _, J = _system(R0, robot.load, robot.load_direction, A, c, rho)
    Jz = np.array(J(list(z)), dtype=float)
    FP = np.zeros((12, 42))
    h = 1e-7
    for k in range(42):
        Pp, Pm = P.copy(), P.copy()
        Pp[k] += h
        Pm[k] -= h
        Fp = _system(R0, robot.load, robot.load_direction, *_unpack(Pp))[0](list(z))
        Fm = _system(R0, robot.load, robot.load_direction, *_unpack(Pm))[0](list(z))
        FP[:, k] = (np.array(Fp, float) - np.array(Fm, float)) / (2 * h)
    return -np.linalg.solve(Jz, FP)


def _sensitivity(robot, cables, R0, P, z):
    """d lam / dP (6 x 42) at the equilibrium z."""
    return _equilibrium_derivative(robot, cables, R0, P, z)[6:12]


def _search_counterexample(robot, cables, R0, P0, W, z0, rounds: int = 4):
    """Local search of the parameter box P0 +- W for a robot whose real equilibrium has a tension <= 0."""
    best = None
    for j in range(6):
        P, z = P0.copy(), z0.copy()
        for _ in range(rounds):
            S = _sensitivity(robot, cables, R0, P, z)
            Pn = P0 - W * np.sign(S[j])
            zn = continued_equilibrium(robot, cables, R0, P0, Pn, z0)
            if zn is None:
                break
            P, z = Pn, zn
            lam = z[6:12]
            if best is None or lam.min() < best[2][6:12].min():
                best = (j, P.copy(), z.copy())
            if lam[j] <= 0:
                return best
    return best


def uncertainty_check(robot, position, cables, rotation=None, dA: float = 0.005, dB: float = 0.001,
                      drho: float = 0.005, max_boxes: int = 20000, region_factor: float = 1.25) -> UncertaintyResult:
    """Seed 002 Sec. II-D for the 6-cable CC ``cables`` (0-based) at the pose (see the module doc)."""
    from flint import arb

    from cdpr_algebra.intervals.balls import krawczyk_certify, lower, upper

    t0 = time.perf_counter()
    for name, v in (("dA", dA), ("dB", dB), ("drho", drho)):
        if not (np.isfinite(v) and v >= 0):
            raise CdprInputError("tolerances", f"{name} must be a finite number >= 0, got {v}")
    G, R0 = check_pose(robot, position, rotation)
    cables = tuple(cables)
    if len(cables) != 6:
        raise CdprInputError("configuration", f"the uncertainty criterion is for 6-cable configurations, got {len(cables)}")
    tol = {"dA": dA, "dB": dB, "drho": drho}
    nominal = configuration_tensions(robot, G, cables, R0)
    if not nominal.valid:
        raise CdprInputError("configuration", f"cables {[c + 1 for c in cables]} are not a valid CC at the pose")
    A, c, rho = _nominal(robot, G, R0, cables)
    P0 = _params_vector(A, c, rho)
    W0 = np.concatenate([np.full(18, dA), np.full(18, dB), np.full(6, drho)])
    lam0 = nominal.tensions / rho
    z0 = np.concatenate([G, np.zeros(3), lam0])

    def result(robust, bounds, ebox, cex, boxes, reason=None):
        return UncertaintyResult(cables, G, tol, robust, bounds, ebox, cex, boxes, time.perf_counter() - t0, reason)

    # 1. a counterexample by first-order worst cases (cheap), before any proof
    cand = _search_counterexample(robot, cables, R0, P0, W0, z0)
    if cand is not None and cand[2][6:12].min() <= 0:
        return result(False, None, None, _counterexample(robot, cables, R0, cand, z0), 0)

    # 2. one parametric Krawczyk test on the whole parameter box: existence, uniqueness and tensions at once
    Pb = np.array([arb(float(p), float(w)) for p, w in zip(P0, W0)], dtype=object)
    Ab, cb, rb = _unpack(Pb)
    Ab, cb, rb = Ab.tolist(), cb.tolist(), list(rb)
    F, J = _system(R0, robot.load, robot.load_direction, Ab, cb, rb)
    Ff, Jf = _system(R0, robot.load, robot.load_direction, A, c, rho)
    scale = np.concatenate([np.full(3, robot.size), np.ones(3), np.full(6, np.abs(lam0).max())])
    kr = krawczyk_certify(F, J, z0, scale, max_rel_width=0.5, F_float=lambda z: np.array(Ff(list(z)), float),
                          J_float=lambda z: np.array(Jf(list(z)), float))
    if kr.proven and all(v > 0 for v in kr.enclosure[6:12]):
        enc = kr.enclosure
        bounds = np.array([[lower(enc[6 + i]) * max(rho[i] - drho, 0.0), upper(enc[6 + i]) * (rho[i] + drho)]
                           for i in range(6)])
        ebox = {"method": "parametric Krawczyk", "position": max(upper(abs(enc[k] - float(G[k]))) for k in range(3)),
                "rotation_angle": 2 * max(upper(abs(enc[3 + k])) for k in range(3)), "unique": True}
        return result(True, bounds, ebox, None, 1)

    # 3. branch and prune over a pose region around X (see _pose_region_proof)
    dz = np.abs(_pose_sensitivity(robot, cables, R0, P0, z0)) @ W0
    used = 0
    for attempt in range(3):  # the region is sized from the first-order worst case; enlarged if too small
        factor = region_factor * 2.0 ** attempt
        rp = max(factor * float(dz[:3].max()), 1e-6 * robot.size)
        re = max(factor * float(dz[3:6].max()), 1e-9)
        ok, info = _pose_region_proof(robot, cables, R0, G, Ab, cb, rb, rp, re, max_boxes - used)
        used += info["boxes"]
        info["boxes"] = used
        if ok is True or "boundary" not in (info.get("reason") or ""):
            break
    if ok is True:
        info["method"] = "branch and prune over the pose region"
        bounds = np.array([[info["lam_lo"][i] * max(rho[i] - drho, 0.0), info["lam_hi"][i] * (rho[i] + drho)]
                           for i in range(6)])
        ebox = {"method": info["method"], "position": rp, "rotation_angle": 2 * float(np.arctan(re)),
                "unique": False, "boxes": info["boxes"]}
        return result(True, bounds, ebox, None, info["boxes"])
    return result(None, None, None, None, info["boxes"], info["reason"])


def _contract(mf, mb, lo, hi, rounds: int = 4):
    """Krawczyk contraction of the pose box [lo, hi] for the 6 length equations: ``mb`` the model with the
    parameters as balls, ``mf`` with their centres (floats, for the preconditioner).  Returns (lo, hi, empty)."""
    from flint import arb, arb_mat

    from cdpr_algebra.intervals.balls import lower, upper

    eye = arb_mat(6, 6, [1 if i == j else 0 for i in range(6) for j in range(6)])
    for _ in range(rounds):
        mid = 0.5 * (lo + hi)
        try:
            C = np.linalg.inv(np.array(mf.J(list(mid)), dtype=float))
        except np.linalg.LinAlgError:
            return lo, hi, False
        y = np.clip(mid - C @ np.array(mf.F(list(mid)), dtype=float), lo, hi)
        X = [arb(float(0.5 * (a + b)), float(0.5 * (b - a))) for a, b in zip(lo, hi)]
        Cm = arb_mat(C.tolist())
        fy = mb.F([arb(float(v)) for v in y])
        Mx = eye - Cm * arb_mat(mb.J(X))
        d = arb_mat([[X[i] - float(y[i])] for i in range(6)])
        K = arb_mat([[float(v)] for v in y]) - Cm * arb_mat([[v] for v in fy]) + Mx * d
        klo = np.array([lower(K[i, 0]) for i in range(6)])
        khi = np.array([upper(K[i, 0]) for i in range(6)])
        if np.any(~np.isfinite(klo)) or np.any(~np.isfinite(khi)):
            return lo, hi, False
        nlo, nhi = np.maximum(lo, klo), np.minimum(hi, khi)
        if np.any(nlo > nhi):
            return lo, hi, True
        shrink = np.max((nhi - nlo) / np.maximum(hi - lo, 1e-300))
        lo, hi = nlo, nhi
        if shrink > 0.9:
            break
    return lo, hi, False


def _pose_sensitivity(robot, cables, R0, P, z):
    """d(G, e) / dP (6 x 42) at the equilibrium (first order; used to size the pose region)."""
    return _equilibrium_derivative(robot, cables, R0, P, z)[:6]


def _pose_region_proof(robot, cables, R0, G, Ab, cb, rb, rp, re, max_boxes):
    """Branch and prune over the pose region G +- rp, e +- re (Rodrigues parameters of R0^T R) with the parameters
    as balls (Ab, cb, rb).  A pose box is discarded when some cable-length equation excludes 0 over it (no
    equilibrium of any robot in the ranges there); boxes touching the region's boundary must all be discarded;
    every other box must have (i) every lam_i > 0 (Krawczyk on the linear statics over the box) and (ii) a regular
    interval Jacobian of the length equations (|I - C J| < 1).  Then, by continuation from the nominal robot
    (whose equilibrium is X) along any segment of parameters, the equilibrium never leaves the region and the CC's
    tensions stay > 0.  Returns (True / None, info)."""
    from flint import arb, arb_mat

    from cdpr_algebra.intervals.balls import krawczyk_certify, lower, upper

    region_lo = np.concatenate([G - rp, [-re] * 3])
    region_hi = np.concatenate([G + rp, [re] * 3])
    weights = np.array([1, 1, 1, 2, 2, 2.0])
    stack = [(region_lo.copy(), region_hi.copy())]
    rhs = -robot.load * np.concatenate([robot.load_direction, np.zeros(3)])
    boxes = 0
    lam_lo, lam_hi = np.full(6, np.inf), np.full(6, -np.inf)
    min_width = 1e-4 * (region_hi - region_lo)
    mb = _LengthModel(R0, Ab, cb, rb)
    mf = _LengthModel(R0, [[float(v) for v in row] for row in Ab], [[float(v) for v in row] for row in cb],
                      [float(v) for v in rb], floats=True)
    eye = arb_mat(6, 6, [1 if i == j else 0 for i in range(6) for j in range(6)])
    while stack:
        lo, hi = stack.pop()
        boxes += 1
        if boxes > max_boxes:
            return None, {"boxes": boxes, "reason": f"undecided after {max_boxes} pose boxes"}
        X = [arb(float(0.5 * (a + b)), float(0.5 * (b - a))) for a, b in zip(lo, hi)]
        if any(not v.contains(0) for v in mb.F(X)):
            continue  # some cable cannot have its length anywhere in the box: no equilibrium there
        # Krawczyk contractor of the length equations: K(X) misses X -> no equilibrium of any robot in X;
        # otherwise X is replaced by X intersected with K(X)
        lo, hi, empty = _contract(mf, mb, lo, hi)
        if empty:
            continue
        touches = bool(np.any(lo <= region_lo) or np.any(hi >= region_hi))
        if not touches:
            X = [arb(float(0.5 * (a + b)), float(0.5 * (b - a))) for a, b in zip(lo, hi)]
            mid = 0.5 * (lo + hi)
            ok = False
            try:
                Mm = np.array(mf.M(list(mid)), dtype=float)
                lam = np.linalg.solve(Mm, rhs)
                CL = np.linalg.inv(np.array(mf.J(list(mid)), dtype=float))
            except np.linalg.LinAlgError:
                lam = None
            if lam is not None and np.all(lam > 0):
                E = eye - arb_mat(CL.tolist()) * arb_mat(mb.J(X))
                regular = max(sum(upper(abs(E[i, j])) for j in range(6)) for i in range(6)) < 1
                if regular:
                    M = mb.M(X)
                    kr = krawczyk_certify(lambda x: [sum(M[a][i] * x[i] for i in range(6)) - float(rhs[a])
                                                     for a in range(6)],
                                          lambda x: M, lam, np.abs(lam), max_rel_width=4.0,
                                          F_float=lambda x: Mm @ x - rhs, J_float=lambda x: Mm)
                    if kr.proven and all(v > 0 for v in kr.enclosure):
                        lam_lo = np.minimum(lam_lo, [lower(v) for v in kr.enclosure])
                        lam_hi = np.maximum(lam_hi, [upper(v) for v in kr.enclosure])
                        ok = True
            if ok:
                continue
        if np.all(hi - lo <= min_width):
            why = "equilibria may reach the boundary of the pose region" if touches else \
                "tensions not proven positive on a tiny pose box"
            return None, {"boxes": boxes, "reason": why}
        k = int(np.argmax((hi - lo) * weights / (region_hi - region_lo)))
        m = 0.5 * (lo[k] + hi[k])
        hi1, lo2 = hi.copy(), lo.copy()
        hi1[k], lo2[k] = m, m
        stack += [(lo2, hi), (lo, hi1)]
    return True, {"boxes": boxes, "lam_lo": lam_lo, "lam_hi": lam_hi, "reason": None}


def _counterexample(robot, cables, R0, cand, z0) -> dict:
    """The robot of ``cand`` = (cable, P, z) as a dict; z is its equilibrium on the branch continued from the
    nominal robot (:func:`continued_equilibrium`), recomputed to full accuracy."""
    _, P, z = cand
    A, c, rho = _unpack(P)
    z, res = equilibrium(robot, cables, R0, A, c, rho, z)
    R = np.asarray(R0) @ matrix_from_rodrigues(*z[3:6])
    lam = z[6:12]
    return {"cable": int(cables[int(np.argmin(lam))]) + 1, "A": A, "platform": c + robot.com, "lengths": rho,
            "position": z[:3], "angles": angles_from_matrix(R), "tensions": lam * rho, "residual": res}
