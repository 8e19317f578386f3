"""The records of one DGP: an admissible equilibrium (:class:`DGPSolution`) and one taut set's account
(:class:`DGPSubproblem`), small immutable objects with ``to_dict()`` (:mod:`.solve` makes them)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from cdpr_algebra.homotopy.results import OUTCOMES
from cdpr_algebra.model.pose import angles_from_matrix
from cdpr_algebra.model.rod_equations import BINARY
from cdpr_algebra.report.jsonable import jsonable

__all__ = ["DGPSolution", "DGPSubproblem", "PARALLELOGRAM_STARTS"]

# the JSON name of each parallelogram subfamily's stored generic set (dgp.parallelogram.KINDS)
PARALLELOGRAM_STARTS = {"centred": "parallelogram_generic", "off_centre": "parallelogram_offcentre_generic",
                        "squares": "parallelogram_squares_generic", "squares_axis": "parallelogram_squares_axis_generic"}


@dataclass(frozen=True)
class DGPSolution:
    """One admissible equilibrium. ``taut`` is 1-based; ``tensions`` has n values (0 for slack cables)."""

    taut: tuple
    position: np.ndarray
    rotation: np.ndarray
    tensions: np.ndarray
    hessian: str
    certified: bool | None = None
    certificate: object = None  # certify.Certificate (interval proof, issue 5) or None when not certified
    alternatives: tuple = ()  # the same pose found with other taut sets (redundantly constrained): DGPSolutions
    found_by: str = "homotopy"  # or "interval": proven by the branch and prune of a subproblem the homotopy left incomplete
    reading: str = BINARY  # DECIMAL: an equilibrium of the robot read in decimal (taut anchors collinear only so)

    def with_certificate(self, cert) -> "DGPSolution":
        """This solution with an interval certificate attached (the proven stability class replaces the floating
        point one when the certificate proves it)."""
        cls = cert.hessian_class if cert.hessian == "proven" and cert.hessian_class else self.hessian
        return replace(self, certified=bool(cert.certified), certificate=cert, hessian=cls)

    @property
    def angles(self) -> np.ndarray:
        return angles_from_matrix(self.rotation)

    @property
    def stable(self) -> bool:
        return self.hessian == ">"

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "position": jsonable(self.position), "angles": jsonable(self.angles),
                "rotation": jsonable(self.rotation), "tensions": jsonable(self.tensions), "hessian": self.hessian,
                "stable": self.stable, "certified": self.certified,
                "certificate": None if self.certificate is None else self.certificate.to_dict(),
                "found_by": self.found_by, "reading": self.reading,
                "alternatives": [{"taut": list(a.taut), "tensions": jsonable(a.tensions), "hessian": a.hessian,
                                  "certified": a.certified} for a in self.alternatives]}


@dataclass(frozen=True)
class DGPSubproblem:
    """One taut set.  ``outcomes``: paths per outcome (regular, singular, at_infinity, failed; they add up to
    ``paths``); ``failures``: failed paths per reason; ``certified`` (``certified_real``): regular endpoints proven
    to be distinct roots (real roots) by Krawczyk boxes that are pairwise disjoint (:func:`cdpr_algebra.certificates.endpoints.certify_endpoints`;
    None where no path was tracked), ``uncertified``: the others per reason; ``complete``: no path failed, the
    outcomes account for the generic count, and every regular endpoint is certified (or the set is proven empty by
    pruning, or proven to hold no admissible equilibrium by the interval filter -- ``excluded``, not tracked, its
    inadmissible solutions not counted -- or solved analytically); ``family``: when regular endpoints that the
    certificates refuse, or singular endpoints, lie on a positive-dimensional solution set, what
    :mod:`.positive_dimensional` saw there (the real families of turning equilibria listed; the subproblem stays
    incomplete), or, for a taut set solved as a rod (:mod:`.rod`), its families, one per root (complete when the
    rod's account is); ``collinear_anchors``: the reading (binary or decimal) of a taut set whose anchors lie on a
    line with G off it, tracked from that subfamily's generic set (:mod:`.collinear_anchors`; None otherwise);
    ``parallelogram``: the 1-based cables in the order of their diagonals when the exit points and the platform
    anchors are two parallelograms, tracked from the generic set of that subfamily (:mod:`.parallelogram`; None
    otherwise), whose kind (the anchors' centred on G or not) is ``parallelogram_kind``."""

    taut: tuple  # 1-based
    paths: int
    finite: int  # distinct finite solutions (regular endpoints, and singular ones counted once)
    real: int
    admissible: int
    seconds: float
    skipped: str | None = None
    outcomes: dict = field(default_factory=lambda: dict.fromkeys(OUTCOMES, 0))
    failures: dict = field(default_factory=dict)
    complete: bool = True
    generic_count: int | None = None
    certified: int | None = None  # regular endpoints proven unique in pairwise disjoint Krawczyk boxes
    certified_real: int | None = None  # of those, proven real
    uncertified: dict = field(default_factory=dict)  # regular endpoints not certified, per reason
    settled: str | None = None  # how the admissible set was proven complete although the homotopy's account is not
    excluded: int | None = None  # boxes of the interval proof that the set holds no admissible equilibrium (not tracked)
    retried: dict = field(default_factory=dict)  # paths whose outcome came from a retry, per kind (taut, detour, ..)
    family: object = None  # positive_dimensional.Family: uncertified endpoints on positive-dimensional sets
    collinear_anchors: str | None = None  # tracked from the collinear-anchors subfamily: the robot's reading there
    parallelogram: tuple | None = None  # tracked from a parallelograms subfamily: the diagonals' order
    parallelogram_kind: str | None = None  # that subfamily: "centred", "off_centre", .. (dgp.parallelogram.KINDS)

    @property
    def admissible_complete(self) -> bool:
        """Every admissible equilibrium of this taut set is known: the homotopy's account is complete, or the set
        was ``settled`` by another proof (:func:`cdpr_algebra.comparison.settle.settle_incomplete`)."""
        return self.complete or self.settled is not None

    @property
    def accounted(self) -> bool:
        """No failed path, and the outcomes add up to the generic count (a count of paths, no proof)."""
        return self.outcomes["failed"] == 0 and sum(self.outcomes.values()) == self.generic_count

    @property
    def failed_paths(self) -> int:
        return self.outcomes["failed"]

    @property
    def at_infinity(self) -> int:
        return self.outcomes["at_infinity"]

    @property
    def status(self) -> str:
        """'complete' or 'incomplete' (see ``complete``)."""
        return "complete" if self.complete else "incomplete"

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "status": self.status, "paths": self.paths, "outcomes": dict(self.outcomes),
                "failures": dict(self.failures), "complete": self.complete, "generic_count": self.generic_count,
                "certified": self.certified, "certified_real": self.certified_real,
                "uncertified": dict(self.uncertified),
                "finite": self.finite, "real": self.real, "admissible": self.admissible,
                "failed_paths": self.failed_paths, "seconds": self.seconds, "skipped": self.skipped,
                "settled": self.settled, "admissible_complete": self.admissible_complete, "excluded": self.excluded,
                "retried": dict(self.retried),
                "positive_dimensional": None if self.family is None else self.family.to_dict(),
                "collinear_anchors": None if self.collinear_anchors is None else
                {"start": "collinear_generic", "reading": self.collinear_anchors},
                "parallelogram": None if self.parallelogram is None else
                {"start": PARALLELOGRAM_STARTS.get(self.parallelogram_kind), "kind": self.parallelogram_kind,
                 "diagonals": [list(self.parallelogram[0::2]), list(self.parallelogram[1::2])]}}
