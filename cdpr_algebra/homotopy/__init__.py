"""Homotopy continuation engine (issue #3): every isolated solution of a polynomial system.

Flat topic modules, after HomotopyContinuation.jl:

* :mod:`.systems` -- polynomial systems with parameters, compiled once into batched numpy evaluators;
* :mod:`.homotopies` -- straight-line (gamma trick) and parameter homotopies;
* :mod:`.tracker` -- vectorized RK4 / Newton path tracker of one segment, :func:`track_segment` (compiled:
  :mod:`.compiled`, with Newton residuals in double-double where double precision stalls, :mod:`.double_double`);
* :mod:`.endgame` -- Cauchy endgame, at-infinity test, Newton refinement, retries (double, mpmath);
* :mod:`.flint_tracker` -- the same step in arbitrary precision (python-flint) over a plain-Python evaluator;
* :mod:`.hybrid_tracker` -- double precision, extended precision only on the stretches where it fails;
* :mod:`.dd_tracker` -- that step compiled in double-double over a rewritten generated evaluator;
* :mod:`.start_systems` -- total degree, multi-homogeneous (linear product), parameter homotopy;
* :mod:`.monodromy` -- generic solution sets from one seed point, saved/loaded instances;
* :mod:`.many_targets` -- :func:`solve_targets`, the one many-target parameter homotopy (the DGP per taut set, the
  robustness radii; chart systems batched as labelled paths);
* :mod:`.trace_test` -- the trace test that certifies a monodromy solution set complete;
* :mod:`.results` -- immutable per-path and summary records;
* :mod:`.solve` -- :func:`solve`, :func:`solve_parameter_homotopy`.
"""

from .systems import PolynomialSystem
from .homotopies import ParameterHomotopy, StraightLineHomotopy
from .tracker import TrackerOptions, track_segment
from .endgame import EndgameOptions, SolveOptions, track_paths
from .start_systems import (multi_homogeneous, multi_homogeneous_bezout_number, bezout_number, parameter_homotopy,
                            total_degree)
from .results import PathResult, Solution, SolveResult, Summary, TrackResult
from .solve import group_solutions, solve, solve_parameter_homotopy
from .many_targets import solve_targets

__all__ = [
    "PolynomialSystem", "ParameterHomotopy", "StraightLineHomotopy", "TrackerOptions", "track_paths", "track_segment",
    "EndgameOptions", "SolveOptions", "multi_homogeneous", "multi_homogeneous_bezout_number", "bezout_number",
    "parameter_homotopy", "total_degree", "PathResult", "Solution", "SolveResult", "Summary", "TrackResult",
    "group_solutions", "solve", "solve_parameter_homotopy", "solve_targets",
]
