"""Taut sets whose cable lines are linearly dependent at every pose (architectural singularity).

The wrench of cable i on the platform is tau_i / rho_i times its line (u_i, B_i x u_i), u_i = A_i - B_i
(:mod:`.statics`).  When the m lines of a taut set are dependent at every pose -- six cables on a planar base and a
planar platform related by a projectivity, e.g. two similar regular hexagons (Roeschel and Mick, 1998; Karger,
2003) -- the tensions of any equilibrium have a null direction: its equilibria are never isolated points of the
taut-set equations (the Jacobian is singular everywhere on them), and a homotopy count of that set means nothing.

Test (:func:`lines_dependent_everywhere`): the exact rank, in rationals from the robot file's doubles (python-flint
``fmpq_mat``), of the m x 6 line matrix at ``TRIALS`` poses with random rational rotations (Cayley transforms of
random rational skew matrices) and positions.  The maximal minors are polynomials in the pose; a nonzero one
vanishes on a proper algebraic set that random rational points avoid unless chosen with probability about
degree / (size of the sample range) = 4 / 2^30 each: rank < m at all of them is a polynomial identity test that
says "dependent at every pose" with error probability below 1e-25.  Rank m at one pose proves the lines
independent at generic poses (exactly).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from flint import fmpq, fmpq_mat

__all__ = ["lines_dependent_everywhere", "TRIALS"]

TRIALS = 3  # random rational poses
_RANGE = 2 ** 30  # numerators of the random rationals, over a denominator 2^20


def _q(v) -> fmpq:
    f = Fraction(float(v))
    return fmpq(f.numerator, f.denominator)


def _random_rational(rng) -> fmpq:
    return fmpq(int(rng.integers(-_RANGE, _RANGE)), 2 ** 20)


def _rational_rotation(rng) -> fmpq_mat:
    """R = (I - S)^-1 (I + S) for a random rational skew S: a rational rotation (Cayley)."""
    a, b, c = (_random_rational(rng) for _ in range(3))
    S = fmpq_mat(3, 3, [0, -c, b, c, 0, -a, -b, a, 0])
    eye = fmpq_mat(3, 3, [1, 0, 0, 0, 1, 0, 0, 0, 1])
    return (eye - S).inv() * (eye + S)


def _line_rank(A, b, R, p) -> int:
    rows = []
    for Ai, bi in zip(A, b):
        Bi = [p[k] + R[k, 0] * bi[0] + R[k, 1] * bi[1] + R[k, 2] * bi[2] for k in range(3)]
        u = [Ai[k] - Bi[k] for k in range(3)]
        rows += u + [Bi[1] * u[2] - Bi[2] * u[1], Bi[2] * u[0] - Bi[0] * u[2], Bi[0] * u[1] - Bi[1] * u[0]]
    return fmpq_mat(len(A), 6, rows).rank()


def lines_dependent_everywhere(robot, cables, seed: int = 0) -> bool:
    """True when the lines of the 0-based taut ``cables`` (m >= 2) are linearly dependent at every pose, by the exact
    rank test of the module doc (False as soon as one random pose has rank m)."""
    cables = [int(c) for c in cables]
    A = [[_q(v) for v in robot.base[i]] for i in cables]
    b = [[_q(v) for v in robot.platform[i]] for i in cables]
    rng = np.random.default_rng(seed)
    for _ in range(TRIALS):
        R = _rational_rotation(rng)
        p = [_random_rational(rng) for _ in range(3)]
        if _line_rank(A, b, R, p) == len(cables):
            return False
    return True
