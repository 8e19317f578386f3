"""Groups of items linked by pairs (single linkage): the connected components of the graph whose edges are the
pairs, by scipy's ``connected_components``."""

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
