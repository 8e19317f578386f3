"""Four taut cables on two centred parallelograms: the subfamily start.

When the exit points of a taut set of four cables are a parallelogram (A_a + A_c = A_b + A_d) and its platform anchors
are a parallelogram with the same diagonals whose centre is the centre of mass (b'_a + b'_c = b'_b + b'_d = 2 g'),
the taut system (:func:`cdpr_algebra.model.taut_equations.taut_family`) is a special member of its family: only 152
of its 216 generic solutions stay finite.  The most common suspended robot is one: a rectangular frame's four top
corners and a flat rectangular platform with G at its centre.  A parameter homotopy from the generic set follows the
other 64 paths towards infinity, and the endgame does not decide all of them (measured, thirty-fifth session:
``examples/symmetric_4cables.toml`` with G at the plate's centre, 40 failed paths; their Study paths approach a
positive-dimensional set at N = e . e = 0 where the steps shrink like the radius squared).

In the normalized problem centred on the diagonals' midpoint and on G (:func:`centred_frame`), the subfamily is
linear: A_1 + A_3 = A_2 + A_4 = 0, b'_1 + b'_3 = b'_2 + b'_4 = 0 (:func:`parallelogram_relations`) and g' = 0
(:func:`fixed_parameters`), the cables ordered so that 1, 3 and 2, 4 are the diagonals (:func:`parallelogram_order`).
Its own generic solution set (``cdpr_algebra/data/parallelogram_generic_m4.json``, made and certified by a trace test
inside the subfamily, ``derivations/solve_generic_parallelogram.py``) is the start of such taut sets; every route the
DGP takes stays on complex lines through two members of the subfamily, or perturbs it inside the subfamily.

Which robots: the parallelograms exact in the robot's doubles (rational arithmetic), as the interval certificates
read them.  A robot only near such a one (seed 002's {1, 3, 5, 7}) is tracked from the generic set as before.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from pathlib import Path

import numpy as np

from cdpr_algebra.homotopy.monodromy import with_relations

__all__ = ["PARALLELOGRAM_M", "centred_frame", "fixed_parameters", "parallelogram_order", "parallelogram_path",
           "parallelogram_relations", "parallelogram_start", "subfamily_target"]

DATA = Path(__file__).resolve().parent.parent / "data"
PARALLELOGRAM_M = 4


def parallelogram_path() -> Path:
    return DATA / f"parallelogram_generic_m{PARALLELOGRAM_M}.json"


def parallelogram_relations(m: int = PARALLELOGRAM_M) -> tuple:
    """The subfamily's relations in the parameters (A_i, rho_i^2, b'_i, g', Q d) of
    :func:`cdpr_algebra.model.taut_equations.taut_family`: A_1 + A_3 = 0, A_2 + A_4 = 0, b'_1 + b'_3 = 0,
    b'_2 + b'_4 = 0, each coordinate, as (index, coefficient) pairs (:class:`.homotopy.monodromy.MonodromyOptions`)."""
    rel = []
    for first in (0, 4 * m):  # A_i from index 0, b'_i from 4 m
        for i, j in ((0, 2), (1, 3)):
            rel += [((first + 3 * i + k, 1.0), (first + 3 * j + k, 1.0)) for k in range(3)]
    return tuple(rel)


def fixed_parameters(m: int = PARALLELOGRAM_M) -> tuple:
    """The indices of g': 0 in the subfamily (the centre of mass at the platform frame's origin)."""
    return tuple(7 * m + k for k in range(3))


@lru_cache(maxsize=None)
def parallelogram_start():
    """(parameters, solutions) of the stored generic set of the subfamily (loaded once per process; the system's hash
    is checked by tests/test_dgp_parallelogram.py)."""
    from cdpr_algebra.homotopy.monodromy import load_instance

    from .taut_system import fast_family

    p, X, _ = load_instance(parallelogram_path(), fast_family(PARALLELOGRAM_M), check_hash=False)
    return p, X


def _exact(v) -> list:
    return [Fraction(float(c)) for c in v]


def parallelogram_order(robot, cables) -> tuple | None:
    """The 0-based taut ``cables`` reordered (a, b, c, d) so that a, c and b, d are the diagonals of a parallelogram
    of exit points and of one of platform anchors centred on the centre of mass, exactly in the robot's doubles;
    None when there are not four cables, no stored subfamily set, or no such pairing."""
    idx = sorted(int(c) for c in cables)
    if len(idx) != PARALLELOGRAM_M or not parallelogram_path().exists():
        return None
    A = {i: _exact(robot.base[i]) for i in idx}
    B = {i: _exact(robot.platform[i]) for i in idx}
    g2 = [2 * c for c in _exact(robot.com)]
    a = idx[0]
    for c in idx[1:]:
        b, d = [i for i in idx[1:] if i != c]
        if all(A[a][k] + A[c][k] == A[b][k] + A[d][k] and B[a][k] + B[c][k] == g2[k] == B[b][k] + B[d][k]
               for k in range(3)):
            return a, b, c, d
    return None


def centred_frame(robot, order) -> tuple:
    """(c, cb) of the normalized problem of the taut set ``order`` (:func:`.normalization.normalized_problem`): the
    midpoint of the exit points' diagonals and the centre of mass, where the subfamily's relations hold."""
    a, _, c, _ = order
    return (robot.base[a] + robot.base[c]) / 2, np.array(robot.com, dtype=float)


def subfamily_target(params) -> np.ndarray:
    """The normalized parameters in :func:`centred_frame`, put exactly in the subfamily (their rounding off it
    removed: g' = 0 and each relation's second point the negative of its first, :func:`with_relations`)."""
    p = np.array(params, dtype=float, copy=True)
    p[list(fixed_parameters())] = 0.0
    return with_relations(p, parallelogram_relations()).real
