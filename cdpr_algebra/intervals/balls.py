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
rigorous.  Floats enter exactly (an arb made from a double is that double).  The inertia test
(:func:`symmetric_inertias`) reads the balls' midpoints and radii and bounds its floating-point products a priori.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

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
    return [arb(m, r) for m, r in zip(mids.tolist(), _per_component(rads, len(mids)).tolist())]


def _per_component(v, n: int) -> np.ndarray:
    """``v`` (a scalar or n values) as n doubles."""
    out = np.empty(n)
    out[...] = v
    return out


def mids(xs) -> np.ndarray:
    """Midpoints (rounded to doubles) of a list (or nested lists) of balls or numbers."""
    return np.array([[_mid(v) for v in row] for row in xs] if xs and isinstance(xs[0], (list, tuple))
                    else [_mid(v) for v in xs], dtype=float)


def _mid(v) -> float:
    return float(v)  # an arb converts to its midpoint


def lower(x) -> float:
    """The largest double <= every point of ``x`` (outward rounding of the lower end)."""
    if type(x) is not arb:
        x = arb(x)
    lo = float(x.lower())  # the double nearest to arb's lower end: at most one step down to go
    if lo < np.inf and x >= lo:
        return lo
    if not x.is_finite():
        return -np.inf
    while not x >= lo:
        lo = float(np.nextafter(lo, -np.inf))
    return lo


def upper(x) -> float:
    """The smallest double >= every point of ``x`` (outward rounding of the upper end)."""
    if type(x) is not arb:
        x = arb(x)
    hi = float(x.upper())
    if hi > -np.inf and x <= hi:
        return hi
    if not x.is_finite():
        return np.inf
    while not x <= hi:
        hi = float(np.nextafter(hi, np.inf))
    return hi


def bounds(xs) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper) doubles enclosing each ball of an array-like of balls (any shape)."""
    arr = np.asarray(xs, dtype=object)
    flat = arr.ravel().tolist()
    lo = np.array(list(map(lower, flat)), dtype=float).reshape(arr.shape)
    hi = np.array(list(map(upper, flat)), dtype=float).reshape(arr.shape)
    return lo, hi


def width(x) -> float:
    """An upper bound of the width of the ball ``x``."""
    if type(x) is not arb:
        x = arb(x)
    w = 2.0 * float(x.rad())  # exact for a radius in the normal range of doubles (a mag has a 30-bit mantissa)
    if 2.3e-308 < w < np.inf and w == 2 * x.rad():
        return w
    return upper(2 * x.rad())


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
NOT_FINITE = "the root is not finite"
SINGULAR = "the Jacobian is singular at the root"


def newton_step_reason(rel_step: float, max_rel_width: float) -> str:
    """Why a root whose Newton step is ``rel_step`` (relative to the unknowns' scale) is not certified."""
    return (f"the Newton step from the root is {rel_step:.1e} (relative to the unknowns' scale), more than the box "
            f"tolerance {max_rel_width:.0e}: no solution proven that close to the root")


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
        s = _per_component(scale, len(self.enclosure)).tolist()
        return max(width(v) / si for v, si in zip(self.enclosure, s))


@lru_cache(maxsize=None)
def _identity(n: int) -> arb_mat:
    """The n x n identity (shared: never modified)."""
    eye = arb_mat(n, n)
    for i in range(n):
        eye[i, i] = 1
    return eye


def krawczyk_operator(F, J, center, radius, C, newton=None) -> tuple[list, list]:
    """(K(X), X) for the box X = center +/- radius, with K(X) = y - C F(y) + (I - C J(X)) (X - y), y = center.

    ``newton``: y - C F(y) as a column of balls, when already computed."""
    n = len(center)
    X = box(center, radius)
    Cm = C if isinstance(C, arb_mat) else arb_mat(np.asarray(C, dtype=float).tolist())
    if newton is None:
        newton = column(box(center)) - Cm * column(F(box(center)))
    JX = J(X)
    M = _identity(n) - Cm * (JX if isinstance(JX, arb_mat) else arb_mat(JX))
    K = newton + M * column([arb(0, r) for r in _per_component(radius, n).tolist()])
    return K.entries(), X


def krawczyk_certify(F, J, x0, scale, max_rel_width: float = 1e-9, max_iter: int = 10, F_float=None,
                     J_float=None, inverse=None, residual=None, refine: int = 0) -> KrawczykResult:
    """Prove that a box of width <= ``max_rel_width`` * ``scale`` (per component) near the floating-point root
    ``x0`` contains exactly one zero of F.

    ``F(x)``, ``J(x)``: interval evaluators (lists of balls -> list of balls / list of rows of balls, or an
    arb_mat).  ``scale``: the size of each unknown (a scalar or one per component), so that widths are comparable.
    ``F_float``, ``J_float``: optional floating-point evaluators (faster) for the approximate inverse C and the
    Newton step, which need not be rigorous; or ``inverse`` (C) and ``residual`` (F(x0)) in floats, already
    computed (e.g. for many roots at once).
    Steps: C = inverse of the midpoint Jacobian at x0; one Newton step y = x0 - C F(x0); then epsilon-inflation
    around y: X = y +/- r with r from |C F(y)|, tested with :func:`krawczyk_operator`, r enlarged from K(X) until
    K(X) lies in the interior of X or the width limit is passed.  The reported root must be within the width
    limit of the certified box (a root off by more is not certified: no box that tight contains it and a zero).
    ``refine`` > 0: y from up to ``refine`` Newton steps in ball arithmetic at the working precision instead
    (:func:`refined_root`; a float Newton step on an ill-conditioned system is noise of about its condition number
    times 1e-16), and x0 must lie within the width limit of y.
    """
    x0 = np.asarray(x0, dtype=float).ravel()
    n = len(x0)
    s = _per_component(scale, n)
    rmax = 0.5 * max_rel_width * s

    def fail(reason, it=0, step=float("nan"), center=x0, X=None):
        return KrawczykResult(False, None, X, center, it, step, reason)

    if not np.all(np.isfinite(x0)):
        return fail(NOT_FINITE)
    if inverse is None:
        Jm = np.asarray(J_float(x0), dtype=float) if J_float else mids(J(box(x0)))
        try:
            C = np.linalg.inv(Jm)
        except np.linalg.LinAlgError:
            return fail(SINGULAR)
    else:
        C = np.asarray(inverse, dtype=float)
    if not np.all(np.isfinite(C)):
        return fail(SINGULAR)
    if residual is None:
        residual = F_float(x0) if F_float else mids(F(box(x0)))
    step = C @ np.asarray(residual, dtype=float)
    rel_step = float(np.max(np.abs(step) / s))
    Cm = arb_mat(C.tolist())
    y = refined_root(F, Cm, x0, s, refine) if refine else None
    if y is not None:
        rel_step = float(np.max(np.abs(y - x0) / s))
    if not rel_step <= 0.5 * max_rel_width:
        return fail(newton_step_reason(rel_step, max_rel_width), 0, rel_step)
    if y is None:
        y = x0 - step
    yb = box(y)
    z = Cm * column(F(yb))
    newton = column(yb) - z
    zabs = np.array(list(map(float, map(arb.abs_upper, z.entries()))))  # ~|C F(y)|, only sizes the first box
    zabs[np.isnan(zabs)] = np.inf
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


def refined_root(F, C, x0, scale, steps: int = 8):
    """Newton's method x <- x - C F(x) from ``x0`` (C: an approximate inverse of the Jacobian, doubles or arb_mat)
    with F in ball arithmetic at the working precision (midpoints only: nothing is proven here), at most
    ``steps`` steps; the root rounded to doubles, or None when the steps do not fall below 4 EPS of ``scale`` (the
    size of each unknown)."""
    Cm = C if isinstance(C, arb_mat) else arb_mat(np.asarray(C, dtype=float).tolist())
    x0 = np.asarray(x0, dtype=float).ravel()
    s = _per_component(scale, len(x0))
    x = [arb(v) for v in x0.tolist()]
    for _ in range(steps):
        d = (Cm * column(F(x))).entries()
        x = [xi - di.mid() for xi, di in zip(x, d)]
        x = [xi.mid() for xi in x]
        dm = np.array([abs(float(di.mid())) for di in d])
        if not np.all(np.isfinite(dm)):
            return None
        if np.all(dm <= 4 * EPS * s):
            return np.array([float(xi) for xi in x])
    return None


# ------------------------------------------------------------------------------ symmetric inertia
def symmetric_inertia(K_balls) -> tuple[int, int] | None:
    """Proven (positives, negatives) eigenvalue counts, the same for every symmetric matrix in the ball matrix
    ``K_balls`` (list of rows; its upper triangle is read), or None when a zero eigenvalue cannot be excluded.

    Method: V = eigenvectors of the midpoint (LAPACK, floating point, need not be exact); M = V^T K V is
    enclosed (:func:`symmetric_inertias`); if every Gershgorin disc of M excludes 0, M (hence V) is nonsingular,
    the discs on each side of 0 hold exactly as many eigenvalues as there are discs there (continuity), and by
    Sylvester's law of inertia K has the same counts.
    """
    return symmetric_inertias([K_balls])[0]


_SLACK = 1.0 + 2.0 ** -30  # > (1 + gamma_k)^8 for k <= 1000: the roundings of a few nonnegative float sums
_UNDER = 2.0 ** -1000  # > the underflow errors (2^-1074 per operation) of the bounds below, for n <= 1000


def symmetric_inertias(Ks) -> list:
    """:func:`symmetric_inertia` of several n x n ball matrices at once (one LAPACK call, numpy bounds).

    The enclosure of M = V^T K V is done in floating point with a priori error bounds: K lies entrywise in
    C +- R (C the midpoints rounded to doubles, R the radii plus 2^-52 |C| for that rounding); M lies in
    Mf +- T with Mf = fl(V^T fl(C V)) and T = |V|^T (R + g |C|) |V|, g = 4 n 2^-53 >= 2 gamma_n + gamma_n^2
    bounding the two roundings of the float product (Higham, Thm. 3.1, any summation order).  T and the
    Gershgorin radii sum_(j != i) |Mf_ij| + sum_j T_ij are sums of nonnegative terms, computed in round-to-nearest
    and multiplied by 1 + 2^-30 (plus 2^-1000 for underflow), which covers their own roundings.  A finite matrix
    left undecided is tested again with M enclosed in ball arithmetic (:func:`_inertia_in_balls`).
    """
    Ks = list(Ks)
    if not Ks:
        return []
    N, n = len(Ks), len(Ks[0])
    iu, ju = np.triu_indices(n)
    ups = [v for K in Ks for i, row in enumerate(K) for v in row[i:]]
    try:
        r = list(map(arb.rad, ups))
    except TypeError:  # not all balls
        ups = list(map(arb, ups))
        r = list(map(arb.rad, ups))
    c = np.array(list(map(float, ups))).reshape(N, -1)  # float(arb): the midpoint rounded to nearest
    r = np.array(list(map(float, r))).reshape(N, -1)  # exact (a mag fits a double) but for underflow
    C, R = np.empty((N, n, n)), np.empty((N, n, n))
    C[:, iu, ju] = C[:, ju, iu] = c  # the upper triangle, mirrored
    R[:, iu, ju] = R[:, ju, iu] = r
    ok = np.isfinite(C).all(axis=(1, 2)) & np.isfinite(R).all(axis=(1, 2))
    C[~ok] = np.eye(n)
    R[~ok] = 0.0
    absC = np.abs(C)
    _, V = np.linalg.eigh(C)
    Mf = np.swapaxes(V, 1, 2) @ (C @ V)
    aV = np.abs(V)
    E = (R + absC * 2.0 ** -52 + _UNDER) + absC * (4 * n * 2.0 ** -53)
    T = (np.swapaxes(aV, 1, 2) @ (E @ aV)) * _SLACK + _UNDER
    d = np.diagonal(Mf, axis1=1, axis2=2).copy()
    off = np.abs(Mf)
    off[:, np.arange(n), np.arange(n)] = 0.0
    rad = (off.sum(axis=2) + T.sum(axis=2)) * _SLACK + _UNDER
    decided = (ok & ((d > rad) | (d < -rad)).all(axis=1)).tolist()
    pos = (d > rad).sum(axis=1).tolist()
    return [(p, n - p) if dk else _inertia_in_balls(K, V[k]) if ok[k] else None
            for k, (K, dk, p) in enumerate(zip(Ks, decided, pos))]


def _inertia_in_balls(K_balls, V) -> tuple[int, int] | None:
    """The Gershgorin test of :func:`symmetric_inertia` with M = V^T K V (upper triangle of K) enclosed in ball
    arithmetic: slower, sharper than the a priori bounds near a singular K (eigenvalues down to ~1e-16 |K|
    rather than ~n^2 1e-16 |K|)."""
    Vm = arb_mat(V.tolist())
    Ku = [[K_balls[min(i, j)][max(i, j)] for j in range(len(V))] for i in range(len(V))]  # the upper triangle
    e = (Vm.transpose() * arb_mat(Ku) * Vm).entries()
    n = len(V)
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
