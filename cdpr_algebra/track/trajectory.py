"""Cable-length trajectories rho(t): piecewise linear through knots (t_k, rho_k), t increasing.

From two length vectors (t = 0 -> 1), or from a table read from a CSV or JSON file: CSV rows ``t, rho_1, .., rho_n``
(a header line of names is allowed), JSON ``{"t": [...], "lengths": [[...], ...]}`` or a list of
``{"t": .., "lengths": [..]}``.  Bad input raises :class:`cdpr_algebra.model.errors.CdprInputError` naming the row.
"""

from __future__ import annotations

import bisect
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cdpr_algebra.model.errors import CdprInputError


@dataclass(frozen=True)
class LengthTrajectory:
    """rho(t) piecewise linear through ``knots`` (k,) and ``lengths`` (k, n)."""

    knots: np.ndarray
    lengths: np.ndarray

    @property
    def start(self) -> float:
        return float(self.knots[0])

    @property
    def end(self) -> float:
        return float(self.knots[-1])

    def __call__(self, t: float) -> np.ndarray:
        knots = self.knots
        t = min(max(float(t), float(knots[0])), float(knots[-1]))
        k = min(max(bisect.bisect_right(knots, t) - 1, 0), len(knots) - 2)
        a, b = float(knots[k]), float(knots[k + 1])
        s = (t - a) / (b - a)
        return (1 - s) * self.lengths[k] + s * self.lengths[k + 1]

    def breakpoints(self, t0: float, t1: float) -> list:
        """Knots strictly inside (t0, t1): where rho(t) changes slope (steps stop there)."""
        return [float(k) for k in self.knots if t0 < k < t1]

    def to_dict(self) -> dict:
        return {"t": self.knots.tolist(), "lengths": self.lengths.tolist()}


def _check(knots, lengths, n: int, field: str) -> LengthTrajectory:
    knots = np.asarray(knots, dtype=float)
    lengths = np.asarray(lengths, dtype=float)
    if len(knots) < 2:
        raise CdprInputError(field, f"a trajectory needs at least 2 rows, got {len(knots)}")
    if lengths.ndim != 2 or lengths.shape[1] != n:
        raise CdprInputError(field, f"expected {n} cable lengths per row, got {lengths.shape[-1] if lengths.ndim == 2 else lengths.shape}")
    for k in range(len(knots)):
        if not np.isfinite(knots[k]) or not np.all(np.isfinite(lengths[k])):
            raise CdprInputError(f"{field} row {k + 1}", "not a finite number")
        if np.any(lengths[k] <= 0):
            raise CdprInputError(f"{field} row {k + 1}", "cable lengths must be > 0")
        if k and knots[k] <= knots[k - 1]:
            raise CdprInputError(f"{field} row {k + 1}", f"t must increase ({knots[k]:g} after {knots[k - 1]:g})")
    return LengthTrajectory(knots, lengths)


def straight(start, end, n: int) -> LengthTrajectory:
    """rho(t) = (1 - t) start + t end, t in [0, 1]."""
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    for name, v in (("--lengths", start), ("--to", end)):
        if v.shape != (n,):
            raise CdprInputError(name, f"expected {n} cable lengths, got {v.size}")
    return _check([0.0, 1.0], [start, end], n, "--to")


def load_trajectory(path, n: int) -> LengthTrajectory:
    """A trajectory table from a CSV or JSON file (module doc)."""
    path = Path(path)
    field = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise CdprInputError("--trajectory", f"cannot read {path}: {err.strerror}") from None
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as err:
            raise CdprInputError("--trajectory", f"not valid JSON ({err.msg}, line {err.lineno})") from None
        if isinstance(data, dict):
            t, L = data.get("t"), data.get("lengths")
            if t is None or L is None:
                raise CdprInputError("--trajectory", 'expected keys "t" and "lengths"')
        elif isinstance(data, list):
            try:
                t = [row["t"] for row in data]
                L = [row["lengths"] for row in data]
            except (TypeError, KeyError):
                raise CdprInputError("--trajectory", 'every row must be {"t": .., "lengths": [..]}') from None
        else:
            raise CdprInputError("--trajectory", "expected an object or a list of rows")
        if isinstance(t, list) and isinstance(L, list) and len(t) != len(L):  # zip would drop the extra ones
            raise CdprInputError(field, f"{len(t)} values of t but {len(L)} rows of lengths")
        try:
            rows = [[float(a)] + [float(v) for v in b] for a, b in zip(t, L)]
        except (TypeError, ValueError):
            raise CdprInputError("--trajectory", "t and lengths must be numbers") from None
        if len({len(r) for r in rows}) > 1:
            bad = next(k for k, r in enumerate(rows) if len(r) != len(rows[0]))
            raise CdprInputError(f"{field} row {bad + 1}", f"expected {n} cable lengths, got {len(rows[bad]) - 1}")
    else:
        rows = []
        seen_line = False
        for k, line in enumerate(text.splitlines()):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            parts = [p.strip() for p in line.replace(";", ",").split(",")]
            try:
                values = [float(p) for p in parts]
            except ValueError:
                if not seen_line:  # a header line of names
                    seen_line = True
                    continue
                raise CdprInputError(f"{field} line {k + 1}", f"not a number in {line!r}") from None
            seen_line = True
            if len(values) != n + 1:
                raise CdprInputError(f"{field} line {k + 1}", f"expected t and {n} cable lengths, got {len(values)} values")
            rows.append(values)
    if not rows:
        raise CdprInputError("--trajectory", "no rows")
    arr = np.array(rows, dtype=float)
    return _check(arr[:, 0], arr[:, 1:], n, field)


@dataclass(frozen=True)
class ExpressionTrajectory:
    """rho(t) given by one expression of t per cable (``sin``, ``cos``, ``pi``, ... as in ``cdpr cc --path``),
    t in [start, end]; smooth, so no breakpoints."""

    expressions: tuple
    start: float
    end: float

    def __post_init__(self):
        import sympy as sp

        t = sp.Symbol("t", real=True)
        object.__setattr__(self, "_f", [sp.lambdify(t, e, "numpy") for e in self.expressions])

    def __call__(self, t: float) -> np.ndarray:
        t = min(max(float(t), self.start), self.end)
        return np.array([float(f(t)) for f in self._f])

    def breakpoints(self, t0: float, t1: float) -> list:
        return []

    def to_dict(self) -> dict:
        return {"expressions": [str(e) for e in self.expressions], "range": [self.start, self.end]}


def from_expressions(texts, t_range, n: int, option: str = "--expressions") -> ExpressionTrajectory:
    """A trajectory from n expression strings of t over ``t_range`` (ends: numbers or constants like ``pi/2``);
    the lengths must be finite and > 0 over the range (checked on 1001 points)."""
    from cdpr_algebra.model.expressions import parse_expression, range_bound

    if len(texts) != n:
        raise CdprInputError(option, f"expected {n} expressions (one per cable), got {len(texts)}")
    if len(t_range) != 2:
        raise CdprInputError("--range", f"expected two ends T0 T1, got {list(t_range)}")
    a, b = range_bound(t_range[0], "--range"), range_bound(t_range[1], "--range")
    if not a < b:
        raise CdprInputError("--range", f"expected T0 < T1, got [{a:g}, {b:g}]")
    traj = ExpressionTrajectory(tuple(parse_expression(s, ("t",), option) for s in texts), a, b)
    for t in np.linspace(a, b, 1001):
        v = traj(t)
        bad = np.flatnonzero(~np.isfinite(v) | (v <= 0))
        if bad.size:
            raise CdprInputError(option, f"cable {bad[0] + 1}'s length {texts[bad[0]]!r} is {v[bad[0]]:.6g} at "
                                 f"t = {t:.6g} (lengths must be > 0)")
    return traj
