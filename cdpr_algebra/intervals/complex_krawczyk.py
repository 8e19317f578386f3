"""Krawczyk certificates of complex roots of a polynomial system with real coefficients, a batch at a time.

A complex square system F(z) = 0, z in C^n, is certified as the real system of 2n equations
(Re F, Im F)(a, b) = 0 in z = a + i b, whose Jacobian is [[Re J, -Im J], [Im J, Re J]] (Cauchy-Riemann,
:func:`realified_jacobian`): the Krawczyk operator of :func:`cdpr_algebra.intervals.arithmetic.krawczyk` (rigorous, outward rounded,
vectorized over boxes) proves that a box X = y +/- r holds exactly one root when K(X) lies in the interior of X
(Krawczyk / Moore; R. Krawczyk 1969, R. E. Moore 1977).  The system and its Jacobian are written once in plain
arithmetic (+, -, *) and evaluated over complex numpy arrays (Newton's method) and over :class:`ComplexPair`
numbers whose parts are :class:`cdpr_algebra.intervals.arithmetic.Interval` (the enclosures over a complex box).

**Real or not, proven.**  The coefficients are real, so the conjugate of a root is a root.  A root whose float
approximation has zero imaginary part is centred on the real space (y_im = 0), so its box is invariant under
conjugation; the one root in it is then its own conjugate: real.  A root whose enclosure excludes 0 from some
imaginary part is proven non-real.

**Distinct, proven.**  Two roots proven in enclosures (X intersected with K(X)) that are disjoint are distinct;
:func:`overlapping` finds every enclosure that meets another (those roots are not proven distinct).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from .arithmetic import Interval
from .operators import krawczyk

__all__ = ["ComplexPair", "realified_jacobian", "ComplexRootBoxes", "certify_complex_roots", "overlapping"]

EPS = 2.0 ** -52
NOT_DISTINCT = "its box meets another root's box (not proven distinct)"
START_RTOL = 1e-11  # first box: +/- 1e-11 of each unknown's scale (one test for most roots), then inflated


class ComplexPair:
    """re + i im with parts of any real number type (float arrays, Interval, Dual); real constants (floats,
    Intervals) may stand on either side of +, -, *."""

    __slots__ = ("re", "im")
    __array_ufunc__ = None  # numpy arrays, Interval and Dual defer to the reflected operators below

    def __init__(self, re, im):
        self.re = re
        self.im = im

    def __add__(self, o):
        if isinstance(o, ComplexPair):
            return ComplexPair(self.re + o.re, self.im + o.im)
        return ComplexPair(self.re + o, self.im)

    __radd__ = __add__

    def __sub__(self, o):
        if isinstance(o, ComplexPair):
            return ComplexPair(self.re - o.re, self.im - o.im)
        return ComplexPair(self.re - o, self.im)

    def __rsub__(self, o):
        return ComplexPair(o - self.re, -self.im)

    def __neg__(self):
        return ComplexPair(-self.re, -self.im)

    def __mul__(self, o):
        if isinstance(o, ComplexPair):
            return ComplexPair(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)
        return ComplexPair(self.re * o, self.im * o)

    def __rmul__(self, o):
        return ComplexPair(o * self.re, o * self.im)


def _parts(v, N):
    """(Re, Im) of an entry of F or J (ComplexPair of Intervals, Interval, or a real number) as Intervals (N,)."""
    def iv(x):
        if isinstance(x, Interval):
            return Interval(np.broadcast_to(x.lo, (N,)), np.broadcast_to(x.hi, (N,)))
        x = np.broadcast_to(np.asarray(x, dtype=float), (N,))
        return Interval(x, x)

    if isinstance(v, ComplexPair):
        return iv(v.re), iv(v.im)
    return iv(v), iv(0.0)


def _complex_box(X: Interval, n: int):
    """The n complex coordinates of real boxes X (N, 2n) (real parts, then imaginary parts)."""
    return [ComplexPair(Interval(X.lo[:, k], X.hi[:, k]), Interval(X.lo[:, n + k], X.hi[:, n + k])) for k in range(n)]


def realified_jacobian(J, N: int, n: int) -> Interval:
    """The real Jacobian (N, 2n, 2n) [[Re J, -Im J], [Im J, Re J]] of the complex Jacobian J (n rows of n entries)
    of a holomorphic F (Cauchy-Riemann), as an Interval."""
    lo = np.zeros((N, 2 * n, 2 * n))
    hi = np.zeros((N, 2 * n, 2 * n))
    for i, row in enumerate(J):
        for k, v in enumerate(row):
            if isinstance(v, (int, float)) and v == 0:
                continue
            re, im = _parts(v, N)
            lo[:, i, k], hi[:, i, k] = re.lo, re.hi
            lo[:, n + i, n + k], hi[:, n + i, n + k] = re.lo, re.hi
            lo[:, n + i, k], hi[:, n + i, k] = im.lo, im.hi
            lo[:, i, n + k], hi[:, i, n + k] = -im.hi, -im.lo
    return Interval(lo, hi)


def _complex_newton(system_float, Z, iterations: int, rows=None):
    """Newton's method in complex floats on the rows of Z (N, n), vectorized; rows whose step fails stay put.
    ``rows``: the batch rows of the system that Z's rows are (default 0 .. N - 1)."""
    N, n = Z.shape
    Z = Z.copy()
    rows = np.arange(N) if rows is None else rows
    for _ in range(iterations):
        F, J = system_float([Z[:, k] for k in range(n)], rows, True)
        Fm = np.stack([np.broadcast_to(np.asarray(f, dtype=complex), (N,)) for f in F], axis=1)
        Jm = np.stack([np.stack([np.broadcast_to(np.asarray(e, dtype=complex), (N,)) for e in row], axis=1)
                       for row in J], axis=1)
        with np.errstate(all="ignore"):
            ok = np.all(np.isfinite(Jm), axis=(1, 2)) & np.all(np.isfinite(Fm), axis=1)
            dz = np.zeros_like(Z)
            try:
                dz[ok] = np.linalg.solve(Jm[ok], Fm[ok][..., None])[..., 0]
            except np.linalg.LinAlgError:  # a singular matrix in the batch: row by row
                for k in np.flatnonzero(ok):
                    try:
                        dz[k] = np.linalg.solve(Jm[k], Fm[k])
                    except np.linalg.LinAlgError:
                        pass
            dz[~np.all(np.isfinite(dz), axis=1)] = 0.0
        Z -= dz
    return Z


def _real_residual(system, n: int, rows):
    """(Re F, Im F) of ``system`` on 2n real numbers (Re z, Im z) for the batch rows ``rows``."""

    def real_residual(xs):
        F = system([ComplexPair(xs[k], xs[n + k]) for k in range(n)], rows, False)[0]
        N = len(rows)
        parts = [_parts(f, N) for f in F]
        return [p[0] for p in parts] + [p[1] for p in parts]

    return real_residual


KRAWCZYK_CHUNK = 128  # roots per vectorized Krawczyk evaluation (memory: O(chunk n^3))


@dataclass(frozen=True)
class ComplexRootBoxes:
    """Outcome of :func:`certify_complex_roots` for N roots of n unknowns.

    ``proven`` (N,): exactly one root of F in the box; ``lo``, ``hi`` (N, 2n): the enclosure of that root
    (X cap K(X); real parts then imaginary parts; the widest box allowed where not proven); ``real`` (N,): the
    root is proven real, ``nonreal`` (N,): proven non-real (neither: not proven, or an imaginary part whose
    enclosure holds 0 in a box that is not invariant under conjugation); ``center`` (N, n) the Newton-refined
    roots; ``reason`` (N,) why a root is not proven ('' when proven).
    """

    proven: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    real: np.ndarray
    nonreal: np.ndarray
    center: np.ndarray
    reason: tuple

    @property
    def count(self) -> int:
        return int(np.sum(self.proven))

    def meeting(self) -> np.ndarray:
        """(N,) bool: the proven boxes that meet another proven box (:func:`overlapping`; those roots are not proven
        distinct)."""
        out = np.zeros(len(self.proven), bool)
        out[self.proven] = overlapping(self.lo[self.proven], self.hi[self.proven])
        return out

    def distinct(self, over) -> tuple:
        """(ok, why): ok (N,) the roots proven unique in boxes that meet no other proven box (``over``:
        :meth:`meeting`), why {reason: count} for the others."""
        ok = self.proven & ~over
        return ok, dict(Counter(NOT_DISTINCT if o else r for r, good, o in zip(self.reason, ok, over) if not good))


def _krawczyk_round(system, n, part, Y, r, rmax, lo, hi, proven, reason, max_rel_width, kernel=None):
    """One epsilon-inflation round of :func:`certify_complex_roots` on the roots ``part`` (updates r, lo, hi,
    proven, reason in place); returns those still pending."""
    y, rr = Y[part], r[part]
    X = Interval(y - rr, y + rr)
    if kernel is not None:
        K, ok = kernel(part, y, rr)
    else:
        _, J = system(_complex_box(X, n), part, True)
        K, ok = krawczyk(_real_residual(system, n, part), X, y, JX=realified_jacobian(J, len(part), n))
    inside = ok & np.all((K.lo > X.lo) & (K.hi < X.hi), axis=1)
    done = part[inside]
    proven[done] = True
    lo[done] = np.fmax(X.lo[inside], K.lo[inside])
    hi[done] = np.fmin(X.hi[inside], K.hi[inside])
    rest = ~inside
    with np.errstate(invalid="ignore"):
        dev = np.maximum(np.abs(K.lo[rest] - y[rest]), np.abs(K.hi[rest] - y[rest]))
    dev = np.where(np.isfinite(dev), dev, np.inf)
    r_new = np.maximum(2 * rr[rest], 1.5 * dev)
    idx = part[rest]
    too_wide = np.any(r_new > rmax[idx], axis=1)
    for k in idx[too_wide]:
        reason[k] = (f"Krawczyk test not satisfied in any box of relative width <= {max_rel_width:.0e}: "
                     f"the root is not proven to exist and be unique (ill-conditioned or singular)")
    r[idx] = r_new
    return idx[~too_wide]


def certify_complex_roots(system, system_float, Z, scale, real_rtol: float = 1e-8,
                          max_rel_width: float = 1e-6, max_iter: int = 12, kernel=None) -> ComplexRootBoxes:
    """Prove that each approximate root z of ``Z`` (N, n complex) has exactly one root of F within a box of
    width <= ``max_rel_width`` * max(scale, |z_k|) in each coordinate (real and imaginary part).

    ``system(z, rows, jacobian) -> (F, J or None)``: the complex system and its Jacobian (n lists of n entries)
    in plain arithmetic for the roots ``rows`` of Z (an index array: constants may differ from row to row),
    rigorous when z is made of :class:`ComplexPair` of Intervals (constants Intervals or exact floats);
    ``system_float``: the same with float constants, evaluated on complex numpy arrays (Newton's method, not
    rigorous); ``scale`` (n,): the size of each unknown.  Roots with |Im z| <= ``real_rtol`` (1 + |Re z|) in every
    coordinate are refined and tested on the real space (see the module doc: a proof of realness); the others in
    C^n.  Steps: two complex Newton steps; epsilon-inflation X = y +/- r from r = ``START_RTOL`` scale, r from
    |K(X) - y|, until K(X) lies in the interior of X (proven) or r passes the width limit (not proven).  A root
    that Newton's method moves by more than the width limit is not proven (the proof would be about another point).
    ``kernel(rows, y, r) -> (K Interval (len(rows), 2n), ok (len(rows),))``: the Krawczyk operator of the same
    system over the boxes y -+ r computed otherwise (compiled: :func:`.complex_kernels.krawczyk_kernel`); then
    ``system`` is not evaluated in interval arithmetic.
    """
    Z = np.asarray(Z, dtype=complex)
    N, n = Z.shape
    empty = np.zeros((N, 2 * n))
    if N == 0:
        return ComplexRootBoxes(np.zeros(0, bool), empty, empty, np.zeros(0, bool), np.zeros(0, bool),
                                Z.copy(), ())
    is_real = np.all(np.abs(Z.imag) <= real_rtol * (1 + np.abs(Z.real)), axis=1)
    finite = np.all(np.isfinite(Z), axis=1)
    Z0 = np.where(finite[:, None], np.where(is_real[:, None], Z.real + 0j, Z), 0.0)
    chunks = [np.arange(c0, min(N, c0 + KRAWCZYK_CHUNK)) for c0 in range(0, N, KRAWCZYK_CHUNK)]
    Zn = np.concatenate([_complex_newton(system_float, Z0[rows], 2, rows) for rows in chunks])
    Y = np.hstack([Zn.real, np.where(is_real[:, None], 0.0, Zn.imag)])  # a real point stays real, rounding aside
    s = np.maximum(np.broadcast_to(np.asarray(scale, dtype=float), (n,)), np.abs(Y[:, :n] + 1j * Y[:, n:]))
    s = np.hstack([s, s])
    rmax = 0.5 * max_rel_width * s
    r = 4 * EPS * np.abs(Y) + START_RTOL * s
    proven = np.zeros(N, bool)
    lo, hi = Y - rmax, Y + rmax
    reason = ["" for _ in range(N)]
    good = finite & np.all(np.isfinite(Y), axis=1)
    for k in np.flatnonzero(~good):
        reason[k] = "the root is not finite"
    # the certified root must be the given one: Newton may not move it by more than the box's width limit
    moved = good & np.any(np.abs(Y - np.hstack([Z.real, Z.imag])) > rmax, axis=1)
    for k in np.flatnonzero(moved):
        reason[k] = (f"Newton's method moves the root by more than the box width limit ({max_rel_width:.0e} "
                     f"relative): it is not a root to that accuracy")
    pending = np.flatnonzero(good & ~moved)
    for _ in range(max_iter):
        if not len(pending):
            break
        # in chunks of KRAWCZYK_CHUNK roots: the interval products of one chunk stay within tens of MiB
        kept = []
        for c0 in range(0, len(pending), KRAWCZYK_CHUNK):
            part = pending[c0:c0 + KRAWCZYK_CHUNK]
            kept.append(_krawczyk_round(system, n, part, Y, r, rmax, lo, hi, proven, reason, max_rel_width,
                                        kernel))
        pending = np.concatenate(kept)
    for k in pending:
        reason[k] = f"Krawczyk test not satisfied after {max_iter} inflations"
    imag_lo, imag_hi = lo[:, n:], hi[:, n:]
    real = proven & is_real
    nonreal = proven & ~is_real & np.any((imag_lo > 0) | (imag_hi < 0), axis=1)
    return ComplexRootBoxes(proven, lo, hi, real, nonreal, Y[:, :n] + 1j * Y[:, n:], tuple(reason))


def overlapping(lo, hi) -> np.ndarray:
    """(N,) bool: box k meets another box of (lo, hi) (N, d) (closed boxes; a box meets another when every
    coordinate interval does)."""
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    N = len(lo)
    if N < 2:
        return np.zeros(N, bool)
    meet = np.ones((N, N), bool)
    for k in range(lo.shape[1]):  # one coordinate at a time: N x N memory
        meet &= (lo[:, None, k] <= hi[None, :, k]) & (lo[None, :, k] <= hi[:, None, k])
    np.fill_diagonal(meet, False)
    return meet.any(axis=1)


def certify_complex_root_balls(system, z, scale, prec: int = 256, max_rel_width: float = 1e-6,
                               real_rtol: float = 1e-8, newton_steps: int = 40, max_iter: int = 10,
                               max_move: float | None = None):
    """The Krawczyk test of :func:`certify_complex_roots` for one root, in complex ball arithmetic at ``prec`` bits
    (python-flint acb): for roots too ill-conditioned for double precision (condition numbers beyond ~1e8, where
    the rounding of F(y) alone exceeds any box the operator can contract).

    Newton's method in midpoint arithmetic (its steps need no error bounds) refines z first, as chord steps
    y <- y - C F(y) with C = mid(J(z))^-1: from z within the Newton basin, the error after k steps is
    ~ (kappa e)^k e (e the first error, kappa the root's condition), so each step costs one evaluation of F and a
    product, not a Jacobian and a solve; where a chord step does not shrink 10-fold, C is taken at the current point
    (a Newton step: huge ill-conditioned roots, kappa e ~ 1, converge only so, after a few steps that do not
    shrink).  It stops when a step falls below 2^-min(prec / 2, 80) of the scale (far below a double's resolution:
    the box's bounds are doubles), or after ``newton_steps`` steps, and that last step, not taken, is the Krawczyk
    operator's y - C F(y) at its centre.  The Krawczyk test
    (epsilon-inflation, as in :func:`certify_complex_roots`) uses the same C (any C gives an enclosure); when it
    fails, it is tried again with C = mid(J(y))^-1 at the refined centre.

    ``system(z, jacobian) -> (F, J)``: plain arithmetic over acb balls, constants exact (or balls), J None without
    ``jacobian``; ``z`` (n,) complex; ``scale`` (n,).  A root whose imaginary parts are within ``real_rtol`` is
    tested in a box invariant under conjugation (a proof of realness).  ``max_move``: how far (relative to the scale)
    Newton's method may move z, default half the box width limit; the box is built around the point it reaches, so
    a larger move proves a root near z, not z to that accuracy (for a caller that counts distinct roots: z a root of
    a slightly different system, e.g. one with rounded parameters).  Returns (proven, lo (2n,), hi (2n,), real,
    nonreal, reason) with lo / hi outward-rounded doubles enclosing the root (real parts, then imaginary parts).
    """
    from flint import acb, acb_mat, arb, ctx

    from .balls import lower, upper

    z = np.asarray(z, dtype=complex)
    n = len(z)
    s = np.maximum(np.broadcast_to(np.asarray(scale, dtype=float), (n,)), np.abs(z))
    rmax = 0.5 * max_rel_width * s
    moved = rmax if max_move is None else max_move * s
    is_real = bool(np.all(np.abs(z.imag) <= real_rtol * (1 + np.abs(z.real))))
    nan = np.full(2 * n, np.nan)
    if not np.all(np.isfinite(z)):
        return False, nan, nan, False, False, "the root is not finite"
    singular = (False, nan, nan, False, False, "the Jacobian is singular at the root (ball arithmetic)")

    def cplx(re, im):
        return acb(re, 0) if is_real else acb(re, im)

    with ctx.workprec(prec):
        eye = acb_mat(n, n, [1 if i == k else 0 for i in range(n) for k in range(n)])

        def inverse(J):
            """mid(J)^-1 (an approximate inverse, midpoints), None when J is singular or the result not finite."""
            try:
                C = acb_mat(J).mid().solve(eye, algorithm="approx").mid()
            except ZeroDivisionError:
                return None
            return C if all(C[i, k].is_finite() for i in range(n) for k in range(n)) else None

        def newton_image(C, y, F):
            """y - C F(y) in ball arithmetic (n x 1)."""
            return acb_mat(n, 1, y) - C * acb_mat(n, 1, F)

        def chord_step(C, y, F):
            """(y - C F(y), the step's midpoints, its size relative to the scale); None when not finite."""
            image = newton_image(C, y, F)
            d = [(y[k] - image[k, 0]).mid() for k in range(n)]
            if not all(v.is_finite() for v in d):
                return None
            return image, d, max(float(abs(d[k]).upper()) / s[k] for k in range(n))

        def krawczyk(C, y, newton):
            """Epsilon-inflation around y with the operator's C; (lo, hi) of the proven box or None."""
            dev0 = np.array([float(abs(newton[k, 0] - y[k]).upper()) for k in range(n)])
            r = np.maximum(4 * dev0, 2.0 ** (8 - prec) * s)
            for _ in range(max_iter):
                if np.any(r > rmax):
                    return None
                X = [acb(arb(y[k].real, r[k]), arb(y[k].imag, r[k])) for k in range(n)]
                _, JX = system(X, True)
                M = eye - C * acb_mat(JX)
                K = newton + M * acb_mat(n, 1, [X[k] - y[k] for k in range(n)])
                Kl = [K[k, 0] for k in range(n)]
                if all(X[k].real.contains_interior(Kl[k].real) and X[k].imag.contains_interior(Kl[k].imag)
                       for k in range(n)):
                    parts = [Kl[k].real for k in range(n)] + [Kl[k].imag for k in range(n)]
                    return np.array([lower(q) for q in parts]), np.array([upper(q) for q in parts])
                dev = np.array([float(abs(Kl[k] - y[k]).upper()) if Kl[k].is_finite() else np.inf for k in range(n)])
                r = np.maximum(2 * r, 1.5 * dev)
            return None

        y = [cplx(float(v.real), float(v.imag)) for v in z]
        F, J = system(y, True)
        C = inverse(J)
        if C is None:
            return singular
        floor = 2.0 ** -min(prec // 2, 80)
        last = np.inf
        newton = None
        for _ in range(newton_steps):
            got = chord_step(C, y, F)
            if got is not None and floor < got[2] > 0.1 * last:  # chord steps too slow: C at y (a Newton step)
                F, J = system(y, True)
                C = inverse(J)
                got = None if C is None else chord_step(C, y, F)
            if got is None:
                return singular
            newton, dy, step = got
            if step <= floor:
                break
            y = [(y[k] - dy[k]).mid() for k in range(n)]
            if is_real:
                y = [acb(v.real) for v in y]
            last = step
            F, _ = system(y, False)
            newton = None
        if newton is None:  # out of steps: the operator's y - C F(y) at the last point
            newton = newton_image(C, y, F)
        yc = np.array([complex(v) for v in y])
        if np.any(np.abs(yc - z) > moved):
            limit = (f"the box width limit ({max_rel_width:.0e} relative)" if max_move is None
                     else f"{max_move:.0e} relative")
            return False, nan, nan, False, False, (
                f"Newton's method moves the root by more than {limit}: it is not a root to that accuracy")
        box = krawczyk(C, y, newton)
        if box is None:  # again with the inverse at the refined centre
            F, J = system(y, True)
            C = inverse(J)
            if C is None:
                return singular
            box = krawczyk(C, y, newton_image(C, y, F))
        if box is not None:
            lo, hi = box
            nonreal = (not is_real) and bool(np.any((lo[n:] > 0) | (hi[n:] < 0)))
            return True, lo, hi, is_real, nonreal, ""
    return False, nan, nan, False, False, (
        f"Krawczyk test not satisfied in any box of relative width <= {max_rel_width:.0e}, also in {prec}-bit "
        f"ball arithmetic: the root is not proven to exist and be unique (ill-conditioned or singular)")
