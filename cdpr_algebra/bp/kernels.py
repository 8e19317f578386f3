"""The filter operator compiled (numba), box by box: the contractors of :mod:`.contractors` with the scalar
outward-rounded twins of the vectorized interval operations."""

from __future__ import annotations

import numba as nb
import numpy as np
from cdpr_algebra.intervals.scalar_kernels import rounding_gamma
from cdpr_algebra.intervals.scalar_kernels import (float_inverse, s_add, s_div, s_down, s_fmax, s_fmin, s_inv_sqr,
                                                   s_mid, s_midrad, s_mr_radius, s_mul, s_sqr, s_sub, s_up)



# ---------------------------------------------------------------------------------------------------------------
# compiled contractors: the filter operator box by box (numba).  The same contractors as above, in the same order
# and with the same outward-rounded operations (:mod:`cdpr_algebra.intervals.arithmetic` s_* twins of the vectorized ones); a box
# reads its own latest bounds (each projection intersects at once, Gauss-Seidel style, which is at least as tight
# as the vectorized version's simultaneous update and as rigorous: every bound used encloses the box), and
# the work on a box stops as soon as it is empty.  tests/test_interval_bp.py checks them against the vectorized
# contractors on batches of boxes.
@nb.njit(cache=True, error_model="numpy")
def _tighten(lo, hi, n, col, a, b):
    lo[n, col] = s_fmax(lo[n, col], a)
    hi[n, col] = s_fmin(hi[n, col], b)
    return lo[n, col] <= hi[n, col]


@nb.njit(cache=True, error_model="numpy")
def _c_relations(lo, hi, n, rel_pt, rel_nref, rel_cl, rel_ch, rel_hasn, rel_bl, rel_bh, n_pt):
    """:func:`contract_secondary`: s = sum_r c_r ref_r (+ bn n), forward onto s, backward onto the refs and n."""
    tl = np.empty(5)
    th = np.empty(5)
    for s in range(rel_pt.shape[0]):
        p = rel_pt[s]
        nref = rel_nref[s]
        nt = nref + (1 if rel_hasn[s] else 0)
        for c in range(3):
            for r in range(nref):
                tl[r], th[r] = s_mul(lo[n, 3 * r + c], hi[n, 3 * r + c], rel_cl[s, r], rel_ch[s, r])
            if rel_hasn[s]:
                tl[nref], th[nref] = s_mul(lo[n, 3 * n_pt + c], hi[n, 3 * n_pt + c], rel_bl[s], rel_bh[s])
            al, ah = tl[0], th[0]
            for k in range(1, nt):
                al, ah = s_add(al, ah, tl[k], th[k])
            if not _tighten(lo, hi, n, 3 * p + c, al, ah):
                return False
            Sl, Sh = lo[n, 3 * p + c], hi[n, 3 * p + c]
            for k in range(nt):
                first = True
                ol, oh = 0.0, 0.0
                for j in range(nt):
                    if j != k:
                        if first:
                            ol, oh = tl[j], th[j]
                            first = False
                        else:
                            ol, oh = s_add(ol, oh, tl[j], th[j])
                xl, xh = s_sub(Sl, Sh, ol, oh)
                a = s_fmax(tl[k], xl)
                b = s_fmin(th[k], xh)
                if not a <= b:  # the term misses its value: no solution in the box
                    return False
                if k < nref:
                    ql, qh = s_div(a, b, rel_cl[s, k], rel_ch[s, k])
                    if not _tighten(lo, hi, n, 3 * k + c, ql, qh):
                        return False
                else:
                    ql, qh = s_div(a, b, rel_bl[s], rel_bh[s])
                    if not _tighten(lo, hi, n, 3 * n_pt + c, ql, qh):
                        return False
    return True


@nb.njit(cache=True, error_model="numpy")
def _c_normal(lo, hi, n, n_pt):
    """:func:`contract_normal`: n = b12 x b13 (forward), n . b12 = 0 and n . b13 = 0 (2B both ways)."""
    ul = np.empty(3)
    uh = np.empty(3)
    wl = np.empty(3)
    wh = np.empty(3)
    tl = np.empty(3)
    th = np.empty(3)
    for c in range(3):
        ul[c], uh[c] = s_sub(lo[n, 3 + c], hi[n, 3 + c], lo[n, c], hi[n, c])
        wl[c], wh[c] = s_sub(lo[n, 6 + c], hi[n, 6 + c], lo[n, c], hi[n, c])
    r0l = lo[n, 0:3].copy()
    r0h = hi[n, 0:3].copy()
    for c in range(3):
        c1 = (c + 1) % 3
        c2 = (c + 2) % 3
        al, ah = s_mul(ul[c1], uh[c1], wl[c2], wh[c2])
        bl, bh = s_mul(ul[c2], uh[c2], wl[c1], wh[c1])
        xl, xh = s_sub(al, ah, bl, bh)
        if not _tighten(lo, hi, n, 3 * n_pt + c, xl, xh):
            return False
    for which in (1, 2):
        if which == 1:
            vl, vh = ul, uh
        else:
            vl, vh = wl, wh
        nl = lo[n, 3 * n_pt:3 * n_pt + 3].copy()
        nh = hi[n, 3 * n_pt:3 * n_pt + 3].copy()
        for c in range(3):
            tl[c], th[c] = s_mul(nl[c], nh[c], vl[c], vh[c])
        nnl = np.empty(3)
        nnh = np.empty(3)
        vnl = np.empty(3)
        vnh = np.empty(3)
        for c in range(3):
            ol, oh = s_add(tl[(c + 1) % 3], th[(c + 1) % 3], tl[(c + 2) % 3], th[(c + 2) % 3])
            a = s_fmax(tl[c], -oh)
            b = s_fmin(th[c], -ol)
            if not a <= b:
                return False
            ql, qh = s_div(a, b, vl[c], vh[c])
            nnl[c], nnh[c] = s_fmax(nl[c], ql), s_fmin(nh[c], qh)
            ql, qh = s_div(a, b, nl[c], nh[c])
            vnl[c], vnh[c] = s_fmax(vl[c], ql), s_fmin(vh[c], qh)
        for c in range(3):
            if not _tighten(lo, hi, n, 3 * n_pt + c, nnl[c], nnh[c]):
                return False
        for c in range(3):
            rwl, rwh = lo[n, 3 * which + c], hi[n, 3 * which + c]
            xl, xh = s_add(vnl[c], vnh[c], r0l[c], r0h[c])
            if not _tighten(lo, hi, n, 3 * which + c, xl, xh):
                return False
            xl, xh = s_sub(rwl, rwh, vnl[c], vnh[c])
            if not _tighten(lo, hi, n, c, xl, xh):
                return False
    return True


@nb.njit(cache=True, error_model="numpy")
def _sos_forward(tl, th, ql, qh):
    for c in range(3):
        ql[c], qh[c] = s_sqr(tl[c], th[c])
    a, b = s_add(ql[0], qh[0], ql[1], qh[1])
    return s_add(a, b, ql[2], qh[2])


@nb.njit(cache=True, error_model="numpy")
def _sos_narrow(tl, th, ql, qh, rl, rh):
    """Forward sum S of the squares of (tl, th) against the range [rl, rh]: (0, S) when S already lies in it (the
    projection would return the box itself), (-1, S) when they are disjoint (no solution in the box), else
    (1, S cap [rl, rh]) to project back with :func:`_sos_backward`."""
    Sl, Sh = _sos_forward(tl, th, ql, qh)
    if Sl >= rl and Sh <= rh:
        return 0, Sl, Sh
    Sl = s_fmax(Sl, rl)
    Sh = s_fmin(Sh, rh)
    if not Sl <= Sh:
        return -1, Sl, Sh
    return 1, Sl, Sh


@nb.njit(cache=True, error_model="numpy")
def _sos_backward(Sl, Sh, tl, th, ql, qh, c):
    """The projection of sum_c t_c^2 in S onto t_c (:func:`_sos_project`)."""
    c1 = (c + 1) % 3
    c2 = (c + 2) % 3
    ol, oh = s_add(ql[c1], qh[c1], ql[c2], qh[c2])
    xl, xh = s_sub(Sl, Sh, ol, oh)
    return s_inv_sqr(s_fmax(ql[c], xl), s_fmin(qh[c], xh), tl[c], th[c])


@nb.njit(cache=True, error_model="numpy")
def _c_spheres(lo, hi, n, sp_pt, cl, ch, rl, rh):
    """:func:`contract_spheres` (|P - c|^2 in R); skipped where the forward sum already lies in R (the projection
    then returns the box itself)."""
    tl = np.empty(3)
    th = np.empty(3)
    ql = np.empty(3)
    qh = np.empty(3)
    for k in range(sp_pt.shape[0]):
        p = sp_pt[k]
        for c in range(3):
            tl[c], th[c] = s_sub(lo[n, 3 * p + c], hi[n, 3 * p + c], cl[k, c], ch[k, c])
        state, Sl, Sh = _sos_narrow(tl, th, ql, qh, rl[k], rh[k])
        if state < 0:
            return False
        if state == 0:
            continue
        for c in range(3):
            vl, vh = _sos_backward(Sl, Sh, tl, th, ql, qh, c)
            vl, vh = s_add(vl, vh, cl[k, c], ch[k, c])
            if not _tighten(lo, hi, n, 3 * p + c, vl, vh):
                return False
    return True


@nb.njit(cache=True, error_model="numpy")
def _c_distances(lo, hi, n, ds_p, ds_q, rl, rh):
    """:func:`contract_distances` (|P - Q|^2 in R), onto P then Q."""
    tl = np.empty(3)
    th = np.empty(3)
    ql = np.empty(3)
    qh = np.empty(3)
    for k in range(ds_p.shape[0]):
        p = ds_p[k]
        q = ds_q[k]
        for c in range(3):
            tl[c], th[c] = s_sub(lo[n, 3 * p + c], hi[n, 3 * p + c], lo[n, 3 * q + c], hi[n, 3 * q + c])
        state, Sl, Sh = _sos_narrow(tl, th, ql, qh, rl[k], rh[k])
        if state < 0:
            return False
        if state == 0:
            continue
        for c in range(3):
            vl, vh = _sos_backward(Sl, Sh, tl, th, ql, qh, c)
            xl, xh = s_add(vl, vh, lo[n, 3 * q + c], hi[n, 3 * q + c])
            if not _tighten(lo, hi, n, 3 * p + c, xl, xh):
                return False
            xl, xh = s_sub(lo[n, 3 * p + c], hi[n, 3 * p + c], vl, vh)
            if not _tighten(lo, hi, n, 3 * q + c, xl, xh):
                return False
    return True


@nb.njit(cache=True, error_model="numpy")
def _c_chirality(lo, hi, n, chir, dl, dh):
    """:func:`contract_chirality`: det(b12, b13, b14) must meet its platform value [dl, dh]."""
    if chir == 0:
        return True
    al = np.empty((3, 3))
    ah = np.empty((3, 3))
    for k in range(3):
        for c in range(3):
            al[k, c], ah[k, c] = s_sub(lo[n, 3 * (k + 1) + c], hi[n, 3 * (k + 1) + c], lo[n, c], hi[n, c])
    # a . (b x c), left to right as _idot(a, _icross(b, c))
    xl = np.empty(3)
    xh = np.empty(3)
    for c in range(3):
        c1 = (c + 1) % 3
        c2 = (c + 2) % 3
        pl, ph = s_mul(al[1, c1], ah[1, c1], al[2, c2], ah[2, c2])
        ql, qh = s_mul(al[1, c2], ah[1, c2], al[2, c1], ah[2, c1])
        xl[c], xh[c] = s_sub(pl, ph, ql, qh)
    sl, sh = s_mul(al[0, 0], ah[0, 0], xl[0], xh[0])
    for c in range(1, 3):
        pl, ph = s_mul(al[0, c], ah[0, c], xl[c], xh[c])
        sl, sh = s_add(sl, sh, pl, ph)
    return not (sl > dh or sh < dl)


@nb.njit(cache=True, error_model="numpy")
def _c_statics_rows(lo, hi, n, bcols, gcol, lam0, Em, Er, Hm, Hr, act, passes):
    """:func:`contract_statics_rows`: for every row r, sum_i lam_i e_ri(B_i) + h_r(G) = 0 with e_ri = k0_ri +
    kc_ri . B_i and h_r = h0_r + hc_r . G (midpoint-radius products as :func:`cdpr_algebra.intervals.arithmetic.mr_matmul`):
    exclusion, projection onto each lam_i (lam_i in -(others) / e_ri), all rows with the same lam as the vectorized
    version (loops over the rows innermost, so that they vectorize), repeated (``passes``) while some lam shrinks by
    more than 10 %: e and h depend on the pose only.  ``act`` (m, R): cable i is in row r."""
    m = bcols.shape[0]
    R = act.shape[1]
    el = np.empty((m, R))
    eh = np.empty((m, R))
    tl = np.empty((m, R))
    th = np.empty((m, R))
    pl = np.empty((m + 1, R))
    ph = np.empty((m + 1, R))
    sl = np.empty((m + 1, R))
    sh = np.empty((m + 1, R))
    g4 = rounding_gamma(8)
    for i in range(m):
        a1, r1 = s_midrad(lo[n, bcols[i, 0]], hi[n, bcols[i, 0]])
        a2, r2 = s_midrad(lo[n, bcols[i, 1]], hi[n, bcols[i, 1]])
        a3, r3 = s_midrad(lo[n, bcols[i, 2]], hi[n, bcols[i, 2]])
        for r in range(R):  # e_ri = [1 | B_i] [k0_i; kc_i^T][:, r]
            b0, b1, b2, b3 = Em[i, 0, r], Em[i, 1, r], Em[i, 2, r], Em[i, 3, r]
            e0, e1, e2, e3 = Er[i, 0, r], Er[i, 1, r], Er[i, 2, r], Er[i, 3, r]
            S1 = b0 + a1 * b1 + a2 * b2 + a3 * b3
            S3 = abs(b0) + abs(a1) * abs(b1) + abs(a2) * abs(b2) + abs(a3) * abs(b3)
            S2 = (e0 + abs(a1) * e1 + r1 * s_up(abs(b1) + e1) + abs(a2) * e2 + r2 * s_up(abs(b2) + e2)
                  + abs(a3) * e3 + r3 * s_up(abs(b3) + e3))
            W = s_mr_radius(S1, S2, S3 + S2, g4, 8)
            el[i, r] = S1 - W
            eh[i, r] = S1 + W
    g1, q1 = s_midrad(lo[n, gcol], hi[n, gcol])
    g2, q2 = s_midrad(lo[n, gcol + 1], hi[n, gcol + 1])
    g3, q3 = s_midrad(lo[n, gcol + 2], hi[n, gcol + 2])
    for r in range(R):  # h_r = [1 | G] [h0; hc^T][:, r], the last suffix sum
        b0, b1, b2, b3 = Hm[0, r], Hm[1, r], Hm[2, r], Hm[3, r]
        e0, e1, e2, e3 = Hr[0, r], Hr[1, r], Hr[2, r], Hr[3, r]
        S1 = b0 + g1 * b1 + g2 * b2 + g3 * b3
        S3 = abs(b0) + abs(g1) * abs(b1) + abs(g2) * abs(b2) + abs(g3) * abs(b3)
        S2 = (e0 + abs(g1) * e1 + q1 * s_up(abs(b1) + e1) + abs(g2) * e2 + q2 * s_up(abs(b2) + e2)
              + abs(g3) * e3 + q3 * s_up(abs(b3) + e3))
        W = s_mr_radius(S1, S2, S3 + S2, g4, 8)
        sl[m, r] = S1 - W
        sh[m, r] = S1 + W
    for sweep in range(passes):
        shrunk = False
        for i in range(m):
            ll, lh = lo[n, lam0 + i], hi[n, lam0 + i]
            for r in range(R):
                if act[i, r]:
                    tl[i, r], th[i, r] = s_mul(ll, lh, el[i, r], eh[i, r])
                else:
                    tl[i, r] = 0.0
                    th[i, r] = 0.0
        # prefix sums p[k] = t_0 + .. + t_{k-1} (k >= 1), suffix sums s[k] = t_k + .. + t_{m-1} + h
        for r in range(R):
            pl[1, r] = tl[0, r]
            ph[1, r] = th[0, r]
        for k in range(1, m):
            for r in range(R):
                pl[k + 1, r], ph[k + 1, r] = s_add(pl[k, r], ph[k, r], tl[k, r], th[k, r])
        for k in range(m - 1, -1, -1):
            for r in range(R):
                sl[k, r], sh[k, r] = s_add(tl[k, r], th[k, r], sl[k + 1, r], sh[k + 1, r])
        dead = False
        for r in range(R):  # h against the others
            dead |= s_fmax(sl[m, r], -ph[m, r]) > s_fmin(sh[m, r], -pl[m, r])
        if dead:
            return False
        for k in range(m):
            olo = lo[n, lam0 + k]
            ohi = hi[n, lam0 + k]
            nlo, nhi = olo, ohi
            for r in range(R):
                if k == 0:
                    ol, oh = sl[1, r], sh[1, r]
                else:
                    ol, oh = s_add(pl[k, r], ph[k, r], sl[k + 1, r], sh[k + 1, r])
                a = s_fmax(tl[k, r], -oh)
                b = s_fmin(th[k, r], -ol)
                dead |= not a <= b
                if act[k, r]:
                    ql, qh = s_div(a, b, el[k, r], eh[k, r])
                    nlo = s_fmax(nlo, ql)
                    nhi = s_fmin(nhi, qh)
            if dead:
                return False
            if not _tighten(lo, hi, n, lam0 + k, nlo, nhi):
                return False
            w_old = ohi - olo
            if not (hi[n, lam0 + k] - lo[n, lam0 + k] >= 0.9 * w_old) or (w_old == np.inf and nhi < np.inf):
                shrunk = True
        if not shrunk:
            break
    return True


@nb.njit(cache=True, error_model="numpy")
def _c_statics_gauss(lo, hi, n, bcols, gcol, lam0, world6, weight, kcm, k0m, hcm, h0m, bkc, bk0, bhc, bh0):
    """:func:`contract_statics_gauss`: K from the float J at the box centre (eq. 37, or the weighted pseudoinverse
    where W^T J is ill conditioned; 1-norm condition numbers), C = K J(B) with single occurrences of B, rhs = -K h(G),
    interval Gauss elimination, one Gauss-Seidel step.  (kcm, k0m, hcm, h0m): midpoints of the base rows' constants,
    (bkc, bk0, bhc, bh0): their columns' bounds max_r (gamma_2R0 |mid| + rad), rounded upward."""
    R0, m = k0m.shape
    Bm = np.empty((m, 3))
    for i in range(m):
        for c in range(3):
            Bm[i, c] = s_mid(lo[n, bcols[i, c]], hi[n, bcols[i, c]])
    Jm = np.empty((R0, m))
    for r in range(R0):
        for i in range(m):
            acc = 0.0
            for c in range(3):
                acc += kcm[r, i, c] * Bm[i, c]
            Jm[r, i] = acc + k0m[r, i]
    # generalized inverse K (m, R0) = M^-1 W^T
    M = np.empty((m, m))
    Minv = np.empty((m, m))
    WT = np.empty((m, R0))
    K = np.empty((m, R0))
    good = False
    for attempt in range(2):
        if attempt == 0 and not world6:
            continue
        for j in range(m):
            for r in range(R0):
                if attempt == 0:
                    WT[j, r] = Jm[(r + 3) % 6, j]
                else:
                    WT[j, r] = Jm[r, j] * weight[r]
        for j in range(m):
            for i in range(m):
                acc = 0.0
                for r in range(R0):
                    acc += WT[j, r] * Jm[r, i]
                M[j, i] = acc
        n1 = 0.0
        for i in range(m):
            a = 0.0
            for j in range(m):
                a += abs(M[j, i])
            n1 = max(n1, a)
        if not float_inverse(M, Minv):  # overwrites M
            continue
        n2 = 0.0
        for i in range(m):
            b = 0.0
            for j in range(m):
                b += abs(Minv[j, i])
            n2 = max(n2, b)
        if not n1 * n2 < (1e8 if attempt == 0 else 1e12):
            continue
        for j in range(m):
            for r in range(R0):
                acc = 0.0
                for i in range(m):
                    acc += Minv[j, i] * WT[i, r]
                K[j, r] = acc
        good = True
        break
    if not good:
        return True
    for j in range(m):
        for r in range(R0):
            if not np.isfinite(K[j, r]):
                return True
    # C_ji = (K k0)_ji + sum_c (K kc)_jic B_ic ; rhs_j = -((K h0)_j + sum_c (K hc)_jc G_c).  Each float product
    # K v is enclosed by S1 +- (sum_r |K_jr|) max_r (gamma |v_m| + v_r) (rounding errors and the constants' radii)
    Cl = np.empty((m, m))
    Ch = np.empty((m, m))
    rl = np.empty(m)
    rh = np.empty(m)
    for j in range(m):
        ks = 0.0
        for r in range(R0):
            ks = s_up(ks + abs(K[j, r]))
        for i in range(m):
            S1 = 0.0
            for r in range(R0):
                S1 += K[j, r] * k0m[r, i]
            W = s_up(ks * bk0[i])
            cl, ch = s_down(S1 - W), s_up(S1 + W)
            for c in range(3):
                S1 = 0.0
                for r in range(R0):
                    S1 += K[j, r] * kcm[r, i, c]
                W = s_up(ks * bkc[i, c])
                al, ah = s_mul(s_down(S1 - W), s_up(S1 + W), lo[n, bcols[i, c]], hi[n, bcols[i, c]])
                cl, ch = s_add(cl, ch, al, ah)
            Cl[j, i], Ch[j, i] = cl, ch
        S1 = 0.0
        for r in range(R0):
            S1 += K[j, r] * h0m[r]
        W = s_up(ks * bh0)
        xl, xh = s_down(S1 - W), s_up(S1 + W)
        for c in range(3):
            S1 = 0.0
            for r in range(R0):
                S1 += K[j, r] * hcm[r, c]
            W = s_up(ks * bhc[c])
            al, ah = s_mul(s_down(S1 - W), s_up(S1 + W), lo[n, gcol + c], hi[n, gcol + c])
            xl, xh = s_add(xl, xh, al, ah)
        rl[j], rh[j] = -xh, -xl
    # interval Gauss elimination without pivoting (:func:`_interval_gauss`)
    Al = Cl.copy()
    Ah = Ch.copy()
    bl = rl.copy()
    bh = rh.copy()
    ok = True
    for k in range(m):
        pl_, ph_ = Al[k, k], Ah[k, k]
        if not (pl_ > 0 or ph_ < 0):
            ok = False
            break
        for i in range(k + 1, m):
            fl, fh = s_div(Al[i, k], Ah[i, k], pl_, ph_)
            for j in range(k + 1, m):
                xl, xh = s_mul(fl, fh, Al[k, j], Ah[k, j])
                Al[i, j], Ah[i, j] = s_sub(Al[i, j], Ah[i, j], xl, xh)
            xl, xh = s_mul(fl, fh, bl[k], bh[k])
            bl[i], bh[i] = s_sub(bl[i], bh[i], xl, xh)
    if ok:
        xl_ = np.empty(m)
        xh_ = np.empty(m)
        for i in range(m - 1, -1, -1):
            al, ah = bl[i], bh[i]
            for j in range(i + 1, m):
                pl_, ph_ = s_mul(Al[i, j], Ah[i, j], xl_[j], xh_[j])
                al, ah = s_sub(al, ah, pl_, ph_)
            xl_[i], xh_[i] = s_div(al, ah, Al[i, i], Ah[i, i])
            if not (np.isfinite(xl_[i]) and np.isfinite(xh_[i])):
                ok = False
        if ok:
            for i in range(m):
                if not _tighten(lo, hi, n, lam0 + i, xl_[i], xh_[i]):
                    return False
    if not ok:
        return True
    # one Gauss-Seidel step with the current lam
    for i in range(m):
        al, ah = rl[i], rh[i]
        for j in range(m):
            if j != i:
                pl_, ph_ = s_mul(Cl[i, j], Ch[i, j], lo[n, lam0 + j], hi[n, lam0 + j])
                al, ah = s_sub(al, ah, pl_, ph_)
        ql, qh = s_div(al, ah, Cl[i, i], Ch[i, i])
        if not _tighten(lo, hi, n, lam0 + i, ql, qh):
            return False
    return True


@nb.njit(cache=True, error_model="numpy")
def _c_statics(lo, hi, n, rows, gauss, do_gauss):
    """The statics contractors on box n: the rows, then (``do_gauss``) the generalized-inverse form."""
    ok = _c_statics_rows(lo, hi, n, *rows)
    if ok and do_gauss:
        ok = _c_statics_gauss(lo, hi, n, *gauss)
    return ok


@nb.njit(cache=True, error_model="numpy")
def _nonempty(lo, hi, n):
    """Box n has lo <= hi in every column (False also for a NaN bound)."""
    for c in range(lo.shape[1]):
        if not lo[n, c] <= hi[n, c]:
            return False
    return True


@nb.njit(cache=True, error_model="numpy", nogil=True)  # releases the GIL: subproblems search in threads
def _contract_kernel(lo, hi, core, scale, max_sweeps, gain, rel, n_pt, use_n, sph, dst, chir, rows, gauss, do_gauss,
                     order):
    """:func:`contract` box by box; returns alive (N,) bool (a dead box also gets lo[:, 0] = inf).  order 0: the
    sweeps of all contractors while the box shrinks by more than ``gain`` (the vectorized order); order 1: the
    geometric contractors while the pose shrinks by more than ``gain``, then the statics ones once (they narrow
    the tensions only, which the geometric ones do not use)."""
    N = lo.shape[0]
    alive = np.ones(N, dtype=np.bool_)
    npose = core.shape[0] - rows[0].shape[0]
    for n in range(N):
        ok = True
        for sweep in range(max_sweeps):
            w0 = 0.0
            for k in range(npose if order == 1 else core.shape[0]):
                w0 += (hi[n, core[k]] - lo[n, core[k]]) / scale[k]
            ok = _c_relations(lo, hi, n, *rel, n_pt)
            if ok and use_n:
                ok = _c_normal(lo, hi, n, n_pt)
            ok = ok and _c_spheres(lo, hi, n, *sph)
            ok = ok and _c_distances(lo, hi, n, *dst)
            ok = ok and _c_relations(lo, hi, n, *rel, n_pt)
            ok = ok and _c_chirality(lo, hi, n, *chir)
            if order == 0:
                ok = ok and _c_statics(lo, hi, n, rows, gauss, do_gauss)
            ok = ok and _nonempty(lo, hi, n)
            if not ok:
                break
            w1 = 0.0
            for k in range(npose if order == 1 else core.shape[0]):
                w1 += (hi[n, core[k]] - lo[n, core[k]]) / scale[k]
            if not (w1 < (1.0 - gain) * w0 or (not np.isfinite(w0) and np.isfinite(w1))):
                break
        if ok and order == 1:
            ok = _c_statics(lo, hi, n, rows, gauss, do_gauss) and _nonempty(lo, hi, n)
        if not ok:
            alive[n] = False
            lo[n, 0] = np.inf
    return alive
