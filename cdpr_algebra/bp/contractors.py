"""The filter operator (Berti, Merlet and Carricato 2016, Sec. 4.3), vectorized over batches of boxes: 2B/HC4 on the
geometric constraints, statics rows and the interval Gauss elimination (the reference for :mod:`.kernels`)."""

from __future__ import annotations

import numpy as np
from cdpr_algebra.intervals.arithmetic import Interval, inv_sqr, stack
from cdpr_algebra.intervals.operators import midrad, mr_matmul
from .kernels import _contract_kernel
from .model import Model, _Box, _icross, _idot
from .results import BPOptions, _INF


# ---------------------------------------------------------------------------------------------------------------
# contractors (each intersects the boxes in place)
def _sos_project(t: Interval, R2: Interval) -> Interval:
    """HC4 on sum_c t_c^2 in R2 (t: (..., 3)): the projected t."""
    s = t.sqr()
    s0, s1, s2 = s[..., 0], s[..., 1], s[..., 2]
    S = (s0 + s1 + s2).intersect(R2)
    n0 = s0.intersect(S - (s1 + s2))
    n1 = s1.intersect(S - (s0 + s2))
    n2 = s2.intersect(S - (s0 + s1))
    return stack([inv_sqr(n0, t[..., 0]), inv_sqr(n1, t[..., 1]), inv_sqr(n2, t[..., 2])], axis=-1)


def _reduce_tighten(box: _Box, groups, new: Interval, cols_of):
    for u, ks in groups:
        lo = new.lo[:, ks].max(axis=1)
        hi = new.hi[:, ks].min(axis=1)
        s = cols_of(u)
        box.lo[:, s] = np.fmax(box.lo[:, s], lo)
        box.hi[:, s] = np.fmin(box.hi[:, s], hi)


def _pt_cols(p):
    return slice(3 * p, 3 * p + 3)


def _gather(box: _Box, pts) -> Interval:
    cols = 3 * np.asarray(pts)[:, None] + np.arange(3)
    return Interval(box.lo[:, cols], box.hi[:, cols])


def contract_spheres(model: Model, box: _Box):
    X = _gather(box, model.sp_pt)
    t = X - model.sp_c
    tn = _sos_project(t, model.sp_r)
    _reduce_tighten(box, model.sp_groups, tn + model.sp_c, _pt_cols)


def contract_distances(model: Model, box: _Box):
    Xp = _gather(box, model.ds_p)
    Xq = _gather(box, model.ds_q)
    t = Xp - Xq
    tn = _sos_project(t, model.ds_r)
    _reduce_tighten(box, model.ds_gp, (tn + Xq).intersect(Xp), _pt_cols)
    _reduce_tighten(box, model.ds_gq, (Xp - tn).intersect(Xq), _pt_cols)


def contract_secondary(model: Model, box: _Box):
    """Secondary points s = sum_r c_r ref_r (+ bn n), eqs. 17-19, forward then backward onto refs and n."""
    for pts, c, l, bnc in model.relations:
        _contract_relation(model, box, pts, c, l, bnc)


def _contract_relation(model: Model, box: _Box, pts, c: Interval, l: int, bnc):
    R = _gather(box, np.arange(l))  # (N, l, 3)
    terms = []
    for r in range(l):
        cr = Interval(c.lo[:, r, None], c.hi[:, r, None])  # (S, 1)
        terms.append(Interval(R.lo[:, None, r, :], R.hi[:, None, r, :]) * cr)  # (N, S, 3)
    if bnc is not None:
        nv = box.point(model.n_pt)
        bn = Interval(bnc.lo[:, None], bnc.hi[:, None])
        terms.append(Interval(nv.lo[:, None, :], nv.hi[:, None, :]) * bn)
    total = terms[0]
    for t in terms[1:]:
        total = total + t
    S = _gather(box, pts)
    S = S.intersect(total)
    box.lo[:, 3 * pts[:, None] + np.arange(3)] = S.lo
    box.hi[:, 3 * pts[:, None] + np.arange(3)] = S.hi
    # backward: each term = S - (others)
    nterm = len(terms)
    for k in range(nterm):
        others = None
        for j in range(nterm):
            if j != k:
                others = terms[j] if others is None else others + terms[j]
        tk = terms[k].intersect(S - others)
        if k < l:
            cr = Interval(c.lo[:, k, None], c.hi[:, k, None])
            new = tk / cr  # (N, S, 3); (-inf, inf) where the coefficient contains 0
            box.tighten_point(k, Interval(new.lo.max(axis=1), new.hi.min(axis=1)))
        else:
            new = tk / Interval(bnc.lo[:, None], bnc.hi[:, None])
            box.tighten_point(model.n_pt, Interval(new.lo.max(axis=1), new.hi.min(axis=1)))


def contract_normal(model: Model, box: _Box):
    """n = b12 x b13 (forward), n . b12 = 0 and n . b13 = 0 (2B both ways)."""
    if not model.use_n:
        return
    r0, r1, r2 = box.point(0), box.point(1), box.point(2)
    u = r1 - r0
    w = r2 - r0
    nv = box.point(model.n_pt).intersect(_icross(u, w))
    box.set_point(model.n_pt, nv)
    for which, v in ((1, u), (2, w)):
        t = [nv[:, c] * v[:, c] for c in range(3)]
        tn = []
        for c in range(3):
            others = t[(c + 1) % 3] + t[(c + 2) % 3]
            tn.append(t[c].intersect(-others))
        nn = stack([nv[:, c].intersect(tn[c] / v[:, c]) for c in range(3)], axis=-1)
        vn = stack([v[:, c].intersect(tn[c] / nv[:, c]) for c in range(3)], axis=-1)
        box.tighten_point(model.n_pt, nn)
        nv = box.point(model.n_pt)
        rw = box.point(which)
        box.tighten_point(which, vn + r0)
        box.tighten_point(0, rw - vn)


def contract_chirality(model: Model, box: _Box):
    """l = 4: det(b12, b13, b14) equals its platform value (a proper rotation keeps it, the mirror image negates it);
    boxes whose interval determinant misses that value are excluded."""
    if model.chirality is None:
        return
    r = [box.point(p) for p in range(4)]
    det = _idot(r[1] - r[0], _icross(r[2] - r[0], r[3] - r[0]))
    dead = (det.lo > model.det_ref.hi) | (det.hi < model.det_ref.lo)
    box.lo[dead, 0] = _INF


def contract_statics_rows(model: Model, box: _Box):
    """2B on the statics rows sum_i lam_i e_ri(B_i) + h_r(G) = 0 (force rows, moments about P0, A_j, A_j A_k):
    exclusion and projection onto lam.  (The projection back onto the pose was measured not to pay for itself once
    the second-order operator runs on every box, and is not done.)"""
    m = model.m
    B = _gather(box, model.taut_pts)  # (N, m, 3)
    G = box.point(model.G_pt)  # (N, 3)
    lam = Interval(box.lo[:, model.lam0:], box.hi[:, model.lam0:])  # (N, m)
    act = model.st_act
    N = box.lo.shape[0]
    ones, zeros = np.ones((N, 1)), np.zeros((N, 1))
    Bm, Br = midrad(B)
    es = []
    for i in range(m):  # e_ri = k0_ri + kc_ri . B_i for all rows r: one product [1 | B_i] [k0_i; kc_i^T]
        ei = mr_matmul(np.hstack([ones, Bm[:, i]]), np.hstack([zeros, Br[:, i]]), model.st_Em[i], model.st_Er[i])
        es.append(ei)
    e = stack(es, axis=-1)  # (N, R, m)
    lb = Interval(lam.lo[:, None, :], lam.hi[:, None, :])
    t = lb * e
    t = Interval(np.where(act, t.lo, 0.0), np.where(act, t.hi, 0.0))
    Gm, Gr = midrad(G)
    H = mr_matmul(np.hstack([ones, Gm]), np.hstack([zeros, Gr]), model.st_Hm, model.st_Hr)  # (N, R)
    terms = [t[..., i] for i in range(m)] + [H]
    nt = len(terms)
    # prefix / suffix sums give the sum of the others for each term
    pre = [None] * (nt + 1)
    suf = [None] * (nt + 1)
    for k in range(nt):
        pre[k + 1] = terms[k] if pre[k] is None else pre[k] + terms[k]
    for k in range(nt - 1, -1, -1):
        suf[k] = terms[k] if suf[k + 1] is None else terms[k] + suf[k + 1]
    new_terms = []
    for k in range(nt):
        if pre[k] is None:
            others = suf[k + 1]
        elif suf[k + 1] is None:
            others = pre[k]
        else:
            others = pre[k] + suf[k + 1]
        new_terms.append(terms[k].intersect(-others))
    tn = stack(new_terms[:m], axis=-1)  # (N, R, m)
    Hn = new_terms[m]
    dead = np.any(Hn.lo > Hn.hi, axis=1) | np.any(tn.lo > tn.hi, axis=(1, 2))
    # lam_i in t_i / e_i ; e_i in t_i / lam_i
    lam_new = tn / e
    lam_new = Interval(np.where(act, lam_new.lo, -_INF), np.where(act, lam_new.hi, _INF))
    box.lo[:, model.lam0:] = np.fmax(box.lo[:, model.lam0:], lam_new.lo.max(axis=1))
    box.hi[:, model.lam0:] = np.fmin(box.hi[:, model.lam0:], lam_new.hi.min(axis=1))
    box.lo[dead, 0] = _INF


def contract_statics_gauss(model: Model, box: _Box):
    """Interval Gauss elimination of K J(B) lam = -K h(G) (eqs. 34-37) and one Gauss-Seidel step."""
    m = model.m
    nb = model.nbase
    N = box.lo.shape[0]
    B = _gather(box, model.taut_pts)  # (N, m, 3)
    G = box.point(model.G_pt)
    kc = model.st_kc[:nb]  # (R0, m, 3)
    k0 = model.st_k0[:nb]
    hc = model.st_hc[:nb]
    h0 = model.st_h0[:nb]
    K = model.statics_preconditioners(B.mid)
    ok = np.all(np.isfinite(K), axis=(1, 2))
    K = np.where(ok[:, None, None], K, 0.0)
    # C_ji = sum_r K_jr k0_ri + sum_c (sum_r K_jr kc_ric) B_ic ; rhs_j = -(sum_r K_jr h0_r + sum_c (..) G_c)
    R0 = nb
    k0m, k0r = midrad(k0)  # (R0, m)
    kcm, kcr = midrad(kc)  # (R0, m, 3)
    KK0 = mr_matmul(K, None, k0m, k0r)  # (N, m, m)
    KKc = mr_matmul(K, None, kcm.reshape(R0, m * 3), kcr.reshape(R0, m * 3))
    KKc = Interval(KKc.lo.reshape(N, m, m, 3), KKc.hi.reshape(N, m, m, 3))
    h0m, h0r = midrad(h0)
    Kh0 = mr_matmul(K, None, h0m[:, None], h0r[:, None])
    Kh0 = Interval(Kh0.lo[..., 0], Kh0.hi[..., 0])  # (N, m)
    hcm, hcr = midrad(hc)
    Khc = mr_matmul(K, None, hcm, hcr)  # (N, m, 3)
    Bb = Interval(B.lo[:, None], B.hi[:, None])  # (N, 1, m, 3)
    C = KK0 + KKc[..., 0] * Bb[..., 0] + KKc[..., 1] * Bb[..., 1] + KKc[..., 2] * Bb[..., 2]
    Gb = Interval(G.lo[:, None], G.hi[:, None])
    rhs = -(Kh0 + Khc[..., 0] * Gb[..., 0] + Khc[..., 1] * Gb[..., 1] + Khc[..., 2] * Gb[..., 2])
    x, gok = _interval_gauss(C, rhs)
    ok &= gok
    lam = Interval(box.lo[:, model.lam0:], box.hi[:, model.lam0:])
    lam = Interval(np.where(ok[:, None], np.fmax(lam.lo, x.lo), lam.lo),
                   np.where(ok[:, None], np.fmin(lam.hi, x.hi), lam.hi))
    # one Gauss-Seidel step on the preconditioned system with the current lam
    okgs = ok.copy()
    newl = [lam[:, i] for i in range(m)]
    for i in range(m):
        acc = rhs[:, i]
        for j in range(m):
            if j != i:
                acc = acc - C[:, i, j] * newl[j]
        cand = acc / C[:, i, i]
        li = newl[i].intersect(cand)
        newl[i] = Interval(np.where(okgs, li.lo, newl[i].lo), np.where(okgs, li.hi, newl[i].hi))
    lam = stack(newl, axis=-1)
    box.lo[:, model.lam0:] = lam.lo
    box.hi[:, model.lam0:] = lam.hi


def _interval_gauss(C: Interval, b: Interval):
    """Interval Gauss elimination without pivoting for a batch of m x m systems; (x, ok)."""
    N, m, _ = C.lo.shape
    A = [[C[:, i, j] for j in range(m)] for i in range(m)]
    rhs = [b[:, i] for i in range(m)]
    ok = np.ones(N, bool)
    for k in range(m):
        piv = A[k][k]
        ok &= (piv.lo > 0) | (piv.hi < 0)
        for i in range(k + 1, m):
            fct = A[i][k] / piv
            for j in range(k + 1, m):
                A[i][j] = A[i][j] - fct * A[k][j]
            rhs[i] = rhs[i] - fct * rhs[k]
    x = [None] * m
    for i in range(m - 1, -1, -1):
        acc = rhs[i]
        for j in range(i + 1, m):
            acc = acc - A[i][j] * x[j]
        x[i] = acc / A[i][i]
    X = stack(x, axis=-1)
    ok &= np.all(np.isfinite(X.lo) & np.isfinite(X.hi), axis=1)
    return X, ok


def contract(model: Model, lo, hi, opts: BPOptions):
    """Filter operator: all contractors, iterated; returns the surviving boxes.  ``opts.kernels == "compiled"``
    (default): box by box in compiled code (:func:`_contract_kernel`, contractors in the order ``opts.filter_order``);
    "codac": Codac 2's contractors on the same constraints (:mod:`.codac_filter`); "numpy": the vectorized
    contractors (:func:`contract_vectorized`)."""
    if opts.kernels == "compiled":
        lo = np.ascontiguousarray(lo, dtype=float)
        hi = np.ascontiguousarray(hi, dtype=float)
        rel, n_pt, use_n, sph, dst, chir, rows, gauss = model.compiled_data()
        alive = _contract_kernel(lo, hi, model.core_cols.astype(np.int64), model.core_scale, int(opts.max_sweeps),
                                 float(opts.sweep_gain), rel, n_pt, use_n, sph, dst, chir, rows, gauss,
                                 "gauss" in opts.statics_rows, int(opts.filter_order))
    elif opts.kernels == "codac":
        from .codac_filter import codac_filter
        alive = codac_filter(model, opts).contract(lo, hi)
    else:
        alive = contract_vectorized(model, lo, hi, opts)
    return lo[alive], hi[alive]


def contract_vectorized(model: Model, lo, hi, opts: BPOptions):
    """The vectorized filter operator on the boxes (lo, hi), in place: every contractor on the whole batch, the
    sweeps repeated on the boxes that shrank; returns alive (N,) bool."""
    scale = model.core_scale
    with np.errstate(all="ignore"):
        act = np.arange(len(lo))
        for sweep in range(opts.max_sweeps):
            if len(act) == 0:
                break
            box = _Box(lo[act], hi[act])
            w0 = ((box.hi - box.lo)[:, model.core_cols] / scale).sum(axis=1)
            contract_secondary(model, box)
            contract_normal(model, box)
            contract_spheres(model, box)
            contract_distances(model, box)
            contract_secondary(model, box)
            contract_chirality(model, box)
            contract_statics_rows(model, box)
            if "gauss" in opts.statics_rows:
                contract_statics_gauss(model, box)
            lo[act] = box.lo
            hi[act] = box.hi
            dead = np.any(~(box.lo <= box.hi), axis=1)
            w1 = ((box.hi - box.lo)[:, model.core_cols] / scale).sum(axis=1)
            again = ~dead & (w1 < (1 - opts.sweep_gain) * w0)
            # an unbounded lam narrowed to a bounded one also counts as progress
            again |= ~dead & ~np.isfinite(w0) & np.isfinite(w1)
            lo[act[dead], 0] = _INF
            act = act[again]
        return np.all(lo <= hi, axis=1)
