"""Four taut cables on two parallelograms: the subfamily starts.

When the exit points of a taut set of four cables are a parallelogram (A_a + A_c = A_b + A_d) and its platform anchors
are a parallelogram with the same diagonals (b'_a + b'_c = b'_b + b'_d), the taut system
(:func:`cdpr_algebra.model.taut_equations.taut_family`) is a special member of its family, of one of two subfamilies
(``KINDS``):

* ``"centred"``: the anchors' parallelogram centred on the centre of mass (b'_a + b'_c = 2 g'): only 152 of the 216
  generic solutions stay finite.  A rectangular frame's four top corners and a flat rectangular platform with G at
  its centre is one.  A parameter homotopy from the generic set follows the other 64 paths towards infinity, and the
  endgame does not decide all of them (measured, thirty-fifth session: ``examples/symmetric_4cables.toml`` with G at
  the plate's centre, 40 failed paths; their Study paths approach a positive-dimensional set at N = e . e = 0 where
  the steps shrink like the radius squared).
* ``"off_centre"``: G anywhere else (a load hanging below a rectangular plate): 184 of the 216 stay finite
  (measured, thirty-eighth session: four random pairs of parallelograms with G off their centre, 184 regular and 30
  or 32 at infinity, two of them with 2 failed paths; squares similar to each other, ``designed`` robots of
  ``benchmarks/bench_random_robots.py``, 9 to 20 failed).

In the normalized problem centred on the diagonals' midpoints (:func:`centred_frame`), both subfamilies are linear:
A_1 + A_3 = A_2 + A_4 = 0, b'_1 + b'_3 = b'_2 + b'_4 = 0 (:func:`parallelogram_relations`), and for the centred kind
g' = 0 too (:func:`fixed_parameters`); the cables ordered so that 1, 3 and 2, 4 are the diagonals
(:func:`parallelogram_order`).  Each has its own generic solution set (:func:`parallelogram_path`, made and certified
by a trace test inside the subfamily, ``derivations/solve_generic_parallelogram.py [--kind off_centre]``), the start
of such taut sets; every route the DGP takes stays on complex lines through two members of the subfamily, or perturbs
it inside the subfamily.

Which robots: the parallelograms exact in the robot's doubles (rational arithmetic), as the interval certificates
read them.  A robot only near such one (seed 002's {1, 3, 5, 7}) is tracked from the generic set as before.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from pathlib import Path

import numpy as np

from cdpr_algebra.homotopy.monodromy import with_relations

__all__ = ["KINDS", "PARALLELOGRAM_M", "centred_frame", "fixed_parameters", "parallelogram_kind", "parallelogram_order",
           "parallelogram_path", "parallelogram_relations", "parallelogram_start", "subfamily_target"]

DATA = Path(__file__).resolve().parent.parent / "data"
PARALLELOGRAM_M = 4
KINDS = ("centred", "off_centre")


def parallelogram_path(kind: str = "centred") -> Path:
    """The stored generic set of the subfamily ``kind`` (one of ``KINDS``)."""
    if kind not in KINDS:
        raise ValueError(f"parallelogram subfamily {kind!r}: expected one of {KINDS}")
    return DATA / ("parallelogram_generic_m4.json" if kind == "centred" else "parallelogram_offcentre_generic_m4.json")


def parallelogram_relations(m: int = PARALLELOGRAM_M) -> tuple:
    """The subfamily's relations in the parameters (A_i, rho_i^2, b'_i, g', Q d) of
    :func:`cdpr_algebra.model.taut_equations.taut_family`: A_1 + A_3 = 0, A_2 + A_4 = 0, b'_1 + b'_3 = 0,
    b'_2 + b'_4 = 0, each coordinate, as (index, coefficient) pairs (:class:`.homotopy.monodromy.MonodromyOptions`)."""
    rel = []
    for first in (0, 4 * m):  # A_i from index 0, b'_i from 4 m
        for i, j in ((0, 2), (1, 3)):
            rel += [((first + 3 * i + k, 1.0), (first + 3 * j + k, 1.0)) for k in range(3)]
    return tuple(rel)


def fixed_parameters(m: int = PARALLELOGRAM_M, kind: str = "centred") -> tuple:
    """The indices of g' for the centred kind (0 there: the centre of mass at the platform frame's origin); none for
    the off-centre kind."""
    return tuple(7 * m + k for k in range(3)) if kind == "centred" else ()


@lru_cache(maxsize=None)
def parallelogram_start(kind: str = "centred"):
    """(parameters, solutions) of the stored generic set of the subfamily ``kind`` (loaded once per process; the
    system's hash is checked by tests/test_dgp_parallelogram.py)."""
    from cdpr_algebra.homotopy.monodromy import load_instance

    from .taut_system import fast_family

    p, X, _ = load_instance(parallelogram_path(kind), fast_family(PARALLELOGRAM_M), check_hash=False)
    return p, X


def _exact(v) -> list:
    return [Fraction(float(c)) for c in v]


def parallelogram_kind(robot, order) -> str:
    """``"centred"`` when the platform anchors' parallelogram ``order`` (:func:`parallelogram_order`) is centred on
    the centre of mass exactly (b'_a + b'_c = 2 g' in rationals), else ``"off_centre"``."""
    a, _, c, _ = order
    B = [_exact(robot.platform[i]) for i in (a, c)]
    return "centred" if all(B[0][k] + B[1][k] == 2 * g for k, g in enumerate(_exact(robot.com))) else "off_centre"


def parallelogram_order(robot, cables) -> tuple | None:
    """The 0-based taut ``cables`` reordered (a, b, c, d) so that a, c and b, d are the diagonals of a parallelogram
    of exit points and of one of platform anchors, exactly in the robot's doubles; None when there are not four
    cables, no such pairing, or no stored set for its kind (:func:`parallelogram_kind`)."""
    idx = sorted(int(c) for c in cables)
    if len(idx) != PARALLELOGRAM_M:
        return None
    A = {i: _exact(robot.base[i]) for i in idx}
    B = {i: _exact(robot.platform[i]) for i in idx}
    a = idx[0]
    for c in idx[1:]:
        b, d = [i for i in idx[1:] if i != c]
        if all(A[a][k] + A[c][k] == A[b][k] + A[d][k] and B[a][k] + B[c][k] == B[b][k] + B[d][k] for k in range(3)):
            order = a, b, c, d
            return order if parallelogram_path(parallelogram_kind(robot, order)).exists() else None
    return None


def centred_frame(robot, order) -> tuple:
    """(c, cb) of the normalized problem of the taut set ``order`` (:func:`.normalization.normalized_problem`): the
    midpoints of the exit points' diagonals and of the platform anchors' (the centre of mass for the centred kind),
    where the subfamily's relations hold."""
    a, _, c, _ = order
    return (robot.base[a] + robot.base[c]) / 2, (robot.platform[a] + robot.platform[c]) / 2


def subfamily_target(params, kind: str = "centred") -> np.ndarray:
    """The normalized parameters in :func:`centred_frame`, put exactly in the subfamily ``kind`` (their rounding off
    it removed: each relation's second point the negative of its first, :func:`with_relations`, and for the centred
    kind g' = 0)."""
    p = np.array(params, dtype=float, copy=True)
    p[list(fixed_parameters(kind=kind))] = 0.0
    return with_relations(p, parallelogram_relations()).real
