"""Trace test: a certificate that a solution set of a parametrized family is complete.

For a square family F(x; p) = 0 (n equations, n unknowns, parameters p entering polynomially) and a set W01
of solutions at generic parameters p0 (e.g. found by monodromy, :mod:`.monodromy`), the multiprojective trace
test of Leykin, Rodriguez and Sottile ("Trace test", Arnold Math. J. 4 (2018) 113-125) decides whether W01 is
every solution of the irreducible component(s) of the incidence variety that it samples.

Construction (the route of HomotopyContinuation.jl's ``verify_solution_completeness``):

1. a random complex direction q0 - p0 in parameter space gives the curve
   C = {(x, s) : F(x; p0 + s (q0 - p0)) = 0} in C^n x C; W01 x {0} = C intersected with {s = 0};
2. W10 = C intersected with {l(x) = 0} for a random affine form l(x) = l_1 x_1 + ... + l_n x_n + l_{n+1}:
   the solutions of :class:`TraceSliceSystem` [F(x; p0 + s (q0 - p0)); l(x)] in the unknowns (x, s) with the
   parameters l, found by monodromy (:func:`.monodromy.monodromy_solve`) from one point (a point of W01
   moved to s = 1, and a hyperplane through it moved to a random l), then re-solved at other random l and
   moved back, the union kept, until several such rounds add nothing (:func:`trace_witnesses`,
   :func:`complete_witnesses`);
3. the union S = (W01 x {0}) + W10 is the intersection of C with the member tau = 0 of the pencil
   {s l(x) = tau} (:class:`TracePencilSystem`); S is tracked to tau = +eps gamma and to tau = -eps gamma
   (gamma a random unit complex number) and the trace
   ``trace = (sum(S+) - sum(S)) - (sum(S) - sum(S-))`` is computed (:func:`compute_trace`).  The sum of the
   points of a complete intersection of the curve's sampled components with the pencil is an affine-linear
   function of tau, so the trace (a second difference) is zero up to rounding; for a proper subset
   (a point missing from W01 or from W10) it is not linear, and the trace is the second difference of the
   missing points, nonzero for generic data.

Every path's outcome is recorded (``outcomes``: counts of the engine's statuses per direction).  A path that
does not end at a regular, distinct point at tau = +-eps gamma makes the attempt lost: the pencil is tried
again with another gamma (``attempts``); if every attempt loses a path the verdict is ``undecided``, never
``passed``.  ``detection`` gives the smallest second difference of a single point (relative): the trace a set
with that one point missing would have, a measure of how clearly the test separates complete from incomplete.  A
trace passes only when it is below the tolerance AND ``separation`` (100) times below ``detection``: a trace that
vanishes no more clearly than a missing point's signal could not have failed, and is ``undecided``.

Numerics.  Points are compared by a duplicate test scaled by their condition number (:func:`distinct_points`):
monodromy's fixed relative 1e-8 counts an ill-conditioned point once per loop that finds it again.  Before the
sums, points of S, S+ and S- with a condition number above ``polish_condition`` are refined by Newton's method in
arbitrary precision (:func:`polish`): in double precision one point of condition 1e9 puts ~1e-7 of noise into a
trace whose single-point signals can be that small.  ``coordinates`` runs the test on the image of the curve in a
subset of the unknowns that separates the solutions (:func:`verify_solution_completeness`).

Points of very large norm.  W10 can hold points far out along the curve (DGP m = 4: one of norm 1.7e4, with
condition numbers of 1e11-1e14 on the way there); in affine coordinates the monodromy paths towards such a point fail
every time, the point is never found and the trace fails.  ``verify_solution_completeness(chart=seed)`` finds W10
on a random chart of projective space (:func:`coordinate_chart`, zero off y0 and the trace coordinates, so that
its hyperplanes are affine hyperplanes: :func:`slice_from_chart`), where such points are ordinary; and
:func:`compute_trace` tracks a pencil path lost in affine coordinates again on a chart (:class:`ChartPencilSystem`,
the same pencil; ``TraceTestOptions.chart_retrack``).  The sums are always taken in affine coordinates.

What this proves and what it does not: the trace certifies completeness for the components of C through the
points of W01 (monodromy from one seed samples one irreducible component); solutions on other components of
the family (e.g. a component where some unknown is identically zero) are outside its scope.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field, replace

import numpy as np

from .clusters import duplicate_groups, linked_groups
from .endgame import SolveOptions
from .homotopies import ParameterHomotopy
from .monodromy import MonodromyOptions, monodromy_solve, subfamily_point
from .results import STATUSES, SUCCESS
from .endgame import track_paths
from .trace_systems import (ChartPencilSystem, TracePencilSystem, TraceSliceSystem, _crandn,  # noqa: F401
                            chart_coordinates, coordinate_chart, curve_from_chart, curve_to_chart,
                            slice_from_chart, slice_to_chart)

__all__ = ["TraceSliceSystem", "TracePencilSystem", "TraceTestOptions", "TraceResult", "TraceTestResult",
           "distinct_points", "coinciding", "trace_witnesses", "complete_witnesses", "polish", "compute_trace",
           "verify_solution_completeness", "random_direction", "ChartPencilSystem", "chart_coordinates",
           "coordinate_chart", "slice_to_chart", "slice_from_chart"]


# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TraceTestOptions:
    """Settings of :func:`verify_solution_completeness` (defaults in brackets).

    * ``eps`` [0.1]: the pencil is tracked to tau = +-eps gamma (|gamma| = 1);
    * ``tol`` [1e-8]: largest relative trace accepted as zero (see :class:`TraceResult`);
    * ``attempts`` [3]: gammas tried when a pencil path is lost;
    * ``direction_scale`` [1.0]: q0 = p0 + direction_scale (1 + |p0|) z, z standard complex normal;
    * ``fixed_parameters`` [()]: indices of parameters where z = 0: the curve stays in that linear subfamily (the
      test of a subfamily's own solution set, as :class:`.monodromy.MonodromyOptions` finds it);
    * ``parameter_relations`` [()]: more linear relations of that subfamily (as
      :class:`.monodromy.MonodromyOptions`' own);
    * ``witness_loops_no_progress`` [5]: the first W10 monodromy runs in batches of this many loops and ends
      after a batch without a new distinct point (:func:`distinct_points`, conditioning-aware);
    * ``confirm_loops_no_progress`` [3]: the same for the re-solves at other random l;
    * ``confirmations`` [3]: rounds of :func:`complete_witnesses` in a row that must add nothing to W10 (at most
      ``max_confirm_tries`` [8] rounds);
    * ``max_loops`` [200]: cap of every monodromy run;
    * ``polish_condition`` [1e6]: points of S, S+ and S- with a larger condition number are refined in arbitrary
      precision before the sums (:func:`polish`; 0: every point, the trace's rounding noise then ~1e-15; None:
      never);
    * ``separation`` [100]: the trace passes only when a single missing point would change it by at least this
      many times the trace measured (``detection >= separation * relative``); a trace below ``tol`` that
      separates less is ``undecided`` (it would not notice a missing point);
    * ``solve`` [SolveOptions(retry_mpmath=False)]: tracking options of the monodromy loops and moves;
    * ``pencil`` [SolveOptions()]: tracking options of the pencil paths (arbitrary-precision retries included);
    * ``chart_retrack`` [20131]: seed of a random chart of projective space in which the pencil paths lost in
      affine coordinates are tracked again (:class:`ChartPencilSystem`: the same pencil, so a point of very large
      norm is an ordinary point there), their endpoints mapped back; None: never (systems whose equations are not
      all quadratic are never re-tracked so).
    """

    eps: float = 0.1
    tol: float = 1e-8
    attempts: int = 3
    direction_scale: float = 1.0
    fixed_parameters: tuple = ()
    parameter_relations: tuple = ()
    witness_loops_no_progress: int = 5
    confirm_loops_no_progress: int = 3
    confirmations: int = 3
    max_confirm_tries: int = 8
    max_loops: int = 200
    polish_condition: float | None = 1e6
    separation: float = 100.0
    solve: SolveOptions = field(default_factory=lambda: SolveOptions(retry_mpmath=False))
    pencil: SolveOptions = field(default_factory=SolveOptions)
    chart_retrack: int | None = 20131

    def to_dict(self) -> dict:
        d = {k: v for k, v in asdict(self).items() if k not in ("solve", "pencil")}
        d["solve"] = self.solve.to_dict()
        d["pencil"] = self.pencil.to_dict()
        return d


@dataclass(frozen=True)
class TraceResult:
    """One evaluation of the trace.

    * ``trace``: the (n + 1)-vector (sum(S+) - sum(S)) - (sum(S) - sum(S-));
    * ``scale``: max over the coordinates of max(|sum(S+) - sum(S)|, |sum(S) - sum(S-)|, 1), the size of the
      first differences (HomotopyContinuation.jl's normalization, with a common scale);
    * ``relative``: max_k |trace_k| / scale; ``passed`` when every path ended regular and distinct and
      ``relative <= tol`` and ``detection >= required_separation * relative``; ``status``: "passed", "failed"
      (trace not zero) or "undecided" (a path lost, or a trace that does not separate: ``reason``);
    * ``detection``: min over the points of S of max_k |y_k(+) - 2 y_k(0) + y_k(-)| / scale: the relative trace
      of S with that single point removed (``detection_median``: the median); ``separation`` = detection /
      relative, how many times the measured trace a single missing point would add;
    * ``outcomes``: per attempt and direction, counts of path statuses (plus ``duplicate`` endpoints);
    """

    status: str
    trace: np.ndarray
    relative: float
    scale: float
    tol: float
    detection: float
    detection_median: float
    gamma: complex
    eps: float
    points: int
    outcomes: list
    seconds: float
    endpoints_plus: np.ndarray | None = None
    endpoints_minus: np.ndarray | None = None
    required_separation: float = 100.0
    reason: str = ""

    @property
    def passed(self) -> bool:
        return self.status == "passed"

    @property
    def separation(self) -> float:
        return float(self.detection / self.relative) if self.relative > 0 else float("inf")

    def to_dict(self) -> dict:
        return {"status": self.status, "trace": {"re": np.real(self.trace).tolist(), "im": np.imag(self.trace).tolist()},
                "trace_norm": float(np.max(np.abs(self.trace))) if self.trace.size else None,
                "relative": self.relative, "scale": self.scale, "tol": self.tol, "detection": self.detection,
                "detection_median": self.detection_median, "gamma": {"re": self.gamma.real, "im": self.gamma.imag},
                "eps": self.eps, "points": self.points, "outcomes": self.outcomes, "seconds": self.seconds,
                "separation": self.separation if np.isfinite(self.relative) else None,
                "required_separation": self.required_separation, "reason": self.reason}


@dataclass(frozen=True)
class TraceTestResult:
    """A full trace test: q0, l, the additional witnesses W10 and how they were found, and the trace."""

    trace: TraceResult
    q0: np.ndarray
    l: np.ndarray
    W10: np.ndarray
    witnesses: dict
    seed: int
    seconds: float
    coordinates: np.ndarray | None = None
    chart: np.ndarray | None = None  # the chart of :func:`coordinate_chart` W10 was found on (None: affine)

    @property
    def status(self) -> str:
        return self.trace.status

    @property
    def passed(self) -> bool:
        return self.trace.passed


def random_direction(p0, rng, scale: float = 1.0, fixed=(), relations=()):
    """q0 = p0 + scale (1 + |p0|) z, z standard complex normal (componentwise), zero at the indices ``fixed``
    (and, with ``relations``, projected onto the subfamily: :func:`.monodromy.subfamily_point`)."""
    p0 = np.asarray(p0, dtype=complex)
    return subfamily_point(p0, scale * (1 + np.abs(p0)) * _crandn(rng, *p0.shape), fixed, relations)


def _track(system, X, p_from, p_to, options, seed):
    """Track rows X of ``system`` from parameters p_from (t = 1) to p_to (t = 0); the PathResults."""
    X = np.asarray(X, dtype=complex).reshape(-1, system.n)
    if not len(X):
        return []
    hom = ParameterHomotopy(system, np.atleast_1d(p_from), np.atleast_1d(p_to))
    return list(track_paths(hom, X, options, seed=seed).paths)


def _regular_distinct(paths, tol):
    """(endpoints, outcome counts, all regular and distinct) of a list of PathResults."""
    counts = {s: 0 for s in STATUSES}
    for p in paths:
        counts[p.status] = counts.get(p.status, 0) + 1
    X = np.array([p.endpoint for p in paths])
    ok = all(p.status == SUCCESS for p in paths)
    dup = duplicate_groups(X, tol) if ok and len(X) > 1 else []
    counts["duplicate"] = int(sum(len(g) for g in dup))
    return X, counts, ok and not dup


def _coordinates(system, coordinates, W01):
    """The coordinates of x the trace test works in (all by default), checked to separate the points of W01."""
    cs = np.arange(system.n) if coordinates is None else np.asarray(coordinates, dtype=int)
    if len(np.unique(cs)) != len(cs) or cs.min() < 0 or cs.max() >= system.n:
        raise ValueError("coordinates must be distinct indices of unknowns")
    P = np.asarray(W01, dtype=complex).reshape(-1, system.n)[:, cs]
    if duplicate_groups(P, 1e-6):
        raise ValueError("the chosen coordinates do not separate the points of W01: the projection is not injective")
    return cs


def _close_groups(system, parameters, X, floor, digits_lost, polish_condition):
    """The points X refined (Newton; points of cond > ``polish_condition`` in arbitrary precision where the system
    allows it) and grouped by the conditioning-aware duplicate test of :func:`distinct_points`.  Returns
    (refined points, condition numbers, groups (lists of row indices), number polished, residuals)."""
    from .refinement import refine

    p = np.asarray(parameters, dtype=complex)
    Xr, _, res, cond, _ = refine(ParameterHomotopy(system, p, p), X, 0.0)
    cond = np.where(np.isfinite(cond), cond, 1e16)
    tol = np.maximum(floor, digits_lost * 2.2e-16 * cond)
    polished = 0
    if polish_condition is not None and hasattr(system, "mp_functions"):
        idx = np.flatnonzero(cond > polish_condition)
        if idx.size:
            Xr, ok = _mp_newton(system, p, Xr, idx)
            tol[idx[ok]] = floor
            polished = int(ok.sum())
    scale = 1 + np.max(np.abs(Xr), axis=1)
    pi, pj = [], []
    for i in range(len(Xr) - 1):
        d = np.max(np.abs(Xr[i + 1:] - Xr[i]), axis=1) / np.maximum(scale[i + 1:], scale[i])
        close = np.flatnonzero(d <= np.maximum(tol[i + 1:], tol[i])) + i + 1
        pi += [i] * len(close)
        pj += close.tolist()
    return Xr, cond, linked_groups(len(Xr), pi, pj), polished, res


def distinct_points(system, parameters, X, floor: float = 1e-8, digits_lost: float = 100.0,
                    polish_condition: float | None = 1e6):
    """Distinct solutions among points X of ``system`` at ``parameters``, with a duplicate test that accounts for
    conditioning: after Newton refinement (:func:`.refinement.refine`), two points are one solution when they are
    closer (max-norm, relative to 1 + |x|) than max(floor, digits_lost * 2.2e-16 * cond), cond being the scaled
    condition number of dF/dx at either point (the accuracy double precision allows there).  (A fixed relative
    tolerance such as monodromy's 1e-8 counts an ill-conditioned solution, cond ~ 1e10, found again around each
    loop, many times.)  Points with cond > ``polish_condition`` are first refined in arbitrary precision
    (:func:`_mp_newton`, where the system offers ``mp_functions``); those that converge are accurate to rounding
    and are compared with ``floor`` alone, so two distinct ill-conditioned solutions closer than the conditioning
    allowance are not merged.  Returns (distinct refined points, the best-conditioned of each group; record of the
    merged groups)."""
    X = np.asarray(X, dtype=complex).reshape(-1, system.n)
    if not len(X):
        return X, {"groups": [], "max_condition": None}
    Xr, cond, groups, polished, res = _close_groups(system, parameters, X, floor, digits_lost, polish_condition)
    scale = 1 + np.max(np.abs(Xr), axis=1)
    keep = sorted(g[int(np.argmin(cond[g]))] for g in groups)
    merged = [{"size": len(g), "norm": float(np.max(scale[g]) - 1), "condition": float(np.max(cond[g])),
               "spread": float(np.max(np.abs(Xr[g] - Xr[g[0]])) / np.max(scale[g]))}
              for g in groups if len(g) > 1]
    rule = f"relative distance <= max({floor:g}, {digits_lost:g} * 2.2e-16 * cond)"
    if polish_condition is not None:
        rule += f"; {floor:g} for points of cond > {polish_condition:g} refined in arbitrary precision"
    return Xr[keep], {"rule": rule, "groups": merged, "max_condition": float(np.max(cond)),
                      "max_residual": float(np.max(res)), "polished": polished}


def coinciding(system, parameters, X, floor: float = 1e-8, digits_lost: float = 100.0,
               polish_condition: float | None = 1e6) -> np.ndarray:
    """Mask of the points X that coincide with another one of X (the test of :func:`distinct_points`): endpoints
    of paths from distinct start points that coincide mean a path jumped."""
    X = np.asarray(X, dtype=complex).reshape(-1, system.n)
    mask = np.zeros(len(X), dtype=bool)
    if len(X) < 2:
        return mask
    _, _, groups, _, _ = _close_groups(system, parameters, X, floor, digits_lost, polish_condition)
    for g in groups:
        if len(g) > 1:
            mask[list(g)] = True
    return mask


def trace_witnesses(system, p0, W01, q0=None, seed: int = 0, options: TraceTestOptions | None = None,
                    verbose: bool = False, coordinates=None, start=None):
    """W10 = C cut by l(x) = 0 for a random l (module doc, step 2).  Returns (W10, q0, l, record dict).
    ``coordinates``: see :func:`verify_solution_completeness`.  ``start``: points of W10 already known (from an
    earlier run with the same seed, options and coordinates, hence the same q0), alone (they lie on the first
    hyperplane l drawn from the seed) or as a pair (points, the hyperplane l they lie on): the first monodromy
    starts from them instead of from one point of W01 (each must solve the slice system at l; ValueError otherwise).
    How W10 was found does not enter the certificate: the trace decides whether it is complete."""
    o = options or TraceTestOptions()
    cs = _coordinates(system, coordinates, W01)
    k1 = len(cs) + 1
    rng = np.random.default_rng(seed)
    t0 = time.perf_counter()
    p0 = np.asarray(p0, dtype=complex)
    W01 = np.asarray(W01, dtype=complex).reshape(-1, system.n)
    if q0 is None:
        q0 = random_direction(p0, rng, o.direction_scale, o.fixed_parameters, o.parameter_relations)
    q0 = np.asarray(q0, dtype=complex)
    slice_ = TraceSliceSystem(system, p0, q0 - p0, cs)
    record = {"moves": [], "monodromy": []}
    if start is not None:  # the hyperplanes drawn as below (l1 unused), so l is that of the earlier run
        rng.random(len(cs))
        l0 = _crandn(rng, k1)
        if isinstance(start, tuple):
            start, l0 = start[0], np.asarray(start[1], dtype=complex)
        Y = np.asarray(start, dtype=complex).reshape(-1, slice_.n)
        D, merged = distinct_points(slice_, l0, Y)
        res = np.max(np.abs(slice_.evaluate(D, l0)), axis=1) / (1 + np.max(np.abs(D), axis=1))
        if not len(D) or not np.all(res <= 1e-8):
            raise ValueError(f"start points off the slice at l (largest relative residual {np.max(res):.1e})")
        record["moves"].append({"from": "start points given (an earlier run, same seed)", "paths": int(len(Y)),
                                "distinct": int(len(D)), "max_relative_residual": float(np.max(res))})
        W, l0, rec = complete_witnesses(slice_, l0, D, o, seed=seed, verbose=verbose, first=True)
        record["moves"] += rec["moves"]
        record["monodromy"] += rec["monodromy"]
        record.update({k: v for k, v in rec.items() if k not in ("moves", "monodromy")})
        record["seconds"] = time.perf_counter() - t0
        return W, q0, np.asarray(l0), record
    # a point of C at s = 1: a point of W01 moved from p0 to q0 (the first that arrives regular)
    y1 = None
    for i in range(len(W01)):
        paths = _track(system, W01[i:i + 1], p0, q0, o.solve, seed)
        record["moves"].append({"from": "W01", "index": i, "status": paths[0].status})
        if paths[0].status == SUCCESS:
            y1 = np.concatenate([paths[0].endpoint, [1.0]])
            break
    if y1 is None:
        raise RuntimeError("no point of W01 could be moved to the direction point q0")
    # a hyperplane through it, then a generic one
    l1 = np.exp(2j * np.pi * rng.random(len(cs)))
    l1 = np.concatenate([l1, [-(l1 @ y1[cs])]])
    l0 = _crandn(rng, k1)
    paths = _track(slice_, y1[None, :], l1, l0, o.solve, seed)
    record["moves"].append({"from": "hyperplane through the moved point", "status": paths[0].status})
    if paths[0].status != SUCCESS:
        raise RuntimeError(f"the first point of W10 could not be moved to a generic l ({paths[0].status})")

    W, l0, rec = complete_witnesses(slice_, l0, paths[0].endpoint[None, :], o, seed=seed, verbose=verbose, first=True)
    record["moves"] += rec["moves"]
    record["monodromy"] += rec["monodromy"]
    record.update({k: v for k, v in rec.items() if k not in ("moves", "monodromy")})
    record["seconds"] = time.perf_counter() - t0
    return W, q0, np.asarray(l0), record


def complete_witnesses(slice_, l, W, options: TraceTestOptions | None = None, seed: int = 0, verbose: bool = False,
                       first: bool = False):
    """Grow the witness set W of ``slice_`` (a :class:`TraceSliceSystem`) at the hyperplane l by monodromy.

    With ``first``, a monodromy run at l from W (``witness_loops_no_progress``; every monodromy run here goes in
    batches of that many loops and stops after a batch that adds no distinct point).  Then rounds: W is moved to
    another random hyperplane k, completed there by monodromy (``confirm_loops_no_progress``), and the result is
    moved back to l and united with W (distinct points by :func:`distinct_points`); the points a move loses
    (ill-conditioned ones fail now and then) stay in W.  When the other hyperplane holds more points than the
    union (the moves back lose points that are ill-conditioned at l), it becomes l: every random hyperplane is as
    generic as the first, and the trace decides completeness wherever W was found.  The rounds stop when
    ``confirmations`` rounds in a row add nothing (at most ``max_confirm_tries``).  Returns (W, the hyperplane l
    it lies on, record dict; ``hyperplane_changes``: the rounds that changed l)."""
    o = options or TraceTestOptions()
    rng = np.random.default_rng(seed + 1)
    l = np.asarray(l, dtype=complex)
    record = {"moves": [], "monodromy": [], "union_counts": [], "hyperplane_changes": []}

    def mono(lk, X, loops_np, s):
        # monodromy in batches of loops_np loops, progress measured in distinct points (distinct_points) after
        # each batch: monodromy's own fixed duplicate test re-adds an ill-conditioned point (cond ~1e9) found
        # again around a loop as a new one, so its no-progress stop may never come (m = 4: 5 points of condition
        # 1e9-6e9 came back 37 times in 34 loops, one more every loop or two); stop after a batch that adds none
        t0 = time.perf_counter()
        D, merged = distinct_points(slice_, lk, X)
        start = int(len(D))
        batches, loops, paths, b, stopped = [], 0, 0, 0, "max_loops"
        while loops < o.max_loops:
            r = monodromy_solve(slice_, parameters=lk, solutions=D, seed=s + 10007 * b,
                                options=MonodromyOptions(max_loops_no_progress=loops_np,
                                                         max_loops=min(loops_np, o.max_loops - loops),
                                                         initial_loops=1, solve=o.solve))
            Dn, merged = distinct_points(slice_, lk, r.solutions)
            batches.append({**r.to_dict(), "count_raw": int(len(r.solutions)), "count": int(len(Dn)),
                            "merged": merged["groups"]})
            loops, paths, b = loops + r.loops, paths + r.paths_tracked, b + 1
            grew = len(Dn) > len(D)
            D = Dn
            if verbose:
                print(f"  W10 monodromy batch {b}: {r.summary_line()}; {len(D)} distinct", flush=True)
            if not grew:
                stopped = "no_progress"
                break
        record["monodromy"].append({"count": int(len(D)), "loops": loops, "paths_tracked": paths,
                                    "seconds": time.perf_counter() - t0, "seed": s, "stopped_by": stopped,
                                    "start_points": len(np.atleast_2d(X)), "start_distinct": start,
                                    "loops_per_batch": loops_np, "batches": batches})
        if verbose:
            print(f"  W10 monodromy: {len(D)} distinct ({loops} loops, {paths} paths, "
                  f"{time.perf_counter() - t0:.0f} s, stopped by {stopped})", flush=True)
        return D

    def move(X, la, lb, what, s, detours: int = 2):
        # paths that fail on the straight segment la -> lb (ill-conditioned points now and then), or whose endpoints
        # coincide (a path jumped: the start points are distinct), are tracked again along another route, la -> a
        # random hyperplane -> lb, with 100x tighter steps (``detours`` routes at most)
        X = np.asarray(X, dtype=complex).reshape(-1, slice_.n)
        paths = _track(slice_, X, la, lb, o.solve, s)
        ok = np.array([p.status == SUCCESS for p in paths], dtype=bool)
        E = np.array([p.endpoint for p in paths]).reshape(-1, slice_.n)
        okidx = np.flatnonzero(ok)
        jumped = okidx[coinciding(slice_, lb, E[okidx])] if okidx.size else okidx
        ok[jumped] = False
        Y = [E[i] for i in np.flatnonzero(ok)]
        rec = {"from": what, "paths": len(paths), "success": int(ok.sum()), "coinciding": int(len(jumped)),
               "detours": []}
        todo = X[~ok]
        tight = replace(o.solve, tracker=o.solve.tracker.tightened(100.0))
        for d in range(detours):
            if not len(todo):
                break
            mid = _crandn(rng, slice_.m)
            p1 = _track(slice_, todo, la, mid, tight, s + 31 * (d + 1))
            ok1 = np.array([p.status == SUCCESS for p in p1], dtype=bool)
            Z = np.array([p.endpoint for p in p1 if p.status == SUCCESS]).reshape(-1, slice_.n)
            p2 = _track(slice_, Z, mid, lb, tight, s + 31 * (d + 1) + 1)
            ok2 = np.array([p.status == SUCCESS for p in p2], dtype=bool)
            Y += [p.endpoint for p in p2 if p.status == SUCCESS]
            rec["detours"].append({"paths": int(len(todo)), "success": int(ok2.sum())})
            done = np.zeros(len(todo), dtype=bool)
            done[np.flatnonzero(ok1)[ok2]] = True
            todo = todo[~done]
        rec["failed"] = int(len(todo))
        record["moves"].append(rec)
        return np.array(Y).reshape(-1, slice_.n)

    W = np.asarray(W, dtype=complex).reshape(-1, slice_.n)
    if first:
        W = mono(l, W, o.witness_loops_no_progress, seed)
    record["union_counts"].append(int(len(W)))
    stable = tries = 0
    while stable < o.confirmations and tries < o.max_confirm_tries:
        tries += 1
        k = _crandn(rng, slice_.m)
        X = move(W, l, k, "W10 to another l", seed + tries)
        if not len(X):
            stable = 0
            continue
        R = mono(k, X, o.confirm_loops_no_progress, seed + 100 + tries)
        back = move(R, k, l, "back to l", seed + 200 + tries)
        U, _ = distinct_points(slice_, l, np.concatenate([W, back]))
        adopt = len(R) > len(U)
        if verbose:
            print(f"  W10 round {tries}: {len(R)} at another l, {len(back)} moved back, union {len(U)} "
                  f"(was {len(W)})" + ("; the other l holds more: it becomes l" if adopt else ""), flush=True)
        if adopt:  # the moves back lose points that the other hyperplane holds (ill-conditioned at l): go on there
            l, W, stable = k, R, 0
            record["hyperplane_changes"].append(tries)
        else:
            stable = 0 if len(U) > len(W) else stable + 1
            if len(U) > len(W):
                W = U
        record["union_counts"].append(int(len(W)))
    record.update({"count": int(len(W)), "stable_rounds": stable, "rounds": tries})
    return W, l, record


def _mp_newton(system, parameters, Y, idx, dps: int = 40, iterations: int = 8):
    """Points Y[idx] refined by Newton's method in arbitrary precision (mpmath, ``dps`` digits, the system's
    ``mp_functions``), rounded back to double.  Returns (Y with them replaced, converged mask over idx): converged
    when the last update is below 10^-(dps - 5) relative (a simple root; Newton stalls at a multiple one).  The
    Newton update is solved by python-flint (:func:`_flint_newton_update`)."""
    import mpmath
    from flint import ctx

    Y = np.array(Y, dtype=complex, copy=True)
    ok = np.zeros(len(idx), dtype=bool)
    mF, mJ, _ = system.mp_functions()
    with mpmath.workdps(dps), ctx.workprec(mpmath.mp.prec + 8):
        pm = [mpmath.mpc(complex(c)) for c in np.asarray(parameters, dtype=complex)]
        for k, i in enumerate(idx):
            y = mpmath.matrix([mpmath.mpc(complex(c)) for c in Y[i]])
            for _ in range(iterations):
                d = _flint_newton_update(mJ(y, pm), mF(y, pm))
                if d is None:  # singular Jacobian
                    break
                y = y + d
                if mpmath.norm(d) <= mpmath.mpf(10) ** (-(dps - 5)) * (1 + mpmath.norm(y)):
                    ok[k] = True
                    break
            Y[i] = np.array([complex(c) for c in y])
    return Y, ok


def _flint_newton_update(J, F):
    """-J^{-1} F for an mpmath matrix J and vector F, solved by python-flint in midpoint arithmetic at its working
    precision (``acb_mat.solve(..., algorithm="approx")``: Newton's update needs no error bound), as an mpmath vector;
    None when J is singular.  Measured: 10x faster than ``mpmath.lu_solve`` on 20 x 20 at 40 digits, conversions
    included (mpmath's elimination took 17.6 s of the 41 s of the m = 4 witness test under the profiler)."""
    import mpmath
    from flint import acb, acb_mat

    n = J.rows
    A = acb_mat([[acb(J[r, c]) for c in range(J.cols)] for r in range(n)])
    B = acb_mat([[acb(-F[r])] for r in range(n)])
    try:
        X = A.solve(B, algorithm="approx")
    except ZeroDivisionError:
        return None
    out = []
    for r in range(n):
        z = X[r, 0]
        if not (z.real.is_finite() and z.imag.is_finite()):
            return None
        re, im = z.real.mid().man_exp(), z.imag.mid().man_exp()
        out.append(mpmath.mpc(mpmath.mpf((int(re[0]), int(re[1]))), mpmath.mpf((int(im[0]), int(im[1])))))
    return mpmath.matrix(out)


def polish(system, parameters, Y, threshold: float = 1e6, dps: int = 40, iterations: int = 8):
    """Points Y of ``system`` at ``parameters`` whose scaled condition number exceeds ``threshold`` refined by
    Newton's method in arbitrary precision (mpmath, ``dps`` digits; the system's ``mp_functions``), then rounded to
    double: their error drops from ~ cond * 1e-16 to the rounding of their coordinates.  The trace is a sum of
    hundreds of points, and one point of condition 1e9 would otherwise put ~1e-7 of noise into it.  Returns
    (Y, number of points refined, largest condition number)."""
    from .refinement import refine

    Y = np.array(Y, dtype=complex, copy=True).reshape(-1, system.n)
    if not len(Y):
        return Y, 0, 0.0
    p = np.asarray(parameters, dtype=complex)
    _, _, _, cond, _ = refine(ParameterHomotopy(system, p, p), Y, 0.0, max_iter=0)
    cond = np.where(np.isfinite(cond), cond, np.inf)
    idx = np.flatnonzero(cond > threshold)
    if not idx.size or not hasattr(system, "mp_functions"):
        return Y, 0, float(np.max(cond))
    Y, _ = _mp_newton(system, p, Y, idx, dps, iterations)
    return Y, int(idx.size), float(np.max(cond))


def _retrack_in_chart(system, p0, q0, l, cs, S, paths, tau, o, seed):
    """The pencil paths of ``paths`` (from the rows of S to tau) that were lost, tracked again on a random chart
    (``o.chart_retrack``, :class:`ChartPencilSystem`) and, when they end regular at a finite point, replaced by
    that (mapped back to affine coordinates, ``retried`` = "chart").  Returns (paths, lost, rescued)."""
    lost = [i for i, p in enumerate(paths) if p.status != SUCCESS]
    degrees = getattr(system, "degrees", None)
    if not lost or o.chart_retrack is None or degrees is None or any(d != 2 for d in degrees):
        return paths, len(lost), 0
    from .projective import HomogenizedQuadratic, _chart

    hom = HomogenizedQuadratic(system, _chart(system.n, o.chart_retrack))
    v = np.asarray(q0, dtype=complex) - np.asarray(p0, dtype=complex)
    cp = ChartPencilSystem(hom, p0, v, l, cs)
    out, rescued = list(paths), 0
    for i, p in zip(lost, _track(cp, curve_to_chart(S[lost], hom.c), [0.0], [tau], o.pencil, seed)):
        if p.status != SUCCESS:
            continue
        x, ratio = curve_from_chart(p.endpoint[None, :])
        if ratio[0] > 1e-12:
            out[i] = replace(p, index=paths[i].index, endpoint=x[0], retried="chart")
            rescued += 1
    return out, len(lost), rescued


def compute_trace(system, p0, q0, l, W01, W10, options: TraceTestOptions | None = None, seed: int = 0,
                  gamma=None, keep_endpoints: bool = False, coordinates=None) -> TraceResult:
    """Track S = (W01 x {0}) + W10 along the pencil s l(x) = tau to +-eps gamma and evaluate the trace
    (module doc, step 3) over the ``coordinates`` of x (all by default) and s.  ``gamma`` (unit complex) is
    drawn from ``seed`` when None; a lost path makes the attempt count as lost and another gamma is drawn
    (``options.attempts`` in all)."""
    o = options or TraceTestOptions()
    cs = _coordinates(system, coordinates, W01)
    keep = np.concatenate([cs, [system.n]])
    rng = np.random.default_rng(seed + 7919)
    t0 = time.perf_counter()
    W01 = np.asarray(W01, dtype=complex).reshape(-1, system.n)
    W10 = np.asarray(W10, dtype=complex).reshape(-1, system.n + 1)
    S = np.concatenate([np.concatenate([W01, np.zeros((len(W01), 1), dtype=complex)], axis=1), W10], axis=0)
    pencil = TracePencilSystem(system, p0, np.asarray(q0, dtype=complex) - np.asarray(p0, dtype=complex), l, cs)
    outcomes = []
    for attempt in range(o.attempts):
        g = complex(gamma) if (gamma is not None and attempt == 0) else complex(np.exp(2j * np.pi * rng.random()))
        ends, ok = [], True
        rec = {"attempt": attempt, "gamma": {"re": g.real, "im": g.imag}}
        for sign, name in ((1.0, "plus"), (-1.0, "minus")):
            paths = _track(pencil, S, [0.0], [sign * o.eps * g], o.pencil, seed + attempt)
            paths, lost, rescued = _retrack_in_chart(system, p0, q0, l, cs, S, paths, sign * o.eps * g, o,
                                                     seed + attempt)
            X, counts, good = _regular_distinct(paths, o.pencil.duplicate_tol)
            rec[name] = counts
            if lost:
                rec.setdefault("chart_retracks", {})[name] = {"lost_in_affine": lost, "regular_in_chart": rescued}
            ends.append(X)
            ok &= good
        outcomes.append(rec)
        if not ok:
            continue
        Sp, Sm = ends
        # ill-conditioned points refined in arbitrary precision (their double-precision error would be noise)
        polished = {}
        if o.polish_condition is not None:
            S, polished["start"], c0 = polish(pencil, [0.0], S, o.polish_condition)
            Sp, polished["plus"], c1 = polish(pencil, [o.eps * g], Sp, o.polish_condition)
            Sm, polished["minus"], c2 = polish(pencil, [-o.eps * g], Sm, o.polish_condition)
            polished["max_condition"] = max(c0, c1, c2)
        rec["polished"] = polished
        # the trace in the coordinates of the curve's image (x_cs, s); the other unknowns are not linear there
        Sp, Sm, S = Sp[:, keep], Sm[:, keep], S[:, keep]
        s0, sp_, sm_ = S.sum(axis=0), Sp.sum(axis=0), Sm.sum(axis=0)
        trace = (sp_ - s0) - (s0 - sm_)
        scale = float(max(np.max(np.abs(sp_ - s0)), np.max(np.abs(s0 - sm_)), 1.0))
        rel = float(np.max(np.abs(trace)) / scale)
        d2 = np.max(np.abs(Sp - 2 * S + Sm), axis=1) / scale
        status, reason = _verdict(rel, float(np.min(d2)), o)
        return TraceResult(status=status, trace=trace, relative=rel, scale=scale,
                           tol=o.tol, detection=float(np.min(d2)), detection_median=float(np.median(d2)), gamma=g,
                           eps=o.eps, points=len(S), outcomes=outcomes, seconds=time.perf_counter() - t0,
                           endpoints_plus=Sp if keep_endpoints else None,
                           endpoints_minus=Sm if keep_endpoints else None, required_separation=o.separation,
                           reason=reason)
    return TraceResult(status="undecided", trace=np.full(len(keep), np.nan + 0j), relative=float("nan"),
                       scale=float("nan"), tol=o.tol, detection=float("nan"), detection_median=float("nan"),
                       gamma=complex(np.nan), eps=o.eps, points=len(S), outcomes=outcomes,
                       seconds=time.perf_counter() - t0, required_separation=o.separation,
                       reason=f"a pencil path was lost in each of {o.attempts} attempt(s)")


def _verdict(relative: float, detection: float, o: TraceTestOptions) -> tuple[str, str]:
    """(status, reason) of a trace whose paths all ended regular: "failed" above ``o.tol``; "passed" when a single
    missing point would also show, ``detection >= o.separation * relative``; "undecided" otherwise (the trace is
    zero to the tolerance but no clearer than one point's second difference: it could not have failed)."""
    if relative > o.tol:
        return "failed", f"relative trace {relative:.1e} > tol {o.tol:.0e}"
    if detection < o.separation * relative:
        return "undecided", (f"the trace {relative:.1e} does not separate: a single missing point would add only "
                             f"{detection:.1e} (< {o.separation:g} times the trace); refine the points "
                             f"(polish_condition=0) or widen the pencil (eps)")
    return "passed", ""



def verify_solution_completeness(system, p0, W01, seed: int = 0, options: TraceTestOptions | None = None,
                                 verbose: bool = False, coordinates=None, start=None,
                                 chart: int | None = None) -> TraceTestResult:
    """Trace test of the solution set W01 of ``system`` at parameters p0 (module doc): W10 by
    :func:`trace_witnesses`, then :func:`compute_trace`.  ``result.status`` is "passed", "failed" or
    "undecided".

    ``coordinates`` (indices of unknowns, all by default): run the test on the image C' of the curve under
    (x, s) -> (x_coordinates, s): hyperplanes l and the trace in those coordinates only.  Valid when the
    projection separates the solutions (checked on W01; then C -> C' is birational and witness sets
    correspond); useful when some unknowns (e.g. ones determined linearly by the others) have poles along the
    curve and so raise its degree, and hence the size of W10.  ``start``: known points of W10 (see
    :func:`trace_witnesses`; with ``chart``, a pair (points, the hyperplane l they lie on)).

    ``chart`` (a seed; systems whose equations are all quadratic): W10 is found on a random chart of projective
    space (:func:`coordinate_chart`, :class:`.projective.HomogenizedQuadratic`), where witness points of very
    large norm are ordinary points (DGP m = 4: a point of norm 1.7e4 that monodromy in affine coordinates never
    reached, and without which the trace failed), then mapped back (:func:`slice_from_chart`); the trace is
    computed in affine coordinates as always."""
    o = options or TraceTestOptions()
    t0 = time.perf_counter()
    cs = _coordinates(system, coordinates, W01)
    c = None
    if chart is None:
        W10, q0, l, rec = trace_witnesses(system, p0, W01, seed=seed, options=o, verbose=verbose,
                                          coordinates=coordinates, start=start)
    else:
        from .projective import HomogenizedQuadratic, to_chart

        c = coordinate_chart(system.n, cs, chart)
        st = None
        if start is not None:
            if not isinstance(start, tuple):
                raise ValueError("with a chart, start must be a pair (points, the hyperplane l they lie on)")
            st = slice_to_chart(start[0], start[1], c)
        W10c, q0, lc, rec = trace_witnesses(HomogenizedQuadratic(system, c), p0, to_chart(W01, c), seed=seed,
                                            options=o, verbose=verbose, coordinates=chart_coordinates(cs),
                                            start=st)
        W10, l = slice_from_chart(W10c, lc, c, cs)
    tr = compute_trace(system, p0, q0, l, W01, W10, o, seed=seed, coordinates=coordinates)
    return TraceTestResult(trace=tr, q0=q0, l=l, W10=W10, witnesses=rec, seed=seed, seconds=time.perf_counter() - t0,
                           coordinates=cs, chart=c)
