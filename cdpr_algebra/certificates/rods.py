"""Interval certificates of the roots of the rod system: the families of equilibria of a taut set whose platform
anchors and centre of mass lie on one line (issue 15).

The rod system (:mod:`cdpr_algebra.model.rod_equations`) has one isolated root per family: the line's pose (G, u)
and the multipliers lam_i, mu.  Its constants are rational in the robot's doubles when the points are exactly
collinear (s_i = (b'_i - g').D / D.D and D.D exact as fractions, :func:`cdpr_algebra.model.rod_equations.
line_coordinates`), and are enclosed here, as are rho_i^2 and Q d; the exit points A_i are doubles.  Each root is
proven unique in a box of C^(m+7) by the Krawczyk test of :func:`cdpr_algebra.intervals.complex_krawczyk.
certify_complex_roots` (real or non-real proven where decidable), and the proven boxes that meet another are found
(those roots are not proven distinct).  A proven root is a whole family: every turn of the platform about the line
keeps B_i = G + s_i u and G, hence every equation of the 6-DOF taut system.
"""

from __future__ import annotations

import numpy as np

from cdpr_algebra.generated.rod_equations import rod_equations

__all__ = ["certify_rod_roots", "rod_scales"]


def _enclosed(value):
    """An Interval enclosing a :class:`fractions.Fraction` or a double (a point for a double)."""
    from cdpr_algebra.intervals.arithmetic import Interval, enclose_fraction

    lo, hi = enclose_fraction(value)
    return Interval(np.float64(lo), np.float64(hi))


def rod_scales(robot, m: int, DD) -> np.ndarray:
    """The size of each unknown (G, u, lam, mu) of the rod system: the cable geometry's scale L, |D|, Q / L, Q / |D|."""
    L, Q, d = robot.cable_scale, robot.load, float(np.sqrt(float(DD)))
    return np.array([L] * 3 + [d] * 3 + [Q / L] * m + [Q / d])


def certify_rod_roots(robot, lengths, cables, s, DD, Z):
    """(:class:`cdpr_algebra.intervals.complex_krawczyk.ComplexRootBoxes`, overlapping (N,) bool) for the roots Z
    (N x (m + 7), world coordinates (G, u, lam, mu)) of the rod system of the 0-based taut ``cables`` with the exact
    line coordinates ``s`` and ``DD`` (fractions); ``lengths`` all n (None: the robot's)."""
    from cdpr_algebra.intervals.arithmetic import Interval
    from cdpr_algebra.intervals.complex_krawczyk import certify_complex_roots

    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)
    idx = [int(c) for c in cables]
    m = len(idx)
    Z = np.asarray(Z, dtype=complex).reshape(-1, m + 7)
    A = [float(v) for i in idx for v in robot.base[i]]
    exact = (A + [Interval.point(float(rho[i])).sqr() for i in idx] + [_enclosed(v) for v in s] + [_enclosed(DD)]
             + [Interval.point(robot.load) * float(c) for c in robot.load_direction])
    approx = (A + [float(rho[i]) ** 2 for i in idx] + [float(v) for v in s] + [float(DD)]
              + [robot.load * float(c) for c in robot.load_direction])

    def system(p):
        def evaluate(x, rows, jacobian):
            n = len(x)
            F = np.zeros(n, dtype=object)
            J = np.zeros((n, n), dtype=object) if jacobian else None
            rod_equations(list(x), p, F, J, jacobian)
            return list(F), ([list(r) for r in J] if jacobian else None)

        return evaluate

    boxes = certify_complex_roots(system(exact), system(approx), Z, rod_scales(robot, m, DD))
    return boxes, boxes.meeting()
