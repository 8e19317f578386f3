"""Taut sets whose platform anchors lie on one line and whose centre of mass does not: the subfamily start.

With m >= 3 taut platform anchors on a line and G off it, gravity alone fixes the platform's turn about the line,
and the taut system of m cables (:func:`cdpr_algebra.model.taut_equations.taut_family`) is a special member of its
family: of the generic solutions (156, 216, 140 for m = 3, 4, 5) all but 76, 56, 16 leave to infinity, along
complex rotations about the line whose entries grow without bound.  A parameter homotopy from the generic set
follows them there and the endgame does not always decide them (measured, twenty-sixth session: the beam of
``examples/beam_4cables.toml`` with G 0.25 below its line, 2, 2 and 7 paths "step too small" at |x| ~ 6e5).

The anchors on the x axis, b'_i = (s_i, 0, 0), are a linear subfamily of the parameters (:func:`fixed_parameters`
stay 0); its own generic solution set (``cdpr_algebra/data/collinear_generic_m{m}.json``, made and certified by a
trace test inside the subfamily, ``derivations/solve_generic_collinear.py``) is the start of such taut sets: the
normalized problem (:func:`.normalization.normalized_problem`) in a platform frame turned so that the line is its
x axis (:class:`LineFrame`), tracked inside the subfamily (every route the DGP takes stays on complex lines
through two members, or perturbs only the free parameters), its roots turned back.

Which robot is solved: the anchors exactly collinear in the robot's doubles (reading BINARY), or else in the
decimals that print them (DECIMAL, :func:`cdpr_algebra.model.rod_equations.exact_rational`): then it is the robot
read in decimal, whose endpoints are proven in ball arithmetic with those decimals
(:func:`cdpr_algebra.certificates.endpoints.certify_endpoints`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from cdpr_algebra.model.pose import rotation_taking
from cdpr_algebra.model.rod_equations import BINARY, DECIMAL

__all__ = ["COLLINEAR_M", "LineFrame", "collinear_path", "fixed_parameters", "line_frame", "collinear_start"]

DATA = Path(__file__).resolve().parent.parent / "data"
COLLINEAR_M = (3, 4, 5)  # m = 2: any two anchors are on a line (the generic set is that case); m = 6: no solution


def collinear_path(m: int) -> Path:
    return DATA / f"collinear_generic_m{m}.json"


def fixed_parameters(m: int) -> tuple:
    """Indices, in the parameters (A_i, rho_i^2, b'_i, g', Q d) of :func:`cdpr_algebra.model.taut_equations.taut_family`,
    of the anchors' y and z coordinates: 0 in the subfamily."""
    return tuple(4 * m + 3 * i + k for i in range(m) for k in (1, 2))


@lru_cache(maxsize=None)
def collinear_start(m: int):
    """(parameters, solutions) of the stored generic set of the subfamily (loaded once per process; the system's
    hash is checked by tests/test_dgp_collinear.py)."""
    from cdpr_algebra.homotopy.monodromy import load_instance

    from .taut_system import fast_family

    p, X, _ = load_instance(collinear_path(m), fast_family(m), check_hash=False)
    return p, X


@dataclass(frozen=True)
class LineFrame:
    """The line of the taut anchors in the robot's platform frame: a point ``origin`` of it and its unit
    ``direction`` (doubles of the exact line in ``reading``), and ``offsets`` s_i = (b'_i - origin) . direction."""

    reading: str
    origin: np.ndarray
    direction: np.ndarray
    offsets: np.ndarray

    @property
    def turn(self) -> np.ndarray:
        """Rp, the rotation taking the x axis to the line's direction (the platform frame of the subfamily: x' =
        Rp^T (x - origin))."""
        return rotation_taking(np.array([1.0, 0.0, 0.0]), self.direction)

    def target(self, params: np.ndarray, m: int, cb, L: float) -> np.ndarray:
        """The normalized parameters ``params`` (:func:`.normalization.normalized_problem`: b'_i - cb and g' - cb
        over L) in the subfamily's platform frame: b'_i = (s_i / L, 0, 0) exactly, g' turned and moved alike."""
        o, Rp = (self.origin - cb) / L, self.turn
        p = np.array(params, dtype=float, copy=True)
        k = 4 * m
        p[k:k + 3 * m] = np.concatenate([[s / L, 0.0, 0.0] for s in self.offsets])
        p[k + 3 * m:k + 3 * m + 3] = Rp.T @ (params[k + 3 * m:k + 3 * m + 3] - o)
        return p

    def roots_back(self, X: np.ndarray, m: int, cb, L: float) -> np.ndarray:
        """Roots (p'', u'', v'', w'', lam) of :meth:`target`'s problem -> (p^, u^, v^, w^, lam) of the normalized
        problem: R^ = R'' Rp^T, p^ = p'' - R^ o (world point p'' + R'' x' = p^ + R^ (o + Rp x'))."""
        X = np.asarray(X).reshape(-1, 12 + m)
        o, Rp = (self.origin - cb) / L, self.turn
        R2 = np.stack([X[:, 3:6], X[:, 6:9], X[:, 9:12]], axis=-1)
        R = R2 @ Rp.T
        p = X[:, 0:3] - R @ o
        return np.hstack([p, R[:, :, 0], R[:, :, 1], R[:, :, 2], X[:, 12:]])


def line_frame(robot, cables) -> LineFrame | None:
    """The :class:`LineFrame` of the 0-based taut ``cables`` when m is in COLLINEAR_M with a stored subfamily set,
    their platform anchors are collinear and not all at one point, exactly in the robot's doubles (BINARY) or else
    in the decimals that print them (DECIMAL), and the centre of mass is off their line in that reading (on it,
    the taut set is a rod: :mod:`.rod`); else None."""
    from cdpr_algebra.certificates.families import collinear_exactly, exact_line

    idx = [int(c) for c in cables]
    if len(idx) not in COLLINEAR_M or not collinear_path(len(idx)).exists():
        return None
    points = [robot.platform[i] for i in idx]
    arms = np.asarray(points, dtype=float) - points[0]
    far = arms[int(np.argmax(np.linalg.norm(arms, axis=1)))]
    if np.max(np.abs(np.cross(arms, far))) > 1e-9 * (np.max(np.abs(points)) + 1e-300) ** 2:
        return None  # plainly off one line in every reading (the exact tests below cost a millisecond)
    for reading in (BINARY, DECIMAL):
        line = exact_line(points, reading)
        if line is not None and not collinear_exactly(points + [robot.com], reading):
            P, d = line
            norm = float(sum(c * c for c in d)) ** 0.5
            if norm == 0:
                return None
            s = [float(sum((q[k] - P[0][k]) * d[k] for k in range(3))) / norm for q in P]
            return LineFrame(reading, np.array([float(v) for v in P[0]]), np.array([float(c) for c in d]) / norm,
                             np.array(s))
    return None
