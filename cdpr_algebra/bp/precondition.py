"""The generalized inverse K of eq. 37 (Berti, Merlet and Carricato 2016, Sec. 4.3) that preconditions the statics
J(B) lam = -h(G) before the interval Gauss elimination, at the centres of a batch of boxes (float, no rounding
control needed: K only has to be some matrix)."""

from __future__ import annotations

import numpy as np


def condition_numbers(M):
    """Condition numbers of a batch of square matrices (inf where not finite)."""
    out = np.full(len(M), np.inf)
    fin = np.all(np.isfinite(M), axis=(1, 2))
    if fin.any():
        try:
            out[fin] = np.linalg.cond(M[fin])
        except np.linalg.LinAlgError:
            pass
    return out


def generalized_inverse(Jm, weight, use_w: bool):
    """K (N, m, R0): eq. 37 K = (W^T J)^-1 W^T (W: J with force and moment halves swapped) where well
    conditioned, else the weighted pseudoinverse (J^T S J)^-1 J^T S, S = diag(weight)."""
    N, R0, m = Jm.shape
    K = np.full((N, m, R0), np.nan)
    with np.errstate(all="ignore"):
        todo = np.ones(N, bool)
        if use_w and R0 == 6:
            W = Jm[:, [3, 4, 5, 0, 1, 2], :]
            M = np.einsum("nrj,nri->nji", W, Jm)
            cond = condition_numbers(M)
            good = np.isfinite(cond) & (cond < 1e8)
            if good.any():
                K[good] = np.linalg.solve(M[good], np.swapaxes(W[good], 1, 2))
            todo = ~good
        if todo.any():
            JS = np.swapaxes(Jm[todo], 1, 2) * weight[None, None, :]
            M = JS @ Jm[todo]
            cond = condition_numbers(M)
            good = np.isfinite(cond) & (cond < 1e12)
            Kt = np.full((int(todo.sum()), m, R0), np.nan)
            if good.any():
                Kt[good] = np.linalg.solve(M[good], JS[good])
            K[todo] = Kt
    return K
