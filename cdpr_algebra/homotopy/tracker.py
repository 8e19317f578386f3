"""Path tracker: RK4 predictor, Newton corrector, adaptive step size, all paths vectorized.

Method. Along a straight segment t(s) = t_a + s (t_b - t_a), s in [0, 1] (t complex, per path),
a path solves H(x(s), t(s)) = 0, hence dx/ds = -H_x^{-1} H_t (t_b - t_a). One step of size h:

1. predictor: classical Runge-Kutta (RK4) on that ODE (4 batched linear solves);
2. corrector: Newton iterations at t(s + h), updates d1, d2 (and more, step 3);
3. accept when the predictor error |d1| <= ``predictor_tol`` (1 + |x|) and Newton contracts
   (|d2| <= ``max_contraction`` |d1|, or both are below 1e-9 / 1e-10: round-off level) and |d2| <= ``corrector_tol`` (1 + |x|);
   or after more Newton updates (at most ``max_updates`` in all), when Newton contracted but |d2| was above
   ``corrector_tol``: accept at the first update below it, each update having contracted again (a predictor
   error up to ``predictor_tol`` need not be squared below ``corrector_tol`` in two updates; where Newton
   contracts only linearly, as on an ill-conditioned stretch, it takes more); or when an update shows
   stagnation at the round-off floor (<= ``noise_tol``);
4. next step h * clip(``step_safety`` (predictor_tol / |d1|)^(1/5), ...): the RK4 local error is O(h^5), so
   this keeps the predictor error near the tolerance; rejected steps shrink by at least 2, the step after a
   rejection does not grow, and an accepted step whose error was near the tolerance shrinks the next one (by up
   to ``step_safety``: where the error grows along the path, as towards a near-singular point, the next step
   would otherwise be rejected).  (Measured on 3 DGP subproblems of seed 000 Test 3, 1860 paths: safety 0.9 and
   growth right after a rejection rejected 28 % of the steps; 0.8 and no growth 13 %, 16 % fewer steps in all,
   the same endpoints.  Twelfth session, compiled tracker, whole DGPs: letting accepted steps shrink took 16 % ->
   11 % of phase-1 steps rejected on Test 3, and all steps from 667k to 639k (Test 2 877k -> 807k, seed 002's
   8-cable robot 5.15M -> 4.72M), with the same outcome counts on Test 3 and fewer failed paths on the 8-cable
   robot, 565 -> 556.)

Homotopies that offer compiled evaluators (``compiled_kernels()``) are tracked by the same step compiled
with numba, one path at a time (:mod:`.compiled`; it also reuses LU factors: a chord second Newton update and
the Newton factors for the next k1, so its error estimates and step counts differ slightly from these).  Otherwise all active paths step together: every stage is one call of the compiled evaluator on
(npaths, n) points and one ``np.linalg.solve`` on (npaths, n, n). Paths that reach s = 1 or fail
leave the active set. Failures: ``step_too_small`` (h < ``min_step``), ``too_many_steps``,
``diverged`` (|x| > ``max_norm`` or a non-finite value).

:func:`.endgame.track_paths` runs the whole pipeline (tracking, endgame, refinement, retries, path-jumping check).
"""

from __future__ import annotations

from dataclasses import dataclass, asdict, replace

import numpy as np

from .results import DIVERGED, RUNNING, STEP_TOO_SMALL, SUCCESS, TOO_MANY_STEPS, SegmentResult

__all__ = ["TrackerOptions", "track_segment"]

@dataclass(frozen=True)
class TrackerOptions:
    """Step control of :func:`track_segment` (defaults in brackets are the values used).

    * ``initial_step`` [0.05]: first step as a fraction of the segment;
    * ``max_step`` [0.25]: largest step as a fraction of the segment;
    * ``min_step`` [1e-13]: below this the path fails with ``step_too_small``;
    * ``max_steps`` [3000]: accepted + rejected steps per path and segment;
    * ``predictor_tol`` [1e-5]: accepted size of the first Newton update, relative to 1 + |x|;
    * ``corrector_tol`` [1e-8]: accepted size of the last Newton update, relative to 1 + |x|;
    * ``max_contraction`` [0.2]: |d2| / |d1| must not exceed this (Newton is converging);
    * ``max_norm`` [1e10]: |x| beyond this is ``diverged``;
    * ``noise_tol`` [1e-6]: a step whose Newton updates stagnate (an update <= 2 x the one before) below this
      is accepted as limited by round-off (ill-conditioned stretch of a path);
    * ``step_safety`` [0.8]: safety factor of the step-size rule (step 4 of the module doc);
    * ``extended_residual`` [False]: with the compiled tracker and a system that offers a double-double residual
      (``compiled_residual_dd``), a path whose Newton corrections stall although its predictor was good takes
      its residuals in double-double from then on (:func:`.compiled.track_kernel`); the numpy tracker has none;
    * ``max_updates`` [5]: most Newton updates of one step (step 3 of the module doc; 2 at least).  Measured,
      seed 000 Test 2 (coplanar platform, paths that pass near Study's exceptional set): 3 updates rejected a
      quarter of the steps of its slowest paths, whose Newton updates contract by 0.03 .. 0.2 (chord updates,
      :mod:`.compiled`), and the finish t = 0.1 -> 0 took 249,923 steps; 5 updates: 221,993, every account and
      admissible pose the same; 8: no fewer than 5.
    """

    initial_step: float = 0.05
    max_step: float = 0.25
    min_step: float = 1e-13
    max_steps: int = 3000
    predictor_tol: float = 1e-5
    corrector_tol: float = 1e-8
    max_contraction: float = 0.2
    max_norm: float = 1e10
    noise_tol: float = 1e-6
    step_safety: float = 0.8
    extended_residual: bool = False
    max_updates: int = 5

    def tightened(self, factor: float = 100.0) -> "TrackerOptions":
        """Stricter settings for re-tracking suspicious paths."""
        return replace(self, predictor_tol=self.predictor_tol / factor, max_step=self.max_step / 5,
                       initial_step=self.initial_step / 5, max_contraction=min(self.max_contraction, 0.1),
                       max_steps=self.max_steps * 4, min_step=self.min_step / 10)

    def to_dict(self) -> dict:
        return asdict(self)


def _norm(v):
    return np.sqrt(np.einsum("ij,ij->i", v.real, v.real) + np.einsum("ij,ij->i", v.imag, v.imag))


def _solve(A, b):
    """Batched solve A x = b for b of shape (N, n); singular matrices give non-finite rows."""
    try:
        return np.linalg.solve(A, b[..., None])[..., 0]
    except np.linalg.LinAlgError:
        out = np.full(b.shape, np.nan + 0j)
        for i in range(len(A)):
            try:
                out[i] = np.linalg.solve(A[i], b[i])
            except np.linalg.LinAlgError:
                pass
        return out


def track_segment(homotopy, x0, t_a, t_b, options: TrackerOptions | None = None, h0=None) -> SegmentResult:
    """Track every path from t_a to t_b (arrays of shape (N,) or scalars), vectorized across paths."""
    o = options or TrackerOptions()
    kernels = getattr(homotopy, "compiled_kernels", None)
    if kernels is not None and kernels() is not None:  # the same step, compiled (numba), one path at a time
        from .compiled import track_segment_compiled

        return track_segment_compiled(homotopy, x0, t_a, t_b, o, h0)
    x = np.array(x0, dtype=complex, copy=True)
    N, n = x.shape
    t_a = np.broadcast_to(np.asarray(t_a, dtype=complex), (N,)).copy()
    t_b = np.broadcast_to(np.asarray(t_b, dtype=complex), (N,)).copy()
    dt = t_b - t_a
    s = np.zeros(N)
    h = np.full(N, o.initial_step) if h0 is None else np.clip(np.broadcast_to(h0, (N,)).astype(float), o.min_step, o.max_step)
    steps = np.zeros(N, dtype=int)
    rejected = np.zeros(N, dtype=bool)  # the last step of the path was rejected
    status = np.full(N, RUNNING, dtype=object)
    active = np.flatnonzero(dt != 0)
    status[dt == 0] = SUCCESS
    ev = homotopy.evaluate_all
    evj = homotopy.evaluate_and_jacobian

    def f(xx, ss, a):
        _, Hx, Ht = ev(xx, t_a[a] + ss * dt[a])
        return _solve(Hx, -Ht * dt[a][:, None])

    while active.size:
        a = active
        xa, sa = x[a], s[a]
        ha = np.minimum(h[a], 1.0 - sa)
        hc = ha[:, None]
        k1 = f(xa, sa, a)
        k2 = f(xa + 0.5 * hc * k1, sa + 0.5 * ha, a)
        k3 = f(xa + 0.5 * hc * k2, sa + 0.5 * ha, a)
        k4 = f(xa + hc * k3, sa + ha, a)
        xp = xa + (hc / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        sn = sa + ha
        tn = t_a[a] + sn * dt[a]
        H, Hx = evj(xp, tn)
        d1 = _solve(Hx, -H)
        x1 = xp + d1
        H, Hx = evj(x1, tn)
        d2 = _solve(Hx, -H)
        x2 = x1 + d2
        scale = 1.0 + _norm(x2)
        e1 = _norm(d1) / scale
        e2 = _norm(d2) / scale
        finite = np.isfinite(e1) & np.isfinite(e2)
        # contraction is only measurable above round-off: a predictor within 1e-9 needs no such test
        contracting = (e2 <= o.max_contraction * e1) | ((e1 <= 1e-9) & (e2 <= 1e-10))
        ok = finite & (e1 <= o.predictor_tol) & contracting & (e2 <= o.corrector_tol)
        # more Newton iterations (up to max_updates in all): (a) Newton contracts but |d2| is above corrector_tol (a
        # large predictor error still inside the convergence region): accept at the first update <= corrector_tol,
        # each having contracted again; (b) the round-off floor: on an ill-conditioned stretch Newton stagnates at
        # cond * eps instead of contracting; an update that does not move away either (<= 2 x the one before, both
        # <= noise_tol) shows that the point is as accurate as double precision allows: accept it
        cand = np.flatnonzero(finite & ~ok & (e1 <= o.predictor_tol) & (contracting | (e2 <= o.noise_tol)))
        eprev, more = e2[cand], contracting[cand]
        for _ in range(o.max_updates - 2):
            if not cand.size:
                break
            H3, Hx3 = evj(x2[cand], tn[cand])
            d3 = _solve(Hx3, -H3)
            e3 = _norm(d3) / scale[cand]
            fin3 = np.isfinite(e3)
            more = more & (e3 <= o.max_contraction * eprev)
            good = fin3 & ((more & (e3 <= o.corrector_tol))
                           | ((eprev <= o.noise_tol) & (e3 <= 2.0 * eprev) & (e3 <= o.noise_tol)))
            ok[cand[good]] = True
            x2[cand] += np.where(fin3[:, None], d3, 0)
            go = fin3 & ~good & more
            cand, eprev, more = cand[go], e3[go], more[go]
        steps[a] += 1
        # accepted
        acc = a[ok]
        x[acc] = x2[ok]
        s[acc] = np.where(sn[ok] >= 1.0 - 1e-15, 1.0, sn[ok])
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = o.step_safety * (o.predictor_tol / np.maximum(e1, 1e-300)) ** 0.2
        grow = np.minimum(ratio, np.where(rejected[a], 1.0, 2.5))  # >= step_safety: e1 <= predictor_tol
        shrink = np.where(finite, np.clip(ratio, 0.1, 0.5), 0.25)
        hn = np.where(ok, np.minimum(ha * grow, o.max_step), ha * shrink)
        # keep a grown step after a final short step to the end
        h[a] = np.where(ok & (ha < h[a]), np.maximum(h[a], hn), hn)
        rejected[a] = ~ok
        done = s[a] >= 1.0
        status[a[done]] = SUCCESS
        big = ok & (scale > o.max_norm)
        status[a[big & ~done]] = DIVERGED
        small = ~ok & (h[a] < o.min_step)
        status[a[small]] = STEP_TOO_SMALL
        many = (status[a] == RUNNING) & (steps[a] >= o.max_steps)
        status[a[many]] = TOO_MANY_STEPS
        active = a[status[a] == RUNNING]
    t = t_a + s * dt
    return SegmentResult(x=x, s=s, t=t, status=status, steps=steps, h=h)
