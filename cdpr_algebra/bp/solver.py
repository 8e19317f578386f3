"""Interval branch-and-prune DGP solver (seed 000, Berti-Merlet-Carricato 2016): an independent, complete method
that finds every admissible equilibrium (real, tensions >= 0, other cables slack) of each set of taut cables.

Everything rests on the outward-rounded arithmetic of :mod:`cdpr_algebra.intervals.arithmetic`: boxes are processed in batches
(arrays of lower / upper bounds of shape (nboxes, ncols)), and every exclusion, every contraction and every
existence-and-uniqueness proof is rigorous.  The filter and the second-order operator, where the time goes, run
box by box in compiled kernels (numba; ``KERNELS = "compiled"``, the default) made of the scalar twins of the
vectorized interval operations (same bounds, bit for bit), with each projection applied at once and the work on a
box stopped as soon as it is empty; ``KERNELS = "numpy"`` keeps the vectorized operators as the reference (tests
compare the two).  Seed 000 Test 3, profiled: 942 s vectorized, of which the filter 64 % and the second-order
operator 33 %; each kernel is 3-6 times faster than its vectorized form.

**Equation sets (Sec. 3), tensions as unknowns.**  lam_i = tau_i / rho_i (tensions scaled by the constant 1/rho_i).

* m = 1 (Sec. 3.2): B_i = A_i + rho_i d and G on the vertical through B_i (G below or above, tension Q > 0);
  the platform turns freely about the cable.  Instead of Algorithm 2 (a float test of each slack cable alone), the
  turning angle is searched by interval bisection in two rational charts t = tan(theta / 2) of the circle, where
  every other cable must satisfy |B_j - A_j| <= rho_j (an equilibrium is proven when an interval of t satisfies all
  of them strictly, excluded when one is violated over every t).
* m = 2 (Sec. 3.3): the frame turned about the load so that A_i, A_j and the load lie in the plane y = 0; unknowns
  (x, z) of B_i, B_j, G and lam: 8 equations (eqs. 10-12: three distances, two lengths, force x, force z, moment y).
* m >= 3 (Secs. 3.4-3.6): l = 3 reference points (the taut anchors are coplanar; other platform points by eq. 18, or
  eq. 17 with the cross product n = b12 x b13 when off the plane) or l = 4 (eq. 19), the reference points among the
  taut anchors; unknowns the 3l coordinates and the m lam: m lengths (eqs. 14, 20, 21), C(l, 2) distances (eqs. 13,
  22) and 6 statics equations (eq. 5, moments about a fixed pole P0), 3l + m equations.  With l = 4 the six
  distances also admit the mirror image of the platform, rejected on the verified enclosure by the sign of
  det(b12, b13, b14).  m = 6 keeps lam as unknowns (the paper drops them; an implementation choice).

**Initial search domain (Sec. 4.1).**  Each anchor in the box of its sphere (taut: |B_i - A_i| = rho_i) or ball
(slack: <= rho_i), every platform point P within rho_j + d_Pj of every A_j; lam_i in [0, +inf).  The refined bounds
of Fig. 5 and the tension bound of eq. 26 are then produced by the same 2B contraction run on the initial box:
the force balance along the load, lam_i (B_i - A_i).d <= Q - ..., bounds lam_i exactly as eq. 26 whenever the box
is suspended ((B_i - A_i).d > 0); otherwise the statics filter bounds them (the paper's non-suspended case).

**Filter operator (Sec. 4.3)**: the geometric contractors iterated while the pose shrinks by more than 10 %
(``max_sweeps``), then the statics ones, which narrow only the tensions (``ORDER = 1``; ``ORDER = 0``: all of them
iterated, the vectorized order):

* 2B / HC4 on the geometric constraints: the spheres of the taut anchors (eqs. 14, 20, 21), the distances between
  all platform points (reference and secondary, eqs. 13, 22), the inequalities of eqs. 31-32 (every platform point
  P and cable j: (rho_j - d_Pj)^2 <= |P - A_j|^2 <= (rho_j + d_Pj)^2 if j is taut, |P - A_j| <= rho_j + d_Pj and
  |B_j - A_j| <= rho_j if j is slack), the secondary points by eqs. 17-19 both ways, n = b12 x b13 with |n| constant
  and n . b12 = n . b13 = 0 (the constant products of eq. 33).
* statics: 2B (exclusion and projection onto lam) on the force rows (x, y, z and along the load), the moment rows
  about P0, about each taut exit point A_j (cable j drops out) and about each axis A_j A_k (cables j, k drop out: the
  sign of one cable's term is fixed by the load's), repeated while a lam shrinks by 10 %; then the interval Gauss
  elimination of K J lam = -K Q L_e (eqs. 34-35) with the generalized inverse K = (W^T mid J)^-1 W^T of eq. 37 (the
  length-scaled pseudoinverse where W^T J is singular, e.g. m = 2, whose force and moment rows do not pair), its
  entries written with single occurrences of the pose (J is affine in each anchor), followed by one Gauss-Seidel
  step.  The Plucker-constrained optimization of C (eqs. 39-42) is not done.

**Evaluation operator with unicity test (Sec. 4.2).**  Every equation set is quadratic (seed 000's remark, which
makes its Kantorovich constant p fixed), so F(x) = F(y) + J(y)(x - y) + (1/2) Q(x - y) holds exactly with constant
Hessians (:class:`cdpr_algebra.intervals.arithmetic.QuadraticSystem`).  On every bounded box the operator
T(X) = y - C F(y) - (C J(y) - I)(X - y) - C (1/2) Q(X - y), C = mid J(y)^-1, excludes the box (T(X) cap X empty) or
contracts it (X cap T(X)); it plays the role of the gradient-based evaluation and interval Newton filtering of
ALIAS's Solve_General_Gradient_Interval and is about twice as tight as the Krawczyk operator.  On boxes narrower
than ``krawczyk_width`` the Krawczyk operator K(X) proves a unique solution (K(X) in the interior of X) -- it
replaces the Kantorovich test.  It is tried where T(X) lies in the interior of X (``GATE``; Brouwer: X holds a
solution), elsewhere it would hardly ever succeed and the box is bisected.  A box where Newton converges is also
tried inflated around the Newton point (epsilon-inflation); a box inside a proven box is discarded (its only
solution is already counted); two proven boxes are the same solution when one's enclosure lies in the other
(uniqueness), so nothing is counted twice.

**Bisection**: the widest pose variable (lengths) until every pose width is below ``eps`` (relative to the robot
size), then the widest variable overall (lam scaled by Q / size).  Boxes that reach ``eps`` undecided are
reported (:class:`UndecidedBox`), never dropped: the result is complete -- every admissible equilibrium lies in a
proven solution box or in an undecided box.  A proven solution whose enclosure straddles a domain boundary
(a tension interval containing 0, a slack cable exactly at its length, an undecided mirror sign) is reported as
undecided as well (it is an equilibrium of a smaller taut set or a degenerate one).
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass, field
from fractions import Fraction

import numba as nb
import numpy as np

from cdpr_algebra.model.taut_sets import solve_each_taut_set
from cdpr_algebra.intervals.arithmetic import (Interval, QuadraticSystem, _float_inverse, _gamma, _midrad, enclose_fraction, inv_sqr,
                             mr_matmul, newton, s_add, s_div, s_down, s_fmax, s_fmin, s_inv_sqr, s_mid, s_midrad,
                             s_mr_radius, s_mul, s_sqr, s_sub, s_up, sq, stack, up)
from cdpr_algebra.report.jsonable import jsonable
from cdpr_algebra.model.pose import angles_from_matrix

__all__ = ["BPOptions", "IntervalSolution", "UndecidedBox", "IntervalSubproblem", "IntervalDGPResult",
           "solve_taut_set_interval", "interval_dgp", "build_model"]

_INF = np.inf
ROWS = {"poles": True, "axes": True, "gauss": True}  # statics row families (switches kept for experiments)
KERNELS = "compiled"  # "compiled" (numba, box by box) or "numpy" (vectorized reference) filter and Taylor operators
ORDER = 1  # compiled filter: 1 geometric sweeps then statics, 0 all contractors per sweep (the vectorized order)
GATE = True  # unicity test only where the second-order operator maps the box into its interior


@dataclass(frozen=True)
class BPOptions:
    """Tolerances of the branch and prune (widths relative to the robot size L; lam relative to Q / L)."""

    eps: float = 1e-9  # minimum width: boxes narrower than this and undecided are reported
    krawczyk_width: float = 0.05  # Krawczyk unicity test / contraction on boxes narrower than this
    newton_width: float = 0.02  # epsilon-inflation around a Newton point on boxes narrower than this
    batch: int = 4096  # boxes processed together
    max_sweeps: int = 3  # filter iterations per box (compiled, ORDER 1: of the geometric contractors)
    taylor_iterations: int = 2  # applications of the second-order operator per batch
    sweep_gain: float = 0.1  # ... repeated while some box shrinks by more than this fraction
    max_boxes: int = 20_000_000  # safety stop (then the remaining boxes are reported undecided)
    bisection: str = "widest"  # "widest" (seed 000); "smear": where the Krawczyk operator was formed, the variable
    # j maximizing max_i |I - C J(X)|_ij w_j / scale_i; "taylor": the largest share of the second-order part of the
    # width of T(X).  Measured on Test 1: the three give the same number of boxes within 2 %.


# ---------------------------------------------------------------------------------------------------------------
# results
@dataclass(frozen=True)
class IntervalSolution:
    """A proven equilibrium: unique solution of the equation set in ``box`` (core variables), enclosed in
    ``enclosure``; pose and tensions are floats inside the enclosure.  ``taut`` is 1-based."""

    taut: tuple
    position: np.ndarray
    rotation: np.ndarray
    tensions: np.ndarray  # n values, 0 for slack cables
    enclosure_width: float  # max width of the enclosure (model units)
    variables: tuple = ()
    enclosure_lo: np.ndarray = field(default_factory=lambda: np.zeros(0))
    enclosure_hi: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def angles(self) -> np.ndarray:
        return angles_from_matrix(self.rotation)

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "position": jsonable(self.position), "angles": jsonable(self.angles),
                "rotation": jsonable(self.rotation), "tensions": jsonable(self.tensions),
                "enclosure_width": self.enclosure_width, "variables": list(self.variables),
                "enclosure_lo": jsonable(self.enclosure_lo), "enclosure_hi": jsonable(self.enclosure_hi)}


@dataclass(frozen=True)
class UndecidedBox:
    """A box neither excluded nor proven to hold a unique admissible solution (``reason`` says why)."""

    taut: tuple
    reason: str
    variables: tuple
    lo: np.ndarray
    hi: np.ndarray
    position: np.ndarray | None = None  # a pose inside the box (platform origin), when it can be formed
    tensions: np.ndarray | None = None

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "reason": self.reason, "variables": list(self.variables),
                "lo": jsonable(self.lo), "hi": jsonable(self.hi),
                "position": None if self.position is None else jsonable(self.position),
                "tensions": None if self.tensions is None else jsonable(self.tensions)}


@dataclass(frozen=True)
class IntervalSubproblem:
    taut: tuple  # 1-based
    solutions: tuple  # IntervalSolution, admissible and proven
    undecided: tuple  # UndecidedBox
    boxes: int  # boxes processed
    bisections: int
    proven_inadmissible: int  # proven solutions of the equation set outside the admissible domain
    seconds: float
    method: str = ""
    skipped: str | None = None

    @property
    def admissible(self) -> int:
        return len(self.solutions)

    @property
    def complete(self) -> bool:
        return not self.undecided

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "admissible": self.admissible, "complete": self.complete,
                "solutions": [s.to_dict() for s in self.solutions],
                "undecided": [u.to_dict() for u in self.undecided], "boxes": self.boxes,
                "bisections": self.bisections, "proven_inadmissible": self.proven_inadmissible,
                "seconds": self.seconds, "method": self.method, "skipped": self.skipped}


@dataclass(frozen=True)
class IntervalDGPResult:
    subproblems: tuple
    seconds: float

    @property
    def solutions(self) -> tuple:
        return tuple(s for sub in self.subproblems for s in sub.solutions)

    @property
    def undecided(self) -> tuple:
        return tuple(u for sub in self.subproblems for u in sub.undecided)

    def by_m(self, m: int) -> tuple:
        return tuple(s for s in self.solutions if len(s.taut) == m)

    def to_dict(self) -> dict:
        return {"subproblems": [s.to_dict() for s in self.subproblems], "seconds": self.seconds,
                "admissible": len(self.solutions), "undecided": len(self.undecided)}


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


class SkipSubproblem(Exception):
    pass


# ---------------------------------------------------------------------------------------------------------------
class Model:
    """The equation set of one taut set (m >= 2) in a model frame, its domain and its filter data."""

    def __init__(self, robot, rho, cables):
        self.robot = robot
        self.rho = np.asarray(rho, dtype=float)
        self.cables = tuple(cables)
        self.m = len(cables)
        self.n = robot.n
        self.L = float(robot.size)
        self.Q = float(robot.load)
        self.lam_scale = self.Q / self.L
        bF = [_F(b) for b in robot.platform]
        gF = _F(robot.com)
        self.platF = bF + [gF]  # platform points: anchors 0..n-1, G = n
        self.G_id = self.n
        if self.m == 2:
            self._frame_planar()
        else:
            self._frame_world()
        self._layout()
        self._constants()
        self._filters()
        lo, hi = self.initial_box()
        c0 = 0.5 * (lo[0, self.core_cols] + hi[0, self.core_cols])
        c0[self.h - self.m:] = 0.0
        self.system = QuadraticSystem(self.residual, self.h, c0)  # every equation set is quadratic

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
                nrm = _fcross(_fsub(P[tri[1]], P[tri[0]]), _fsub(P[tri[2]], P[tri[0]]))
                a2 = _fdot(nrm, nrm)
                if a2 > 0 and (best is None or a2 > best):
                    best, refs = a2, list(tri)
            if refs is None:
                raise SkipSubproblem("the taut anchors are collinear: the platform turns freely about their line")
            nrm = _fcross(_fsub(P[refs[1]], P[refs[0]]), _fsub(P[refs[2]], P[refs[0]]))
            off = [k for k in taut if _fdot(nrm, _fsub(P[k], P[refs[0]])) != 0]
            if off:
                best4 = None
                for quad in itertools.combinations(taut, 4):
                    vol = abs(_fdet(_fsub(P[quad[1]], P[quad[0]]), _fsub(P[quad[2]], P[quad[0]]),
                                    _fsub(P[quad[3]], P[quad[0]])))
                    if vol > 0 and (best4 is None or vol > best4):
                        best4, refs = vol, list(quad)
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
        self.bisect_cols = np.array(ref_cols, dtype=int)
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
                w = _fsub(P[self.plat_ids[p]], P[self.plat_ids[q]])
                self.d2[(p, q)] = _fdot(w, w)
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
        P = self.platF
        for p, k in enumerate(self.plat_ids):
            blo, bhi = np.full(3, -_INF), np.full(3, _INF)
            for j in range(self.n):
                if k == j:
                    r = rho[j]
                else:
                    w = _fsub(P[k], P[j])
                    r = rho[j] + _Isqrt(_fdot(w, w))
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
        P = self.platF
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
                w = _fsub(P[k], P[j])
                d = _Isqrt(_fdot(w, w))
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
        m = self.m
        A = self.A
        f = self.f
        Ai = [Interval(A.lo[i], A.hi[i]) for i in self.cables]

        def unit(c):
            e = np.zeros(3)
            e[c] = 1.0
            return Interval(e, e)

        def force_row(u):
            kc = [Interval(-u.hi, -u.lo) for _ in range(m)]
            k0 = [_idot(a, u) for a in Ai]
            return (kc, k0, Interval(np.zeros(3), np.zeros(3)), _idot(f, u), [True] * m)

        def moment_row(Pt, u, inactive):
            kc, k0 = [], []
            for a in Ai:
                w = a - Pt
                wu = _icross(w, u)
                kc.append(wu)
                k0.append(-_idot(Pt, wu))
            fu = _icross(f, u)
            return (kc, k0, fu, -_idot(Pt, fu), [k not in inactive for k in range(m)])

        P0 = Interval.point(self.P0)
        if self.frame == "planar":
            base = [force_row(unit(0)), force_row(unit(2)), moment_row(P0, unit(1), ())]
            extra = [moment_row(Ai[k], unit(1), (k,)) for k in range(m)]
        else:
            base = [force_row(unit(c)) for c in range(3)] + [moment_row(P0, unit(c), ()) for c in range(3)]
            extra = []
            dd = np.asarray(self.robot.load_direction, dtype=float)
            if np.count_nonzero(dd) > 1:
                extra.append(force_row(Interval.point(dd)))
            if ROWS["poles"]:
                for k in range(m):
                    extra += [moment_row(Ai[k], unit(c), (k,)) for c in range(3)]
            for k1, k2 in (itertools.combinations(range(m), 2) if ROWS["axes"] else ()):
                axis = Ai[k2] - Ai[k1]
                inactive = tuple(k for k in range(m) if k in (k1, k2) or
                                 (np.array_equal(Ai[k].lo, Ai[k1].lo) or np.array_equal(Ai[k].lo, Ai[k2].lo)))
                extra.append(moment_row(Ai[k1], axis, inactive))
        allrows = base + extra
        self.nbase = len(base)
        R = len(allrows)
        kc_lo = np.zeros((R, m, 3))
        kc_hi = np.zeros((R, m, 3))
        k0_lo = np.zeros((R, m))
        k0_hi = np.zeros((R, m))
        hc_lo = np.zeros((R, 3))
        hc_hi = np.zeros((R, 3))
        h0_lo = np.zeros(R)
        h0_hi = np.zeros(R)
        act = np.zeros((R, m), bool)
        for r, (kc, k0, hc, h0, active) in enumerate(allrows):
            for k in range(m):
                if active[k]:
                    kc_lo[r, k], kc_hi[r, k] = kc[k].lo, kc[k].hi
                    k0_lo[r, k], k0_hi[r, k] = k0[k].lo, k0[k].hi
            hc_lo[r], hc_hi[r] = hc.lo, hc.hi
            h0_lo[r], h0_hi[r] = h0.lo, h0.hi
            act[r] = active
        self.st_kc = Interval(kc_lo, kc_hi)
        self.st_k0 = Interval(k0_lo, k0_hi)
        self.st_hc = Interval(hc_lo, hc_hi)
        self.st_h0 = Interval(h0_lo, h0_hi)
        self.st_act = act
        # [k0_i; kc_i^T] (4, R) per cable and [h0; hc^T] (4, R), midpoint-radius, for one-product evaluations
        self.st_Em, self.st_Er = [], []
        for k in range(m):
            Em, Er = _midrad(Interval(np.vstack([k0_lo[:, k][None], kc_lo[:, k, :].T]),
                                      np.vstack([k0_hi[:, k][None], kc_hi[:, k, :].T])))
            self.st_Em.append(np.ascontiguousarray(Em))
            self.st_Er.append(np.ascontiguousarray(Er))
        Hm, Hr = _midrad(Interval(np.vstack([h0_lo[None], hc_lo.T]), np.vstack([h0_hi[None], hc_hi.T])))
        self.st_Hm, self.st_Hr = np.ascontiguousarray(Hm), np.ascontiguousarray(Hr)
        # weights of the scaled pseudoinverse (force rows 1, moment rows 1 / L^2)
        if self.frame == "planar":
            self.st_weight = np.array([1.0, 1.0, 1.0 / self.L ** 2])
        else:
            self.st_weight = np.array([1.0] * 3 + [1.0 / self.L ** 2] * 3)

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
        kcm, kcr = _midrad(self.st_kc[:nb_])
        k0m, k0r = _midrad(self.st_k0[:nb_])
        hcm, hcr = _midrad(self.st_hc[:nb_])
        h0m, h0r = _midrad(self.st_h0[:nb_])
        g = float(_gamma(2 * nb_))

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
    e1 = e1 / np.linalg.norm(e1)
    e3 = np.cross(b - a, c - a)
    e3 = e3 / np.linalg.norm(e3)
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
    Bm, Br = _midrad(B)
    es = []
    for i in range(m):  # e_ri = k0_ri + kc_ri . B_i for all rows r: one product [1 | B_i] [k0_i; kc_i^T]
        ei = mr_matmul(np.hstack([ones, Bm[:, i]]), np.hstack([zeros, Br[:, i]]), model.st_Em[i], model.st_Er[i])
        es.append(ei)
    e = stack(es, axis=-1)  # (N, R, m)
    lb = Interval(lam.lo[:, None, :], lam.hi[:, None, :])
    t = lb * e
    t = Interval(np.where(act, t.lo, 0.0), np.where(act, t.hi, 0.0))
    Gm, Gr = _midrad(G)
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
    Bm = B.mid
    Jm = np.einsum("rmc,nmc->nrm", kc.mid, Bm) + k0.mid[None]  # (N, R0, m)
    K = _generalized_inverse(Jm, model.st_weight, model.frame == "world")
    ok = np.all(np.isfinite(K), axis=(1, 2))
    K = np.where(ok[:, None, None], K, 0.0)
    # C_ji = sum_r K_jr k0_ri + sum_c (sum_r K_jr kc_ric) B_ic ; rhs_j = -(sum_r K_jr h0_r + sum_c (..) G_c)
    R0 = nb
    k0m, k0r = _midrad(k0)  # (R0, m)
    kcm, kcr = _midrad(kc)  # (R0, m, 3)
    KK0 = mr_matmul(K, None, k0m, k0r)  # (N, m, m)
    KKc = mr_matmul(K, None, kcm.reshape(R0, m * 3), kcr.reshape(R0, m * 3))
    KKc = Interval(KKc.lo.reshape(N, m, m, 3), KKc.hi.reshape(N, m, m, 3))
    h0m, h0r = _midrad(h0)
    Kh0 = mr_matmul(K, None, h0m[:, None], h0r[:, None])
    Kh0 = Interval(Kh0.lo[..., 0], Kh0.hi[..., 0])  # (N, m)
    hcm, hcr = _midrad(hc)
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


def _cond(M):
    """Condition numbers of a batch of square matrices (inf where not finite)."""
    out = np.full(len(M), np.inf)
    fin = np.all(np.isfinite(M), axis=(1, 2))
    if fin.any():
        try:
            out[fin] = np.linalg.cond(M[fin])
        except np.linalg.LinAlgError:
            pass
    return out


def _generalized_inverse(Jm, weight, use_w: bool):
    """K (N, m, R0): eq. 37 K = (W^T J)^-1 W^T (W: J with force and moment halves swapped) where well
    conditioned, else the weighted pseudoinverse (J^T S J)^-1 J^T S, S = diag(weight)."""
    N, R0, m = Jm.shape
    K = np.full((N, m, R0), np.nan)
    with np.errstate(all="ignore"):
        todo = np.ones(N, bool)
        if use_w and R0 == 6:
            W = Jm[:, [3, 4, 5, 0, 1, 2], :]
            M = np.einsum("nrj,nri->nji", W, Jm)
            cond = _cond(M)
            good = np.isfinite(cond) & (cond < 1e8)
            if good.any():
                K[good] = np.linalg.solve(M[good], np.swapaxes(W[good], 1, 2))
            todo = ~good
        if todo.any():
            JS = np.swapaxes(Jm[todo], 1, 2) * weight[None, None, :]
            M = JS @ Jm[todo]
            cond = _cond(M)
            good = np.isfinite(cond) & (cond < 1e12)
            Kt = np.full((int(todo.sum()), m, R0), np.nan)
            if good.any():
                Kt[good] = np.linalg.solve(M[good], JS[good])
            K[todo] = Kt
    return K


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
    """Filter operator: all contractors, iterated; returns the surviving boxes.  ``KERNELS == "compiled"``
    (default): box by box in compiled code (:func:`_contract_kernel`, contractors in the order ``ORDER``);
    "numpy": the vectorized contractors (:func:`contract_vectorized`)."""
    if KERNELS == "compiled":
        lo = np.ascontiguousarray(lo, dtype=float)
        hi = np.ascontiguousarray(hi, dtype=float)
        rel, n_pt, use_n, sph, dst, chir, rows, gauss = model.compiled_data()
        alive = _contract_kernel(lo, hi, model.core_cols.astype(np.int64), model.core_scale, int(opts.max_sweeps),
                                 float(opts.sweep_gain), rel, n_pt, use_n, sph, dst, chir, rows, gauss,
                                 bool(ROWS["gauss"]), int(ORDER))
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
            if ROWS["gauss"]:
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
    g4 = _gamma(8)
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
        if not _float_inverse(M, Minv):  # overwrites M
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


@nb.njit(cache=True, error_model="numpy")
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


# ---------------------------------------------------------------------------------------------------------------
def _branch_and_prune(model: Model, opts: BPOptions):
    core = model.core_cols
    scale = model.core_scale
    h = model.h
    lo, hi = model.initial_box()
    stack_ = [(lo, hi)]
    proven = []  # (Xs_lo (h,), Xs_hi, E_lo, E_hi, id)
    regions_lo = np.zeros((0, h))
    regions_hi = np.zeros((0, h))
    sol_enclosures = []  # one per distinct solution: (E_lo, E_hi)
    undecided = []
    nboxes = 0
    nbis = 0
    pose_n = len(model.bisect_cols)

    def record(Xs_lo, Xs_hi, E_lo, E_hi):
        nonlocal regions_lo, regions_hi
        regions_lo = np.vstack([regions_lo, Xs_lo[None]])
        regions_hi = np.vstack([regions_hi, Xs_hi[None]])
        for k, (ol, oh, el, eh) in enumerate(proven):
            if (np.all(E_lo >= ol) and np.all(E_hi <= oh)) or (np.all(el >= Xs_lo) and np.all(eh <= Xs_hi)):
                proven.append((Xs_lo, Xs_hi, E_lo, E_hi))
                return False
        proven.append((Xs_lo, Xs_hi, E_lo, E_hi))
        sol_enclosures.append((E_lo, E_hi))
        return True

    def refine(X: Interval, y=None):
        """A few Krawczyk iterations on proven boxes X: tighter enclosures (intersected)."""
        E = X
        for _ in range(4):
            K, ok = model.system.krawczyk(E, y)
            E = E.intersect(K)
            y = None
        return E

    with np.errstate(all="ignore"):
        while stack_:
            parts_lo, parts_hi, total = [], [], 0
            while stack_ and total < opts.batch:
                l1, h1 = stack_.pop()
                take = opts.batch - total
                if len(l1) > take:
                    stack_.append((l1[take:], h1[take:]))
                    l1, h1 = l1[:take], h1[:take]
                parts_lo.append(l1)
                parts_hi.append(h1)
                total += len(l1)
            lo = np.concatenate(parts_lo) if len(parts_lo) > 1 else parts_lo[0]
            hi = np.concatenate(parts_hi) if len(parts_hi) > 1 else parts_hi[0]
            nboxes += len(lo)
            if nboxes > opts.max_boxes:
                for k in range(len(lo)):
                    undecided.append((lo[k, core], hi[k, core], "box budget exhausted"))
                for l2, h2 in stack_:
                    for k in range(len(l2)):
                        undecided.append((l2[k, core], h2[k, core], "box budget exhausted"))
                stack_ = []
                break
            lo, hi = contract(model, lo.copy(), hi.copy(), opts)
            if not len(lo):
                continue
            # inside a proven box: its only solution is already counted
            if len(regions_lo):
                X_lo, X_hi = lo[:, core], hi[:, core]
                inside = np.any(np.all((X_lo[:, None, :] >= regions_lo[None]) & (X_hi[:, None, :] <= regions_hi[None]),
                                       axis=2), axis=1)
                lo, hi = lo[~inside], hi[~inside]
                if not len(lo):
                    continue
            keep = np.ones(len(lo), bool)
            smear_pick = np.full(len(lo), -1)
            # exact second-order (Taylor) form of the quadratic system on every bounded box: exclusion, contraction
            w = (hi - lo)[:, core] / scale
            fin = np.flatnonzero(np.all(np.isfinite(w), axis=1))
            candidate = np.ones(len(lo), bool)  # boxes worth the unicity test
            if KERNELS == "compiled" and opts.bisection != "taylor" and len(fin):
                Xl, Xh, exT, inT = model.system.taylor_contract(lo[np.ix_(fin, core)], hi[np.ix_(fin, core)], scale,
                                                                opts.taylor_iterations, opts.sweep_gain)
                if GATE:
                    candidate[fin] = inT
                keep[fin[exT]] = False
                upd = fin[~exT]
                lo[np.ix_(upd, core)] = Xl[~exT]
                hi[np.ix_(upd, core)] = Xh[~exT]
                fin = fin[:0]
            for _ in range(opts.taylor_iterations):
                if not len(fin):
                    break
                X = Interval(lo[fin][:, core], hi[fin][:, core])
                if opts.bisection == "taylor":
                    T, okT, score = model.system.taylor(X, scale=scale)
                    smear_pick[fin] = np.where(okT, np.argmax(score, axis=1), -1)
                else:
                    T, okT = model.system.taylor(X)
                exT = okT & (np.any(T.lo > X.hi, axis=1) | np.any(T.hi < X.lo, axis=1))
                keep[fin[exT]] = False
                Xc = X.intersect(T)
                upd = okT & ~exT
                lo[np.ix_(fin[upd], core)] = Xc.lo[upd]
                hi[np.ix_(fin[upd], core)] = Xc.hi[upd]
                # iterate on the boxes that shrank by more than sweep_gain
                w0 = ((X.hi - X.lo) / scale).sum(axis=1)
                w1 = ((Xc.hi - Xc.lo) / scale).sum(axis=1)
                fin = fin[upd & (w1 < (1 - opts.sweep_gain) * w0)]
            w = (hi - lo)[:, core] / scale
            wmax = np.max(w, axis=1)
            small = np.flatnonzero(keep & candidate & np.isfinite(wmax) & (wmax < opts.krawczyk_width))
            if len(small):
                X = Interval(lo[small][:, core], hi[small][:, core])
                K, ok, Mabs = model.system.krawczyk(X, want_m=True)
                if opts.bisection == "smear":
                    score = np.max(Mabs * ((X.hi - X.lo)[:, None, :] / scale[None, :, None]), axis=1)
                    smear_pick[small] = np.where(ok, np.argmax(score, axis=1), -1)
                excl = np.any(K.lo > X.hi, axis=1) | np.any(K.hi < X.lo, axis=1)
                ver = ok & ~excl & np.all(K.subset_interior(X), axis=1)
                keep[small[excl]] = False
                for k in np.flatnonzero(ver):
                    E = refine(X[k:k + 1].intersect(K[k:k + 1]))
                    record(X.lo[k], X.hi[k], E.lo[0], E.hi[0])
                    keep[small[k]] = False
                rest = ok & ~excl & ~ver
                if rest.any():
                    Kc = X.intersect(K)
                    idx = small[rest]
                    lo[np.ix_(idx, core)] = Kc.lo[rest]
                    hi[np.ix_(idx, core)] = Kc.hi[rest]
                # epsilon-inflation around Newton points
                cand = small[rest & (wmax[small] < opts.newton_width)]
                if len(cand):
                    Xc = Interval(lo[cand][:, core], hi[cand][:, core])
                    xs, conv, _ = newton(model.residual_float, Xc.mid)
                    near = conv & np.all(np.abs(xs - Xc.mid) <= (Xc.hi - Xc.lo) + 1e-12 * scale, axis=1)
                    if near.any():
                        xs_n = xs[near]
                        rad = np.maximum(np.maximum(Xc.hi[near] - xs_n, xs_n - Xc.lo[near]) * 1.01,
                                         1e-12 * scale)
                        Xs = Interval(xs_n - rad, xs_n + rad)
                        K2, ok2 = model.system.krawczyk(Xs, xs_n)
                        ver2 = ok2 & np.all(K2.subset_interior(Xs), axis=1)
                        ids = cand[near]
                        for k in np.flatnonzero(ver2):
                            E = refine(Xs[k:k + 1].intersect(K2[k:k + 1]))
                            record(Xs.lo[k], Xs.hi[k], E.lo[0], E.hi[0])
                            keep[ids[k]] = False
            lo, hi, smear_pick = lo[keep], hi[keep], smear_pick[keep]
            if not len(lo):
                continue
            # bisection
            w = (hi - lo)[:, core] / scale
            wpose = w[:, :pose_n]
            wmax_pose = wpose.max(axis=1)
            wmax_all = w.max(axis=1)
            tiny = np.isfinite(wmax_all) & (wmax_all < opts.eps)
            for k in np.flatnonzero(tiny):
                undecided.append((lo[k, core], hi[k, core], f"minimum width {opts.eps:g} reached"))
            stuck = ~np.isfinite(wmax_all) & (wmax_pose < opts.eps)
            for k in np.flatnonzero(stuck):
                undecided.append((lo[k, core], hi[k, core], "tension unbounded at minimum pose width"))
            go = ~tiny & ~stuck
            lo, hi, w, wpose, wmax_pose = lo[go], hi[go], w[go], wpose[go], wmax_pose[go]
            smear_pick = smear_pick[go]
            if not len(lo):
                continue
            finite_w = np.where(np.isfinite(w), w, -1.0)
            pick = np.where(wmax_pose >= opts.eps, np.argmax(wpose, axis=1), np.argmax(finite_w, axis=1))
            sp = smear_pick >= 0
            if sp.any():
                ok_sp = sp & (w[np.arange(len(w)), np.maximum(smear_pick, 0)] > opts.eps)
                pick = np.where(ok_sp, smear_pick, pick)
            col = core[pick]
            rows = np.arange(len(lo))
            a, b = lo[rows, col], hi[rows, col]
            midv = 0.5 * a + 0.5 * b
            lo1, hi1 = lo.copy(), hi.copy()
            hi1[rows, col] = midv
            lo2, hi2 = lo.copy(), hi.copy()
            lo2[rows, col] = midv
            nbis += len(lo)
            stack_.append((np.vstack([lo1, lo2]), np.vstack([hi1, hi2])))
    return proven, sol_enclosures, undecided, nboxes, nbis


def solve_taut_set_interval(robot, rho, cables, options: BPOptions | None = None) -> IntervalSubproblem:
    """Every admissible equilibrium with the 0-based taut set ``cables`` (rho: all n lengths), by interval
    branch and prune; proven solutions and undecided boxes (see the module docstring)."""
    opts = options or BPOptions()
    t0 = time.perf_counter()
    cables = tuple(sorted(cables))
    taut1 = tuple(c + 1 for c in cables)
    rho = np.asarray(rho, dtype=float)
    if len(cables) == 1:
        return _solve_one_cable(robot, rho, cables[0], opts, t0)
    try:
        model = Model(robot, rho, cables)
    except SkipSubproblem as exc:
        return IntervalSubproblem(taut1, (), (), 0, 0, 0, time.perf_counter() - t0, "interval", str(exc))
    proven, sols, undecided_raw, nboxes, nbis = _branch_and_prune(model, opts)
    solutions, undecided = [], []
    inadmissible = 0
    for E_lo, E_hi in sols:
        E = Interval(E_lo[None], E_hi[None])
        status = model.classify(E)
        x = E.mid[0]
        p, R, tau = model.pose(x)
        if status == "admissible":
            solutions.append(IntervalSolution(taut1, p, R, tau, float(np.max(E_hi - E_lo)), model.variables,
                                              E_lo, E_hi))
        elif status == "inadmissible":
            inadmissible += 1
        else:
            undecided.append(UndecidedBox(taut1, "proven solution on the domain boundary: " + status, model.variables,
                                          E_lo, E_hi, p, tau))
    for blo, bhi, reason in undecided_raw:
        x = 0.5 * (blo + bhi)
        try:
            p, _, tau = model.pose(np.where(np.isfinite(x), x, 0.0))
        except Exception:  # degenerate box centre: no pose
            p, tau = None, None
        undecided.append(UndecidedBox(taut1, reason, model.variables, blo, bhi, p, tau))
    solutions.sort(key=lambda s: tuple(np.round(s.position, 9)))
    return IntervalSubproblem(taut1, tuple(solutions), tuple(undecided), nboxes, nbis, inadmissible,
                              time.perf_counter() - t0, f"interval B&P, {model.frame} frame, l = {model.l}")


def build_model(robot, rho, cables) -> Model:
    """The :class:`Model` of a taut set with m >= 2 cables (0-based), for inspection and tests."""
    return Model(robot, np.asarray(rho, dtype=float), tuple(sorted(cables)))


# ---------------------------------------------------------------------------------------------------------------
# m = 1
def _unit_frame(dF):
    """Interval orthonormal frame (X, Y, d^) with X x Y = d^ for the exact direction dF (Gram-Schmidt)."""
    dd = _fdot(dF, dF)
    k = int(np.argmin([abs(float(x)) for x in dF]))
    e = [Fraction(0)] * 3
    e[k] = Fraction(1)
    xF = [e[c] - _fdot(e, dF) * dF[c] / dd for c in range(3)]
    yF = _fcross(dF, xF)
    nd = _Isqrt(dd)
    nx = _Isqrt(_fdot(xF, xF))
    ny = _Isqrt(_fdot(yF, yF))
    return _Ivec(xF) / nx, _Ivec(yF) / ny, _Ivec(dF) / nd


def _solve_one_cable(robot, rho, i, opts, t0):
    """m = 1: the candidates with tension Q > 0 (G below / above B_i on the load line) and a search of the
    turning angle keeping every other cable slack (see the module docstring)."""
    taut1 = (i + 1,)
    n = robot.n
    bF = [_F(b) for b in robot.platform]
    gF = _F(robot.com)
    dF = _F(robot.load_direction)
    v3 = _fsub(gF, bF[i])
    if _fdot(v3, v3) == 0:
        return IntervalSubproblem(taut1, (), (), 0, 0, 0, time.perf_counter() - t0, "interval, m = 1",
                                  "G coincides with the anchor: every orientation is an equilibrium")
    X, Y, D = _unit_frame(dF)
    # platform frame e1', e2', e3' = (g' - b_i') / |..|
    e1p, e2p, e3p = _unit_frame(v3)
    A = Interval.point(np.asarray(robot.base, dtype=float))
    Ai = A[i]
    rho_i = Interval.point(rho[i])
    Bi = Ai + D * rho_i  # tension s1 Q with s1 = +1: B_i = A_i + rho_i d^
    solutions, undecided = [], []
    nboxes = 0
    nbis = 0
    inadm = 2  # the two candidates with B_i = A_i - rho_i d have tension -Q < 0
    for s2 in (+1, -1):
        alphas, betas, hs = [], [], []
        for j in range(n):
            if j == i:
                continue
            w3 = _Ivec(_fsub(bF[j], bF[i]))
            pj, qj, rj = _idot(w3, e1p), _idot(w3, e2p), _idot(w3, e3p)
            w = Bi - Interval(A.lo[j], A.hi[j]) + D * (rj * float(s2))
            wX, wY = _idot(w, X), _idot(w, Y)
            alphas.append((pj * wX + qj * wY * float(s2)) * 2.0)
            betas.append((pj * wY - qj * wX * float(s2)) * 2.0)
            hs.append(Interval.point(rho[j]).sqr() - w.sqr().sum(axis=-1) - pj.sqr() - qj.sqr())
        if alphas:
            al = stack(alphas)
            be = stack(betas)
            hh = stack(hs)
        status, t_found, boxes, bis, und = _one_cable_search(al if alphas else None, be if alphas else None,
                                                             hh if alphas else None, opts)
        nboxes += boxes
        nbis += bis
        # pose at the found angle (floats)
        Xm, Ym, Dm = X.mid, Y.mid, D.mid
        E1p, E2p, E3p = e1p.mid, e2p.mid, e3p.mid
        Bim = Bi.mid
        if status == "admissible" or und:
            chart, t = t_found if t_found is not None else und[0][:2]
            c, s = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
            if chart == 1:
                c, s = -c, -s
            E1 = c * Xm + s * Ym
            E2 = s2 * (-s * Xm + c * Ym)
            R = np.stack([E1, E2, s2 * Dm], axis=1) @ np.stack([E1p, E2p, E3p], axis=1).T
            p = Bim - R @ np.asarray(robot.platform[i], dtype=float)
            tau = np.zeros(n)
            tau[i] = robot.load
        if status == "admissible":
            solutions.append(IntervalSolution(taut1, p, R, tau, 0.0, ("t",), np.array([t]), np.array([t])))
        elif status == "inadmissible":
            inadm += 1
        else:
            for chart, tl, th in und:
                undecided.append(UndecidedBox(taut1, f"turning angle undecided ({'G below' if s2 > 0 else 'G above'} "
                                              f"the anchor, chart {chart})", ("t",), np.array([tl]), np.array([th]),
                                              p, tau))
    return IntervalSubproblem(taut1, tuple(solutions), tuple(undecided), nboxes, nbis, inadm,
                              time.perf_counter() - t0, "interval, m = 1 (turning angle search)")


def _one_cable_search(al, be, hh, opts):
    """Search t in [-1, 1] in two charts for alpha c + beta s <= h (all slack cables): c = +-(1 - t^2)/(1 + t^2),
    s = +-2t/(1 + t^2); multiplied by 1 + t^2 > 0: (-+alpha - h) t^2 +- 2 beta t + (+-alpha - h) <= 0."""
    if al is None:
        return "admissible", (0, 0.0), 1, 0, []
    boxes, bis = 0, 0
    und = []
    for chart, sg in ((0, 1.0), (1, -1.0)):
        a2 = (al * -sg) - hh  # coefficient of t^2
        a1 = be * (2.0 * sg)
        a0 = (al * sg) - hh
        tl = np.array([-1.0])
        th = np.array([1.0])
        while len(tl):
            boxes += len(tl)
            T = Interval(tl[:, None], th[:, None])
            g = a2 * T.sqr() + a1 * T + a0  # (N, ncons)
            inner = np.all(g.hi < 0, axis=1)
            if inner.any():
                k = int(np.flatnonzero(inner)[0])
                return "admissible", (chart, float(0.5 * (tl[k] + th[k]))), boxes, bis, []
            out = np.any(g.lo > 0, axis=1)
            keep = ~out
            tl, th = tl[keep], th[keep]
            tiny = (th - tl) < opts.eps
            for a, b in zip(tl[tiny], th[tiny]):
                und.append((chart, float(a), float(b)))
            tl, th = tl[~tiny], th[~tiny]
            mid = 0.5 * (tl + th)
            bis += len(tl)
            tl, th = np.concatenate([tl, mid]), np.concatenate([mid, th])
    if und:
        return "undecided", None, boxes, bis, und
    return "inadmissible", None, boxes, bis, []


# ---------------------------------------------------------------------------------------------------------------
def interval_dgp(robot, lengths=None, max_m: int = 6, progress=None, options: BPOptions | None = None,
                 sets=None) -> IntervalDGPResult:
    """Interval B&P over every set of m = 1 .. min(n, 6, max_m) taut cables (or the 0-based ``sets``)."""
    _, subs, seconds = solve_each_taut_set(robot, lengths, max_m, sets,
                                           lambda rho, c: solve_taut_set_interval(robot, rho, c, options), progress)
    return IntervalDGPResult(tuple(subs), seconds)
