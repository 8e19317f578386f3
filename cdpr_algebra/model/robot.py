"""Robot description: base exit points, platform anchors, centre of mass, load (a robot is data).

Conventions (see README):
* ``base[i]`` = A_i, exit point of cable i in the world frame.
* ``platform[i]`` = b_i', anchor point B_i in the platform frame; ``com`` = g', centre of mass in the
  platform frame. With pose (p, R) of the platform frame: B_i = p + R b_i', G = p + R g'.
* The load is a force of magnitude ``load`` = Q > 0 along the unit vector ``load_direction`` applied at G
  (default [0, 0, -1]: gravity with z up). A cable pulls the platform with tau_i (A_i - B_i) / rho_i.
* ``lengths`` (optional) are the cable lengths rho_i.

Files are JSON or TOML with exactly the keys ``name``, ``base``, ``platform``, ``com``, ``load``,
``load_direction`` (optional), ``lengths`` (optional).
"""

from __future__ import annotations

import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .errors import MAX_MAGNITUDE, CdprInputError, check_magnitude, reject_unknown_keys

ROBOT_KEYS = ("name", "base", "platform", "com", "load", "load_direction", "lengths")
REQUIRED_KEYS = ("base", "platform", "com", "load")


def _is_number(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _vector(value: Any, fieldname: str, size: int = 3) -> np.ndarray:
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if not isinstance(value, (list, tuple)):
        raise CdprInputError(fieldname, f"expected a list of {size} numbers, got {type(value).__name__}")
    if len(value) != size:
        raise CdprInputError(fieldname, f"expected {size} numbers, got {len(value)}")
    for k, x in enumerate(value):
        if not _is_number(x):
            raise CdprInputError(f"{fieldname}[{k}]", f"expected a number, got {x!r}")
        if not math.isfinite(float(x)):
            raise CdprInputError(f"{fieldname}[{k}]", f"expected a finite number, got {x!r}")
        check_magnitude(float(x), f"{fieldname}[{k}]")
    return np.array([float(x) for x in value], dtype=float)


def _points(value: Any, fieldname: str) -> np.ndarray:
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if not isinstance(value, (list, tuple)) or len(value) == 0:
        raise CdprInputError(fieldname, "expected a non-empty list of points [x, y, z]")
    pts = np.array([_vector(p, f"{fieldname}[{i}]") for i, p in enumerate(value)])
    return pts


def _check_distinct(points: np.ndarray, fieldname: str, scale: float) -> None:
    n = len(points)
    for i in range(n):
        for j in range(i + 1, n):
            if np.linalg.norm(points[i] - points[j]) <= 1e-12 * scale:
                raise CdprInputError(
                    fieldname, f"points {i + 1} and {j + 1} coincide ({points[i].tolist()}); anchor points must be distinct"
                )


@dataclass(frozen=True)
class Robot:
    """An n-cable robot. Arrays are read-only float64; build with :meth:`from_dict` or :func:`load_robot`."""

    base: np.ndarray  # (n, 3) A_i, world frame
    platform: np.ndarray  # (n, 3) b_i', platform frame
    com: np.ndarray  # (3,) g', platform frame
    load: float  # Q > 0
    load_direction: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, -1.0]))
    lengths: np.ndarray | None = None  # (n,) rho_i
    name: str = "robot"

    def __post_init__(self):
        base = _points(self.base, "base")
        platform = _points(self.platform, "platform")
        if len(platform) != len(base):
            raise CdprInputError("platform", f"expected {len(base)} points (one per cable in 'base'), got {len(platform)}")
        com = _vector(self.com, "com")
        if not _is_number(self.load) and not isinstance(self.load, np.floating):
            raise CdprInputError("load", f"expected a number, got {self.load!r}")
        load = float(self.load)
        if not math.isfinite(load) or load <= 0:
            raise CdprInputError("load", f"expected a finite number > 0, got {load:g}")
        check_magnitude(load, "load")
        if load < 1.0 / MAX_MAGNITUDE:
            raise CdprInputError("load", f"{load:g} is below {1.0 / MAX_MAGNITUDE:g}: tensions and their products "
                                         f"underflow double precision (choose other units)")
        d = _vector(self.load_direction, "load_direction")
        nd = float(np.linalg.norm(d))
        if nd == 0.0:
            raise CdprInputError("load_direction", "the zero vector has no direction")
        d = d / nd
        lengths = None
        if self.lengths is not None:
            lengths = _vector(self.lengths, "lengths", size=len(base))
            for i, rho in enumerate(lengths):
                if rho <= 0:
                    raise CdprInputError(f"lengths[{i}]", f"cable lengths must be > 0, got {float(rho):g}")
        if not isinstance(self.name, str):
            raise CdprInputError("name", f"expected a string, got {self.name!r}")
        scale = max(1.0, float(np.abs(base).max()), float(np.abs(platform).max()))
        _check_distinct(base, "base", scale)
        _check_distinct(platform, "platform", scale)
        for arr in (base, platform, com, d) + ((lengths,) if lengths is not None else ()):
            arr.setflags(write=False)
        object.__setattr__(self, "base", base)
        object.__setattr__(self, "platform", platform)
        object.__setattr__(self, "com", com)
        object.__setattr__(self, "load", load)
        object.__setattr__(self, "load_direction", d)
        object.__setattr__(self, "lengths", lengths)
        pts = np.vstack([base, platform - com])  # the robot's length scale, computed once (hot in tracking loops)
        object.__setattr__(self, "_size", float(max(np.ptp(pts, axis=0).max(),
                                                    np.linalg.norm(platform - com, axis=1).max(), 1e-300)))

    @property
    def n(self) -> int:
        """Number of cables."""
        return len(self.base)

    @property
    def size(self) -> float:
        """A length scale of the robot: the largest coordinate extent of the base points together with the platform
        points relative to G, or the largest |b'_i - g'| if larger (>= 1e-300)."""
        return self._size

    @property
    def cable_scale(self) -> float:
        """The length scale of the cable geometry alone: the largest coordinate extent of the base points or of the
        platform points (:attr:`size` when both vanish).  Unlike :attr:`size` it does not grow with a centre of
        mass far from the attachment points (a long boom, a robot built with huge internal forces), so tolerances
        and normalizations of poses and tensions use it."""
        scale = max(float(np.ptp(self.base, axis=0).max()), float(np.ptp(self.platform, axis=0).max()))
        return scale if scale > 0 else self._size

    @property
    def cable_frame(self) -> tuple:
        """(c, cb): the centroids of the base points and of the platform points, the origins of the frames in which
        the DGP is normalized and its roots certified (distances to them are of the order of :attr:`cable_scale`)."""
        return self.base.mean(axis=0), self.platform.mean(axis=0)

    def with_lengths(self, lengths) -> "Robot":
        return Robot(self.base, self.platform, self.com, self.load, self.load_direction, lengths, self.name)

    def subset(self, cables) -> "Robot":
        """The robot made of the given cables (0-based indices), in that order."""
        idx = list(cables)
        lengths = None if self.lengths is None else self.lengths[idx]
        return Robot(self.base[idx], self.platform[idx], self.com, self.load, self.load_direction, lengths, self.name)

    @classmethod
    def from_dict(cls, data: Any, source: str | None = None) -> "Robot":
        """Build from a mapping with exactly the keys of :data:`ROBOT_KEYS`; errors name the field."""
        try:
            if not isinstance(data, dict):
                raise CdprInputError("<top level>", f"expected a table/object of robot fields, got {type(data).__name__}")
            reject_unknown_keys(data, ROBOT_KEYS)
            missing = [k for k in REQUIRED_KEYS if k not in data]
            if missing:
                raise CdprInputError(missing[0], "required key is missing")
            kwargs = {k: data[k] for k in ROBOT_KEYS if k in data}
            kwargs.setdefault("load_direction", [0.0, 0.0, -1.0])
            if kwargs.get("name") is None:
                kwargs["name"] = "robot"
            return cls(**kwargs)
        except CdprInputError as err:
            raise err.with_source(source) if source else err

    def to_dict(self) -> dict:
        d = {
            "name": self.name,
            "base": self.base.tolist(),
            "platform": self.platform.tolist(),
            "com": self.com.tolist(),
            "load": self.load,
            "load_direction": self.load_direction.tolist(),
        }
        if self.lengths is not None:
            d["lengths"] = self.lengths.tolist()
        return d


def load_robot(path: str | Path) -> Robot:
    """Read a robot file (``.json`` or ``.toml``). Raises :class:`CdprInputError` naming the field on bad input."""
    path = Path(path)
    src = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise CdprInputError("<file>", "no such file", src) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise CdprInputError("<file>", f"cannot read the file ({exc.__class__.__name__}: {exc})", src) from None
    suffix = path.suffix.lower()
    try:
        if suffix == ".json":
            data = json.loads(text)
        elif suffix == ".toml":
            data = tomllib.loads(text)
        else:
            raise CdprInputError("<file>", f"unknown file type {suffix!r}: expected .json or .toml", src)
    except json.JSONDecodeError as exc:
        raise CdprInputError("<file>", f"not valid JSON (line {exc.lineno}, column {exc.colno}: {exc.msg})", src) from None
    except tomllib.TOMLDecodeError as exc:
        raise CdprInputError("<file>", f"not valid TOML ({exc})", src) from None
    return Robot.from_dict(data, source=src)
