"""Interval certificate of one equilibrium of a family that turns about the line of the taut anchors (issue 15).

When the taut anchors B_i and the centre of mass G lie on one line of the platform, the platform turns freely
about it: the taut system's solutions are circles, and no point of them is an isolated root to certify.  As for
one taut cable (:mod:`.equilibria`, m = 1), a square sub-formulation isolates the reported point: the moment
equations are kept only along two world directions e1, e2 orthogonal to the family's axis a (the line's direction
at the reported pose), and the turning angle is fixed by the gauge t . (R c) = 0, c a platform vector orthogonal to
the line, t = a x (R0 c) for the reported rotation R0 (:func:`.equilibria._gauged_system`).

Why a root of the sub-formulation is an equilibrium: given force balance, the moment rows (about the world origin)
equal the moment about G, sum (B_k - G) x F_k, and each B_k - G is parallel to the line's direction e(x) at that
pose, so the moment is orthogonal to e(x).  It is also orthogonal to e1 and e2, so it is zero whenever e(x) is
not in span(e1, e2) -- true in the certified box, where e(x) is within its width of a.  The argument needs the
robot's anchors and centre of mass exactly collinear, which is checked in exact rational arithmetic
(:func:`collinear_exactly`) on the doubles the robot holds or, with ``reading`` DECIMAL, on the decimals that print
them: decimal data collinear on paper, such as a centre of mass at 0.4 of a diagonal, are seldom collinear once
rounded, and their family is one of the robot read in decimal (its taut anchors and centre of mass as those
decimals, enclosed exactly; the rest as doubles), not of the doubles.

The certificate proves the reported pose (existence and uniqueness in its box under the gauge, tension signs,
slack cables), not the whole arc; its H_r class is undecided (the turn is a null direction).
"""

from __future__ import annotations

import numpy as np

from .equilibria import (BOX_RTOL, FLINT, Certificate, _consequences, _failed, _gauged_system, _krawczyk,
                         _robot_data, _scales, _turning_gauge)
from cdpr_algebra.model.rod_equations import BINARY, exact_rational
from cdpr_algebra.model.taut_equations import encode, to_cable_frame

__all__ = ["certify_turning_equilibrium", "collinear_exactly", "exact_line"]


def collinear_exactly(points, reading: str = BINARY) -> bool:
    """Whether the 3-vectors ``points`` (doubles) lie on one line, in exact rational arithmetic on their binary values
    or, with ``reading`` DECIMAL, on the decimals that print them
    (:func:`cdpr_algebra.model.rod_equations.exact_rational`)."""
    return exact_line(points, reading) is not None


def exact_line(points, reading: str = BINARY):
    """(P, d) when the ``points`` lie on one line in ``reading`` (see :func:`collinear_exactly`): P the points as
    exact fractions, d = (the point farthest from P[0]) - P[0] (all zero when every point is at P[0]); else None."""
    P = [[exact_rational(v, reading) for v in p] for p in points]
    o = P[0]
    far = max(P, key=lambda q: sum((q[k] - o[k]) ** 2 for k in range(3)))
    d = [far[k] - o[k] for k in range(3)]
    for q in P if any(d) else ():
        w = [q[k] - o[k] for k in range(3)]
        if any(d[(k + 1) % 3] * w[(k + 2) % 3] - d[(k + 2) % 3] * w[(k + 1) % 3] for k in range(3)):
            return None
    return P, d


def certify_turning_equilibrium(robot, lengths, cables, position, rotation, tensions,
                                box_rtol: float = BOX_RTOL, reading: str = BINARY) -> Certificate:
    """Certificate of the reported pose of a family turning about the line of the taut anchors (0-based ``cables``,
    m >= 2) and G: ``position``, ``rotation``, the m taut ``tensions``; ``lengths`` all n (None: the robot's);
    ``reading``: the taut anchors and G as the robot's doubles or as the decimals that print them (module doc)."""
    from flint import ctx

    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)
    taut = [int(c) for c in cables]
    m = len(taut)
    tensions = np.asarray(tensions, dtype=float).ravel()
    if m < 2 or tensions.shape != (m,):
        raise ValueError(f"expected 2..6 taut cables and one tension each, got {m} cables and {tensions.shape}")
    if not collinear_exactly([robot.platform[i] for i in taut] + [robot.com], reading):
        return _failed("dgp", robot.n, f"the taut anchors and the centre of mass are not exactly collinear in the "
                                       f"robot's {reading} data: no exact family to certify a point of", None, taut)
    R0 = np.asarray(rotation, dtype=float)
    arms = robot.platform[taut] - robot.platform[taut[0]]
    arm = arms[int(np.argmax(np.linalg.norm(arms, axis=1)))]
    gauge = _turning_gauge(R0 @ arm / np.linalg.norm(arm), arm, R0)
    frame = robot.cable_frame
    x0 = to_cable_frame(encode(np.asarray(position, float), R0, tensions / rho[taut])[None], frame)[0]

    def make_system(num):
        A, b, g, f = _robot_data(robot, taut, num, frame=frame, reading=reading)
        return _gauged_system(A, b, g, f, [num(float(rho[i])) ** 2 for i in taut], *gauge)

    scale = _scales(robot, m, range(12 + m), robot.cable_scale, x0)
    with FLINT, ctx.workprec(53):
        kr = _krawczyk(make_system, x0, scale, box_rtol)
        if not kr.proven:
            return _failed("dgp", robot.n, kr.reason, kr, taut)
        X = kr.enclosure
        R = [[X[3 + k], X[6 + k], X[9 + k]] for k in range(3)]
        return _consequences("dgp", robot, taut, rho, X[0:3], R, X[12:], kr, kr.relative_width(scale),
                             robot.cable_scale, extra={"family": "turning about the line of the taut anchors and G "
                                                                 "(gauge-fixed point; the arc is not certified)",
                                                       "reading": reading},
                             frame=frame, reading=reading)
