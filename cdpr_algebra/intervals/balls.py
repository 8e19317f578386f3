"""Rigorous enclosures in ball arithmetic (python-flint ``arb``): the Krawczyk existence and uniqueness test for a
square system with epsilon-inflation around a floating-point root, and small helpers on arb boxes.

Krawczyk (Moore 1977; Rump, Acta Numerica 2010, Thm. 8.8): for a box X, a point y in X and any real matrix C,
    K(X) = y - C F(y) + (I - C J(X)) (X - y),
where J(X) encloses the Jacobian of F over X.  If K(X) lies in the interior of X, then C and every matrix of J(X)
are nonsingular and F has exactly one zero in X, and that zero lies in K(X).  This is the role of the Kantorovich
test of seed 000 Sec. 4.2 (existence and unicity in a small box), with no constants to bound by hand.

Everything is generic: the caller gives interval evaluators ``F(x) -> list`` and ``J(x) -> list of rows`` written
in plain arithmetic (they run on floats and on arb balls alike); parameters may be balls too (a parametric test:
then the statement holds for every parameter value in the balls).  arb rounds outward, so every enclosure is
rigorous.  Floats enter exactly (an arb made from a double is that double).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from flint import arb, arb_mat

EPS = np.finfo(float).eps


# ------------------------------------------------------------------------------------------- boxes
def ball(mid, rad: float = 0.0) -> arb:
    """The ball [mid +/- rad] (``mid`` a float is taken exactly; the radius is rounded up)."""
    return arb(float(mid), float(rad)) if rad else arb(float(mid))


def box(mids, rads=None) -> list:
    """A box as a list of balls; ``rads`` None gives the exact point."""
    mids = np.asarray(mids, dtype=float).ravel()
    if rads is None:
        return [arb(v) for v in mids.tolist()]
    rads = np.broadcast_to(np.asarray(rads, dtype=float), mids.shape)
    return [arb(m, r) for m, r in zip(mids.tolist(), rads.tolist())]


def mids(xs) -> np.ndarray:
    """Midpoints (rounded to doubles) of a list (or nested lists) of balls or numbers."""
    return np.array([[_mid(v) for v in row] for row in xs] if xs and isinstance(xs[0], (list, tuple))
                    else [_mid(v) for v in xs], dtype=float)


def _mid(v) -> float:
    return float(v)  # an arb converts to its midpoint


def lower(x) -> float:
    """The largest double <= every point of ``x`` (outward rounding of the lower end)."""
    x = arb(x)
    if not x.is_finite():
        return -np.inf
    lo = float(x.lower())
    while not arb(lo) <= x:
        lo = float(np.nextafter(lo, -np.inf))
    return lo


def upper(x) -> float:
    """The smallest double >= every point of ``x`` (outward rounding of the upper end)."""
    x = arb(x)
    if not x.is_finite():
        return np.inf
    hi = float(x.upper())
    while not arb(hi) >= x:
        hi = float(np.nextafter(hi, np.inf))
    return hi


def bounds(xs) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper) doubles enclosing each ball of an array-like of balls (any shape)."""
    arr = np.asarray(xs, dtype=object)
    lo = np.array([lower(v) for v in arr.ravel()], dtype=float).reshape(arr.shape)
    hi = np.array([upper(v) for v in arr.ravel()], dtype=float).reshape(arr.shape)
    return lo, hi


def width(x) -> float:
    """An upper bound of the width of the ball ``x``."""
    return float(upper(2 * arb(x).rad()))


def sign(x) -> str:
    """'positive' or 'negative' when the sign of every point of ``x`` is proven, else 'boundary' (0 in x)."""
    if x > 0:
        return "positive"
    if x < 0:
        return "negative"
    return "boundary"


def column(xs) -> arb_mat:
    return arb_mat(len(xs), 1, list(xs))


# --------------------------------------------------------------------------------------- Krawczyk
@dataclass(frozen=True)
class KrawczykResult:
    """Outcome of :func:`krawczyk_certify`.

    ``proven``: exactly one zero of F in ``box`` (then ``enclosure`` = K(X) intersected with X contains it);
    ``box``: the last box X tried (balls), ``center``: its midpoint (the Newton-refined root, doubles);
    ``newton_step``: |C F(x0)| of the reported root, relative to ``scale`` (max over components);
    ``reason``: why the test failed, else None.
    """

    proven: bool
    enclosure: list | None
    box: list | None
    center: np.ndarray
    iterations: int
    newton_step: float
    reason: str | None = None

    def relative_width(self, scale) -> float:
        """Max width of the enclosure divided by ``scale`` (per component), an upper bound."""
        if self.enclosure is None:
            return float("nan")
        s = np.broadcast_to(np.asarray(scale, dtype=float), (len(self.enclosure),))
        return max(width(v) / si for v, si in zip(self.enclosure, s))


def krawczyk_operator(F, J, center, radius, C, newton=None) -> tuple[list, list]:
    """(K(X), X) for the box X = center +/- radius, with K(X) = y - C F(y) + (I - C J(X)) (X - y), y = center.

    ``newton``: y - C F(y) as a column of balls, when already computed."""
    n = len(center)
    X = box(center, radius)
    Cm = C if isinstance(C, arb_mat) else arb_mat(np.asarray(C, dtype=float).tolist())
    if newton is None:
        newton = column(box(center)) - Cm * column(F(box(center)))
    M = arb_mat(n, n, [1 if i == j else 0 for i in range(n) for j in range(n)]) - Cm * arb_mat(J(X))
    K = newton + M * column(box(np.zeros(n), radius))
    return [K[i, 0] for i in range(n)], X


def krawczyk_certify(F, J, x0, scale, max_rel_width: float = 1e-9, max_iter: int = 10, F_float=None,
                     J_float=None) -> KrawczykResult:
    """Prove that a box of width <= ``max_rel_width`` * ``scale`` (per component) near the floating-point root
    ``x0`` contains exactly one zero of F.

    ``F(x)``, ``J(x)``: interval evaluators (lists of balls -> list of balls / list of rows of balls).
    ``scale``: the size of each unknown (a scalar or one per component), so that widths are comparable.
    ``F_float``, ``J_float``: optional floating-point evaluators (faster) for the approximate inverse C and the
    Newton step, which need not be rigorous.
    Steps: C = inverse of the midpoint Jacobian at x0; one Newton step y = x0 - C F(x0); then epsilon-inflation
    around y: X = y +/- r with r from |C F(y)|, tested with :func:`krawczyk_operator`, r enlarged from K(X) until
    K(X) lies in the interior of X or the width limit is passed.  The reported root must be within the width
    limit of the certified box (a root off by more is not certified: no box that tight contains it and a zero).
    """
    x0 = np.asarray(x0, dtype=float).ravel()
    n = len(x0)
    s = np.broadcast_to(np.asarray(scale, dtype=float), (n,)).copy()
    rmax = 0.5 * max_rel_width * s

    def fail(reason, it=0, step=float("nan"), center=x0, X=None):
        return KrawczykResult(False, None, X, center, it, step, reason)

    if not np.all(np.isfinite(x0)):
        return fail("the root is not finite")
    Jm = np.asarray(J_float(x0), dtype=float) if J_float else mids(J(box(x0)))
    try:
        C = np.linalg.inv(Jm)
    except np.linalg.LinAlgError:
        return fail("the Jacobian is singular at the root")
    if not np.all(np.isfinite(C)):
        return fail("the Jacobian is singular at the root")
    step = C @ (np.asarray(F_float(x0), dtype=float) if F_float else mids(F(box(x0))))
    rel_step = float(np.max(np.abs(step) / s))
    if not rel_step <= 0.5 * max_rel_width:
        return fail(f"the Newton step from the root is {rel_step:.1e} (relative to the unknowns' scale), more than "
                    f"the box tolerance {max_rel_width:.0e}: no solution proven that close to the root", 0, rel_step)
    y = x0 - step
    Cm = arb_mat(C.tolist())
    z = Cm * column(F(box(y)))
    newton = column(box(y)) - z
    zabs = np.array([upper(abs(z[i, 0])) for i in range(n)])
    floor = 4 * EPS * np.abs(y) + 1e-15 * s
    r = np.maximum(4 * zabs, floor)
    X = None
    for it in range(1, max_iter + 1):
        if np.any(r > rmax):
            return fail(f"Krawczyk test not satisfied in any box of width <= {max_rel_width:.0e} (relative) "
                        f"around the root: the zero is not proven to exist and be unique", it - 1, rel_step, y, X)
        K, X = krawczyk_operator(F, J, y, r, Cm, newton)
        if all(Xi.contains_interior(Ki) for Xi, Ki in zip(X, K)):
            enc = [Xi.intersection(Ki) for Xi, Ki in zip(X, K)]
            return KrawczykResult(True, enc, X, y, it, rel_step, None)
        dev = np.array([upper(abs(Ki - yi)) if Ki.is_finite() else np.inf for Ki, yi in zip(K, y.tolist())])
        r = np.maximum(2 * r, 1.5 * dev)
    return fail(f"Krawczyk test not satisfied after {max_iter} inflations", max_iter, rel_step, y, X)


# ------------------------------------------------------------------------------ symmetric inertia
def symmetric_inertia(K_balls) -> tuple[int, int] | None:
    """Proven (positives, negatives) eigenvalue counts, the same for every symmetric matrix in the ball matrix
    ``K_balls`` (list of rows), or None when a zero eigenvalue cannot be excluded.

    Method: V = eigenvectors of the midpoint (LAPACK, floating point, need not be exact); M = V^T K V is
    enclosed in ball arithmetic; if every Gershgorin disc of M excludes 0, M (hence V) is nonsingular, the discs
    on each side of 0 hold exactly as many eigenvalues as there are discs there (continuity), and by Sylvester's
    law of inertia K has the same counts.
    """
    Kmid = mids(K_balls)
    Kmid = 0.5 * (Kmid + Kmid.T)
    if not np.all(np.isfinite(Kmid)):
        return None
    _, V = np.linalg.eigh(Kmid)
    Vm = arb_mat(V.tolist())
    M = Vm.transpose() * arb_mat(K_balls) * Vm
    n = len(Kmid)
    e = M.entries()
    pos = neg = 0
    for i in range(n):
        rad = sum((e[i * n + j].abs_upper() for j in range(n) if j != i), arb(0))
        d = e[i * n + i]
        if d - rad > 0:
            pos += 1
        elif d + rad < 0:
            neg += 1
        else:
            return None
    return pos, neg
