"""Branch and prune over one taut set and over every taut set (Berti, Merlet and Carricato 2016, Sec. 4): bisection,
the second-order evaluation operator, the Krawczyk unicity test, undecided boxes reported, never dropped."""

from __future__ import annotations

import time
import numpy as np
from cdpr_algebra.model.taut_sets import solve_each_taut_set
from cdpr_algebra.intervals.arithmetic import Interval
from cdpr_algebra.intervals.operators import newton
from .contractors import contract
from .model import Model, SkipSubproblem
from .one_cable import _solve_one_cable
from .results import BPOptions, IntervalDGPResult, IntervalSolution, IntervalSubproblem, UndecidedBox


# ---------------------------------------------------------------------------------------------------------------
UNDECIDED_KEPT = 1000  # undecided boxes kept (with their reasons) per subproblem; the others are only counted


class _Undecided(list):
    """The undecided boxes of one search, (lo, hi, reason): the first ``UNDECIDED_KEPT`` kept, every one counted
    per reason (``reasons``).  Why: near a nearly degenerate taut set millions of boxes reach the minimum width
    (seed 002's 8-cable robot, taut set {2, 4, 6, 8}: 458,000 of 2 million boxes, 1 GiB; `cdpr dgp --settle` with its
    default budget of 20 million boxes grew to 10 GiB); a list of them says no more than their count and reasons."""

    def __init__(self):
        super().__init__()
        self.reasons: dict = {}

    def add(self, lo, hi, reason: str) -> None:
        self.reasons[reason] = self.reasons.get(reason, 0) + 1
        if len(self) < UNDECIDED_KEPT:
            self.append((lo.copy(), hi.copy(), reason))


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
    undecided = _Undecided()
    nboxes = 0
    nbis = 0
    pose_n = len(model.bisect_cols)  # the bisected columns lead the core ones
    pose_all = h - model.m  # every pose column of the core

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
                    undecided.add(lo[k, core], hi[k, core], "box budget exhausted")
                for l2, h2 in stack_:
                    for k in range(len(l2)):
                        undecided.add(l2[k, core], h2[k, core], "box budget exhausted")
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
            if opts.taylor_iterations and opts.kernels in ("compiled", "codac") and opts.bisection != "taylor" \
                    and len(fin):
                Xl, Xh, exT, inT = model.system.taylor_contract(lo[np.ix_(fin, core)], hi[np.ix_(fin, core)], scale,
                                                                opts.taylor_iterations, opts.sweep_gain)
                if opts.unicity_gate:
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
                undecided.add(lo[k, core], hi[k, core], f"minimum width {opts.eps:g} reached")
            stuck = ~np.isfinite(wmax_all) & (w[:, :pose_all].max(axis=1) < opts.eps)
            for k in np.flatnonzero(stuck):
                undecided.add(lo[k, core], hi[k, core], "tension unbounded at minimum pose width")
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
        model = Model(robot, rho, cables, opts.statics_rows)
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
    reasons = dict(undecided_raw.reasons)
    for u in undecided[:len(undecided) - len(undecided_raw)]:  # proven solutions on the boundary
        reasons[u.reason] = reasons.get(u.reason, 0) + 1
    return IntervalSubproblem(taut1, tuple(solutions), tuple(undecided), nboxes, nbis, inadmissible,
                              time.perf_counter() - t0, f"interval B&P, {model.frame} frame, l = {model.l}",
                              undecided_reasons=reasons)


def excluded_by_filter(robot, rho, cables, max_boxes: int = 64) -> int | None:
    """A short branch and prune of the taut set ``cables`` (0-based, m >= 2; rho: all n lengths) with the filter
    operator and bisection only (no second-order operator, no proofs): the number of boxes when it excluded every
    box -- a proof that the set holds no admissible equilibrium (real, tensions >= 0, the other cables no longer
    than their lengths) -- or None when boxes remain after ``max_boxes`` (or the set is skipped)."""
    opts = BPOptions(max_boxes=max_boxes, taylor_iterations=0, krawczyk_width=0.0, newton_width=0.0)
    try:
        model = Model(robot, np.asarray(rho, dtype=float), tuple(sorted(cables)), opts.statics_rows)
    except SkipSubproblem:
        return None
    proven, _, undecided, nboxes, _ = _branch_and_prune(model, opts)
    return None if proven or undecided else nboxes


def build_model(robot, rho, cables, options: BPOptions | None = None) -> Model:
    """The :class:`Model` of a taut set with m >= 2 cables (0-based), for inspection and tests."""
    return Model(robot, np.asarray(rho, dtype=float), tuple(sorted(cables)), (options or BPOptions()).statics_rows)


# ---------------------------------------------------------------------------------------------------------------
def interval_dgp(robot, lengths=None, max_m: int = 6, progress=None, options: BPOptions | None = None,
                 sets=None) -> IntervalDGPResult:
    """Interval B&P over every set of m = 1 .. min(n, 6, max_m) taut cables (or the 0-based ``sets``)."""
    _, subs, seconds = solve_each_taut_set(robot, lengths, max_m, sets,
                                           lambda rho, c: solve_taut_set_interval(robot, rho, c, options), progress)
    return IntervalDGPResult(tuple(subs), seconds)
