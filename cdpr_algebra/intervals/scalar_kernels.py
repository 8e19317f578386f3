"""Compiled scalar interval operations (numba): the s_* twins of the vectorized :class:`.arithmetic.Interval`
operations with the same "fast" widening, bit for bit, and the box-by-box kernel of the second-order operator."""

from __future__ import annotations

import numba as nb
import numpy as np

from .arithmetic import _CAP, _FLOOR, _INF, _TINY, _U


@nb.njit(cache=True, error_model="numpy")
def rounding_gamma(k: int) -> float:
    """A bound g >= gamma_k / (1 - gamma_k), gamma_k = k u / (1 - k u), u = 2^-53 (Higham, Thm. 3.1)."""
    return (k + 2) * 2.0 ** -53 * 1.01


# ---------------------------------------------------------------------------------------------------------------
# Compiled scalar interval operations (numba), for the per-box kernels of :mod:`cdpr_algebra.bp` and
# :meth:`QuadraticSystem.taylor_contract`.  Each takes and returns (lo, hi) float pairs and performs exactly the
# operations of the vectorized :class:`Interval` method of the same name with the default "fast" widening
# (x -+ min(|x| 2^-52 + 2^-900, 1e300) after every rounded operation), so the two give identical bounds
# (tests/test_interval_bp.py checks it bit for bit).  numba compiles IEEE 754 double arithmetic without fastmath:
# no reassociation and no contraction of a * b + c into a fused multiply-add.
@nb.njit(cache=True, error_model="numpy")
def s_down(x):
    t = abs(x) * _U + _TINY
    if t > _CAP:
        t = _CAP
    return x - t


@nb.njit(cache=True, error_model="numpy")
def s_up(x):
    t = abs(x) * _U + _TINY
    if t > _CAP:
        t = _CAP
    return x + t


@nb.njit(cache=True, error_model="numpy")
def s_fmin(a, b):
    """np.fmin: the smaller, a NaN counting as missing."""
    if a != a:
        return b
    if b != b:
        return a
    return a if a < b else b


@nb.njit(cache=True, error_model="numpy")
def s_fmax(a, b):
    if a != a:
        return b
    if b != b:
        return a
    return a if a > b else b


@nb.njit(cache=True, error_model="numpy")
def s_add(al, ah, bl, bh):
    return s_down(al + bl), s_up(ah + bh)


@nb.njit(cache=True, error_model="numpy")
def s_sub(al, ah, bl, bh):
    return s_down(al - bh), s_up(ah - bl)


@nb.njit(cache=True, error_model="numpy")
def s_mul(al, ah, bl, bh):
    p1 = al * bl
    p2 = al * bh
    p3 = ah * bl
    p4 = ah * bh
    return s_down(s_fmin(s_fmin(p1, p2), s_fmin(p3, p4))), s_up(s_fmax(s_fmax(p1, p2), s_fmax(p3, p4)))


@nb.njit(cache=True, error_model="numpy")
def s_div(al, ah, bl, bh):
    """Division; (-inf, inf) where the divisor contains 0.  Of the four quotients of the vectorized form only the two
    that the signs make extreme are computed (rounding is monotone, so they are also the extreme rounded ones)."""
    if bl > 0:
        lo = al / bh if al >= 0 else al / bl
        hi = ah / bl if ah >= 0 else ah / bh
    elif bh < 0:
        lo = ah / bh if ah >= 0 else ah / bl
        hi = al / bl if al >= 0 else al / bh
    else:
        return -_INF, _INF
    return s_down(lo), s_up(hi)


@nb.njit(cache=True, error_model="numpy")
def s_sqr(l, h):
    l2 = l * l
    h2 = h * h
    if l > 0:
        mn = l2
    elif h < 0:
        mn = h2
    else:
        mn = 0.0
    lo = s_down(mn)
    return (lo if lo > 0.0 else 0.0), s_up(s_fmax(l2, h2))


@nb.njit(cache=True, error_model="numpy")
def s_inv_sqr(yl, yh, xl, xh):
    """:func:`inv_sqr`: hull of x cap (-sqrt(y) u sqrt(y)), empty (lo > hi) if none."""
    s1 = s_down(np.sqrt(yl if yl > 0.0 else 0.0))
    if not s1 > 0.0:
        s1 = 0.0
    s2 = s_up(np.sqrt(yh if yh > 0.0 else 0.0)) if yh >= 0 else -_INF
    plo = s_fmax(xl, s1)
    phi = s_fmin(xh, s2)
    nlo = s_fmax(xl, -s2)
    nhi = s_fmin(xh, -s1)
    pok = plo <= phi
    nok = nlo <= nhi
    lo = nlo if nok else (plo if pok else _INF)
    hi = phi if pok else (nhi if nok else -_INF)
    return lo, hi


@nb.njit(cache=True, error_model="numpy")
def s_sub_exact(a, b):
    """[lo, hi] containing a - b for floats a, b, a point when the difference is a float: the error of the rounded
    difference is computed exactly (Knuth's TwoSum) and the bound widened only on its side.  Keeps the exact zeros
    of y - c0 zeros (a widened zero times a widened zero would underflow: slow subnormal arithmetic)."""
    c = -b
    s = a + c
    a1 = s - c
    c1 = s - a1
    e = (a - a1) + (c - c1)
    if e > 0:
        return s, s_up(s)
    if e < 0:
        return s_down(s), s
    if e == 0:
        return s, s
    return s_down(s), s_up(s)  # not finite


@nb.njit(cache=True, error_model="numpy")
def s_mid(lo, hi):
    """:attr:`Interval.mid`."""
    m = 0.5 * lo + 0.5 * hi
    if m < lo:
        m = lo
    if m > hi:
        m = hi
    return m


@nb.njit(cache=True, error_model="numpy")
def s_midrad(lo, hi):
    """:func:`midrad`: (m, r) with [m - r, m + r] containing [lo, hi]."""
    m = s_mid(lo, hi)
    r1 = s_up(hi - m)
    r2 = s_up(m - lo)
    return m, (r1 if r1 > r2 else r2)


@nb.njit(cache=True, error_model="numpy")
def s_mr_radius(S1, S2, S3, g, k):
    """The radius W of :func:`mr_matmul` for one dot product of length k: S1 = sum am bm, S2 = sum |am| br +
    ar (|bm| + br) (radius part), S3 = sum |am| |bm| + S2, all computed in floating point in any order, g = rounding_gamma(k);
    the exact product set lies in [S1 - W, S1 + W] (exact), and so does the computed pair (S1 - W, S1 + W)."""
    S3f = S3 if S3 > _FLOOR else _FLOOR
    return (S2 + S3f * g) * (1.0 + g + 2.0 ** -47) + abs(S1) * 2.0 ** -50 + k * 2.0 ** -1022


@nb.njit(cache=True, error_model="numpy")
def s_mr_bound(S1, S2, S3, g, k):
    """The enclosure (S1 - W, S1 + W) of :func:`s_mr_radius`."""
    W = s_mr_radius(S1, S2, S3, g, k)
    return S1 - W, S1 + W


_TINY_ENTRY = 2.0 ** -800


def _sparse_columns(Mm, Mr):
    """(ptr, row, m, r, tiny): the significant entries of the (k, n) midpoint-radius matrix (Mm, Mr), column by
    column (column j holds entries ptr[j]:ptr[j + 1]), and per column the largest radius ``tiny`` of the others (zero
    midpoint, radius <= 2^-800: widened zeros, e.g. structural zeros of J(c0) computed as [-2^-900, 2^-900]).  A
    product only adds tiny[j] * sum_k (|am_k| + ar_k) for those (:func:`_taylor_kernel`): multiplying two widened zeros
    would form subnormal numbers, about a hundred times slower."""
    small = (Mm == 0) & (Mr <= _TINY_ENTRY)
    cols, rows = np.nonzero((~small & ((Mm != 0) | (Mr != 0))).T)
    ptr = np.searchsorted(cols, np.arange(Mm.shape[1] + 1)).astype(np.int64)
    tiny = np.where(small, Mr, 0.0).max(axis=0)
    return (ptr, rows.astype(np.int64), np.ascontiguousarray(Mm[rows, cols]), np.ascontiguousarray(Mr[rows, cols]),
            np.ascontiguousarray(tiny))


@nb.njit(cache=True, error_model="numpy")
def float_inverse(A, C):
    """C = A^-1 by Gauss-Jordan elimination with partial pivoting, overwriting A (floats: a preconditioner, no
    rigour needed); False if a pivot vanishes or a result is not finite."""
    h = A.shape[0]
    for i in range(h):
        for j in range(h):
            C[i, j] = 1.0 if i == j else 0.0
    for k in range(h):
        p = k
        best = abs(A[k, k])
        for i in range(k + 1, h):
            if abs(A[i, k]) > best:
                best = abs(A[i, k])
                p = i
        if not best > 0.0:
            return False
        if p != k:
            for j in range(h):
                A[k, j], A[p, j] = A[p, j], A[k, j]
                C[k, j], C[p, j] = C[p, j], C[k, j]
        piv = 1.0 / A[k, k]
        for j in range(h):
            A[k, j] *= piv
            C[k, j] *= piv
        for i in range(h):
            if i != k:
                f = A[i, k]
                if f != 0.0:
                    for j in range(k + 1, h):  # columns < k of A are already eliminated, column k becomes 0
                        A[i, j] -= f * A[k, j]
                    A[i, k] = 0.0
                    for j in range(h):
                        C[i, j] -= f * C[k, j]
    for i in range(h):
        for j in range(h):
            if not np.isfinite(C[i, j]):
                return False
    return True


@nb.njit(cache=True, error_model="numpy")
def _sparse_midrad_sums(am_, ar_, ptr, row, bm_, br_, e, S2):
    """The sums of a midpoint-radius dot product of the vector (am_, ar_) with the sparse column e (rows
    row[ptr[e]:ptr[e+1]], midpoints bm_, radii br_): S1 = sum am bm (float), S3 = sum |am| |bm|, and the radius part
    S2 (starting from the given bound) += |am| br + ar (|bm| + br) rounded up, for :func:`s_mr_radius` /
    :func:`s_mr_bound`."""
    S1 = 0.0
    S3 = 0.0
    for q in range(ptr[e], ptr[e + 1]):
        k = row[q]
        am, ar = am_[k], ar_[k]
        bm, br = bm_[q], br_[q]
        S1 += am * bm
        S3 += abs(am) * abs(bm)
        S2 += abs(am) * br + ar * s_up(abs(bm) + br)
    return S1, S2, S3


@nb.njit(cache=True, error_model="numpy", nogil=True)  # releases the GIL: subproblems search in threads
def _taylor_kernel(lo, hi, c0, jh_ptr, jh_row, jh_m, jh_r, jh_t, sf_ptr, sf_row, sf_m, sf_r, sf_t, pj, pk, scale,
                   iterations, gain, excluded, inner):
    """Compiled second-order operator of :meth:`QuadraticSystem.taylor` applied to each box (row of lo, hi (N, h)),
    iterated as in the branch and prune: T(X) disjoint from X excludes the box (``excluded``), else X is replaced by
    X cap T(X), again while the sum of the scaled widths shrinks by more than ``gain``; ``inner``: some T(X) lay in
    the interior of X (by Brouwer's theorem X then holds a zero of F: a candidate for the unicity test).

    With y = mid X, d = x - y for a zero x of F in X: F(y) + J(y) d + (1/2) Q(d) = 0 exactly, so for C = mid(J(y))^-1
    (float), d = -C (F(y) + (1/2) Q(d)) - (C J(y) - I) d and T(X) = y - C S - (C J(y) - I)(X - y) with S enclosing
    F(y) + (1/2) Q(X - y) (the one-product form of :meth:`QuadraticSystem.taylor`, sparse columns sf_*).  J(y) =
    J(c0) + H (y - c0) is enclosed as midpoint Jm and radius Jr from the sparse columns jh_* of [J(c0); H^T]
    (:func:`_sparse_columns`; the tiny entries add their bound to the radius part S2); the last
    term is bounded in magnitude, |C J(y) - I| <= |fl(C Jm) - I| (1 + 2u) + gamma |C| |Jm| + |C| Jr with |C| |Jm| <=
    (row sums of |C|) (column maxima of |Jm|) and the same for Jr (it is a rounding-error term), every operation on
    these non-negative bounds rounded upward.  Every other product is bounded as in :func:`mr_matmul` (a zero term
    left out of a sum changes nothing; the radius sums have 2k terms, hence gamma_2k)."""
    N, h = lo.shape
    npair = pj.shape[0]
    nS = 1 + h + 2 * npair
    gJ = rounding_gamma(2 * (h + 1))
    gS = rounding_gamma(2 * nS)
    gh = rounding_gamma(2 * h)
    y = np.empty(h)
    d0l = np.empty(h)
    d0h = np.empty(h)
    d0m = np.empty(h + 1)
    d0r = np.empty(h + 1)
    Jm = np.empty((h, h))
    Jr = np.empty((h, h))
    Aw = np.empty((h, h))
    C = np.empty((h, h))
    vin_m = np.empty(nS)
    vin_r = np.empty(nS)
    Sm = np.empty(h)
    Sr = np.empty(h)
    Dl = np.empty(h)
    Dh = np.empty(h)
    Dmag = np.empty(h)
    Tl = np.empty(h)
    Th = np.empty(h)
    r1 = np.empty(h)
    for n in range(N):
        excluded[n] = False
        inner[n] = False
        for it in range(iterations):
            w0 = 0.0
            for i in range(h):
                y[i] = s_mid(lo[n, i], hi[n, i])
                w0 += (hi[n, i] - lo[n, i]) / scale[i]
            # [1 | y - c0] in midpoint-radius form
            d0m[0] = 1.0
            d0r[0] = 0.0
            for i in range(h):
                d0l[i], d0h[i] = s_sub_exact(y[i], c0[i])
                d0m[i + 1], d0r[i + 1] = s_midrad(d0l[i], d0h[i])
            # J(y) = [1 | y - c0] [J(c0); H^T]: J(y) in [Jm - Jr, Jm + Jr]
            asum = 0.0  # sum_k |am_k| + ar_k, for the tiny entries
            for k in range(h + 1):
                asum = s_up(asum + s_up(abs(d0m[k]) + d0r[k]))
            for e in range(h * h):
                S1, S2, S3 = _sparse_midrad_sums(d0m, d0r, jh_ptr, jh_row, jh_m, jh_r, e, s_up(jh_t[e] * asum))
                Jm[e // h, e % h] = S1
                Jr[e // h, e % h] = s_mr_radius(S1, S2, S3 + S2, gJ, 2 * (h + 1))
            for i in range(h):
                for j in range(h):
                    Aw[i, j] = Jm[i, j]
            if not float_inverse(Aw, C):
                break
            # bound b_i >= |((C J(y) - I)(X - y))_i|
            for i in range(h):
                Dl[i], Dh[i] = s_sub(lo[n, i], hi[n, i], y[i], y[i])
                Dmag[i] = max(abs(Dl[i]), abs(Dh[i]))
            CB = 0.0  # sum_j (gamma max_k |Jm_kj| + max_k Jr_kj) |X - y|_j
            for j in range(h):
                mj = 0.0
                mr = 0.0
                for k in range(h):
                    mj = max(mj, abs(Jm[k, j]))
                    mr = max(mr, Jr[k, j])
                CB = s_up(CB + s_up(s_up(s_up(gh * mj) + mr) * Dmag[j]))
            for i in range(h):
                cr = 0.0
                for k in range(h):
                    cr = s_up(cr + abs(C[i, k]))
                for j in range(h):
                    r1[j] = 0.0
                for k in range(h):  # fl(C Jm), innermost loop over j (vectorizes)
                    c = C[i, k]
                    for j in range(h):
                        r1[j] += c * Jm[k, j]
                r1[i] -= 1.0
                sE = 0.0  # sum_j |fl(C Jm) - I|_ij |X - y|_j, 2h roundings: times (1 + 2 gamma_2h) bounds the exact
                for j in range(h):
                    sE += abs(r1[j]) * Dmag[j]
                bi = s_up(s_up(sE * (1.0 + 2.0 * gh)) + s_up(cr * CB))
                Tl[i] = -bi
                Th[i] = bi
            # S = F(c0) + J(c0)(y - c0) + (1/2) Q(y - c0) + (1/2) Q(X - y): one product
            vin_m[0] = 1.0
            vin_r[0] = 0.0
            for i in range(h):
                vin_m[1 + i], vin_r[1 + i] = d0m[1 + i], d0r[1 + i]
            for p in range(npair):
                j, k = pj[p], pk[p]
                if j == k:
                    ql, qh = s_sqr(d0l[j], d0h[j])
                    rl, rh = s_sqr(Dl[j], Dh[j])
                else:
                    ql, qh = s_mul(d0l[j], d0h[j], d0l[k], d0h[k])
                    rl, rh = s_mul(Dl[j], Dh[j], Dl[k], Dh[k])
                vin_m[1 + h + p], vin_r[1 + h + p] = s_midrad(ql, qh)
                vin_m[1 + h + npair + p], vin_r[1 + h + npair + p] = s_midrad(rl, rh)
            asum = 0.0
            for k in range(nS):
                asum = s_up(asum + s_up(abs(vin_m[k]) + vin_r[k]))
            for i in range(h):
                S1, S2, S3 = _sparse_midrad_sums(vin_m, vin_r, sf_ptr, sf_row, sf_m, sf_r, i, s_up(sf_t[i] * asum))
                a, b = s_mr_bound(S1, S2, S3 + S2, gS, 2 * nS)
                Sm[i], Sr[i] = s_midrad(a, b)
            # T = y - C S - [-b, b]
            for i in range(h):
                S1 = 0.0
                S2 = 0.0
                S3 = 0.0
                for k in range(h):
                    c = C[i, k]
                    S1 += c * Sm[k]
                    S3 += abs(c) * abs(Sm[k])
                    S2 += abs(c) * Sr[k]
                csl, csh = s_mr_bound(S1, S2, S3 + S2, gh, 2 * h)
                a, b = s_sub(y[i], y[i], csl, csh)
                Tl[i], Th[i] = s_sub(a, b, Tl[i], Th[i])
            out = False
            inside = True
            for i in range(h):
                if Tl[i] > hi[n, i] or Th[i] < lo[n, i]:
                    out = True
                if not (Tl[i] > lo[n, i] and Th[i] < hi[n, i]):
                    inside = False
            if out:
                excluded[n] = True
                break
            if inside:
                inner[n] = True
            w1 = 0.0
            for i in range(h):
                lo[n, i] = s_fmax(lo[n, i], Tl[i])
                hi[n, i] = s_fmin(hi[n, i], Th[i])
                w1 += (hi[n, i] - lo[n, i]) / scale[i]
            if not w1 < (1.0 - gain) * w0:
                break
