"""DGP paths tracked in Study parameters (:mod:`cdpr_algebra.model.study_equations`): every path first
(:func:`track_study_first`, the DGP's default since the nineteenth session), or the failed paths of a run in
(p, u, v, w, lam) again (:func:`retrack_failed_in_study`, which the first also uses on placeholders of all paths).

:func:`track_study_first` tracks every path in Study parameters, with detours around phase-1 failures (the run
holds every path, so a detour that reaches a point no other path holds at t = 0.1 is that path's), keeps what the
rules below keep, and tracks the rest in the taut system (``TAUT_FALLBACK``); a taut endpoint on a point that a
Study path holds sends that Study path to the taut system too (one of the two jumped), and only a clash that
remains makes the taut path ``path_jumping``.  Why first: on seed 000 Tests 2 and 3 and seed 002's 8-cable robot
the paths that (p, u, v, w, lam) loses were re-tracked here anyway, after a long crawl and projective retries
(Test 2's taut set {1, 2, 5, 6}: 33 of 216 paths, 44,000 of its 79,000 steps in the taut system), and the detours
of a run of every path settle some that a re-track of the failed paths alone cannot (Test 3: 5 -> 1 failed paths;
module doc of :mod:`.solve`).

The DGP tracked in (p, u, v, w, lam) (:mod:`cdpr_algebra.model.taut_equations`) first until then.  Its paths that pass near the isotropic
infinity of the complex rotation group meet condition numbers of 1e10-1e11 there, and double precision loses them
(``step_too_small``; README "What the failed paths are").  In Euler parameters on a chart, e . c = 1, those rotations
are ordinary points with small N = e . e.  :func:`retrack_failed_in_study` takes each failed path's start point to
Study coordinates and tracks it again along the same parameter path (the same segment, or the same gamma: the
homotopy is drawn from the same seed), so it follows the same solution curve in other coordinates and ends on that
path's own endpoint.  A path whose new run ends regular, or ``singular`` by its condition number alone (a limit
on one sheet at a pose, :func:`_limit_of_one_sheet`), is kept when its endpoint, mapped back, converges under
Newton's method in the taut system to ``RESIDUAL_TOL`` and is distinct from every other path's regular endpoint
(``clusters.coincides_with_any`` at the endgame's cluster tolerance, the detour retry's test; a coincidence means a jump
of one of them: the path stays failed, nothing is merged); a path whose new run ends on the quadric N = 0 is at
infinity (below); every other path keeps its outcome.  A kept endpoint is then certified like any other (the DGP's
endpoint certificates, in the taut system).

Measured (fifteenth session, Berti et al. 2016 Test 3, taut set {2, 3, 4, 5}, 13 failed paths in (p, u, v, w, lam)):
with the generic engine tracking all 216 paths in Study parameters 213 end regular; the 10 former failures among
them end at complex poses with |R| = 1.6e3 .. 2.1e4 (N / |e|^2 = 6e-4 .. 5e-5), the 203 others on the same points
as before (relative differences <= 4e-9).

Sixteenth session, Test 2's taut set {1, 2, 4, 6} (39 failed paths): the Study endgame ended 35 of them ``singular``
and 4 ``at_infinity``.  The singular ones have winding number 1, Cauchy accuracies 1e-10 .. 1e-16, residuals ~1e-17
and N / |e|^2 ~ 1e-6 .. 1e-5 (poses with |R| ~ 1e5, |lam| ~ 1e4); only their condition numbers (1e12 .. 1e16) made
them singular.  Newton's method at 60 digits converges quadratically from each (residual 1e-56): they are regular
roots, distinct, ill-conditioned, and Newton in the taut system with double-double residuals settles them; the ball
Krawczyk test proves every one.  The 4 ``at_infinity`` came from the affine endgame's rule that a loop mean with a
large residual (1e-4 at t = 1.6e-3) means divergence; here the loops enclosed other branch points of that cluster,
and sampled further (``EndgameOptions.infinity_verdicts`` off: a re-track keeps only what Newton settles, so it
needs no verdict at infinity) they end on proven roots too.  Test 2: 123 failed paths -> 4, 12 incomplete subproblems
-> 4.

With ``retry_mpmath`` in the DGP's options (``cdpr dgp --mpmath-retry``), the Study paths still failed (at most
``max_mpmath_paths`` a run) are tracked once more from their start points by
:func:`cdpr_algebra.homotopy.hybrid_tracker.hybrid_track`: in double precision, and in compiled double-double
arithmetic (:mod:`cdpr_algebra.homotopy.dd_tracker` over the generated
:mod:`cdpr_algebra.generated.study_equations_dd`, the same equations' one source) wherever double precision fails,
to t = 0 without an endgame; an endpoint where Newton's method converges quadratically is then kept by the same
tests as above (``retried="study_extended"``).  Measured (eighteenth session) on the 16 Study paths that Test 3's runs
left failed: they crawl near N = 0 (N / |e|^2 ~ 1e-7 .. 1e-5, condition numbers 1e12 .. 1e17) where Newton in double
precision cannot meet the corrector tolerance; with 106 bits (python-flint first) the same step control tracks them,
most with ordinary steps, one only after ~27,000 steps of ~1e-6 in t (7.9 s in double-double, 111 s in
python-flint).  Test 3 with ``--mpmath-retry --jobs 1``: 5 failed paths -> 1, 3 incomplete subproblems -> 1, 55 s
instead of 16 s; Test 2 4 -> 3 failed paths; seed 002's 8-cable robot 138 -> 132 (most of its failed Study paths end
near N = 0, where a track without an endgame cannot end).

A Study path whose limit lies on the quadric N = 0 (no pose there: R = Q(e) / N, and Q(e) != 0 for e != 0) has its
pose at infinity: the endgame decides it with ``FastStudySystem.infinity_coordinate`` (N / |e|^2) as it decides
y0 = 0 in a projective chart (the limit's N within its accuracy of 0, and N(t) ~ t^v, v > 0, at the last two sample
radii), and the taut path is ``at_infinity`` (retried "study", its winding number and order v; its endpoint stays
its last point in (p, u, v, w, lam)).  Measured (sixteenth session) on seed 002's 8-cable robot: 122 such limits,
all with N / |e|^2 < 1e-10 (median 7e-14), winding number 2, v ~ 1/2; its taut set {1, 2, 5} then has 100 regular
endpoints and 56 at infinity, as {1, 3, 5} has; the robot: 248 failed paths -> 138, 37 incomplete subproblems -> 24.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cdpr_algebra.homotopy.results import AT_INFINITY, FAILURES, SINGULAR, SUCCESS
from cdpr_algebra.model.study_equations import STUDY_CHART_PARAMETERS, from_study, study_family, to_study

from .taut_system import LazyFamilySystem
from .unheld_roots import residual_bound

__all__ = ["FastStudySystem", "fast_study_family", "retrack_failed_in_study", "track_study_first", "warm_study_kernels",
           "study_roots", "RESIDUAL_TOL", "TAUT_FALLBACK"]

TAUT_FALLBACK = "taut"  # retried kind of a path that the Study run left undecided and the taut system settled
RESIDUAL_TOL = 1e-8  # residual of the mapped-back endpoint in the taut system after Newton (refinement.refine's measure)
EXTENDED = True  # Newton residuals in double-double where double precision stalls (TrackerOptions.extended_residual)
ILL_CONDITIONED_LIMIT = 1e13  # Study endpoints up to this condition, Newton at full precision, N nonzero: regular
CHART_SEED = 104729  # the chart c of e: drawn from this seed (any generic complex vector serves)


class FastStudySystem(LazyFamilySystem):
    """:func:`cdpr_algebra.model.study_equations.study_family` (m) with the compiled evaluator generated from it
    (``derivations/derive_study_equations.py``); the sympy family is built only when asked for."""

    family_builder = staticmethod(study_family)

    def __init__(self, m: int):
        super().__init__(m)
        self.n = 8 + m
        self.m = 7 * m + 6 + STUDY_CHART_PARAMETERS
        self.neq = 8 + m

    @property
    def degrees(self) -> tuple:
        return (1, 2) + (2,) * self.mm + (3,) * 6

    @staticmethod
    def infinity_coordinate(Y) -> np.ndarray:
        """N / |e|^2 = e . e / (e . conj(e)) of the points Y (rows): 0 on the quadric of points that are no pose (R =
        Q(e) / N, p = 2 g e* / N: a path whose limit has N = 0 has its rotation, in (p, u, v, w, lam), at
        infinity; Q(e) does not vanish for e != 0, and the chart keeps e != 0).  The endgame decides such limits at
        infinity as it decides y0 = 0 in a projective chart (:func:`cdpr_algebra.homotopy.endgame.decide_in_chart`)."""
        e = np.atleast_2d(Y)[:, :4]
        with np.errstate(all="ignore"):
            return np.sum(e * e, axis=1) / np.sum(np.abs(e) ** 2, axis=1)

    def compiled_kernels(self):
        """Evaluators for the compiled tracker (:mod:`cdpr_algebra.dgp.kernels`), the LU with the lam columns first."""
        from .kernels import study_apply, study_factor, study_fj, study_fjt

        return study_fj, study_fjt, study_factor, study_apply

    def compiled_residual_dd(self):
        """The residual in double-double (:mod:`cdpr_algebra.generated.study_residual_dd`) for the compiled tracker's
        extended-precision Newton."""
        from cdpr_algebra.generated.study_residual_dd import study_residual

        return study_residual

    def _eval(self, x, p, dp=None):
        from .kernels import study_batch

        X = np.array(np.atleast_2d(np.asarray(x, dtype=complex)), order="C")
        N = len(X)
        P = np.array(np.broadcast_to(np.asarray(p, dtype=complex), (N, self.m)), order="C")
        DP = P if dp is None else np.array(np.broadcast_to(np.asarray(dp, dtype=complex), (N, self.m)), order="C")
        F = np.empty((N, self.neq), dtype=complex)
        J = np.zeros((N, self.neq, self.n), dtype=complex)
        H = np.zeros((N, self.neq), dtype=complex)
        study_batch(X, P, DP, F, J, H, dp is not None)
        return F, J, H

    def evaluate(self, x, p=None):
        return self._eval(x, p)[0]

    def evaluate_and_jacobian(self, x, p=None):
        return self._eval(x, p)[:2]

    def evaluate_directional(self, x, p, dp):
        return self._eval(x, p, dp)


_FAST: dict = {}


def fast_study_family(m: int) -> FastStudySystem:
    if m not in _FAST:
        _FAST[m] = FastStudySystem(m)
    return _FAST[m]


def warm_study_kernels() -> None:
    """Compile (or load from numba's cache) the batched Study evaluator, the double-double residual and the
    double-double evaluator and tracker of ``--mpmath-retry``: ``cdpr warm`` calls it, since robots without failed
    paths never reach them (the single-point kernels compile when
    :mod:`.kernels` is imported)."""
    from cdpr_algebra.generated.study_equations_dd import study_equations  # compiled on import (explicit signature)
    from cdpr_algebra.homotopy.dd_tracker import dd_track
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    sys_ = fast_study_family(2)
    sys_.compiled_residual_dd()  # compiled on import (explicit signature)
    x = np.ones(sys_.n, dtype=complex)
    p = np.ones(sys_.m, dtype=complex)
    sys_.evaluate_directional(x, p, p)
    dd_track(study_equations, sys_.neq, p, p, None, x, 1.0, 0.0, TrackerOptions(), 1, start_newton=0)  # the kernel


def study_chart() -> np.ndarray:
    """The chart c of e (fixed: a generic complex vector from CHART_SEED)."""
    rng = np.random.default_rng(CHART_SEED)
    return rng.normal(size=STUDY_CHART_PARAMETERS) + 1j * rng.normal(size=STUDY_CHART_PARAMETERS)


def _study_options(options, detours: bool = False):
    """The DGP's options for the Study run (its step budget and tolerances included): affine endgame (the projective
    one homogenizes quadratic systems only) with no verdicts at infinity (a path that is not settled stays failed),
    no retries of any kind (a path failed here stays failed), and Newton residuals in double-double where double
    precision stalls (``EXTENDED``); fast-finish endpoints that are only ill-conditioned (condition number up to
    ``ILL_CONDITIONED_LIMIT``, Newton at full precision, N = e . e nonzero) end regular without Cauchy loops
    (``EndgameOptions.ill_conditioned_limit``; every Study endpoint is tested again in the taut system); detours
    around phase-1 failures only with ``detours`` (a run of every path: a detour is kept when it reaches a point at
    t = 0.1 that no other path of the run holds, which proves nothing when the run holds only some of the paths)."""
    from cdpr_algebra.homotopy.endgame import SolveOptions

    base = options if options is not None else SolveOptions()
    return replace(base, endgame=replace(base.endgame, projective=False, infinity_verdicts=False,
                                         ill_conditioned_limit=ILL_CONDITIONED_LIMIT),
                   detour_retry=bool(detours and base.detour_retry), retry_tight=False,
                   retry_mpmath=False, check_path_jumping=False,
                   tracker=replace(base.tracker, extended_residual=EXTENDED))


def _study_parameters(start_parameters, target) -> tuple:
    """(P1, P0): the start and target parameters of the Study family, the chart of e appended to both."""
    chart = study_chart()
    return (np.concatenate([start_parameters, chart]), np.concatenate([np.asarray(target, dtype=complex), chart]))


def _study_homotopy_and_twin(m: int, P1, P0, seed: int, gamma: bool, **floor):
    """The Study run's parameter homotopy from P1 to P0 (drawn again from ``seed`` and ``gamma`` as
    :func:`cdpr_algebra.homotopy.solve.solve_parameter_homotopy` drew it) and its double-double twin over the generated
    :mod:`cdpr_algebra.generated.study_equations_dd` (``floor``: its ``corrector_floor``, when given)."""
    from cdpr_algebra.generated.study_equations_dd import study_equations
    from cdpr_algebra.homotopy.dd_tracker import DoubleDoubleParameterHomotopy
    from cdpr_algebra.homotopy.start_systems import parameter_homotopy

    (hom,) = parameter_homotopy(fast_study_family(m), P1, P0, rng=np.random.default_rng(seed), gamma=gamma)
    return hom, DoubleDoubleParameterHomotopy.like(hom, study_equations, **floor)


def _limit_of_one_sheet(q, o) -> bool:
    """A Study path ``q`` that the endgame (options ``o``) ended ``singular`` only by its condition number: its Cauchy
    estimate converged on one sheet (winding number 1, accuracy within ``DECENT_ACCURACY``) to a point that solves
    the Study system (relative residual <= ``o.finite_residual``) and whose N = e . e is nonzero beyond that
    accuracy (the endgame's own test of a limit at infinity, :func:`cdpr_algebra.homotopy.endgame.decide_in_chart` on
    ``FastStudySystem.infinity_coordinate``: a pose, not a point of N = 0)."""
    from cdpr_algebra.homotopy.endgame import DECENT_ACCURACY, decide_in_chart

    if q.status != SINGULAR or q.winding_number != 1 or not (q.residual <= o.finite_residual):
        return False
    if not (np.isfinite(q.accuracy) and q.accuracy <= DECENT_ACCURACY):
        return False
    zero, _, _ = decide_in_chart(q.endpoint[None], np.array([q.accuracy]), o=o,
                                 coordinate=FastStudySystem.infinity_coordinate)
    return not bool(zero[0])


PRECISE_ENDGAME = "precise_endgame"  # the ``retried`` of a path decided by _precise_endgames
PRECISE_ENDGAME_PATHS = 64  # failed Study paths per run given the endgame with double-double (~0.1-0.3 s each)
PRECISE_ENDGAME_STEPS = 6000  # its steps in double-double per path (~0.1-0.3 ms each)
PRECISE_ENDGAME_BUDGET = 40000  # ... and per run
PRECISE_FLOOR = 1e-16  # the double-double tracker's corrector floor there (dd_tracker.dd_track's corrector_floor)


def _precise_endgames(m: int, spaths, Y1, P1, P0, seed: int, gamma: bool, opts) -> list:
    """The Study paths ``spaths`` that failed in the endgame zone (t <= te; phase-1 failures have had their detours;
    from the start points Y1; at most ``PRECISE_ENDGAME_PATHS``, and
    ``PRECISE_ENDGAME_STEPS`` double-double steps a path, ``PRECISE_ENDGAME_BUDGET`` a run) tracked again to
    te by :func:`cdpr_algebra.homotopy.hybrid_tracker.hybrid_track` and given the Cauchy endgame over it
    (:func:`cdpr_algebra.homotopy.precise_endgame.precise_cauchy_endgame`: double precision, double-double where it
    fails, with the corrector floor ``PRECISE_FLOOR``).  A path whose Cauchy estimates converge (``cauchy_tol``) is
    decided as the double endgame decides: ``at_infinity`` when N = e . e of the limit vanishes to its accuracy and
    N(t) ~ t^v (v > 0) at the last two radii (:func:`cdpr_algebra.homotopy.endgame.decide_in_chart` on
    ``FastStudySystem.infinity_coordinate``), and also ``at_infinity`` when its translation and tensions (g, lam,
    affine in the Study system) are unbounded there (:func:`cdpr_algebra.homotopy.endgame.block_at_infinity`: the
    Cauchy means converge on such paths too, to a Puiseux constant term); a finite limit on one sheet (winding
    number 1) is returned as the path's endpoint for the caller's Newton test (``success``), one on c >= 2 sheets
    whose (g, lam) stay bounded as ``singular`` (winding number c) for the caller's residual test; the others keep
    their outcome.  Returns the paths (``retried = "precise_endgame"`` where decided).

    Why.  Measured (twenty-first session) on seed 002's 8-cable robot: its failed Study paths near t ~ 1e-4 .. 1e-5
    are ill-conditioned pairs (winding number 2) whose double-precision loops fail before two estimates agree; in
    double-double with the corrector floor the estimates agree to 1e-10 .. 1e-12 at t ~ 1e-7 on limits with
    N ~ 1e-16 (order 0.4 .. 0.6), ~0.2 s a path.  With the default floor (2^-86) the double-double steps are
    rejected there: Newton's updates stop at ~1e-32 times the condition number.  Phase-1 failures are left out: on
    seed 000 Test 3 its three (crawls at t ~ 0.3-0.4) cost 0.8 s serial in double-double, which the taut system or a
    re-run with a new gamma settles anyway; on seed 002 it decided 4 of 9 such paths, against 88 of 135 in the
    endgame zone.  Budgets (twenty-second session): with 1500 double-double steps a path and 10,000 a run, 8 paths of
    seed 002's taut sets {1, 2, 5, 6} and {1, 4, 5, 8} were cut off before two estimates agreed; with 6000 and 40,000
    they end at infinity (winding number 2, v c = 0.85 .. 1.23, as the 8 of each sibling taut set with cables 1 and
    5) and both subproblems are complete (seed 002: 49 -> 41 failed paths, 6 -> 4 incomplete, 63 s either way);
    bench_large_forces seeds 300-303 the same counts in 84 s instead of 68 s (their 3 flagged robots spend it)."""
    spaths = list(spaths)
    eo, tr = opts.endgame, opts.tracker
    te = eo.endgame_start
    bad = [j for j, q in enumerate(spaths) if q.status in FAILURES and abs(q.t) <= te][:PRECISE_ENDGAME_PATHS]
    if not bad:  # nothing to load (the double-double kernels cost ~8 MiB)
        return spaths
    from cdpr_algebra.homotopy.endgame import block_at_infinity, decide_in_chart
    from cdpr_algebra.homotopy.hybrid_tracker import hybrid_track
    from cdpr_algebra.homotopy.precise_endgame import precise_cauchy_endgame, relative_change

    hom, precise = _study_homotopy_and_twin(m, P1, P0, seed, gamma, corrector_floor=PRECISE_FLOOR)
    left = PRECISE_ENDGAME_BUDGET
    block = slice(4, 8 + m)  # g and lam, affine in the Study system

    def verdict(loop, loop_prev, turns):
        """(status, order) of a limit from its last two loops (their means agreed), or None: sample on.  The
        translation and tensions (g, lam) unbounded: at infinity whatever N, the loops' mean being their Puiseux
        constant term, no limit (block_at_infinity); N = 0 with N(t) ~ t^v: at infinity (decide_in_chart); a
        finite pose with (g, lam) steady: success on one sheet (for the caller's Newton test), else singular."""
        moved, bounded, v = block_at_infinity(loop, loop_prev, block, turns, eo)
        if moved:
            return BLOCK_AT_INFINITY, v
        est = loop.mean(axis=0)  # the Cauchy estimate, as precise_cauchy_endgame computes it
        acc = relative_change(est, loop_prev.mean(axis=0))
        inf, undecided, order = decide_in_chart(est[None], np.array([acc]), loop[:1], loop_prev[:1], eo,
                                                FastStudySystem.infinity_coordinate, [turns])
        if inf[0]:
            return AT_INFINITY, float(order[0])
        if undecided[0] or not bounded:
            return None
        return (SUCCESS if turns == 1 else SINGULAR), float("nan")

    for j in bad:
        if left <= 0:
            break
        seg = hybrid_track(hom, precise, Y1[j], 1.0, te, tr, chunk=PRECISE_CHUNK,
                           max_precise_steps=min(PRECISE_ENDGAME_STEPS, left))
        left -= seg.precise_steps
        steps = spaths[j].steps + seg.steps
        if seg.status != SUCCESS:
            spaths[j] = replace(spaths[j], steps=steps)
            continue
        lim = precise_cauchy_endgame(hom, precise, seg.x, te, eo, tr,
                                     max_precise_steps=min(PRECISE_ENDGAME_STEPS - seg.precise_steps, left),
                                     settled=lambda *loops: verdict(*loops) is not None)
        left -= lim.precise_steps
        steps += lim.steps
        spaths[j] = replace(spaths[j], steps=steps)
        if not lim.converged:
            continue
        status, v = verdict(lim.loop, lim.loop_prev, lim.winding)
        common = dict(t=0j, accuracy=lim.accuracy, winding_number=lim.winding, retried=PRECISE_ENDGAME)
        if status in (BLOCK_AT_INFINITY, AT_INFINITY):  # its last two samples kept (PathResult.valuation): the
            # limit is no point (a Puiseux constant term, or a point of N = 0, where no pose is)
            spaths[j] = replace(spaths[j], **{**common, "t": complex(lim.t)}, status=AT_INFINITY, endpoint=lim.xlast,
                                order=v, previous=lim.xprev, previous_t=complex(lim.t / eo.sample_ratio))
        else:  # success on one sheet, singular on c >= 2 (the caller tests them)
            spaths[j] = replace(spaths[j], **common, status=status, endpoint=lim.x)
    return spaths


STUDY_EXTENDED = "study_extended"  # the ``retried`` of a path that the Study run in extended precision rescued
BLOCK_AT_INFINITY = "block_at_infinity"  # a verdict of _precise_endgames (reported as at_infinity)
PRECISE_CHUNK = 500  # steps in double-double before double precision is tried again (hybrid_track)
PRECISE_STEPS = 30000  # steps in double-double per path (~0.3 ms each, m = 4)


def _rescue_in_extended_precision(m: int, spaths, Y1, P1, P0, seed: int, gamma: bool, opts, max_paths: int) -> dict:
    """The Study paths ``spaths`` (from the start points Y1) of the run from P1 to P0 (seed, gamma: the homotopy is
    drawn again, as :func:`cdpr_algebra.homotopy.solve.solve_parameter_homotopy` drew it) that failed, at most
    ``max_paths`` of them, tracked again with :func:`cdpr_algebra.homotopy.hybrid_tracker.hybrid_track` (double
    precision, and double-double where it fails: :mod:`cdpr_algebra.homotopy.dd_tracker` over
    :mod:`cdpr_algebra.generated.study_equations_dd`; at most ``PRECISE_STEPS`` such steps per path) to t = te, then
    on to t = 0 (no endgame: a path that does not reach a regular point there stays failed).  Returns {path: (Study
    endpoint, steps)} for the paths that reach a point where Newton's method in the Study system converges
    quadratically with a condition number at most the endgame's ``singular_condition``, or beyond it with its last
    update at ``refine_tol`` and N = e . e clearly nonzero (:func:`cdpr_algebra.homotopy.endgame.ill_conditioned_roots`;
    no upper limit: measured, thirty-fourth session, a random 5-cable robot's conjugate pair of roots with
    |x| = 8.5e6 and condition 2e13 here, which the endpoint certificates prove in ball arithmetic)."""
    from cdpr_algebra.homotopy.endgame import ill_conditioned_roots
    from cdpr_algebra.homotopy.refinement import refine
    from cdpr_algebra.homotopy.hybrid_tracker import hybrid_track

    bad = [j for j, q in enumerate(spaths) if q.status in FAILURES][:max_paths]
    if not bad:
        return {}
    hom, precise = _study_homotopy_and_twin(m, P1, P0, seed, gamma)
    te, tr = opts.endgame.endgame_start, opts.tracker
    unlimited = replace(opts.endgame, ill_conditioned_limit=np.inf)
    out = {}
    for j in bad:
        y, steps, spent, status = Y1[j], 0, 0, SUCCESS
        for ta, tb in ((1.0, te), (te, 0.0)):
            seg = hybrid_track(hom, precise, y, ta, tb, tr, chunk=PRECISE_CHUNK,
                               max_precise_steps=PRECISE_STEPS - spent)
            y, status = seg.x, seg.status
            steps += seg.steps
            spent += seg.precise_steps
            if status != SUCCESS:
                break
        if status != SUCCESS:
            continue
        # a regular root: Newton quadratic and, beyond the endgame's singular_condition, the fast finish's rule for
        # ill-conditioned roots (full precision, N clearly nonzero) without its upper limit
        yr, upd, _, cond, quad = refine(hom, y[None], 0.0)
        if quad[0] and (cond[0] <= opts.endgame.singular_condition
                        or ill_conditioned_roots(hom, yr, upd, cond, unlimited)[0]):
            out[j] = (yr[0], steps)
    return out


def retrack_failed_in_study(system, res, m: int, start_parameters, start_solutions, target, seed: int, gamma: bool,
                            options=None, detours: bool = False, failed_in_study: bool = False,
                            estimates: dict | None = None):
    """``res`` (the :class:`.homotopy.results.SolveResult` of the taut system ``system`` from ``start_solutions`` at
    ``start_parameters`` to ``target``, run with ``seed`` and ``gamma``) with its failed paths tracked again in Study
    parameters (module doc); rescued paths (regular, or at infinity through N = 0) have ``retried="study"`` (or the
    Study run's own retry, ``detour`` / ``endgame_detour``).  Returns (result, number rescued).  ``detours``: the
    Study run makes detours around failures (:mod:`cdpr_algebra.homotopy.detours`; only when ``res``
    holds every path and all of them failed, as :func:`track_study_first` calls it).  ``failed_in_study``: the
    failed paths of ``res`` were tracked in Study parameters in double precision already (by
    :func:`track_study_first`), so only the rescue in extended precision of ``retry_mpmath`` runs (the same homotopy
    in double precision again would fail the same way).  ``estimates``: a dict that receives {path: its last point
    in Study coordinates} for the paths that the Study run left failed or whose endpoint the tests above refused
    (:func:`study_roots` starts from them)."""
    from cdpr_algebra.homotopy.clusters import coincides_with_any
    from cdpr_algebra.homotopy.refinement import refine, relative_residual
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
    from cdpr_algebra.homotopy.solve import group_solutions, solve_parameter_homotopy

    paths = list(res.track.paths)
    failed = [i for i, p in enumerate(paths) if p.status in FAILURES]
    if not failed:
        return res, 0
    chart = study_chart()
    X1 = np.asarray(start_solutions, dtype=complex)[failed]  # path k starts at start solution k
    Y1 = to_study(X1, m, chart)
    opts = _study_options(options, detours)
    P1, P0 = _study_parameters(start_parameters, target)
    if failed_in_study:  # placeholders: every one of them failed (and goes to the rescue below)
        spaths = tuple(replace(paths[i], index=j, endpoint=y, steps=0) for j, (i, y) in enumerate(zip(failed, Y1)))
    else:
        sres = solve_parameter_homotopy(fast_study_family(m), P1, Y1, P0, seed=seed, options=opts, gamma=gamma,
                                        retries=0)
        spaths = sres.track.paths
        if PRECISE_ENDGAME_PATHS:
            spaths = _precise_endgames(m, spaths, Y1, P1, P0, seed, gamma, opts)
    ok = [j for j, q in enumerate(spaths) if q.status == SUCCESS or _limit_of_one_sheet(q, opts.endgame)]
    ends = {j: spaths[j].endpoint for j in ok}
    precise = {}
    if options is not None and options.retry_mpmath:  # the paths still failed, in double-double where double fails
        precise = _rescue_in_extended_precision(m, spaths, Y1, P1, P0, seed, gamma, opts, options.max_mpmath_paths)
        ends.update({j: y for j, (y, _) in precise.items()})
        ok = sorted(ends)
    with np.errstate(all="ignore"):
        X0 = from_study(np.array([ends[j] for j in ok]).reshape(-1, 8 + m), m)
    finite = np.all(np.isfinite(X0), axis=1)
    ok, X0 = [j for j, f in zip(ok, finite) if f], X0[finite]
    rescued, done = 0, set()
    if ok:  # Newton in the taut system (residuals in double-double where the system offers them), as every endpoint
        X, upd, residual, cond, quad = refine(ParameterHomotopy(system, start_parameters, target), X0, 0.0)  # t = 0
    regular = [p.endpoint for p in paths if p.status == SUCCESS]
    bound = residual_bound(X, RESIDUAL_TOL) if ok else None
    for k, j in enumerate(ok):
        x = X[k]
        if not (quad[k] and residual[k] <= bound[k] and np.all(np.isfinite(x))):
            continue
        if coincides_with_any(regular, x, opts.endgame.cluster_tol):  # the detour retry's test of a new point
            continue
        i = failed[j]
        # the Study run's own retries (its detours) named, else "study"
        extra, how = (precise[j][1], STUDY_EXTENDED) if j in precise else (0, spaths[j].retried or "study")
        paths[i] = replace(paths[i], status=SUCCESS, endpoint=x, t=0j, residual=float(residual[k]),
                           condition=float(cond[k]), accuracy=float(upd[k]),
                           steps=paths[i].steps + spaths[j].steps + extra, winding_number=1, retried=how)
        regular.append(x)
        rescued += 1
        done.add(j)
    sing = [j for j, q in enumerate(spaths) if q.status == SINGULAR and q.retried == PRECISE_ENDGAME]
    if sing:  # finite limits of c >= 2 sheets: singular roots, kept where they solve the taut system
        with np.errstate(all="ignore"):
            XS = from_study(np.array([spaths[j].endpoint for j in sing]), m)
            F, _ = system.evaluate_and_jacobian(XS, target)
            rs = relative_residual(F, XS)
            tol = np.maximum(opts.endgame.finite_residual, residual_bound(XS, RESIDUAL_TOL))
        for k, j in enumerate(sing):
            if not (np.all(np.isfinite(XS[k])) and rs[k] <= tol[k]):
                continue
            if coincides_with_any(regular, XS[k], opts.endgame.cluster_tol):  # c sheets meet on no regular root
                continue
            i = failed[j]
            q = spaths[j]
            paths[i] = replace(paths[i], status=SINGULAR, endpoint=XS[k], t=0j, residual=float(rs[k]),
                               condition=float("inf"), accuracy=q.accuracy, steps=paths[i].steps + q.steps,
                               winding_number=q.winding_number, retried=PRECISE_ENDGAME)
            rescued += 1
            done.add(j)
    for j, q in enumerate(spaths):  # limits on N = 0: the pose is at infinity (FastStudySystem.infinity_coordinate)
        if q.status == AT_INFINITY:  # or (g, lam) unbounded: its last two samples, mapped back (where finite)
            i = failed[j]
            last = {}
            if q.previous is not None:
                with np.errstate(all="ignore"):
                    Z = from_study(np.array([q.endpoint, q.previous]), m)
                if np.all(np.isfinite(Z)):
                    last = dict(endpoint=Z[0], t=q.t, previous=Z[1], previous_t=q.previous_t)
            paths[i] = replace(paths[i], status=AT_INFINITY, steps=paths[i].steps + q.steps,  # else: start point
                               winding_number=q.winding_number, order=q.order, retried=q.retried or "study", **last)
            rescued += 1
            done.add(j)
    for j, q in enumerate(spaths):  # the others keep their outcome; their steps include the Study run's
        if j not in done:
            i = failed[j]
            if estimates is not None and np.all(np.isfinite(q.endpoint)):  # failed, or an endpoint refused above
                estimates[i] = q.endpoint
            paths[i] = replace(paths[i], steps=paths[i].steps + q.steps + (precise[j][1] if j in precise else 0))
    if not rescued:
        return replace(res, track=replace(res.track, paths=tuple(paths))), 0
    track = replace(res.track, paths=tuple(paths))
    sols = group_solutions(track, opts.duplicate_tol, opts.endgame.cluster_tol)
    return replace(res, track=track, solutions=sols), rescued


def track_study_first(system, m: int, start_parameters, start_solutions, target, seed: int, gamma: bool, options,
                      track_taut, estimates: dict | None = None):
    """Every path of the parameter homotopy from ``start_solutions`` (taut coordinates) at ``start_parameters`` to
    ``target`` tracked in Study parameters first, then in the taut ``system`` only where Study leaves it undecided.

    The Study run is :func:`retrack_failed_in_study` applied to all paths (placeholders, none tracked yet): a path
    ends ``regular`` there when its endpoint, mapped back, is a Newton-quadratic root of the taut system distinct
    from every other kept endpoint, and ``at_infinity`` when its limit lies on N = 0; it follows the same parameter
    path (same ``seed`` and ``gamma``) as a taut-system run would.  ``track_taut(indices) -> SolveResult`` tracks the
    other paths (failed in Study, or singular at a point other than a regular root) in the taut system, with its
    own retries, from ``start_solutions[indices]``; its outcomes replace theirs (``retried`` = ``TAUT_FALLBACK``
    unless the taut run retried them itself).  A regular taut endpoint on a point that a Study path holds means a
    jump of one of the two: that Study path is tracked in the taut system too, and when it ends on a point that no
    other path holds, the Study run had jumped and it takes its taut outcome; else the taut path is
    ``path_jumping`` (failed: nothing is merged).  Returns the :class:`.homotopy.results.SolveResult` of all paths
    (solutions grouped as the engine groups them; the Study paths' ``retried`` is empty, theirs is the first run,
    unless the Study run made a detour for them: ``detour`` or ``endgame_detour``).  ``estimates``: as in
    :func:`retrack_failed_in_study`, the Study run's last points of its failed paths."""
    from cdpr_algebra.homotopy.clusters import coincides_with_any
    from cdpr_algebra.homotopy.results import PATH_JUMPING, STEP_TOO_SMALL, PathResult, SolveResult, TrackResult
    from cdpr_algebra.homotopy.solve import group_solutions

    X = np.asarray(start_solutions, dtype=complex)
    nan = float("nan")
    todo = tuple(PathResult(i, STEP_TOO_SMALL, X[i], 1.0 + 0j, nan, nan, nan, 0) for i in range(len(X)))
    blank = SolveResult(solutions=(), track=TrackResult(paths=todo, seconds=0.0, seed=seed))
    sres, _ = retrack_failed_in_study(system, blank, m, start_parameters, X, target, seed, gamma,
                                      replace(options, retry_mpmath=False), detours=True, estimates=estimates)
    paths = [replace(p, retried="") if p.retried == "study" else p for p in sres.track.paths]
    rest = [i for i, p in enumerate(paths) if p.status in FAILURES]
    template = sres
    tol = options.endgame.cluster_tol

    def taut_outcomes(rows):
        res = track_taut(rows)
        return res, {i: replace(q, index=i, retried=q.retried or TAUT_FALLBACK, steps=q.steps + paths[i].steps)
                     for i, q in zip(rows, res.track.paths)}  # steps: the Study run's too

    def holder(x, skip):
        """The path other than ``skip`` whose regular endpoint is x (within the endgame's cluster tolerance)."""
        return next((j for j, p in enumerate(paths) if j != skip and p.status == SUCCESS
                     and coincides_with_any([p.endpoint], x, tol)), None)

    if rest:
        template, new = taut_outcomes(rest)
        for i, q in new.items():
            paths[i] = replace(q, status=STEP_TOO_SMALL) if q.status == SUCCESS else q  # placed below
        # a taut endpoint on a point that a Study path holds: one of the two jumped.  The Study path is tracked in
        # the taut system too; when it ends there on a point nobody holds, the Study run had jumped and both
        # points stand, else the taut path stays failed (path_jumping).
        clash = {i: holder(q.endpoint, i) for i, q in new.items() if q.status == SUCCESS}
        partners = sorted({j for j in clash.values() if j is not None})
        if partners:
            _, again = taut_outcomes(partners)
            for j in partners:
                q = again[j]
                if q.status == SUCCESS and holder(q.endpoint, j) is None and not any(
                        coincides_with_any([new[i].endpoint], q.endpoint, tol) for i, h in clash.items() if h == j):
                    paths[j] = q
        for i, q in new.items():
            if q.status == SUCCESS:
                paths[i] = q if holder(q.endpoint, i) is None else replace(q, status=PATH_JUMPING)
    track = replace(template.track, paths=tuple(paths), seed=seed)
    sols = group_solutions(track, options.duplicate_tol, options.endgame.cluster_tol)
    return replace(template, track=track, solutions=sols)


def study_roots(m: int, start_parameters, target, estimates):
    """Roots of the equations in Study parameters at the ``target`` (t = 0) reached by Newton's method from the Study
    points ``estimates`` (a failed path's last point), in taut coordinates: those that
    :func:`.unheld_roots.newton_roots` accepts in Study parameters (quadratic, last update <= ``SETTLED``, condition
    <= ``MAX_CONDITION``; no residual test there), at a pose (N = e . e nonzero beyond that update: not a point at
    infinity).

    Why.  A path of the taut system whose pose grows without bound on the way (N / |e|^2 ~ 1e-7, |R| ~ 1e6) is
    ill-conditioned in both coordinates near t = 0, and its tracking fails there; Newton's method in the taut system
    from its estimate does not reach the root, while in Study parameters the same root has a moderate condition
    number.  Measured (twenty-first session) on seed 002's 8-cable robot, taut set {1, 3, 4, 5, 8}: the two failed
    paths' Study estimates at t = 2.4e-5 lead to two distinct roots (scaled condition 9e10 in Study parameters,
    1e14 in the taut system, |x| = 2.4e6 there), confirmed by Newton's method at 60 digits.
    The caller keeps a root only as :func:`.unheld_roots.settle_on_unheld_roots` keeps any."""
    from cdpr_algebra.homotopy.endgame import off_infinity
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy

    from .unheld_roots import newton_roots

    Y = np.asarray(list(estimates), dtype=complex).reshape(-1, 8 + m)
    if not len(Y):
        return np.zeros((0, 12 + m), dtype=complex)
    hom = ParameterHomotopy(fast_study_family(m), *_study_parameters(start_parameters, target))
    y, info, good = newton_roots(hom, Y, np.inf)
    with np.errstate(all="ignore"):
        upd = np.array([u for _, _, u in info])
        good &= off_infinity(FastStudySystem.infinity_coordinate, y, upd)  # a pose
        X = from_study(y[good], m) if good.any() else np.zeros((0, 12 + m), dtype=complex)
    return X[np.all(np.isfinite(X), axis=1)]
