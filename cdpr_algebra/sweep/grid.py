"""Sweep grids: ``NAME=START:STOP:NUM`` specs over cable lengths (``rho1`` .. ``rhon``: the DGP at every point) or
pose coordinates (``x``, ``y``, ``z`` of G and the angles ``phi_x``, ``phi_y``, ``phi_z`` of R = Rz Ry Rx, radians:
the IGP with assigned position for 3-cable robots, the cable configurations and robustness radii for robots with more
than 6 cables).  Points are numbered in C order of the product of the axes (the last name varies fastest)."""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass

import numpy as np

from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.model.expressions import range_bound

POSE_NAMES = ("x", "y", "z", "phi_x", "phi_y", "phi_z")
KINDS = ("dgp", "igp", "cc")


@dataclass(frozen=True)
class Axis:
    name: str
    values: tuple

    def to_dict(self) -> dict:
        return {"name": self.name, "values": list(self.values)}


@dataclass(frozen=True)
class Grid:
    """The axes of a sweep, its kind, and the fixed values (the robot file's lengths, or the default pose)."""

    axes: tuple
    kind: str

    @property
    def names(self) -> tuple:
        return tuple(a.name for a in self.axes)

    @property
    def size(self) -> int:
        return int(np.prod([len(a.values) for a in self.axes]))

    def points(self):
        """(index, values) for every point, C order."""
        for k, vals in enumerate(itertools.product(*[a.values for a in self.axes])):
            yield k, tuple(float(v) for v in vals)

    def to_dict(self) -> dict:
        return {"kind": self.kind, "axes": [a.to_dict() for a in self.axes]}


def parse_axis(spec: str, n: int) -> Axis:
    """``NAME=START:STOP:NUM`` (START and STOP numbers or constants like ``pi/2``; NUM >= 1 points, both ends
    included) -> an Axis; errors name ``--vary``."""
    m = re.fullmatch(r"\s*([A-Za-z_][A-Za-z_0-9]*)\s*=\s*([^:]+):([^:]+):([^:]+)\s*", spec)
    if not m:
        raise CdprInputError("--vary", f"expected NAME=START:STOP:NUM, got {spec!r}")
    name, a, b, num = m.groups()
    lengths = tuple(f"rho{i + 1}" for i in range(n))
    if name not in lengths + POSE_NAMES:
        raise CdprInputError("--vary", f"unknown name {name!r} (cable lengths {lengths[0]} .. {lengths[-1]}, or "
                             f"{', '.join(POSE_NAMES)})")
    try:
        num = int(num)
    except ValueError:
        raise CdprInputError("--vary", f"NUM must be an integer, got {num!r} in {spec!r}") from None
    if num < 1:
        raise CdprInputError("--vary", f"NUM must be >= 1, got {num} in {spec!r}")
    lo, hi = range_bound(a.strip(), "--vary"), range_bound(b.strip(), "--vary")
    values = np.linspace(lo, hi, num) if num > 1 else np.array([lo])
    if name.startswith("rho") and np.any(values <= 0):
        raise CdprInputError("--vary", f"cable lengths must be > 0 ({spec!r})")
    return Axis(name, tuple(float(v) for v in values))


def make_grid(robot, specs, kind: str | None = None) -> Grid:
    """The grid of ``--vary`` specs for ``robot``; ``kind`` defaults to dgp for lengths, igp (3 cables) or cc (more
    than 6 cables) for poses."""
    if not specs:
        raise CdprInputError("--vary", "give at least one NAME=START:STOP:NUM")
    axes = tuple(parse_axis(s, robot.n) for s in specs)
    names = [a.name for a in axes]
    if len(set(names)) != len(names):
        raise CdprInputError("--vary", f"a name is varied twice: {names}")
    lengths = any(nm.startswith("rho") for nm in names)
    pose = any(nm in POSE_NAMES for nm in names)
    if lengths and pose:
        raise CdprInputError("--vary", "vary either cable lengths (DGP) or pose coordinates (IGP / CC), not both")
    if kind is None:
        kind = "dgp" if lengths else ("igp" if robot.n == 3 else "cc")
    if kind not in KINDS:
        raise CdprInputError("--kind", f"expected one of {', '.join(KINDS)}, got {kind!r}")
    if kind == "dgp" and not lengths:
        raise CdprInputError("--kind", "a DGP sweep varies cable lengths (rho1 ..)")
    if kind in ("igp", "cc") and not pose:
        raise CdprInputError("--kind", f"an {kind.upper()} sweep varies pose coordinates ({', '.join(POSE_NAMES)})")
    if kind == "igp" and robot.n != 3:
        raise CdprInputError("--kind", f"the IGP sweep is for 3-cable robots (this one has {robot.n})")
    if kind == "cc" and robot.n <= 6:
        raise CdprInputError("--kind", f"cable configurations are for robots with more than 6 cables ({robot.n})")
    if kind == "igp" and any(nm.startswith("phi") for nm in names):
        raise CdprInputError("--vary", "the IGP with assigned position varies x, y, z (the orientation is solved for)")
    if kind == "dgp" and robot.lengths is None and len(names) < robot.n:
        raise CdprInputError("--vary", "the robot file has no lengths: vary every cable length")
    return Grid(axes, kind)
