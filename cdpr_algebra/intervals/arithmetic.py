"""Vectorized interval arithmetic on numpy arrays, outward rounded (the arithmetic of :mod:`cdpr_algebra.bp.solver`).

An :class:`Interval` holds two float64 arrays ``lo`` and ``hi`` of the same (broadcastable) shape: a batch of
intervals, e.g. a batch of boxes of shape (nboxes, nvars).  Operations act elementwise with numpy broadcasting.

**Rounding.**  numpy computes in IEEE 754 double precision with round-to-nearest; IEEE 754 requires +, -, *, /
and sqrt to be correctly rounded, so a computed bound differs from the exact result of the operation on the
(exact) input bounds by at most half an ulp.  Every operation here moves each computed lower bound at least one
ulp down and each computed upper bound at least one ulp up, so the returned interval contains the exact image of
the input intervals: all enclosures are rigorous.  With ``ROUNDING = "nextafter"`` the widening is exactly one
ulp, ``np.nextafter(x, -inf)`` / ``np.nextafter(x, +inf)``.  The default ``"fast"`` widening computes
up(x) = x + min(|x| 2^-52 + 2^-900, 1e300) (and down(x) = x - ...) with four array operations, 5-7 times faster
than ``np.nextafter`` in numpy, and never narrower: for a normal x in [2^e, 2^(e+1)) in magnitude,
fl(|x| 2^-52) >= 2^(e-52), the spacing of the floats at x, so the exact x + |x| 2^-52 + ... lies at or beyond the
neighbouring float and round-to-nearest (monotone) cannot bring it back; for subnormal or zero x the added
2^-900 exceeds the subnormal spacing 2^-1074 (and keeps widened zeros normal numbers: arithmetic on subnormals is
about 100 times slower); infinities stay infinite (the cap keeps -inf + inf from making a NaN).
``tests/test_interval_bp.py`` checks both against ``np.nextafter`` and exact rational arithmetic.  Exact
operations (negation, min/max, intersection, hull) are not widened.  Sums are always taken one addition at a
time (never ``np.sum``, whose pairwise summation has no per-step widening).  Nothing relies on library
functions without a correct-rounding guarantee (no exp/log/trigonometry).  Constants that are not floats
(e.g. rationals from the robot data) enter through :func:`enclose_fraction`, which rounds outward exactly.

**Matrix products** (:func:`mr_matmul`, used by the Newton-type operators and the statics filter) are the one
exception to the one-widening-per-operation rule: they are computed in midpoint-radius form with BLAS, and the
rounding errors of the floating-point dot products are bounded a priori (gamma_k of Higham, Thm. 3.1, valid for any
summation order) and added to the radius -- equally rigorous, and about ten times faster for batches of 12 x 12
matrices than looping over the terms.

Unbounded intervals are allowed (+-inf bounds).  Products 0 * inf (NaN in IEEE) are dropped by taking bounds
with ``np.fmin`` / ``np.fmax``, which gives the right set for an unbounded factor times an interval containing 0.
An empty interval has lo > hi.

:class:`Dual` carries a value and a sparse gradient (forward-mode differentiation) over either floats or
Intervals: the same residual code gives F, the float Jacobian for Newton and the interval Jacobian for the Krawczyk
test (:func:`krawczyk`); nested, it gives the constant Hessians of a quadratic system (:func:`quadratic_form`), with
which :class:`QuadraticSystem` evaluates F and J over batches of boxes by matrix products and forms the exact
second-order operator used by the branch and prune.

**Compiled twins.**  The s_* functions (numba) are the scalar forms of the interval operations with the same
"fast" widening, bit for bit (tested), for kernels that work box by box; :meth:`QuadraticSystem.taylor_contract`
applies the second-order operator that way (sparse Hessians, the rounding-error term of the preconditioned
Jacobian bounded in magnitude, exact zeros of y - c0 kept exact: products of two widened zeros would be subnormal
numbers, about a hundred times slower).
"""

from __future__ import annotations

from fractions import Fraction

import numba as nb
import numpy as np

__all__ = ["Interval", "Dual", "down", "up", "enclose_fraction", "sq", "isum", "inv_sqr", "krawczyk",
           "matvec_point", "newton", "quadratic_form", "QuadraticSystem", "mr_matmul"]

_INF = np.inf


_U = 2.0 ** -52
_TINY = 2.0 ** -900  # >= the subnormal spacing 2^-1074; large enough that widened zeros (and 2^-52 times them)
# stay normal numbers: subnormal arithmetic is ~100x slower on x86
_FLOOR = 2.0 ** -940  # floor of the terms scaled by ~2^-52 in mr_matmul, so that no subnormal is formed
_CAP = 1e300  # keeps the widening of +-inf finite (so up(-inf) = -inf, down(inf) = inf)
ROUNDING = "fast"  # "fast" (default) or "nextafter" (the reference widening, 5-7x slower in numpy)


def down(x):
    """A float <= np.nextafter(x, -inf): x moved at least one ulp toward -inf (lower bounds after a rounded
    operation).  Fast form x - min(|x| 2^-52 + 2^-1074, 1e300), see the module docstring."""
    if ROUNDING == "nextafter":
        return np.nextafter(x, -_INF)
    t = np.abs(x)
    if type(t) is not np.ndarray:
        return x - np.minimum(t * _U + _TINY, _CAP)
    t *= _U
    t += _TINY
    np.minimum(t, _CAP, out=t)
    return np.subtract(x, t, out=t)


def up(x):
    """A float >= np.nextafter(x, +inf): x moved at least one ulp toward +inf (upper bounds)."""
    if ROUNDING == "nextafter":
        return np.nextafter(x, _INF)
    t = np.abs(x)
    if type(t) is not np.ndarray:
        return x + np.minimum(t * _U + _TINY, _CAP)
    t *= _U
    t += _TINY
    np.minimum(t, _CAP, out=t)
    t += x
    return t


def enclose_fraction(fr) -> tuple[float, float]:
    """(lo, hi) floats with lo <= fr <= hi, lo == hi when the rational ``fr`` is a float (exact comparison)."""
    fr = Fraction(fr)
    f = float(fr)  # correctly rounded
    F = Fraction(f)
    if F == fr:
        return f, f
    if F < fr:
        return f, float(np.nextafter(f, _INF))
    return float(np.nextafter(f, -_INF)), f


def _foreign(o) -> bool:
    """o is a number type of another module that opted out of numpy's ufuncs (``__array_ufunc__ = None``, e.g.
    :class:`cdpr_algebra.intervals.complex_krawczyk.ComplexPair`): Interval and Dual operators defer to its reflected operators."""
    t = type(o)
    return t is not Interval and t is not Dual and getattr(t, "__array_ufunc__", 0) is None


class Interval:
    """A batch of closed intervals [lo, hi] (numpy arrays or scalars); rigorous outward-rounded operations."""

    __slots__ = ("lo", "hi")
    __array_ufunc__ = None  # ndarray (op) Interval defers to Interval's reflected operators

    def __init__(self, lo, hi=None):
        self.lo = lo
        self.hi = lo if hi is None else hi

    # -- construction ------------------------------------------------------------------------------------------
    @classmethod
    def point(cls, x) -> "Interval":
        x = np.asarray(x, dtype=float)
        return cls(x, x)

    @classmethod
    def from_fractions(cls, values) -> "Interval":
        """Outward enclosure of an array (nested lists) of rationals / ints / floats, elementwise."""
        arr = np.asarray(values, dtype=object)
        flat = [enclose_fraction(v) for v in arr.ravel()]
        lo = np.array([a for a, _ in flat], dtype=float).reshape(arr.shape)
        hi = np.array([b for _, b in flat], dtype=float).reshape(arr.shape)
        return cls(lo, hi)

    @classmethod
    def empty_like(cls, shape) -> "Interval":
        return cls(np.full(shape, _INF), np.full(shape, -_INF))

    # -- inspection --------------------------------------------------------------------------------------------
    @property
    def shape(self):
        return np.broadcast_shapes(np.shape(self.lo), np.shape(self.hi))

    @property
    def mid(self):
        """A float inside the interval (for finite bounds)."""
        m = 0.5 * self.lo + 0.5 * self.hi
        return np.minimum(np.maximum(m, self.lo), self.hi)

    @property
    def width(self):
        return self.hi - self.lo

    @property
    def mag(self):
        return np.maximum(np.abs(self.lo), np.abs(self.hi))

    def is_empty(self):
        return ~(self.lo <= self.hi)

    def contains(self, x):
        return (self.lo <= x) & (x <= self.hi)

    def __getitem__(self, idx) -> "Interval":
        return Interval(np.asarray(self.lo)[idx], np.asarray(self.hi)[idx])

    def __repr__(self):
        return f"Interval({self.lo!r}, {self.hi!r})"

    # -- set operations (exact) --------------------------------------------------------------------------------
    def intersect(self, o) -> "Interval":
        """Intersection (may be empty: lo > hi).  A NaN bound counts as no information (fmax / fmin)."""
        if isinstance(o, Interval):
            return Interval(np.fmax(self.lo, o.lo), np.fmin(self.hi, o.hi))
        return Interval(np.fmax(self.lo, o), np.fmin(self.hi, o))

    def hull(self, o) -> "Interval":
        return Interval(np.minimum(self.lo, o.lo), np.maximum(self.hi, o.hi))

    def subset_interior(self, o):
        """Elementwise: self is inside the interior of o."""
        return (self.lo > o.lo) & (self.hi < o.hi)

    # -- arithmetic --------------------------------------------------------------------------------------------
    def __neg__(self) -> "Interval":
        return Interval(-self.hi, -self.lo)

    def __pos__(self):
        return self

    def __add__(self, o) -> "Interval":
        if isinstance(o, Dual) or _foreign(o):
            return NotImplemented
        if isinstance(o, Interval):
            return Interval(down(self.lo + o.lo), up(self.hi + o.hi))
        return Interval(down(self.lo + o), up(self.hi + o))

    __radd__ = __add__

    def __sub__(self, o) -> "Interval":
        if isinstance(o, Dual) or _foreign(o):
            return NotImplemented
        if isinstance(o, Interval):
            return Interval(down(self.lo - o.hi), up(self.hi - o.lo))
        return Interval(down(self.lo - o), up(self.hi - o))

    def __rsub__(self, o) -> "Interval":
        return Interval(down(o - self.hi), up(o - self.lo))

    def __mul__(self, o) -> "Interval":
        if isinstance(o, Dual) or _foreign(o):
            return NotImplemented
        if isinstance(o, Interval):
            p1 = self.lo * o.lo
            p2 = self.lo * o.hi
            p3 = self.hi * o.lo
            p4 = self.hi * o.hi
            lo = np.fmin(np.fmin(p1, p2), np.fmin(p3, p4))
            hi = np.fmax(np.fmax(p1, p2), np.fmax(p3, p4))
            return Interval(down(lo), up(hi))
        p1 = self.lo * o
        p2 = self.hi * o
        return Interval(down(np.fmin(p1, p2)), up(np.fmax(p1, p2)))

    __rmul__ = __mul__

    def __truediv__(self, o) -> "Interval":
        """Division; where the divisor contains 0 the result is (-inf, inf)."""
        if isinstance(o, Dual) or _foreign(o):
            return NotImplemented
        if not isinstance(o, Interval):
            o = Interval(o, o)
        q1 = self.lo / o.lo
        q2 = self.lo / o.hi
        q3 = self.hi / o.lo
        q4 = self.hi / o.hi
        ok = (o.lo > 0) | (o.hi < 0)
        lo = np.where(ok, down(np.fmin(np.fmin(q1, q2), np.fmin(q3, q4))), -_INF)
        hi = np.where(ok, up(np.fmax(np.fmax(q1, q2), np.fmax(q3, q4))), _INF)
        return Interval(lo, hi)

    def __rtruediv__(self, o) -> "Interval":
        return Interval(o, o) / self

    def sqr(self) -> "Interval":
        """{x^2 : x in self} (sharper than self * self)."""
        l2 = self.lo * self.lo
        h2 = self.hi * self.hi
        mn = np.where(self.lo > 0, l2, np.where(self.hi < 0, h2, 0.0))
        return Interval(np.maximum(down(mn), 0.0), up(np.fmax(l2, h2)))

    def sqrt(self) -> "Interval":
        """{sqrt(x) : x in self, x >= 0} (empty where self < 0)."""
        lo = np.maximum(down(np.sqrt(np.maximum(self.lo, 0.0))), 0.0)
        hi = np.where(self.hi >= 0, up(np.sqrt(np.maximum(self.hi, 0.0))), -_INF)
        return Interval(lo, hi)

    def sum(self, axis=-1) -> "Interval":
        """Sum along ``axis``, one widened addition at a time."""
        lo = np.moveaxis(np.asarray(self.lo), axis, 0)
        hi = np.moveaxis(np.asarray(self.hi), axis, 0)
        out = Interval(lo[0], hi[0])
        for k in range(1, lo.shape[0]):
            out = out + Interval(lo[k], hi[k])
        return out


def stack(items, axis=-1) -> Interval:
    items = [i if isinstance(i, Interval) else Interval.point(i) for i in items]
    shape = np.broadcast_shapes(*(i.shape for i in items))
    return Interval(np.stack([np.broadcast_to(i.lo, shape) for i in items], axis=axis),
                    np.stack([np.broadcast_to(i.hi, shape) for i in items], axis=axis))


def isum(items) -> Interval:
    """Sum of a list of Intervals (or floats), one widened addition at a time."""
    out = items[0]
    for it in items[1:]:
        out = out + it
    return out


def sq(x):
    """x^2 for floats, arrays, Intervals and Duals (the tight square for intervals)."""
    if isinstance(x, (Interval, Dual)):
        return x.sqr()
    return x * x


def inv_sqr(y: Interval, x: Interval) -> Interval:
    """Projection of x^2 in y onto x (HC4 backward step of a square): hull of x cap (-sqrt(y) u sqrt(y))."""
    r = y.sqrt()  # [s1, s2], empty (hi = -inf) where y < 0
    s1, s2 = r.lo, r.hi
    plo = np.fmax(x.lo, s1)
    phi = np.fmin(x.hi, s2)
    nlo = np.fmax(x.lo, -s2)
    nhi = np.fmin(x.hi, -s1)
    pok = plo <= phi
    nok = nlo <= nhi
    lo = np.where(nok, nlo, np.where(pok, plo, _INF))
    hi = np.where(pok, phi, np.where(nok, nhi, -_INF))
    return Interval(lo, hi)


# ---------------------------------------------------------------------------------------------------------------
class Dual:
    """Value and sparse gradient (forward-mode derivative): ``v`` a value (float array or Interval), ``g`` a dict
    {variable index: partial derivative} holding only the structurally non-zero partials, so the cost follows the
    sparsity of the equations.  Over Intervals the partials enclose the derivatives over the whole box."""

    __slots__ = ("v", "g")
    __array_ufunc__ = None

    def __init__(self, v, g):
        self.v = v
        self.g = g

    def __add__(self, o):
        if _foreign(o):
            return NotImplemented
        if isinstance(o, Dual):
            g = dict(self.g)
            for k, x in o.g.items():
                g[k] = g[k] + x if k in g else x
            return Dual(self.v + o.v, g)
        return Dual(self.v + o, self.g)

    __radd__ = __add__

    def __sub__(self, o):
        if _foreign(o):
            return NotImplemented
        if isinstance(o, Dual):
            g = dict(self.g)
            for k, x in o.g.items():
                g[k] = g[k] - x if k in g else -x
            return Dual(self.v - o.v, g)
        return Dual(self.v - o, self.g)

    def __rsub__(self, o):
        return Dual(o - self.v, {k: -x for k, x in self.g.items()})

    def __neg__(self):
        return Dual(-self.v, {k: -x for k, x in self.g.items()})

    def __mul__(self, o):
        if _foreign(o):
            return NotImplemented
        if isinstance(o, Dual):
            g = {k: x * o.v for k, x in self.g.items()}
            for k, x in o.g.items():
                t = x * self.v
                g[k] = g[k] + t if k in g else t
            return Dual(self.v * o.v, g)
        return Dual(self.v * o, {k: x * o for k, x in self.g.items()})

    __rmul__ = __mul__

    def sqr(self):
        tv = self.v * 2.0
        return Dual(sq(self.v), {k: x * tv for k, x in self.g.items()})


def dual_variables(X, interval: bool):
    """The h columns of X (N, h) as Duals with unit gradients (values float arrays, or Intervals if ``interval``)."""
    h = X.lo.shape[1] if interval else X.shape[1]
    if interval:
        return [Dual(Interval(X.lo[:, k], X.hi[:, k]), {k: 1.0}) for k in range(h)]
    return [Dual(X[:, k], {k: 1.0}) for k in range(h)]


def _as_interval(v, N):
    if isinstance(v, Interval):
        return Interval(np.broadcast_to(v.lo, (N,)), np.broadcast_to(v.hi, (N,)))
    v = np.broadcast_to(np.asarray(v, dtype=float), (N,))
    return Interval(v, v)


def _jacobian(res, N, h, interval: bool):
    if interval:
        lo = np.zeros((N, len(res), h))
        hi = np.zeros((N, len(res), h))
        for r, d in enumerate(res):
            for k, x in d.g.items():
                x = _as_interval(x, N)
                lo[:, r, k] = x.lo
                hi[:, r, k] = x.hi
        return Interval(lo, hi)
    J = np.zeros((N, len(res), h))
    for r, d in enumerate(res):
        for k, x in d.g.items():
            J[:, r, k] = x
    return J


def _midrad(M: Interval):
    """(mid, rad) with [mid - rad, mid + rad] containing M (rad rounded upward)."""
    m = M.mid
    return m, np.maximum(up(M.hi - m), up(m - M.lo))


@nb.njit(cache=True, error_model="numpy")
def _gamma(k: int) -> float:
    """A bound g >= gamma_k / (1 - gamma_k), gamma_k = k u / (1 - k u), u = 2^-53 (Higham, Thm. 3.1)."""
    return (k + 2) * 2.0 ** -53 * 1.01


def mr_matmul(Am, Ar, Bm, Br) -> Interval:
    """Rigorous enclosure of {A B : |A - Am| <= Ar, |B - Bm| <= Br} for batches of matrices (matmul shapes).

    Midpoint-radius product (Rump 1999): A B lies in Am Bm +- (|Am| Br + Ar (|Bm| + Br)).  The products are computed
    in floating point (BLAS); a dot product of length k computed in any order (with or without FMA) differs from the
    exact one by at most gamma_k times the sum of the absolute terms (Higham, Thm. 3.1), plus k 2^-1074 for
    underflow; those errors and the roundings of the bound itself are added to the radius (below)."""
    k = Am.shape[-1]
    g = _gamma(k)
    S1 = Am @ Bm
    absA = np.abs(Am)
    absB = np.abs(Bm)
    S3 = absA @ absB
    if Br is None and Ar is None:
        S2 = np.zeros_like(S1)
    elif Ar is None:
        S2 = absA @ Br
        S3 = S3 + S2
    elif Br is None:
        S2 = Ar @ absB
        S3 = S3 + S2
    else:
        BB = up(absB + Br)
        S2 = up(absA @ Br + Ar @ BB)
        S3 = S3 + S2
    # All terms are >= 0.  W = (S2 + g S3)(1 + g + 2^-47) + 2^-50 |S1| + k 2^-1022 bounds the radius, the error of
    # the computed S1, the (at most six) roundings of computing W itself (16 u >= 6 u), and the rounding of the
    # final S1 -+ W (|fl(S1 - W) - (S1 - W)| <= u (|S1| + W), covered by the 2^-50 |S1| = 8 u |S1| term and the
    # factor); so [S1 - W, S1 + W] computed in round-to-nearest encloses the exact product set.
    W = (S2 + np.maximum(S3, _FLOOR) * g) * (1.0 + g + 2.0 ** -47) + np.abs(S1) * 2.0 ** -50 + k * 2.0 ** -1022
    return Interval(S1 - W, S1 + W)


def matvec_point(C, V: Interval) -> Interval:
    """C (N, h, k) float times interval vectors V (N, k), rigorous (:func:`mr_matmul`)."""
    Vm, Vr = _midrad(V)
    out = mr_matmul(C, None, Vm[..., None], Vr[..., None])
    return Interval(out.lo[..., 0], out.hi[..., 0])


def residual_interval(residual, X: Interval):
    """F over the boxes X (N, h) with its interval Jacobian (N, h, h), via :class:`Dual` over Intervals."""
    N, h = X.lo.shape
    res = residual(dual_variables(X, interval=True))
    F = stack([_as_interval(r.v, N) for r in res], axis=1)
    return F, _jacobian(res, N, h, True)


def krawczyk(residual, X: Interval, y=None, JX: Interval | None = None, want_m: bool = False):
    """Krawczyk operator K(X, y) = y - C F(y) + (I - C J(X)) (X - y), C = mid(J(X))^-1, for a batch of boxes.

    ``residual(vars)`` maps a list of h numbers (floats, Intervals or Duals) to a list of h numbers.  Returns
    (K (Interval (N, h)), ok (N,) bool: C could be formed[, |I - C J(X)| (N, h, h) if ``want_m``]).  Every zero of F in X lies in K(X, y) (for any C); if
    K(X, y) lies in the interior of X, F has exactly one zero in X (Krawczyk / Moore).  ``y`` defaults to mid(X).
    """
    N, h = X.lo.shape
    if y is None:
        y = X.mid
    if JX is None:
        _, JX = residual_interval(residual, X)
    Jm = JX.mid
    C, ok = _inverse(Jm)
    with np.errstate(all="ignore"):
        cond = np.abs(C).sum(axis=2).max(axis=1) * np.abs(Jm).sum(axis=2).max(axis=1)
    ok &= np.isfinite(cond) & (cond < 1e14)
    C[~ok] = 0.0
    Fy = stack([_as_interval(r, N) for r in residual([Interval(y[:, k], y[:, k]) for k in range(h)])], axis=1)
    CF = matvec_point(C, Fy)
    Jm_, Jr_ = _midrad(JX)
    CJ = mr_matmul(C, None, Jm_, Jr_)
    eye = np.eye(h)
    M = Interval(down(eye - CJ.hi), up(eye - CJ.lo))  # I - C J(X)
    Mm, Mr = _midrad(M)
    D = X - y
    Dm, Dr = _midrad(D)
    MD = mr_matmul(Mm, Mr, Dm[..., None], Dr[..., None])
    K = (y - CF) + Interval(MD.lo[..., 0], MD.hi[..., 0])
    K = Interval(np.where(ok[:, None], K.lo, -_INF), np.where(ok[:, None], K.hi, _INF))
    if want_m:
        return K, ok, np.abs(Mm) + Mr
    return K, ok


class QuadraticForm:
    """The constant second-order part of a quadratic system: (1/2) d^T H_i d = sum_p V[i, p] d_j(p) d_k(p) over the
    pairs p = (j, k), j <= k, with a non-zero Hessian entry; V an Interval (h, npairs)."""

    def __init__(self, pairs, V: Interval):
        self.pairs = pairs
        self.j = np.array([a for a, _ in pairs], dtype=int)
        self.k = np.array([b for _, b in pairs], dtype=int)
        self.V = V
        self.Vm, self.Vr = _midrad(V)

    def pair_products(self, D: Interval) -> Interval:
        """The products d_j d_k (d_j^2 for j = k) of the pairs over the boxes D (N, h): Interval (N, npairs)."""
        Dj = Interval(D.lo[:, self.j], D.hi[:, self.j])
        Dk = Interval(D.lo[:, self.k], D.hi[:, self.k])
        P = Dj * Dk
        same = self.j == self.k
        if same.any():
            sqv = Dj.sqr()
            P = Interval(np.where(same, sqv.lo, P.lo), np.where(same, sqv.hi, P.hi))
        return P

    def enclose(self, D: Interval) -> Interval:
        """(1/2) Q(d) over the boxes d in D (N, h): an Interval (N, h)."""
        if not self.pairs:
            return Interval(np.zeros(D.lo.shape), np.zeros(D.lo.shape))
        Pm, Pr = _midrad(self.pair_products(D))
        return mr_matmul(Pm, Pr, np.ascontiguousarray(self.Vm.T), np.ascontiguousarray(self.Vr.T))


def quadratic_form(residual, h: int) -> QuadraticForm:
    """The Hessians of a system of quadratic equations (constant), by nested forward differentiation over
    Intervals (rigorous enclosures of the constant second derivatives)."""
    zero = Interval(np.zeros(1), np.zeros(1))
    xs = [Dual(Dual(zero, {k: 1.0}), {k: 1.0}) for k in range(h)]
    res = residual(xs)
    H = {}
    for i, r in enumerate(res):
        if not isinstance(r, Dual):
            continue
        for j, gj in r.g.items():
            if not isinstance(gj, Dual):
                continue
            for k, hjk in gj.g.items():
                a, b = (j, k) if j <= k else (k, j)
                hv = hjk if isinstance(hjk, Interval) else Interval(np.float64(hjk), np.float64(hjk))
                hv = Interval(np.asarray(hv.lo).reshape(-1)[0], np.asarray(hv.hi).reshape(-1)[0])
                key = (i, a, b)
                if key in H:  # H_ijk and H_ikj enclose the same number
                    H[key] = H[key].intersect(hv)
                else:
                    H[key] = hv
    pairs = sorted({(a, b) for (_, a, b) in H})
    index = {p: n for n, p in enumerate(pairs)}
    lo = np.zeros((len(res), len(pairs)))
    hi = np.zeros((len(res), len(pairs)))
    for (i, a, b), hv in H.items():
        n = index[(a, b)]
        if a == b:  # (1/2) H_ijj d_j^2
            lo[i, n], hi[i, n] = down(0.5 * hv.lo), up(0.5 * hv.hi)
        else:  # (1/2)(H_ijk + H_ikj) d_j d_k = H_ijk d_j d_k
            lo[i, n], hi[i, n] = hv.lo, hv.hi
    return QuadraticForm(pairs, Interval(lo, hi))


def _inverse(Jm):
    """Batch inverse of float matrices; (C, ok) with C = 0 where not invertible or not finite."""
    ok = np.all(np.isfinite(Jm), axis=(1, 2))
    C = np.zeros_like(Jm)
    if ok.any():
        with np.errstate(all="ignore"):
            try:
                C[ok] = np.linalg.inv(Jm[ok])
            except np.linalg.LinAlgError:
                for k in np.flatnonzero(ok):
                    try:
                        C[k] = np.linalg.inv(Jm[k])
                    except np.linalg.LinAlgError:
                        ok[k] = False
        ok &= np.all(np.isfinite(C), axis=(1, 2))
        C[~ok] = 0.0
    return C, ok


class QuadraticSystem:
    """A square system of quadratic equations F (``residual``) expanded exactly about a point c0:
    F(x) = F(c0) + J(c0) d + (1/2) Q(d), J(x) = J(c0) + H d, d = x - c0, with F(c0), J(c0) and the constant
    Hessians H enclosed once (forward differentiation over Intervals); afterwards F and J over any batch of boxes
    are a few rigorous matrix products (:func:`mr_matmul`) instead of a new differentiation per box."""

    def __init__(self, residual, h: int, c0):
        self.residual = residual
        self.h = h
        self.c0 = np.asarray(c0, dtype=float)
        self.quad = quadratic_form(residual, h)
        F0, J0 = residual_interval(residual, Interval(self.c0[None], self.c0[None]))
        self.F0 = F0[0]
        self.J0 = J0[0]
        self.J0m, self.J0r = _midrad(self.J0)
        # H as an (h*h, h) matrix: J(x)_ij = J0_ij + sum_k H_ijk d_k
        lo = np.zeros((h, h, h))
        hi = np.zeros((h, h, h))
        V = self.quad.V
        for p, (j, k) in enumerate(self.quad.pairs):
            vl, vh = V.lo[:, p], V.hi[:, p]
            if j == k:  # (1/2) H_ijj d_j^2: H_ijj = 2 V
                lo[:, j, j], hi[:, j, j] = down(2.0 * vl), up(2.0 * vh)
            else:  # H_ijk d_j d_k with H_ijk = H_ikj = V
                lo[:, j, k], hi[:, j, k] = vl, vh
                lo[:, k, j], hi[:, k, j] = vl, vh
        self.Hm, self.Hr = _midrad(Interval(lo.reshape(h * h, h), hi.reshape(h * h, h)))
        self.HmT = np.ascontiguousarray(self.Hm.T)
        self.HrT = np.ascontiguousarray(self.Hr.T)
        # stacked coefficient matrices of the one-product forms used by :meth:`taylor`
        self._JHm = np.vstack([self.J0m.reshape(1, h * h), self.HmT])
        self._JHr = np.vstack([self.J0r.reshape(1, h * h), self.HrT])
        F0m, F0r = _midrad(self.F0)
        VmT, VrT = self.quad.Vm.T, self.quad.Vr.T
        self._SFm = np.ascontiguousarray(np.vstack([F0m[None], self.J0m.T, VmT, VmT]))
        self._SFr = np.ascontiguousarray(np.vstack([F0r[None], self.J0r.T, VrT, VrT]))
        # the non-zero entries of [J(c0); H^T] column by column (H is sparse), for the compiled operator
        self._jh = _sparse_columns(self._JHm, self._JHr)
        self._sf = _sparse_columns(self._SFm, self._SFr)
        self._pj = self.quad.j.astype(np.int64)
        self._pk = self.quad.k.astype(np.int64)

    def jacobian(self, X: Interval) -> Interval:
        """J over the boxes X (N, h): J(c0) + H (X - c0), an Interval (N, h, h)."""
        N = X.lo.shape[0]
        D = X - self.c0
        Dm, Dr = _midrad(D)
        HD = mr_matmul(Dm, Dr, self.HmT, self.HrT)  # (N, h*h)
        h = self.h
        return Interval(down(HD.lo.reshape(N, h, h) + self.J0.lo), up(HD.hi.reshape(N, h, h) + self.J0.hi))

    def value(self, X: Interval) -> Interval:
        """F over the boxes X by the expansion (exact form; use ``residual`` for accurate values at points)."""
        D = X - self.c0
        Dm, Dr = _midrad(D)
        JD = mr_matmul(Dm, Dr, np.ascontiguousarray(self.J0m.T), np.ascontiguousarray(self.J0r.T))
        return self.F0 + JD + self.quad.enclose(D)

    def point_value(self, y) -> Interval:
        """F at the points y (N, h), evaluated directly from the residual (no cancellation of the expansion)."""
        N = y.shape[0]
        return stack([_as_interval(r, N) for r in self.residual([Interval(y[:, k], y[:, k])
                                                                 for k in range(self.h)])], axis=1)

    def taylor(self, X: Interval, y=None, scale=None):
        """The second-order operator T(X) = y - C F(y) - (C J(y) - I)(X - y) - C (1/2) Q(X - y), exact form of
        the quadratic system, C = mid(J(y))^-1: every zero of F in X lies in T(X); about twice as tight as the
        Krawczyk operator (whose remainder (I - C J(X))(X - y) is Q's interval form without the 1/2 and with
        d_j^2 over [-r^2, r^2]).  Returns (T (N, h), ok (N,))."""
        N, h = X.lo.shape
        if y is None:
            y = X.mid
        D0 = Interval(y, y) - self.c0  # y - c0, enclosed
        D0m, D0r = _midrad(D0)
        ones = np.ones((N, 1))
        zeros = np.zeros((N, 1))
        # J(y) = J(c0) + H (y - c0): one product [1 | y - c0] [J(c0); H]
        Jy = mr_matmul(np.hstack([ones, D0m]), np.hstack([zeros, D0r]), self._JHm, self._JHr)
        Jmm, Jrr = _midrad(Interval(Jy.lo.reshape(N, h, h), Jy.hi.reshape(N, h, h)))
        C, ok = _inverse(Jmm)
        D = X - y
        Dm, Dr = _midrad(D)
        # F(y) + (1/2) Q(X - y) = F(c0) + J(c0)(y - c0) + (1/2) Q(y - c0) + (1/2) Q(X - y): one product
        P0m, P0r = _midrad(self.quad.pair_products(D0))
        P1m, P1r = _midrad(self.quad.pair_products(D))
        Sm_in = np.hstack([ones, D0m, P0m, P1m])
        Sr_in = np.hstack([zeros, D0r, P0r, P1r])
        S = mr_matmul(Sm_in, Sr_in, self._SFm, self._SFr)  # (N, h)
        Sm, Sr = _midrad(S)
        CS = mr_matmul(C, None, Sm[..., None], Sr[..., None])
        A = mr_matmul(C, None, Jmm, Jrr)
        eye = np.eye(h)
        AmI = Interval(down(A.lo - eye), up(A.hi - eye))
        Am, Ar = _midrad(AmI)
        AD = mr_matmul(Am, Ar, Dm[..., None], Dr[..., None])
        T = y - Interval(CS.lo[..., 0], CS.hi[..., 0]) - Interval(AD.lo[..., 0], AD.hi[..., 0])
        T = Interval(np.where(ok[:, None], T.lo, -_INF), np.where(ok[:, None], T.hi, _INF))
        if scale is None:
            return T, ok
        # bisection score of each variable: its share of the second-order part of the width of T,
        # sum_i |C| |V| (pairs containing the variable) |d_j d_k| / scale_i
        contrib = np.einsum("nih,hp->np", np.abs(C) / scale[None, :, None], np.abs(self.quad.Vm)) * P1r  # (N, npairs)
        score = np.zeros((N, h))
        np.add.at(score, (slice(None), self.quad.j), contrib)
        np.add.at(score, (slice(None), self.quad.k), contrib)
        return T, ok, score

    def taylor_contract(self, lo, hi, scale, iterations: int, gain: float):
        """The operator of :meth:`taylor` (y = mid X) on each box of (lo, hi) (N, h), compiled, applied up to
        ``iterations`` times while the sum of the widths / ``scale`` shrinks by more than ``gain``: returns
        (lo, hi, excluded, inner) -- X cap T(X), whether T(X) is disjoint from X (no zero of F in X), whether some
        T(X) lay in the interior of X (a zero of F in X; unicity is the Krawczyk test's business)."""
        lo = np.array(lo, dtype=float, order="C")
        hi = np.array(hi, dtype=float, order="C")
        excluded = np.zeros(len(lo), dtype=np.bool_)
        inner = np.zeros(len(lo), dtype=np.bool_)
        if len(lo):
            _taylor_kernel(lo, hi, self.c0, *self._jh, *self._sf, self._pj, self._pk, np.asarray(scale, dtype=float),
                           int(iterations), float(gain), excluded, inner)
        return lo, hi, excluded, inner

    def krawczyk(self, X: Interval, y=None, want_m: bool = False):
        """:func:`krawczyk` with J(X) from the expansion and F(y) from the residual."""
        return krawczyk(self.residual, X, y, JX=self.jacobian(X), want_m=want_m)


def newton(residual, x0, iterations: int = 8, tol: float = 1e-13):
    """Float Newton iterations from x0 (N, h), vectorized; returns (x, converged (N,) bool, last step norm)."""
    x = np.array(x0, dtype=float)
    N, h = x.shape
    step = np.full(N, np.inf)
    alive = np.ones(N, bool)
    for _ in range(iterations):
        res = residual(dual_variables(x, interval=False))
        F = np.stack([np.broadcast_to(r.v, (N,)) for r in res], axis=1)
        J = _jacobian(res, N, h, False)
        with np.errstate(all="ignore"):
            good = alive & np.all(np.isfinite(J), axis=(1, 2)) & np.all(np.isfinite(F), axis=1)
            dx = np.zeros_like(x)
            if good.any():
                try:
                    dx[good] = np.linalg.solve(J[good], F[good][..., None])[..., 0]
                except np.linalg.LinAlgError:
                    for k in np.flatnonzero(good):
                        try:
                            dx[k] = np.linalg.solve(J[k], F[k])
                        except np.linalg.LinAlgError:
                            good[k] = False
            alive = good & np.all(np.isfinite(dx), axis=1)
            x = np.where(alive[:, None], x - dx, x)
            step = np.where(alive, np.max(np.abs(dx), axis=1) / (1 + np.max(np.abs(x), axis=1)), np.inf)
        if not np.any(alive & (step > tol)):
            break
    return x, alive & (step <= 1e-8), step


# ---------------------------------------------------------------------------------------------------------------
# Compiled scalar interval operations (numba), for the per-box kernels of :mod:`cdpr_algebra.bp.solver` and
# :meth:`QuadraticSystem.taylor_contract`.  Each takes and returns (lo, hi) float pairs and performs exactly the
# operations of the vectorized :class:`Interval` method of the same name with the default "fast" widening
# (x -+ min(|x| 2^-52 + 2^-900, 1e300) after every rounded operation), so the two give identical bounds
# (tests/test_interval_bp.py checks it bit for bit).  numba compiles IEEE 754 double arithmetic without fastmath:
# no reassociation and no contraction of a * b + c into a fused multiply-add.
@nb.njit(cache=True, error_model="numpy")
def s_down(x):
    t = abs(x) * _U + _TINY
    if t > _CAP:
        t = _CAP
    return x - t


@nb.njit(cache=True, error_model="numpy")
def s_up(x):
    t = abs(x) * _U + _TINY
    if t > _CAP:
        t = _CAP
    return x + t


@nb.njit(cache=True, error_model="numpy")
def s_fmin(a, b):
    """np.fmin: the smaller, a NaN counting as missing."""
    if a != a:
        return b
    if b != b:
        return a
    return a if a < b else b


@nb.njit(cache=True, error_model="numpy")
def s_fmax(a, b):
    if a != a:
        return b
    if b != b:
        return a
    return a if a > b else b


@nb.njit(cache=True, error_model="numpy")
def s_add(al, ah, bl, bh):
    return s_down(al + bl), s_up(ah + bh)


@nb.njit(cache=True, error_model="numpy")
def s_sub(al, ah, bl, bh):
    return s_down(al - bh), s_up(ah - bl)


@nb.njit(cache=True, error_model="numpy")
def s_mul(al, ah, bl, bh):
    p1 = al * bl
    p2 = al * bh
    p3 = ah * bl
    p4 = ah * bh
    return s_down(s_fmin(s_fmin(p1, p2), s_fmin(p3, p4))), s_up(s_fmax(s_fmax(p1, p2), s_fmax(p3, p4)))


@nb.njit(cache=True, error_model="numpy")
def s_div(al, ah, bl, bh):
    """Division; (-inf, inf) where the divisor contains 0.  Of the four quotients of the vectorized form only the two
    that the signs make extreme are computed (rounding is monotone, so they are also the extreme rounded ones)."""
    if bl > 0:
        lo = al / bh if al >= 0 else al / bl
        hi = ah / bl if ah >= 0 else ah / bh
    elif bh < 0:
        lo = ah / bh if ah >= 0 else ah / bl
        hi = al / bl if al >= 0 else al / bh
    else:
        return -_INF, _INF
    return s_down(lo), s_up(hi)


@nb.njit(cache=True, error_model="numpy")
def s_sqr(l, h):
    l2 = l * l
    h2 = h * h
    if l > 0:
        mn = l2
    elif h < 0:
        mn = h2
    else:
        mn = 0.0
    lo = s_down(mn)
    return (lo if lo > 0.0 else 0.0), s_up(s_fmax(l2, h2))


@nb.njit(cache=True, error_model="numpy")
def s_inv_sqr(yl, yh, xl, xh):
    """:func:`inv_sqr`: hull of x cap (-sqrt(y) u sqrt(y)), empty (lo > hi) if none."""
    s1 = s_down(np.sqrt(yl if yl > 0.0 else 0.0))
    if not s1 > 0.0:
        s1 = 0.0
    s2 = s_up(np.sqrt(yh if yh > 0.0 else 0.0)) if yh >= 0 else -_INF
    plo = s_fmax(xl, s1)
    phi = s_fmin(xh, s2)
    nlo = s_fmax(xl, -s2)
    nhi = s_fmin(xh, -s1)
    pok = plo <= phi
    nok = nlo <= nhi
    lo = nlo if nok else (plo if pok else _INF)
    hi = phi if pok else (nhi if nok else -_INF)
    return lo, hi


@nb.njit(cache=True, error_model="numpy")
def s_sub_exact(a, b):
    """[lo, hi] containing a - b for floats a, b, a point when the difference is a float: the error of the rounded
    difference is computed exactly (Knuth's TwoSum) and the bound widened only on its side.  Keeps the exact zeros
    of y - c0 zeros (a widened zero times a widened zero would underflow: slow subnormal arithmetic)."""
    c = -b
    s = a + c
    a1 = s - c
    c1 = s - a1
    e = (a - a1) + (c - c1)
    if e > 0:
        return s, s_up(s)
    if e < 0:
        return s_down(s), s
    if e == 0:
        return s, s
    return s_down(s), s_up(s)  # not finite


@nb.njit(cache=True, error_model="numpy")
def s_mid(lo, hi):
    """:attr:`Interval.mid`."""
    m = 0.5 * lo + 0.5 * hi
    if m < lo:
        m = lo
    if m > hi:
        m = hi
    return m


@nb.njit(cache=True, error_model="numpy")
def s_midrad(lo, hi):
    """:func:`_midrad`: (m, r) with [m - r, m + r] containing [lo, hi]."""
    m = s_mid(lo, hi)
    r1 = s_up(hi - m)
    r2 = s_up(m - lo)
    return m, (r1 if r1 > r2 else r2)


@nb.njit(cache=True, error_model="numpy")
def s_mr_radius(S1, S2, S3, g, k):
    """The radius W of :func:`mr_matmul` for one dot product of length k: S1 = sum am bm, S2 = sum |am| br +
    ar (|bm| + br) (radius part), S3 = sum |am| |bm| + S2, all computed in floating point in any order, g = _gamma(k);
    the exact product set lies in [S1 - W, S1 + W] (exact), and so does the computed pair (S1 - W, S1 + W)."""
    S3f = S3 if S3 > _FLOOR else _FLOOR
    return (S2 + S3f * g) * (1.0 + g + 2.0 ** -47) + abs(S1) * 2.0 ** -50 + k * 2.0 ** -1022


@nb.njit(cache=True, error_model="numpy")
def s_mr_bound(S1, S2, S3, g, k):
    """The enclosure (S1 - W, S1 + W) of :func:`s_mr_radius`."""
    W = s_mr_radius(S1, S2, S3, g, k)
    return S1 - W, S1 + W


_TINY_ENTRY = 2.0 ** -800


def _sparse_columns(Mm, Mr):
    """(ptr, row, m, r, tiny): the significant entries of the (k, n) midpoint-radius matrix (Mm, Mr), column by
    column (column j holds entries ptr[j]:ptr[j + 1]), and per column the largest radius ``tiny`` of the others (zero
    midpoint, radius <= 2^-800: widened zeros, e.g. structural zeros of J(c0) computed as [-2^-900, 2^-900]).  A
    product only adds tiny[j] * sum_k (|am_k| + ar_k) for those (:func:`_taylor_kernel`): multiplying two widened zeros
    would form subnormal numbers, about a hundred times slower."""
    small = (Mm == 0) & (Mr <= _TINY_ENTRY)
    cols, rows = np.nonzero((~small & ((Mm != 0) | (Mr != 0))).T)
    ptr = np.searchsorted(cols, np.arange(Mm.shape[1] + 1)).astype(np.int64)
    tiny = np.where(small, Mr, 0.0).max(axis=0)
    return (ptr, rows.astype(np.int64), np.ascontiguousarray(Mm[rows, cols]), np.ascontiguousarray(Mr[rows, cols]),
            np.ascontiguousarray(tiny))


@nb.njit(cache=True, error_model="numpy")
def _float_inverse(A, C):
    """C = A^-1 by Gauss-Jordan elimination with partial pivoting, overwriting A (floats: a preconditioner, no
    rigour needed); False if a pivot vanishes or a result is not finite."""
    h = A.shape[0]
    for i in range(h):
        for j in range(h):
            C[i, j] = 1.0 if i == j else 0.0
    for k in range(h):
        p = k
        best = abs(A[k, k])
        for i in range(k + 1, h):
            if abs(A[i, k]) > best:
                best = abs(A[i, k])
                p = i
        if not best > 0.0:
            return False
        if p != k:
            for j in range(h):
                A[k, j], A[p, j] = A[p, j], A[k, j]
                C[k, j], C[p, j] = C[p, j], C[k, j]
        piv = 1.0 / A[k, k]
        for j in range(h):
            A[k, j] *= piv
            C[k, j] *= piv
        for i in range(h):
            if i != k:
                f = A[i, k]
                if f != 0.0:
                    for j in range(k + 1, h):  # columns < k of A are already eliminated, column k becomes 0
                        A[i, j] -= f * A[k, j]
                    A[i, k] = 0.0
                    for j in range(h):
                        C[i, j] -= f * C[k, j]
    for i in range(h):
        for j in range(h):
            if not np.isfinite(C[i, j]):
                return False
    return True


@nb.njit(cache=True, error_model="numpy")
def _sparse_midrad_sums(am_, ar_, ptr, row, bm_, br_, e, S2):
    """The sums of a midpoint-radius dot product of the vector (am_, ar_) with the sparse column e (rows
    row[ptr[e]:ptr[e+1]], midpoints bm_, radii br_): S1 = sum am bm (float), S3 = sum |am| |bm|, and the radius part
    S2 (starting from the given bound) += |am| br + ar (|bm| + br) rounded up, for :func:`s_mr_radius` /
    :func:`s_mr_bound`."""
    S1 = 0.0
    S3 = 0.0
    for q in range(ptr[e], ptr[e + 1]):
        k = row[q]
        am, ar = am_[k], ar_[k]
        bm, br = bm_[q], br_[q]
        S1 += am * bm
        S3 += abs(am) * abs(bm)
        S2 += abs(am) * br + ar * s_up(abs(bm) + br)
    return S1, S2, S3


@nb.njit(cache=True, error_model="numpy")
def _taylor_kernel(lo, hi, c0, jh_ptr, jh_row, jh_m, jh_r, jh_t, sf_ptr, sf_row, sf_m, sf_r, sf_t, pj, pk, scale,
                   iterations, gain, excluded, inner):
    """Compiled second-order operator of :meth:`QuadraticSystem.taylor` applied to each box (row of lo, hi (N, h)),
    iterated as in the branch and prune: T(X) disjoint from X excludes the box (``excluded``), else X is replaced by
    X cap T(X), again while the sum of the scaled widths shrinks by more than ``gain``; ``inner``: some T(X) lay in
    the interior of X (by Brouwer's theorem X then holds a zero of F: a candidate for the unicity test).

    With y = mid X, d = x - y for a zero x of F in X: F(y) + J(y) d + (1/2) Q(d) = 0 exactly, so for C = mid(J(y))^-1
    (float), d = -C (F(y) + (1/2) Q(d)) - (C J(y) - I) d and T(X) = y - C S - (C J(y) - I)(X - y) with S enclosing
    F(y) + (1/2) Q(X - y) (the one-product form of :meth:`QuadraticSystem.taylor`, sparse columns sf_*).  J(y) =
    J(c0) + H (y - c0) is enclosed as midpoint Jm and radius Jr from the sparse columns jh_* of [J(c0); H^T]
    (:func:`_sparse_columns`; the tiny entries add their bound to the radius part S2); the last
    term is bounded in magnitude, |C J(y) - I| <= |fl(C Jm) - I| (1 + 2u) + gamma |C| |Jm| + |C| Jr with |C| |Jm| <=
    (row sums of |C|) (column maxima of |Jm|) and the same for Jr (it is a rounding-error term), every operation on
    these non-negative bounds rounded upward.  Every other product is bounded as in :func:`mr_matmul` (a zero term
    left out of a sum changes nothing; the radius sums have 2k terms, hence gamma_2k)."""
    N, h = lo.shape
    npair = pj.shape[0]
    nS = 1 + h + 2 * npair
    gJ = _gamma(2 * (h + 1))
    gS = _gamma(2 * nS)
    gh = _gamma(2 * h)
    y = np.empty(h)
    d0l = np.empty(h)
    d0h = np.empty(h)
    d0m = np.empty(h + 1)
    d0r = np.empty(h + 1)
    Jm = np.empty((h, h))
    Jr = np.empty((h, h))
    Aw = np.empty((h, h))
    C = np.empty((h, h))
    vin_m = np.empty(nS)
    vin_r = np.empty(nS)
    Sm = np.empty(h)
    Sr = np.empty(h)
    Dl = np.empty(h)
    Dh = np.empty(h)
    Dmag = np.empty(h)
    Tl = np.empty(h)
    Th = np.empty(h)
    r1 = np.empty(h)
    for n in range(N):
        excluded[n] = False
        inner[n] = False
        for it in range(iterations):
            w0 = 0.0
            for i in range(h):
                y[i] = s_mid(lo[n, i], hi[n, i])
                w0 += (hi[n, i] - lo[n, i]) / scale[i]
            # [1 | y - c0] in midpoint-radius form
            d0m[0] = 1.0
            d0r[0] = 0.0
            for i in range(h):
                d0l[i], d0h[i] = s_sub_exact(y[i], c0[i])
                d0m[i + 1], d0r[i + 1] = s_midrad(d0l[i], d0h[i])
            # J(y) = [1 | y - c0] [J(c0); H^T]: J(y) in [Jm - Jr, Jm + Jr]
            asum = 0.0  # sum_k |am_k| + ar_k, for the tiny entries
            for k in range(h + 1):
                asum = s_up(asum + s_up(abs(d0m[k]) + d0r[k]))
            for e in range(h * h):
                S1, S2, S3 = _sparse_midrad_sums(d0m, d0r, jh_ptr, jh_row, jh_m, jh_r, e, s_up(jh_t[e] * asum))
                Jm[e // h, e % h] = S1
                Jr[e // h, e % h] = s_mr_radius(S1, S2, S3 + S2, gJ, 2 * (h + 1))
            for i in range(h):
                for j in range(h):
                    Aw[i, j] = Jm[i, j]
            if not _float_inverse(Aw, C):
                break
            # bound b_i >= |((C J(y) - I)(X - y))_i|
            for i in range(h):
                Dl[i], Dh[i] = s_sub(lo[n, i], hi[n, i], y[i], y[i])
                Dmag[i] = max(abs(Dl[i]), abs(Dh[i]))
            CB = 0.0  # sum_j (gamma max_k |Jm_kj| + max_k Jr_kj) |X - y|_j
            for j in range(h):
                mj = 0.0
                mr = 0.0
                for k in range(h):
                    mj = max(mj, abs(Jm[k, j]))
                    mr = max(mr, Jr[k, j])
                CB = s_up(CB + s_up(s_up(s_up(gh * mj) + mr) * Dmag[j]))
            for i in range(h):
                cr = 0.0
                for k in range(h):
                    cr = s_up(cr + abs(C[i, k]))
                for j in range(h):
                    r1[j] = 0.0
                for k in range(h):  # fl(C Jm), innermost loop over j (vectorizes)
                    c = C[i, k]
                    for j in range(h):
                        r1[j] += c * Jm[k, j]
                r1[i] -= 1.0
                sE = 0.0  # sum_j |fl(C Jm) - I|_ij |X - y|_j, 2h roundings: times (1 + 2 gamma_2h) bounds the exact
                for j in range(h):
                    sE += abs(r1[j]) * Dmag[j]
                bi = s_up(s_up(sE * (1.0 + 2.0 * gh)) + s_up(cr * CB))
                Tl[i] = -bi
                Th[i] = bi
            # S = F(c0) + J(c0)(y - c0) + (1/2) Q(y - c0) + (1/2) Q(X - y): one product
            vin_m[0] = 1.0
            vin_r[0] = 0.0
            for i in range(h):
                vin_m[1 + i], vin_r[1 + i] = d0m[1 + i], d0r[1 + i]
            for p in range(npair):
                j, k = pj[p], pk[p]
                if j == k:
                    ql, qh = s_sqr(d0l[j], d0h[j])
                    rl, rh = s_sqr(Dl[j], Dh[j])
                else:
                    ql, qh = s_mul(d0l[j], d0h[j], d0l[k], d0h[k])
                    rl, rh = s_mul(Dl[j], Dh[j], Dl[k], Dh[k])
                vin_m[1 + h + p], vin_r[1 + h + p] = s_midrad(ql, qh)
                vin_m[1 + h + npair + p], vin_r[1 + h + npair + p] = s_midrad(rl, rh)
            asum = 0.0
            for k in range(nS):
                asum = s_up(asum + s_up(abs(vin_m[k]) + vin_r[k]))
            for i in range(h):
                S1, S2, S3 = _sparse_midrad_sums(vin_m, vin_r, sf_ptr, sf_row, sf_m, sf_r, i, s_up(sf_t[i] * asum))
                a, b = s_mr_bound(S1, S2, S3 + S2, gS, 2 * nS)
                Sm[i], Sr[i] = s_midrad(a, b)
            # T = y - C S - [-b, b]
            for i in range(h):
                S1 = 0.0
                S2 = 0.0
                S3 = 0.0
                for k in range(h):
                    c = C[i, k]
                    S1 += c * Sm[k]
                    S3 += abs(c) * abs(Sm[k])
                    S2 += abs(c) * Sr[k]
                csl, csh = s_mr_bound(S1, S2, S3 + S2, gh, 2 * h)
                a, b = s_sub(y[i], y[i], csl, csh)
                Tl[i], Th[i] = s_sub(a, b, Tl[i], Th[i])
            out = False
            inside = True
            for i in range(h):
                if Tl[i] > hi[n, i] or Th[i] < lo[n, i]:
                    out = True
                if not (Tl[i] > lo[n, i] and Th[i] < hi[n, i]):
                    inside = False
            if out:
                excluded[n] = True
                break
            if inside:
                inner[n] = True
            w1 = 0.0
            for i in range(h):
                lo[n, i] = s_fmax(lo[n, i], Tl[i])
                hi[n, i] = s_fmin(hi[n, i], Th[i])
                w1 += (hi[n, i] - lo[n, i]) / scale[i]
            if not w1 < (1.0 - gain) * w0:
                break
