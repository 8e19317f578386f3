"""The normalized problem the DGP tracks (a taut set's parameters in the frame of its cable geometry, load 1) and
the maps between its coordinates and the robot's world coordinates."""

from __future__ import annotations

import numpy as np

from cdpr_algebra.model.pose import rotation_taking
from cdpr_algebra.model.taut_equations import from_cable_frame, to_cable_frame

__all__ = ["normalized_coordinates", "normalized_problem", "world_coordinates"]


def normalized_problem(robot, rho, cables, frame=None):
    """(parameters of the normalized problem, c, L, Rw, cb): world coordinates x' = Rw (x - c) / L with Rw taking
    the load direction to -z (the direction of the stored generic sets: a straight parameter path from there never
    passes near a vanishing load), load 1, and the platform frame moved to the centroid cb of the platform points
    (b'_i - cb, g' - cb: the pose's origin is then at the cables' attachment points wherever the robot file puts it).
    L (:attr:`Robot.cable_scale`) is the size of the cable geometry alone: a centre of mass far from the attachment points
    (a long boom, or robots built with huge internal forces, tests/large_forces.py) does not shrink it.  Measured
    (thirteenth session, m = 4 and 5, K = 1e5, g' 1e4-1.5e5 sizes away): 0-2 failed paths instead of 138-194 with
    the robot's size, which includes |b'_i - g'|.  ``frame``: other origins (c, cb) (a subfamily's,
    :func:`.parallelogram.centred_frame`)."""
    c, cb = robot.cable_frame if frame is None else frame
    L = robot.cable_scale
    Rw = rotation_taking(robot.load_direction, np.array([0.0, 0.0, -1.0]))
    idx = list(cables)
    params = np.concatenate([((robot.base[idx] - c) @ Rw.T / L).ravel(), (rho[idx] / L) ** 2,
                             ((robot.platform[idx] - cb) / L).ravel(), (robot.com - cb) / L, [0.0, 0.0, -1.0]])
    return params, c, L, Rw, cb


def world_coordinates(X, m, c, L, Rw, cb, Q):
    """Roots (p^, u^, v^, w^, lam^) of the normalized problem (complex rows) -> (p, u, v, w, lam) of the robot:
    columns of R = Rw^T R^, p = c + L Rw^T p^ - R cb, lam = Q lam^ / L (see :func:`normalized_problem`)."""
    Y = np.hstack([L * (X[:, 0:3] @ Rw), X[:, 3:6] @ Rw, X[:, 6:9] @ Rw, X[:, 9:12] @ Rw, Q * X[:, 12:12 + m] / L])
    return from_cable_frame(Y, (c, cb))


def normalized_coordinates(X, m, c, L, Rw, cb, Q):
    """The inverse of :func:`world_coordinates`: rows (p, u, v, w, lam) of the robot -> (p^, u^, v^, w^, lam^),
    u^ = Rw u (and v, w), p^ = Rw (p + R cb - c) / L, lam^ = L lam / Q."""
    Y = to_cable_frame(X, (c, cb))
    return np.hstack([Y[:, 0:3] @ Rw.T / L, Y[:, 3:6] @ Rw.T, Y[:, 6:9] @ Rw.T, Y[:, 9:12] @ Rw.T,
                      L * Y[:, 12:12 + m] / Q])
