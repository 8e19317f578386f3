"""Valid cable configurations (CC) of a suspended robot at a pose (seed 002 Sec. I, II-A, eqs. 1-2).

A CC at a pose is a set S of at most 6 cables that holds the platform alone: the statics
F = J^{-T} tau (seed 002 eq. 2) restricted to the columns of S has a solution with every tau_i > 0; the
other cables are made slack by the controller (their lengths set above |A_i B_i|), so they impose nothing.

Wrench columns (seed 002, moments about the centre of mass C = G; the pole does not change the solution):
cable i contributes lam_i (A_i - B_i ; c_i x (A_i - B_i)) with c_i = B_i - G = R (b_i' - g') and
lam_i = tau_i / rho_i, rho_i = |A_i - B_i|; the load contributes (Q d ; 0).  So M_S lam = -Q (d ; 0).
For |S| = 6 the system is square (Cramer: tau_i = rho_i |M_i| / |M|); for |S| < 6 it is overdetermined and S is
valid only where it is consistent (relative least-squares residual <= ``residual_tol``), i.e. at poses that are
equilibria of fewer cables.

The ``position`` of a pose is that of the centre of mass G (seed 002's C; the ``cdpr igp`` convention); the
orientation is a rotation matrix R (B_i = G + R (b_i' - g')).  Ranking: by the robustness index r_min when it has
been computed (larger first, :mod:`cdpr_algebra.cc.radii`), then by the largest tension (smaller first).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.report.jsonable import jsonable
from cdpr_algebra.model.statics import cross

__all__ = ["CableConfiguration", "check_pose", "wrench_columns", "configuration_tensions", "valid_configurations",
           "rank_configurations", "parse_cables"]

RESIDUAL_TOL = 1e-9


def check_pose(robot, position, rotation=None) -> tuple[np.ndarray, np.ndarray]:
    """(G, R) as float arrays; raises :class:`CdprInputError` on bad shapes or non-finite numbers."""
    try:
        G = np.asarray(position, dtype=float).reshape(3)
    except (TypeError, ValueError):
        raise CdprInputError("position", "expected 3 numbers") from None
    if not np.all(np.isfinite(G)):
        raise CdprInputError("position", "expected finite numbers")
    if rotation is None:
        R = np.eye(3)
    else:
        from cdpr_algebra.model.pose import check_rotation

        R = check_rotation(rotation, "rotation")
    return G, R


def parse_cables(robot, cables, fieldname: str = "cables", size: int | None = None) -> tuple[int, ...]:
    """1-based cable numbers -> sorted 0-based tuple, checked (distinct, in range, at most 6 or exactly ``size``)."""
    try:
        idx = [int(c) for c in cables]
    except (TypeError, ValueError):
        raise CdprInputError(fieldname, f"expected cable numbers, got {cables!r}") from None
    if any(float(c) != int(c) for c in cables):
        raise CdprInputError(fieldname, f"expected integer cable numbers, got {list(cables)!r}")
    if len(set(idx)) != len(idx):
        raise CdprInputError(fieldname, f"cable numbers must be distinct, got {idx}")
    bad = [c for c in idx if not 1 <= c <= robot.n]
    if bad:
        raise CdprInputError(fieldname, f"cable numbers must be in 1..{robot.n}, got {bad[0]}")
    if size is not None and len(idx) != size:
        raise CdprInputError(fieldname, f"expected {size} cables, got {len(idx)}")
    if not 1 <= len(idx) <= 6:
        raise CdprInputError(fieldname, f"a cable configuration has 1 to 6 cables, got {len(idx)}")
    return tuple(sorted(c - 1 for c in idx))


def wrench_columns(robot, position, rotation=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(W, rhs, rho): W (6, n) columns (A_i - B_i ; c_i x (A_i - B_i)), rhs = -Q (d ; 0), rho_i = |A_i - B_i|.

    Also for a stack of positions (..., 3): W (..., 6, n), rho (..., n)."""
    G = np.asarray(position, dtype=float)
    R = np.eye(3) if rotation is None else np.asarray(rotation, dtype=float)
    c = (robot.platform - robot.com) @ R.T  # (n, 3)
    s = robot.base - (G[..., None, :] + c)  # A_i - B_i
    W = np.swapaxes(np.concatenate([s, cross(c, s)], axis=-1), -1, -2)
    rhs = -robot.load * np.concatenate([robot.load_direction, np.zeros(3)])
    return W, rhs, np.linalg.norm(s, axis=-1)


@dataclass(frozen=True)
class CableConfiguration:
    """A set of taut cables at a pose with its tensions (cables 0-based here, 1-based in ``to_dict``).

    ``residual`` is |M_S lam - rhs| / Q (0 up to rounding for 6 cables); ``valid`` says every tension is > 0
    and the statics is consistent.  ``rmin`` / ``radii`` are filled by :func:`cdpr_algebra.cc.radii.attach_radii`.
    """

    cables: tuple
    tensions: np.ndarray
    residual: float
    valid: bool
    rmin: float | None = None

    @property
    def numbers(self) -> list[int]:
        return [c + 1 for c in self.cables]

    @property
    def max_tension(self) -> float:
        return float(np.max(self.tensions))

    @property
    def min_tension(self) -> float:
        return float(np.min(self.tensions))

    def to_dict(self) -> dict:
        return jsonable({"cables": self.numbers, "tensions": self.tensions, "residual": self.residual,
                         "valid": self.valid, "max_tension": self.max_tension, "rmin": self.rmin})


def configuration_tensions(robot, position, cables, rotation=None, residual_tol: float = RESIDUAL_TOL
                           ) -> CableConfiguration:
    """Tensions of the 0-based cable set ``cables`` at the pose (least squares when fewer than 6 cables)."""
    G, R = check_pose(robot, position, rotation)
    cables = tuple(cables)
    W, rhs, rho = wrench_columns(robot, G, R)
    Ws = W[:, list(cables)]
    if len(cables) == 6:
        try:
            lam = np.linalg.solve(Ws, rhs)
        except np.linalg.LinAlgError:
            lam = np.full(6, np.nan)
    else:
        lam = np.linalg.lstsq(Ws, rhs, rcond=None)[0]
    res = float(np.linalg.norm(Ws @ lam - rhs) / robot.load) if np.all(np.isfinite(lam)) else np.inf
    tau = lam * rho[list(cables)]
    scale = np.linalg.norm(Ws, axis=0).max() * max(1.0, np.abs(lam).max()) / robot.load
    valid = bool(np.all(np.isfinite(tau)) and np.all(tau > 0) and res <= residual_tol * max(1.0, scale))
    return CableConfiguration(cables, tau, res, valid)


def valid_configurations(robot, position, rotation=None, sizes=range(1, 7), residual_tol: float = RESIDUAL_TOL
                         ) -> list[CableConfiguration]:
    """Every valid CC at the pose (sets of ``sizes`` cables, all tensions > 0), ranked by largest tension.

    Vectorized over the C(n, 6) square systems; smaller sets by least squares."""
    G, R = check_pose(robot, position, rotation)
    W, rhs, _ = wrench_columns(robot, G, R)
    n = robot.n
    out = []
    for m in sizes:
        if m > n or m < 1 or m > 6:
            continue
        subsets = list(itertools.combinations(range(n), m))
        if m == 6:
            Ms = np.stack([W[:, list(S)] for S in subsets])
            det = np.linalg.det(Ms)
            ok = np.abs(det) > 1e-13 * np.prod(np.linalg.norm(Ms, axis=1), axis=-1)
            lam = np.full((len(subsets), 6), np.nan)
            if np.any(ok):
                lam[ok] = np.linalg.solve(Ms[ok], np.broadcast_to(rhs, (int(ok.sum()), 6))[..., None])[..., 0]
            for S, l, good in zip(subsets, lam, ok):
                if good and np.all(l > 0):
                    out.append(configuration_tensions(robot, G, S, R, residual_tol))
        else:
            for S in subsets:
                cc = configuration_tensions(robot, G, S, R, residual_tol)
                if cc.valid:
                    out.append(cc)
    out = [c for c in out if c.valid]
    return rank_configurations(out)


def rank_configurations(configurations) -> list:
    """More cables first (6 taut cables keep the platform fully controlled), then larger r_min (when known), then
    smaller largest tension."""
    def key(c):
        r = getattr(c, "rmin", None)
        return (-len(c.cables), -(r if r is not None else -1.0), c.max_tension)
    return sorted(configurations, key=key)
