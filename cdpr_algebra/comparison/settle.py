"""Settling the admissible equilibria of subproblems that the homotopy left incomplete, by the interval branch and
prune (Berti et al. 2016's method, :mod:`cdpr_algebra.bp`).

A homotopy subproblem with failed paths (e.g. paths into the singular solutions at infinity of a near-degenerate
robot, which double precision cannot follow to the end) cannot say that it found every complex solution, so
equilibria may be missing there.  Users mostly need the admissible ones (real, tensions >= 0, other cables slack),
and the interval search decides exactly those: when it finishes with no undecided box, its proven solutions are
every admissible equilibrium of the taut set.  :func:`settle_incomplete` runs it on each incomplete subproblem:

* ``settled``: the interval search is complete and every admissible solution of the homotopy is among its proven
  ones (matched by pose as in :mod:`.compare`).  The subproblem's ``settled`` says so; its admissible set is the
  interval search's, and a proven solution that the homotopy did not find is added (``found_by = "interval"``,
  with the homotopy's stability class and interval certificate at that pose).  The complex account stays
  incomplete (``complete`` False): only the admissible set is proven.
* ``disagree``: a homotopy solution that the complete interval search does not have -- one of the two is wrong;
  nothing is settled, the record says which solution.
* ``undecided``: the interval search skipped the set or left undecided boxes; nothing is settled.  A subproblem
  whose endpoints lie on continuous families of solutions (its ``family``) is not searched (every box around a
  family stays undecided): ``undecided`` at once.
"""

from __future__ import annotations

import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, replace

import numpy as np

from cdpr_algebra.bp.results import BPOptions
from cdpr_algebra.bp.search import solve_taut_set_interval
from cdpr_algebra.dgp.solve import DGPResult, collected_solutions, equilibrium_from_pose
from cdpr_algebra.report.jsonable import jsonable

from .compare import _match

__all__ = ["FAMILY_NOT_SEARCHED", "SettleRecord", "settle_incomplete"]

FAMILY_NOT_SEARCHED = ("not searched: its solutions come in continuous families (dgp.positive_dimensional), which "
                       "no branch and prune reduces to proven isolated boxes")


@dataclass(frozen=True)
class SettleRecord:
    """What the interval search did for one incomplete subproblem (``taut`` 1-based)."""

    taut: tuple
    outcome: str  # "settled", "disagree" or "undecided"
    detail: str
    interval_admissible: int | None
    added: int  # proven solutions the homotopy had not found
    seconds: float

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "outcome": self.outcome, "detail": self.detail,
                "interval_admissible": self.interval_admissible, "added": self.added, "seconds": self.seconds}


def settle_incomplete(robot, result: DGPResult, lengths=None, options: BPOptions | None = None,
                      progress=None, jobs: int | None = None) -> tuple[DGPResult, tuple]:
    """(the result with its incomplete subproblems settled where the interval search proves their admissible set,
    one :class:`SettleRecord` per incomplete subproblem); see the module doc.  ``progress(record, done, total)``
    after each subproblem; ``jobs`` threads run the interval searches (default ``os.cpu_count()``; its compiled
    kernels release the GIL), the matching and certificates run in the calling thread, in subproblem order, so the
    result does not depend on ``jobs``."""
    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)
    todo = [s for s in result.subproblems if not s.complete]
    subs = {tuple(s.taut): s for s in result.subproblems}
    added_solutions, records = [], []
    jobs = os.cpu_count() if jobs is None else max(1, int(jobs))

    def search(sub):
        t0 = time.perf_counter()
        return solve_taut_set_interval(robot, rho, [c - 1 for c in sub.taut], options), time.perf_counter() - t0

    with ThreadPoolExecutor(max_workers=jobs) as ex:
        # a set whose solutions come in families holds a continuum of them: the search would only split boxes
        futures = [None if s.family is not None else ex.submit(search, s) for s in todo]
        for k, (sub, fut) in enumerate(zip(todo, futures)):
            if fut is None:
                rec, added = SettleRecord(tuple(sub.taut), "undecided", FAMILY_NOT_SEARCHED, None, 0, 0.0), []
                records.append(rec)
                if progress:
                    progress(rec, k + 1, len(todo))
                continue
            isub, seconds = fut.result()
            rec, added = _settle_one(robot, rho, result, sub, isub, seconds)
            if rec.outcome == "settled":
                subs[tuple(sub.taut)] = replace(sub, settled=rec.detail, admissible=isub.admissible)
            added_solutions += added
            records.append(rec)
            if progress:
                progress(rec, k + 1, len(todo))
    # the added equilibria join the others by the DGP's own rule (one per pose, same order)
    sols = collected_solutions(list(result.solutions) + added_solutions, robot.cable_scale)
    settled = replace(result, solutions=sols, subproblems=tuple(subs[tuple(s.taut)] for s in result.subproblems))
    return settled, tuple(records)


def _settle_one(robot, rho, result, sub, isub, seconds):
    """(SettleRecord, added DGPSolutions) of one subproblem from its interval search ``isub``."""
    t0 = time.perf_counter() - seconds
    taut = tuple(sub.taut)
    cables = [c - 1 for c in taut]
    hsols = [s for s in result.solutions if tuple(s.taut) == taut]
    if isub.skipped is not None or not isub.complete:
        reasons = sorted(isub.undecided_by_reason)
        why = (f"interval search skipped ({isub.skipped})" if isub.skipped
               else f"interval search left {isub.n_undecided} undecided box(es) ({'; '.join(reasons[:3])})")
        return SettleRecord(taut, "undecided", why, None, 0, time.perf_counter() - t0), []
    h_only, i_only = _match(robot, taut, hsols, list(isub.solutions))
    if h_only:
        where = "; ".join(f"position {jsonable(np.round(s.position, 6))}" for s in h_only)
        return SettleRecord(taut, "disagree", f"{len(h_only)} homotopy solution(s) not among the proven solutions of "
                            f"the complete interval search ({where})", isub.admissible, 0, time.perf_counter() - t0), []
    added = [equilibrium_from_pose(robot, rho, cables, s.position, s.rotation, s.tensions, found_by="interval")
             for s in i_only]
    detail = (f"the interval branch and prune ({isub.admissible} admissible proven, no undecided box, {isub.boxes} "
              f"boxes)")
    return SettleRecord(taut, "settled", detail, isub.admissible, len(added), time.perf_counter() - t0), added
