"""Cross-check another solver's DGP results (ALIAS, IbexSolve, Codac, ...) against ours, taut set by taut set.

Their file, JSON::

    {"solver": "IbexSolve 2.8", "subproblems": [{"taut": [1, 2, 3], "count": 6,
                                                  "boxes": [[[lo, hi], [lo, hi], [lo, hi]], ...]}, ...]}

optional top-level ``"robot"`` (the robot's name) and ``"lengths"`` (the n cable lengths they solved for; checked
against ours: a file for other lengths is an error, not a comparison); other keys are errors (a misspelt key would
otherwise be a silently wrong comparison); cables numbered from 1; ``count``: their number of admissible
equilibria; ``boxes`` (optional): one per equilibrium,
intervals for the position of the platform frame's origin (x, y, z in the robot's base frame, as ``cdpr dgp``
prints it); further intervals are ignored.  Or plain text, one box per line, the way interval solvers print them::

    1 2 3 ; [lo, hi] [lo, hi] [lo, hi]

(a taut set's count is then its number of lines; ``#`` starts a comment; a line ``1 2 3 ; none`` says that set has
no equilibrium).  For every subproblem in their file: our DGP of that taut set (certified); their boxes matched to
our certified admissible equilibria inside them, ours not covered by any of their boxes, and ``agree``: true when
ours is complete, the counts are equal and (with boxes) every box holds exactly one of ours and every one of ours is
in a box; false on any definite difference; null ("not compared") when our subproblem is incomplete.
"""

from __future__ import annotations

import json
import re
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cdpr_algebra.model.errors import CdprInputError, reject_unknown_keys
from cdpr_algebra.report.jsonable import jsonable

from .compare import overall_status

BOX_SLACK = 1e-9  # relative to the robot's size: a point on a box face counts as inside


@dataclass(frozen=True)
class TheirSubproblem:
    taut: tuple  # 1-based
    count: int | None
    boxes: tuple  # of (3, 2) arrays, or () when not given


@dataclass(frozen=True)
class ExternalComparison:
    """One taut set: their count and boxes against our certified admissible equilibria."""

    taut: tuple
    theirs: int | None
    ours: int | None
    agree: bool | None
    compared: str
    matched: tuple  # (box index, our solution index)
    unmatched_boxes: tuple  # box indices holding none of ours (or several)
    uncovered: tuple  # our solutions (positions) in none of their boxes
    seconds: float

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "theirs": self.theirs, "ours": self.ours, "agree": self.agree,
                "compared": self.compared, "matched": [list(m) for m in self.matched],
                "unmatched_boxes": list(self.unmatched_boxes), "uncovered": [jsonable(p) for p in self.uncovered],
                "seconds": self.seconds}


@dataclass(frozen=True)
class ExternalResult:
    robot: str
    solver: str
    lengths: np.ndarray
    subproblems: tuple
    seconds: float

    @property
    def disagreements(self) -> tuple:
        return tuple(c for c in self.subproblems if c.agree is False)

    @property
    def not_compared(self) -> tuple:
        return tuple(c for c in self.subproblems if c.agree is None)

    @property
    def status(self) -> str:
        return overall_status(c.agree for c in self.subproblems)

    def to_dict(self) -> dict:
        return {"robot": self.robot, "solver": self.solver, "lengths": jsonable(self.lengths), "status": self.status,
                "subproblems": [c.to_dict() for c in self.subproblems], "seconds": self.seconds,
                "summary": {"agree": sum(c.agree is True for c in self.subproblems),
                            "disagree": len(self.disagreements), "not_compared": len(self.not_compared)}}


def _taut(value, n: int, where: str) -> tuple:
    try:
        taut = tuple(int(c) for c in value)
    except (TypeError, ValueError):
        raise CdprInputError(where, f"taut must be cable numbers, got {value!r}") from None
    if not taut or len(set(taut)) != len(taut) or any(not 1 <= c <= n for c in taut) or len(taut) > 6:
        raise CdprInputError(where, f"taut must be 1 to 6 distinct cable numbers in 1 .. {n}, got {list(taut)}")
    return tuple(sorted(taut))


def _box(value, where: str) -> np.ndarray:
    try:
        B = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise CdprInputError(where, f"a box is a list of [lo, hi] intervals, got {value!r}") from None
    if B.ndim != 2 or B.shape[1] != 2 or B.shape[0] < 3:
        raise CdprInputError(where, f"a box needs at least 3 intervals [lo, hi] (x, y, z), got {value!r}")
    B = B[:3]
    if not np.all(np.isfinite(B)) or np.any(B[:, 0] > B[:, 1]):
        raise CdprInputError(where, f"an interval must have finite lo <= hi, got {B.tolist()}")
    return B


TOP_KEYS = ("solver", "subproblems", "robot", "lengths")
SUBPROBLEM_KEYS = ("taut", "count", "boxes")


def _check_lengths(data: dict, lengths) -> None:
    """Their ``"lengths"`` (when given) must be ours to 1e-9 relative: else they solved another problem."""
    if "lengths" not in data or lengths is None:
        return
    ours = np.asarray(lengths, dtype=float)
    try:
        theirs = np.asarray(data["lengths"], dtype=float)
    except (TypeError, ValueError):
        raise CdprInputError("lengths", f"expected {len(ours)} numbers, got {data['lengths']!r}") from None
    if theirs.shape != ours.shape:
        raise CdprInputError("lengths", f"expected {len(ours)} cable lengths, got {theirs.size}")
    if not np.allclose(theirs, ours, rtol=1e-9, atol=0.0):
        raise CdprInputError("lengths", f"their results are for lengths {theirs.tolist()}, ours are {ours.tolist()}: "
                                        "give the same lengths (--lengths) or drop the key")


def load_results(path, n: int, lengths=None) -> tuple[str, tuple]:
    """(solver name, TheirSubproblems) from a JSON or text results file (module doc); ``lengths``: ours, checked
    against the file's ``"lengths"`` when it has one."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise CdprInputError("--against", f"cannot read {path}: {err.strerror}") from None
    if text.lstrip().startswith(("{", "[")) or path.suffix.lower() == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as err:
            raise CdprInputError("--against", f"not valid JSON ({err.msg}, line {err.lineno})") from None
        if not isinstance(data, dict):
            raise CdprInputError("--against", f'expected a JSON object {{"solver", "subproblems"}}, got a '
                                              f"{type(data).__name__}")
        reject_unknown_keys(data, TOP_KEYS)
        _check_lengths(data, lengths)
        subs = data.get("subproblems")
        if not isinstance(subs, list):
            raise CdprInputError("--against", 'expected a list "subproblems"')
        if not subs:  # nothing compared is no agreement
            raise CdprInputError("--against", '"subproblems" is empty: no result to compare')
        out, seen = [], set()
        for k, s in enumerate(subs):
            where = f"subproblems[{k}]"
            if not isinstance(s, dict) or "taut" not in s:
                raise CdprInputError(where, 'expected {"taut": [..], "count": N, "boxes": [..]}')
            reject_unknown_keys(s, SUBPROBLEM_KEYS, where)
            taut = _taut(s["taut"], n, where)
            if taut in seen:
                raise CdprInputError(where, f"taut set {list(taut)} listed twice")
            seen.add(taut)
            count = s.get("count")
            if count is not None and (not isinstance(count, int) or count < 0):
                raise CdprInputError(where, f"count must be a non-negative integer, got {count!r}")
            boxes = tuple(_box(b, f"{where}.boxes[{j}]") for j, b in enumerate(s.get("boxes") or []))
            if count is None and boxes:
                count = len(boxes)
            out.append(TheirSubproblem(taut, count, boxes))
        return str(data.get("solver", "unnamed solver")), tuple(out)
    groups: dict = {}
    nones: set = set()  # taut sets a line says have no equilibrium
    for k, line in enumerate(text.splitlines()):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        where = f"{path.name} line {k + 1}"
        if ";" not in line:
            raise CdprInputError(where, "expected 'C1 C2 .. ; [lo, hi] [lo, hi] [lo, hi]'")
        head, tail = line.split(";", 1)
        taut = _taut(head.replace(",", " ").split(), n, where)
        groups.setdefault(taut, [])
        said_none = tail.strip().lower() == "none"
        if (said_none and groups[taut]) or (not said_none and taut in nones):
            raise CdprInputError(where, f"taut set {list(taut)} has boxes and 'none'")
        if said_none:
            nones.add(taut)
            continue
        pairs = re.findall(r"\[\s*([^,\]\s]+)\s*,\s*([^\]\s]+)\s*\]", tail)
        if len(pairs) < 3:
            raise CdprInputError(where, f"expected 3 intervals [lo, hi] after ';', got {tail.strip()!r}")
        try:
            numbers = [[float(a), float(b)] for a, b in pairs]
        except ValueError:
            raise CdprInputError(where, f"not a number in {tail.strip()!r}") from None
        groups[taut].append(_box(numbers, where))
    if not groups:
        raise CdprInputError("--against", "no result lines")
    return "text results", tuple(TheirSubproblem(t, len(b), tuple(b)) for t, b in groups.items())


def _inside(box, p, slack) -> bool:
    return bool(np.all(p >= box[:, 0] - slack) and np.all(p <= box[:, 1] + slack))


def compare_subproblem(robot, rho, their: TheirSubproblem, seed: int = 0) -> ExternalComparison:
    from cdpr_algebra.dgp.solve import incompleteness, solve_taut_set

    t0 = time.perf_counter()
    cables = tuple(c - 1 for c in their.taut)
    sub, sols = solve_taut_set(robot, rho, cables, seed=seed, certify=True)
    seconds = time.perf_counter() - t0
    ours = len(sols)
    if not sub.complete:
        return ExternalComparison(their.taut, their.count, ours, None,
                                  f"not compared: our subproblem is incomplete ({incompleteness(sub)})", (), (), (),
                                  seconds)
    if their.count is None:
        return ExternalComparison(their.taut, None, ours, None, "not compared: no count or box in their file", (),
                                  (), (), seconds)
    slack = BOX_SLACK * robot.size
    P = [s.position for s in sols]
    matched, unmatched = [], []
    covered = set()
    for j, box in enumerate(their.boxes):
        inside = [i for i, p in enumerate(P) if _inside(box, p, slack)]
        if len(inside) == 1:
            matched.append((j, inside[0]))
            covered.add(inside[0])
        else:
            unmatched.append(j)
        covered.update(inside)
    uncovered = tuple(P[i] for i in range(ours) if i not in covered) if their.boxes else ()
    reasons = []
    if their.count != ours:
        reasons.append(f"counts differ (theirs {their.count}, ours {ours}, all certified)")
    if their.boxes and unmatched:
        reasons.append(f"{len(unmatched)} of their boxes hold none (or several) of our certified equilibria")
    if uncovered:
        reasons.append(f"{len(uncovered)} of our certified equilibria lie in none of their boxes")
    agree = not reasons
    what = "agree" if agree else "; ".join(reasons)
    return ExternalComparison(their.taut, their.count, ours, agree, what, tuple(matched), tuple(unmatched),
                              uncovered, seconds)


def crosscheck_against(robot, lengths, path, seed: int = 0, progress=None) -> ExternalResult:
    """Their results file (:func:`load_results`) against our DGP at ``lengths``."""
    t0 = time.perf_counter()
    rho = np.asarray(lengths, dtype=float)
    solver, subs = load_results(path, robot.n, rho)
    out = []
    for k, s in enumerate(subs):
        c = compare_subproblem(robot, rho, s, seed)
        out.append(c)
        if progress is not None:
            progress(c, k + 1, len(subs))
    return ExternalResult(robot.name, solver, rho, tuple(out), time.perf_counter() - t0)


def external_table(result: ExternalResult) -> str:
    from cdpr_algebra.report.tables import format_table

    rows = []
    for c in result.subproblems:
        word = {True: "agree", False: "DISAGREE", None: "not compared"}[c.agree]
        rows.append([str(list(c.taut)), "-" if c.theirs is None else str(c.theirs), str(c.ours), word,
                     f"{len(c.matched)}", f"{len(c.unmatched_boxes)}", f"{len(c.uncovered)}"])
    table = format_table(["taut", "theirs", "ours", "result", "boxes matched", "boxes unmatched", "ours uncovered"],
                         rows)
    lines = [table]
    for c in result.subproblems:
        if c.agree is not True:
            lines.append(f"  {list(c.taut)}: {c.compared}")
            for p in c.uncovered:
                lines.append(f"    ours not in their boxes: position {np.round(p, 6).tolist()}")
    d = result.to_dict()["summary"]
    lines.append(f"{result.solver} against cdpr_algebra: {d['agree']} agree, {d['disagree']} disagree, "
                 f"{d['not_compared']} not compared ({result.seconds:.3g} s)")
    return "\n".join(lines)
