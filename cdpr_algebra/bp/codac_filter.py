"""The filter operator of Berti, Merlet and Carricato 2016 (Sec. 4.3) built on Codac 2 (issue 20 item 2): the same
constraints as :mod:`.kernels`, handed to Codac's contractors instead of our hand-written ones.

* geometric: one :class:`codac.CtcInverse` (HC4-revise, forward-backward on the expression tree) of the vector of
  every geometric constraint -- the spheres and inequalities of eqs. 14, 20-21, 31-32, the distances of eqs. 13, 22,
  the secondary points of eqs. 17-19 (linear, interval coefficients), n = b12 x b13 with n . b12 = n . b13 = 0, the
  chirality det(b12, b13, b14) of l = 4 -- iterated by :class:`codac.CtcFixpoint` (ratio ``opts.sweep_gain``);
* statics rows: a second :class:`codac.CtcInverse` on the rows sum_i lam_i e_ri(B_i) + h_r(G) = 0 (force, moments
  about P0, about each taut exit point and each axis A_j A_k; cables dropping out of a row are left out);
* the interval Gauss elimination of K J(B) lam = -K h(G) (eqs. 34-37) with :class:`codac.CtcGaussElim` and one
  :class:`codac.CtcGaussSeidel` step; K is the generalized inverse of eq. 37 at the box centre
  (:meth:`.model.Model.statics_preconditioners`), K J(B) formed with Codac's interval matrices, each anchor once.

Codac's contractors work box by box on ``IntervalVector``; this module loops over a batch in Python (a few
microseconds of overhead per call).  Every constant is an outward-rounded interval of the model (exact fractions
rounded out), so the contraction is rigorous.

**Rounding mode.**  Importing Codac switches the processor's rounding mode to upward and leaves it there: its
interval arithmetic relies on that global mode (in round-to-nearest its 1 / 3 is a point interval that misses
1 / 3), while ours, and every floating-point computation of the package, assumes round-to-nearest (measured: after
``import codac``, numpy's 1 / 3 is 0.33333333333333337).  So Codac is imported only here (:func:`_codac`), the
mode is put back right after the import, and every use of Codac runs inside :func:`codac_rounding`, which sets
Codac's mode and restores the caller's (the mode is per thread).  Selected by ``BPOptions(kernels="codac")``; the rest of the
branch and prune (second-order operator, Krawczyk proofs, bisection) is unchanged, so the two engines are compared
on the filter alone.  Codac is an optional dependency (``pip install codac``).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import importlib
import platform
import sys
from contextlib import contextmanager

import numpy as np
from .model import Model, _cross_list
from .results import BPOptions


_LIBM = ctypes.CDLL(ctypes.util.find_library("m"))
_FE_UPWARD = {"x86_64": 0x800, "AMD64": 0x800, "aarch64": 0x400000, "arm64": 0x400000}
_CODAC_MODE = None  # the rounding mode Codac's arithmetic needs (measured at its import)


def _codac():
    """The codac module, imported with the caller's rounding mode put back (module doc)."""
    global _CODAC_MODE
    if _CODAC_MODE is None:
        fresh = "codac" not in sys.modules
        mode = _LIBM.fegetround()
        try:
            importlib.import_module("codac")
        except ImportError as exc:  # optional dependency
            raise RuntimeError("the Codac filter engine needs Codac 2: pip install codac") from exc
        if fresh:
            _CODAC_MODE = _LIBM.fegetround()
            _LIBM.fesetround(mode)
        else:  # imported before, elsewhere: its mode is upward rounding
            _CODAC_MODE = _FE_UPWARD.get(platform.machine(), 0x800)
    return sys.modules["codac"]


@contextmanager
def codac_rounding():
    """Run the block in Codac's rounding mode (upward), then restore the caller's."""
    _codac()
    mode = _LIBM.fegetround()
    _LIBM.fesetround(_CODAC_MODE)
    try:
        yield
    finally:
        _LIBM.fesetround(mode)


def _const(codac, lo, hi):
    """A constant of an expression: a float where the interval is a point, else a Codac interval."""
    lo, hi = float(lo), float(hi)
    return lo if lo == hi else codac.Interval(lo, hi)


class CodacFilter:
    """Codac's contractors for one :class:`Model` (built once per model, :func:`codac_filter`)."""

    def __init__(self, model: Model, opts: BPOptions):
        with codac_rounding():
            self._build(model, opts)

    def _build(self, model: Model, opts: BPOptions):
        codac = _codac()
        self.codac = codac
        self.model = model
        x = codac.VectorVar(model.ncols)
        self._x = x  # expressions keep a reference to their variable

        def pt(p):
            return [x[3 * p + c] for c in range(3)]

        def sub(a, b):
            return [a[c] - b[c] for c in range(3)]

        def dot(a, b):
            return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]

        exprs, ranges = [], []
        # spheres and the inequalities of eqs. 31-32: |P - A_j|^2 in [r2lo, r2hi]
        for k, p in enumerate(model.sp_pt):
            P = pt(int(p))
            t = [P[c] - _const(codac, model.sp_c.lo[k, c], model.sp_c.hi[k, c]) for c in range(3)]
            exprs.append(codac.sqr(t[0]) + codac.sqr(t[1]) + codac.sqr(t[2]))
            ranges.append([max(float(model.sp_r.lo[k]), 0.0), float(model.sp_r.hi[k])])
        # distances between platform points
        for k in range(len(model.ds_p)):
            t = sub(pt(int(model.ds_p[k])), pt(int(model.ds_q[k])))
            exprs.append(codac.sqr(t[0]) + codac.sqr(t[1]) + codac.sqr(t[2]))
            ranges.append([float(model.ds_r.lo[k]), float(model.ds_r.hi[k])])
        # secondary points: s - sum_r c_r ref_r - bn n = 0
        for pts, cf, nref, bnc in model.relations:
            for s_, p in enumerate(pts):
                S = pt(int(p))
                for c in range(3):
                    e = S[c]
                    for r in range(nref):
                        e = e - _const(codac, cf.lo[s_, r], cf.hi[s_, r]) * x[3 * r + c]
                    if bnc is not None:
                        e = e - _const(codac, bnc.lo[s_], bnc.hi[s_]) * x[3 * model.n_pt + c]
                    exprs.append(e)
                    ranges.append([0.0, 0.0])
        if model.use_n:
            r0, r1, r2 = pt(0), pt(1), pt(2)
            u, w = sub(r1, r0), sub(r2, r0)
            nv = pt(model.n_pt)
            for c, e in enumerate(_cross_list(u, w)):
                exprs.append(nv[c] - e)
                ranges.append([0.0, 0.0])
            exprs += [dot(nv, u), dot(nv, w)]
            ranges += [[0.0, 0.0], [0.0, 0.0]]
        if model.chirality is not None:
            r = [pt(p) for p in range(4)]
            exprs.append(dot(sub(r[1], r[0]), _cross_list(sub(r[2], r[0]), sub(r[3], r[0]))))
            ranges.append([float(model.det_ref.lo), float(model.det_ref.hi)])
        self.geometric = codac.CtcFixpoint(self._hc4(exprs, ranges), opts.sweep_gain)
        # statics rows
        m = model.m
        B = [pt(int(p)) for p in model.taut_pts]
        G = pt(int(model.G_pt))
        lam = [x[model.lam0 + i] for i in range(m)]
        kc, k0, hc, h0 = model.st_kc, model.st_k0, model.st_hc, model.st_h0

        def e_ri(r, i):
            e = _const(codac, k0.lo[r, i], k0.hi[r, i])
            for c in range(3):
                if kc.lo[r, i, c] != 0 or kc.hi[r, i, c] != 0:
                    e = e + _const(codac, kc.lo[r, i, c], kc.hi[r, i, c]) * B[i][c]
            return e

        rows = []
        for r in range(len(model.st_act)):
            e = _const(codac, h0.lo[r], h0.hi[r])
            for c in range(3):
                if hc.lo[r, c] != 0 or hc.hi[r, c] != 0:
                    e = e + _const(codac, hc.lo[r, c], hc.hi[r, c]) * G[c]
            for i in range(m):
                if model.st_act[r, i]:
                    e = e + lam[i] * e_ri(r, i)
            rows.append(e)
        self.statics = codac.CtcFixpoint(self._hc4(rows, [[0.0, 0.0]] * len(rows)), opts.sweep_gain)
        # Gauss elimination data: J_ri(B) = k0_ri + kc_ri . B_i (base rows), h_r(G) = h0_r + hc_r . G
        nb = model.nbase
        self.nb = nb
        self.gauss = "gauss" in opts.statics_rows
        self.k0 = codac.IntervalMatrix([[codac.Interval(float(k0.lo[r, i]), float(k0.hi[r, i])) for i in range(m)]
                                        for r in range(nb)])
        self.kc = [codac.IntervalMatrix([[codac.Interval(float(kc.lo[r, i, c]), float(kc.hi[r, i, c]))
                                          for i in range(m)] for r in range(nb)]) for c in range(3)]
        self.h0 = codac.IntervalVector([[float(h0.lo[r]), float(h0.hi[r])] for r in range(nb)])
        self.hc = codac.IntervalMatrix([[codac.Interval(float(hc.lo[r, c]), float(hc.hi[r, c])) for c in range(3)]
                                        for r in range(nb)])
        self.b_cols = [[3 * int(p) + c for c in range(3)] for p in model.taut_pts]
        self.g_cols = [3 * int(model.G_pt) + c for c in range(3)]
        self.elim = codac.CtcGaussElim()
        self.seidel = codac.CtcGaussSeidel()

    def _hc4(self, exprs, ranges):
        """HC4: one forward-backward contractor (:class:`codac.CtcInverse`, no centered form) per constraint
        expr in range, intersected."""
        codac = self.codac
        return codac.CtcInter(*[codac.CtcInverse(codac.AnalyticFunction([self._x], e), codac.Interval(*r), False)
                                for e, r in zip(exprs, ranges)])

    def _contract_gauss(self, X, K) -> bool:
        """K J(B) lam = -K h(G) by Gauss elimination, then one Gauss-Seidel step; False when the box is empty."""
        codac, model = self.codac, self.model
        m = model.m
        Km = codac.Matrix(K.tolist())
        C = Km * self.k0
        for c in range(3):  # K kc_c diag(B_c): each anchor coordinate once per entry
            D = codac.IntervalMatrix.zero(m, m)
            for i in range(m):
                D[i, i] = X[self.b_cols[i][c]]
            C = C + (Km * self.kc[c]) * D
        Gv = codac.IntervalVector([X[c] for c in self.g_cols])
        rhs = -(Km * (self.h0 + self.hc * Gv))
        lam = X.subvector(model.lam0, model.lam0 + m - 1)
        _, lam1, _ = self.elim.contract(C, codac.IntervalVector(lam), rhs)
        if lam1.is_empty():
            return False
        if not lam1.is_unbounded():
            lam = lam & lam1
        _, lam, _ = self.seidel.contract(C, lam, rhs)
        if lam.is_empty():
            return False
        X.put(model.lam0, lam)
        return True

    def contract(self, lo, hi):
        """The filter on every box (rows of lo, hi), in place; returns alive (N,) bool: the geometric and statics
        rows box by box, then (``gauss``) the elimination with K at the centres of the contracted boxes."""
        codac = self.codac
        alive = np.ones(len(lo), bool)
        boxes = []
        with codac_rounding():
            for k in range(len(lo)):
                X = codac.IntervalVector(np.stack([lo[k], hi[k]], axis=1).tolist())
                self.geometric.contract(X)
                if not X.is_empty():
                    self.statics.contract(X)
                if X.is_empty():
                    alive[k] = False
                    continue
                lo[k] = np.array(X.lb())
                hi[k] = np.array(X.ub())
                boxes.append((k, X))
        if self.gauss and boxes:
            idx = np.array([k for k, _ in boxes])
            with np.errstate(all="ignore"):
                mid = 0.5 * lo[idx] + 0.5 * hi[idx]
                Ks = self.model.statics_preconditioners(mid[:, np.asarray(self.b_cols)])  # round-to-nearest
            with codac_rounding():
                for (k, X), K in zip(boxes, Ks):
                    if not np.all(np.isfinite(K)):
                        continue
                    if not self._contract_gauss(X, K):
                        alive[k] = False
                        continue
                    lo[k] = np.array(X.lb())
                    hi[k] = np.array(X.ub())
        lo[~alive, 0] = np.inf
        return alive


def codac_filter(model: Model, opts: BPOptions) -> CodacFilter:
    """The model's :class:`CodacFilter`, built on first use."""
    f = getattr(model, "_codac_filter", None)
    if f is None:
        f = CodacFilter(model, opts)
        model._codac_filter = f
    return f
