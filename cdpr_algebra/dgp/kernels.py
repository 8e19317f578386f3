"""Compiled (numba) evaluators of the DGP taut-set equations of :mod:`cdpr_algebra.model.taut_equations`, for the compiled tracker.

``taut_fj(x, p, F, J)`` writes F and dF/dx, ``taut_fjt(x, p, dp, F, J, Ht)`` also Ht = dF/dp . dp, for any
m = 2 .. 6 (m = len(x) - 12), with x = (p, u, v, w, lam) and p = (A_i, rho_i^2, b'_i, g', Q d) in the order of
:func:`cdpr_algebra.model.taut_equations.taut_family`.  With R = [u v w], B_i = p + R b'_i, G = p + R g', s_i = B_i - A_i:

    F = (u.u - 1, v.v - 1, u.v, w - u x v, |s_i|^2 - rho_i^2, -sum lam_i s_i + Q d, G x Q d + sum lam_i B_i x A_i)

dF/dx by hand (d(a x c)/da = -[c]x, d(a x c)/dc = [a]x); Ht from dB_i = R db'_i, dG = R dg':
    2 s_i . (dB_i - dA_i) - d rho_i^2,   sum lam_i (dA_i - dB_i) + d(Qd),
    dG x Qd + G x d(Qd) + sum lam_i (dB_i x A_i + B_i x dA_i).
Only the nonzero pattern of J is written (the caller zeroes J once).  ``taut_factor`` / ``taut_apply`` solve
J d = b with w eliminated first and the lam columns pivoted first (see their docstrings).  Checked against the
sympy family and a dense solve in tests/test_dgp_kernels.py.  One compiled function serves every m (cached by numba on first use).
"""

from __future__ import annotations

import numba as nb
from numba import types as nbt

from cdpr_algebra.homotopy.compiled import APPLY_SIG, FACTOR_SIG, lu_apply_sparse_lead, lu_factor_sparse_lead

__all__ = ["taut_fj", "taut_fjt", "taut_factor", "taut_apply"]

_C1 = nbt.complex128[::1]
_C2 = nbt.complex128[:, ::1]


@nb.njit(cache=True)
def _eval(x, p, dp, F, J, Ht, with_ht):
    """F and J; with ``with_ht`` also Ht = dF/dp . dp (see the module doc), in the same pass."""
    m = x.shape[0] - 12
    ia, ir, ib = 0, 3 * m, 4 * m
    ig, i_f = 7 * m, 7 * m + 3
    P0, P1, P2 = x[0], x[1], x[2]
    u0, u1, u2 = x[3], x[4], x[5]
    v0, v1, v2 = x[6], x[7], x[8]
    w0, w1, w2 = x[9], x[10], x[11]
    f0, f1, f2 = p[i_f], p[i_f + 1], p[i_f + 2]
    g0, g1, g2 = p[ig], p[ig + 1], p[ig + 2]
    F[0] = u0 * u0 + u1 * u1 + u2 * u2 - 1.0
    F[1] = v0 * v0 + v1 * v1 + v2 * v2 - 1.0
    F[2] = u0 * v0 + u1 * v1 + u2 * v2
    F[3] = w0 - (u1 * v2 - u2 * v1)
    F[4] = w1 - (u2 * v0 - u0 * v2)
    F[5] = w2 - (u0 * v1 - u1 * v0)
    G0 = P0 + g0 * u0 + g1 * v0 + g2 * w0
    G1 = P1 + g0 * u1 + g1 * v1 + g2 * w1
    G2 = P2 + g0 * u2 + g1 * v2 + g2 * w2
    fo0, fo1, fo2 = f0, f1, f2
    mo0 = G1 * f2 - G2 * f1
    mo1 = G2 * f0 - G0 * f2
    mo2 = G0 * f1 - G1 * f0
    rf, rm = 6 + m, 9 + m
    # Ht: the rows 0-5 do not depend on the parameters; load terms dG x Qd + G x d(Qd), dG = R dg'
    hf0 = hf1 = hf2 = hm0 = hm1 = hm2 = 0j
    if with_ht:
        for k in range(6):
            Ht[k] = 0.0
        df0, df1, df2 = dp[i_f], dp[i_f + 1], dp[i_f + 2]
        dg0, dg1, dg2 = dp[ig], dp[ig + 1], dp[ig + 2]
        dG0 = dg0 * u0 + dg1 * v0 + dg2 * w0
        dG1 = dg0 * u1 + dg1 * v1 + dg2 * w1
        dG2 = dg0 * u2 + dg1 * v2 + dg2 * w2
        hf0, hf1, hf2 = df0, df1, df2
        hm0 = dG1 * f2 - dG2 * f1 + G1 * df2 - G2 * df1
        hm1 = dG2 * f0 - dG0 * f2 + G2 * df0 - G0 * df2
        hm2 = dG0 * f1 - dG1 * f0 + G0 * df1 - G1 * df0
    J[0, 3], J[0, 4], J[0, 5] = 2.0 * u0, 2.0 * u1, 2.0 * u2
    J[1, 6], J[1, 7], J[1, 8] = 2.0 * v0, 2.0 * v1, 2.0 * v2
    J[2, 3], J[2, 4], J[2, 5] = v0, v1, v2
    J[2, 6], J[2, 7], J[2, 8] = u0, u1, u2
    # d(w - u x v)/du = [v]x, /dv = -[u]x, /dw = I
    J[3, 4], J[3, 5] = -v2, v1
    J[4, 3], J[4, 5] = v2, -v0
    J[5, 3], J[5, 4] = -v1, v0
    J[3, 7], J[3, 8] = u2, -u1
    J[4, 6], J[4, 8] = -u2, u0
    J[5, 6], J[5, 7] = u1, -u0
    J[3, 9], J[4, 10], J[5, 11] = 1.0, 1.0, 1.0
    # moment rows, load part: d(G x f)/dG = -[f]x, G = p + g0 u + g1 v + g2 w
    for c in range(4):
        sc = 1.0 if c == 0 else (g0 if c == 1 else (g1 if c == 2 else g2))
        col = 3 * c
        J[rm, col + 1] = sc * f2
        J[rm, col + 2] = -sc * f1
        J[rm + 1, col] = -sc * f2
        J[rm + 1, col + 2] = sc * f0
        J[rm + 2, col] = sc * f1
        J[rm + 2, col + 1] = -sc * f0
        J[rm, col] = 0.0
        J[rm + 1, col + 1] = 0.0
        J[rm + 2, col + 2] = 0.0
        J[rf, col] = 0.0
        J[rf + 1, col + 1] = 0.0
        J[rf + 2, col + 2] = 0.0
    for i in range(m):
        a0, a1, a2 = p[ia + 3 * i], p[ia + 3 * i + 1], p[ia + 3 * i + 2]
        b0, b1, b2 = p[ib + 3 * i], p[ib + 3 * i + 1], p[ib + 3 * i + 2]
        B0 = P0 + b0 * u0 + b1 * v0 + b2 * w0
        B1 = P1 + b0 * u1 + b1 * v1 + b2 * w1
        B2 = P2 + b0 * u2 + b1 * v2 + b2 * w2
        s0, s1, s2 = B0 - a0, B1 - a1, B2 - a2
        lam = x[12 + i]
        F[6 + i] = s0 * s0 + s1 * s1 + s2 * s2 - p[ir + i]
        fo0 -= lam * s0
        fo1 -= lam * s1
        fo2 -= lam * s2
        c0 = B1 * a2 - B2 * a1
        c1 = B2 * a0 - B0 * a2
        c2 = B0 * a1 - B1 * a0
        mo0 += lam * c0
        mo1 += lam * c1
        mo2 += lam * c2
        r = 6 + i
        for c in range(4):
            sc = 2.0 if c == 0 else 2.0 * (b0 if c == 1 else (b1 if c == 2 else b2))
            col = 3 * c
            J[r, col], J[r, col + 1], J[r, col + 2] = sc * s0, sc * s1, sc * s2
            # force rows: -lam_i (I, b0 I, b1 I, b2 I)
            fs = lam * (1.0 if c == 0 else (b0 if c == 1 else (b1 if c == 2 else b2)))
            J[rf, col] -= fs
            J[rf + 1, col + 1] -= fs
            J[rf + 2, col + 2] -= fs
            # moment rows: lam_i d(B_i x A_i)/dB_i = -lam_i [A_i]x
            J[rm, col + 1] += fs * a2
            J[rm, col + 2] -= fs * a1
            J[rm + 1, col] -= fs * a2
            J[rm + 1, col + 2] += fs * a0
            J[rm + 2, col] += fs * a1
            J[rm + 2, col + 1] -= fs * a0
        J[rf, 12 + i], J[rf + 1, 12 + i], J[rf + 2, 12 + i] = -s0, -s1, -s2
        J[rm, 12 + i], J[rm + 1, 12 + i], J[rm + 2, 12 + i] = c0, c1, c2
        if with_ht:  # dB_i = R db'_i
            da0, da1, da2 = dp[ia + 3 * i], dp[ia + 3 * i + 1], dp[ia + 3 * i + 2]
            db0, db1, db2 = dp[ib + 3 * i], dp[ib + 3 * i + 1], dp[ib + 3 * i + 2]
            dB0 = db0 * u0 + db1 * v0 + db2 * w0
            dB1 = db0 * u1 + db1 * v1 + db2 * w1
            dB2 = db0 * u2 + db1 * v2 + db2 * w2
            Ht[6 + i] = 2.0 * (s0 * (dB0 - da0) + s1 * (dB1 - da1) + s2 * (dB2 - da2)) - dp[ir + i]
            hf0 += lam * (da0 - dB0)
            hf1 += lam * (da1 - dB1)
            hf2 += lam * (da2 - dB2)
            hm0 += lam * (dB1 * a2 - dB2 * a1 + B1 * da2 - B2 * da1)
            hm1 += lam * (dB2 * a0 - dB0 * a2 + B2 * da0 - B0 * da2)
            hm2 += lam * (dB0 * a1 - dB1 * a0 + B0 * da1 - B1 * da0)
    F[rf], F[rf + 1], F[rf + 2] = fo0, fo1, fo2
    F[rm], F[rm + 1], F[rm + 2] = mo0, mo1, mo2
    if with_ht:
        Ht[rf], Ht[rf + 1], Ht[rf + 2] = hf0, hf1, hf2
        Ht[rm], Ht[rm + 1], Ht[rm + 2] = hm0, hm1, hm2


@nb.njit(nbt.void(_C1, _C1, _C1, _C2), cache=True)
def taut_fj(x, p, F, J):
    _eval(x, p, p, F, J, F, False)  # dp and Ht unused


@nb.njit(nbt.void(_C1, _C1, _C1, _C1, _C2, _C1), cache=True)
def taut_fjt(x, p, dp, F, J, Ht):
    _eval(x, p, dp, F, J, Ht, True)


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
