"""Poses and rotation parametrizations.

* Fixed-axes angles (seed 000 tables): R = Rz(phi_z) Ry(phi_y) Rx(phi_x), angles in radians.
* Euler parameters (e0, e1, e2, e3), seed 004 eq. (20):
  R = I + 2 (e0 E + E E) / (e0^2 + e1^2 + e2^2 + e3^2), E = skew(e1, e2, e3); scale-free (projective),
  so e0 = 0 (half-turns) is included.
* Rodrigues parameters: Euler parameters normalized to e0 = 1, i.e. (e1, e2, e3) = axis * tan(theta / 2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import CdprInputError


def skew(v) -> np.ndarray:
    """The matrix of the operator v x."""
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def rotation_about(axis, theta) -> np.ndarray:
    """The rotation by ``theta`` (radians) about the unit ``axis`` (Rodrigues' formula)."""
    K = skew(axis)
    return np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K


def rotation_taking(a, b) -> np.ndarray:
    """A rotation R with R a = b (unit vectors): the smallest one, or a half-turn when b = -a."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    v = np.cross(a, b)
    c = float(a @ b)
    if np.linalg.norm(v) < 1e-14:
        if c > 0:
            return np.eye(3)
        axis = np.cross(a, [1.0, 0, 0])
        if np.linalg.norm(axis) < 1e-8:
            axis = np.cross(a, [0, 1.0, 0])
        axis /= np.linalg.norm(axis)
        return 2 * np.outer(axis, axis) - np.eye(3)
    K = skew(v)
    return np.eye(3) + K + K @ K / (1 + c)


def rot_x(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


def rot_z(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def matrix_from_angles(phi_x: float, phi_y: float, phi_z: float) -> np.ndarray:
    """R = Rz(phi_z) Ry(phi_y) Rx(phi_x): rotations about the fixed x, then y, then z axes."""
    return rot_z(phi_z) @ rot_y(phi_y) @ rot_x(phi_x)


def angles_from_matrix(R) -> np.ndarray:
    """Inverse of :func:`matrix_from_angles`, phi_y in [-pi/2, pi/2]; at gimbal lock phi_x = 0."""
    R = np.asarray(R, dtype=float)
    sy = -R[2, 0]
    sy = min(1.0, max(-1.0, sy))
    phi_y = np.arcsin(sy)
    if abs(abs(sy) - 1.0) < 1e-12:
        phi_x = 0.0
        phi_z = np.arctan2(-R[0, 1], R[1, 1])
    else:
        phi_x = np.arctan2(R[2, 1], R[2, 2])
        phi_z = np.arctan2(R[1, 0], R[0, 0])
    return np.array([phi_x, phi_y, phi_z])


def matrix_from_euler_parameters(e) -> np.ndarray:
    """Seed 004 eq. (20). ``e`` = (e0, e1, e2, e3), any non-zero scale; real or complex; a stack (..., 4) gives
    (..., 3, 3).  Written out: R = ((e0^2 - v.v) I + 2 v v^T + 2 e0 skew(v)) / (e0^2 + v.v), v = (e1, e2, e3)."""
    e = np.asarray(e)
    e0, v = e[..., 0], e[..., 1:]
    n2 = e0 * e0 + np.sum(v * v, axis=-1)
    if np.any(n2 == 0):
        raise CdprInputError("euler_parameters", "e0^2 + e1^2 + e2^2 + e3^2 must not vanish")
    vv = np.sum(v * v, axis=-1)
    R = 2.0 * v[..., :, None] * v[..., None, :]
    R = R + ((e0 * e0 - vv)[..., None, None] * np.eye(3))
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    R[..., 0, 1] -= 2 * e0 * z
    R[..., 1, 0] += 2 * e0 * z
    R[..., 0, 2] += 2 * e0 * y
    R[..., 2, 0] -= 2 * e0 * y
    R[..., 1, 2] -= 2 * e0 * x
    R[..., 2, 1] += 2 * e0 * x
    return R / n2[..., None, None]


def matrix_from_rodrigues(e1, e2, e3) -> np.ndarray:
    """Seed 004 eq. (20) with e0 = 1."""
    return matrix_from_euler_parameters(np.array([1.0, e1, e2, e3]))


def euler_parameters_from_matrix(R) -> np.ndarray:
    """Unit quaternion (e0, e1, e2, e3), scalar first, with e0 >= 0 (Shepperd's method)."""
    R = np.asarray(R, dtype=float)
    t = np.trace(R)
    cands = [t, R[0, 0], R[1, 1], R[2, 2]]
    k = int(np.argmax(cands))
    if k == 0:
        e0 = 0.5 * np.sqrt(1.0 + t)
        q = np.array([e0, (R[2, 1] - R[1, 2]) / (4 * e0), (R[0, 2] - R[2, 0]) / (4 * e0), (R[1, 0] - R[0, 1]) / (4 * e0)])
    elif k == 1:
        e1 = 0.5 * np.sqrt(max(0.0, 1.0 + 2 * R[0, 0] - t))
        q = np.array([(R[2, 1] - R[1, 2]) / (4 * e1), e1, (R[0, 1] + R[1, 0]) / (4 * e1), (R[0, 2] + R[2, 0]) / (4 * e1)])
    elif k == 2:
        e2 = 0.5 * np.sqrt(max(0.0, 1.0 + 2 * R[1, 1] - t))
        q = np.array([(R[0, 2] - R[2, 0]) / (4 * e2), (R[0, 1] + R[1, 0]) / (4 * e2), e2, (R[1, 2] + R[2, 1]) / (4 * e2)])
    else:
        e3 = 0.5 * np.sqrt(max(0.0, 1.0 + 2 * R[2, 2] - t))
        q = np.array([(R[1, 0] - R[0, 1]) / (4 * e3), (R[0, 2] + R[2, 0]) / (4 * e3), (R[1, 2] + R[2, 1]) / (4 * e3), e3])
    if q[0] < 0:
        q = -q
    return q / np.linalg.norm(q)


def rodrigues_from_matrix(R) -> np.ndarray | None:
    """(e1, e2, e3) with e0 = 1, or None for a half-turn (e0 = 0)."""
    q = euler_parameters_from_matrix(R)
    if q[0] < 1e-14:
        return None
    return q[1:] / q[0]


def check_rotation(R, fieldname: str = "rotation", tol: float = 1e-9) -> np.ndarray:
    try:
        R = np.asarray(R, dtype=float)
    except (TypeError, ValueError):
        raise CdprInputError(fieldname, "expected a 3x3 matrix of numbers") from None
    if R.shape != (3, 3):
        raise CdprInputError(fieldname, f"expected a 3x3 matrix, got shape {R.shape}")
    if not np.all(np.isfinite(R)):
        raise CdprInputError(fieldname, "expected finite numbers")
    if np.abs(R.T @ R - np.eye(3)).max() > tol or np.linalg.det(R) < 0:
        raise CdprInputError(fieldname, "not a rotation matrix (R^T R != I or det R != 1)")
    return R


@dataclass(frozen=True)
class Pose:
    """Platform pose: ``position`` of the platform-frame origin (world frame) and ``rotation`` matrix."""

    position: np.ndarray
    rotation: np.ndarray

    def __post_init__(self):
        p = np.asarray(self.position, dtype=float).reshape(3)
        R = np.asarray(self.rotation, dtype=float).reshape(3, 3)
        p.setflags(write=False)
        R.setflags(write=False)
        object.__setattr__(self, "position", p)
        object.__setattr__(self, "rotation", R)

    @classmethod
    def from_angles(cls, position, angles) -> "Pose":
        return cls(position, matrix_from_angles(*angles))

    @classmethod
    def from_com(cls, com_position, rotation, com_local) -> "Pose":
        """The pose whose centre of mass (platform frame ``com_local``) is at ``com_position``."""
        R = np.asarray(rotation, dtype=float)
        return cls(np.asarray(com_position, dtype=float) - R @ np.asarray(com_local, dtype=float), R)

    @property
    def angles(self) -> np.ndarray:
        return angles_from_matrix(self.rotation)

    @property
    def euler_parameters(self) -> np.ndarray:
        return euler_parameters_from_matrix(self.rotation)

    def transform(self, points_local) -> np.ndarray:
        """World coordinates p + R b of platform-frame points (rows)."""
        return self.position + np.asarray(points_local, dtype=float) @ self.rotation.T

    def to_dict(self) -> dict:
        return {"position": self.position.tolist(), "rotation": self.rotation.tolist(), "angles": self.angles.tolist()}
