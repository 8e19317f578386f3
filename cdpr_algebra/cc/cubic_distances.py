"""Distances from the origin to many cubic surfaces at once (Merlet, robustness radii): the projective Lagrange
(Euclidean-distance) system of each cubic, solved by batched parameter homotopies from a generic instance; real
critical points and their distances."""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass
import numpy as np

from cdpr_algebra.generated.cubic_distance import MONOMIALS, lagrange_system
from cdpr_algebra.homotopy.endgame import track_paths
from cdpr_algebra.homotopy.many_targets import chart_options, solve_targets
from cdpr_algebra.homotopy.results import FAILURES, SINGULAR, SUCCESS



_NODES = np.cos(np.pi * (np.arange(4) + 0.5) / 4)  # Chebyshev nodes in [-1, 1]
_VINV = np.linalg.inv(np.vander(_NODES, 4, increasing=True))
_GRID = np.stack(np.meshgrid(_NODES, _NODES, _NODES, indexing="ij"), -1).reshape(-1, 3)


def _ed_parts(Z, C, a, b, jac=True, dC=None):
    """The generated projective ED system (:func:`cdpr_algebra.generated.cubic_distance.ed_directional_into`,
    compiled over the points by :mod:`.ed_kernels`) at the chart points Z (N, 6) for the cubics C: (N, 20) rows, or
    one coefficient vector shared by all.  Returns [F (N, 6)], plus J (N, 6, 6) with ``jac``, plus dF/dc . dC
    (N, 6) for a direction dC (N, 20) (then J is returned too)."""
    from .ed_kernels import ed_values

    N = len(Z)
    vals = ed_values(Z, C, a, b, dC)
    out = [vals[:, :6]]
    if jac or dC is not None:
        out.append(vals[:, 6:42].reshape(N, 6, 6))
    if dC is not None:
        out.append(vals[:, 42:])
    return out


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
    """The chart of the projective ED system: F(z; c), z = (y0, y1, y2, y3, mu, lam), with a.(y0..y3) = 1 and
    b.(mu, lam) = 1 as its last two equations (random complex a, b); batched over points with one cubic per
    point, as :func:`cdpr_algebra.homotopy.many_targets.solve_targets` wants its systems."""

    n = neq = 6

    def __init__(self, a, b):
        self.a = np.asarray(a, dtype=complex)
        self.b = np.asarray(b, dtype=complex)

    def parts(self, Z, C, jac=True, dC=None):
        """F (N, 6), J (N, 6, 6) and, for a coefficient direction dC (N, 20), dF/dc . dC (N, 6)."""
        return _ed_parts(Z, C, self.a, self.b, jac, dC)

    def evaluate(self, Z, C):
        return self.parts(Z, C, jac=False)[0]

    def evaluate_and_jacobian(self, Z, C):
        return tuple(self.parts(Z, C))

    def evaluate_directional(self, Z, C, dC):
        """F, dF/dz and dF/dc . dC (F is linear in c) in one generated evaluation."""
        return tuple(self.parts(Z, C, dC=dC))


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

    chart = True  # chart coordinates (y0 first): the endgame decides finite / at infinity there

    def __init__(self, start: _LinearProductStart, system: _EDSystem, c1, gamma):
        self.start, self.sys, self.gamma = start, system, complex(gamma)
        self.c1 = np.asarray(c1, dtype=complex)
        self.n = self.neq = 6

    def evaluate_all(self, x, t):
        G, JG = self.start.parts(x)
        F, JF = self.sys.parts(x, self.c1)
        a = (self.gamma * np.asarray(t, dtype=complex))[:, None]
        b = (1 - np.asarray(t, dtype=complex))[:, None]
        return a * G + b * F, a[..., None] * JG + b[..., None] * JF, self.gamma * G - F

    def evaluate_and_jacobian(self, x, t):
        return self.evaluate_all(x, t)[:2]

    def evaluate(self, x, t):
        return self.evaluate_all(x, t)[0]


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
        # only the regular endpoints are kept: no Cauchy endgame for the others
        tr = track_paths(_StartHomotopy(start, system, c1, gamma), start.solutions, chart_options(cauchy=False),
                         seed=seed)
        X = np.array([p.endpoint for p in tr.paths if p.status == SUCCESS]).reshape(-1, 6)
        if len(X):
            X = X[np.abs(X[:, 4]) > 1e-6]  # mu = 0: a singular point of the cubic, not a critical point
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
    """Real Newton on the generated affine Lagrange system (y - lam grad P(y), P(y)) (scaled coordinates)."""
    c = [float(v) for v in c]
    for _ in range(iters):
        vals = lagrange_system(*(float(v) for v in y), float(lam), *c)
        F = np.array(vals[:4], dtype=float)
        J = np.array(vals[4:], dtype=float).reshape(4, 4)
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


# Step control of the batched parameter homotopies: predictor tolerance 1e-4 (engine default 1e-5) halves the
# steps; measured on the 48 cubics of seed 002 Sec. IV-B.1 it gives the same critical points (to 2e-12), and the
# engine re-tracks any path that ends on the same point as another one.
PREDICTOR_TOL = 1e-4


def batch_options():
    """The engine options of the batched distance homotopies (:func:`cdpr_algebra.homotopy.many_targets.chart_options`)."""
    return chart_options(PREDICTOR_TOL)


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
    results = solve_targets(gen.system, gen.c1, gen.solutions, U, seed=seed, options=batch_options(), chart=True)
    for u, res in enumerate(results):
        solved[u] = _classify(U[u], scales[uniq[u]], res.track.paths, real_tol)
    return [solved[which[k]] for k in range(K)]


SINGULAR_POINT_MU = 0.05  # |mu| / |(mu, lam)| below this: the path may be heading for a singular point
# Newton's residual on (P, grad P), relative to the size of the terms: the cubics are interpolated from determinants,
# so a node of the true surface is a near-node of the cubic (measured: 1e-11 on CC [3..8] at (1, 0, 2), whose paths
# into that node do not converge in double precision); its point is on the surface to that accuracy, a candidate
SINGULAR_POINT_RESIDUAL = 1e-9


def _singular_point_near(c, z):
    """The singular point y (P(y) = 0 and grad P(y) = 0, complex) that Gauss-Newton on those four equations reaches
    from the chart point z, or None: z must be finite with |mu| small (the ED system's singular-point solutions
    have mu = 0) and Gauss-Newton must settle there with a residual below SINGULAR_POINT_RESIDUAL."""
    if not np.all(np.isfinite(z)) or abs(z[0]) <= 1e-8 * np.abs(z[:4]).max():
        return None
    if abs(z[4]) > SINGULAR_POINT_MU * np.abs(z[4:6]).max():
        return None
    y = z[1:4] / z[0]
    cc = [complex(v) for v in c]
    mag = np.abs(np.asarray(c, dtype=float)).sum()
    for _ in range(30):
        v = lagrange_system(*y, 1.0, *cc)  # with lam = 1: F[3] = P, J[3, :3] = grad P, J[:3, :3] = I - Hessian
        J = np.array(v[4:], dtype=complex).reshape(4, 4)
        grad, hess = J[3, :3], np.eye(3) - J[:3, :3]
        f = np.concatenate([[v[3]], grad])
        A = np.vstack([grad[None, :], hess])
        d = np.linalg.lstsq(A, -f, rcond=None)[0]
        y = y + d
        if np.abs(d).max() <= 1e-14 * (1 + np.abs(y).max()):
            break
    v = lagrange_system(*y, 1.0, *cc)
    J = np.array(v[4:], dtype=complex).reshape(4, 4)
    res = max(abs(v[3]), np.abs(J[3, :3]).max())
    scale = mag * (1 + np.abs(y).max()) ** 3
    return y if res <= SINGULAR_POINT_RESIDUAL * scale else None


def _classify(c, s, paths, real_tol):
    """Real critical points and singular points of one cubic from its paths (chart points; the endgame decided
    finite or at infinity)."""
    pts, kinds, lams = [], [], []
    failed = 0
    finite = 0
    for p in paths:
        st, z = p.status, p.endpoint
        if st in FAILURES:
            # a path whose endgame did not converge, heading for mu = 0: if its last point leads Newton to a
            # singular point of the surface (P = 0, grad P = 0: a node), the path is accounted for by that point,
            # a candidate of its own (and covered by the interval exclusion, which includes singular points)
            node = _singular_point_near(c, z)
            if node is None:
                failed += 1
                continue
            finite += 1
            if np.abs(node.imag).max() <= max(real_tol, 1e-5) * (1 + np.abs(node).max()):
                pts.append(node.real)
                kinds.append("singular point")
                lams.append(np.nan)
            continue
        if st not in (SUCCESS, SINGULAR):
            continue
        finite += 1
        y = z[1:4] / z[0]
        tol = real_tol if st == SUCCESS else max(real_tol, 1e-5)
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
                             failed, len(paths), finite, c, s)
