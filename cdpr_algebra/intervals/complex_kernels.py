"""Compiled complex-interval arithmetic and the compiled Krawczyk round of :mod:`.complex_krawczyk` (numba).

A complex interval is a 4-tuple (re lo, re hi, im lo, im hi) (a rectangle), a real one a pair (lo, hi); arrays
of them have a trailing axis of length 4.  The operations (``cc_mul``: complex times complex, ``cr_add``: complex
plus real, ...; :data:`OPERATIONS`) are those of :class:`.complex_krawczyk.ComplexPair` over
:class:`.arithmetic.Interval` parts, performed by the scalar twins of :mod:`.scalar_kernels` (the same outward
widening after every rounded operation), so an evaluator rewritten by :func:`.codegen.complex_interval_source`
gives the enclosures of the Python objects (real times real, exact floats in Python, is an interval product
here).

:func:`krawczyk_kernel` is one epsilon-inflation round of :func:`.complex_krawczyk.certify_complex_roots` for a
batch of roots, the operator of :func:`.operators.krawczyk` on the realified system (Cauchy-Riemann), root by root
without the GIL: J over the box and F at its centre by the rewritten evaluators, C = mid(J)^-1, and the
midpoint-radius products of :func:`.operators.mr_matmul` (Rump 1999, with the same rounding-error bound).
:func:`.real_kernels.real_subsystem_krawczyk_kernel` applies the same operator (:func:`_krawczyk_operator`) to real
boxes of a square subsystem of such an evaluator.
"""

from __future__ import annotations

import numba as nb
import numpy as np
from numba import types as nbt

from .arithmetic import _INF
from .scalar_kernels import rounding_gamma, s_add, s_down, s_mid, s_midrad, s_mr_bound, s_mul, s_sub, s_up

__all__ = ["OPERATIONS", "EVALUATOR_SIG", "EVALUATOR_TYPE", "krawczyk_kernel"]

_J = dict(cache=True, error_model="numpy")


# complex o complex
@nb.njit(**_J)
def cc_add(a, b):
    rl, rh = s_add(a[0], a[1], b[0], b[1])
    il, ih = s_add(a[2], a[3], b[2], b[3])
    return (rl, rh, il, ih)


@nb.njit(**_J)
def cc_sub(a, b):
    rl, rh = s_sub(a[0], a[1], b[0], b[1])
    il, ih = s_sub(a[2], a[3], b[2], b[3])
    return (rl, rh, il, ih)


@nb.njit(**_J)
def cc_mul(a, b):
    """(ar + i ai)(br + i bi) = (ar br - ai bi) + i (ar bi + ai br), each part in interval arithmetic."""
    p1l, p1h = s_mul(a[0], a[1], b[0], b[1])
    p2l, p2h = s_mul(a[2], a[3], b[2], b[3])
    p3l, p3h = s_mul(a[0], a[1], b[2], b[3])
    p4l, p4h = s_mul(a[2], a[3], b[0], b[1])
    rl, rh = s_sub(p1l, p1h, p2l, p2h)
    il, ih = s_add(p3l, p3h, p4l, p4h)
    return (rl, rh, il, ih)


@nb.njit(**_J)
def c_neg(a):
    return (-a[1], -a[0], -a[3], -a[2])


# complex o real, real o complex: the imaginary part as ComplexPair leaves it (untouched by + and -)
@nb.njit(**_J)
def cr_add(a, b):
    rl, rh = s_add(a[0], a[1], b[0], b[1])
    return (rl, rh, a[2], a[3])


@nb.njit(**_J)
def rc_add(a, b):
    rl, rh = s_add(b[0], b[1], a[0], a[1])
    return (rl, rh, b[2], b[3])


@nb.njit(**_J)
def cr_sub(a, b):
    rl, rh = s_sub(a[0], a[1], b[0], b[1])
    return (rl, rh, a[2], a[3])


@nb.njit(**_J)
def rc_sub(a, b):
    rl, rh = s_sub(a[0], a[1], b[0], b[1])
    return (rl, rh, -b[3], -b[2])


@nb.njit(**_J)
def cr_mul(a, b):
    rl, rh = s_mul(a[0], a[1], b[0], b[1])
    il, ih = s_mul(a[2], a[3], b[0], b[1])
    return (rl, rh, il, ih)


@nb.njit(**_J)
def rc_mul(a, b):
    rl, rh = s_mul(a[0], a[1], b[0], b[1])
    il, ih = s_mul(a[0], a[1], b[2], b[3])
    return (rl, rh, il, ih)


# real o real
@nb.njit(**_J)
def rr_add(a, b):
    return s_add(a[0], a[1], b[0], b[1])


@nb.njit(**_J)
def rr_sub(a, b):
    return s_sub(a[0], a[1], b[0], b[1])


@nb.njit(**_J)
def rr_mul(a, b):
    return s_mul(a[0], a[1], b[0], b[1])


@nb.njit(**_J)
def r_neg(a):
    return (-a[1], -a[0])


@nb.njit(**_J)
def r2c(a):
    return (a[0], a[1], 0.0, 0.0)


# loads and stores (arrays with a trailing axis of 4)
@nb.njit(**_J)
def c_ld(a, k):
    return (a[k, 0], a[k, 1], a[k, 2], a[k, 3])


@nb.njit(**_J)
def r_ld(a, k):
    return (a[k, 0], a[k, 1])


@nb.njit(**_J)
def c_st1(a, k, v):
    a[k, 0], a[k, 1], a[k, 2], a[k, 3] = v[0], v[1], v[2], v[3]


@nb.njit(**_J)
def c_st2(a, r, c, v):
    a[r, c, 0], a[r, c, 1], a[r, c, 2], a[r, c, 3] = v[0], v[1], v[2], v[3]


OPERATIONS = ["cc_add", "cc_sub", "cc_mul", "c_neg", "cr_add", "rc_add", "cr_sub", "rc_sub", "cr_mul", "rc_mul",
              "rr_add", "rr_sub", "rr_mul", "r_neg", "r2c", "c_ld", "r_ld", "c_st1", "c_st2"]


_C2 = nbt.float64[:, ::1]
_C3 = nbt.float64[:, :, ::1]
# (x, p, dp, F, J, Ht, with_ht) of a rewritten generated evaluator (x: n complex intervals, p: the parameters)
EVALUATOR_SIG = nbt.void(_C2, _C2, _C2, _C2, _C3, _C2, nbt.boolean)
EVALUATOR_TYPE = nbt.FunctionType(EVALUATOR_SIG)  # numba type of such an evaluator passed as an argument


@nb.njit(cache=True, error_model="numpy")
def _mr_product(Am, Ar, Bm, Br, with_ar, lo, hi):
    """[lo, hi] encloses {A B : |A - Am| <= Ar, |B - Bm| <= Br} (:func:`.operators.mr_matmul`; ``with_ar`` False: A
    is the point matrix Am, Ar unused, as Ar None there), the radius by :func:`.scalar_kernels.s_mr_bound`."""
    k = Am.shape[1]
    g = rounding_gamma(k)
    aA = np.abs(Am)
    S1 = Am @ Bm
    S2r = aA @ Br
    if with_ar:
        BB = np.empty_like(Bm)
        for i in range(Bm.shape[0]):
            for j in range(Bm.shape[1]):
                BB[i, j] = s_up(abs(Bm[i, j]) + Br[i, j])
        S2r += Ar @ BB
    S3 = aA @ np.abs(Bm)
    for i in range(S1.shape[0]):
        for j in range(S1.shape[1]):
            s2 = s_up(S2r[i, j])
            lo[i, j], hi[i, j] = s_mr_bound(S1[i, j], s2, S3[i, j] + s2, g, k)


@nb.njit(**_J)
def _krawczyk_operator(Jlo, Jhi, Flo, Fhi, y, r, C, Jm, Jr, Fm, Fr, Mlo, Mhi, Mm, Mr, Dm, Dr, CFlo, CFhi, MDlo, MDhi,
                       Klo, Khi):
    """K(X, y) = y - C F(y) + (I - C J(X)) (X - y), C = mid(J(X))^-1, for one box X = [y - r, y + r] (the floats
    fl(y -+ r)) from J(X) = [Jlo, Jhi] (h, h) and F(y) = [Flo, Fhi] (h,); the other arrays are workspace of their
    shapes ((h, h) or (h, 1)).  Writes Klo, Khi (h,); returns False (K = (-inf, inf)) when C could not be formed
    with a condition estimate below 1e14.  The operator of :func:`.operators.krawczyk`."""
    h = len(y)
    good = True
    for a in range(h):
        for b in range(h):
            Jm[a, b] = s_mid(Jlo[a, b], Jhi[a, b])
            if not np.isfinite(Jm[a, b]):
                good = False
    if good:
        try:
            C[:, :] = np.linalg.inv(Jm)
        except Exception:  # singular midpoint matrix
            good = False
    if good:
        c1 = 0.0
        c2 = 0.0
        for a in range(h):
            r1 = 0.0
            r2 = 0.0
            for b in range(h):
                r1 += abs(C[a, b])
                r2 += abs(Jm[a, b])
            c1 = max(c1, r1)
            c2 = max(c2, r2)
        cond = c1 * c2
        good = np.isfinite(cond) and cond < 1e14
    if not good:
        for k in range(h):
            Klo[k], Khi[k] = -_INF, _INF
        return False
    for k in range(h):
        Fm[k, 0], Fr[k, 0] = s_midrad(Flo[k], Fhi[k])
    _mr_product(C, C, Fm, Fr, False, CFlo, CFhi)  # C F(y)
    for a in range(h):
        for b in range(h):
            Jm[a, b], Jr[a, b] = s_midrad(Jlo[a, b], Jhi[a, b])
    _mr_product(C, C, Jm, Jr, False, Mlo, Mhi)  # C J(X), then I - C J(X)
    for a in range(h):
        for b in range(h):
            d = 1.0 if a == b else 0.0
            lo_, hi_ = s_down(d - Mhi[a, b]), s_up(d - Mlo[a, b])
            Mm[a, b], Mr[a, b] = s_midrad(lo_, hi_)
    for k in range(h):  # X - y
        dl, dh = s_sub(y[k] - r[k], y[k] + r[k], y[k], y[k])
        Dm[k, 0], Dr[k, 0] = s_midrad(dl, dh)
    _mr_product(Mm, Mr, Dm, Dr, True, MDlo, MDhi)
    for k in range(h):
        yl, yh = s_sub(y[k], y[k], CFlo[k, 0], CFhi[k, 0])
        Klo[k], Khi[k] = s_add(yl, yh, MDlo[k, 0], MDhi[k, 0])
    return True


@nb.njit(**_J)
def _workspace(n, h):
    """The work arrays of a kernel over an evaluator of n unknowns whose operator has h unknowns: x (n, 4), F (n, 4),
    J (n, n, 4), J(X) and F(y) as (lo, hi) (h, h) and (h,), then those of :func:`_krawczyk_operator`."""
    return (np.zeros((n, 4)), np.zeros((n, 4)), np.zeros((n, n, 4)), np.zeros((h, h)), np.zeros((h, h)), np.zeros(h),
            np.zeros(h), np.zeros((h, h)), np.zeros((h, h)), np.zeros((h, h)), np.zeros((h, 1)), np.zeros((h, 1)),
            np.zeros((h, h)), np.zeros((h, h)), np.zeros((h, h)), np.zeros((h, h)), np.zeros((h, 1)),
            np.zeros((h, 1)), np.zeros((h, 1)), np.zeros((h, 1)), np.zeros((h, 1)), np.zeros((h, 1)))


@nb.njit(nbt.void(EVALUATOR_TYPE, EVALUATOR_TYPE, nbt.float64[:, ::1], nbt.float64[:, ::1], nbt.float64[:, :, ::1],
                  nbt.float64[:, ::1], nbt.float64[:, ::1], nbt.boolean[::1]),
         cache=True, error_model="numpy", nogil=True)
def krawczyk_kernel(jac, res, Y, R, P, Klo, Khi, ok):
    """K(X, y) for the boxes X = Y -+ R (N, 2n: real parts, then imaginary parts) of the complex system whose
    rewritten evaluators are ``jac`` (J over a box, pattern entries) and ``res`` (F at a point), the parameters of
    root i in P[i] (np, 4).  Writes Klo, Khi (N, 2n) and ok (N,): C = mid(J(X))^-1 could be formed with a
    condition estimate below 1e14 (elsewhere K = (-inf, inf)).  The operator of :func:`.operators.krawczyk`
    (:func:`_krawczyk_operator`) on the realified Jacobian [[Re J, -Im J], [Im J, Re J]]."""
    N, h = Y.shape
    n = h // 2
    (x, F, J, Jlo, Jhi, Flo, Fhi, C, Jm, Jr, Fm, Fr, Mlo, Mhi, Mm, Mr, Dm, Dr, CFlo, CFhi, MDlo,
     MDhi) = _workspace(n, h)
    for i in range(N):
        p = P[i]
        for k in range(n):
            x[k, 0], x[k, 1] = Y[i, k] - R[i, k], Y[i, k] + R[i, k]
            x[k, 2], x[k, 3] = Y[i, n + k] - R[i, n + k], Y[i, n + k] + R[i, n + k]
        J[:] = 0.0
        jac(x, p, p, F, J, F, False)
        # realified Jacobian [[Re J, -Im J], [Im J, Re J]]
        for a in range(n):
            for b in range(n):
                rl, rh, il, ih = J[a, b, 0], J[a, b, 1], J[a, b, 2], J[a, b, 3]
                Jlo[a, b], Jhi[a, b] = rl, rh
                Jlo[n + a, n + b], Jhi[n + a, n + b] = rl, rh
                Jlo[n + a, b], Jhi[n + a, b] = il, ih
                Jlo[a, n + b], Jhi[a, n + b] = -ih, -il
        # F at the centre y (point intervals), realified
        for k in range(n):
            x[k, 0], x[k, 1], x[k, 2], x[k, 3] = Y[i, k], Y[i, k], Y[i, n + k], Y[i, n + k]
        res(x, p, p, F, J, F, False)
        for k in range(n):
            Flo[k], Fhi[k] = F[k, 0], F[k, 1]
            Flo[n + k], Fhi[n + k] = F[k, 2], F[k, 3]
        ok[i] = _krawczyk_operator(Jlo, Jhi, Flo, Fhi, Y[i], R[i], C, Jm, Jr, Fm, Fr, Mlo, Mhi, Mm, Mr, Dm, Dr,
                                   CFlo, CFhi, MDlo, MDhi, Klo[i], Khi[i])
