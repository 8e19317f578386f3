"""Interval operators on batches of boxes: forward-mode dual numbers for interval Jacobians, midpoint-radius
matrix products, the Krawczyk operator, the second-order (Taylor) operator of quadratic systems, and a float
Newton iteration to centre boxes on."""

from __future__ import annotations

import numpy as np

from .arithmetic import Dual, Interval, _FLOOR, _INF, down, dual_variables, stack, up
from .scalar_kernels import rounding_gamma
from .scalar_kernels import _sparse_columns, _taylor_kernel

__all__ = ["krawczyk", "matvec_point", "newton", "quadratic_form", "QuadraticSystem", "mr_matmul", "residual_interval"]


# ---------------------------------------------------------------------------------------------------------------
def _as_interval(v, N):
    if isinstance(v, Interval):
        return Interval(np.broadcast_to(v.lo, (N,)), np.broadcast_to(v.hi, (N,)))
    v = np.broadcast_to(np.asarray(v, dtype=float), (N,))
    return Interval(v, v)


def _jacobian(res, N, h, interval: bool):
    if interval:
        lo = np.zeros((N, len(res), h))
        hi = np.zeros((N, len(res), h))
        for r, d in enumerate(res):
            for k, x in d.g.items():
                x = _as_interval(x, N)
                lo[:, r, k] = x.lo
                hi[:, r, k] = x.hi
        return Interval(lo, hi)
    J = np.zeros((N, len(res), h))
    for r, d in enumerate(res):
        for k, x in d.g.items():
            J[:, r, k] = x
    return J


def midrad(M: Interval):
    """(mid, rad) with [mid - rad, mid + rad] containing M (rad rounded upward)."""
    m = M.mid
    return m, np.maximum(up(M.hi - m), up(m - M.lo))


def mr_matmul(Am, Ar, Bm, Br) -> Interval:
    """Rigorous enclosure of {A B : |A - Am| <= Ar, |B - Bm| <= Br} for batches of matrices (matmul shapes).

    Midpoint-radius product (Rump 1999): A B lies in Am Bm +- (|Am| Br + Ar (|Bm| + Br)).  The products are computed
    in floating point (BLAS); a dot product of length k computed in any order (with or without FMA) differs from the
    exact one by at most gamma_k times the sum of the absolute terms (Higham, Thm. 3.1), plus k 2^-1074 for
    underflow; those errors and the roundings of the bound itself are added to the radius (below)."""
    k = Am.shape[-1]
    g = rounding_gamma(k)
    S1 = Am @ Bm
    absA = np.abs(Am)
    absB = np.abs(Bm)
    S3 = absA @ absB
    if Br is None and Ar is None:
        S2 = np.zeros_like(S1)
    elif Ar is None:
        S2 = absA @ Br
        S3 = S3 + S2
    elif Br is None:
        S2 = Ar @ absB
        S3 = S3 + S2
    else:
        BB = up(absB + Br)
        S2 = up(absA @ Br + Ar @ BB)
        S3 = S3 + S2
    # All terms are >= 0.  W = (S2 + g S3)(1 + g + 2^-47) + 2^-50 |S1| + k 2^-1022 bounds the radius, the error of
    # the computed S1, the (at most six) roundings of computing W itself (16 u >= 6 u), and the rounding of the
    # final S1 -+ W (|fl(S1 - W) - (S1 - W)| <= u (|S1| + W), covered by the 2^-50 |S1| = 8 u |S1| term and the
    # factor); so [S1 - W, S1 + W] computed in round-to-nearest encloses the exact product set.
    W = (S2 + np.maximum(S3, _FLOOR) * g) * (1.0 + g + 2.0 ** -47) + np.abs(S1) * 2.0 ** -50 + k * 2.0 ** -1022
    return Interval(S1 - W, S1 + W)


def matvec_point(C, V: Interval) -> Interval:
    """C (N, h, k) float times interval vectors V (N, k), rigorous (:func:`mr_matmul`)."""
    Vm, Vr = midrad(V)
    out = mr_matmul(C, None, Vm[..., None], Vr[..., None])
    return Interval(out.lo[..., 0], out.hi[..., 0])


def residual_interval(residual, X: Interval):
    """F over the boxes X (N, h) with its interval Jacobian (N, h, h), via :class:`Dual` over Intervals."""
    N, h = X.lo.shape
    res = residual(dual_variables(X, interval=True))
    F = stack([_as_interval(r.v, N) for r in res], axis=1)
    return F, _jacobian(res, N, h, True)


def krawczyk(residual, X: Interval, y=None, JX: Interval | None = None, want_m: bool = False):
    """Krawczyk operator K(X, y) = y - C F(y) + (I - C J(X)) (X - y), C = mid(J(X))^-1, for a batch of boxes.

    ``residual(vars)`` maps a list of h numbers (floats, Intervals or Duals) to a list of h numbers.  Returns
    (K (Interval (N, h)), ok (N,) bool: C could be formed[, |I - C J(X)| (N, h, h) if ``want_m``]).  Every zero of F in X lies in K(X, y) (for any C); if
    K(X, y) lies in the interior of X, F has exactly one zero in X (Krawczyk / Moore).  ``y`` defaults to mid(X).
    """
    N, h = X.lo.shape
    if y is None:
        y = X.mid
    if JX is None:
        _, JX = residual_interval(residual, X)
    Jm = JX.mid
    C, ok = _inverse(Jm)
    with np.errstate(all="ignore"):
        cond = np.abs(C).sum(axis=2).max(axis=1) * np.abs(Jm).sum(axis=2).max(axis=1)
    ok &= np.isfinite(cond) & (cond < 1e14)
    C[~ok] = 0.0
    Fy = stack([_as_interval(r, N) for r in residual([Interval(y[:, k], y[:, k]) for k in range(h)])], axis=1)
    CF = matvec_point(C, Fy)
    Jm_, Jr_ = midrad(JX)
    CJ = mr_matmul(C, None, Jm_, Jr_)
    eye = np.eye(h)
    M = Interval(down(eye - CJ.hi), up(eye - CJ.lo))  # I - C J(X)
    Mm, Mr = midrad(M)
    D = X - y
    Dm, Dr = midrad(D)
    MD = mr_matmul(Mm, Mr, Dm[..., None], Dr[..., None])
    K = (y - CF) + Interval(MD.lo[..., 0], MD.hi[..., 0])
    K = Interval(np.where(ok[:, None], K.lo, -_INF), np.where(ok[:, None], K.hi, _INF))
    if want_m:
        return K, ok, np.abs(Mm) + Mr
    return K, ok


class QuadraticForm:
    """The constant second-order part of a quadratic system: (1/2) d^T H_i d = sum_p V[i, p] d_j(p) d_k(p) over the
    pairs p = (j, k), j <= k, with a non-zero Hessian entry; V an Interval (h, npairs)."""

    def __init__(self, pairs, V: Interval):
        self.pairs = pairs
        self.j = np.array([a for a, _ in pairs], dtype=int)
        self.k = np.array([b for _, b in pairs], dtype=int)
        self.V = V
        self.Vm, self.Vr = midrad(V)

    def pair_products(self, D: Interval) -> Interval:
        """The products d_j d_k (d_j^2 for j = k) of the pairs over the boxes D (N, h): Interval (N, npairs)."""
        Dj = Interval(D.lo[:, self.j], D.hi[:, self.j])
        Dk = Interval(D.lo[:, self.k], D.hi[:, self.k])
        P = Dj * Dk
        same = self.j == self.k
        if same.any():
            sqv = Dj.sqr()
            P = Interval(np.where(same, sqv.lo, P.lo), np.where(same, sqv.hi, P.hi))
        return P

    def enclose(self, D: Interval) -> Interval:
        """(1/2) Q(d) over the boxes d in D (N, h): an Interval (N, h)."""
        if not self.pairs:
            return Interval(np.zeros(D.lo.shape), np.zeros(D.lo.shape))
        Pm, Pr = midrad(self.pair_products(D))
        return mr_matmul(Pm, Pr, np.ascontiguousarray(self.Vm.T), np.ascontiguousarray(self.Vr.T))


def quadratic_form(residual, h: int) -> QuadraticForm:
    """The Hessians of a system of quadratic equations (constant), by nested forward differentiation over
    Intervals (rigorous enclosures of the constant second derivatives)."""
    zero = Interval(np.zeros(1), np.zeros(1))
    xs = [Dual(Dual(zero, {k: 1.0}), {k: 1.0}) for k in range(h)]
    res = residual(xs)
    H = {}
    for i, r in enumerate(res):
        if not isinstance(r, Dual):
            continue
        for j, gj in r.g.items():
            if not isinstance(gj, Dual):
                continue
            for k, hjk in gj.g.items():
                a, b = (j, k) if j <= k else (k, j)
                hv = hjk if isinstance(hjk, Interval) else Interval(np.float64(hjk), np.float64(hjk))
                hv = Interval(np.asarray(hv.lo).reshape(-1)[0], np.asarray(hv.hi).reshape(-1)[0])
                key = (i, a, b)
                if key in H:  # H_ijk and H_ikj enclose the same number
                    H[key] = H[key].intersect(hv)
                else:
                    H[key] = hv
    pairs = sorted({(a, b) for (_, a, b) in H})
    index = {p: n for n, p in enumerate(pairs)}
    lo = np.zeros((len(res), len(pairs)))
    hi = np.zeros((len(res), len(pairs)))
    for (i, a, b), hv in H.items():
        n = index[(a, b)]
        if a == b:  # (1/2) H_ijj d_j^2
            lo[i, n], hi[i, n] = down(0.5 * hv.lo), up(0.5 * hv.hi)
        else:  # (1/2)(H_ijk + H_ikj) d_j d_k = H_ijk d_j d_k
            lo[i, n], hi[i, n] = hv.lo, hv.hi
    return QuadraticForm(pairs, Interval(lo, hi))


def _inverse(Jm):
    """Batch inverse of float matrices; (C, ok) with C = 0 where not invertible or not finite."""
    ok = np.all(np.isfinite(Jm), axis=(1, 2))
    C = np.zeros_like(Jm)
    if ok.any():
        with np.errstate(all="ignore"):
            try:
                C[ok] = np.linalg.inv(Jm[ok])
            except np.linalg.LinAlgError:
                for k in np.flatnonzero(ok):
                    try:
                        C[k] = np.linalg.inv(Jm[k])
                    except np.linalg.LinAlgError:
                        ok[k] = False
        ok &= np.all(np.isfinite(C), axis=(1, 2))
        C[~ok] = 0.0
    return C, ok


class QuadraticSystem:
    """A square system of quadratic equations F (``residual``) expanded exactly about a point c0:
    F(x) = F(c0) + J(c0) d + (1/2) Q(d), J(x) = J(c0) + H d, d = x - c0, with F(c0), J(c0) and the constant
    Hessians H enclosed once (forward differentiation over Intervals); afterwards F and J over any batch of boxes
    are a few rigorous matrix products (:func:`mr_matmul`) instead of a new differentiation per box."""

    def __init__(self, residual, h: int, c0):
        self.residual = residual
        self.h = h
        self.c0 = np.asarray(c0, dtype=float)
        self.quad = quadratic_form(residual, h)
        F0, J0 = residual_interval(residual, Interval(self.c0[None], self.c0[None]))
        self.F0 = F0[0]
        self.J0 = J0[0]
        self.J0m, self.J0r = midrad(self.J0)
        # H as an (h*h, h) matrix: J(x)_ij = J0_ij + sum_k H_ijk d_k
        lo = np.zeros((h, h, h))
        hi = np.zeros((h, h, h))
        V = self.quad.V
        for p, (j, k) in enumerate(self.quad.pairs):
            vl, vh = V.lo[:, p], V.hi[:, p]
            if j == k:  # (1/2) H_ijj d_j^2: H_ijj = 2 V
                lo[:, j, j], hi[:, j, j] = down(2.0 * vl), up(2.0 * vh)
            else:  # H_ijk d_j d_k with H_ijk = H_ikj = V
                lo[:, j, k], hi[:, j, k] = vl, vh
                lo[:, k, j], hi[:, k, j] = vl, vh
        self.Hm, self.Hr = midrad(Interval(lo.reshape(h * h, h), hi.reshape(h * h, h)))
        self.HmT = np.ascontiguousarray(self.Hm.T)
        self.HrT = np.ascontiguousarray(self.Hr.T)
        # stacked coefficient matrices of the one-product forms used by :meth:`taylor`
        self._JHm = np.vstack([self.J0m.reshape(1, h * h), self.HmT])
        self._JHr = np.vstack([self.J0r.reshape(1, h * h), self.HrT])
        F0m, F0r = midrad(self.F0)
        VmT, VrT = self.quad.Vm.T, self.quad.Vr.T
        self._SFm = np.ascontiguousarray(np.vstack([F0m[None], self.J0m.T, VmT, VmT]))
        self._SFr = np.ascontiguousarray(np.vstack([F0r[None], self.J0r.T, VrT, VrT]))
        # the non-zero entries of [J(c0); H^T] column by column (H is sparse), for the compiled operator
        self._jh = _sparse_columns(self._JHm, self._JHr)
        self._sf = _sparse_columns(self._SFm, self._SFr)
        self._pj = self.quad.j.astype(np.int64)
        self._pk = self.quad.k.astype(np.int64)

    def jacobian(self, X: Interval) -> Interval:
        """J over the boxes X (N, h): J(c0) + H (X - c0), an Interval (N, h, h)."""
        N = X.lo.shape[0]
        D = X - self.c0
        Dm, Dr = midrad(D)
        HD = mr_matmul(Dm, Dr, self.HmT, self.HrT)  # (N, h*h)
        h = self.h
        return Interval(down(HD.lo.reshape(N, h, h) + self.J0.lo), up(HD.hi.reshape(N, h, h) + self.J0.hi))

    def value(self, X: Interval) -> Interval:
        """F over the boxes X by the expansion (exact form; use ``residual`` for accurate values at points)."""
        D = X - self.c0
        Dm, Dr = midrad(D)
        JD = mr_matmul(Dm, Dr, np.ascontiguousarray(self.J0m.T), np.ascontiguousarray(self.J0r.T))
        return self.F0 + JD + self.quad.enclose(D)

    def point_value(self, y) -> Interval:
        """F at the points y (N, h), evaluated directly from the residual (no cancellation of the expansion)."""
        N = y.shape[0]
        return stack([_as_interval(r, N) for r in self.residual([Interval(y[:, k], y[:, k])
                                                                 for k in range(self.h)])], axis=1)

    def taylor(self, X: Interval, y=None, scale=None):
        """The second-order operator T(X) = y - C F(y) - (C J(y) - I)(X - y) - C (1/2) Q(X - y), exact form of
        the quadratic system, C = mid(J(y))^-1: every zero of F in X lies in T(X); about twice as tight as the
        Krawczyk operator (whose remainder (I - C J(X))(X - y) is Q's interval form without the 1/2 and with
        d_j^2 over [-r^2, r^2]).  Returns (T (N, h), ok (N,))."""
        N, h = X.lo.shape
        if y is None:
            y = X.mid
        D0 = Interval(y, y) - self.c0  # y - c0, enclosed
        D0m, D0r = midrad(D0)
        ones = np.ones((N, 1))
        zeros = np.zeros((N, 1))
        # J(y) = J(c0) + H (y - c0): one product [1 | y - c0] [J(c0); H]
        Jy = mr_matmul(np.hstack([ones, D0m]), np.hstack([zeros, D0r]), self._JHm, self._JHr)
        Jmm, Jrr = midrad(Interval(Jy.lo.reshape(N, h, h), Jy.hi.reshape(N, h, h)))
        C, ok = _inverse(Jmm)
        D = X - y
        Dm, Dr = midrad(D)
        # F(y) + (1/2) Q(X - y) = F(c0) + J(c0)(y - c0) + (1/2) Q(y - c0) + (1/2) Q(X - y): one product
        P0m, P0r = midrad(self.quad.pair_products(D0))
        P1m, P1r = midrad(self.quad.pair_products(D))
        Sm_in = np.hstack([ones, D0m, P0m, P1m])
        Sr_in = np.hstack([zeros, D0r, P0r, P1r])
        S = mr_matmul(Sm_in, Sr_in, self._SFm, self._SFr)  # (N, h)
        Sm, Sr = midrad(S)
        CS = mr_matmul(C, None, Sm[..., None], Sr[..., None])
        A = mr_matmul(C, None, Jmm, Jrr)
        eye = np.eye(h)
        AmI = Interval(down(A.lo - eye), up(A.hi - eye))
        Am, Ar = midrad(AmI)
        AD = mr_matmul(Am, Ar, Dm[..., None], Dr[..., None])
        T = y - Interval(CS.lo[..., 0], CS.hi[..., 0]) - Interval(AD.lo[..., 0], AD.hi[..., 0])
        T = Interval(np.where(ok[:, None], T.lo, -_INF), np.where(ok[:, None], T.hi, _INF))
        if scale is None:
            return T, ok
        # bisection score of each variable: its share of the second-order part of the width of T,
        # sum_i |C| |V| (pairs containing the variable) |d_j d_k| / scale_i
        contrib = np.einsum("nih,hp->np", np.abs(C) / scale[None, :, None], np.abs(self.quad.Vm)) * P1r  # (N, npairs)
        score = np.zeros((N, h))
        np.add.at(score, (slice(None), self.quad.j), contrib)
        np.add.at(score, (slice(None), self.quad.k), contrib)
        return T, ok, score

    def taylor_contract(self, lo, hi, scale, iterations: int, gain: float):
        """The operator of :meth:`taylor` (y = mid X) on each box of (lo, hi) (N, h), compiled, applied up to
        ``iterations`` times while the sum of the widths / ``scale`` shrinks by more than ``gain``: returns
        (lo, hi, excluded, inner) -- X cap T(X), whether T(X) is disjoint from X (no zero of F in X), whether some
        T(X) lay in the interior of X (a zero of F in X; unicity is the Krawczyk test's business)."""
        lo = np.array(lo, dtype=float, order="C")
        hi = np.array(hi, dtype=float, order="C")
        excluded = np.zeros(len(lo), dtype=np.bool_)
        inner = np.zeros(len(lo), dtype=np.bool_)
        if len(lo):
            _taylor_kernel(lo, hi, self.c0, *self._jh, *self._sf, self._pj, self._pk, np.asarray(scale, dtype=float),
                           int(iterations), float(gain), excluded, inner)
        return lo, hi, excluded, inner

    def krawczyk(self, X: Interval, y=None, want_m: bool = False):
        """:func:`krawczyk` with J(X) from the expansion and F(y) from the residual."""
        return krawczyk(self.residual, X, y, JX=self.jacobian(X), want_m=want_m)


def newton(residual, x0, iterations: int = 8, tol: float = 1e-13):
    """Float Newton iterations from x0 (N, h), vectorized; returns (x, converged (N,) bool, last step norm)."""
    x = np.array(x0, dtype=float)
    N, h = x.shape
    step = np.full(N, np.inf)
    alive = np.ones(N, bool)
    for _ in range(iterations):
        res = residual(dual_variables(x, interval=False))
        F = np.stack([np.broadcast_to(r.v, (N,)) for r in res], axis=1)
        J = _jacobian(res, N, h, False)
        with np.errstate(all="ignore"):
            good = alive & np.all(np.isfinite(J), axis=(1, 2)) & np.all(np.isfinite(F), axis=1)
            dx = np.zeros_like(x)
            if good.any():
                try:
                    dx[good] = np.linalg.solve(J[good], F[good][..., None])[..., 0]
                except np.linalg.LinAlgError:
                    for k in np.flatnonzero(good):
                        try:
                            dx[k] = np.linalg.solve(J[k], F[k])
                        except np.linalg.LinAlgError:
                            good[k] = False
            alive = good & np.all(np.isfinite(dx), axis=1)
            x = np.where(alive[:, None], x - dx, x)
            step = np.where(alive, np.max(np.abs(dx), axis=1) / (1 + np.max(np.abs(x), axis=1)), np.inf)
        if not np.any(alive & (step > tol)):
            break
    return x, alive & (step <= 1e-8), step
