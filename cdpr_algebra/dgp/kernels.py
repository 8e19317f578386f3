"""Compiled (numba) evaluators of the DGP taut-set equations of :mod:`cdpr_algebra.model.taut_equations`, for the
compiled tracker.

``taut_fj(x, p, F, J)`` writes F and dF/dx, ``taut_fjt(x, p, dp, F, J, Ht)`` also Ht = dF/dp . dp, for any
m = 2 .. 6 (m = len(x) - 12), with x = (p, u, v, w, lam) and p = (A_i, rho_i^2, b'_i, g', Q d) in the order of
:func:`cdpr_algebra.model.taut_equations.taut_family`: the generated
:func:`cdpr_algebra.generated.taut_equations.taut_equations` (derived from that family by
``derivations/derive_taut_equations.py``) compiled for one point; ``taut_fj_batch`` / ``taut_jp_batch`` loop it
over rows of points.  Only the nonzero pattern of J is written (the caller zeroes J once).  ``taut_factor`` /
``taut_apply`` solve J d = b with w eliminated first and the lam columns pivoted first (see their docstrings).
Checked against the sympy family and a dense solve in tests/test_dgp_kernels.py.  One compiled function serves
every m (cached by numba on first use).
"""

from __future__ import annotations

import numba as nb
from numba import types as nbt

from cdpr_algebra.generated.taut_equations import taut_equations, taut_parameter_jacobian
from cdpr_algebra.homotopy.compiled import APPLY_SIG, FACTOR_SIG, lu_apply_sparse_lead, lu_factor_sparse_lead

__all__ = ["taut_fj", "taut_fj_batch", "taut_fjt", "taut_jp_batch", "taut_factor", "taut_apply", "chart_factor",
           "chart_apply"]

_C1 = nbt.complex128[::1]
_C2 = nbt.complex128[:, ::1]


# F, J and Ht from the one generated source (derivations/derive_taut_equations.py), compiled for one point
_eval = nb.njit(cache=True)(taut_equations)


@nb.njit(nbt.void(_C1, _C1, _C1, _C2), cache=True)
def taut_fj(x, p, F, J):
    _eval(x, p, p, F, J, F, False)  # dp and Ht unused


@nb.njit(nbt.void(_C1, _C1, _C1, _C1, _C2, _C1), cache=True)
def taut_fjt(x, p, dp, F, J, Ht):
    _eval(x, p, dp, F, J, Ht, True)


_jp = nb.njit(cache=True)(taut_parameter_jacobian)


@nb.njit(cache=True)
def taut_fj_batch(X, P, F, J, with_j):
    """F (and J when ``with_j``) at every row of X with the parameters in the same row of P (zeroed J)."""
    for k in range(X.shape[0]):
        if with_j:
            _eval(X[k], P[k], P[k], F[k], J[k], F[k], False)
        else:
            _eval(X[k], P[k], P[k], F[k], J[0], F[k], False)


@nb.njit(cache=True)
def taut_jp_batch(X, P, JP):
    """dF/dp at every row of X with the parameters in the same row of P (zeroed JP)."""
    for k in range(X.shape[0]):
        _jp(X[k], P[k], JP[k])


@nb.njit(cache=True)
def _reduced_row(r, m):
    """The row of J that is row r of the reduced system: statics rows, then u.u, v.v, u.v, then the spheres."""
    if r < 6:
        return 6 + m + r
    if r < 9:
        return r - 6
    return r - 3


@nb.njit(FACTOR_SIG, cache=True, error_model="numpy")
def taut_factor(J, A, piv):
    """LU factors (in A, piv) of the reduced system of a Jacobian of the taut family: w eliminated, lam pivoted
    first.

    Rows 3-5 (w - u x v) read dw = b[3:6] - J[3:6, 3:9] d(u, v) (their w block is the identity), so the other
    rows give the reduced system (unknowns p, u, v, lam; n - 3 of them)
    sum_j (J[i, j] - J[i, w] J[3:6, j]) d_j = b_i - J[i, w] b[3:6].  It is assembled with the m lam columns
    first and the 6 statics rows on top: lam enters no other row, so the first m eliminations touch those 6
    rows only (:func:`.homotopy.compiled.lu_factor_sparse_lead`), and the rest is a dense 9 x 9 elimination
    (partial pivoting throughout; a singular lam block makes J singular, so nothing is lost).  False when the
    reduced system (hence J) is singular."""
    n = J.shape[1]
    m = n - 12
    k = n - 3
    for r in range(k):
        i = _reduced_row(r, m)
        jw0, jw1, jw2 = J[i, 9], J[i, 10], J[i, 11]
        for c in range(m):
            A[r, c] = J[i, 12 + c]
        for j in range(9):
            v = J[i, j]
            if j >= 3:
                v -= jw0 * J[3, j] + jw1 * J[4, j] + jw2 * J[5, j]
            A[r, m + j] = v
    return lu_factor_sparse_lead(A, piv, k, m, 6)


@nb.njit(APPLY_SIG, cache=True, error_model="numpy")
def taut_apply(J, A, piv, b, out):
    """out = J^{-1} b from the factors of :func:`taut_factor` of this J (row n - 3 of A serves as scratch)."""
    n = b.shape[0]
    m = n - 12
    k = n - 3
    for r in range(k):
        i = _reduced_row(r, m)
        out[r] = b[i] - (J[i, 9] * b[3] + J[i, 10] * b[4] + J[i, 11] * b[5])
    lu_apply_sparse_lead(A, piv, out, k, m, 6)
    y = A[k]
    for c in range(k):
        y[c] = out[c]
    for j in range(9):
        out[j] = y[m + j]
    for c in range(m):
        out[12 + c] = y[c]
    for q in range(3):
        acc = b[3 + q]
        for j in range(3, 9):
            acc -= J[3 + q, j] * out[j]
        out[9 + q] = acc


@nb.njit(cache=True)
def _reverse(x, a, b):
    """x[a:b] reversed in place."""
    i, j = a, b - 1
    while i < j:
        x[i], x[j] = x[j], x[i]
        i += 1
        j -= 1


@nb.njit(cache=True)
def _chart_row(r, m):
    """The row of a chart Jacobian (the homogenized taut system, y0 first, then the chart row) that is row r of the
    reordered system: the 6 statics rows, the chart row, then the others in order."""
    if r < 6:
        return 6 + m + r
    if r == 6:
        return 12 + m
    return r - 7


@nb.njit(FACTOR_SIG, cache=True, error_model="numpy")
def chart_factor(J, A, piv):
    """LU factors (in A, piv) of a Jacobian of the taut system homogenized on a chart (unknowns y0, p, u, v, w, lam;
    rows F_h, then the chart row): lam enters only the 6 statics rows and the chart row, so with the lam columns
    first and those 7 rows on top the first m eliminations touch 7 rows only
    (:func:`.homotopy.compiled.lu_factor_sparse_lead`; partial pivoting, the factors of the full elimination of the
    reordered matrix), the rest is dense.  The w block is y0 I here (zero at infinity), so the w elimination of
    :func:`taut_factor` does not apply.  False when J is singular."""
    n = J.shape[1]
    m = n - 13
    for r in range(n):
        i = _chart_row(r, m)
        for c in range(m):
            A[r, c] = J[i, 13 + c]
        for j in range(13):
            A[r, m + j] = J[i, j]
    return lu_factor_sparse_lead(A, piv, n, m, 7)


@nb.njit(APPLY_SIG, cache=True, error_model="numpy")
def chart_apply(J, A, piv, b, out):
    """out = J^{-1} b from the factors of :func:`chart_factor`: the rows of b reordered into ``out``, solved there,
    and its entries (lam first) rotated back into place by three reversals (no allocation)."""
    n = b.shape[0]
    m = n - 13
    for r in range(n):
        out[r] = b[_chart_row(r, m)]
    lu_apply_sparse_lead(A, piv, out, n, m, 7)
    _reverse(out, 0, m)
    _reverse(out, m, n)
    _reverse(out, 0, n)
