"""Distances from the origin to many cubic surfaces at once (Merlet, robustness radii): the projective Lagrange
(Euclidean-distance) system of each cubic, solved by batched parameter homotopies from a generic instance; real
critical points and their distances."""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass
import numpy as np

from cdpr_algebra.homotopy.many_targets import INFINITY_Y0, LABEL_SCALE, track_many



# monomials y1^i y2^j y3^k of total degree <= 3 (the coefficient order of every cubic here)
MONOMIALS = tuple((i, j, k) for i in range(4) for j in range(4) for k in range(4) if i + j + k <= 3)
_EXPH = np.array([(3 - sum(m),) + m for m in MONOMIALS])  # homogeneous exponents (y0, y1, y2, y3), (20, 4)
_NODES = np.cos(np.pi * (np.arange(4) + 0.5) / 4)  # Chebyshev nodes in [-1, 1]
_VINV = np.linalg.inv(np.vander(_NODES, 4, increasing=True))
_GRID = np.stack(np.meshgrid(_NODES, _NODES, _NODES, indexing="ij"), -1).reshape(-1, 3)


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
        xend, status = track_many(_StartHomotopy(start, system, c1, gamma), start.solutions, seed,
                                  at_infinity=_chart_at_infinity)
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


# Step control of the batched parameter homotopies: predictor tolerance 1e-4 (engine default 1e-5) halves the
# steps; measured on the 48 cubics of seed 002 Sec. IV-B.1 it gives the same critical points (to 2e-12) and the
# duplicate check of track_many re-tracks any path that jumps onto another one.


def _batch_tracker():
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    return TrackerOptions(predictor_tol=1e-4)



def _chart_at_infinity(z):
    """The ED system's chart points with y0 ~ 0 (coordinates 0..3 are (y0 : y))."""
    return np.abs(z[:, 0]) <= INFINITY_Y0 * np.abs(z[:, :4]).max(axis=1)


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
        xend, status = track_many(hom, X0, seed, at_infinity=_chart_at_infinity, tracker=_batch_tracker())
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
