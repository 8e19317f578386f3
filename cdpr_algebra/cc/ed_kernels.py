"""The projective distance system of the robustness radii compiled (numba) over batches of points: the generated
:func:`cdpr_algebra.generated.cubic_distance.ed_directional_into` in a loop, for the batched homotopies of
:mod:`.cubic_distances` (the numpy evaluation of the same generated code costs about twice as much per call)."""

from __future__ import annotations

import numba as nb
import numpy as np

from cdpr_algebra.generated.cubic_distance import ed_directional_into

_into = nb.njit(cache=True)(ed_directional_into)


@nb.njit(cache=True)
def ed_batch(Z, C, a, b, D, out):
    """out[k] <- F (6), dF/dz (36, row by row), dF/dc . D[k] (6) at the chart point Z[k] for the cubic C[k]."""
    for k in range(Z.shape[0]):
        z = Z[k]
        c = C[k]
        d = D[k]
        _into(z[0], z[1], z[2], z[3], z[4], z[5], c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10], c[11], c[12], c[13], c[14], c[15], c[16], c[17], c[18], c[19], a[0], a[1], a[2], a[3], b[0], b[1], d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8], d[9], d[10], d[11], d[12], d[13], d[14], d[15], d[16], d[17], d[18], d[19], out[k])


def ed_values(Z, C, a, b, D=None) -> np.ndarray:
    """(N, 48) values of :func:`ed_batch` (D: zero direction when None)."""
    N = len(Z)
    Z = np.ascontiguousarray(Z, dtype=np.complex128)
    C = np.array(np.broadcast_to(np.asarray(C, dtype=np.complex128), (N, 20)), order="C")  # writable: one signature
    D = np.zeros((N, 20), dtype=np.complex128) if D is None else np.ascontiguousarray(D, dtype=np.complex128)
    out = np.empty((N, 48), dtype=np.complex128)
    ed_batch(Z, C, np.asarray(a, dtype=np.complex128), np.asarray(b, dtype=np.complex128), D, out)
    return out
