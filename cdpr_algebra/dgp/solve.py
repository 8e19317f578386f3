"""Direct geometrico-static problem (DGP, issue 4): every equilibrium of an n-cable robot with given cable
lengths, over every set of taut cables with m = 1 .. min(n, 6) cables.

Per taut set S (a *subproblem*, cables 1-based in reports):

* **m = 1**: analytic (:mod:`cdpr_algebra.dgp.one_cable`, seed 000 Sec. 3.2); the platform may still turn about the
  cable, the reported pose is the middle of the widest feasible arc.
* **m = 2 .. 6**: the engine's parameter homotopy (:func:`cdpr_algebra.homotopy.many_targets.solve_targets`
  with one target: :func:`cdpr_algebra.homotopy.solve.solve_parameter_homotopy`, which re-tracks failed or
  coinciding paths itself) from the stored generic solution set of :func:`cdpr_algebra.model.taut_equations.taut_family`
  (``cdpr_algebra/data/dgp_generic_m{m}.json``, made by ``derivations/solve_generic_dgp.py``) to the robot's
  parameters, **every path in Study parameters first** (``STUDY_FIRST``, :func:`.study_retrack.track_study_first`:
  Euler parameters on a chart, where the near-isotropic complex rotations that ruin the conditioning of
  (p, u, v, w, lam) are ordinary points; a path is kept there when its endpoint, mapped back, is a Newton-quadratic
  root of the taut system distinct from every other, or at infinity when its limit lies on N = e . e = 0; the run
  makes detours around phase-1 failures, since it holds every path, and gives its paths that failed in the endgame
  zone a Cauchy endgame over double-double, :func:`.study_retrack._precise_endgames`), then the paths it leaves
  undecided in the
  taut system along the same parameter path with that engine's own retries (below; no detours: they need every
  path of the run) (retried ``taut``).  Measured (nineteenth session, 2 cores, against the taut system first with
  failed paths re-tracked in Study parameters, ``python -m benchmarks.bench_against 3412981 --tests
  test1,test3,test2 --rounds 2 --repeat 2``): seed 000 Test 3 5 -> 1 failed paths, 3 -> 1 incomplete subproblems,
  37 -> 8 uncertified endpoints, 9.1 -> 11.2 s (a Study step costs ~19 us against ~12 us: its evaluator is cubic);
  Test 2 4 -> 2, 4 -> 2, 134 -> 57, 15.3 -> 13.4 s (its ill-conditioned complex roots with |R| ~ 1e5, which the
  taut system's endgame ended ``singular``, are regular points there); seed 002's 8-cable robot 138 -> 128 failed,
  24 -> 21 incomplete, 59 -> 54 s (one run each); Test 1 (no hard path) 0.17 -> 0.34 s; the same admissible
  equilibria.  Subproblems whose m has no
  stored set are reported as skipped.  The robot is first normalized
  to the scale of the stored sets: base centred at the centroid c of the exit points, platform frame moved to
  the centroid cb of its points, world frame turned by Rw so that the load acts along -z, lengths divided by the
  cable geometry's scale L (:attr:`Robot.cable_scale`), load Q d replaced by -z; then R = Rw^T R^,
  p = c + L Rw^T p^ - R cb, lam = Q lam^ / L, tau_i = lam_i rho_i.
  Tracking uses the compiled tracker (:mod:`.homotopy.compiled` with the numba evaluators and structured linear
  solve of :mod:`cdpr_algebra.dgp.kernels`; numpy evaluators :class:`FastTautSystem` for the endgame checks and retries;
  predictor tolerance 3e-4; endpoints refined with Newton residuals in double-double, :func:`.homotopy.refinement.refine`;
  with ``default_options(extended=True)`` (``cdpr dgp --extended-precision``) a path whose Newton corrections stall
  in double precision although its predictor was good takes its Newton residuals in double-double from then on,
  :mod:`.homotopy.double_double`: near large complex solutions and the singular sets at infinity the condition
  number reaches 1e10..1e14 and double-precision Newton stops at cond x eps.  Measured (eleventh session, 2 cores,
  medians): seed 000 Test 3 47 -> 6 failed paths, 11 -> 2 incomplete subproblems, 4.1 -> 9.9 s; Test 2 185 -> 34,
  16 -> 7, 7.3 -> 13.3 s; seed 002's 8-cable robot 565 -> 223, 98 -> 35, 34 -> 55 s; the time is spent on the
  paths that need it, the others are tracked bit for bit as without it, so it stays an option).  No norm decides
  whether a path goes to infinity: the endgame of every path that
  does not finish as a regular point runs in a random chart of projective space (all unknowns, tensions
  included, homogenized; :mod:`.homotopy.endgame`), where a path is ``at_infinity`` only when the homogenizing
  coordinate goes to zero (with its order and winding number), and a finite solution is returned however large
  its coordinates or tensions.  A path that fails before the endgame zone (t > 0.1) is first tracked again
  around the point where it failed, on a half circle in the complex t-plane, and kept when it reaches there a
  regular solution that no other path holds (``SolveOptions.detour_retry``: the system at t = 0.1 is generic, so
  its solutions are exactly as many as the paths; on seed 000 Test 3 this left 47 failed paths instead of 86 and
  11 subproblems incomplete instead of 23, in less time, since fewer subproblems are re-run).  Any suspect path
  (failed, or ending on another path's endpoint) is then re-tracked by the engine in projective coordinates along
  the same parameter path with steps tightened 10x (one round,
  ``PROJECTIVE_RETRIES``: a second round tightened 100x rescued none of 181 paths on seed 000 Test 3 and none of
  639 on Test 2; the paths still failed there lose accuracy to conditioning, 1e10..1e11 near large non-real
  solutions or singular sets at infinity, which smaller steps do not restore).  (Without ``STUDY_FIRST``, the
  taut system tracks every path first and the paths it leaves failed are tracked again in Study parameters along
  the same parameter path, ``STUDY_RETRACK``, :func:`.study_retrack.retrack_failed_in_study`.)  Up to 8 failed paths are
  then tracked again from their start points with every step in double-double (:mod:`.taut_extended`: huge finite
  roots, |x| ~ 2e7, that double precision loses in both coordinates).  If one or two failed
  paths remain (at most ``RERUN_MAX_FAILED`` = 4), the subproblem is re-run once with a random gamma and another seed,
  the run with fewer failures is kept and its failed paths are settled on the other run's regular roots that none of
  its paths holds (:func:`_settle_on_other_runs_roots`), then on those of a run from another generic instance
  (:mod:`.other_start`) (each run's failed paths are first settled, where Newton's method from
  their last estimates, and in Study parameters from the Study run's last points, :func:`.study_retrack.study_roots`,
  finds regular roots that no other path holds, :mod:`.unheld_roots`); with ``retry_mpmath`` in the options (``cdpr dgp --mpmath-retry``), the
  paths still failed are tracked once more in Study parameters, in compiled double-double
  arithmetic wherever double precision fails (:func:`.study_retrack._rescue_in_extended_precision`: at most
  ``MP_RETRY_PATHS`` = 4 paths per run, up to ~10 s each, so off by default, and automatic for a subproblem left
  with at most ``AUTO_RESCUE_MAX_FAILED`` = 2 failed paths, :func:`_rescue_last_failed_paths`).  Every path ends with one outcome (``regular``, ``singular``, ``at_infinity``,
  ``failed`` with its reason), counted per subproblem (``outcomes``, ``failures``); a subproblem is
  ``complete`` when no path failed and its regular, singular and at-infinity endpoints account for the generic
  count (paths ending on one regular point are failures, ``path_jumping``: a solution is then missing).  A path put
  at infinity while only its tension multipliers grow, its pose staying finite
  (:func:`.tension_infinity.tension_infinity_undecided`),
  is ``endgame_failed``: that limit needs an exactly singular wrench matrix, and a finite equilibrium with huge
  tensions looks the same.

**Pruning** (seed 000 Sec. 4.1, recorded as the ``skipped`` reason): with D_ij = |A_i - A_j| and
d_ij = |b_i' - b_j'|, every pair of cables needs D_ij <= rho_i + rho_j + d_ij (B_i and B_j lie within
rho_i, rho_j of A_i, A_j: taut or slack); two taut cables also need |rho_i - rho_j| <= D_ij + d_ij
(B_i on the sphere (A_i, rho_i) must reach outside the ball (A_j, rho_j - d_ij)).

**Exclusion by the interval filter** (``exclude=True``, the default; ``cdpr dgp --track-all`` turns it off): before
a taut set of m >= 2 cables is tracked, a short interval branch and prune of it (:func:`cdpr_algebra.bp.search.excluded_by_filter`:
the filter operator of seed 000 Sec. 4.3 and bisection, at most ``EXCLUSION_BOXES`` boxes, outward-rounded) tries to
exclude every box of its domain: tensions >= 0 and the other cables no longer than rho_j (1 + 2 ``SLACK_TOL``), so
that every solution the filtering below would admit lies in it (one with a tension in [-tol, 0) belongs to a
smaller taut set by the deduplication rule).  When it does, the set provably holds no admissible equilibrium and is
not tracked: ``skipped`` says so and ``excluded`` gives the boxes; its subproblem is ``complete`` (nothing
admissible is missing) but its real inadmissible and complex solutions are not counted.  On seed 000 Test 2 it
excludes 30 of the 57 sets of m >= 2 in at most 17 boxes each, among them the m = 3 sets whose paths fail near
singular solutions at infinity.  ``crosscheck`` turns it off (the interval solver is the other side).

**Filtering** of the finite endpoints (after two real Newton steps on the normalized system):
real (imaginary parts <= 1e-6 in the normalized, unit-size coordinates); a proper rotation
(|R^T R - I| <= 1e-6, det R > 0); tensions tau_i >= -tol with tol = 1e-9 Q; every other cable slack:
|B_j - A_j| <= rho_j (1 + 1e-9).  Stability: class of the reduced Hessian (:mod:`cdpr_algebra.model.stability`), stable = '>'.
**Certification** (:mod:`cdpr_algebra.certificates.equilibria`): every admissible solution gets an interval certificate (Krawczyk:
existence and uniqueness in a box of relative width <= 1e-9, tension signs, slack margins, Hessian class).

**Deduplication rule.** An equilibrium is reported once, in the subproblem with the fewest taut cables:
a solution of subproblem S with a tension |tau_i| <= tol is not reported by S (it is the solution of
S minus {i}, whose subproblem reports it: there cable i is exactly at its length, which passes the slack
test).  Admissible solutions of different subproblems with the same pose (within 1e-7 L) are merged into
one, the one with fewer taut cables (the first subproblem among equals); the others are listed as its
``alternatives`` (taut set, tensions, H_r): a pose held by several taut sets with positive tensions, as every
valid cable configuration of a robot with more than 6 cables at the cable lengths of that pose.
"""

from __future__ import annotations

import itertools
from collections import Counter
import os
import time
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from cdpr_algebra.model.line_dependence import lines_dependent_everywhere
from cdpr_algebra.model.rod_equations import BINARY
from cdpr_algebra.model.taut_equations import decode
from cdpr_algebra.model.taut_sets import lengths_and_taut_sets
from .normalization import normalized_problem, world_coordinates
from .one_cable import one_cable_equilibria
from .positive_dimensional import families_of_endpoints
from .rod import rod_geometry, solve_rod_taut_set
from .other_start import other_generic_instance
from .collinear_anchors import collinear_start, fixed_parameters, line_frame
from .parallelogram import (centred_frame, flip_platform, flip_roots_back, parallelogram_kind, parallelogram_order,
                            parallelogram_relations, parallelogram_start, subfamily_target)
from .parallelogram import fixed_parameters as parallelogram_fixed
from .tension_infinity import tension_infinity_undecided
from .taut_extended import MAX_PATHS as EXTENDED_MAX_FAILED, rescue_in_taut_extended
from .study_retrack import RESIDUAL_TOL, retrack_failed_in_study, study_roots, track_study_first
from .unheld_roots import settle_on_conjugates, settle_on_unheld_roots
from .taut_system import FastTautSystem, fast_family
from .table import dgp_table, incompleteness, summary_line  # noqa: F401 (the module's public names)
from .results import DGPSolution, DGPSubproblem
from cdpr_algebra.homotopy.results import FAILURES, OUTCOMES, SUCCESS, outcome_counts
from cdpr_algebra.model.stability import stability_classes

__all__ = ["DGPSolution", "DGPSubproblem", "DGPResult", "dgp", "generic_path", "available_m", "prune", "FastTautSystem",
           "fast_family", "dgp_table", "summary_line", "incompleteness", "taut_set_roots"]

DATA = Path(__file__).resolve().parents[1] / "data"
REAL_TOL = 1e-6
SLACK_TOL = 1e-9
TENSION_RTOL = 1e-9
EXCLUSION_BOXES = 64  # box budget of the interval exclusion test run before tracking a taut set
LINES_DEPENDENT = ("the {m} cable lines are linearly dependent at every pose (architectural singularity: exact rank at "
                   "random rational poses, model.line_dependence): its equilibria, if any, are not isolated and a "
                   "homotopy cannot count them; not tracked")
_GENERIC: dict = {}


def generic_path(m: int) -> Path:
    return DATA / f"dgp_generic_m{m}.json"


def available_m() -> list[int]:
    """The m (2..6) with a stored generic solution set."""
    return [m for m in range(2, 7) if generic_path(m).exists()]


def _generic(m: int):
    if m not in _GENERIC:
        from cdpr_algebra.homotopy.monodromy import load_instance

        # the residual by the generated evaluator; the hash of the sympy family (slow to build: ~0.25 s per m,
        # every process) is checked by tests/test_dgp.py::test_stored_generic_sets
        p, X, _ = load_instance(generic_path(m), fast_family(m), check_hash=False)
        _GENERIC[m] = (p, X)
    return _GENERIC[m]


@dataclass(frozen=True)
class DGPResult:
    """Every admissible equilibrium of one DGP, its subproblems, and what reproduces it: ``seed`` and ``options``
    (the homotopy's :class:`cdpr_algebra.homotopy.endgame.SolveOptions`, None for :func:`default_options`).
    ``status`` is "complete" (every subproblem proven complete) or "incomplete"."""

    solutions: tuple
    subproblems: tuple
    seconds: float
    seed: int = 0
    options: object = None

    @property
    def stable(self) -> tuple:
        return tuple(s for s in self.solutions if s.stable)

    def by_m(self, m: int) -> tuple:
        return tuple(s for s in self.solutions if len(s.taut) == m)

    def taut_set(self, taut) -> tuple:
        """(DGPSubproblem, its admissible solutions) of the 1-based taut set ``taut`` (KeyError when not solved)."""
        taut = tuple(sorted(int(c) for c in taut))
        sub = next((s for s in self.subproblems if tuple(s.taut) == taut), None)
        if sub is None:
            raise KeyError(f"taut set {taut} was not solved")
        return sub, tuple(s for s in self.solutions if tuple(s.taut) == taut)

    @property
    def incomplete(self) -> tuple:
        """The subproblems that are not complete (a failed path, or no stored generic set)."""
        return tuple(s for s in self.subproblems if not s.complete)

    @property
    def complete(self) -> bool:
        return not self.incomplete

    @property
    def status(self) -> str:
        return "complete" if self.complete else "incomplete"

    @property
    def admissible_complete(self) -> bool:
        """Every admissible equilibrium is known (each subproblem complete or settled), whatever the complex count."""
        return all(s.admissible_complete for s in self.subproblems)

    @property
    def families(self) -> tuple:
        """The admissible families of turning equilibria of every subproblem (:class:`.positive_dimensional.
        FamilyMember`: not isolated, so not among ``solutions``)."""
        return tuple(f for s in self.subproblems if s.family is not None for f in s.family.members)

    def outcomes(self) -> dict:
        """Paths per outcome over all subproblems."""
        total = dict.fromkeys(OUTCOMES, 0)
        for s in self.subproblems:
            for k, v in s.outcomes.items():
                total[k] += v
        return total

    def to_dict(self) -> dict:
        return {"status": self.status, "complete": self.complete, "incomplete": [list(s.taut) for s in self.incomplete],
                "admissible_complete": self.admissible_complete,
                "settled": [list(s.taut) for s in self.incomplete if s.settled is not None],
                "outcomes": self.outcomes(), "solutions": [s.to_dict() for s in self.solutions],
                "families": [f.to_dict() for f in self.families],
                "subproblems": [s.to_dict() for s in self.subproblems], "seconds": self.seconds, "seed": self.seed,
                "options": (self.options or default_options()).to_dict()}


# ---------------------------------------------------------------------------------------------
def prune(robot, rho, cables) -> str | None:
    """Reason why the taut set ``cables`` (0-based) cannot hold an equilibrium, or None (see module doc)."""
    A, b = robot.base, robot.platform
    n = robot.n
    for i in range(n):
        for j in range(i + 1, n):
            D = np.linalg.norm(A[i] - A[j])
            d = np.linalg.norm(b[i] - b[j])
            if D > (rho[i] + rho[j] + d) * (1 + 1e-12):
                return (f"cables {i + 1} and {j + 1} cannot reach each other's anchor: |A{i + 1}A{j + 1}| = {D:.6g} > "
                        f"rho{i + 1} + rho{j + 1} + |b{i + 1}'b{j + 1}'| = {rho[i] + rho[j] + d:.6g}")
    for i, j in itertools.combinations(cables, 2):
        D = np.linalg.norm(A[i] - A[j])
        d = np.linalg.norm(b[i] - b[j])
        if abs(rho[i] - rho[j]) > (D + d) * (1 + 1e-12) + 1e-12 * robot.size:
            return (f"cables {i + 1} and {j + 1} cannot both be taut: |rho{i + 1} - rho{j + 1}| = {abs(rho[i] - rho[j]):.6g}"
                    f" > |A{i + 1}A{j + 1}| + |b{i + 1}'b{j + 1}'| = {D + d:.6g}")
    return None


def _slack_ok(robot, rho, cables, p, R) -> bool:
    others = [j for j in range(robot.n) if j not in cables]
    if not others:
        return True
    B = p + robot.platform[others] @ R.T
    dist = np.linalg.norm(B - robot.base[others], axis=1)
    return bool(np.all(dist <= rho[others] * (1 + SLACK_TOL)))


def _classify(robot, rho, cables, p, R, tau):
    idx = list(cables)
    B = p + robot.platform[idx] @ R.T
    G = p + R @ robot.com
    return stability_classes(robot.base[idx], B, G, tau, rho[idx], robot.load, robot.size)


def _solve_one_cable(robot, rho, i):
    t0 = time.perf_counter()
    tol = TENSION_RTOL * robot.load
    # candidates: 4 (2 when G lies on the cable line through B_i); report those with an admissible turning angle
    dist = np.linalg.norm(robot.com - robot.platform[i])
    candidates = 4 if dist > 1e-12 * robot.size else 2
    sols = []
    for e in one_cable_equilibria(robot, i, rho):
        if e.tension < -tol:
            continue
        tau = np.zeros(robot.n)
        tau[i] = e.tension
        cls = _classify(robot, rho, [i], e.position, e.rotation, np.array([e.tension]))
        sols.append(DGPSolution((i + 1,), np.array(e.position), np.array(e.rotation), tau, cls))
    sub = DGPSubproblem((i + 1,), candidates, candidates, candidates, len(sols), time.perf_counter() - t0,
                        outcomes={**dict.fromkeys(OUTCOMES, 0), "regular": candidates}, generic_count=candidates)
    return sub, sols


MP_RETRY_PATHS = 4  # with retry_mpmath: failed paths per subproblem run tracked again in double-double (Study)
RERUN_MAX_FAILED = 4  # re-run a subproblem with a new gamma only when at most this many of its paths failed
AUTO_RESCUE_MAX_FAILED = 2  # ... then the extended-precision rescue of --mpmath-retry for at most this many left
# ... and, where some are still left, the other route's failed paths rescued the same way, whose roots settle them.
# No condition limit on those roots: the rescue kept them in Study parameters (Newton quadratic to full precision, N
# clearly nonzero), where they are far better conditioned than in (p, u, v, w, lam); the endpoint certificates prove
# them or not.  Measured (thirty-fourth session): a random 5-cable robot's {2, 3, 4} has a conjugate pair of roots
# with |x| = 8.5e6 (condition 2e13 in Study parameters, 1.3e16 here), each route reached one of them
RESCUED_MAX_CONDITION = np.inf
# last, a real target's failed paths settled on the conjugates of its non-real regular endpoints that no path holds
# (dgp.unheld_roots.settle_on_conjugates).  Measured (thirty-fourth session): a random 6-cable robot's {1, 2, 3, 6}
# and a random 3-cable robot's {1, 2, 3} (tests/test_dgp_round_trips.py, seed 3), one root of a huge conjugate pair
# reached in double-double, the other by no route, complete with it
CONJUGATE_ROOTS = True
OTHER_START = True  # ... after the gamma re-run, a run from another generic instance settles failed paths too
# predictor tolerance of the tracker (engine default 1e-5; the corrector still ends at 1e-8, with a third Newton
# update where two do not reach it).  Measured on seed 000 Tests 2 and 3 (tenth session): 1e-4 -> 3e-4 takes
# Test 3's phase 1 from 533k to 457k steps; 1e-3 (413k) left one more subproblem of Test 2 incomplete.
PREDICTOR_TOL = 3e-4
STUDY_FIRST = True  # every path tracked in Study parameters first, the taut system only where Study leaves it undecided
UNHELD_ROOTS = True  # failed paths settled on regular roots no other path holds, from their estimates (dgp.unheld_roots)
STUDY_RETRACK = True  # without STUDY_FIRST: failed paths tracked again in Study parameters (dgp.study_retrack)
PROJECTIVE_RETRIES = 1  # rounds of projective re-tracking of suspect paths (step control tightened 10x)


def default_options(extended: bool = False):
    """The homotopy options of the DGP (module doc): predictor tolerance 3e-4, projective endgame, detours around
    the point where a path failed before the endgame zone, no in-place double-precision retries (suspect paths
    are re-tracked in projective coordinates), no arbitrary precision; with ``extended`` Newton residuals in
    double-double wherever double precision stalls (``TrackerOptions.extended_residual``)."""
    from cdpr_algebra.homotopy.endgame import EndgameOptions, SolveOptions
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    return SolveOptions(tracker=TrackerOptions(predictor_tol=PREDICTOR_TOL, extended_residual=extended),
                        endgame=EndgameOptions(projective=True),
                        retry_tight=False, retry_mpmath=False, max_mpmath_paths=MP_RETRY_PATHS,
                        detour_retry=True)


def _track(m, target, seed, gamma, options=None, start=None):
    """Parameter homotopy from the stored generic set (see the module doc), or from ``start`` = (parameters, all
    solutions) of another generic instance.  Returns (result, failed paths)."""
    from cdpr_algebra.homotopy.many_targets import solve_targets

    p_gen, X_gen = _generic(m) if start is None else start
    # no in-place double retries: suspect paths are re-tracked in projective coordinates, then in Study parameters;
    # with retry_mpmath, paths still failed there are tracked in Study parameters in double-double where double
    # precision fails (dgp.study_retrack, at most MP_RETRY_PATHS per run), not by the engine's mpmath tracker in
    # (p, u, v, w, lam) (pure Python: minutes per path, and it did not rescue these paths).
    # Predictor tolerance PREDICTOR_TOL (default 1e-5): paths from the stored generic set are nonsingular, and any
    # two paths ending on one point are re-tracked with tightened steps (path jumping cannot go unnoticed).
    # The endgame decides finite / at infinity in a projective chart (no norm threshold).
    options = default_options() if options is None else options

    def track_taut(rows, detour=True):
        (res,) = solve_targets(fast_family(m), p_gen, X_gen[rows], [target], seed=seed,
                               options=replace(options, retry_mpmath=False, detour_retry=options.detour_retry and detour),
                               gamma=gamma, retries=PROJECTIVE_RETRIES)
        return tension_infinity_undecided(res, m)

    estimates = {}  # the Study run's last points of the paths it left failed (or whose endpoints it refused)
    if STUDY_FIRST:
        # the Study run's paths put at infinity too (its precise endgame's block verdict: (g, lam) unbounded)
        res = tension_infinity_undecided(track_study_first(fast_family(m), m, p_gen, X_gen, target, seed, gamma,
                                                           options, lambda rows: track_taut(rows, detour=False),
                                                           estimates), m, sampled_only=True)
        if options.retry_mpmath and any(p.status in FAILURES for p in res.track.paths):
            res, _ = _rescue_last_failed_paths(m, target, res, seed, gamma, options, start)
    else:
        res = track_taut(np.arange(len(X_gen)))
        if STUDY_RETRACK:
            res, _ = retrack_failed_in_study(fast_family(m), res, m, p_gen, X_gen, target, seed, gamma, options)
            res = tension_infinity_undecided(res, m, sampled_only=True)
    if UNHELD_ROOTS and any(p.status in FAILURES for p in res.track.paths):
        left = [i for i, p in enumerate(res.track.paths) if p.status in FAILURES and i in estimates]
        res, _ = _settle_on_unheld_roots(m, target, res, options,
                                         study_roots(m, p_gen, target, [estimates[i] for i in left]))
    return res, sum(1 for p in res.track.paths if p.status in FAILURES)


def _settle_on_unheld_roots(m, target, res, options, estimates=(), max_condition: float | None = None):
    """:func:`.unheld_roots.settle_on_unheld_roots` for the run ``res`` of the taut system of m cables to ``target``
    (``estimates``: more points to start Newton's method from): (result, failed paths left)."""
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy

    return settle_on_unheld_roots(ParameterHomotopy(fast_family(m), _generic(m)[0], target), res, options,
                                  RESIDUAL_TOL, estimates, max_condition)


def solve_taut_set(robot, rho, cables, seed: int = 0, certify: bool = True, options=None, exclude: bool = True):
    """(DGPSubproblem, [DGPSolution]) for the 0-based taut set ``cables`` (pruning, ``exclude``: the interval
    exclusion test, tracking, filtering, and with ``certify`` an interval certificate for every admissible solution,
    :mod:`cdpr_algebra.certificates.equilibria`); ``options``: the homotopy's :class:`.homotopy.endgame.SolveOptions`
    (default: those of the module doc)."""
    sub, sols, Z = _solve_and_certify_solutions(robot, rho, cables, seed, certify, options, exclude)
    (sub,) = _with_endpoint_certificates(robot, rho, [(cables, sub, Z)])
    return sub, sols


def taut_set_roots(robot, rho, cables, seed: int = 0, options=None):
    """(DGPSubproblem with its endpoint certificates, Z (N, 12 + m) its regular endpoints in world coordinates (p, the
    columns u, v, w of R, lam_i = tau_i / rho_i: the unknowns of :mod:`cdpr_algebra.dgp.export`) or None (a set
    pruned, or solved as a rod), proven (N,) bool: each proven a root, unique in its box and distinct from the others)
    of the 0-based taut set ``cables``, tracked whatever the interval filter says: every root, for comparisons with
    another solver's (:mod:`cdpr_algebra.comparison.roots`)."""
    sub, _, Z = _solve_taut_set(robot, np.asarray(rho, dtype=float), tuple(cables), seed, options, exclude=False)
    proofs: dict = {}
    (sub,) = _with_endpoint_certificates(robot, rho, [(cables, sub, Z)], proofs)
    return sub, Z, proofs.get(0, np.zeros(0 if Z is None else len(Z), dtype=bool))


def equilibrium_from_pose(robot, rho, cables, position, rotation, tensions, found_by: str = "homotopy",
                          certify: bool = True) -> DGPSolution:
    """The DGPSolution of the 0-based taut set ``cables`` at a pose found by another method (tensions: all n, 0 on
    slack cables): stability class from the reduced Hessian and, with ``certify``, the interval certificate of the
    homotopy's own solutions (:func:`cdpr_algebra.certificates.equilibria.certify_taut_root`)."""
    rho = np.asarray(rho, dtype=float)
    idx = list(cables)
    position, rotation = np.asarray(position, dtype=float), np.asarray(rotation, dtype=float)
    tau = np.asarray(tensions, dtype=float)
    sol = DGPSolution(tuple(c + 1 for c in idx), position, rotation, tau,
                      _classify(robot, rho, idx, position, rotation, tau[idx]), found_by=found_by)
    return _certify_solutions(robot, rho, [sol])[0] if certify else sol


def _certify_solutions(robot, rho, sols):
    """The admissible solutions with their interval certificates (:func:`cdpr_algebra.certificates.equilibria.certify_taut_root`)."""
    if not sols:
        return sols
    from cdpr_algebra.certificates.equilibria import certify_taut_root, polished_taut_root

    out = []
    for s in sols:
        idx = [t - 1 for t in s.taut]
        cert = certify_taut_root(robot, rho, idx, s.position, s.rotation, s.tensions[idx], reading=s.reading)
        polished = None if cert.exists_unique else polished_taut_root(robot, rho, idx, s.position, s.rotation,
                                                                      s.tensions[idx], reading=s.reading)
        if polished is not None:  # ill-conditioned: doubles did not locate the root within the certificate's box
            p, R, t = polished
            c = certify_taut_root(robot, rho, idx, p, R, t, reading=s.reading)
            if c.exists_unique:
                tau = np.zeros(robot.n)
                tau[idx] = t
                moved = float(max(np.abs(p - s.position).max() / robot.cable_scale,
                                  np.abs(t - s.tensions[idx]).max() / np.abs(t).max()))
                s = replace(s, position=p, rotation=R, tensions=tau, hessian=_classify(robot, rho, idx, p, R, t))
                cert = replace(c, extra={**c.extra, "polished": moved})
        out.append(s.with_certificate(cert))
    return out


def _solve_and_certify_solutions(robot, rho, cables, seed, certify, options, exclude):
    """:func:`_solve_taut_set` plus the certificates of its admissible solutions (endpoint certificates to come)."""
    sub, sols, Z = _solve_taut_set(robot, rho, cables, seed, options, exclude)
    return sub, _certify_solutions(robot, rho, sols) if certify else sols, Z


def excluded_subproblem(robot, rho, cables) -> DGPSubproblem | None:
    """The subproblem of the 0-based taut set ``cables`` (m >= 2) when the interval filter proves that it holds no
    admissible equilibrium (see the module doc), else None."""
    from cdpr_algebra.bp.search import excluded_by_filter

    t0 = time.perf_counter()
    rho_x = np.array(rho, dtype=float)
    others = [j for j in range(robot.n) if j not in cables]
    rho_x[others] *= 1 + 2 * SLACK_TOL
    boxes = excluded_by_filter(robot, rho_x, cables, EXCLUSION_BOXES)
    if boxes is None:
        return None
    return DGPSubproblem(tuple(c + 1 for c in cables), 0, 0, 0, 0, time.perf_counter() - t0,
                         f"no admissible equilibrium: the interval filter excluded every box of its domain ({boxes} "
                         "boxes); not tracked, its inadmissible solutions not counted", generic_count=0,
                         excluded=boxes)


def _solve_taut_set(robot, rho, cables, seed: int = 0, options=None, exclude: bool = True, rods: bool = True):
    """(DGPSubproblem, admissible DGPSolutions, regular endpoints in world coordinates or None) of the 0-based taut
    set ``cables``; ``rods`` False tracks a taut set on a line, or on two centred parallelograms, with the generic
    6-DOF homotopy too (tests: the two routes cross-checked)."""
    t0 = time.perf_counter()
    cables = tuple(cables)
    taut1 = tuple(c + 1 for c in cables)
    m = len(cables)
    reason = prune(robot, rho, cables)
    if reason is not None:  # a proof that the set holds no equilibrium: complete
        return DGPSubproblem(taut1, 0, 0, 0, 0, time.perf_counter() - t0, reason, generic_count=0), [], None
    if m == 1:
        return (*_solve_one_cable(robot, rho, cables[0]), None)
    line = rod_geometry(robot, cables) if rods else None
    # taut anchors on a line, G off it: tracked inside the subfamily of collinear anchors (dgp.collinear_anchors)
    frame = line_frame(robot, cables) if rods and line is None else None
    # not on a line: the interval filter reads the robot's doubles, which for a line collinear only in decimal are a
    # robot off the line, with other (isolated) equilibria (measured, twenty-sixth session: the flat plate with its
    # frame moved by (0.1, 0.2, 0.3), {2, 4} excluded while the decimal reading has an admissible family)
    if exclude and line is None and (frame is None or frame.reading == BINARY):
        sub = excluded_subproblem(robot, rho, cables)
        if sub is not None:
            return sub, [], None
    if line is not None:  # taut anchors and G on one line: families, solved as a rod (dgp.rod)
        fields = solve_rod_taut_set(robot, rho, cables, line, seed, options, TENSION_RTOL * robot.load)
        return DGPSubproblem(taut1, seconds=time.perf_counter() - t0, **fields), [], None
    if lines_dependent_everywhere(robot, cables):  # no isolated equilibrium: nothing for a homotopy to count
        return DGPSubproblem(taut1, 0, 0, 0, 0, time.perf_counter() - t0, LINES_DEPENDENT.format(m=m),
                             complete=False), [], None
    if not generic_path(m).exists():
        return DGPSubproblem(taut1, 0, 0, 0, 0, time.perf_counter() - t0,
                             f"no stored generic solution set for m = {m} (run derivations/solve_generic_dgp.py --m {m})",
                             complete=False), [], None
    fam = fast_family(m)
    # four cables on two parallelograms: tracked inside that subfamily (dgp.parallelogram), the cables in the order
    # of its diagonals (the roots' tensions are put back in the order of ``cables`` below)
    order = parallelogram_order(robot, cables) if rods and line is None and frame is None else None
    kind = None if order is None else parallelogram_kind(robot, order)
    flip = kind is not None and kind.startswith("squares") and flip_platform(robot, order)
    cables_in, cables = cables, cables if order is None else order
    frame_c = None if order is None else centred_frame(robot, order)
    target, c, L, Rw, cb = normalized_problem(robot, rho, cables, frame_c)
    start, fixed, relations = None, (), ()
    if frame is not None:  # the subfamily's own generic set, the line as the platform frame's x axis
        target, start, fixed = frame.target(target, m, cb, L), collinear_start(m), fixed_parameters(m)
    if order is not None:
        target, start = subfamily_target(target, kind, flip), parallelogram_start(kind)
        fixed, relations = parallelogram_fixed(kind=kind), parallelogram_relations(kind=kind)
    res, failed = _track(m, target, seed, gamma=False, options=options, start=start)
    real_target = CONJUGATE_ROOTS and np.all(np.imag(target) == 0)  # then conjugates of roots are roots
    if 0 < failed <= EXTENDED_MAX_FAILED:  # the failed paths again, every step in double-double (dgp.taut_extended)
        res, failed = rescue_in_taut_extended(m, res, *(start or _generic(m)), target, options or default_options(),
                                              real_target)  # (conjugates of its roots settle paths there: cheaper)
    # another route (gamma trick) when one or two paths failed, and the run with fewer failures is kept (each run is
    # a whole account).  Only a run with no failure completes the subproblem, and a new route seldom gives one: the
    # failures are mostly paths into the singular sets at infinity of the target itself, which every route meets.
    # Measured (ninth session, seed 000): re-run at up to 5 % failed paths, Tests 2 and 3 re-ran 37 subproblems
    # (a fifth of their tracking steps) and 5 came out complete, all of them with 1 or 2 failed paths at first
    # (5 of 18 such); none of the 19 with 3 to 10 failures did.
    route, other, other_route = (seed, False), None, None
    if 0 < failed <= RERUN_MAX_FAILED:
        res2, failed2 = _track(m, target, seed + 7919, gamma=True, options=options, start=start)
        other, other_route = res2, (seed + 7919, True)
        if failed2 < failed:
            res, failed, other, route, other_route = res2, failed2, res, other_route, route
        if failed:  # the other run's regular roots that no path of this one holds settle its failed paths
            res, failed = _settle_on_other_runs_roots(m, target, res, other, options)
        other_start = other_generic_instance(lambda p, s: _track(m, p, s, True, start=start)[0],
                                             *(start or _generic(m)), fixed=fixed, relations=relations) \
            if failed and OTHER_START else None
        if other_start is not None:  # ... and those of a run from another generic instance (dgp.other_start)
            res, failed = _settle_on_other_runs_roots(
                m, target, res, _track(m, target, seed, True, options, other_start)[0], options)
    if 0 < failed <= AUTO_RESCUE_MAX_FAILED and not (options is not None and options.retry_mpmath):
        res, failed = _rescue_last_failed_paths(m, target, res, *route, options, start)
        if failed and other is not None:  # the other route's failed paths rescued too: their roots settle these
            other, _ = _rescue_last_failed_paths(m, target, other, *other_route, options, start)
            res, failed = _settle_on_other_runs_roots(m, target, res, other, options, RESCUED_MAX_CONDITION)
    if failed and real_target:
        res, failed = settle_on_conjugates(res, default_options() if options is None else options)
    X = np.array([s.x for s in res.solutions]).reshape(-1, fam.n)
    finite = len(X)
    real = np.all(np.abs(X.imag) <= REAL_TOL * (1 + np.abs(X.real)), axis=1) if finite else np.zeros(0, bool)
    Xr = X[real].real
    Xr = _real_newton_polish(fam, Xr, target)

    def back(Y):  # roots in the subfamily's platform frame -> the normalized problem's
        return flip_roots_back(Y, m) if flip else Y if frame is None else frame.roots_back(Y, m, cb, L)

    Xr = back(Xr)
    tol = TENSION_RTOL * robot.load
    sols = []
    idx = list(cables)
    for x in world_coordinates(Xr, m, c, L, Rw, cb, robot.load):
        p, R, lam = decode(x, m)
        p, R, lam = p[0], R[0], lam[0]
        if np.max(np.abs(R.T @ R - np.eye(3))) > 1e-6 or np.linalg.det(R) <= 0:
            continue
        tau_S = lam * rho[idx]
        if np.any(tau_S < -tol):
            continue
        if not _slack_ok(robot, rho, cables, p, R):
            continue
        if np.any(np.abs(tau_S) <= tol):
            continue  # a solution of a smaller taut set: reported there (deduplication rule)
        tau = np.zeros(robot.n)
        tau[idx] = tau_S
        cls = _classify(robot, rho, cables, p, R, tau_S)
        sols.append(DGPSolution(taut1, p, R, tau, cls, reading=BINARY if frame is None else frame.reading))
    paths = res.track.paths
    outcomes = outcome_counts(paths)
    failures = dict(Counter(p.status for p in paths if p.status in FAILURES))
    retried = dict(Counter(p.retried for p in paths if p.retried))  # paths per kind of retry
    generic = len((start or _generic(m))[1])
    # singular endpoints count as isolated roots of some multiplicity only where they are not on a positive-dimensional
    # set (measured, twenty-fifth session: seed 002's {1, 5}, B1, B5 and G collinear, tracked by this homotopy, ended
    # its 24 paths on its families' circles labelled singular, and the subproblem counted as complete)
    singular = back(np.array([s.x for s in res.solutions if s.singular]).reshape(-1, fam.n))
    family = families_of_endpoints(robot, rho, cables, world_coordinates(singular, m, c, L, Rw, cb, robot.load),
                                   TENSION_RTOL * robot.load) if len(singular) else None
    # complete only once the regular endpoints are certified (_with_endpoint_certificates)
    sub = DGPSubproblem(taut1, len(paths), finite, int(np.sum(real)), len(sols), time.perf_counter() - t0,
                        outcomes=outcomes, failures=failures, complete=False, generic_count=generic, retried=retried,
                        family=family,
                        collinear_anchors=None if frame is None else frame.reading,
                        parallelogram=None if order is None else tuple(k + 1 for k in order), parallelogram_kind=kind)
    regular = back(np.array([s.x for s in res.solutions if not s.singular]).reshape(-1, fam.n))
    Z = world_coordinates(regular, m, c, L, Rw, cb, robot.load)
    if order is not None:  # the tensions in the order of the taut set as given
        Z = np.hstack([Z[:, :12], Z[:, 12:][:, [order.index(k) for k in cables_in]]])
    return sub, sols, Z


def _real_newton_polish(fam, Xr, target, iterations: int = 2):
    """Two real Newton updates of the real endpoints Xr (rows) at ``target``, each kept only on the rows whose
    residual it does not increase.  Why: on an ill-conditioned root a Newton update in double precision moves the
    point by up to cond x eps.  Measured (thirtieth session): a 6-cable robot built with tensions 1e6 times the load
    (benchmarks/bench_large_forces.py --m 6 --K 1e6, seed 363) has its equilibrium among the 40 proven endpoints to
    2e-16, and the unconditional polish moved its tensions by 0.2 %; its certificate then failed."""
    def residual(X):
        F, J = fam.evaluate_and_jacobian(X.astype(complex), target)
        return F.real, J.real, np.max(np.abs(F.real), axis=1)

    if not len(Xr):
        return Xr
    F, J, r = residual(Xr)
    for _ in range(iterations):
        with np.errstate(all="ignore"):
            try:
                step = np.linalg.solve(J, F[..., None])[..., 0]
            except np.linalg.LinAlgError:
                break
            Xn = Xr - step
            Fn, Jn, rn = residual(Xn)
            better = np.all(np.isfinite(Xn), axis=1) & (rn <= r)
        Xr = np.where(better[:, None], Xn, Xr)
        F, J, r = np.where(better[:, None], Fn, F), np.where(better[:, None, None], Jn, J), np.where(better, rn, r)
    return Xr


def _rescue_last_failed_paths(m, target, res, seed, gamma, options, start=None):
    """(``res``, the run of ``seed`` and ``gamma``, with its failed paths tracked once more in Study parameters in
    double-double wherever double precision fails, as ``retry_mpmath`` does for every subproblem: at most
    ``MP_RETRY_PATHS``; failed paths left).  For the subproblems that every other step leaves with at most
    ``AUTO_RESCUE_MAX_FAILED`` failed paths, and with ``retry_mpmath`` for every run (:func:`_track`).  Measured (twenty-second session): seed 002's taut set {2, 3, 6, 7},
    one phase-1 crawl in both routes, complete in 4.7 s instead of incomplete in 1.6 s.  ``start``: as in
    :func:`_track`."""
    p_gen, X_gen = _generic(m) if start is None else start
    opts = replace(default_options() if options is None else options, retry_mpmath=True)
    res, _ = retrack_failed_in_study(fast_family(m), res, m, p_gen, X_gen, target, seed, gamma, opts,
                                     failed_in_study=True)
    return res, sum(1 for p in res.track.paths if p.status in FAILURES)


def _settle_on_other_runs_roots(m, target, res, other, options, max_condition: float | None = None):
    """(``res`` with its failed paths settled on the regular roots of the ``other`` run (another route to the same
    target) that no path of ``res`` holds, failed paths left): :func:`.unheld_roots.settle_on_unheld_roots` with those
    roots as the estimates (each tested again by Newton's method at the target).  Why this accounts for paths: a
    regular root of the target is the limit of exactly one branch of each run, so a regular root that no settled path
    of ``res`` ends on is the limit of one of its failed paths (the module doc of :mod:`.unheld_roots`).  Measured
    (twenty-second session) on seed 002's 8-cable robot: the taut sets {3, 6, 7} and {2, 3, 6, 7} lose 3 and 1 paths
    to phase-1 crawls near Study's exceptional set in each run, not the same paths in both."""
    options = default_options() if options is None else options
    return _settle_on_unheld_roots(m, target, res, options,
                                   [p.endpoint for p in other.track.paths if p.status == SUCCESS], max_condition)


def _with_endpoint_certificates(robot, rho, items, proofs: dict | None = None) -> list:
    """The subproblems of ``items`` = [(0-based cables, DGPSubproblem, regular endpoints in world coordinates or
    None)] with their endpoint certificates (one vectorized Krawczyk run per m, :func:`cdpr_algebra.certificates.endpoints.certify_endpoints`)
    and ``complete`` decided: no failed path, outcomes adding up to the generic count, and every regular endpoint
    proven a distinct root (its box unique-root, disjoint from the others).  ``proofs``: a dict that receives, for
    the index k of each item with endpoints, which of them are so proven ((N,) bool)."""
    from cdpr_algebra.certificates.endpoints import certify_endpoints

    out = [sub for _, sub, _ in items]
    by_m = {}
    for k, (cables, _, Z) in enumerate(items):
        if Z is not None:
            by_m.setdefault(len(cables), []).append(k)
    for ks in by_m.values():
        # ball arithmetic (slow) only where it can complete a subproblem: not where paths failed
        balls = [items[k][1].failed_paths == 0 for k in ks]
        readings = [items[k][1].collinear_anchors or BINARY for k in ks]  # the robot read in decimal, or its doubles
        for k, (boxes, over) in zip(ks, certify_endpoints(robot, rho, [(items[k][0], items[k][2]) for k in ks],
                                                          balls, readings)):
            sub = items[k][1]
            ok, why = boxes.distinct(over)
            if proofs is not None:
                proofs[k] = ok
            certified = int(ok.sum())
            # a singular endpoint on a positive-dimensional set (sub.family, _solve_taut_set) leaves it incomplete
            complete = sub.accounted and certified == len(ok) == sub.outcomes["regular"] and sub.family is None
            family = families_of_endpoints(robot, rho, items[k][0], items[k][2][~ok], TENSION_RTOL * robot.load) \
                if not ok.all() else None
            family = family or sub.family
            out[k] = replace(sub, certified=certified, certified_real=int(np.sum(ok & boxes.real)), uncertified=why,
                             complete=complete, family=family)
    return out


def _merge(solutions, L):
    """One solution per pose (within 1e-7 L): the one with the fewest taut cables (first in subproblem order among
    equals); the others are kept as its ``alternatives`` (a pose held by several taut sets, e.g. every valid cable
    configuration of a robot with more than 6 cables at lengths of that pose)."""
    out = []
    for s in sorted(solutions, key=lambda s: len(s.taut)):
        same = [k for k, t in enumerate(out) if len(s.taut) > 1 and np.max(np.abs(s.position - t.position)) <= 1e-7 * L
                and np.max(np.abs(s.rotation - t.rotation)) <= 1e-7]
        if same:
            k = same[0]
            out[k] = replace(out[k], alternatives=out[k].alternatives + (s,))
            continue
        out.append(s)
    return out


def collected_solutions(solutions, L) -> tuple:
    """The admissible solutions of several subproblems as a DGP reports them: one per pose (:func:`_merge`, ``L``
    the cable geometry's scale, :attr:`Robot.cable_scale`: robot.size would grow with a far centre of mass), the most taut
    cables first, then by taut set and position."""
    sols = _merge(list(solutions), L)
    sols.sort(key=lambda s: (-len(s.taut), s.taut, tuple(np.round(s.position, 9))))
    return tuple(sols)


def dgp(robot, lengths=None, jobs: int | None = None, progress=None, max_m: int = 6, seed: int = 0,
        certify: bool = True, options=None, exclude: bool = True) -> "DGPResult":
    """Every admissible equilibrium of ``robot`` with cable ``lengths`` (default: the robot's).

    Subproblems: every taut set of m = 1 .. min(n, 6, max_m) cables, solved by ``jobs`` threads (default
    ``os.cpu_count()``; 1 = one after the other; the compiled tracker releases the GIL, so they track in
    parallel); ``progress(sub, done, total)`` is called in the calling thread after each finished subproblem; ``certify``: attach an interval certificate to every solution;
    ``options``: the homotopy's :class:`.homotopy.endgame.SolveOptions` (default: those of the module doc);
    ``exclude``: the interval exclusion test before tracking a taut set (module doc; False tracks every set).
    """
    t0 = time.perf_counter()
    rho, sets = lengths_and_taut_sets(robot, lengths, max_m)
    jobs = os.cpu_count() if jobs is None else max(1, int(jobs))
    results = {}
    heavy = [c for c in sets if len(c) >= 2 and generic_path(len(c)).exists()]
    done = 0
    if jobs > 1 and len(heavy) > 1:
        for m in sorted({len(c) for c in heavy}):  # build and load shared data once, before the threads start
            _generic(m)
            fast_family(m)
        light = [c for c in sets if c not in heavy]
        # threads: the compiled tracker and the compiled Krawczyk test release the GIL, so subproblems track and
        # certify in parallel without the cost of worker processes (start-up, pickling); the Python parts (endgame,
        # filtering) interleave.  Each task certifies its own endpoints (per taut set: with the compiled test a
        # batch costs per root, not per round), so no batch of certificates waits for the last set of its m
        # (seed 000 Test 3: per-m batches after the last set of each m left 0.3-0.6 s of one core idle at the end)
        with ThreadPoolExecutor(max_workers=min(jobs, len(heavy))) as ex:
            futs = {ex.submit(solve_taut_set, robot, rho, c, seed, certify, options, exclude): c
                    for c in sorted(heavy, key=lambda c: -len(c))}
            for c in light:
                results[c] = _solve_and_certify_solutions(robot, rho, c, seed, certify, options, exclude)
                done += 1
                if progress:
                    progress(results[c][0], done, len(sets))
            for f in as_completed(futs):
                c = futs[f]
                results[c] = (*f.result(), None)  # endpoints certified by the task
                done += 1
                if progress:
                    progress(results[c][0], done, len(sets))
    else:
        for c in sets:
            results[c] = _solve_and_certify_solutions(robot, rho, c, seed, certify, options, exclude)
            done += 1
            if progress:
                progress(results[c][0], done, len(sets))
    # the regular endpoints of the subproblems not certified yet (all of them when serial; the threads above certify
    # their own sets): one batch per m
    subs = tuple(_with_endpoint_certificates(robot, rho, [(c, *results[c][::2]) for c in sets]))
    sols = collected_solutions([s for c in sets for s in results[c][1]], robot.cable_scale)
    return DGPResult(sols, subs, time.perf_counter() - t0, seed, options)
