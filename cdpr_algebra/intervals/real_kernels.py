"""The compiled Krawczyk operator of :mod:`.complex_kernels` over real boxes of a square subsystem (numba), for
:func:`.real_krawczyk.certify_real_roots`.

In its own module so that the programs that do not use it (the DGP) do not load it: numba loads every kernel of a
module with an explicit signature when the module is imported (~4 MiB each).
"""

from __future__ import annotations

import numba as nb
from numba import types as nbt

from .complex_kernels import EVALUATOR_TYPE, _krawczyk_operator, _workspace

__all__ = ["real_subsystem_krawczyk_kernel"]


@nb.njit(nbt.void(EVALUATOR_TYPE, EVALUATOR_TYPE, nbt.float64[:, ::1], nbt.float64[:, ::1], nbt.float64[:, :, ::1],
                  nbt.float64[:, ::1], nbt.int64[::1], nbt.int64[::1], nbt.float64[:, ::1], nbt.float64[:, ::1],
                  nbt.boolean[::1]),
         cache=True, error_model="numpy", nogil=True)
def real_subsystem_krawczyk_kernel(jac, res, Y, R, P, X0, rows, cols, Klo, Khi, ok):
    """K(X, y) for real boxes X = Y -+ R (N, h) of the square real subsystem F[rows](x) = 0 in the unknowns
    x[cols] of a system with real coefficients whose rewritten complex-interval evaluators are ``jac`` and ``res``
    (as :func:`.complex_kernels.krawczyk_kernel`), every other unknown of root i fixed at the real point X0[i]
    (N, n).  The real parts of the complex enclosures enclose the real function over the real box (the imaginary
    parts are zero).  Writes Klo, Khi (N, h) and ok (N,) as :func:`.complex_kernels.krawczyk_kernel` does."""
    N, h = Y.shape
    n = X0.shape[1]
    (x, F, J, Jlo, Jhi, Flo, Fhi, C, Jm, Jr, Fm, Fr, Mlo, Mhi, Mm, Mr, Dm, Dr, CFlo, CFhi, MDlo,
     MDhi) = _workspace(n, h)
    for i in range(N):
        p = P[i]
        for k in range(n):
            x[k, 0], x[k, 1], x[k, 2], x[k, 3] = X0[i, k], X0[i, k], 0.0, 0.0
        for k in range(h):
            x[cols[k], 0], x[cols[k], 1] = Y[i, k] - R[i, k], Y[i, k] + R[i, k]
        J[:] = 0.0
        jac(x, p, p, F, J, F, False)
        for a in range(h):
            for b in range(h):
                Jlo[a, b], Jhi[a, b] = J[rows[a], cols[b], 0], J[rows[a], cols[b], 1]
        for k in range(h):
            x[cols[k], 0], x[cols[k], 1] = Y[i, k], Y[i, k]
        res(x, p, p, F, J, F, False)
        for k in range(h):
            Flo[k], Fhi[k] = F[rows[k], 0], F[rows[k], 1]
        ok[i] = _krawczyk_operator(Jlo, Jhi, Flo, Fhi, Y[i], R[i], C, Jm, Jr, Fm, Fr, Mlo, Mhi, Mm, Mr, Dm, Dr,
                                   CFlo, CFhi, MDlo, MDhi, Klo[i], Khi[i])
