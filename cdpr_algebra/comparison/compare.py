"""Cross-check of the two DGP solvers (issue 8): homotopy continuation (:func:`cdpr_algebra.dgp.solve_taut_set`) against the
interval branch and prune (:func:`cdpr_algebra.bp.search.solve_taut_set_interval`), subproblem by subproblem.

For each set of taut cables: the homotopy's admissible count (real, tensions >= 0, other cables slack), the
interval solver's count of proven admissible solutions, its undecided boxes, and every disagreement with the
solutions involved.  Solutions are matched by pose: for m >= 2 the platform origin within ``MATCH_TOL`` robot sizes
and the rotation within ``MATCH_TOL``; for m = 1 (the platform turns freely about the cable, each solver reports some
angle) the anchor B_i and the centre of mass G, which do not depend on that angle.

**Outcome of a subproblem** (``agree``, with the reason in ``compared``; issue 15 item 5: agreement is claimed only
where both sides stand behind their answer):

* ``True`` (agree): both sides are complete -- the homotopy ran with no failed path, or it pruned the subproblem
  by a test that is a proof (below); the interval search ran and left no undecided box -- and the solutions match
  one to one.
* ``False`` (disagree): a difference that completeness makes definite -- a homotopy solution that is not among the
  proven solutions of a complete interval search, or a proven interval solution that a complete homotopy does not
  have.
* ``None`` (not compared): everything else -- either side skipped the subproblem (the interval solver's skip
  reasons, e.g. non-isolated equilibria; the homotopy's missing generic set; a homotopy pruning that interval
  arithmetic could not confirm), or left it incomplete (homotopy failed paths, or a homotopy subproblem flagged
  ``complete = False``; undecided interval boxes) without a definite difference.  It is never counted as agreement.
  A taut set the homotopy solved as a rod (:mod:`cdpr_algebra.dgp.rod`: families turning about a line) is not
  compared either: the interval search lists isolated equilibria, and where the line holds only in the decimal
  reading of the robot's numbers it searches the doubles, a robot off the line.  A taut set whose anchors alone are
  collinear only in that reading (:mod:`cdpr_algebra.dgp.collinear_anchors`, G off the line: isolated equilibria)
  is compared, and ``compared`` says that the two sides solved robots a rounding apart.

**Pruning as a proof.**  The homotopy DGP skips a taut set when two cables cannot reach each other
(|A_i A_j| > rho_i + rho_j + |b_i' b_j'|: B_i lies within rho_i of A_i, B_j within rho_j of A_j, and |B_i B_j| =
|b_i' b_j'|, so the triangle inequality rules out every pose) or cannot both be taut (|rho_i - rho_j| > |A_i A_j| +
|b_i' b_j'|, the same triangle inequality with both cables at their lengths).  Each is a statement that no pose
satisfies the geometric constraints, hence no equilibrium exists.  :func:`pruning_proof` re-checks the inequality in
outward-rounded ball arithmetic (arb) on the robot's numbers; only then is the homotopy's 0 a proven, complete
answer compared with the interval search's (which still runs: its answer must be complete and empty to agree).

Boundary cases follow the homotopy's deduplication rule (:mod:`cdpr_algebra.dgp.solve`): a solution with a zero tension belongs to
the smaller taut set; the interval solver reports such a proven solution as undecided (its tension enclosure
contains 0), so that subproblem is "not compared" with the undecided box listed, never silently agreed.
"""

from __future__ import annotations

import itertools
import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from cdpr_algebra.model.taut_sets import lengths_and_taut_sets, solve_each_taut_set
from cdpr_algebra.bp.results import BPOptions
from cdpr_algebra.bp.search import solve_taut_set_interval
from cdpr_algebra.dgp.positive_dimensional import ROD
from cdpr_algebra.model.rod_equations import BINARY
from cdpr_algebra.report.jsonable import jsonable

__all__ = ["SubproblemComparison", "CrosscheckResult", "compare_taut_set", "crosscheck", "crosscheck_table",
           "pruning_proof", "exit_status", "overall_status", "MATCH_TOL"]

MATCH_TOL = 1e-6


@dataclass(frozen=True)
class SubproblemComparison:
    taut: tuple  # 1-based
    homotopy: int | None  # admissible count (None: the homotopy could not run this subproblem)
    interval: int  # proven admissible solutions
    undecided: int  # undecided boxes of the interval search
    agree: bool | None  # True: agree, False: disagree, None: not compared (see ``compared``)
    homotopy_only: tuple  # DGPSolution found by the homotopy only
    interval_only: tuple  # IntervalSolution found by the interval search only
    undecided_boxes: tuple  # UndecidedBox
    homotopy_seconds: float
    interval_seconds: float
    interval_boxes: int
    homotopy_skipped: str | None = None
    interval_skipped: str | None = None
    compared: str = ""  # why agree is what it is (for None: why the subproblem was not compared)
    homotopy_failed_paths: int = 0

    @property
    def status(self) -> str:
        """'agree', 'disagree' or 'not compared'."""
        return {True: "agree", False: "disagree", None: "not compared"}[self.agree]

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "status": self.status, "homotopy": self.homotopy, "interval": self.interval,
                "undecided": self.undecided, "agree": self.agree, "compared": self.compared,
                "homotopy_only": [s.to_dict() for s in self.homotopy_only],
                "interval_only": [s.to_dict() for s in self.interval_only],
                "undecided_boxes": [u.to_dict() for u in self.undecided_boxes],
                "homotopy_seconds": self.homotopy_seconds, "interval_seconds": self.interval_seconds,
                "interval_boxes": self.interval_boxes, "homotopy_skipped": self.homotopy_skipped,
                "homotopy_failed_paths": self.homotopy_failed_paths, "interval_skipped": self.interval_skipped}


@dataclass(frozen=True)
class CrosscheckResult:
    robot: str
    lengths: np.ndarray
    comparisons: tuple
    seconds: float

    @property
    def agree(self) -> bool:
        """Every subproblem compared and in agreement (a subproblem not compared is not agreement)."""
        return all(c.agree is True for c in self.comparisons)

    @property
    def disagreements(self) -> tuple:
        return tuple(c for c in self.comparisons if c.agree is False)

    @property
    def not_compared(self) -> tuple:
        return tuple(c for c in self.comparisons if c.agree is None)

    @property
    def agreements(self) -> tuple:
        return tuple(c for c in self.comparisons if c.agree is True)

    @property
    def status(self) -> str:
        return overall_status(c.agree for c in self.comparisons)

    def to_dict(self) -> dict:
        return {"status": self.status, "robot": self.robot, "lengths": jsonable(self.lengths),
                "agree": True if self.agree else (False if self.disagreements else None),
                "summary": {"subproblems": len(self.comparisons), "agree": len(self.agreements),
                            "disagree": len(self.disagreements), "not_compared": len(self.not_compared)},
                "exit_status": exit_status(self),
                "subproblems": [c.to_dict() for c in self.comparisons], "seconds": self.seconds,
                "homotopy_admissible": sum(c.homotopy or 0 for c in self.comparisons),
                "interval_admissible": sum(c.interval for c in self.comparisons),
                "undecided": sum(c.undecided for c in self.comparisons)}


def overall_status(agree) -> str:
    """The verdict over subproblems from their ``agree`` (True, False or None): 'disagree' if any disagrees, else
    'not compared' if any was not compared, else 'agree'."""
    agree = list(agree)
    if any(a is False for a in agree):
        return "disagree"
    return "not compared" if any(a is None for a in agree) else "agree"


def exit_status(result: CrosscheckResult) -> int:
    """0: every subproblem agrees; 1: some subproblem disagrees; 3: nothing disagrees but some subproblem was not
    compared (skipped or left incomplete by a solver)."""
    if result.disagreements:
        return 1
    return 3 if result.not_compared else 0


def pruning_proof(robot, rho, cables) -> str | None:
    """The pruning test of :func:`cdpr_algebra.dgp.solve.prune` for the 0-based taut set ``cables``, re-checked in ball arithmetic
    (arb, outward rounded; the robot's doubles taken as exact): the reason when one of its inequalities is proven
    (no pose, hence no equilibrium), None otherwise (see the module docstring)."""
    from flint import arb

    A = [[arb(float(v)) for v in a] for a in robot.base]
    b = [[arb(float(v)) for v in p] for p in robot.platform]
    r = [arb(float(v)) for v in rho]

    def dist(P, Q):
        return sum(((P[k] - Q[k]) ** 2 for k in range(3)), arb(0)).sqrt()

    n = robot.n
    for i in range(n):
        for j in range(i + 1, n):
            if dist(A[i], A[j]) > r[i] + r[j] + dist(b[i], b[j]):
                return (f"cables {i + 1} and {j + 1} cannot reach each other's anchor (|A{i + 1}A{j + 1}| > "
                        f"rho{i + 1} + rho{j + 1} + |b{i + 1}'b{j + 1}'|, proven in interval arithmetic)")
    for i, j in itertools.combinations(sorted(cables), 2):
        if abs(r[i] - r[j]) > dist(A[i], A[j]) + dist(b[i], b[j]):
            return (f"cables {i + 1} and {j + 1} cannot both be taut (|rho{i + 1} - rho{j + 1}| > |A{i + 1}A{j + 1}| + "
                    f"|b{i + 1}'b{j + 1}'|, proven in interval arithmetic)")
    return None


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


def _homotopy(robot, rho, cables, seed, extended=False):
    from cdpr_algebra.dgp.solve import default_options, solve_taut_set

    # the comparison needs the solutions only (no certificates), and every set tracked: the interval exclusion
    # test would put the other side's method into the homotopy's answer
    return solve_taut_set(robot, rho, cables, seed=seed, certify=False, exclude=False,
                          options=default_options(extended=True) if extended else None)


def _incompleteness(hsub):
    from cdpr_algebra.dgp.solve import incompleteness

    return incompleteness(hsub)


def _outcome(hskip, hcount, hfailed, hflag, pruned, isub, h_only, i_only, hwhy=None):
    """(agree, compared) of one subproblem (see the module docstring); ``hflag``: the homotopy subproblem's own
    ``complete`` flag when it has one (None otherwise), ``hwhy``: why it is not complete."""
    h_complete = hcount is not None and ((hskip is None and hfailed == 0 and hflag is not False) or pruned is not None)
    i_complete = isub.skipped is None and isub.complete
    if i_complete and h_only:
        return False, (f"{len(h_only)} homotopy solution(s) not among the proven solutions of the complete interval "
                       f"search")
    if h_complete and i_only:
        return False, (f"{len(i_only)} proven interval solution(s) missing from the complete homotopy solve")
    if h_complete and i_complete:
        if pruned is not None:
            return True, f"homotopy pruned: {pruned}; interval search complete, no solution"
        return True, "both complete, solutions matched one to one"
    why = []
    if hcount is None:
        why.append(f"homotopy did not run ({hskip})")
    elif hskip is not None and pruned is None:
        why.append(f"homotopy skipped ({hskip}), not confirmed in interval arithmetic")
    elif hfailed:
        why.append(f"homotopy incomplete: {hfailed} failed path(s)")
    elif hflag is False:
        why.append(f"homotopy incomplete: {hwhy or 'its path outcomes do not account for the generic solution count'}")
    if isub.skipped is not None:
        why.append(f"interval search skipped ({isub.skipped})")
    elif not isub.complete:
        why.append(f"interval search incomplete: {isub.n_undecided} undecided box(es)")
    return None, "not compared: " + "; ".join(why)


def compare_taut_set(robot, rho, cables, options: BPOptions | None = None, seed: int = 0,
                     interval_result=None, homotopy_result=None, extended: bool = False) -> SubproblemComparison:
    """Both solvers on the 0-based taut set ``cables`` (rho: all n lengths) and their comparison
    (``interval_result``: an :class:`cdpr_algebra.bp.results.IntervalSubproblem` already computed for this set;
    ``homotopy_result``: the pair (DGPSubproblem, its admissible DGPSolutions) of the homotopy DGP already
    computed for this set at these lengths, e.g. taken from a :func:`cdpr_algebra.dgp.solve.dgp` result;
    ``extended``: the homotopy with Newton residuals in double-double where double precision stalls,
    :func:`cdpr_algebra.dgp.solve.default_options`)."""
    rho = np.asarray(rho, dtype=float)
    cables = tuple(sorted(cables))
    taut1 = tuple(c + 1 for c in cables)
    t0 = time.perf_counter()
    hsub, hsols = homotopy_result if homotopy_result is not None else _homotopy(robot, rho, cables, seed, extended)
    th = time.perf_counter() - t0 if homotopy_result is None else hsub.seconds
    hskip = hsub.skipped
    hcount = len(hsols)
    hfailed = int(getattr(hsub, "failed_paths", 0) or 0)
    hflag = getattr(hsub, "complete", None)
    pruned = None
    if hskip is not None and (hskip.startswith("no stored generic solution set")
                              or getattr(hsub, "excluded", None) is not None):
        hcount = None  # the homotopy cannot say (not tracked: no set stored, or excluded by the interval filter)
    elif hskip is not None:
        pruned = pruning_proof(robot, rho, cables)
    isub = interval_result if interval_result is not None else solve_taut_set_interval(robot, rho, cables, options)
    h_only, i_only = _match(robot, taut1, list(hsols), list(isub.solutions))
    hwhy = _incompleteness(hsub) if hflag is False else None
    agree, compared = _outcome(hskip, hcount, hfailed, hflag, pruned, isub, h_only, i_only, hwhy)
    family = getattr(hsub, "family", None)
    if family is not None and family.method == ROD:  # families on a line: nothing isolated to compare
        agree, compared = None, (f"not compared: the homotopy solved the taut set as a rod (families of equilibria "
                                 f"turning about a line, {family.reading} reading of the robot's data); the interval "
                                 f"search lists isolated equilibria of the robot's doubles"
                                 + (f"; interval search skipped ({isub.skipped})" if isub.skipped else ""))
    elif getattr(hsub, "collinear_anchors", None) not in (None, BINARY) and compared:
        # isolated equilibria of two robots a rounding apart: compared, and said
        compared += " (the homotopy solved the robot read in decimal, its taut anchors collinear only so; the interval " \
                    "search the robot's doubles)"
    return SubproblemComparison(taut1, hcount, isub.admissible, isub.n_undecided, agree, h_only, i_only,
                                tuple(isub.undecided), th, isub.seconds, isub.boxes, hskip, isub.skipped, compared,
                                hfailed)


def crosscheck(robot, lengths=None, sets=None, max_m: int = 6, options: BPOptions | None = None, seed: int = 0,
               progress=None, jobs: int | None = 1, extended: bool = False) -> CrosscheckResult:
    """Compare the solvers on every taut set of m = 1 .. min(n, 6, max_m) cables, or on the 0-based ``sets``.
    ``progress(comparison, done, total)`` is called after each subproblem.  ``jobs`` > 1 (None: ``os.cpu_count()``):
    the interval searches run ahead in that many threads (their compiled kernels release the GIL) while the
    homotopy and the comparison run in the calling thread, in subproblem order (the homotopy's certificates change
    the precision of the ball arithmetic, which is global), so the result does not depend on ``jobs``; ``extended``:
    see :func:`compare_taut_set`."""
    jobs = os.cpu_count() if jobs is None else max(1, int(jobs))
    rho, every_set = lengths_and_taut_sets(robot, lengths, max_m)
    sets = every_set if sets is None else sets
    with ThreadPoolExecutor(max_workers=jobs) as ex:
        ahead = {tuple(c): ex.submit(solve_taut_set_interval, robot, rho, c, options) for c in sets} if jobs > 1 else {}

        def one(rho, c):
            fut = ahead.get(tuple(c))
            return compare_taut_set(robot, rho, c, options, seed, interval_result=None if fut is None else fut.result(),
                                    extended=extended)

        rho, out, seconds = solve_each_taut_set(robot, lengths, max_m, sets, one, progress)
    return CrosscheckResult(robot.name, rho, tuple(out), seconds)


def _fmt_solution(tag, s) -> str:
    return (f"    {tag}: O' = ({', '.join(f'{v:+.6f}' for v in s.position)}), angles = "
            f"({', '.join(f'{v:+.6f}' for v in s.angles)}), tau = ({', '.join(f'{v:.6f}' for v in s.tensions)})")


def _cell(c) -> str:
    return {True: "yes", False: "NO", None: "not compared"}[c.agree]


def summary_line(result: CrosscheckResult) -> str:
    """Counts of agree / disagree / not compared, then the admissible counts of both sides."""
    nh = sum(c.homotopy or 0 for c in result.comparisons)
    ni = sum(c.interval for c in result.comparisons)
    return (f"{len(result.comparisons)} subproblems: {len(result.agreements)} agree, {len(result.disagreements)} "
            f"disagree, {len(result.not_compared)} not compared; homotopy {nh} admissible, interval {ni} admissible "
            f"(proven), {sum(c.undecided for c in result.comparisons)} undecided boxes; {result.seconds:.2f} s")


def crosscheck_table(result: CrosscheckResult) -> str:
    """One row per subproblem, then every disagreement with its solutions, every subproblem not compared with the
    reason (and its undecided boxes), and the summary line."""
    from cdpr_algebra.report.tables import format_table

    headers = ["taut", "homotopy", "interval", "undecided", "agree", "t_homotopy", "t_interval", "boxes"]
    rows = []
    for c in result.comparisons:
        rows.append([" ".join(str(t) for t in c.taut), "-" if c.homotopy is None else str(c.homotopy), str(c.interval),
                     str(c.undecided), _cell(c), f"{c.homotopy_seconds:.2f}s",
                     f"{c.interval_seconds:.2f}s", str(c.interval_boxes)])
    lines = [format_table(headers, rows)]
    for c in result.comparisons:
        if c.agree is True:
            continue
        what = "DISAGREE" if c.agree is False else "not compared"
        lines.append(f"taut {list(c.taut)}: {what}: homotopy {c.homotopy if c.homotopy is not None else '-'} "
                     f"({c.homotopy_skipped or 'ran'}"
                     f"{f', {c.homotopy_failed_paths} failed paths' if c.homotopy_failed_paths else ''}), "
                     f"interval {c.interval} ({c.interval_skipped or 'ran'}), {c.undecided} undecided"
                     + ("" if c.agree is None else f"; {c.compared}"))
        if c.agree is None:
            lines.append(f"    {c.compared}")
        for s in c.homotopy_only:
            lines.append(_fmt_solution("homotopy only", s))
        for s in c.interval_only:
            lines.append(_fmt_solution("interval only", s))
        for u in c.undecided_boxes[:10]:
            pos = "" if u.position is None else f", near O' = ({', '.join(f'{v:+.4f}' for v in u.position)})"
            lines.append(f"    undecided: {u.reason}{pos}")
        if len(c.undecided_boxes) > 10:
            lines.append(f"    ... {len(c.undecided_boxes) - 10} more undecided boxes (see --json)")
    lines.append(summary_line(result))
    return "\n".join(lines)
