"""Top-level solves: start system + tracking + grouping of endpoints into distinct solutions.

* :func:`solve` -- total-degree (default) or multi-homogeneous (``groups=``) homotopy for a system
  (with its parameters fixed by ``parameters=``).
* :func:`solve_parameter_homotopy` -- from a solved generic (complex) instance (p1, its solutions)
  to target parameters p0 along the straight segment (optionally through a random complex detour
  point, or with the gamma trick).
* :func:`group_solutions` -- distinct finite solutions: nonsingular endpoints (tolerance
  ``duplicate_tol``) and singular endpoints clustered (tolerance ``singular_tol``) into points
  whose multiplicity is the number of paths ending there.

Every run takes a ``seed`` (int) that is reported in the result and reproduces it exactly.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from .clusters import coincides_with_any, duplicate_groups
from .endgame import SolveOptions, mp_path, mp_track
from .refinement import refine
from .projective import from_chart, to_chart
from .results import (ENDGAME_FAILED, FAILURES, PATH_JUMPING, SINGULAR, STEP_TOO_SMALL, SUCCESS, Solution,
                      SolveResult, TrackResult)
from .start_systems import multi_homogeneous, parameter_homotopy, random_gamma, total_degree
from .systems import PolynomialSystem
from .endgame import track_paths

__all__ = ["solve", "solve_parameter_homotopy", "group_solutions"]


def group_solutions(track: TrackResult, duplicate_tol: float = 1e-8, singular_tol: float = 1e-6) -> tuple:
    """Distinct finite solutions of a :class:`TrackResult` (see module doc)."""
    sols = []
    for status, tol in ((SUCCESS, duplicate_tol), (SINGULAR, singular_tol)):
        paths = [p for p in track.paths if p.status == status]
        if not paths:
            continue
        pts = np.array([p.endpoint for p in paths])
        groups = duplicate_groups(pts, tol)
        seen = set(i for g in groups for i in g)
        groups += [[i] for i in range(len(paths)) if i not in seen]
        for g in sorted(groups, key=lambda g: g[0]):
            ps = [paths[i] for i in g]
            x = np.mean([p.endpoint for p in ps], axis=0)
            sols.append(Solution(x=x, multiplicity=len(g) if status == SINGULAR else len(g),
                                 singular=status == SINGULAR or len(g) > 1,
                                 residual=max(p.residual for p in ps), condition=max(p.condition for p in ps),
                                 accuracy=max(p.accuracy for p in ps), paths=tuple(p.index for p in ps)))
    return tuple(sols)


def solve(system: PolynomialSystem, parameters=None, groups=None, seed: int = 0,
          options: SolveOptions | None = None) -> SolveResult:
    """All isolated solutions of a square system by a total-degree or multi-homogeneous homotopy."""
    options = options or SolveOptions()
    rng = np.random.default_rng(seed)
    gamma = random_gamma(rng)
    if groups is None:
        start = total_degree(system)
    else:
        start = multi_homogeneous(system, groups, seed=int(rng.integers(2**31)))
    hom = start.homotopy(system, gamma, parameters)
    tr = track_paths(hom, start.solutions, options, seed=seed)
    sols = group_solutions(tr, options.duplicate_tol, options.endgame.cluster_tol)
    return SolveResult(solutions=sols, track=tr, start_system=start.kind)


def _track_segments(system, homs, X, options, seed):
    """Track X through consecutive parameter segments; per-path records (steps summed over segments)."""
    paths = None
    for k, hom in enumerate(homs):
        last = k == len(homs) - 1
        if paths is None:
            tr = track_paths(hom, X, options, seed=seed)
            paths = list(tr.paths)
        else:
            live = [i for i, p in enumerate(paths) if p.status == SUCCESS]
            tr = track_paths(hom, np.array([paths[i].endpoint for i in live]).reshape(len(live), system.n), options, seed=seed)
            for j, i in enumerate(live):
                q = tr.paths[j]
                paths[i] = type(q)(index=i, status=q.status, endpoint=q.endpoint, t=q.t, residual=q.residual,
                                   condition=q.condition, accuracy=q.accuracy, steps=q.steps + paths[i].steps,
                                   winding_number=q.winding_number, retried=q.retried or paths[i].retried)
        if not last:
            # an intermediate (generic) endpoint that is not nonsingular cannot be continued
            for i, p in enumerate(paths):
                if p.status not in (SUCCESS,) + FAILURES:
                    paths[i] = type(p)(**{**p.__dict__, "status": "diverged"})
    return paths


def _mp_retrack(homs, x0, index, options):
    """Path ``index`` from x0 through the parameter segments ``homs`` in arbitrary precision (mpmath, ``mp_dps``
    digits): the intermediate segments to t = 0, the last one by :func:`.endgame.mp_path` (endgame in double
    precision); a PathResult with ``retried="mpmath"``, or None when the arbitrary-precision tracking fails too."""
    x, steps = x0, 0
    for hom in homs[:-1]:
        x, status, ns = mp_track(hom, x, 1.0, 0.0, options.mp_dps, options.tracker)
        steps += ns
        if status != SUCCESS:
            return None
    return mp_path(homs[-1], x, index, options, options.tracker, steps)


def _suspects(paths, tol, projective_endgame_start=None):
    """Failed paths, singular endpoints reached with winding number 1 (ill-conditioned in affine coordinates,
    e.g. of large norm), and successful paths that end on the same point as another one (path jumping).

    ``projective_endgame_start`` (te, when the endgame already ran in a projective chart): a path that failed by
    step size or in the endgame inside the endgame zone (|t| < te), or that ended singular, was already followed
    and decided in that chart, so re-tracking it in the chart is left out (measured on seed 000 Tests 2 and 3: 530
    such re-tracks changed 2 outcomes for 1.1 million steps, half of Test 2's time; paths that ran out of steps
    are still re-tracked, 7 of 9 finished)."""
    te = projective_endgame_start

    def decided_in_chart(p):
        return te is not None and (p.status == SINGULAR or (p.status in (STEP_TOO_SMALL, ENDGAME_FAILED)
                                                            and abs(p.t) < te))

    bad = {i for i, p in enumerate(paths) if (p.status in FAILURES or (p.status == SINGULAR and p.winding_number == 1))
           and not decided_in_chart(p)}
    ok = [i for i, p in enumerate(paths) if p.status == SUCCESS]
    if len(ok) > 1:
        for g in duplicate_groups(np.array([paths[i].endpoint for i in ok]), tol):
            if len(g) > 1:
                bad.update(ok[j] for j in g)
    return sorted(bad)


def _mark_path_jumping(homotopy, paths, options):
    """Paths whose finite endpoints still coincide after the retries: where the common point is nonsingular
    (Newton converges quadratically there and the condition number is moderate), distinct paths cannot both end
    there (implicit function theorem), so the first keeps it and the others are failed with ``path_jumping``:
    a solution is missing, and nothing is merged silently.  Coinciding singular endpoints keep their status:
    one singular solution whose multiplicity is the number of paths."""
    fin = [i for i, p in enumerate(paths) if p.status in (SUCCESS, SINGULAR)]
    if len(fin) < 2:
        return paths
    eo = options.endgame
    for g in duplicate_groups(np.array([paths[i].endpoint for i in fin]), eo.cluster_tol):
        idx = [fin[j] for j in g]
        x = np.mean([paths[i].endpoint for i in idx], axis=0)[None, :]
        xr, upd, res, cond, quad = refine(homotopy, x, 0.0, tol=eo.refine_tol)
        if not (quad[0] and cond[0] <= eo.singular_condition):
            continue
        first, rest = idx[0], idx[1:]
        paths[first] = type(paths[first])(**{**paths[first].__dict__, "status": SUCCESS, "endpoint": xr[0],
                                            "winding_number": 1})
        for i in rest:
            paths[i] = type(paths[i])(**{**paths[i].__dict__, "status": PATH_JUMPING})
    return paths


def solve_parameter_homotopy(system: PolynomialSystem, start_parameters, start_solutions, target_parameters,
                             seed: int = 0, options: SolveOptions | None = None, detour: bool = False,
                             gamma: bool = False, retries: int = 3) -> SolveResult:
    """Track the solutions of F(x; p1) = 0 to F(x; p0) = 0 (see :func:`.start_systems.parameter_homotopy`).

    Paths that fail, or that end on the same point as another path (a sign of path jumping), are tracked
    again from their start points in projective coordinates (:mod:`.projective`) along the same parameter
    path, with step control tightened 10x, 100x, ..., up to ``retries`` rounds; a path keeps the first
    successful, distinct endpoint it reaches (``retried`` says it was re-run).  (Re-tracking a subset of
    paths along another route would not do: its paths may end on solutions that other paths already reached.)
    Then, with ``options.retry_mpmath``, paths still failed are tracked once more in arbitrary precision
    (:func:`.endgame.mp_track`, ``options.mp_dps`` digits, at most ``options.max_mpmath_paths`` of them, slow:
    pure Python) along the same parameter path, the endgame in double precision (``retried="mpmath"``).
    Paths whose nonsingular endpoints still coincide at the end fail with ``path_jumping``
    (:func:`_mark_path_jumping`).  Endpoints are returned in affine coordinates; a path re-tracked in projective
    coordinates is decided finite or at infinity by its endgame (:func:`.endgame.decide_in_chart`).
    """
    options = options or SolveOptions()
    rng = np.random.default_rng(seed)
    t0 = time.perf_counter()
    X = np.asarray(start_solutions, dtype=complex)
    homs = parameter_homotopy(system, start_parameters, target_parameters, rng=rng, detour=detour, gamma=gamma)
    asked = options
    options = replace(options, retry_mpmath=False)  # double-precision retries first, arbitrary precision last
    # the detour retry needs every start solution of one homotopy (see SolveOptions.detour_retry): the first run of
    # a one-segment route only, never the re-tracks of some paths below
    first = options if len(homs) == 1 else replace(options, detour_retry=False)
    options = replace(options, detour_retry=False)
    paths = _track_segments(system, homs, X, first, seed)
    proj = chart = None  # built on the first retry (a system may be slow to homogenize)
    for round_ in range(retries):
        redo = _suspects(paths, options.duplicate_tol,
                         options.endgame.endgame_start if options.endgame.projective else None)
        if round_ >= 1:  # a singular endpoint reached again in projective coordinates is an answer, not a failure
            redo = [i for i in redo if paths[i].status != SINGULAR]
        if not redo:
            break
        # re-track in projective coordinates (large-norm solutions become ordinary points of a random chart)
        # along the SAME parameter path: paths of one homotopy end on distinct solutions, but a path re-tracked
        # along another route (a new detour) may legitimately end on a solution another path already reached
        if proj is None:
            phoms = [h.projective() for h in homs]
            proj, chart = phoms[0].system, phoms[0].chart
        tight = replace(options, tracker=options.tracker.tightened(10.0 ** (round_ + 1)))
        again = _track_segments(proj, phoms, to_chart(X[redo], chart), tight, seed + 1 + round_)
        for i, q in zip(redo, again):
            with np.errstate(all="ignore"):
                x, _ = from_chart(q.endpoint[None, :])
            status = q.status  # decided in the chart (finite, at infinity, singular, failed)
            # regularity is judged in the chart, where a large-norm solution is well conditioned
            q = type(q)(**{**q.__dict__, "endpoint": x[0]})
            candidate = type(q)(**{**q.__dict__, "index": i, "status": status, "retried": "projective"})
            others = np.array([paths[j].endpoint for j in range(len(paths)) if j != i and paths[j].status == SUCCESS])
            distinct = not coincides_with_any(others, candidate.endpoint, options.duplicate_tol)
            if (status == SUCCESS and distinct) or (paths[i].status in FAILURES and status not in FAILURES):
                paths[i] = candidate
    if asked.retry_mpmath and hasattr(homs[0], "mp_evaluate_all"):
        redo = [i for i, p in enumerate(paths) if p.status in FAILURES]
        for i in redo[: options.max_mpmath_paths]:
            q = _mp_retrack(homs, X[i], i, options)
            if q is not None and q.status not in FAILURES:
                paths[i] = q
    paths = _mark_path_jumping(homs[-1], paths, options)
    track = TrackResult(paths=tuple(paths), seconds=time.perf_counter() - t0, seed=seed, options=asked.to_dict())
    return SolveResult(solutions=group_solutions(track, options.duplicate_tol, options.endgame.cluster_tol), track=track, start_system="parameter")
