"""Endgame, refinement and retries: from tracked paths to classified endpoints.

Pipeline (:func:`run_pipeline`, used by :func:`track_paths`), all vectorized across paths:

1. track t = 1 -> ``endgame_start`` (0.1). Paths that fail are retried with tighter double-precision
   settings, then (``detour_retry``) around the point where they failed on a half circle in the complex t-plane,
   kept only on a regular solution at t = te that no other path holds (:func:`.detours.phase1_detours`), then by
   a scalar mpmath tracker (``mp_dps`` digits) before being reported failed.
2. fast finish: track t = 0.1 -> 0 and refine by Newton on H(x, 0); an endpoint is ``success`` when
   Newton converges quadratically to full double precision (last update <= ``refine_tol`` (1 + |x|))
   and cond(dF/dx) <= ``singular_condition``.
3. the other paths go through a Cauchy endgame from t = 0.1: samples at t_k = 0.1 * ratio^k; the
   growth of log|x(t_k)| estimates the valuation v of the Puiseux expansion x ~ t^v; a stable
   v < 0 (or |x| > ``at_infinity_norm``) means ``at_infinity``. Otherwise the path is looped
   around t = 0 on the circle |t| = t_k (``samples_per_loop`` chords a loop) until it closes:
   the number of loops is the winding number c, and by Cauchy's integral formula (trapezoid
   rule in s = t^(1/c)) the mean of the c * samples_per_loop loop points estimates x(0). Two
   successive radii agreeing to ``cauchy_tol`` end the endgame; c > 1 or an ill-conditioned
   endpoint is ``singular``.
   With ``EndgameOptions.projective`` (homotopies that offer ``projective()``, e.g. parameter homotopies of
   systems whose equations all have degree 2) no norm decides anything: phase 2 switches a path whose norm
   passes ``switch_norm`` to a random affine chart of projective space (where every solution, however large,
   is an ordinary point), and the Cauchy endgame runs there.  Its limit Y* = (y0*, y*) is a finite solution
   x = y* / y0* when y0* is nonzero beyond the endgame's accuracy, and at infinity when y0* vanishes to that
   accuracy while the samples show y0(t) ~ t^v with v > 0 (``order`` v, winding number c); anything else is
   ``endgame_failed``.  Homotopies that are already projective (retries) are decided the same way, and so are the
   affine endgame's limits of a system that names its points at infinity (``system.infinity_coordinate(Y)``, a
   quantity of size ~1 that vanishes there, e.g. Study's N / |e|^2 for the DGP's re-track) in place of y0.
4. path jumping: distinct paths must not end at the same nonsingular point; duplicates are
   re-tracked from the start with tighter settings (then in mpmath). Endpoints still shared by
   several paths (within ``cluster_tol``) are singular: their multiplicity is the path count.

Everything is deterministic: randomness lives only in the start systems (seeded).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, asdict, replace

import numpy as np

from .clusters import duplicate_groups
from .detours import endgame_detours, phase1_detours
from .refinement import refine, relative_residual
from .results import (AT_INFINITY, DIVERGED, ENDGAME_FAILED, FAILURES, SINGULAR, STEP_TOO_SMALL, SUCCESS,
                      TOO_MANY_STEPS, PathResult, TrackResult)
from .tracker import TrackerOptions, _norm, track_segment

__all__ = ["EndgameOptions", "SolveOptions", "run_pipeline", "refine", "cauchy_endgame", "decide_in_chart",
           "block_at_infinity", "mp_track",
           "mp_path", "track_paths"]


@dataclass(frozen=True)
class EndgameOptions:
    """Endgame and refinement settings (defaults are the values used).

    * ``endgame_start`` [0.1]: t where the endgame zone begins;
    * ``sample_ratio`` [0.25]: t_{k+1} / t_k of the geometric samples;
    * ``max_samples`` [12]: geometric samples before giving up (t down to ~ 6e-9);
    * ``samples_per_loop`` [8], ``max_winding_number`` [16]: Cauchy loops;
    * ``loop_closure_tol`` [1e-6]: relative distance at which a loop is closed;
    * ``cauchy_tol`` [1e-9]: agreement of two successive Cauchy estimates;
    * ``at_infinity_norm`` [1e8]: |x| beyond this in the endgame is at infinity;
    * ``min_valuation`` [-0.02]: a stable valuation estimate below this is at infinity;
    * ``singular_condition`` [1e10]: cond(dF/dx) beyond this is singular;
    * ``refine_tol`` [1e-13]: last Newton update accepted as full double precision;
    * ``cauchy`` [True]: run the Cauchy endgame on paths that do not finish regular; False leaves them
      ``endgame_failed`` (undecided) at once, for solves that keep only regular endpoints (the generic instance
      of a many-target homotopy, whose total-degree paths mostly go to infinity);
    * ``settled_update`` [0, off]: a last Newton update (relative) at or below this also ends a path regular at
      the fast finish when the condition number is below ``singular_condition`` (for chart points with large
      coordinates, whose updates stall above ``refine_tol`` although Newton has converged);
    * ``ill_conditioned_limit`` [0, off]: a fast-finish endpoint with cond(dF/dx) above ``singular_condition`` and
      at most this also ends regular when Newton's last update reached ``refine_tol`` itself (not the floor that a
      large condition number allows) and, on a system with an ``infinity_coordinate``, that coordinate exceeds
      1e3 times the update: an isolated root that is only ill-conditioned, which the Cauchy loops would end
      ``singular`` with winding number 1 at the same point, for a caller that tests every endpoint again in its own
      coordinates (the DGP's Study run, :func:`_finish`);
    * ``finite_residual`` [1e-6]: a Cauchy estimate with a larger relative residual is not a finite
      endpoint (the loop mean of a diverging Puiseux series is finite): the path is at infinity; in a projective
      chart, where nothing diverges, such a mean means the loops enclosed branch points other than t = 0 (a cluster
      near it, on near-degenerate targets), and sampling goes on at smaller radii; a singular limit of the
      projective endgame must also solve the affine system to it, in affine coordinates (:func:`_unsolved_in_affine`),
      else it is ``endgame_failed``;
    * ``cluster_tol`` [1e-6]: finite endpoints of several paths closer than this (relative) are one
      singular solution whose multiplicity is the number of those paths;
    * ``projective`` [False]: decide finite / at infinity in a random projective chart (module doc, step 3);
      ``at_infinity_norm`` and ``min_valuation`` then play no part;
    * ``switch_norm`` [1e8]: with ``projective``, a path of the fast finish (phase 2) whose |x| passes this
      goes on in the chart (a change of coordinates, not a verdict: solutions of any norm are returned).  The
      affine tracker measures its steps relative to 1 + |x|, so it follows a large finite solution as well as
      the chart does and only the verdict "at infinity" needs the chart; switching early re-starts such paths
      there for nothing: on the DGP of seed 000 Test 2, whose complex solutions reach |x| ~ 1e4..1e5, a switch
      at 1e4 left 538 failed paths in 150 s (one thread), at 1e7 or 1e10 491 in 130 s (the two agree on every
      outcome); Test 3: 80 -> 74 failed, same time;
    * ``infinity_margin`` [10]: with ``projective``, y0* counts as zero when |y0*| <= margin x its accuracy
      (the Cauchy estimate's, at least 1e-14) and as nonzero beyond; ``min_order`` [1 / 32]: the smallest
      valuation v of y0(t) ~ t^v that shows y0 -> 0 (1 / (2 ``max_winding_number``)); ``min_order_winding``
      [0.5]: where the path's winding number c is known, v must also reach this / c.  Why: on a path of winding
      number c, y0 is a power series in t^(1 / c), so a y0 that vanishes at t = 0 does so with order k / c, k >= 1;
      a measured v well below 1 / c is a limit that has not settled, not a zero.  Measured (twenty-second session,
      seed 000 Test 3, taut set {1, 2, 5, 6}, the Study run in a chart c . e + d . g = 1 that was tried): three
      finite roots with |R| ~ 4e5 .. 9e5 (certified) were decided at infinity from v = 0.06 .. 0.11 with c = 1;
      every at-infinity verdict of seed 002's 8-cable robot (447 paths) has c = 2 and v c = 0.7 .. 1.3 or ~3;
    * ``infinity_verdicts`` [True]: False makes the affine Cauchy endgame decide no path at infinity (no norm or
      valuation test; a loop mean that does not solve H = 0 sends the path to smaller radii, as in a chart): for runs
      whose caller keeps only endpoints it can prove (the DGP's re-track in Study parameters, where a mean with a large
      residual at t ~ 1e-3 came from loops around a cluster of ill-conditioned roots, not from a diverging path);
    * ``infinity_samples`` [12]: in a chart, a path whose ``max_samples`` radii end without two agreeing Cauchy
      estimates, and whose best estimate has y0 within ``infinity_margin`` of its accuracy (it would be decided at
      infinity from an estimate that did not converge), is sampled at up to this many further radii (t down to
      ~4e-16) first.  Measured (twelfth session): robots built around an equilibrium with a wrench matrix within
      3e-5 of singular (tests/large_forces.py, m = 6, tensions 1e4 and 1e5 times the load) have a regular root with
      |lam| ~ 2e4 in a near-double pair across infinity; at t ~ 6e-9 its two paths still circle the pair's branch
      point, y0 falling like t^(1/2), and they were decided at infinity, the subproblem complete and the
      equilibrium missing; sampled further they are not decided (failed) and the subproblem is incomplete.
    """

    endgame_start: float = 0.1
    sample_ratio: float = 0.25
    max_samples: int = 12
    samples_per_loop: int = 8
    max_winding_number: int = 16
    loop_closure_tol: float = 1e-6
    cauchy_tol: float = 1e-9
    at_infinity_norm: float = 1e8
    min_valuation: float = -0.02
    singular_condition: float = 1e10
    refine_tol: float = 1e-13
    settled_update: float = 0.0
    ill_conditioned_limit: float = 0.0
    cauchy: bool = True
    finite_residual: float = 1e-6
    cluster_tol: float = 1e-6
    projective: bool = False
    switch_norm: float = 1e8
    infinity_margin: float = 10.0
    min_order: float = 1.0 / 32.0
    min_order_winding: float = 0.5
    infinity_samples: int = 12
    infinity_verdicts: bool = True

    def to_dict(self):
        return asdict(self)


@dataclass(frozen=True)
class SolveOptions:
    """All options of a run: ``tracker``, ``endgame``, and the retry policy.

    * ``retry_tight`` [True]: retry failed / duplicate paths in double precision with
      ``tracker.tightened()``;
    * ``retry_mpmath`` [True], ``mp_dps`` [30], ``max_mpmath_paths`` [16]: then retry them with the
      scalar mpmath tracker (at most that many paths, the rest are reported failed);
    * ``check_path_jumping`` [True]: re-track paths whose nonsingular endpoints coincide;
    * ``duplicate_tol`` [1e-8]: relative distance under which two endpoints coincide;
    * ``detour_retry`` [False]: track a path that failed in phase 1 (at t_f in (te, 1)) again around t_f on a
      half circle in the complex t-plane (radius at most ``detours.DETOUR_RADII``, above, then below, the smaller first),
      and keep the point it reaches at t = te only when Newton converges there quadratically and it is distinct
      from the points every other path reached (:func:`.detours.phase1_detours`).  Only for a call given every
      start solution of a homotopy whose system at t = te is generic (a parameter homotopy from a generic
      instance): it has exactly as many regular solutions as paths, so once every path holds a distinct regular one
      there, they are all of them, whichever path holds which (a detour may swap two paths' solutions).  With it,
      a path whose tracking failed later (in the endgame zone) is tracked around that point too, to t = 0, and
      kept only on a regular root that no other path ends on (:func:`.detours.endgame_detours`).
    """

    tracker: TrackerOptions = field(default_factory=TrackerOptions)
    endgame: EndgameOptions = field(default_factory=EndgameOptions)
    retry_tight: bool = True
    retry_mpmath: bool = True
    mp_dps: int = 30
    max_mpmath_paths: int = 16
    check_path_jumping: bool = True
    duplicate_tol: float = 1e-8
    detour_retry: bool = False

    def to_dict(self):
        return {"tracker": self.tracker.to_dict(), "endgame": self.endgame.to_dict(), "retry_tight": self.retry_tight,
                "retry_mpmath": self.retry_mpmath, "mp_dps": self.mp_dps, "max_mpmath_paths": self.max_mpmath_paths,
                "check_path_jumping": self.check_path_jumping, "duplicate_tol": self.duplicate_tol,
                "detour_retry": self.detour_retry}


# ---------------------------------------------------------------------------------------------
# refinement
# ---------------------------------------------------------------------------------------------
# ---------------------------------------------------------------------------------------------
# Cauchy endgame
# ---------------------------------------------------------------------------------------------
@dataclass
class EndgameResult:
    x: np.ndarray
    status: np.ndarray
    winding: np.ndarray
    accuracy: np.ndarray
    t: np.ndarray
    steps: np.ndarray
    xlast: np.ndarray = None  # the path at the last sample radius reached
    xprev: np.ndarray = None  # ... and at the radius before (NaN when there was none)
    tprev: np.ndarray = None  # that radius (NaN when there was none)


def _cauchy_loops(homotopy, x, r, o: EndgameOptions, tr: TrackerOptions):
    """Loop each path around t = 0 on |t| = r until it closes. Returns (estimate, c, ok, steps)."""
    N, n = x.shape
    M = o.samples_per_loop
    total = np.zeros((N, n), dtype=complex)
    cnt = np.zeros(N, dtype=int)
    wind = np.zeros(N, dtype=int)
    ok = np.zeros(N, dtype=bool)
    steps = np.zeros(N, dtype=int)
    xcur = x.copy()
    active = np.arange(N)
    loop_tr = replace(tr, max_step=1.0)
    hlast = np.full(N, 0.5)
    j = 0
    while active.size and j < M * o.max_winding_number:
        a = active
        ta = r[a] * np.exp(2j * np.pi * j / M)
        tb = r[a] * np.exp(2j * np.pi * (j + 1) / M)
        total[a] += xcur[a]
        cnt[a] += 1
        seg = track_segment(homotopy, xcur[a], ta, tb, loop_tr, h0=hlast[a])
        hlast[a] = seg.h
        steps[a] += seg.steps
        xcur[a] = seg.x
        fail = seg.status != SUCCESS
        j += 1
        keep = ~fail
        if j % M == 0:
            d = _norm(xcur[a] - x[a]) / (1 + _norm(x[a]))
            closed = keep & (d <= o.loop_closure_tol)
            ok[a[closed]] = True
            wind[a[closed]] = j // M
            keep &= ~closed
        active = a[keep]
    with np.errstate(all="ignore"):
        est = total / np.maximum(cnt, 1)[:, None]
    return est, wind, ok, steps


DECENT_ACCURACY = 1e-5  # a Cauchy estimate at least this accurate (relative) still decides a path out of samples


def cauchy_endgame(homotopy, x, t0: float, o: EndgameOptions, tr: TrackerOptions, chart: bool = False) -> EndgameResult:
    """Power-series valuation test for divergence plus Cauchy-integral endgame (see module doc).  With ``chart``
    (x in a projective chart) no path is declared at infinity here: every converged limit is returned as a finite
    chart point (``singular``, provisional) for :func:`decide_in_chart`, and a limit that does not solve H = 0
    is ``endgame_failed``; without ``o.infinity_verdicts`` likewise (no chart decision follows)."""
    verdicts = not chart and o.infinity_verdicts
    x = np.array(x, dtype=complex, copy=True)
    xprev = np.full_like(x, np.nan)
    N, n = x.shape
    r = np.full(N, float(t0))
    rprev = np.full(N, np.nan)
    status = np.full(N, "", dtype=object)
    xend = x.copy()
    wind = np.ones(N, dtype=int)
    acc = np.full(N, np.inf)
    steps = np.zeros(N, dtype=int)
    prev_est = np.full((N, n), np.nan + 0j)
    lognorm = [np.log(np.max(np.abs(x), axis=1) + 1e-300)]
    vals = []
    active = np.arange(N)
    parked = np.zeros(0, dtype=int)  # out of samples, not to be sampled further (see infinity_samples)
    for k in range(o.max_samples + (o.infinity_samples if chart else 0)):
        if k >= o.max_samples:  # only limits that would be decided at infinity from unconverged estimates go on
            deeper = _would_be_at_infinity(xend[active], acc[active], o)
            parked = np.concatenate([parked, active[~deeper]])
            active = active[deeper]
        if not active.size:
            break
        a = active
        seg = track_segment(homotopy, x[a], r[a], r[a] * o.sample_ratio, tr)
        steps[a] += seg.steps
        xprev[a] = x[a]
        rprev[a] = r[a]
        x[a] = seg.x
        r[a] = np.where(seg.status == SUCCESS, r[a] * o.sample_ratio, np.abs(seg.t))
        ln = np.full(N, np.nan)
        ln[a] = np.log(np.max(np.abs(x[a]), axis=1) + 1e-300)
        v = (ln - lognorm[-1]) / np.log(o.sample_ratio)
        lognorm.append(ln)
        vals.append(v)
        nx = np.max(np.abs(x[a]), axis=1)
        if not verdicts:  # a chart point does not go to infinity: only a failed segment stops the path
            infl = np.zeros(len(a), dtype=bool)
        else:
            infl = (nx > o.at_infinity_norm) | (seg.status == DIVERGED)
            if len(vals) >= 2:
                v1, v0 = vals[-1][a], vals[-2][a]
                stable = np.abs(v1 - v0) <= 0.1 * np.abs(v1) + 0.01
                infl |= (v1 < o.min_valuation) & (v0 < o.min_valuation) & stable & (np.exp(ln[a]) > 10.0)
        status[a[infl]] = AT_INFINITY
        xend[a[infl]] = x[a[infl]]
        acc[a[infl]] = np.nan
        infl_or_out = infl
        failed = (seg.status != SUCCESS) & ~infl_or_out
        status[a[failed]] = seg.status[failed]
        xend[a[failed]] = x[a[failed]]
        a = a[~infl_or_out & ~failed]
        if k == 0 or not a.size:
            active = a
            continue
        est, c, ok, st = _cauchy_loops(homotopy, x[a], r[a], o, tr)
        steps[a] += st
        diff = _norm(est - prev_est[a]) / (1 + _norm(est))
        prev_est[a] = np.where(ok[:, None], est, np.nan)
        conv = ok & (diff <= o.cauchy_tol)
        if conv.any():
            # a finite limit must solve H(x, 0) = 0; a stable mean with a large residual is the constant
            # term of a Puiseux series with negative exponents: the path diverges
            Hc = homotopy.evaluate(est[conv], np.zeros(int(conv.sum()), dtype=complex))
            resid = relative_residual(Hc, est[conv])
            ci = np.flatnonzero(conv)
            diverging = ci[~(resid <= o.finite_residual)]
            conv[diverging] = False
            ok[diverging] = False
            if not verdicts:
                # a chart point does not diverge: the loops enclosed branch points other than t = 0 (a cluster
                # near it), so the mean is not the limit yet; go on at smaller radii (failed if samples run out)
                prev_est[a[diverging]] = np.nan
            else:
                status[a[diverging]] = AT_INFINITY
                xend[a[diverging]] = x[a[diverging]]
                acc[a[diverging]] = np.nan
                wind[a[diverging]] = c[diverging]
        xend[a[conv]] = est[conv]
        wind[a[conv]] = c[conv]
        acc[a[conv]] = diff[conv]
        status[a[conv]] = SINGULAR  # provisional: finite endpoint, classified by the caller
        # keep the best estimate so far in case the samples run out
        better = ok & ~conv & (diff < acc[a])
        xend[a[better]] = est[better]
        acc[a[better]] = diff[better]
        wind[a[better]] = c[better]
        active = a[~conv & (status[a] == "")]
    # out of samples: finite if the best estimate is decent and solves H = 0, else the endgame did not converge
    active = np.concatenate([parked, active])
    decent = np.array([i for i in active if np.isfinite(acc[i]) and acc[i] <= DECENT_ACCURACY], dtype=int)
    solves = np.zeros(len(decent), dtype=bool)
    if decent.size:
        with np.errstate(all="ignore"):
            Hd = homotopy.evaluate(xend[decent], np.zeros(decent.size, dtype=complex))
            resid = relative_residual(Hd, xend[decent])
        solves = resid <= o.finite_residual
    status[decent[solves]] = SINGULAR
    for i in set(active.tolist()) - set(decent[solves].tolist()):
        status[i] = ENDGAME_FAILED
        xend[i] = x[i]
    return EndgameResult(x=xend, status=status, winding=wind, accuracy=acc, t=r.astype(complex), steps=steps,
                         xlast=x, xprev=xprev, tprev=rprev.astype(complex))


def _would_be_at_infinity(Y, accuracy, o: EndgameOptions) -> np.ndarray:
    """Rows Y of chart estimates (with their accuracies) that the out-of-samples rule of :func:`cauchy_endgame` would
    keep (``DECENT_ACCURACY``) and :func:`decide_in_chart` would then put at infinity by the size of y0 alone."""
    return (accuracy <= DECENT_ACCURACY) & decide_in_chart(Y, accuracy, o=o)[0]


def _vanishing_order_shown(v, winding, o: EndgameOptions):
    """Whether samples falling like t^v show a coordinate that vanishes at the limit: v >= ``min_order``, and
    v c >= ``min_order_winding`` where the winding numbers c are given (a power series in t^(1 / c) vanishes with
    order k / c, k >= 1)."""
    v = np.asarray(v, dtype=float)
    with np.errstate(all="ignore"):
        shown = np.isfinite(v) & (v >= o.min_order)
        if winding is not None:
            shown &= v * np.asarray(winding, dtype=float) >= o.min_order_winding
    return shown


def decide_in_chart(Y, accuracy, ylast=None, yprev=None, o: EndgameOptions = EndgameOptions(), coordinate=None,
                    winding=None):
    """Finite or at infinity, for limits Y* (rows) of paths in a projective chart, from the homogenizing
    coordinate y0 (column 0).  Returns (at_infinity, undecided, order): ``at_infinity`` where |y0*| <=
    ``infinity_margin`` x the accuracy (relative ``accuracy``, at least 1e-14, times |Y*|) and the samples at the
    last two radii of the endgame (``ylast``, ``yprev``: None for endpoints that Newton refined, whose accuracy
    is then full precision) show y0(t) ~ t^v with v >= ``min_order``, and v >= ``min_order_winding`` / c where the
    paths' winding numbers c are given (``winding``; ``order`` = v); ``undecided`` where y0*
    vanishes to accuracy but the samples do not show y0 -> 0; finite elsewhere (y0* nonzero beyond its
    accuracy: x = y* / y0*, whatever its size).  ``coordinate(Y) -> (N,)``: instead of y0 / |Y|, another
    quantity of size ~1 whose vanishing means infinity (:func:`_finish`: a system's ``infinity_coordinate``)."""
    Y = np.atleast_2d(Y)
    acc = o.infinity_margin * np.maximum(np.where(np.isfinite(accuracy), accuracy, np.inf), 1e-14)
    order = np.full(len(Y), np.nan)
    if coordinate is None:  # y0, measured against |Y*| (a chart point's size)
        coordinate, scale = (lambda Z: Z[:, 0]), np.max(np.abs(Y), axis=1)
    else:
        scale = 1.0
    zero = np.abs(coordinate(Y)) <= acc * scale
    if ylast is None:
        return zero, np.zeros(len(Y), dtype=bool), order
    with np.errstate(all="ignore"):
        v = np.log(np.abs(coordinate(ylast)) / np.abs(coordinate(yprev))) / np.log(o.sample_ratio)
    shown = _vanishing_order_shown(v, winding, o)
    order[zero & shown] = v[zero & shown]
    return zero & shown, zero & ~shown, order


def block_at_infinity(loop, loop_prev, cols, winding: int, o: EndgameOptions = EndgameOptions(),
                      seed: int = 0) -> tuple[bool, bool, float]:
    """(at infinity, finite, order v): whether the affine coordinates ``cols`` of a path are unbounded at its limit
    (or bounded: ``finite``; neither where undecided), from the
    samples (rows) of its last two Cauchy loops: ``loop`` at the radius r, ``loop_prev`` at r / ``sample_ratio``, c =
    ``winding`` turns each (:class:`.precise_endgame.PreciseLimit`).

    The block's homogenizing coordinate on a random chart, h = 1 / (a0 + a . y) (a random complex, fixed by
    ``seed``), is analytic in s = t^(1/c) at a limit where the block diverges, and vanishes there; its value at
    s = 0 is the mean of its samples on the loop (Cauchy's integral formula: the endgame's trapezoid rule in s).
    At infinity when |mean h| <= ``infinity_margin`` x ``cauchy_tol`` (at least 1e-14) x the mean of |h| on the
    loop (the accuracy to which the endgame's estimates agree), |mean h| <= ``infinity_margin`` x its change from
    the previous loop (or is at the samples' rounding, 1e-14 of |h|), and the loops show |h| ~ t^v with v >=
    ``min_order`` and v c >= ``min_order_winding`` (as :func:`decide_in_chart` decides y0).  A finite limit y*
    has mean h ~ h(0) = 1 / (a0 + a . y*), as large as the samples themselves: never at infinity, however large
    y*.  ``finite`` where |mean h| is not zero so and |h| is steady between the two radii (|v| < ``min_order``: a
    block still growing there has not reached the regime where its Puiseux series converges on the loop, h may have
    poles inside it and its mean is no value of h).

    Why.  The loop means of a diverging block converge too, to the constant term of its Puiseux series (the
    negative powers of s average to zero over a loop), so agreeing Cauchy estimates do not show a finite limit.
    Measured (twenty-eighth session): 3-cable robots whose platform triangle is similar to the base triangle (an
    equilateral base and platform) have Study paths whose translation and tensions grow like 1 / t (winding number
    2, h falling with v = 1.00 .. 1.09) while the rotation converges (isotropic translations); their double-double
    loops agreed to 1e-10 .. 1e-12 on the constant term, N / |e|^2 ~ 0.2 showed no rotation at infinity, and the
    paths were left failed."""
    if loop is None or loop_prev is None:
        return False, False, float("nan")
    rng = np.random.default_rng(seed)
    Y, P = np.asarray(loop)[:, cols], np.asarray(loop_prev)[:, cols]
    a = (rng.normal(size=Y.shape[1] + 1) + 1j * rng.normal(size=Y.shape[1] + 1)) / np.sqrt(2 * (Y.shape[1] + 1))
    with np.errstate(all="ignore"):
        h, hp = 1.0 / (a[0] + Y @ a[1:]), 1.0 / (a[0] + P @ a[1:])
        if not (np.all(np.isfinite(h)) and np.all(np.isfinite(hp))):
            return False, False, float("nan")
        hm = h.mean()
        size, mean = np.mean(np.abs(h)), abs(hm)
        # small against the loop's values, and no steady value: a mean that the previous loop repeats is h(0) != 0
        # (measured: a root with tensions 1e5 times the load, reached by two paths circling a near-double root,
        # |mean h| = 2.07e-11 on both loops, 1.3e-9 of |h|), unless it is at the rounding of the samples
        zero = mean <= o.infinity_margin * max(o.cauchy_tol, 1e-14) * size and (
            mean <= o.infinity_margin * abs(hm - hp.mean()) or mean <= 1e-14 * size)
        v = float(np.log(size / np.mean(np.abs(hp))) / np.log(o.sample_ratio))
    shown = bool(_vanishing_order_shown(v, [winding], o))
    steady = np.isfinite(v) and abs(v) < o.min_order  # h(t) ~ h(0): the loops are in the limit's neighbourhood
    return bool(zero and shown), bool(not zero and steady), (v if zero and shown else float("nan"))


# ---------------------------------------------------------------------------------------------
# high-precision retry
# ---------------------------------------------------------------------------------------------
def mp_track(homotopy, x0, t_a, t_b, dps: int = 30, options: TrackerOptions | None = None):
    """Scalar tracker in mpmath (``dps`` digits): the same RK4 + 2 Newton scheme as :func:`track_segment`.

    Returns (x as complex128 array, status, steps). Slow (pure Python): only for the few retried paths.
    """
    import mpmath

    o = options or TrackerOptions()
    with mpmath.workdps(dps):
        x = mpmath.matrix([mpmath.mpc(complex(v)) for v in x0])
        ta, tb = mpmath.mpc(complex(t_a)), mpmath.mpc(complex(t_b))
        dt = tb - ta
        s, h = mpmath.mpf(0), mpmath.mpf(o.initial_step)
        rejected = False
        safety = o.step_safety
        tol_p = mpmath.mpf(o.predictor_tol)
        tol_c = mpmath.mpf(10) ** (-(dps - 8))
        steps = 0

        def nrm(v):
            return mpmath.sqrt(sum(abs(c) ** 2 for c in v))

        def f(xx, ss):
            _, Hx, Ht = homotopy.mp_evaluate_all(xx, ta + ss * dt)
            return mpmath.lu_solve(Hx, -Ht * dt)

        while s < 1:
            if steps >= o.max_steps * 4:
                return np.array([complex(c) for c in x]), TOO_MANY_STEPS, steps
            steps += 1
            hh = min(h, 1 - s)
            try:
                k1 = f(x, s)
                k2 = f(x + k1 * (hh / 2), s + hh / 2)
                k3 = f(x + k2 * (hh / 2), s + hh / 2)
                k4 = f(x + k3 * hh, s + hh)
                xp = x + (k1 + 2 * k2 + 2 * k3 + k4) * (hh / 6)
                tn = ta + (s + hh) * dt
                d = []
                xc = xp
                for _ in range(3):
                    H, Hx, _ = homotopy.mp_evaluate_all(xc, tn)
                    dd = mpmath.lu_solve(Hx, -H)
                    xc = xc + dd
                    d.append(nrm(dd) / (1 + nrm(xc)))
                okk = d[0] <= tol_p and d[2] <= max(tol_c, d[1] * o.max_contraction) and d[1] <= o.max_contraction * d[0] + tol_c
            except (ZeroDivisionError, ValueError):
                okk, d = False, [mpmath.inf]
            if okk:
                x, s = xc, s + hh
                ratio = safety * (tol_p / max(d[0], mpmath.mpf(10) ** -300)) ** 0.2
                h = min(hh * min(max(ratio, 1), 1 if rejected else 2.5), o.max_step)
            else:
                h = hh * (0.25 if not mpmath.isfinite(d[0]) else min(max(safety * (tol_p / d[0]) ** 0.2, 0.1), 0.5))
                if h < o.min_step * 1e-3:
                    return np.array([complex(c) for c in x]), STEP_TOO_SMALL, steps
            rejected = not okk
            if nrm(x) > o.max_norm:
                return np.array([complex(c) for c in x]), DIVERGED, steps
        return np.array([complex(c) for c in x]), SUCCESS, steps


# ---------------------------------------------------------------------------------------------
# the pipeline
# ---------------------------------------------------------------------------------------------
def _track_to_endgame(homotopy, X0, idx, opts: SolveOptions, te, tr: TrackerOptions):
    """Phase 1 for the paths ``idx``: t = 1 -> te, with retries. Returns (x, status, steps, retried, h, t_fail) with h
    the last step length in t (absolute; NaN for retried paths) and t_fail the t where a failed path stopped."""
    seg = track_segment(homotopy, X0[idx], 1.0, te, tr)
    x, status, steps = seg.x, seg.status.copy(), seg.steps.copy()
    t_fail = seg.t.copy()
    h = seg.h * abs(1.0 - te)
    retried = np.full(len(idx), "", dtype=object)
    bad = np.flatnonzero(status != SUCCESS)
    if bad.size and opts.retry_tight:
        seg2 = track_segment(homotopy, X0[idx[bad]], 1.0, te, tr.tightened())
        x[bad], status[bad] = seg2.x, seg2.status
        t_fail[bad] = seg2.t
        steps[bad] += seg2.steps
        retried[bad] = "tight"
        h[bad] = np.nan
        bad = bad[seg2.status != SUCCESS]
    if bad.size and opts.detour_retry and len(idx) == len(X0):
        phase1_detours(homotopy, X0[idx], x, status, steps, retried, h, t_fail, te, tr, opts)
        bad = bad[status[bad] != SUCCESS]
    if bad.size and opts.retry_mpmath and hasattr(homotopy, "mp_evaluate_all"):
        for i in bad[: opts.max_mpmath_paths]:
            xm, st, ns = mp_track(homotopy, X0[idx[i]], 1.0, te, opts.mp_dps, tr)
            steps[i] += ns
            retried[i] = "mpmath"
            if st == SUCCESS:
                x[i], status[i] = xm, SUCCESS
                h[i] = np.nan
    return x, status, steps, retried, h, t_fail


def _finish(homotopy, x_te, opts: SolveOptions, tr: TrackerOptions, h=None):
    """Phases 2-3 for paths at t = te (``h``: step lengths in t that phase 1 ended with, to start phase 2 with;
    NaN or None: the tracker's initial step).  Returns per-path arrays (x, status, winding, accuracy, t, steps,
    order, (prev, prev_t)): ``prev`` the sample before the last of the paths decided at infinity after Cauchy
    samples (in the coordinates of x), ``prev_t`` its radius (NaN elsewhere).  A homotopy with a ``chart`` (it is
    itself projective) has its endpoints decided by :func:`decide_in_chart`; with ``endgame.projective`` an affine
    homotopy that offers ``projective()`` hands the paths that do not finish regular (or pass ``switch_norm``) to
    its projective twin for the endgame, and gets them back in affine coordinates (module doc)."""
    eo = opts.endgame
    te = eo.endgame_start
    N = len(x_te)
    chart = getattr(homotopy, "chart", None)
    proj = None
    if chart is None and eo.projective and hasattr(homotopy, "projective"):
        from .projective import to_chart

        proj = homotopy.projective()
    out_x = x_te.copy()
    status = np.full(N, "", dtype=object)
    wind = np.ones(N, dtype=int)
    acc = np.full(N, np.inf)
    tfin = np.zeros(N, dtype=complex)
    order = np.full(N, np.nan)
    prev = np.full((N, x_te.shape[1]), np.nan, dtype=complex)  # at-infinity paths: the sample before the last
    prev_t = np.full(N, np.nan, dtype=complex)  # ... and its radius
    h0 = None
    if h is not None:
        h0 = np.where(np.isfinite(h), np.asarray(h, dtype=float) / abs(te), tr.initial_step)
    fast = tr if proj is None else replace(tr, max_norm=min(tr.max_norm, eo.switch_norm))
    seg = track_segment(homotopy, x_te, te, 0.0, fast, h0=h0)
    steps = seg.steps.copy()
    reached = seg.status == SUCCESS
    xr, upd, res, cond, quad = refine(homotopy, seg.x[reached], 0.0, tol=eo.refine_tol)
    good = (quad | (upd <= eo.settled_update)) & (cond <= eo.singular_condition)
    if eo.ill_conditioned_limit > eo.singular_condition:
        good |= ill_conditioned_roots(homotopy, xr, upd, cond, eo)
    gi = np.flatnonzero(reached)[good]
    out_x[gi] = xr[good]
    status[gi] = SUCCESS
    acc[gi] = upd[good]
    if chart is not None and gi.size:  # a regular point of the chart may lie at infinity (y0 = 0)
        inf, _, _ = decide_in_chart(out_x[gi], acc[gi], o=eo)
        status[gi[inf]] = AT_INFINITY
    if chart is not None:
        _stopped_before_first_sample(seg, np.arange(N), status, out_x, tfin, te, eo)
    elif proj is None:  # affine: its tracking failures only (a divergence is the endgame's to decide)
        _stopped_before_first_sample(seg, np.arange(N), status, out_x, tfin, te, eo, reasons=(STEP_TOO_SMALL,
                                                                                              TOO_MANY_STEPS))
    rest = np.flatnonzero(status == "")
    if rest.size and proj is not None:
        # first the plain track to t = 0 in the chart: a regular point there with y0 nonzero beyond its accuracy
        # is a regular finite solution, however large (no Cauchy loops); the others go to the endgame below
        Yc = to_chart(x_te[rest], proj.chart)
        seg_c = track_segment(proj, Yc, te, 0.0, tr)
        steps[rest] += seg_c.steps
        ok_c = np.flatnonzero(seg_c.status == SUCCESS)
        if ok_c.size:
            Yr, upd, _, cond_c, quad_c = refine(proj, seg_c.x[ok_c], 0.0, tol=eo.refine_tol)
            reg = quad_c & (cond_c <= eo.singular_condition)
            inf_c, _, _ = decide_in_chart(Yr, upd, o=eo)
            fin_c = reg & ~inf_c
            gi = rest[ok_c[fin_c]]
            with np.errstate(all="ignore"):
                out_x[gi] = Yr[fin_c][:, 1:] / Yr[fin_c][:, :1]
            status[gi] = SUCCESS
            acc[gi] = upd[fin_c]
        _stopped_before_first_sample(seg_c, rest, status, out_x, tfin, te, eo, lambda Y: Y[:, 1:] / Y[:, :1])
        rest = np.flatnonzero(status == "")
    if rest.size and not eo.cauchy:  # no endgame asked for: these paths stay undecided (failed)
        status[rest] = ENDGAME_FAILED
        tfin[rest] = 0.0
        rest = rest[:0]
    if rest.size:
        in_chart = chart is not None or proj is not None
        hend = proj if proj is not None else homotopy
        if proj is not None:
            Y0 = to_chart(x_te[rest], proj.chart)
        else:
            Y0 = x_te[rest]
        eg = cauchy_endgame(hend, Y0, te, eo, tr, chart=in_chart)
        steps[rest] += eg.steps
        st, Y, a_ = eg.status.copy(), eg.x, eg.accuracy.copy()
        fin = np.flatnonzero(st == SINGULAR)
        # a system of other coordinates may say where its points are at infinity (Study's N = e . e = 0)
        vanish = None if in_chart else _infinity_coordinate(homotopy)
        if (in_chart or vanish is not None) and fin.size:
            inf, undecided, ordv = decide_in_chart(Y[fin], a_[fin], eg.xlast[fin], eg.xprev[fin], eo, vanish,
                                                   eg.winding[fin])
            st[fin[inf]] = AT_INFINITY
            st[fin[undecided]] = ENDGAME_FAILED
            order[rest[fin]] = ordv
            fin = np.flatnonzero(st == SINGULAR)
        if fin.size:
            # finite endpoints: winding number 1 and quadratic Newton -> nonsingular after all
            Yr, upd_, res_, cond_, quad_ = refine(hend, Y[fin], 0.0, tol=eo.refine_tol)
            ns = (eg.winding[fin] == 1) & quad_ & (cond_ <= eo.singular_condition)
            Y[fin[ns]] = Yr[ns]
            a_[fin[ns]] = upd_[ns]
            st[fin[ns]] = SUCCESS
        before = eg.xprev
        if proj is not None:  # back to affine coordinates (a path at infinity keeps its last sample)
            last = np.where((st == AT_INFINITY)[:, None] | np.isin(st, FAILURES)[:, None], eg.xlast, Y)
            with np.errstate(all="ignore"):
                Y = last[:, 1:] / last[:, :1]
                before = before[:, 1:] / before[:, :1]
            st[_unsolved_in_affine(homotopy, Y, st, eo)] = ENDGAME_FAILED
        if vanish is not None:  # a limit on the coordinate at infinity: the path keeps its last sample (not the
            Y = np.where((st == AT_INFINITY)[:, None], eg.xlast, Y)  # estimate there), the pair of ``before``
        inf_ = st == AT_INFINITY
        prev[rest[inf_]] = before[inf_]
        prev_t[rest[inf_]] = eg.tprev[inf_]
        out_x[rest] = Y
        status[rest] = st
        wind[rest] = eg.winding
        acc[rest] = a_
        tfin[rest] = np.where(np.isin(st, (SINGULAR, SUCCESS)), 0.0, eg.t)
    return out_x, status, wind, acc, tfin, steps, order, (prev, prev_t)


def ill_conditioned_roots(homotopy, X, upd, cond, eo: EndgameOptions) -> np.ndarray:
    """The points X (Newton-refined fast-finish endpoints, last updates ``upd``, condition numbers ``cond``) that
    ``eo.ill_conditioned_limit`` lets end regular: singular_condition < cond <= that limit, the last update at
    ``refine_tol`` (Newton converged to full precision, which it does not near a singular root) and, where the
    system names an ``infinity_coordinate``, that coordinate above 1e3 times the update (not a point at infinity).
    Measured (thirty-first session) on seed 000 Test 2 (coplanar platform), Study runs of taut set {1, 2, 5, 6} (its
    two routes): 23 such endpoints each (cond 2e10 .. 2e12, N / |e|^2 ~ 1e-6 .. 1e-5, updates <= 1e-13); their
    Cauchy loops (800 steps a path) ended each at the same point (to 1e-11 .. 3e-7), singular with winding number 1."""
    ok = (cond > eo.singular_condition) & (cond <= eo.ill_conditioned_limit) & (upd <= eo.refine_tol)
    vanish = _infinity_coordinate(homotopy)
    if vanish is not None and ok.any():
        ok[ok] = off_infinity(vanish, X[ok], upd[ok])
    return ok


def _infinity_coordinate(homotopy):
    """The system's ``infinity_coordinate`` (a function of the points whose vanishing means infinity), or None."""
    return getattr(getattr(homotopy, "system", None), "infinity_coordinate", None)


def off_infinity(coordinate, X, update) -> np.ndarray:
    """(N,) bool: the points X (rows) whose coordinate at infinity ``coordinate(X)`` (e.g. Study's N / |e|^2) exceeds
    1e3 times their last Newton update ``update``: a point, not one at infinity, to that accuracy."""
    with np.errstate(all="ignore"):
        return np.abs(coordinate(X)) > 1e3 * np.maximum(update, 1e-16)


def _unsolved_in_affine(homotopy, X, status, eo: EndgameOptions) -> np.ndarray:
    """The ``singular`` limits of chart paths, mapped to the affine points X, that do not solve the affine system at
    t = 0 to ``finite_residual`` (relative to 1 + |x|, as every reported endpoint): a chart residual is relative to
    the chart point, so a limit far from the origin (|y0| small) passes it with an affine residual up to
    finite_residual / |y0|.  Measured (twelfth session): on robots built around an equilibrium with a nearly
    singular wrench matrix (tests/large_forces.py, m = 3 and 6), Cauchy means of two paths circling a near-double
    root had chart residuals ~2e-7 and affine ones 5e-4 .. 9e-2 and were reported singular while the equilibrium
    (a regular root, confirmed by 60-digit Newton) was missing; the singular endpoints of seed 000 Tests 2 and 3
    have affine residuals <= 3e-6.  Such a limit is not decided: ``endgame_failed``."""
    idx = np.flatnonzero(status == SINGULAR)
    bad = np.zeros(len(X), dtype=bool)
    if not idx.size:
        return bad
    with np.errstate(all="ignore"):
        H = homotopy.evaluate(X[idx], np.zeros(idx.size, dtype=complex))
        res = relative_residual(H, X[idx])
    bad[idx] = ~(res <= eo.finite_residual)
    return bad


def _stopped_before_first_sample(seg, idx, status, out_x, tfin, te, eo: EndgameOptions, to_out=lambda Y: Y,
                                 reasons=None):
    """Paths ``idx`` of a chart track from t = te towards 0 (``seg``) that failed (for one of ``reasons``, None: any)
    before reaching the endgame's first sample radius te * ``sample_ratio``: the endgame would track the same path
    from the same point through the same stretch with the same step control (its first segment, te -> te * ratio),
    where double precision has already run out (condition 1e10-1e11 near the singular sets at infinity, measured on
    seed 000 Test 3), so they fail here, with the track's reason, at the t where it stopped, instead of failing a
    second time in the endgame (measured, twentieth session, on the affine Study tracks of seed 000 Tests 2 and 3
    and seed 002's 8-cable robot: all 19 such endgames stopped at the same t, 3000 steps each).  Sets their
    ``status``, ``out_x`` (the last point, ``to_out`` of the chart point: the identity, or the map back to affine
    coordinates) and ``tfin``."""
    failed = seg.status != SUCCESS if reasons is None else np.isin(seg.status, reasons)
    early = np.flatnonzero(failed & (np.abs(seg.t) > te * eo.sample_ratio) & (status[idx] == ""))
    ii = idx[early]
    status[ii] = seg.status[early]
    with np.errstate(all="ignore"):
        out_x[ii] = to_out(seg.x[early])
    tfin[ii] = seg.t[early]


def _records(homotopy, idx, x, status, wind, acc, tfin, steps, retried, order=None, prev=None):
    """PathResults of the paths ``idx`` from the per-path arrays of :func:`_run` (``prev``: the (samples, radii) of
    :func:`_finish`, kept for paths at infinity)."""
    n = len(idx)
    res = np.full(n, np.inf)
    cond = np.full(n, np.inf)
    ok = np.flatnonzero(np.all(np.isfinite(x), axis=1))  # a path at infinity may have no finite affine point
    if ok.size:
        H, Hx = homotopy.evaluate_and_jacobian(x[ok], np.zeros(ok.size, dtype=complex))
        with np.errstate(all="ignore"):
            res[ok] = relative_residual(H, x[ok])
            try:
                cond[ok] = np.linalg.cond(Hx)
            except np.linalg.LinAlgError:
                pass
    res = np.where(np.isfinite(res), res, np.inf)
    cond = np.where(np.isfinite(cond), cond, np.inf)
    order = np.full(n, np.nan) if order is None else order
    out = []
    for k, i in enumerate(idx):
        # a path at infinity keeps the sample before its last one (PathResult.valuation)
        before = prev is not None and status[k] == AT_INFINITY and bool(np.all(np.isfinite(prev[0][k]))
                                                                         and np.isfinite(prev[1][k]))
        out.append(PathResult(index=int(i), status=str(status[k]), endpoint=x[k], t=complex(tfin[k]),
                              residual=float(res[k]), condition=float(cond[k]), accuracy=float(acc[k]),
                              steps=int(steps[k]), winding_number=int(wind[k]), retried=str(retried[k]),
                              order=float(order[k]), previous=prev[0][k] if before else None,
                              previous_t=complex(prev[1][k]) if before else None))
    return out


def _run(homotopy, X0, idx, opts: SolveOptions, tr: TrackerOptions):
    te = opts.endgame.endgame_start
    x, st1, steps, retried, h, t_fail = _track_to_endgame(homotopy, X0, idx, opts, te, tr)
    n = len(idx)
    status = st1.copy()
    wind = np.ones(n, dtype=int)
    acc = np.full(n, np.inf)
    tfin = np.where(st1 == SUCCESS, te, t_fail).astype(complex)
    order = np.full(n, np.nan)
    prev = (np.full(x.shape, np.nan, dtype=complex), np.full(n, np.nan, dtype=complex))
    ok = np.flatnonzero(st1 == SUCCESS)
    if ok.size:
        xo, so, wo, ao, to, sto, oo, po = _finish(homotopy, x[ok], opts, tr, h[ok])
        x[ok], status[ok], wind[ok], acc[ok], tfin[ok], order[ok] = xo, so, wo, ao, to, oo
        prev[0][ok], prev[1][ok] = po
        steps[ok] += sto
    if opts.detour_retry and len(idx) == len(X0):  # failures after phase 1: around them to t = 0
        inf = None if getattr(homotopy, "chart", None) is None else (
            lambda Y, a: decide_in_chart(Y, a, o=opts.endgame)[0])
        endgame_detours(homotopy, X0[idx], x, status, steps, retried, acc, tfin, tr, opts, inf)
    return _records(homotopy, idx, x, status, wind, acc, tfin, steps, retried, order, prev)


def mp_path(homotopy, x0, index, opts: SolveOptions, tr: TrackerOptions, steps: int = 0):
    """Path ``index`` from x0 tracked in arbitrary precision (:func:`mp_track`, ``opts.mp_dps`` digits) up to the
    endgame zone, then phases 2-3 in double precision: a PathResult with ``retried="mpmath"`` (``steps`` added to
    its count), or None when the arbitrary-precision tracking fails too."""
    xm, st, ns = mp_track(homotopy, x0, 1.0, opts.endgame.endgame_start, opts.mp_dps, tr)
    if st != SUCCESS:
        return None
    xo, so, wo, ao, to, sto, oo, po = _finish(homotopy, xm[None, :], opts, tr)
    return _records(homotopy, np.array([index]), xo, so, wo, ao, to, sto + ns + steps,
                    np.array(["mpmath"], dtype=object), oo, po)[0]


def run_pipeline(homotopy, X0, opts: SolveOptions):
    """All phases for all start points; returns a list of :class:`PathResult` in start order."""
    N = len(X0)
    idx = np.arange(N)
    paths = _run(homotopy, X0, idx, opts, opts.tracker)
    if opts.check_path_jumping and (opts.retry_tight or opts.retry_mpmath):
        succ = [p for p in paths if p.status == SUCCESS]
        if succ:
            pts = np.array([p.endpoint for p in succ])
            groups = duplicate_groups(pts, opts.duplicate_tol)
            redo = sorted({succ[i].index for g in groups for i in g})
            if redo:
                tight = opts.tracker.tightened()
                new = _run(homotopy, X0, np.array(redo), replace(opts, retry_tight=False), tight)
                for p in new:
                    paths[p.index] = replace(p, retried="tight")
                # still duplicated: try mpmath on the later members of each group
                succ = [p for p in paths if p.status == SUCCESS]
                pts = np.array([p.endpoint for p in succ])
                groups = duplicate_groups(pts, opts.duplicate_tol)
                if groups and opts.retry_mpmath and hasattr(homotopy, "mp_evaluate_all"):
                    redo = sorted({succ[i].index for g in groups for i in g[1:]})[: opts.max_mpmath_paths]
                    for i in redo:
                        rec = mp_path(homotopy, X0[i], i, opts, tight)
                        if rec is not None:
                            paths[i] = rec
    # distinct paths of a homotopy that is regular for t in (0, 1] cannot meet at a nonsingular
    # point (implicit function theorem): an endpoint shared by several paths is singular
    fin = [p for p in paths if p.status in (SUCCESS, SINGULAR)]
    if len(fin) > 1:
        pts = np.array([p.endpoint for p in fin])
        for g in duplicate_groups(pts, opts.endgame.cluster_tol):
            for i in g:
                if fin[i].status == SUCCESS:
                    paths[fin[i].index] = replace(fin[i], status=SINGULAR)
    return paths


def track_paths(homotopy, start_solutions, options=None, seed=None):
    """Track every start solution of ``homotopy`` to t = 0, run the endgame and classify each path.

    ``options`` is a :class:`SolveOptions` (or None for its defaults). Returns a
    :class:`.results.TrackResult`. See :func:`run_pipeline` for the pipeline.
    """
    options = options or SolveOptions()
    t0 = time.perf_counter()
    paths = run_pipeline(homotopy, np.asarray(start_solutions, dtype=complex), options)
    return TrackResult(paths=tuple(paths), seconds=time.perf_counter() - t0, seed=seed, options=options.to_dict())
