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
* ``undecided``: the interval search skipped the set or left undecided boxes; nothing is settled.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from cdpr_algebra.bp.results import BPOptions
from cdpr_algebra.bp.search import solve_taut_set_interval
from cdpr_algebra.dgp.solve import DGPResult, equilibrium_from_pose
from cdpr_algebra.report.jsonable import jsonable

from .compare import _match

__all__ = ["SettleRecord", "settle_incomplete"]


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
                      progress=None) -> tuple[DGPResult, tuple]:
    """(the result with its incomplete subproblems settled where the interval search proves their admissible set,
    one :class:`SettleRecord` per incomplete subproblem); see the module doc.  ``progress(record, done, total)``
    after each subproblem."""
    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)
    todo = [s for s in result.subproblems if not s.complete]
    subs = {tuple(s.taut): s for s in result.subproblems}
    added_solutions, records = [], []
    for k, sub in enumerate(todo):
        t0 = time.perf_counter()
        taut = tuple(sub.taut)
        cables = [c - 1 for c in taut]
        isub = solve_taut_set_interval(robot, rho, cables, options)
        hsols = [s for s in result.solutions if tuple(s.taut) == taut]
        if isub.skipped is not None or isub.undecided:
            why = (f"interval search skipped ({isub.skipped})" if isub.skipped
                   else f"interval search left {len(isub.undecided)} undecided box(es)")
            rec = SettleRecord(taut, "undecided", why, None, 0, time.perf_counter() - t0)
        else:
            h_only, i_only = _match(robot, taut, hsols, list(isub.solutions))
            if h_only:
                where = "; ".join(f"position {jsonable(np.round(s.position, 6))}" for s in h_only)
                rec = SettleRecord(taut, "disagree", f"{len(h_only)} homotopy solution(s) not among the proven "
                                   f"solutions of the complete interval search ({where})", isub.admissible, 0,
                                   time.perf_counter() - t0)
            else:
                for s in i_only:
                    added_solutions.append(equilibrium_from_pose(robot, rho, cables, s.position, s.rotation,
                                                                 s.tensions, found_by="interval"))
                rec = SettleRecord(taut, "settled", f"the interval branch and prune ({isub.admissible} admissible "
                                   f"proven, no undecided box, {isub.boxes} boxes)", isub.admissible, len(i_only),
                                   time.perf_counter() - t0)
                subs[taut] = replace(sub, settled=rec.detail, admissible=isub.admissible)
        records.append(rec)
        if progress:
            progress(rec, k + 1, len(todo))
    sols = list(result.solutions) + added_solutions
    sols.sort(key=lambda s: (-len(s.taut), s.taut, tuple(np.round(s.position, 9))))
    settled = replace(result, solutions=tuple(sols), subproblems=tuple(subs[tuple(s.taut)] for s in result.subproblems))
    return settled, tuple(records)
