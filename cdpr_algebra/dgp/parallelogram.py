"""Four taut cables on two parallelograms: the subfamily starts.

When the exit points of a taut set of four cables are a parallelogram (A_a + A_c = A_b + A_d) and its platform anchors
are a parallelogram with the same diagonals (b'_a + b'_c = b'_b + b'_d), the taut system
(:func:`cdpr_algebra.model.taut_equations.taut_family`) is a special member of its family, in one of these subfamilies
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
* ``"squares"``: two squares, G off their centre, the exit points' square in a plane normal to the load and the
  platform anchors' in a plane z' = const of the platform frame (a square frame's top corners and a square plate):
  168 of the 184 stay finite (measured, thirty-eighth session, from the off-centre set: six such robots, 168
  regular and 12 to 16 at infinity, three of them with 2 or 4 failed paths; rectangles, rhombi, and a square with
  a rectangle or a rhombus, 184 regular, complete).  Its relations add b = Rot90(a), the quarter turn about the
  normal, for each square (the cables ordered counter-clockwise about the upward normal -d, and the platform frame
  turned by pi about x' (:func:`flip_roots_back`) when its square turns the other way about z').
* ``"squares_axis"``: the same with G on the plate's axis (the normal through its centre: a load hanging below the
  middle of a square plate): 164 of the 168 stay finite (measured, thirty-eighth session, from the squares set:
  the ``designed`` square robots, 164 regular and 4 failed).  Its relations add g'_x = g'_y = 0.  NOT shipped: its
  set of 164 (monodromy with no target count; PHCpack's 164 on another member, matched both ways) did not pass the
  trace test (undecided, README), so such robots take the squares set until a certified one is stored.

In the normalized problem centred on the diagonals' midpoints (:func:`centred_frame`), every subfamily is linear:
A_1 + A_3 = A_2 + A_4 = 0, b'_1 + b'_3 = b'_2 + b'_4 = 0 (:func:`parallelogram_relations`), for the centred kind
g' = 0 too, for the squares the relations and values above (:func:`fixed_parameters`); the cables ordered so that
1, 3 and 2, 4 are the diagonals (:func:`parallelogram_order`).  Each shipped kind has its own generic solution set
(:func:`parallelogram_path`, made and certified by a trace test inside the subfamily,
``derivations/solve_generic_parallelogram.py --kind KIND``), the start of such taut sets; every route the DGP takes
stays on complex lines through two members of the subfamily, or perturbs it inside the subfamily.

Which robots: the parallelograms exact in the robot's doubles (rational arithmetic), as the interval certificates
read them.  A robot only near such one (seed 002's {1, 3, 5, 7}) is tracked from the generic set as before.
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from pathlib import Path

import numpy as np

from cdpr_algebra.homotopy.monodromy import with_relations

__all__ = ["KINDS", "PARALLELOGRAM_M", "centred_frame", "fixed_parameters", "flip_platform", "flip_roots_back",
           "parallelogram_kind", "parallelogram_order", "parallelogram_path", "parallelogram_relations",
           "parallelogram_start", "subfamily_target", "zero_parameters"]

DATA = Path(__file__).resolve().parent.parent / "data"
PARALLELOGRAM_M = 4
KINDS = ("centred", "off_centre", "squares", "squares_axis")
_FILES = {"centred": "parallelogram_generic_m4.json", "off_centre": "parallelogram_offcentre_generic_m4.json",
          "squares": "parallelogram_squares_generic_m4.json",
          "squares_axis": "parallelogram_squares_axis_generic_m4.json"}


def parallelogram_path(kind: str = "centred") -> Path:
    """The stored generic set of the subfamily ``kind`` (one of ``KINDS``)."""
    if kind not in KINDS:
        raise ValueError(f"parallelogram subfamily {kind!r}: expected one of {KINDS}")
    return DATA / _FILES[kind]


def parallelogram_relations(m: int = PARALLELOGRAM_M, kind: str = "centred") -> tuple:
    """The subfamily's relations in the parameters (A_i, rho_i^2, b'_i, g', Q d) of
    :func:`cdpr_algebra.model.taut_equations.taut_family`: A_1 + A_3 = 0, A_2 + A_4 = 0, b'_1 + b'_3 = 0,
    b'_2 + b'_4 = 0, each coordinate, as (index, coefficient) pairs (:class:`.homotopy.monodromy.MonodromyOptions`);
    for the squares, first A_2 = Rot90(A_1) and b'_2 = Rot90(b'_1) in x, y ((x, y) -> (-y, x))."""
    rel = []
    if kind.startswith("squares"):
        for first in (0, 4 * m):
            rel += [((first + 1, 1.0), (first + 3, 1.0)), ((first, 1.0), (first + 4, -1.0))]
    for first in (0, 4 * m):  # A_i from index 0, b'_i from 4 m
        for i, j in ((0, 2), (1, 3)):
            rel += [((first + 3 * i + k, 1.0), (first + 3 * j + k, 1.0)) for k in range(3)]
    return tuple(rel)


def zero_parameters(m: int = PARALLELOGRAM_M, kind: str = "centred") -> tuple:
    """The indices of the parameters that are 0 in the subfamily: g' for the centred kind (the centre of mass at the
    platform frame's origin), the z coordinates of A_i and b'_i for the squares (their planes), none else."""
    if kind == "centred":
        return tuple(7 * m + k for k in range(3))
    if not kind.startswith("squares"):
        return ()
    planes = tuple(first + 3 * i + 2 for first in (0, 4 * m) for i in range(m))
    return planes + ((7 * m, 7 * m + 1) if kind == "squares_axis" else ())


def fixed_parameters(m: int = PARALLELOGRAM_M, kind: str = "centred") -> tuple:
    """The indices of the parameters that keep their value in the subfamily: :func:`zero_parameters`, and for the
    squares the load Q d = (0, 0, -1) too (the exit points' plane normal to it)."""
    return zero_parameters(m, kind) + (tuple(7 * m + 3 + k for k in range(3)) if kind.startswith("squares") else ())


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


def _dot(u, v):
    return sum(x * y for x, y in zip(u, v))


def _arms(points, order) -> tuple:
    """(u, v) = (P_a - c, P_b - c), c the diagonals' midpoint, in rationals."""
    a, b, c, _ = order
    P = {i: _exact(points[i]) for i in (a, b, c)}
    mid = [(x + y) / 2 for x, y in zip(P[a], P[c])]
    return [x - y for x, y in zip(P[a], mid)], [x - y for x, y in zip(P[b], mid)]


def _square(u, v, normal) -> bool:
    """u, v half diagonals of a square (equal, perpendicular, not 0) in a plane normal to ``normal``."""
    return _dot(u, u) == _dot(v, v) != 0 and _dot(u, v) == 0 and _dot(u, normal) == 0 == _dot(v, normal)


def _turns(u, v, axis) -> int:
    """The sign of (u x v) . axis (+1: u to v counter-clockwise about the axis)."""
    w = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    t = _dot(w, axis)
    return (t > 0) - (t < 0)


def parallelogram_kind(robot, order) -> str:
    """The subfamily of the two parallelograms ``order`` (:func:`parallelogram_order`), exactly in rationals:
    ``"centred"`` when the platform anchors' are centred on the centre of mass (b'_a + b'_c = 2 g'); else
    ``"squares_axis"`` when both are squares, the exit points' in a plane normal to the load direction and the
    anchors' in a plane z' = const, G on the plate's axis (the normal through its centre); ``"squares"`` with G
    elsewhere (each when its stored set exists); else ``"off_centre"``."""
    a, _, c, _ = order
    mid = [(x + y) / 2 for x, y in zip(_exact(robot.platform[a]), _exact(robot.platform[c]))]
    g = _exact(robot.com)
    if mid == g:
        return "centred"
    if _square(*_arms(robot.base, order), _exact(robot.load_direction)) and _square(*_arms(robot.platform, order),
                                                                                    [0, 0, 1]):
        for kind in (("squares_axis",) if mid[:2] == g[:2] else ()) + ("squares",):
            if parallelogram_path(kind).exists():
                return kind
    return "off_centre"


def flip_platform(robot, order) -> bool:
    """For the squares: True when the platform anchors' square turns clockwise about z' in ``order`` (the platform
    frame is then turned by pi about x' for the subfamily, :func:`subfamily_target`, :func:`flip_roots_back`)."""
    return _turns(*_arms(robot.platform, order), [0, 0, 1]) < 0


def flip_roots_back(X, m: int = PARALLELOGRAM_M) -> np.ndarray:
    """Roots (p, u, v, w, lam) in the platform frame turned by pi about x' (R0 = diag(1, -1, -1): b'' = R0 b') ->
    the normalized problem's: R = R'' R0, its columns (u, -v, -w); p unchanged (the turn is about the origin)."""
    X = np.array(X, copy=True).reshape(-1, 12 + m)
    X[:, 6:12] *= -1
    return X


def parallelogram_order(robot, cables) -> tuple | None:
    """The 0-based taut ``cables`` reordered (a, b, c, d) so that a, c and b, d are the diagonals of a parallelogram
    of exit points and of one of platform anchors, exactly in the robot's doubles (for the squares, a, b, c, d
    counter-clockwise about the upward normal); None when there are not four cables, no such pairing, or no stored
    set for its kind (:func:`parallelogram_kind`)."""
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
            kind = parallelogram_kind(robot, order)
            up = [-x for x in _exact(robot.load_direction)]
            if kind.startswith("squares") and _turns(*_arms(robot.base, order), up) < 0:
                order = a, d, c, b  # counter-clockwise about the upward normal
            return order if parallelogram_path(kind).exists() else None
    return None


def centred_frame(robot, order) -> tuple:
    """(c, cb) of the normalized problem of the taut set ``order`` (:func:`.normalization.normalized_problem`): the
    midpoints of the exit points' diagonals and of the platform anchors' (the centre of mass for the centred kind),
    where the subfamily's relations hold."""
    a, _, c, _ = order
    return (robot.base[a] + robot.base[c]) / 2, (robot.platform[a] + robot.platform[c]) / 2


def subfamily_target(params, kind: str = "centred", flip: bool = False, m: int = PARALLELOGRAM_M) -> np.ndarray:
    """The normalized parameters in :func:`centred_frame`, put exactly in the subfamily ``kind`` (their rounding off
    it removed: each relation's last point set from the others, :func:`with_relations`, and the
    :func:`zero_parameters` set to 0); ``flip``: the platform frame first turned by pi about x' (b'_i and g' with y,
    z negated, :func:`flip_platform`)."""
    p = np.array(params, dtype=float, copy=True)
    if flip:
        for i in range(m + 1):  # b'_1 .. b'_m, g'
            p[4 * m + 3 * i + 1:4 * m + 3 * i + 3] *= -1
    p[list(zero_parameters(m, kind))] = 0.0
    return with_relations(p, parallelogram_relations(m, kind)).real
