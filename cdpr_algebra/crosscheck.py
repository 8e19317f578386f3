"""Cross-check of the two DGP solvers (issue 8): homotopy continuation (:func:`.dgp.solve_taut_set`) against the
interval branch and prune (:func:`.interval_bp.solve_taut_set_interval`), subproblem by subproblem.

For each set of taut cables: the homotopy's admissible count (real, tensions >= 0, other cables slack), the
interval solver's count of proven admissible solutions, its undecided boxes, and every disagreement with the
solutions involved.  Solutions are matched by pose: for m >= 2 the platform origin within ``MATCH_TOL`` robot sizes
and the rotation within ``MATCH_TOL``; for m = 1 (the platform turns freely about the cable, each solver reports some
angle) the anchor B_i and the centre of mass G, which do not depend on that angle.  A subproblem agrees when the
counts are equal, every solution is matched one to one and the interval search is complete (no undecided box).

Boundary cases follow the homotopy's deduplication rule (:mod:`.dgp`): a solution with a zero tension belongs to
the smaller taut set; the interval solver reports such a proven solution as undecided (its tension enclosure
contains 0), so it shows up as a disagreement to look at, never silently.
"""

from __future__ import annotations

import inspect
import time
from dataclasses import dataclass

import numpy as np

from .dgp import solve_each_taut_set
from .interval_bp import BPOptions, solve_taut_set_interval
from .jsonable import jsonable

__all__ = ["SubproblemComparison", "CrosscheckResult", "compare_taut_set", "crosscheck", "crosscheck_table",
           "MATCH_TOL"]

MATCH_TOL = 1e-6


@dataclass(frozen=True)
class SubproblemComparison:
    taut: tuple  # 1-based
    homotopy: int | None  # admissible count (None: the homotopy could not run this subproblem)
    interval: int  # proven admissible solutions
    undecided: int  # undecided boxes of the interval search
    agree: bool
    homotopy_only: tuple  # DGPSolution found by the homotopy only
    interval_only: tuple  # IntervalSolution found by the interval search only
    undecided_boxes: tuple  # UndecidedBox
    homotopy_seconds: float
    interval_seconds: float
    interval_boxes: int
    homotopy_skipped: str | None = None
    interval_skipped: str | None = None

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "homotopy": self.homotopy, "interval": self.interval,
                "undecided": self.undecided, "agree": self.agree,
                "homotopy_only": [s.to_dict() for s in self.homotopy_only],
                "interval_only": [s.to_dict() for s in self.interval_only],
                "undecided_boxes": [u.to_dict() for u in self.undecided_boxes],
                "homotopy_seconds": self.homotopy_seconds, "interval_seconds": self.interval_seconds,
                "interval_boxes": self.interval_boxes, "homotopy_skipped": self.homotopy_skipped,
                "interval_skipped": self.interval_skipped}


@dataclass(frozen=True)
class CrosscheckResult:
    robot: str
    lengths: np.ndarray
    comparisons: tuple
    seconds: float

    @property
    def agree(self) -> bool:
        return all(c.agree for c in self.comparisons)

    @property
    def disagreements(self) -> tuple:
        return tuple(c for c in self.comparisons if not c.agree)

    def to_dict(self) -> dict:
        return {"robot": self.robot, "lengths": jsonable(self.lengths), "agree": self.agree,
                "subproblems": [c.to_dict() for c in self.comparisons], "seconds": self.seconds,
                "homotopy_admissible": sum(c.homotopy or 0 for c in self.comparisons),
                "interval_admissible": sum(c.interval for c in self.comparisons),
                "undecided": sum(c.undecided for c in self.comparisons)}


def _key(robot, taut, position, rotation):
    """What identifies an equilibrium: the full pose (m >= 2), B_i and G (m = 1)."""
    if len(taut) == 1:
        i = taut[0] - 1
        return np.concatenate([position + rotation @ robot.platform[i], position + rotation @ robot.com]) / robot.size
    return np.concatenate([position / robot.size, rotation.ravel()])


def _match(robot, taut, hsols, isols, tol=MATCH_TOL):
    """(homotopy-only, interval-only): greedy one-to-one matching by the keys of :func:`_key`."""
    hk = [_key(robot, taut, s.position, s.rotation) for s in hsols]
    ik = [_key(robot, taut, s.position, s.rotation) for s in isols]
    pairs = sorted((float(np.max(np.abs(a - b))), i, j) for i, a in enumerate(hk) for j, b in enumerate(ik))
    used_h, used_i = set(), set()
    for d, i, j in pairs:
        if d > tol:
            break
        if i in used_h or j in used_i:
            continue
        used_h.add(i)
        used_i.add(j)
    return (tuple(s for k, s in enumerate(hsols) if k not in used_h),
            tuple(s for k, s in enumerate(isols) if k not in used_i))


def _homotopy(robot, rho, cables, seed):
    from .dgp import solve_taut_set

    kwargs = {"seed": seed}
    if "certify" in inspect.signature(solve_taut_set).parameters:
        kwargs["certify"] = False  # the comparison needs the solutions only
    return solve_taut_set(robot, rho, cables, **kwargs)


def compare_taut_set(robot, rho, cables, options: BPOptions | None = None, seed: int = 0,
                     interval_result=None) -> SubproblemComparison:
    """Both solvers on the 0-based taut set ``cables`` (rho: all n lengths) and their comparison
    (``interval_result``: an :class:`.interval_bp.IntervalSubproblem` already computed for this set)."""
    rho = np.asarray(rho, dtype=float)
    cables = tuple(sorted(cables))
    taut1 = tuple(c + 1 for c in cables)
    t0 = time.perf_counter()
    hsub, hsols = _homotopy(robot, rho, cables, seed)
    th = time.perf_counter() - t0
    hskip = hsub.skipped
    hcount = len(hsols)
    if hskip is not None and hskip.startswith("no stored generic solution set"):
        hcount = None  # the homotopy cannot say
    isub = interval_result if interval_result is not None else solve_taut_set_interval(robot, rho, cables, options)
    h_only, i_only = _match(robot, taut1, list(hsols), list(isub.solutions))
    agree = (hcount is not None and hcount == isub.admissible and not h_only and not i_only and not isub.undecided)
    return SubproblemComparison(taut1, hcount, isub.admissible, len(isub.undecided), agree, h_only, i_only,
                                tuple(isub.undecided), th, isub.seconds, isub.boxes, hskip, isub.skipped)


def crosscheck(robot, lengths=None, sets=None, max_m: int = 6, options: BPOptions | None = None, seed: int = 0,
               progress=None) -> CrosscheckResult:
    """Compare the solvers on every taut set of m = 1 .. min(n, 6, max_m) cables, or on the 0-based ``sets``.
    ``progress(comparison, done, total)`` is called after each subproblem."""
    rho, out, seconds = solve_each_taut_set(robot, lengths, max_m, sets,
                                            lambda rho, c: compare_taut_set(robot, rho, c, options, seed), progress)
    return CrosscheckResult(robot.name, rho, tuple(out), seconds)


def _fmt_solution(tag, s) -> str:
    return (f"    {tag}: O' = ({', '.join(f'{v:+.6f}' for v in s.position)}), angles = "
            f"({', '.join(f'{v:+.6f}' for v in s.angles)}), tau = ({', '.join(f'{v:.6f}' for v in s.tensions)})")


def crosscheck_table(result: CrosscheckResult) -> str:
    """One row per subproblem, then every disagreement with its solutions and undecided boxes."""
    from .tables import format_table

    headers = ["taut", "homotopy", "interval", "undecided", "agree", "t_homotopy", "t_interval", "boxes"]
    rows = []
    for c in result.comparisons:
        rows.append([" ".join(str(t) for t in c.taut), "-" if c.homotopy is None else str(c.homotopy), str(c.interval),
                     str(c.undecided), "yes" if c.agree else "NO", f"{c.homotopy_seconds:.2f}s",
                     f"{c.interval_seconds:.2f}s", str(c.interval_boxes)])
    lines = [format_table(headers, rows)]
    for c in result.disagreements:
        lines.append(f"taut {list(c.taut)}: homotopy {c.homotopy if c.homotopy is not None else '-'} "
                     f"({c.homotopy_skipped or 'ran'}), interval {c.interval} ({c.interval_skipped or 'ran'}), "
                     f"{c.undecided} undecided")
        for s in c.homotopy_only:
            lines.append(_fmt_solution("homotopy only", s))
        for s in c.interval_only:
            lines.append(_fmt_solution("interval only", s))
        for u in c.undecided_boxes[:10]:
            pos = "" if u.position is None else f", near O' = ({', '.join(f'{v:+.4f}' for v in u.position)})"
            lines.append(f"    undecided: {u.reason}{pos}")
        if len(c.undecided_boxes) > 10:
            lines.append(f"    ... {len(c.undecided_boxes) - 10} more undecided boxes (see --json)")
    nh = sum(c.homotopy or 0 for c in result.comparisons)
    ni = sum(c.interval for c in result.comparisons)
    nd = len(result.disagreements)
    lines.append(f"{len(result.comparisons)} subproblems: homotopy {nh} admissible, interval {ni} admissible "
                 f"(proven), {sum(c.undecided for c in result.comparisons)} undecided boxes; "
                 f"{'all agree' if nd == 0 else f'{nd} disagree'}; {result.seconds:.2f} s")
    return "\n".join(lines)
