"""Immutable result records of the homotopy engine, each with ``to_dict()`` (JSON-ready).

* :class:`PathResult` -- one path: return code (status), endpoint, residual, condition number,
  accuracy estimate, steps, winding number, whether it was retried and how.
* :class:`TrackResult` -- all paths of one homotopy plus the summary counts (paths, success,
  real, singular, at_infinity, failed, seconds, seed) and :meth:`TrackResult.summary_line`.
* :class:`Solution` / :class:`SolveResult` -- distinct solutions (with multiplicity) built from
  the endpoints.

Return codes (``status``): ``success`` (finite, nonsingular endpoint refined by Newton),
``singular`` (finite endpoint where dF/dx is singular, or winding number > 1), ``at_infinity``
(the path diverges as t -> 0), and the failures ``step_too_small``, ``too_many_steps``,
``diverged`` (a non-finite value or a blow-up away from t = 0), ``endgame_failed`` (the endgame could not
decide between a finite endpoint and infinity), ``path_jumping`` (the path ends on a nonsingular point that
another path reached too, after the re-tracking rounds).  Each status is one of four *outcomes*
(:func:`outcome`): ``regular``, ``singular``, ``at_infinity``, ``failed``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, asdict
from typing import Optional

import numpy as np



def complex_list(a) -> list:
    """A complex vector as JSON-ready [[re, im], ...] (the engine's records carry no other array)."""
    return [[float(z.real), float(z.imag)] for z in np.asarray(a, dtype=complex).ravel()]


def _number(v):
    """A float, int, bool, complex ([re, im]) or None field as a JSON-ready value."""
    if v is None or isinstance(v, (bool, np.bool_)):
        return None if v is None else bool(v)
    if isinstance(v, (complex, np.complexfloating)):
        return [float(v.real), float(v.imag)]
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v)
    return v

SUCCESS = "success"
SINGULAR = "singular"
AT_INFINITY = "at_infinity"
STEP_TOO_SMALL = "step_too_small"
TOO_MANY_STEPS = "too_many_steps"
DIVERGED = "diverged"
ENDGAME_FAILED = "endgame_failed"
PATH_JUMPING = "path_jumping"
FAILURES = (STEP_TOO_SMALL, TOO_MANY_STEPS, DIVERGED, ENDGAME_FAILED, PATH_JUMPING)
STATUSES = (SUCCESS, SINGULAR, AT_INFINITY) + FAILURES
OUTCOMES = ("regular", "singular", "at_infinity", "failed")


def outcome(status: str) -> str:
    """The outcome of a path with this status: regular, singular, at_infinity or failed."""
    if status == SUCCESS:
        return "regular"
    if status in (SINGULAR, AT_INFINITY):
        return status
    if status in FAILURES:
        return "failed"
    raise ValueError(f"unknown path status {status!r}")


def outcome_counts(paths) -> dict:
    """{"regular": .., "singular": .., "at_infinity": .., "failed": ..} over PathResults (they add up to len)."""
    counts = dict.fromkeys(OUTCOMES, 0)
    for p in paths:
        counts[outcome(p.status)] += 1
    return counts


@dataclass(frozen=True)
class PathResult:
    """Outcome of one path. ``endpoint`` is complex (n,); for failures it is the last point reached."""

    index: int
    status: str
    endpoint: np.ndarray
    t: complex  # t reached (0 when the path finished)
    residual: float  # max-norm of F(endpoint) (relative to 1 + |x|)
    condition: float  # 2-norm condition number of dF/dx at the endpoint
    accuracy: float  # estimated error of the endpoint (last Newton update or endgame estimate difference)
    steps: int  # accepted + rejected steps, all phases
    winding_number: int = 1
    retried: str = ""  # "", "tight" (double precision, tighter settings), "mpmath", "projective" or "gamma"
    order: float = float("nan")  # at_infinity in a chart: y0 ~ t^order (order > 0), estimated by the endgame
    # at_infinity after Cauchy samples: the path at the sample radius before the last (t), and that radius; None
    # where the endgame took no two samples (see valuation)
    previous: np.ndarray | None = None
    previous_t: complex | None = None

    def __post_init__(self):
        ep = np.array(self.endpoint, dtype=complex)
        ep.setflags(write=False)
        object.__setattr__(self, "endpoint", ep)
        if self.previous is not None:
            v = np.array(self.previous, dtype=complex)
            v.setflags(write=False)
            object.__setattr__(self, "previous", v)

    def valuation(self, cols=slice(None)) -> float:
        """v in max_j |x_j(t)| ~ |t|^v over the coordinates ``cols`` (a slice or indices), from the endpoint (the last
        sample) and ``previous`` of a path decided at infinity after Cauchy samples (NaN without them): negative where
        those coordinates grow without bound as t -> 0 (a block of a Puiseux series, v = -k / c on a path of winding
        number c), ~0 where they stay finite."""
        if self.previous is None or self.previous_t is None:
            return float("nan")
        with np.errstate(all="ignore"):
            a = np.max(np.abs(self.endpoint[cols]))
            b = np.max(np.abs(self.previous[cols]))
            return float(np.log(a / b) / np.log(abs(self.t) / abs(self.previous_t)))

    @property
    def is_success(self) -> bool:
        return self.status == SUCCESS

    @property
    def is_failed(self) -> bool:
        return self.status in FAILURES

    def is_real(self, tol: float = 1e-8) -> bool:
        return bool(np.all(np.abs(self.endpoint.imag) <= tol * (1 + np.abs(self.endpoint.real))))

    def to_dict(self) -> dict:
        d = {k: _number(v) for k, v in asdict(self).items() if k not in ("endpoint", "previous", "previous_t")}
        d["endpoint"] = complex_list(self.endpoint)
        return d


@dataclass(frozen=True)
class Summary:
    """Counts of a run. ``real`` counts real endpoints among ``success``."""

    paths: int
    success: int
    real: int
    singular: int
    at_infinity: int
    failed: int
    seconds: float
    seed: Optional[int]
    retried: int = 0
    solutions: Optional[int] = None  # distinct finite solutions (nonsingular + singular clusters), if known

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass(frozen=True)
class TrackResult:
    """All paths of one homotopy run."""

    paths: tuple
    seconds: float
    seed: Optional[int] = None
    options: dict = field(default_factory=dict)

    def __len__(self):
        return len(self.paths)

    def statuses(self) -> list:
        return [p.status for p in self.paths]

    def count(self, status: str) -> int:
        return sum(p.status == status for p in self.paths)

    @property
    def failed(self) -> list:
        return [p for p in self.paths if p.is_failed]

    def endpoints(self, status: str | None = SUCCESS) -> np.ndarray:
        sel = [p.endpoint for p in self.paths if status is None or p.status == status]
        n = len(self.paths[0].endpoint) if self.paths else 0
        return np.array(sel, dtype=complex).reshape(len(sel), n)

    def summary(self, solutions: int | None = None) -> Summary:
        return Summary(
            paths=len(self.paths),
            success=self.count(SUCCESS),
            real=sum(p.is_success and p.is_real() for p in self.paths),
            singular=self.count(SINGULAR),
            at_infinity=self.count(AT_INFINITY),
            failed=sum(p.is_failed for p in self.paths),
            seconds=self.seconds,
            seed=self.seed,
            retried=sum(bool(p.retried) for p in self.paths),
            solutions=solutions,
        )

    def summary_line(self) -> str:
        return summary_line(self.summary())

    def to_dict(self) -> dict:
        return {"summary": self.summary().to_dict(), "options": _plain_options(self.options),
                "paths": [p.to_dict() for p in self.paths]}


def summary_line(s: Summary) -> str:
    sol = f"{s.solutions} solutions, " if s.solutions is not None else ""
    return (f"{sol}{s.success} nonsingular ({s.real} real), {s.singular} singular, {s.at_infinity} at infinity, "
            f"{s.failed} failed; {s.paths} paths tracked in {s.seconds:.3f} s"
            f"{f' ({s.retried} retried)' if s.retried else ''}; seed {s.seed}")


@dataclass(frozen=True)
class Solution:
    """A distinct finite solution: the mean of the endpoints of ``paths`` (``multiplicity`` of them)."""

    x: np.ndarray
    multiplicity: int
    singular: bool
    residual: float
    condition: float
    accuracy: float
    paths: tuple

    def __post_init__(self):
        x = np.array(self.x, dtype=complex)
        x.setflags(write=False)
        object.__setattr__(self, "x", x)

    def is_real(self, tol: float = 1e-8) -> bool:
        return bool(np.all(np.abs(self.x.imag) <= tol * (1 + np.abs(self.x.real))))

    def to_dict(self) -> dict:
        return {"x": complex_list(self.x), "multiplicity": int(self.multiplicity), "singular": bool(self.singular),
                "residual": float(self.residual), "condition": float(self.condition),
                "accuracy": float(self.accuracy), "paths": [int(i) for i in self.paths]}


def _plain_options(v):
    """Options (nested dicts of numbers, strings, tuples) as JSON-ready values."""
    if isinstance(v, dict):
        return {k: _plain_options(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_plain_options(x) for x in v]
    return _number(v)


@dataclass(frozen=True)
class SolveResult:
    """Distinct solutions of a solve plus the underlying :class:`TrackResult`."""

    solutions: tuple
    track: TrackResult
    start_system: str = ""

    @property
    def nonsingular(self) -> list:
        return [s for s in self.solutions if not s.singular]

    @property
    def singular(self) -> list:
        return [s for s in self.solutions if s.singular]

    def real_solutions(self, tol: float = 1e-8) -> list:
        return [s for s in self.solutions if s.is_real(tol)]

    def solution_array(self, nonsingular_only: bool = True) -> np.ndarray:
        sel = self.nonsingular if nonsingular_only else list(self.solutions)
        n = self.track.paths[0].endpoint.size if self.track.paths else 0
        return np.array([s.x for s in sel], dtype=complex).reshape(len(sel), n)

    def summary(self) -> Summary:
        return self.track.summary(solutions=len(self.solutions))

    def summary_line(self) -> str:
        return summary_line(self.summary())

    def to_dict(self) -> dict:
        return {"start_system": self.start_system, "summary": self.summary().to_dict(),
                "solutions": [s.to_dict() for s in self.solutions], "track": self.track.to_dict()}


RUNNING = ""  # status of a path still being tracked (inside one segment)


@dataclass
class SegmentResult:
    """Arrays over the paths of one :func:`track_segment` call."""

    x: np.ndarray  # (N, n) last point
    s: np.ndarray  # (N,) fraction of the segment reached
    t: np.ndarray  # (N,) complex t reached
    status: np.ndarray  # (N,) object: SUCCESS or a failure code
    steps: np.ndarray  # (N,) int
    h: np.ndarray  # (N,) last step (fraction of the segment)
    extended: np.ndarray | None = None  # (N,) bool: Newton residuals in double-double (compiled tracker) or None
