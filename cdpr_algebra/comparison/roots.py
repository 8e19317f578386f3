"""Another solver's complex roots of one DGP subproblem against ours: PHCpack's output, or any solver's roots in JSON.

The equations are those ``cdpr export ROBOT --taut C1 .. Cm --format phc`` writes (unknowns ``px py pz``, ``ux .. wz``
the columns of R, ``lam1 .. lamm`` = tau_i / rho_i; :mod:`cdpr_algebra.dgp.export`).  Their file is either

* PHCpack's output file (``phc -b system.phc output``): the last list ``THE SOLUTIONS`` is read, and a solution
  counts as a root when PHCpack classes it ``real regular`` or ``complex regular`` (its other classes -- at
  infinity, singular, no solution, ... -- are counted and reported, not compared); or
* JSON ``{"solver": "Bertini 2", "variables": ["px", ..., "lam3"], "roots": [[[re, im], ...], ...]}`` (any order
  of the variables; every root a list of [re, im] pairs, or of plain numbers for real roots): their regular roots.

Ours (:func:`cdpr_algebra.dgp.solve.taut_set_roots`): the regular endpoints of the subproblem's homotopy, each
proven a distinct root by its Krawczyk box.  Roots with a zero tension (some |lam_i| <= ``ZERO_LAM`` (1 + |x|)) are
set apart on both sides: the taut system has them (PHCpack finds 16 on Test 1's {1, 2}), but they are equilibria of a
smaller taut set and the generic homotopy does not track them.  The others are matched one to one, nearest first,
within ``MATCH_RTOL`` (1 + |x|) in every unknown.  Each of their roots that none of ours matches is tested as a root
of the same equations with our Krawczyk test (:func:`cdpr_algebra.certificates.endpoints.certify_endpoints`): proven
when a box holds a unique root within that tolerance of the value they give (the test refines it by Newton's method
first: a value of theirs 1e-3 off one of our roots would otherwise prove that root of ours).

**Outcome** (``agree``, with the reason in ``compared``):

* ``True`` (agree): the two sets of roots match one to one, ours all proven, our subproblem complete (every path
  accounted for: :mod:`cdpr_algebra.dgp.solve`).
* ``False`` (disagree): a definite difference -- one of their roots, proven a root, is not among ours (a root we
  missed: our subproblem says incomplete or not); or one of ours, proven, is not among theirs although their file
  reports no failed path.
* ``None`` (not compared): everything else -- some of ours unproven, theirs unproven roots not among ours, ours
  beyond theirs where their file reports failed paths (PHCpack's ``no solution`` and unfinished paths), which may
  explain it, or the same roots on both sides while our subproblem is incomplete (a root both missed is not ruled
  out).  Never counted as agreement.
"""

from __future__ import annotations

import json
import re
import time
from dataclasses import dataclass, field

import numpy as np

from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.report.jsonable import jsonable

MATCH_RTOL = 1e-6  # two roots match when every unknown agrees to this, relative to 1 + the root's largest |x_i|
ZERO_LAM = 1e-9  # |lam_i| <= this (1 + |x|): a root with a zero tension (of a smaller taut set)
PHC_REGULAR = ("real regular", "complex regular")

__all__ = ["TheirRoots", "RootComparison", "read_roots", "compare_roots", "roots_report"]


@dataclass(frozen=True)
class TheirRoots:
    """Their roots (N, n) complex in their ``variables``' order, and the count of every class of their solutions
    (``classes``: PHCpack's, e.g. {"complex regular": 152, "at infinity": 1333, "no solution": 1191}); ``failed``:
    how many of their paths did not finish (PHCpack's ``no solution``, and other paths that stopped short of t = 1
    but at infinity), None
    when their file does not say."""

    solver: str
    variables: tuple
    roots: np.ndarray
    classes: dict = field(default_factory=dict)
    failed: int | None = None


def _phc_blocks(text: str):
    """(variables, values, class, t) of every solution of PHCpack's last ``THE SOLUTIONS`` list."""
    k = text.rfind("THE SOLUTIONS")
    if k < 0:
        raise CdprInputError("--roots", "not a PHCpack output file: no 'THE SOLUTIONS' list")
    head = re.compile(r"^solution\s+\d+\s*:")
    var = re.compile(r"^\s*([A-Za-z_]\w*)\s*:\s*(\S+)\s+(\S+)\s*$")
    tail = re.compile(r"^==\s*err\s*:.*=\s*res\s*:\s*\S+\s*=\s*(.*?)\s*==\s*$")
    tline = re.compile(r"^t\s*:\s*(\S+)\s+(\S+)")
    block = None
    for line in text[k:].splitlines():
        if head.match(line):
            block = {"names": [], "values": [], "t": None, "reading": False}
        elif block is None:
            continue
        elif (m := tline.match(line)) and block["t"] is None:
            block["t"] = complex(float(m.group(1)), float(m.group(2)))
        elif line.strip().startswith("the solution for t"):
            block["reading"] = True
        elif (m := tail.match(line)):
            yield block["names"], block["values"], m.group(1).strip(), block["t"]
            block = None
        elif block["reading"] and (m := var.match(line)):
            block["names"].append(m.group(1))
            block["values"].append(complex(float(m.group(2)), float(m.group(3))))


def _read_phc(text: str) -> TheirRoots:
    variables, roots, classes, failed = None, [], {}, 0
    try:
        for names, values, cls, t in _phc_blocks(text):
            if variables is None:
                variables = tuple(names)
            elif tuple(names) != variables:
                raise CdprInputError("--roots", f"PHCpack solutions with different unknowns: {names} and {variables}")
            classes[cls] = classes.get(cls, 0) + 1
            unfinished = t is not None and abs(t - 1.0) > 1e-12
            if cls == "no solution" or (unfinished and cls != "at infinity"):  # PHCpack stops those short of 1
                failed += 1
            if cls in PHC_REGULAR and not unfinished:
                roots.append(values)
    except ValueError as exc:
        raise CdprInputError("--roots", f"unreadable number in the PHCpack solutions: {exc}") from None
    if variables is None:
        raise CdprInputError("--roots", "no solution in the PHCpack output's last 'THE SOLUTIONS' list")
    return TheirRoots("PHCpack", variables, np.array(roots, dtype=complex).reshape(-1, len(variables)), classes,
                      failed)


def _read_json(data) -> TheirRoots:
    if not isinstance(data, dict) or "variables" not in data or "roots" not in data:
        raise CdprInputError("--roots", "JSON roots need {\"variables\": [...], \"roots\": [[[re, im], ...], ...]}")
    variables = data["variables"]
    if not isinstance(variables, list) or not all(isinstance(v, str) for v in variables):
        raise CdprInputError("--roots", f"variables must be a list of names, got {variables!r}")
    rows = []
    for j, r in enumerate(data["roots"] if isinstance(data["roots"], list) else [None]):
        try:
            z = np.array([complex(*v) if isinstance(v, list) else complex(v) for v in r], dtype=complex)
        except (TypeError, ValueError):
            raise CdprInputError("--roots", f"root {j + 1}: expected [re, im] pairs or numbers, got {r!r}") from None
        if len(z) != len(variables) or not np.all(np.isfinite(z)):
            raise CdprInputError("--roots", f"root {j + 1}: expected {len(variables)} finite values, got {r!r}")
        rows.append(z)
    failed = data.get("failed")
    if failed is not None and (not isinstance(failed, int) or failed < 0):
        raise CdprInputError("--roots", f"failed must be a number of paths >= 0, got {failed!r}")
    return TheirRoots(str(data.get("solver", "their solver")), tuple(variables),
                      np.array(rows, dtype=complex).reshape(-1, len(variables)), {"regular": len(rows)}, failed)


def read_roots(path) -> TheirRoots:
    """Their roots from a PHCpack output file or a JSON file (module doc)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
    except OSError as exc:
        raise CdprInputError("--roots", f"cannot read {path}: {exc.strerror}") from None
    if text.lstrip().startswith("{"):
        try:
            return _read_json(json.loads(text))
        except json.JSONDecodeError as exc:
            raise CdprInputError("--roots", f"{path}: invalid JSON ({exc})") from None
    return _read_phc(text)


@dataclass(frozen=True)
class RootComparison:
    """Their roots against ours for one taut set (1-based ``taut``): counts with every tension nonzero, matched
    pairs (their index, our index), theirs not ours (``theirs_only``: their indices, ``theirs_only_proven``: which
    of them our Krawczyk test proves roots), ours not theirs (our indices), both sides' roots with a zero tension,
    ``agree`` (module doc) and the reason."""

    taut: tuple
    solver: str
    theirs: int
    ours: int
    ours_proven: int
    matched: tuple
    theirs_only: tuple
    theirs_only_proven: tuple
    ours_only: tuple
    theirs_zero_tension: int
    ours_zero_tension: int
    their_classes: dict
    their_failed: int | None
    our_subproblem: object
    agree: bool | None
    compared: str
    seconds: float
    their_roots: np.ndarray = field(repr=False, default=None)
    our_roots: np.ndarray = field(repr=False, default=None)

    def to_dict(self) -> dict:
        sub = self.our_subproblem
        return {"taut": list(self.taut), "solver": self.solver, "agree": self.agree, "compared": self.compared,
                "theirs": self.theirs, "ours": self.ours, "ours_proven": self.ours_proven,
                "matched": len(self.matched), "theirs_only": [jsonable(self.their_roots[j]) for j in self.theirs_only],
                "theirs_only_proven": list(self.theirs_only_proven),
                "ours_only": [jsonable(self.our_roots[i]) for i in self.ours_only],
                "theirs_zero_tension": self.theirs_zero_tension, "ours_zero_tension": self.ours_zero_tension,
                "their_classes": dict(self.their_classes), "their_failed": self.their_failed,
                "our_subproblem": sub.to_dict() if hasattr(sub, "to_dict") else None, "seconds": self.seconds}


def _zero_tension(Z, m) -> np.ndarray:
    scale = 1.0 + np.max(np.abs(Z), axis=1) if len(Z) else np.zeros(0)
    return np.any(np.abs(Z[:, 12:12 + m]) <= ZERO_LAM * scale[:, None], axis=1) if len(Z) else np.zeros(0, bool)


def match_roots(A, B) -> tuple:
    """Pairs (i, j) matching rows of A to rows of B one to one, nearest first, within ``MATCH_RTOL`` (1 + |a|) in
    every unknown (|.| the largest modulus)."""
    if not len(A) or not len(B):
        return ()
    d = np.max(np.abs(A[:, None, :] - B[None, :, :]), axis=2) / (1.0 + np.max(np.abs(A), axis=1))[:, None]
    pairs, used_a, used_b = [], set(), set()
    for flat in np.argsort(d, axis=None):
        i, j = divmod(int(flat), d.shape[1])
        if d[i, j] > MATCH_RTOL:
            break
        if i not in used_a and j not in used_b:
            pairs.append((i, j))
            used_a.add(i)
            used_b.add(j)
    return tuple(sorted(pairs))


def _their_roots_in_our_order(theirs: TheirRoots, m: int) -> np.ndarray:
    from cdpr_algebra.model.taut_equations import taut_unknowns

    ours = taut_unknowns(m)
    missing = [v for v in ours if v not in theirs.variables]
    extra = [v for v in theirs.variables if v not in ours]
    if missing or extra:
        raise CdprInputError("--roots", f"their unknowns must be those of `cdpr export` for {m} taut cables "
                                        f"({' '.join(ours)}); missing {missing}, unknown {extra}")
    return theirs.roots[:, [theirs.variables.index(v) for v in ours]]


def compare_root_sets(robot, rho, cables, theirs: TheirRoots, sub, Z, proven, seconds: float = 0.0) -> RootComparison:
    """The comparison (module doc) of their roots with ours (``sub``, ``Z``, ``proven`` as
    :func:`cdpr_algebra.dgp.solve.taut_set_roots` returns them) for the 0-based taut set ``cables``."""
    from cdpr_algebra.certificates.endpoints import certify_endpoints
    from cdpr_algebra.model.taut_equations import from_cable_frame

    m = len(cables)
    taut = tuple(c + 1 for c in cables)
    T = _their_roots_in_our_order(theirs, m)
    Z = np.zeros((0, 12 + m), complex) if Z is None else np.asarray(Z, dtype=complex)
    proven = np.asarray(proven, dtype=bool)
    tz, oz = _zero_tension(T, m), _zero_tension(Z, m)
    ti, oi = np.flatnonzero(~tz), np.flatnonzero(~oz)
    pairs = match_roots(T[ti], Z[oi])
    matched = tuple((int(ti[a]), int(oi[b])) for a, b in pairs)
    theirs_only = tuple(int(j) for j in sorted(set(ti) - {a for a, _ in matched}))
    ours_only = tuple(int(i) for i in sorted(set(oi) - {b for _, b in matched}))
    theirs_only_proven = ()
    if theirs_only:  # proven: a unique root in a Krawczyk box, within the match tolerance of the value they give
        X = T[list(theirs_only)]
        ((boxes, over),) = certify_endpoints(robot, rho, [(list(cables), X)])
        ok, _ = boxes.distinct(over)
        near = np.max(np.abs(from_cable_frame(boxes.center, robot.cable_frame) - X), axis=1) \
            <= MATCH_RTOL * (1.0 + np.max(np.abs(X), axis=1))
        theirs_only_proven = tuple(j for j, f in zip(theirs_only, ok & near) if f)
    n_ours_proven = int(np.sum(proven[oi])) if len(oi) else 0
    reasons, definite = [], []
    if theirs_only_proven:
        definite.append(f"{len(theirs_only_proven)} of their roots, proven roots by our Krawczyk test, are not among "
                        f"ours" + ("" if sub is not None and getattr(sub, "complete", False) else
                                   " (our subproblem is incomplete)"))
    unexplained = [i for i in ours_only if proven[i]]
    if unexplained and theirs.failed == 0:
        definite.append(f"{len(unexplained)} of our proven roots are not among theirs, and their file reports no "
                        f"failed path")
    elif ours_only:
        why = ("their file does not say whether paths failed" if theirs.failed is None else
               f"{theirs.failed} of their paths failed")
        reasons.append(f"{len(ours_only)} of ours are not among theirs ({why})")
    if len(theirs_only) > len(theirs_only_proven):
        reasons.append(f"{len(theirs_only) - len(theirs_only_proven)} of theirs are not among ours and not proven "
                       f"roots by our Krawczyk test")
    if n_ours_proven < len(oi):
        reasons.append(f"{len(oi) - n_ours_proven} of our roots are not proven")
    complete = bool(getattr(sub, "complete", False))
    if definite:
        agree, compared = False, "disagree: " + "; ".join(definite + reasons)
    elif reasons:
        agree, compared = None, "not compared: " + "; ".join(reasons)
    elif not complete:
        why = "" if theirs.failed is None else f"; {theirs.failed} of their paths failed"
        agree, compared = None, (f"not compared: the same {len(matched)} roots on both sides, but our subproblem is "
                                 f"incomplete{why}: a root both missed is not ruled out")
    else:
        agree, compared = True, (f"agree: {len(matched)} roots matched one to one, ours all proven, our subproblem "
                                 f"complete")
    return RootComparison(taut, theirs.solver, len(ti), len(oi), n_ours_proven, matched, theirs_only,
                          theirs_only_proven, ours_only, int(tz.sum()), int(oz.sum()), dict(theirs.classes),
                          theirs.failed, sub, agree, compared, seconds, T, Z)


def compare_roots(robot, rho, cables, path, seed: int = 0) -> RootComparison:
    """Their roots (file ``path``, :func:`read_roots`) of the 0-based taut set ``cables`` against ours."""
    from cdpr_algebra.dgp.solve import taut_set_roots

    if not 2 <= len(cables) <= 6:
        raise CdprInputError("--taut", f"roots are compared for 2 to 6 taut cables, got {len(cables)}")
    theirs = read_roots(path)
    _their_roots_in_our_order(theirs, len(cables))  # their unknowns checked before our run
    t0 = time.perf_counter()
    sub, Z, proven = taut_set_roots(robot, rho, cables, seed)
    return compare_root_sets(robot, rho, cables, theirs, sub, Z, proven, time.perf_counter() - t0)


def roots_report(c: RootComparison) -> str:
    """Lines for people: both sides' counts, the matches, the differences and the verdict."""
    from cdpr_algebra.dgp.solve import incompleteness

    sub = c.our_subproblem
    others = ", ".join(f"{k} {v}" for k, v in sorted(c.their_classes.items()) if k not in PHC_REGULAR)
    T = c.their_roots[~_zero_tension(c.their_roots, len(c.taut))]
    real_t = int(np.sum(np.all(np.abs(T.imag) <= 1e-8 * (1 + np.abs(T.real)), axis=1)))
    lines = [f"taut {list(c.taut)}: {c.solver} against cdpr_algebra (roots with every tension nonzero)",
             f"  theirs: {c.theirs} regular roots ({real_t} real), {c.theirs_zero_tension} more with a zero "
             f"tension" + (f"; their other solutions: {others}" if others else "")
             + ("" if c.their_failed is None else f"; {c.their_failed} failed paths"),
             f"  ours:   {c.ours} regular roots, {c.ours_proven} proven distinct roots, {c.ours_zero_tension} more with "
             f"a zero tension; our subproblem "
             + ("complete" if getattr(sub, "complete", False) else f"incomplete ({incompleteness(sub)})"),
             f"  matched one to one: {len(c.matched)}; theirs not ours: {len(c.theirs_only)} "
             f"({len(c.theirs_only_proven)} proven roots); ours not theirs: {len(c.ours_only)}"]
    for j in c.theirs_only_proven:
        x = c.their_roots[j]
        lines.append(f"    a proven root of theirs not among ours: p = {np.round(x[:3], 6).tolist()}, "
                     f"lam = {np.round(x[12:], 6).tolist()}")
    lines.append(f"  result: {c.compared} ({c.seconds:.3g} s)")
    return "\n".join(lines)
