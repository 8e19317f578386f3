"""One tracking step compiled (numba): the linear predictor and Newton's corrector of :mod:`.branch` in machine
code, on the DGP's compiled evaluators and structured linear solve (:mod:`cdpr_algebra.dgp.kernels`, generated from
the one sympy source).  :func:`predict_correct` returns the same point as ``branch.tangent`` + ``branch.newton``
(to rounding), without the numpy overhead per call that dominates a real-time update."""

from __future__ import annotations

import numba as nb
import numpy as np

from cdpr_algebra.dgp.kernels import taut_apply, taut_factor, taut_fj, taut_fjt


@nb.njit(cache=True)
def predict_correct(x0, p0, p1, tol, residual_tol, residual_scale, max_its, xout):
    """x0 solves F(x; p0) = 0; xout <- the root of F(x; p1) reached by Newton from x0 - J^{-1} dF/dp . (p1 - p0).
    Returns (status, iterations, max |correction| (beyond 1e-9 relative) / max |prediction|, residual): status 1 converged (last update
    <= tol relative, or residual <= residual_tol after stalled updates), 0 not converged, -1 singular Jacobian."""
    n = x0.shape[0]
    F = np.empty(n, np.complex128)
    Ht = np.empty(n, np.complex128)
    J = np.zeros((n, n), np.complex128)
    A = np.zeros((n, n), np.complex128)
    piv = np.zeros(n, np.int64)
    d = np.empty(n, np.complex128)
    dp = np.empty(p0.shape[0], np.complex128)
    for i in range(p0.shape[0]):
        dp[i] = p1[i] - p0[i]
    taut_fjt(x0, p0, dp, F, J, Ht)
    if not taut_factor(J, A, piv):
        return -1, 0, np.inf, np.inf
    for i in range(n):
        Ht[i] = -Ht[i]
    taut_apply(J, A, piv, Ht, d)
    pred = 0.0
    for i in range(n):
        xout[i] = x0[i] + d[i].real
        pred = max(pred, abs(d[i].real))
    xp = xout.copy()
    prev = np.inf
    for k in range(max_its):
        taut_fj(xout, p1, F, J)
        if not taut_factor(J, A, piv):
            return -1, k, np.inf, np.inf
        for i in range(n):
            F[i] = -F[i]
        taut_apply(J, A, piv, F, d)
        big = 0.0
        step = 0.0
        for i in range(n):
            xout[i] = xout[i] + d[i].real
            big = max(big, abs(xout[i].real))
            step = max(step, abs(d[i].real))
        step /= 1.0 + big
        corr = 0.0
        for i in range(n):
            corr = max(corr, abs(xout[i].real - xp[i].real))
        # the correction beyond rounding (1e-9 relative), over the prediction
        excess = max(corr - 1e-9 * (1.0 + big), 0.0)
        ratio = excess / pred if pred > 0 else 0.0
        if step <= tol or (step <= prev and step <= 1e-6):
            taut_fj(xout, p1, F, J)
            res = 0.0
            for i in range(n):
                res = max(res, abs(F[i]))
            res /= residual_scale
            if step <= tol or res <= residual_tol:
                return 1, k + 1, ratio, res
        prev = step
    return 0, max_its, np.inf, np.inf
