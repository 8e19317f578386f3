"""The equation sets of one taut set (Berti, Merlet and Carricato 2016, Secs. 3-4.1) as an interval model: unknowns,
reference and secondary points, initial search domain, quadratic system; exact helpers on the robot data."""

from __future__ import annotations

import functools
import itertools
from fractions import Fraction
import numpy as np
from cdpr_algebra.intervals.arithmetic import Interval, enclose_fraction, sq, stack, up
from cdpr_algebra.intervals.scalar_kernels import rounding_gamma
from cdpr_algebra.intervals.operators import QuadraticSystem, midrad
from .precondition import generalized_inverse
from .results import _INF


# ---------------------------------------------------------------------------------------------------------------
# exact helpers (robot data are floats, i.e. exact rationals)
def _F(v):
    return [Fraction(float(x)) for x in v]


def _fsub(a, b):
    return [x - y for x, y in zip(a, b)]


def _fdot(a, b):
    return sum((x * y for x, y in zip(a, b)), Fraction(0))


def _fcross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _fdet(a, b, c):
    return _fdot(a, _fcross(b, c))


def _area2(P, tri):
    """|(P_j - P_i) x (P_k - P_i)|^2 (4 x the squared area of the triangle of points tri = (i, j, k)), exact."""
    nrm = _fcross(_fsub(P[tri[1]], P[tri[0]]), _fsub(P[tri[2]], P[tri[0]]))
    return _fdot(nrm, nrm)


def _fsolve3(cols, rhs):
    """x with sum_k x_k cols[k] = rhs (Cramer), or None if singular."""
    D = _fdet(*cols)
    if D == 0:
        return None
    out = []
    for k in range(3):
        cc = list(cols)
        cc[k] = rhs
        out.append(_fdet(*cc) / D)
    return out


def _I(fr) -> Interval:
    return Interval(*enclose_fraction(fr))


def _Ivec(frs) -> Interval:
    return Interval.from_fractions(frs)


def _Isqrt(fr) -> Interval:
    lo, hi = enclose_fraction(fr)
    return Interval(lo, hi).sqrt()


def _iget(v: Interval, k) -> Interval:
    return Interval(np.asarray(v.lo)[k], np.asarray(v.hi)[k])


def _idot(a: Interval, b: Interval) -> Interval:
    """Dot product of two interval 3-vectors (last axis)."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def _icross(a, b) -> Interval:
    return stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                  a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                  a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


def _cross_list(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


@functools.lru_cache(maxsize=16)
def _platform_distances(points):
    """({(k, l): |P_k - P_l|^2 exact}, {(k, l): enclosure of |P_k - P_l|}) for every pair of the platform points
    ``points`` (a tuple of float triples: the anchors b_i' and G): the same for every taut set of a robot."""
    P = [_F(pt) for pt in points]
    d2, d = {}, {}
    for k, l in itertools.combinations(range(len(P)), 2):
        w = _fsub(P[k], P[l])
        d2[(k, l)] = d2[(l, k)] = _fdot(w, w)
        d[(k, l)] = d[(l, k)] = _Isqrt(d2[(k, l)])
    return d2, d


class SkipSubproblem(Exception):
    pass


# ---------------------------------------------------------------------------------------------------------------
class Model:
    """The equation set of one taut set (m >= 2) in a model frame, its domain and its filter data."""

    def __init__(self, robot, rho, cables, statics_rows=("poles", "axes", "gauss")):
        self.robot = robot
        self.rho = np.asarray(rho, dtype=float)
        self.cables = tuple(cables)
        self.statics_rows = tuple(statics_rows)
        self.m = len(cables)
        self.n = robot.n
        self.L = float(robot.size)
        self.Q = float(robot.load)
        self.lam_scale = self.Q / self.L
        bF = [_F(b) for b in robot.platform]
        gF = _F(robot.com)
        self.platF = bF + [gF]  # platform points: anchors 0..n-1, G = n
        # exact squared distances between platform points and enclosures of the distances (per robot, cached)
        self._pd2, self._pd = _platform_distances(tuple(tuple(float(c) for c in pt)
                                                        for pt in list(robot.platform) + [robot.com]))
        self.G_id = self.n
        if self.m == 2:
            self._frame_planar()
        else:
            self._frame_world()
        self._layout()
        self._constants()
        self._filters()
        self._system = None

    @property
    def system(self) -> QuadraticSystem:
        """The equation set as a :class:`QuadraticSystem` (every equation set is quadratic) expanded about the
        centre of the initial box, built on first use (a search that only excludes boxes never needs it)."""
        if self._system is None:
            lo, hi = self.initial_box()
            c0 = 0.5 * (lo[0, self.core_cols] + hi[0, self.core_cols])
            c0[self.h - self.m:] = 0.0
            self._system = QuadraticSystem(self.residual, self.h, c0)
        return self._system

    # -- frames ----------------------------------------------------------------------------------------------------
    def _frame_world(self):
        self.frame = "world"
        A = np.asarray(self.robot.base, dtype=float)
        self.A = Interval(A.copy(), A.copy())
        self.to_world = (np.zeros(3), np.eye(3))
        d = Interval.point(np.asarray(self.robot.load_direction, dtype=float))
        self.f = d * self.Q
        self.dF = _F(self.robot.load_direction)
        self.pinned_y = False

    def _frame_planar(self):
        i, j = self.cables
        AF = [_F(a) for a in self.robot.base]
        dF = _F(self.robot.load_direction)
        v = _fsub(AF[j], AF[i])
        dd = _fdot(dF, dF)
        h = [v[k] - _fdot(v, dF) * dF[k] / dd for k in range(3)]
        hh = _fdot(h, h)
        if hh == 0:
            raise SkipSubproblem(f"A{i + 1} A{j + 1} is parallel to the load: the equilibria are not isolated "
                                 "(free rotation about the vertical through both exit points)")
        nd = _Isqrt(dd)
        nh = _Isqrt(hh)
        dh = _fcross(dF, h)

        def local(P):
            w = _fsub(P, AF[i])
            out = []
            for num, den in ((_fdot(w, h), nh), (_fdot(w, dh), nd * nh), (_fdot(w, dF), nd)):
                out.append(Interval(0.0, 0.0) if num == 0 else _I(num) / den)
            return out

        cols = [local(P) for P in AF]
        self.A = Interval(np.array([[c.lo for c in row] for row in cols], dtype=float),
                          np.array([[c.hi for c in row] for row in cols], dtype=float))
        fz = nd * self.Q
        self.f = Interval(np.array([0.0, 0.0, fz.lo]), np.array([0.0, 0.0, fz.hi]))
        e = (Interval.from_fractions(h) / nh).mid
        zz = (Interval.from_fractions(dF) / nd).mid
        yy = np.cross(zz, e)
        self.to_world = (np.array([float(x) for x in AF[i]]), np.stack([e, yy, zz], axis=1))
        self.dF = [Fraction(0), Fraction(0), Fraction(1)]
        self.pinned_y = True
        self.frame = "planar"

    # -- points, reference points, secondary points -------------------------------------------------------------
    def _layout(self):
        m, n = self.m, self.n
        taut = list(self.cables)
        P = self.platF
        if self.frame == "planar":
            refs = [taut[0], taut[1], self.G_id]
            if all(x == 0 for x in _fcross(_fsub(P[refs[1]], P[refs[0]]), _fsub(P[refs[2]], P[refs[0]]))):
                raise SkipSubproblem("G lies on the line of the two taut anchors: the platform turns freely about it")
        else:
            best, refs = None, None
            for tri in itertools.combinations(taut, 3):
                a2 = _area2(P, tri)
                if a2 > 0 and (best is None or a2 > best):
                    best, refs = a2, list(tri)
            if refs is None:  # collinear taut anchors: G off their line is the third reference point, as for m = 2
                for pair in itertools.combinations(taut, 2):
                    a2 = _area2(P, (*pair, self.G_id))
                    if a2 > 0 and (best is None or a2 > best):
                        best, refs = a2, [*pair, self.G_id]
            if refs is None:
                raise SkipSubproblem("the taut anchors and G are collinear: the platform turns freely about their line")
            nrm = _fcross(_fsub(P[refs[1]], P[refs[0]]), _fsub(P[refs[2]], P[refs[0]]))
            off = [k for k in taut if _fdot(nrm, _fsub(P[k], P[refs[0]])) != 0]
            if off:
                best4 = None
                for quad in itertools.combinations(taut, 4):
                    vol = abs(_fdet(_fsub(P[quad[1]], P[quad[0]]), _fsub(P[quad[2]], P[quad[0]]),
                                    _fsub(P[quad[3]], P[quad[0]])))
                    if vol > 0 and (best4 is None or vol > best4):
                        best4, refs = vol, list(quad)
                # the largest triangle of the four first (as for l = 3): the bisected points (below), which fix
                # the fourth best.  Measured (thirty-fourth session, seed 000 Test 3): with the combinations' order
                # 2.33 million boxes, largest triangle first 2.10 million (taut set {1, 3, 4, 5}: 192,000 -> 94,000)
                first = max(itertools.combinations(refs, 3), key=lambda tri: _area2(P, tri))
                refs = list(first) + [k for k in refs if k not in first]
        self.l = len(refs)
        self.refs_plat = refs  # platform-point ids of the reference points
        self.chirality = None
        if self.l == 4:
            r = [P[k] for k in refs]
            vol6 = _fdet(_fsub(r[1], r[0]), _fsub(r[2], r[0]), _fsub(r[3], r[0]))
            self.chirality = 1 if vol6 > 0 else -1
            self.det_ref = _I(vol6)  # det(b12, b13, b14): invariant under proper rotations, -det for the mirror
        # secondary platform points: every other anchor and G
        others = [k for k in list(range(n)) + [self.G_id] if k not in refs]
        r0 = P[refs[0]]
        basis = [_fsub(P[k], r0) for k in refs[1:]]
        use_n = False
        sec = []
        for k in others:
            rhs = _fsub(P[k], r0)
            if self.l == 3:
                nrm = _fcross(basis[0], basis[1])
                x = _fsolve3([basis[0], basis[1], nrm], rhs)
                coef = [1 - x[0] - x[1], x[0], x[1]]
                bn = x[2]
            else:
                x = _fsolve3(basis, rhs)
                coef = [1 - x[0] - x[1] - x[2], x[0], x[1], x[2]]
                bn = Fraction(0)
            use_n |= bn != 0
            sec.append((k, coef, bn))
        self.n_in_equations = use_n  # the equation set itself uses n = b12 x b13 (eq. 17)
        # l = 4: every point beyond the first three reference points also by eq. 17 (with n), a redundant relation
        # used by the filter only; it couples the fourth reference point to the first three as l = 3 would
        sec3 = []
        if self.l == 4:
            b12, b13 = _fsub(P[refs[1]], r0), _fsub(P[refs[2]], r0)
            nrm = _fcross(b12, b13)
            for k in [refs[3]] + others:
                x = _fsolve3([b12, b13, nrm], _fsub(P[k], r0))
                sec3.append((k, [1 - x[0] - x[1], x[0], x[1]], x[2]))
            use_n = True
        self.use_n = use_n  # the box carries n as an auxiliary point
        # model points: refs, secondaries, then n
        self.plat_ids = refs + [k for k, _, _ in sec]
        self.pid = {k: p for p, k in enumerate(self.plat_ids)}  # platform-point id -> model point
        self.npts = len(self.plat_ids) + (1 if use_n else 0)
        self.n_pt = len(self.plat_ids) if use_n else None
        self.sec = [(self.pid[k], coef, bn) for k, coef, bn in sec]
        self.sec3 = [(self.pid[k], coef, bn) for k, coef, bn in sec3]
        self.ncols = 3 * self.npts + m
        self.lam0 = 3 * self.npts
        pinned = []
        if self.pinned_y:
            pinned += [3 * p + 1 for p in range(self.l)]
            if use_n:
                pinned += [3 * self.n_pt, 3 * self.n_pt + 2]
        self.pinned = np.array(pinned, dtype=int)
        ref_cols = [3 * p + c for p in range(self.l) for c in range(3) if 3 * p + c not in pinned]
        # bisected: the coordinates of the first three reference points, which fix the pose (9 coordinates, 3
        # distances: 6 DOF).  A fourth one (l = 4) is a function of them (eq. 17 with n: the filter's sec3 relations)
        # that the contractors narrow with them; bisecting it too splits boxes along a dependent coordinate.
        # Measured (thirty-fourth session, seed 000 Test 3, all 63 taut sets): 3.23 -> 2.33 million boxes, the same
        # 16 proven solutions, no undecided box.  A column left out is still split once the bisected ones are
        # narrower than eps (the fallback in bp.search).
        self.bisect_cols = np.array([k for k in ref_cols if k < 9], dtype=int)
        self.core_cols = np.array(ref_cols + list(range(self.lam0, self.lam0 + m)), dtype=int)
        self.h = len(self.core_cols)
        self.core_scale = np.array([self.L] * len(ref_cols) + [self.lam_scale] * m)
        names = []
        for p in range(self.l):
            k = self.plat_ids[p]
            nm = "G" if k == self.G_id else f"B{k + 1}"
            names += [f"{nm}.{c}" for c in "xyz" if 3 * p + "xyz".index(c) not in pinned]
        names += [f"lam{c + 1}" for c in self.cables]
        self.variables = tuple(names)
        self.taut_pts = [self.pid[c] for c in self.cables]
        self.G_pt = self.pid[self.G_id]

    # -- constants --------------------------------------------------------------------------------------------------
    def _constants(self):
        P = self.platF
        self.rho2 = Interval.point(self.rho).sqr()
        # squared distances between model platform points (exact)
        npl = len(self.plat_ids)
        self.d2 = {}
        for p in range(npl):
            for q in range(p + 1, npl):
                self.d2[(p, q)] = self._pd2[(self.plat_ids[p], self.plat_ids[q])]
        if self.use_n:
            r = [P[k] for k in self.refs_plat]
            nrm = _fcross(_fsub(r[1], r[0]), _fsub(r[2], r[0]))
            self.nn2 = _fdot(nrm, nrm)
        self.sec_coef = [(p, _Ivec(coef), _I(bn)) for p, coef, bn in self.sec]
        self.sec_coef_f = [(p, np.array([float(c) for c in coef]), float(bn)) for p, coef, bn in self.sec]
        Am = self.A.mid
        self.P0 = np.mean(Am[list(self.cables)], axis=0)
        if self.pinned_y:
            self.P0[1] = 0.0
        # float constants for Newton
        self.cf = {"A": Am, "rho2": self.rho ** 2, "f": self.f.mid, "P0": self.P0,
                   "d2": {k: float(v) for k, v in self.d2.items()}, "sec": self.sec_coef_f}
        self.ci = {"A": self.A, "rho2": self.rho2, "f": self.f, "P0": self.P0,
                   "d2": {k: _I(v) for k, v in self.d2.items()}, "sec": self.sec_coef}

    # -- the square system (core variables) -------------------------------------------------------------------------
    def residual(self, v, interval: bool = True):
        C = self.ci if interval else self.cf
        m, l = self.m, self.l
        pts = {}
        k = 0
        for p in range(l):
            xyz = []
            for c in range(3):
                if 3 * p + c in self.pinned:
                    xyz.append(0.0)
                else:
                    xyz.append(v[k])
                    k += 1
            pts[p] = xyz
        lam = v[k:k + m]
        if interval:
            A = [[_iget(C["A"], (i, c)) for c in range(3)] for i in range(self.n)]
            rho2 = [_iget(C["rho2"], i) for i in range(self.n)]
            f = [_iget(C["f"], c) for c in range(3)]
        else:
            A = C["A"]
            rho2 = C["rho2"]
            f = C["f"]
        need = set(self.taut_pts) | {self.G_pt}
        if any(p not in pts for p in need):
            nvec = None
            if self.n_in_equations:
                u = [pts[1][c] - pts[0][c] for c in range(3)]
                w = [pts[2][c] - pts[0][c] for c in range(3)]
                nvec = _cross_list(u, w)
            for p, coef, bn in C["sec"]:
                if p not in need:
                    continue
                xyz = []
                for c in range(3):
                    acc = None
                    for r in range(l):
                        cr = _iget(coef, r) if interval else coef[r]
                        t = pts[r][c] * cr
                        acc = t if acc is None else acc + t
                    if self.n_in_equations:
                        acc = acc + nvec[c] * bn
                    xyz.append(acc)
                pts[p] = xyz
        eqs = []
        for i, p in zip(self.cables, self.taut_pts):
            B = pts[p]
            eqs.append(sq(B[0] - A[i][0]) + sq(B[1] - A[i][1]) + sq(B[2] - A[i][2]) - rho2[i])
        for a in range(l):
            for b in range(a + 1, l):
                eqs.append(sq(pts[a][0] - pts[b][0]) + sq(pts[a][1] - pts[b][1]) + sq(pts[a][2] - pts[b][2])
                           - C["d2"][(a, b)])
        P0 = C["P0"]
        G = pts[self.G_pt]
        force = [None, None, None]
        mom = [None, None, None]
        for k, (i, p) in enumerate(zip(self.cables, self.taut_pts)):
            B = pts[p]
            s = [A[i][c] - B[c] for c in range(3)]  # A - B
            r = [B[c] - P0[c] for c in range(3)]
            w = [A[i][c] - P0[c] for c in range(3)]
            mo = _cross_list(r, w)  # (B - P0) x (A - P0) = (B - P0) x (A - B)
            for c in range(3):
                t = lam[k] * s[c]
                force[c] = t if force[c] is None else force[c] + t
                t = lam[k] * mo[c]
                mom[c] = t if mom[c] is None else mom[c] + t
        g = [G[c] - P0[c] for c in range(3)]
        lm = _cross_list(g, f)
        if self.frame == "planar":
            eqs += [force[0] + f[0], force[2] + f[2], mom[1] + lm[1]]
        else:
            eqs += [force[c] + f[c] for c in range(3)] + [mom[c] + lm[c] for c in range(3)]
        return eqs

    def residual_float(self, v):
        return self.residual(v, interval=False)

    # -- initial box -------------------------------------------------------------------------------------------------
    def initial_box(self):
        lo = np.full(self.ncols, -_INF)
        hi = np.full(self.ncols, _INF)
        A = self.A
        rho = Interval.point(self.rho)
        for p, k in enumerate(self.plat_ids):
            blo, bhi = np.full(3, -_INF), np.full(3, _INF)
            for j in range(self.n):
                if k == j:
                    r = rho[j]
                else:
                    r = rho[j] + self._pd[(k, j)]
                box = Interval(A.lo[j], A.hi[j]) + Interval(-r.hi, r.hi)
                blo = np.maximum(blo, box.lo)
                bhi = np.minimum(bhi, box.hi)
            lo[3 * p:3 * p + 3] = blo
            hi[3 * p:3 * p + 3] = bhi
        if self.use_n:
            rn = _Isqrt(self.nn2).hi
            lo[3 * self.n_pt:3 * self.n_pt + 3] = -rn
            hi[3 * self.n_pt:3 * self.n_pt + 3] = rn
        lo[self.pinned] = 0.0
        hi[self.pinned] = 0.0
        lo[self.lam0:] = 0.0
        hi[self.lam0:] = _INF
        return lo[None, :], hi[None, :]

    # -- filter data --------------------------------------------------------------------------------------------------
    def _filters(self):
        n = self.n
        rho = Interval.point(self.rho)
        taut = set(self.cables)
        # spheres: (point, center (3,), R2 interval)
        sp_pt, sp_c_lo, sp_c_hi, sp_r_lo, sp_r_hi = [], [], [], [], []

        def add_sphere(p, clo, chi, rlo, rhi):
            sp_pt.append(p)
            sp_c_lo.append(clo)
            sp_c_hi.append(chi)
            sp_r_lo.append(rlo)
            sp_r_hi.append(rhi)

        for p, k in enumerate(self.plat_ids):
            for j in range(n):
                Alo, Ahi = self.A.lo[j], self.A.hi[j]
                if k == j:
                    r2 = self.rho2[j]
                    if j in taut:
                        add_sphere(p, Alo, Ahi, r2.lo, r2.hi)
                    else:
                        add_sphere(p, Alo, Ahi, -_INF, r2.hi)
                    continue
                d = self._pd[(k, j)]
                upper = (rho[j] + d).sqr().hi
                lower = -_INF
                if j in taut:
                    diff = rho[j] - d
                    if diff.lo > 0:
                        lower = diff.sqr().lo
                add_sphere(p, Alo, Ahi, lower, upper)
        if self.use_n:
            nn = _I(self.nn2)
            add_sphere(self.n_pt, np.zeros(3), np.zeros(3), nn.lo, nn.hi)
        self.sp_pt = np.array(sp_pt, dtype=int)
        self.sp_c = Interval(np.array(sp_c_lo, dtype=float), np.array(sp_c_hi, dtype=float))
        self.sp_r = Interval(np.array(sp_r_lo, dtype=float), np.array(sp_r_hi, dtype=float))
        self.sp_groups = _groups(self.sp_pt)
        # distances between platform points
        ds_p, ds_q, ds_lo, ds_hi = [], [], [], []
        for (p, q), v in self.d2.items():
            iv = _I(v)
            ds_p.append(p)
            ds_q.append(q)
            ds_lo.append(iv.lo)
            ds_hi.append(iv.hi)
        self.ds_p = np.array(ds_p, dtype=int)
        self.ds_q = np.array(ds_q, dtype=int)
        self.ds_r = Interval(np.array(ds_lo), np.array(ds_hi))
        self.ds_gp = _groups(self.ds_p)
        self.ds_gq = _groups(self.ds_q)
        # secondary points: (points, coefficients over the first L reference points, coefficient of n or None)
        self.relations = []
        for rel, nref, with_n in ((self.sec, self.l, self.n_in_equations), (self.sec3, 3, True)):
            if not rel:
                continue
            cs = [_Ivec(coef) for _, coef, _ in rel]
            bns = [_I(bn) for _, _, bn in rel]
            self.relations.append((np.array([p for p, _, _ in rel], dtype=int),
                                   Interval(np.array([c.lo for c in cs]), np.array([c.hi for c in cs])), nref,
                                   Interval(np.array([b.lo for b in bns]), np.array([b.hi for b in bns]))
                                   if with_n else None))
        # statics rows
        self._statics_rows()

    def _statics_rows(self):
        """The rows of the statics filter: row r reads sum_k lam_k (kc[r, k] . B_k + k0[r, k]) + hc[r] . G + h0[r]
        = 0 over the active cables of the row.  Force rows along u: kc = -u, k0 = A_k . u, hc = 0, h0 = f . u;
        moment rows about a point P along U (A_taut - P) x U, -P . that, f x U, -P . f x U, every moment row of
        every pole and axis computed in one vectorized pass (the same outward-rounded operations as row by row)."""
        m = self.m
        A = self.A
        f = self.f
        cab = list(self.cables)
        A_taut = Interval(A.lo[cab], A.hi[cab])  # (m, 3)
        eye = np.eye(3)
        rows = []  # ("F", u) or ("M", pole, direction, inactive cables); u, pole, direction: Intervals (3,)
        P0 = Interval.point(self.P0)

        def Ai(k):
            return Interval(A.lo[cab[k]], A.hi[cab[k]])

        def unit(c):
            return Interval(eye[c], eye[c])

        if self.frame == "planar":
            rows += [("F", unit(0)), ("F", unit(2)), ("M", P0, unit(1), ())]
            nbase = len(rows)
            rows += [("M", Ai(k), unit(1), (k,)) for k in range(m)]
        else:
            rows += [("F", unit(c)) for c in range(3)] + [("M", P0, unit(c), ()) for c in range(3)]
            nbase = len(rows)
            dd = np.asarray(self.robot.load_direction, dtype=float)
            if np.count_nonzero(dd) > 1:
                rows.append(("F", Interval.point(dd)))
            if "poles" in self.statics_rows:
                rows += [("M", Ai(k), unit(c), (k,)) for k in range(m) for c in range(3)]
            for k1, k2 in (itertools.combinations(range(m), 2) if "axes" in self.statics_rows else ()):
                inactive = tuple(k for k in range(m) if k in (k1, k2) or
                                 (np.array_equal(Ai(k).lo, Ai(k1).lo) or np.array_equal(Ai(k).lo, Ai(k2).lo)))
                rows.append(("M", Ai(k1), Ai(k2) - Ai(k1), inactive))
        R = len(rows)
        kc_lo = np.zeros((R, m, 3))
        kc_hi = np.zeros((R, m, 3))
        k0_lo = np.zeros((R, m))
        k0_hi = np.zeros((R, m))
        hc_lo = np.zeros((R, 3))
        hc_hi = np.zeros((R, 3))
        h0_lo = np.zeros(R)
        h0_hi = np.zeros(R)
        act = np.ones((R, m), bool)
        fr = [r for r in range(R) if rows[r][0] == "F"]
        mr = [r for r in range(R) if rows[r][0] == "M"]
        if fr:
            U = Interval(np.array([rows[r][1].lo for r in fr]), np.array([rows[r][1].hi for r in fr]))  # (F, 3)
            K0 = _idot(A_taut[None], U[:, None])  # (F, m)
            H0 = _idot(f, U)  # (F,)
            kc_lo[fr] = -U.hi[:, None, :]
            kc_hi[fr] = -U.lo[:, None, :]
            k0_lo[fr], k0_hi[fr] = K0.lo, K0.hi
            h0_lo[fr], h0_hi[fr] = H0.lo, H0.hi
        if mr:
            Pt = Interval(np.array([rows[r][1].lo for r in mr]), np.array([rows[r][1].hi for r in mr]))  # (M, 3)
            U = Interval(np.array([rows[r][2].lo for r in mr]), np.array([rows[r][2].hi for r in mr]))
            WU = _icross(A_taut[None] - Pt[:, None], U[:, None])  # (M, m, 3)
            K0 = -_idot(Pt[:, None], WU)  # (M, m)
            FU = _icross(f, U)  # (M, 3)
            F0 = -_idot(Pt, FU)  # (M,)
            kc_lo[mr], kc_hi[mr] = WU.lo, WU.hi
            k0_lo[mr], k0_hi[mr] = K0.lo, K0.hi
            hc_lo[mr], hc_hi[mr] = FU.lo, FU.hi
            h0_lo[mr], h0_hi[mr] = F0.lo, F0.hi
            for r in mr:
                act[r, list(rows[r][3])] = False
        kc_lo[~act] = 0.0
        kc_hi[~act] = 0.0
        k0_lo[~act] = 0.0
        k0_hi[~act] = 0.0
        self.nbase = nbase
        self.st_kc = Interval(kc_lo, kc_hi)
        self.st_k0 = Interval(k0_lo, k0_hi)
        self.st_hc = Interval(hc_lo, hc_hi)
        self.st_h0 = Interval(h0_lo, h0_hi)
        self.st_act = act
        # [k0_i; kc_i^T] (4, R) per cable and [h0; hc^T] (4, R), midpoint-radius, for one-product evaluations
        self.st_Em, self.st_Er = [], []
        for k in range(m):
            Em, Er = midrad(Interval(np.vstack([k0_lo[:, k][None], kc_lo[:, k, :].T]),
                                      np.vstack([k0_hi[:, k][None], kc_hi[:, k, :].T])))
            self.st_Em.append(np.ascontiguousarray(Em))
            self.st_Er.append(np.ascontiguousarray(Er))
        Hm, Hr = midrad(Interval(np.vstack([h0_lo[None], hc_lo.T]), np.vstack([h0_hi[None], hc_hi.T])))
        self.st_Hm, self.st_Hr = np.ascontiguousarray(Hm), np.ascontiguousarray(Hr)
        # weights of the scaled pseudoinverse (force rows 1, moment rows 1 / L^2)
        if self.frame == "planar":
            self.st_weight = np.array([1.0, 1.0, 1.0 / self.L ** 2])
        else:
            self.st_weight = np.array([1.0] * 3 + [1.0 / self.L ** 2] * 3)

    def statics_preconditioners(self, Bmid):
        """K (N, m, R0) of eq. 37 (:func:`.precondition.generalized_inverse`) for the base statics rows with J
        evaluated at the anchor points Bmid (N, m, 3) (the box centres); NaN where J is too ill-conditioned."""
        nb = self.nbase
        Jm = np.einsum("rmc,nmc->nrm", self.st_kc.mid[:nb], Bmid) + self.st_k0.mid[:nb][None]  # (N, R0, m)
        return generalized_inverse(Jm, self.st_weight, self.frame == "world")

    def compiled_data(self):
        """The model's contractor data as flat arrays for :func:`_contract_kernel` (built once, on first use)."""
        if getattr(self, "_kdata", None) is not None:
            return self._kdata
        i64 = np.int64
        rel_pt, rel_nref, rel_c, rel_hasn, rel_b = [], [], [], [], []
        for pts, c, nref, bnc in self.relations:
            for s_ in range(len(pts)):
                rel_pt.append(pts[s_])
                rel_nref.append(nref)
                cl = np.zeros(4)
                ch = np.zeros(4)
                cl[:nref], ch[:nref] = c.lo[s_, :nref], c.hi[s_, :nref]
                rel_c.append((cl, ch))
                rel_hasn.append(bnc is not None)
                rel_b.append((0.0, 0.0) if bnc is None else (float(bnc.lo[s_]), float(bnc.hi[s_])))
        ns = len(rel_pt)
        rel = (np.array(rel_pt, dtype=i64), np.array(rel_nref, dtype=i64),
               np.array([a for a, _ in rel_c]).reshape(ns, 4), np.array([b for _, b in rel_c]).reshape(ns, 4),
               np.array(rel_hasn, dtype=np.bool_), np.array([a for a, _ in rel_b], dtype=float),
               np.array([b for _, b in rel_b], dtype=float))
        c_ = np.ascontiguousarray
        sph = (self.sp_pt.astype(i64), c_(self.sp_c.lo), c_(self.sp_c.hi), c_(self.sp_r.lo), c_(self.sp_r.hi))
        dst = (self.ds_p.astype(i64), self.ds_q.astype(i64), c_(self.ds_r.lo), c_(self.ds_r.hi))
        chir = (0, 0.0, 0.0) if self.chirality is None else (int(self.chirality), float(self.det_ref.lo),
                                                             float(self.det_ref.hi))
        bcols = (3 * np.asarray(self.taut_pts, dtype=i64)[:, None] + np.arange(3, dtype=i64))
        rows = (bcols, int(3 * self.G_pt), int(self.lam0), c_(np.stack(self.st_Em)), c_(np.stack(self.st_Er)),
                self.st_Hm, self.st_Hr, c_(self.st_act.T), 3)
        nb_ = self.nbase
        kcm, kcr = midrad(self.st_kc[:nb_])
        k0m, k0r = midrad(self.st_k0[:nb_])
        hcm, hcr = midrad(self.st_hc[:nb_])
        h0m, h0r = midrad(self.st_h0[:nb_])
        g = float(rounding_gamma(2 * nb_))

        def colbound(vm, vr):  # max over the rows (axis 0) of gamma |mid| + rad, upward
            return c_(up(up(g * np.abs(vm)) + vr).max(axis=0))

        gauss = (bcols, int(3 * self.G_pt), int(self.lam0), bool(self.frame == "world" and nb_ == 6),
                 np.asarray(self.st_weight, dtype=float), c_(kcm), c_(k0m), c_(hcm), c_(h0m), colbound(kcm, kcr),
                 colbound(k0m, k0r), colbound(hcm, hcr), float(up(up(g * np.abs(h0m)) + h0r).max()))
        self._kdata = (rel, int(self.n_pt) if self.use_n else -1, bool(self.use_n), sph, dst, chir, rows, gauss)
        return self._kdata

    # -- decoding -----------------------------------------------------------------------------------------------------
    def points_float(self, x):
        """Model-frame positions of every platform point for core vectors x (N, h): dict platform id -> (N, 3)."""
        x = np.atleast_2d(x)
        N = len(x)
        refs = np.zeros((N, self.l, 3))
        k = 0
        for p in range(self.l):
            for c in range(3):
                if 3 * p + c in self.pinned:
                    continue
                refs[:, p, c] = x[:, k]
                k += 1
        out = {self.plat_ids[p]: refs[:, p] for p in range(self.l)}
        nvec = np.cross(refs[:, 1] - refs[:, 0], refs[:, 2] - refs[:, 0]) if self.n_in_equations else None
        for p, coef, bn in self.sec_coef_f:
            s = np.einsum("r,nrc->nc", coef, refs)
            if self.n_in_equations:
                s = s + bn * nvec
            out[self.plat_ids[p]] = s
        return out

    def pose(self, x):
        """(position of the platform origin, rotation, tensions (n,)) in the world frame, for one core vector."""
        x = np.asarray(x, dtype=float)
        pts = self.points_float(x[None, :])
        origin, T = self.to_world
        ids = self.refs_plat[:3]
        W = [origin + T @ pts[k][0] for k in ids]
        Pp = [np.array([float(c) for c in self.platF[k]]) for k in ids]
        R = _frame(W) @ _frame(Pp).T
        p = W[0] - R @ Pp[0]
        tau = np.zeros(self.n)
        lam = x[self.h - self.m:]
        tau[list(self.cables)] = lam * self.rho[list(self.cables)]
        return p, R, tau

    def classify(self, E: Interval):
        """'admissible', 'inadmissible' or a reason string (boundary) for a proven enclosure E (1, h) of a solution."""
        lam = E[:, self.h - self.m:]
        if np.any(lam.hi < 0):
            return "inadmissible"
        # full box from the core enclosure
        lo = np.zeros((1, self.ncols))
        hi = np.zeros((1, self.ncols))
        lo[:, self.core_cols] = E.lo
        hi[:, self.core_cols] = E.hi
        lo[:, self.pinned] = 0.0
        hi[:, self.pinned] = 0.0
        box = _Box(lo, hi)
        if self.use_n:
            r = [box.point(p) for p in range(3)]
            box.set_point(self.n_pt, _icross(r[1] - r[0], r[2] - r[0]))
        if self.sec:
            refs = [box.point(p) for p in range(self.l)]
            for s, (p, coef, bn) in enumerate(self.sec_coef):
                acc = None
                for r in range(self.l):
                    t = refs[r] * _iget(coef, r)
                    acc = t if acc is None else acc + t
                if self.n_in_equations:
                    acc = acc + box.point(self.n_pt) * bn
                box.set_point(p, acc)
        reasons = []
        for j in range(self.n):
            if j in self.cables:
                continue
            B = box.point(self.pid[j])
            Aj = Interval(self.A.lo[j], self.A.hi[j])
            dist2 = (B - Aj).sqr().sum(axis=-1)
            if np.any(dist2.lo > self.rho2.hi[j]):
                return "inadmissible"
            if np.any(dist2.hi >= self.rho2.lo[j]):
                reasons.append(f"cable {j + 1} (slack) is at its length within the enclosure")
        if self.chirality is not None:
            r = [box.point(p) for p in range(4)]
            det = _idot(r[1] - r[0], _icross(r[2] - r[0], r[3] - r[0]))
            if (self.chirality > 0 and np.all(det.hi < 0)) or (self.chirality < 0 and np.all(det.lo > 0)):
                return "inadmissible"  # the mirror image of the platform
            if not ((self.chirality > 0 and np.all(det.lo > 0)) or (self.chirality < 0 and np.all(det.hi < 0))):
                reasons.append("orientation (mirror image) not decided on the enclosure")
        for k, c in enumerate(self.cables):
            if lam.lo[0, k] <= 0:
                reasons.append(f"tension {c + 1} encloses 0")
        return "admissible" if not reasons else "; ".join(reasons)


def _frame(pts):
    a, b, c = pts
    e1 = b - a
    e3 = np.cross(b - a, c - a)
    n1, n3 = np.linalg.norm(e1), np.linalg.norm(e3)
    if not (n1 > 0 and n3 > 0):  # e.g. the centre of an undecided box: no pose (callers catch it)
        raise ValueError("no frame: the three points are collinear")
    e1, e3 = e1 / n1, e3 / n3
    return np.stack([e1, np.cross(e3, e1), e3], axis=1)


def _groups(idx):
    return [(u, np.flatnonzero(idx == u)) for u in np.unique(idx)]


class _Box:
    """Helper view of a batch of boxes (lo, hi (N, ncols)) by points."""

    def __init__(self, lo, hi):
        self.lo = lo
        self.hi = hi

    def point(self, p) -> Interval:
        return Interval(self.lo[:, 3 * p:3 * p + 3], self.hi[:, 3 * p:3 * p + 3])

    def set_point(self, p, v: Interval):
        self.lo[:, 3 * p:3 * p + 3] = v.lo
        self.hi[:, 3 * p:3 * p + 3] = v.hi

    def tighten_point(self, p, v: Interval):
        s = slice(3 * p, 3 * p + 3)
        self.lo[:, s] = np.fmax(self.lo[:, s], v.lo)
        self.hi[:, s] = np.fmin(self.hi[:, s], v.hi)
