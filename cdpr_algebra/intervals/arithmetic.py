"""Vectorized interval arithmetic on numpy arrays, outward rounded (the arithmetic of :mod:`cdpr_algebra.bp`).

An :class:`Interval` holds two float64 arrays ``lo`` and ``hi`` of the same (broadcastable) shape: a batch of
intervals, e.g. a batch of boxes of shape (nboxes, nvars).  Operations act elementwise with numpy broadcasting.

**Rounding.**  numpy computes in IEEE 754 double precision with round-to-nearest; IEEE 754 requires +, -, *, /
and sqrt to be correctly rounded, so a computed bound differs from the exact result of the operation on the
(exact) input bounds by at most half an ulp.  Every operation here moves each computed lower bound at least one
ulp down and each computed upper bound at least one ulp up, so the returned interval contains the exact image of
the input intervals: all enclosures are rigorous.  The widening computes
up(x) = x + min(|x| 2^-52 + 2^-900, 1e300) (and down(x) = x - ...) with four array operations, 5-7 times faster
than ``np.nextafter`` (exactly one ulp) in numpy, and never narrower than it: for a normal x in [2^e, 2^(e+1)) in magnitude,
fl(|x| 2^-52) >= 2^(e-52), the spacing of the floats at x, so the exact x + |x| 2^-52 + ... lies at or beyond the
neighbouring float and round-to-nearest (monotone) cannot bring it back; for subnormal or zero x the added
2^-900 exceeds the subnormal spacing 2^-1074 (and keeps widened zeros normal numbers: arithmetic on subnormals is
about 100 times slower); infinities stay infinite (the cap keeps -inf + inf from making a NaN).
``tests/test_interval_bp.py`` checks it against ``np.nextafter`` and exact rational arithmetic.  Exact
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

import numpy as np

__all__ = ["Interval", "Dual", "dual_variables", "down", "up", "enclose_fraction", "sq", "isum", "inv_sqr", "stack"]

_INF = np.inf


_U = 2.0 ** -52
_TINY = 2.0 ** -900  # >= the subnormal spacing 2^-1074; large enough that widened zeros (and 2^-52 times them)
# stay normal numbers: subnormal arithmetic is ~100x slower on x86
_FLOOR = 2.0 ** -940  # floor of the terms scaled by ~2^-52 in mr_matmul, so that no subnormal is formed
_CAP = 1e300  # keeps the widening of +-inf finite (so up(-inf) = -inf, down(inf) = inf)


def down(x):
    """A float <= np.nextafter(x, -inf): x moved at least one ulp toward -inf (lower bounds after a rounded
    operation).  Fast form x - min(|x| 2^-52 + 2^-1074, 1e300), see the module docstring."""
    t = np.abs(x)
    if type(t) is not np.ndarray:
        return x - np.minimum(t * _U + _TINY, _CAP)
    t *= _U
    t += _TINY
    np.minimum(t, _CAP, out=t)
    return np.subtract(x, t, out=t)


def up(x):
    """A float >= np.nextafter(x, +inf): x moved at least one ulp toward +inf (upper bounds)."""
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
