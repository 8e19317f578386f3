"""Options and results of the interval branch-and-prune (:class:`BPOptions`, :class:`IntervalSubproblem`, ...)."""

from __future__ import annotations

from dataclasses import dataclass, field
import numpy as np
from cdpr_algebra.report.jsonable import jsonable
from cdpr_algebra.model.pose import angles_from_matrix



_INF = np.inf


@dataclass(frozen=True)
class BPOptions:
    """Tolerances of the branch and prune (widths relative to the robot size L; lam relative to Q / L)."""

    eps: float = 1e-9  # minimum width: boxes narrower than this and undecided are reported
    krawczyk_width: float = 0.05  # Krawczyk unicity test / contraction on boxes narrower than this
    newton_width: float = 0.02  # epsilon-inflation around a Newton point on boxes narrower than this
    batch: int = 4096  # boxes processed together
    max_sweeps: int = 3  # filter iterations per box (compiled, filter_order 1: of the geometric contractors)
    taylor_iterations: int = 2  # applications of the second-order operator per batch
    sweep_gain: float = 0.1  # ... repeated while some box shrinks by more than this fraction
    max_boxes: int = 20_000_000  # safety stop (then the remaining boxes are reported undecided)
    bisection: str = "widest"  # "widest" (seed 000); "smear": where the Krawczyk operator was formed, the variable
    # j maximizing max_i |I - C J(X)|_ij w_j / scale_i; "taylor": the largest share of the second-order part of the
    # width of T(X).  Measured on Test 1: the three give the same number of boxes within 2 %.
    kernels: str = "compiled"  # filter and second-order operators: "compiled" (numba, box by box) or "numpy"
    # (vectorized, the reference the tests compare with)
    filter_order: int = 1  # compiled filter: 1 geometric sweeps then statics; 0 all contractors per sweep (the
    # vectorized order)
    unicity_gate: bool = True  # Krawczyk unicity test only where the second-order operator maps the box into its
    # interior (Brouwer: the box holds a solution)
    statics_rows: tuple = ("poles", "axes", "gauss")  # statics row families: moments about the exit points
    # ("poles"), about the axes A_j A_k ("axes"), the interval Gauss elimination ("gauss")


# ---------------------------------------------------------------------------------------------------------------
# results
@dataclass(frozen=True)
class IntervalSolution:
    """A proven equilibrium: unique solution of the equation set in ``box`` (core variables), enclosed in
    ``enclosure``; pose and tensions are floats inside the enclosure.  ``taut`` is 1-based."""

    taut: tuple
    position: np.ndarray
    rotation: np.ndarray
    tensions: np.ndarray  # n values, 0 for slack cables
    enclosure_width: float  # max width of the enclosure (model units)
    variables: tuple = ()
    enclosure_lo: np.ndarray = field(default_factory=lambda: np.zeros(0))
    enclosure_hi: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def angles(self) -> np.ndarray:
        return angles_from_matrix(self.rotation)

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "position": jsonable(self.position), "angles": jsonable(self.angles),
                "rotation": jsonable(self.rotation), "tensions": jsonable(self.tensions),
                "enclosure_width": self.enclosure_width, "variables": list(self.variables),
                "enclosure_lo": jsonable(self.enclosure_lo), "enclosure_hi": jsonable(self.enclosure_hi)}


@dataclass(frozen=True)
class UndecidedBox:
    """A box neither excluded nor proven to hold a unique admissible solution (``reason`` says why)."""

    taut: tuple
    reason: str
    variables: tuple
    lo: np.ndarray
    hi: np.ndarray
    position: np.ndarray | None = None  # a pose inside the box (platform origin), when it can be formed
    tensions: np.ndarray | None = None

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "reason": self.reason, "variables": list(self.variables),
                "lo": jsonable(self.lo), "hi": jsonable(self.hi),
                "position": None if self.position is None else jsonable(self.position),
                "tensions": None if self.tensions is None else jsonable(self.tensions)}


@dataclass(frozen=True)
class IntervalSubproblem:
    taut: tuple  # 1-based
    solutions: tuple  # IntervalSolution, admissible and proven
    undecided: tuple  # UndecidedBox
    boxes: int  # boxes processed
    bisections: int
    proven_inadmissible: int  # proven solutions of the equation set outside the admissible domain
    seconds: float
    method: str = ""
    skipped: str | None = None
    undecided_reasons: dict | None = None  # {reason: boxes}, every undecided box counted (``undecided`` keeps some)

    @property
    def admissible(self) -> int:
        return len(self.solutions)

    @property
    def undecided_by_reason(self) -> dict:
        """{reason: boxes} of every undecided box: as the search counted them (``undecided_reasons``), else those
        of ``undecided``."""
        if self.undecided_reasons is not None:
            return dict(self.undecided_reasons)
        out = {}
        for u in self.undecided:
            out[u.reason] = out.get(u.reason, 0) + 1
        return out

    @property
    def n_undecided(self) -> int:
        """Undecided boxes, all of them (``undecided`` holds the first ``bp.search.UNDECIDED_KEPT``)."""
        return sum(self.undecided_by_reason.values())

    @property
    def complete(self) -> bool:
        return self.n_undecided == 0

    @property
    def status(self) -> str:
        """'complete' (every admissible equilibrium proven, none undecided), 'skipped' or 'undecided'."""
        return "skipped" if self.skipped else ("complete" if self.complete else "undecided")

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "status": self.status, "admissible": self.admissible, "complete": self.complete,
                "solutions": [s.to_dict() for s in self.solutions],
                "undecided": [u.to_dict() for u in self.undecided], "undecided_count": self.n_undecided,
                "undecided_reasons": self.undecided_by_reason, "boxes": self.boxes,
                "bisections": self.bisections, "proven_inadmissible": self.proven_inadmissible,
                "seconds": self.seconds, "method": self.method, "skipped": self.skipped}


@dataclass(frozen=True)
class IntervalDGPResult:
    subproblems: tuple
    seconds: float

    @property
    def solutions(self) -> tuple:
        return tuple(s for sub in self.subproblems for s in sub.solutions)

    @property
    def undecided(self) -> tuple:
        return tuple(u for sub in self.subproblems for u in sub.undecided)

    def by_m(self, m: int) -> tuple:
        return tuple(s for s in self.solutions if len(s.taut) == m)

    @property
    def status(self) -> str:
        """'complete' when every subproblem is, else 'undecided' (some box undecided or subproblem skipped)."""
        return "complete" if all(s.status == "complete" for s in self.subproblems) else "undecided"

    def to_dict(self) -> dict:
        return {"status": self.status, "subproblems": [s.to_dict() for s in self.subproblems], "seconds": self.seconds,
                "admissible": len(self.solutions), "undecided": sum(s.n_undecided for s in self.subproblems)}
