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

import itertools
import time
from dataclasses import dataclass, field

import numpy as np

from .configurations import check_pose, parse_cables, wrench_columns
from cdpr_algebra.report.jsonable import jsonable

__all__ = ["MONOMIALS", "CCPolynomials", "CCRadii", "cc_polynomials", "cc_radii",
           "cc_radii_many", "distance_to_cubics", "certify_radius", "arb_cubic", "evaluate_cubic"]

# monomials y1^i y2^j y3^k of total degree <= 3 (the coefficient order of every cubic here)
MONOMIALS = tuple((i, j, k) for i in range(4) for j in range(4) for k in range(4) if i + j + k <= 3)
_EXPH = np.array([(3 - sum(m),) + m for m in MONOMIALS])  # homogeneous exponents (y0, y1, y2, y3), (20, 4)
_NODES = np.cos(np.pi * (np.arange(4) + 0.5) / 4)  # Chebyshev nodes in [-1, 1]
_VINV = np.linalg.inv(np.vander(_NODES, 4, increasing=True))
_GRID = np.stack(np.meshgrid(_NODES, _NODES, _NODES, indexing="ij"), -1).reshape(-1, 3)
LABEL_SCALE = 1024  # path label k is stored as k / LABEL_SCALE


def _tensor_map() -> np.ndarray:
    """(64, 20) matrix taking cubic coefficients (MONOMIALS order) to the symmetric tensor T (4, 4, 4) with
    P^h(Y) = sum T_ijk Y_i Y_j Y_k, Y = (y0, y1, y2, y3)."""
    S = np.zeros((4, 4, 4, len(MONOMIALS)))
    for m, e in enumerate(_EXPH):
        idx = [v for v in range(4) for _ in range(e[v])]
        perms = set(itertools.permutations(idx))
        for p in perms:
            S[p + (m,)] = 1.0 / len(perms)
    return S.reshape(64, -1)


_TMAP = _tensor_map()


def cubic_tensors(C) -> np.ndarray:
    """Symmetric tensors (..., 4, 4, 4) of cubics given by coefficients (..., 20)."""
    C = np.asarray(C)
    return (C @ _TMAP.T).reshape(C.shape[:-1] + (4, 4, 4))


def _form_parts(T, Y):
    """For tensors T (N, 4, 4, 4) and points Y (N, 4): P^h (N,), gradient (N, 4), Hessian (N, 4, 4)."""
    V = np.einsum("nijk,nk->nij", T, Y)
    g = np.einsum("nij,nj->ni", V, Y)
    return np.einsum("ni,ni->n", g, Y), 3.0 * g, 6.0 * V


def evaluate_cubic(coefficients, y) -> np.ndarray:
    """P(y) = sum_m c_m y^m for points y (..., 3) (affine, MONOMIALS order)."""
    y = np.asarray(y)
    c = np.asarray(coefficients)
    E = np.array(MONOMIALS)
    mon = np.prod(y[..., None, :] ** E, axis=-1)
    return mon @ c if c.ndim == 1 else np.einsum("...m,...m->...", mon, c)


# ---------------------------------------------------------------------------------------------------------------
# The projective Lagrange system and its homotopies (duck-typed for homotopy.endgame.track_paths)


class _EDSystem:
    """F(z; c), z = (y0, y1, y2, y3, mu, lam): mu y0 y_k - lam dP^h/dy_k, P^h, a.(y0..y3) - 1, b.(mu, lam) - 1."""

    n = neq = 6

    def __init__(self, a, b):
        self.a = np.asarray(a, dtype=complex)
        self.b = np.asarray(b, dtype=complex)

    def parts(self, Z, T, jac=True, dT=None):
        """F (N, 6), J (N, 6, 6) and, for a tensor direction dT (N, 4, 4, 4), dF/dT . dT (N, 6)."""
        Y, mu, lam = Z[:, :4], Z[:, 4], Z[:, 5]
        P, G, H = _form_parts(T, Y)
        N = len(Z)
        F = np.empty((N, 6), dtype=complex)
        y0 = Y[:, 0]
        F[:, :3] = (mu * y0)[:, None] * Y[:, 1:] - lam[:, None] * G[:, 1:]
        F[:, 3] = P
        F[:, 4] = Y @ self.a - 1.0
        F[:, 5] = mu * self.b[0] + lam * self.b[1] - 1.0
        out = [F]
        if jac:
            J = np.zeros((N, 6, 6), dtype=complex)
            J[:, :3, :4] = -lam[:, None, None] * H[:, 1:, :]
            J[:, :3, 0] += mu[:, None] * Y[:, 1:]
            for k in range(1, 4):
                J[:, k - 1, k] += mu * y0
            J[:, :3, 4] = y0[:, None] * Y[:, 1:]
            J[:, :3, 5] = -G[:, 1:]
            J[:, 3, :4] = G
            J[:, 4, :4] = self.a
            J[:, 5, 4:] = self.b
            out.append(J)
        if dT is not None:
            dP, dG, _ = _form_parts(dT, Y)
            D = np.zeros((N, 6), dtype=complex)
            D[:, :3] = -lam[:, None] * dG[:, 1:]
            D[:, 3] = dP
            out.append(D)
        return out


class _LinearProductStart:
    """G_k = l_k1(Y) l_k2(Y) m_k(mu, lam) (k = 1..3), G_4 = l_41 l_42 l_43 (Y), plus the same charts: the
    2-homogeneous linear-product start system of the bidegrees (2, 1), (2, 1), (2, 1), (3, 0); 36 solutions."""

    def __init__(self, system: _EDSystem, rng):
        def rnd(*s):
            return rng.normal(size=s) + 1j * rng.normal(size=s)

        self.sys = system
        self.L = rnd(4, 3, 4)  # y-forms: rows k = 0..2 use 2 of them, row 3 uses 3
        self.M = rnd(3, 2)  # (mu, lam)-forms of rows 0..2
        sols = []
        for kmu in range(3):  # the row whose (mu, lam) factor vanishes
            others = [k for k in range(3) if k != kmu]
            for f0, f1, f3 in itertools.product(range(2), range(2), range(3)):
                Arows = [self.L[others[0], f0], self.L[others[1], f1], self.L[3, f3], system.a]
                Y = np.linalg.solve(np.array(Arows), np.array([0, 0, 0, 1.0]))
                ml = np.linalg.solve(np.array([self.M[kmu], system.b]), np.array([0, 1.0]))
                sols.append(np.concatenate([Y, ml]))
        self.solutions = np.array(sols)

    def parts(self, Z):
        Y, ML = Z[:, :4], Z[:, 4:6]
        N = len(Z)
        ly = np.einsum("kfv,nv->nkf", self.L, Y)  # (N, 4, 3)
        mm = ML @ self.M.T  # (N, 3)
        F = np.empty((N, 6), dtype=complex)
        J = np.zeros((N, 6, 6), dtype=complex)
        for k in range(3):
            F[:, k] = ly[:, k, 0] * ly[:, k, 1] * mm[:, k]
            J[:, k, :4] = (ly[:, k, 1, None] * self.L[k, 0] + ly[:, k, 0, None] * self.L[k, 1]) * mm[:, k, None]
            J[:, k, 4:] = (ly[:, k, 0] * ly[:, k, 1])[:, None] * self.M[k]
        F[:, 3] = ly[:, 3, 0] * ly[:, 3, 1] * ly[:, 3, 2]
        J[:, 3, :4] = (ly[:, 3, 1, None] * ly[:, 3, 2, None] * self.L[3, 0] + ly[:, 3, 0, None] * ly[:, 3, 2, None]
                       * self.L[3, 1] + ly[:, 3, 0, None] * ly[:, 3, 1, None] * self.L[3, 2])
        F[:, 4] = Y @ self.sys.a - 1.0
        F[:, 5] = ML @ self.sys.b - 1.0
        J[:, 4, :4] = self.sys.a
        J[:, 5, 4:] = self.sys.b
        return F, J


class _StartHomotopy:
    """H = gamma t G(z) + (1 - t) F(z; c1) (the gamma trick), for the one-time generic solve."""

    def __init__(self, start: _LinearProductStart, system: _EDSystem, c1, gamma):
        self.start, self.sys, self.gamma = start, system, complex(gamma)
        self.T1 = cubic_tensors(np.asarray(c1, dtype=complex))
        self.n = self.neq = 6

    def evaluate_all(self, x, t):
        G, JG = self.start.parts(x)
        F, JF = self.sys.parts(x, np.broadcast_to(self.T1, (len(x), 4, 4, 4)))
        a = (self.gamma * np.asarray(t, dtype=complex))[:, None]
        b = (1 - np.asarray(t, dtype=complex))[:, None]
        return a * G + b * F, a[..., None] * JG + b[..., None] * JF, self.gamma * G - F

    def evaluate_and_jacobian(self, x, t):
        return self.evaluate_all(x, t)[:2]

    def evaluate(self, x, t):
        return self.evaluate_all(x, t)[0]


class _BatchParameterHomotopy:
    """H(z, t) = F(z; t c1 + (1 - t) C0[k]) for many real target cubics C0 (K, 20) at once.

    The path of instance k has the extra last coordinate k / LABEL_SCALE, kept constant by the equation
    z_6 - round(z_6 LABEL_SCALE) / LABEL_SCALE = 0 (its row of dH/dz is e_6 and its dH/dt is 0).  F is linear in
    the cubic, so the forms of the shared generic cubic and of the gathered targets are evaluated separately."""

    def __init__(self, system: _EDSystem, c1, C0):
        self.sys = system
        # T0[k, j] = (T_k)_{:, :, j} flattened (16,): the targets' tensors sliced along the last index, real
        self.T0 = np.ascontiguousarray(cubic_tensors(np.asarray(C0, dtype=float)).reshape(-1, 16, 4).transpose(0, 2, 1))
        self.T1 = np.ascontiguousarray(cubic_tensors(np.asarray(c1, dtype=complex)).reshape(16, 4).T)  # (4, 16)
        self.K = len(self.T0)
        self.n = self.neq = 7

    def _index(self, x):
        k = np.nan_to_num(x[:, 6].real * LABEL_SCALE, nan=0.0, posinf=0.0, neginf=0.0)
        return np.clip(np.rint(k), 0, self.K - 1).astype(int)

    def evaluate_all(self, x, t, jac=True, dt=True):
        k = self._index(x)
        N = len(x)
        t = np.asarray(t, dtype=complex)[:, None]
        Y = np.ascontiguousarray(x[:, :4])  # (a strided operand makes matmul ~100x slower)
        mu, lam = x[:, 4], x[:, 5]
        # V = T . Y (N, 16) for the generic cubic and the targets; g = V . Y; P = g . Y
        # elementwise sums, not matmul: OpenBLAS threads spin on these tiny products
        T1 = self.T1
        V1 = T1[0] * Y[:, 0, None] + T1[1] * Y[:, 1, None] + T1[2] * Y[:, 2, None] + T1[3] * Y[:, 3, None]
        Tk = self.T0[k]
        V0 = Tk[:, 0] * Y[:, 0, None] + Tk[:, 1] * Y[:, 1, None] + Tk[:, 2] * Y[:, 2, None] + Tk[:, 3] * Y[:, 3, None]
        V = t * V1 + (1 - t) * V0
        V3 = V.reshape(N, 4, 4)
        g = V3[:, :, 0] * Y[:, 0, None] + V3[:, :, 1] * Y[:, 1, None] + V3[:, :, 2] * Y[:, 2, None] \
            + V3[:, :, 3] * Y[:, 3, None]
        G = 3.0 * g
        H = np.empty((N, 7), dtype=complex)
        y0 = Y[:, 0]
        H[:, :3] = (mu * y0)[:, None] * Y[:, 1:] - lam[:, None] * G[:, 1:]
        H[:, 3] = (g * Y).sum(axis=1)
        a_ = self.sys.a
        H[:, 4] = Y[:, 0] * a_[0] + Y[:, 1] * a_[1] + Y[:, 2] * a_[2] + Y[:, 3] * a_[3] - 1.0
        H[:, 5] = mu * self.sys.b[0] + lam * self.sys.b[1] - 1.0
        H[:, 6] = x[:, 6] - k / LABEL_SCALE
        out = [H]
        if jac:
            Hx = np.zeros((N, 7, 7), dtype=complex)
            Hx[:, :3, :4] = (-6.0 * lam)[:, None, None] * V3[:, 1:, :]
            Hx[:, :3, 0] += mu[:, None] * Y[:, 1:]
            muy0 = mu * y0
            Hx[:, 0, 1] += muy0
            Hx[:, 1, 2] += muy0
            Hx[:, 2, 3] += muy0
            Hx[:, :3, 4] = y0[:, None] * Y[:, 1:]
            Hx[:, :3, 5] = -G[:, 1:]
            Hx[:, 3, :4] = G
            Hx[:, 4, :4] = self.sys.a
            Hx[:, 5, 4:6] = self.sys.b
            Hx[:, 6, 6] = 1.0
            out.append(Hx)
        if dt:
            dV = (V1 - V0).reshape(N, 4, 4)
            dg = dV[:, :, 0] * Y[:, 0, None] + dV[:, :, 1] * Y[:, 1, None] + dV[:, :, 2] * Y[:, 2, None] \
                + dV[:, :, 3] * Y[:, 3, None]
            Ht = np.zeros((N, 7), dtype=complex)
            Ht[:, :3] = (-3.0 * lam)[:, None] * dg[:, 1:]
            Ht[:, 3] = (dg * Y).sum(axis=1)
            out.append(Ht)
        return out

    def evaluate_and_jacobian(self, x, t):
        return self.evaluate_all(x, t, dt=False)

    def evaluate(self, x, t):
        return self.evaluate_all(x, t, jac=False, dt=False)[0]


@dataclass
class _Generic:
    system: _EDSystem
    c1: np.ndarray
    solutions: np.ndarray  # (21, 6) chart coordinates
    seconds: float
    seed: int


_GENERIC: dict[int, _Generic] = {}
ED_DEGREE = 21


def _generic(seed: int = 0) -> _Generic:
    """The 21 critical points of a random complex cubic (cached per seed): linear-product homotopy, 36 paths."""
    if seed in _GENERIC:
        return _GENERIC[seed]
    t0 = time.perf_counter()
    for attempt in range(5):
        rng = np.random.default_rng([seed, attempt, 20020])

        def rnd(*s):
            v = rng.normal(size=s) + 1j * rng.normal(size=s)
            return v / np.linalg.norm(v)

        system = _EDSystem(rnd(4), rnd(2))
        c1 = rng.normal(size=20) + 1j * rng.normal(size=20)
        start = _LinearProductStart(system, rng)
        gamma = np.exp(2j * np.pi * rng.random())
        xend, status = _track_batch(_StartHomotopy(start, system, c1, gamma), start.solutions, seed)
        X = xend[status == "success"]
        if len(X):
            X = X[(np.abs(X[:, 0]) > 1e-6) & (np.abs(X[:, 4]) > 1e-6)]
        # distinct, nonsingular, finite: must be the Euclidean distance degree of a cubic
        if len(X) == ED_DEGREE and len({tuple(np.round(x, 6)) for x in X}) == ED_DEGREE:
            g = _Generic(system, c1, X, time.perf_counter() - t0, seed)
            _GENERIC[seed] = g
            return g
    raise RuntimeError(f"generic solve of the cubic distance family did not give {ED_DEGREE} solutions")


# ---------------------------------------------------------------------------------------------------------------
# distances from the origin to many cubic surfaces


@dataclass(frozen=True)
class CriticalDistances:
    """Real critical points of the distance from y = 0 to {P = 0} (scaled coordinates), for one cubic P.

    ``points`` (k, 3) sorted by distance, ``kinds`` 'critical' or 'singular point', ``failed`` paths that did not
    finish (then the minimum is not proven global), ``paths`` tracked."""

    points: np.ndarray
    distances: np.ndarray
    kinds: tuple
    lams: np.ndarray
    failed: int
    paths: int
    finite: int
    balanced: np.ndarray  # the balanced, normalized cubic c~ the homotopy solved (y = scale * y~)
    scale: float

    @property
    def minimum(self) -> float:
        return float(self.distances[0]) if len(self.distances) else np.inf


def _newton_real(c, y, lam, iters=6):
    """Real Newton on (y - lam grad P(y), P(y)) (affine, scaled coordinates)."""
    T = cubic_tensors(np.asarray(c, dtype=float))[None]
    for _ in range(iters):
        P, G, H = _form_parts(T, np.concatenate([[1.0], y])[None])
        F = np.concatenate([y - lam * G[0, 1:], P])
        J = np.zeros((4, 4))
        J[:3, :3] = np.eye(3) - lam * H[0, 1:, 1:]
        J[:3, 3] = -G[0, 1:]
        J[3, :3] = G[0, 1:]
        try:
            d = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            break
        y = y + d[:3]
        lam = lam + d[3]
        if np.abs(d).max() <= 1e-15 * (1 + np.abs(y).max() + abs(lam)):
            break
    return y, lam


_DEG = np.array([sum(m) for m in MONOMIALS])


def balance(c) -> tuple[np.ndarray, float]:
    """(c~, s): the cubic P~(y~) = P(s y~) / max|.|, with s chosen so that the parts of degree 0..3 have
    comparable sizes (least-squares fit of log max|c_d| + d log s = const).  Keeps the homotopy away from the
    scale mismatch between a real target and the random generic cubic."""
    c = np.asarray(c, dtype=float)
    if not np.any(c):
        raise ArithmeticError("the zero polynomial has no zero set to measure a distance to (every point is on it)")
    sizes = np.array([np.abs(c[_DEG == d]).max() for d in range(4)])
    ok = sizes > 1e-14 * sizes.max()
    d = np.arange(4)[ok]
    if len(d) >= 2:
        slope = np.polyfit(d, np.log(sizes[ok]), 1)[0]
        s = float(np.exp(-slope))
    else:
        s = 1.0
    ct = c * s ** _DEG
    return ct / np.abs(ct).max(), s


ACCEPT_UPDATE = 1e-9
# Step control of the batched parameter homotopies: predictor tolerance 1e-4 (engine default 1e-5) halves the
# steps; measured on the 48 cubics of seed 002 Sec. IV-B.1 it gives the same critical points (to 2e-12) and the
# duplicate check of _track_batch re-tracks any path that jumps onto another one.


def _batch_tracker():
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    return TrackerOptions(predictor_tol=1e-4)

INFINITY_Y0 = 1e-5  # chart points with |y0| <= this * |Y| are at infinity (|y| >~ 1e5 in scaled units)


def _chart_at_infinity(z):
    """The ED system's chart points with y0 ~ 0 (coordinates 0..3 are (y0 : y))."""
    return np.abs(z[:, 0]) <= INFINITY_Y0 * np.abs(z[:, :4]).max(axis=1)


def _track_batch(hom, X0, seed: int = 0, at_infinity=_chart_at_infinity, tracker=None):
    """Track every path of ``hom`` with the engine's tracker and endgame pieces; returns (endpoints, status).

    Phase 1 (t = 1 -> 0.1) with one tightened retry of failed paths; phase 2 (0.1 -> 0) and Newton refinement
    (:func:`.homotopy.endgame.refine`): quadratic convergence and cond <= 1e10 is ``success``.  Paths that end
    with y0 ~ 0 in the chart are ``at_infinity`` without an endgame (they are of no use for a distance); the
    remaining ones go through the engine's Cauchy endgame (``singular`` when finite).  Nonsingular endpoints of
    one instance that coincide (path jumping) are re-tracked with tightened steps.  ``at_infinity(z)`` flags
    chart points at infinity (a boolean per row)."""
    from cdpr_algebra.homotopy.endgame import EndgameOptions, cauchy_endgame, duplicate_groups, refine
    from cdpr_algebra.homotopy.tracker import TrackerOptions, track_segment

    tr, eo = tracker or TrackerOptions(), EndgameOptions()
    te = eo.endgame_start

    def run(X, tro):
        N = len(X)
        xend = np.array(X, dtype=complex)
        status = np.full(N, "failed", dtype=object)
        seg = track_segment(hom, X, 1.0, te, tro)
        x1, ok1 = seg.x, seg.status == "success"
        bad = np.flatnonzero(~ok1)
        if bad.size:
            seg_b = track_segment(hom, X[bad], 1.0, te, tro.tightened())
            x1[bad] = seg_b.x
            ok1[bad] = seg_b.status == "success"
        live = np.flatnonzero(ok1)
        xend[~ok1] = x1[~ok1]
        if not live.size:
            return xend, status
        seg2 = track_segment(hom, x1[live], te, 0.0, tro)
        xr, upd, _, cond, quad = refine(hom, seg2.x, 0.0, tol=eo.refine_tol)
        # nonsingular: Newton settled (last update <= ACCEPT_UPDATE; the engine's 1e-13 floor is too strict for
        # points whose chart coordinates carry a large lam) and the Jacobian is well conditioned
        good = (seg2.status == "success") & ((upd <= ACCEPT_UPDATE) | quad) & (cond <= eo.singular_condition)
        xend[live] = np.where(good[:, None], xr, seg2.x)
        status[live[good]] = "success"
        rest = live[~good]
        if rest.size:
            inf = at_infinity(xend[rest])
            status[rest[inf]] = "at_infinity"
            rest = rest[~inf]
        if rest.size:
            eg = cauchy_endgame(hom, x1[rest], te, eo, tro)
            xend[rest] = eg.x
            for i, st, xx in zip(rest, eg.status, eg.x):
                if st == "singular":
                    if at_infinity(xx[None, :])[0]:
                        st = "at_infinity"
                    else:
                        xr1, _, _, c1_, q1 = refine(hom, xx[None, :], 0.0, tol=eo.refine_tol)
                        if q1[0] and c1_[0] <= eo.singular_condition:
                            xend[i], st = xr1[0], "success"
                status[i] = st if st in ("success", "singular", "at_infinity") else "failed"
        return xend, status

    X0 = np.asarray(X0, dtype=complex)
    xend, status = run(X0, tr)
    succ = np.flatnonzero(status == "success")
    if succ.size > 1:
        groups = duplicate_groups(xend[succ], 1e-8)
        redo = sorted({int(succ[i]) for g in groups for i in g})
        if redo:
            x2, s2 = run(X0[redo], tr.tightened(10.0))
            xend[redo], status[redo] = x2, s2
    return xend, status


def distance_to_cubics(C, seed: int = 0, real_tol: float = 1e-7) -> list[CriticalDistances]:
    """Real critical points of the distance from the origin to each cubic surface {sum C[k, m] y^m = 0}.

    ``C`` (K, 20) real coefficients (MONOMIALS order).  Identical cubics (up to a factor) are solved once.  One
    batched parameter homotopy (21 paths per cubic) for all of them."""
    C = np.atleast_2d(np.asarray(C, dtype=float))
    K = len(C)
    bal = [balance(c) for c in C]
    Cn = np.array([b[0] for b in bal])
    scales = np.array([b[1] for b in bal])
    # identical cubics up to sign (e.g. the Cramer numerator of the same 5 cables in two CCs)
    canon = np.array([c * np.sign(c[np.argmax(np.abs(c))]) for c in Cn])
    uniq, first = [], {}
    for k in range(K):
        key = tuple(np.round(canon[k], 11)) + (round(float(np.log(scales[k])), 11),)
        if key not in first:
            first[key] = len(uniq)
            uniq.append(k)
    which = [first[tuple(np.round(canon[k], 11)) + (round(float(np.log(scales[k])), 11),)] for k in range(K)]
    gen = _generic(seed)
    solved: list = [None] * len(uniq)
    U = canon[uniq]
    for lo in range(0, len(uniq), LABEL_SCALE):
        idx = np.arange(lo, min(len(uniq), lo + LABEL_SCALE))
        X0 = np.concatenate([np.tile(gen.solutions, (len(idx), 1)),
                             np.repeat((idx - lo) / LABEL_SCALE, ED_DEGREE)[:, None]], axis=1)
        hom = _BatchParameterHomotopy(gen.system, gen.c1, U[idx])
        xend, status = _track_batch(hom, X0, seed, tracker=_batch_tracker())
        for j, u in enumerate(idx):
            sl = slice(j * ED_DEGREE, (j + 1) * ED_DEGREE)
            solved[u] = _classify(U[u], scales[uniq[u]], xend[sl], status[sl], real_tol)
    return [solved[which[k]] for k in range(K)]


def _classify(c, s, xend, status, real_tol):
    pts, kinds, lams = [], [], []
    failed = int(np.sum(status == "failed"))
    finite = 0
    for z, st in zip(xend, status):
        if st not in ("success", "singular"):
            continue
        scale = np.abs(z[:4]).max()
        if abs(z[0]) <= INFINITY_Y0 * scale:
            continue  # at infinity
        finite += 1
        y = z[1:4] / z[0]
        tol = real_tol if st == "success" else max(real_tol, 1e-5)
        if np.abs(y.imag).max() > tol * (1 + np.abs(y).max()):
            continue
        singular_point = abs(z[4]) <= 1e-8 * np.abs(z[4:6]).max()
        if singular_point:
            pts.append(y.real)
            kinds.append("singular point")
            lams.append(np.nan)
        else:
            lam = z[5] / z[4]
            if abs(lam.imag) > tol * (1 + abs(lam)):
                continue
            yr, lr = _newton_real(c, y.real, lam.real)
            pts.append(yr)
            kinds.append("critical")
            lams.append(lr)
    pts = np.array(pts).reshape(-1, 3)
    d = np.linalg.norm(pts, axis=1)
    order = np.argsort(d)
    # merge duplicates (the same real point reached twice, e.g. a singular endpoint)
    keep = []
    for i in order:
        if all(np.abs(pts[i] - pts[j]).max() > 1e-9 * (1 + np.abs(pts[i]).max()) for j in keep):
            keep.append(i)
    return CriticalDistances(s * pts[keep], s * d[keep], tuple(kinds[i] for i in keep), np.array(lams)[keep],
                             failed, len(status), finite, c, s)


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


def _polynomials_batch(robot, positions, rotations, cable_sets, scale):
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
    coef, dropped = _polynomials_batch(robot, [G], [R], [tuple(cables)], h)
    return CCPolynomials(tuple(cables), G, R, h, coef[0], float(dropped[0].max()))


def _default_scale(robot) -> float:
    return robot.size / 10.0


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

    def radii_by_number(self) -> dict:
        """{"<cable number>": r, ..., "singular": r} (the JSON contract)."""
        d = {str(c + 1): float(r) for c, r in self.radii.items()}
        d["singular"] = float(self.singular)
        return d

    def to_dict(self) -> dict:
        return jsonable({"cables": [c + 1 for c in self.cables], "position": self.position,
                         "tensions": self.tensions, "radii": self.radii_by_number(), "rmin": self.rmin,
                         "limiting": self.limiting + 1 if isinstance(self.limiting, (int, np.integer)) else self.limiting,
                         "nearest": self.nearest, "failed_paths": self.failed_paths, "certified": self.certified,
                         "radius_certificate": self.radius_certificate, "certificate": self.certificate,
                         "seconds": self.seconds})


def cc_radii_many(robot, requests, scale: float | None = None, seed: int = 0, certify: bool = False
                  ) -> list[CCRadii]:
    """Radii of many (position, 0-based cables[, rotation]) requests in one batched homotopy run."""
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
    coef, dropped = _polynomials_batch(robot, Gs, Rs, Ss, h)
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
                      sum(c.failed for c in cd), shared)
        if certify:
            res = _with_certificate(res, robot, h)
        out.append(res)
    return out


def cc_radii(robot, position, cables, rotation=None, scale: float | None = None, seed: int = 0,
             certify: bool = False) -> CCRadii:
    """Seed 002 Sec. II-B.1 for one 6-cable CC given by 1-based cable numbers (e.g. [1, 2, 3, 4, 5, 6])."""
    S = parse_cables(robot, cables, "configuration", size=6)
    return cc_radii_many(robot, [(position, S, rotation)], scale, seed, certify)[0]


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
    """F(y, lam) = (y - lam grad P(y), P(y)) and its Jacobian for P = sum c_m y^m; plain arithmetic (floats or
    arb balls, coefficients ``c`` floats or balls)."""
    E = MONOMIALS

    def parts(Y):
        pw = [[1, Y[v], Y[v] * Y[v], Y[v] * Y[v] * Y[v]] for v in range(3)]
        P = 0
        G = [0, 0, 0]
        H = [[0, 0, 0] for _ in range(3)]
        for cm, e in zip(c, E):
            P = P + cm * pw[0][e[0]] * pw[1][e[1]] * pw[2][e[2]]
            for v in range(3):
                if e[v]:
                    f = list(e)
                    f[v] -= 1
                    G[v] = G[v] + cm * e[v] * pw[0][f[0]] * pw[1][f[1]] * pw[2][f[2]]
                    for w in range(3):
                        if f[w]:
                            g = list(f)
                            g[w] -= 1
                            H[v][w] = H[v][w] + cm * e[v] * f[w] * pw[0][g[0]] * pw[1][g[1]] * pw[2][g[2]]
        return P, G, H

    def F(x):
        P, G, _ = parts(x[:3])
        return [x[v] - x[3] * G[v] for v in range(3)] + [P]

    def J(x):
        _, G, H = parts(x[:3])
        rows = [[(1 if v == w else 0) - x[3] * H[v][w] for w in range(3)] + [-G[v]] for v in range(3)]
        rows.append([G[0], G[1], G[2], 0])
        return rows

    return F, J, parts


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
    Ff, Jf, parts = _lagrange_evaluators(cf)
    _, G, _ = parts(list(y))
    G = np.array(G, dtype=float)
    lam = float(y @ G / (G @ G))
    x0 = np.concatenate([y, [lam]])
    F, J, _ = _lagrange_evaluators(cb)
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


class _Poly:
    """A real polynomial in y1, y2, y3 with interval coefficients: exponent tuples -> (lo, hi), outward rounded."""

    def __init__(self, terms: dict):
        self.terms = {e: c for e, c in terms.items() if not (c[0] == 0.0 and c[1] == 0.0)}

    @staticmethod
    def _add(a, b):
        from cdpr_algebra.intervals.arithmetic import down, up

        return (float(down(a[0] + b[0])), float(up(a[1] + b[1])))

    @classmethod
    def from_bounds(cls, lo, hi):
        return cls({e: (float(l), float(h)) for e, l, h in zip(MONOMIALS, lo, hi)})

    def deriv(self, v: int) -> "_Poly":
        from cdpr_algebra.intervals.arithmetic import down, up

        out = {}
        for e, (lo, hi) in self.terms.items():
            if e[v]:
                f = list(e)
                f[v] -= 1
                k = float(e[v])
                out[tuple(f)] = (float(down(lo * k)), float(up(hi * k)))
        return _Poly(out)

    def times_var(self, v: int) -> "_Poly":
        out = {}
        for e, c in self.terms.items():
            f = list(e)
            f[v] += 1
            out[tuple(f)] = c
        return _Poly(out)

    def __sub__(self, o: "_Poly") -> "_Poly":
        out = dict(self.terms)
        for e, (lo, hi) in o.terms.items():
            out[e] = self._add(out[e], (-hi, -lo)) if e in out else (-hi, -lo)
        return _Poly(out)

    def matrix_row(self):
        """(lo, hi) coefficient rows over MONOMIALS (every polynomial here has degree <= 3)."""
        lo, hi = np.zeros(len(MONOMIALS)), np.zeros(len(MONOMIALS))
        for e, (l, h) in self.terms.items():
            k = _MONO_INDEX[e]
            lo[k], hi[k] = l, h
        return lo, hi


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
    from cdpr_algebra.intervals.arithmetic import Interval, _midrad, mr_matmul, up

    max_boxes = NEAREST_MAX_BOXES if max_boxes is None else max_boxes
    P = _Poly.from_bounds(coef_lo, coef_hi)
    grad = [P.deriv(v) for v in range(3)]
    funcs = [P] + [grad[b].times_var(a) - grad[a].times_var(b) for a, b in ((0, 1), (0, 2), (1, 2))]
    polys = funcs + [f.deriv(v) for v in range(3) for f in funcs]  # 4 functions, then d/dy_v of each
    rows = [f.matrix_row() for f in polys]
    Cm, Cr = _midrad(Interval(np.array([r[0] for r in rows]), np.array([r[1] for r in rows])))
    CmT, CrT = np.ascontiguousarray(Cm.T), np.ascontiguousarray(Cr.T)
    nf = len(funcs)
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
        Mm, Mr = _midrad(MY)
        vals = mr_matmul(Mm, Mr, CmT, CrT)  # (n, 16): the functions and their derivatives over the boxes
        Mcm, Mcr = _midrad(_monomials(c, c))
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


def _with_certificate(res: CCRadii, robot, h: float) -> CCRadii:
    """Certify the minimizing critical point (Krawczyk) and prove that it is the nearest (interval exclusion, within a
    relative ``NEAREST_REL_GAP`` of the certified distance); ``certified`` when both are proven."""
    from dataclasses import replace

    which = res.limiting
    column = None if which == "singular" else res.cables.index(which)
    cert = certify_radius(robot, res.position, res.rotation, res.cables, column, h, res.nearest)
    base = cert["radius_enclosure"][0] if cert["proven"] else float(res.rmin)
    near = prove_nearest(robot, res.position, res.rotation, res.cables, h, (1.0 - NEAREST_REL_GAP) * base)
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
