"""Groups of items linked by pairs (single linkage): the connected components of the graph whose edges are the
pairs, by scipy's ``connected_components``; and the coincidence test of endpoints (:func:`duplicate_groups`,
:func:`coincides_with_any`) that makes those pairs."""

from __future__ import annotations

import numpy as np


def linked_groups(n: int, i, j) -> list:
    """The connected components of items 0..n-1 linked by the pairs (i[k], j[k]): lists of indices in increasing
    order, the groups ordered by their smallest member (singletons included).  scipy.sparse is imported only when
    there is a pair (its import costs ~0.1 s, and most calls have none: distinct endpoints)."""
    if n == 0:
        return []
    i = np.asarray(i, dtype=np.int64).ravel()
    j = np.asarray(j, dtype=np.int64).ravel()
    if not len(i):
        return [[k] for k in range(n)]
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(i), dtype=np.int8), (i, j)), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    groups = {}
    for k in range(n):
        groups.setdefault(int(label[k]), []).append(k)
    return list(groups.values())


def _agree(a, b, tol: float):
    """Rows of a and b (broadcast) agree in every coordinate to tol (1 + the larger modulus of that coordinate): the
    test of :func:`duplicate_groups` and :func:`coincides_with_any`."""
    return np.all(np.abs(a - b) <= tol * (1 + np.maximum(np.abs(a), np.abs(b))), axis=-1)


def coincides_with_any(points, x, tol: float) -> bool:
    """x agrees with some row of ``points`` (:func:`_agree`): the test of :func:`duplicate_groups`, for one point
    against many."""
    points = np.asarray(points)
    if not len(points):
        return False
    return bool(np.any(_agree(points, x, tol)))


DUPLICATE_CHUNK = 1 << 16  # candidate pairs tested at once by duplicate_groups


def duplicate_groups(points: np.ndarray, tol: float) -> list:
    """Groups (lists of row indices, size >= 2) of points that agree in every coordinate to tol (1 + |that
    coordinate|): each coordinate at its own scale, so that points with one huge coordinate and another that
    differs (x ~ 1e9, y = +-1) are not taken for one."""
    if len(points) < 2:
        return []

    order = np.argsort(points[:, 0].real)
    key = points[order, 0].real
    span = tol * (1 + np.max(np.abs(points[np.isfinite(points)]), initial=0.0))
    # candidate pairs (a, b), a < b in sorted order, whose first real parts are within span (a window per a), then
    # the test of every coordinate, vectorized over chunks of candidates
    N = len(order)
    hi = np.searchsorted(key, key + span, side="right")
    counts = np.maximum(hi - np.arange(N) - 1, 0)
    pi, pj = [], []
    start = 0
    while start < N:  # chunks of about DUPLICATE_CHUNK candidate pairs: memory stays O(DUPLICATE_CHUNK n)
        stop = min(N, start + 1 + int(np.searchsorted(np.cumsum(counts[start:]), DUPLICATE_CHUNK)))
        c = counts[start:stop]
        a = np.repeat(np.arange(start, stop), c)
        b = a + 1 + (np.arange(len(a)) - np.repeat(np.cumsum(c) - c, c))
        i, j = order[a], order[b]
        same = _agree(points[i], points[j], tol)
        pi.append(i[same])
        pj.append(j[same])
        start = stop
    i, j = np.concatenate(pi).astype(np.int64), np.concatenate(pj).astype(np.int64)
    return [g for g in linked_groups(len(points), i, j) if len(g) > 1]
