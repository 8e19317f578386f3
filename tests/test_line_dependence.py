"""Taut sets whose cable lines are dependent at every pose (model.line_dependence): two similar regular hexagons,
base and platform planar, are architecturally singular (Roeschel and Mick 1998); the DGP does not track such a set
and says why.  Independent check: the smallest singular value of the 6 x 6 line matrix at random poses in floats."""

import itertools
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.dgp.solve import solve_taut_set
from cdpr_algebra.model.line_dependence import lines_dependent_everywhere
from cdpr_algebra.model.pose import matrix_from_euler_parameters
from cdpr_algebra.model.robot import Robot, load_robot

ROOT = Path(__file__).resolve().parents[1]


def _hexagons(shift=0.0):
    """Regular hexagons (base radius 5 at z = 5, flat platform radius 0.5 turned by 30 deg), as a robot file would
    print them (6 decimals); ``shift`` moves B_1 along x."""
    a = np.arange(6) * np.pi / 3
    A = np.column_stack([5 * np.cos(a), 5 * np.sin(a), np.full(6, 5.0)]).round(6)
    B = np.column_stack([0.5 * np.cos(a + np.pi / 6), 0.5 * np.sin(a + np.pi / 6), np.zeros(6)]).round(6)
    B[0, 0] += shift
    rho = np.linalg.norm(A - (np.array([0.3, 0.2, 1.0]) + B), axis=1).round(6)
    return Robot(A, B, [0, 0, 0], 1.0, [0, 0, -1], rho, name="hexagons")


def _smallest_singular_values(robot, cables, n=10, seed=1):
    """sigma_min / sigma_max of the line matrix (u_i, B_i x u_i) at n random poses (floats)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        R = matrix_from_euler_parameters(rng.normal(size=4))
        B = rng.normal(size=3) + np.asarray(robot.platform)[list(cables)] @ R.T
        u = np.asarray(robot.base)[list(cables)] - B
        s = np.linalg.svd(np.column_stack([u, np.cross(B, u)]), compute_uv=False)
        out.append(s[-1] / s[0])
    return np.array(out)


def test_similar_hexagons_are_dependent_everywhere_and_not_tracked():
    robot = _hexagons()
    assert lines_dependent_everywhere(robot, range(6))
    assert np.all(_smallest_singular_values(robot, range(6)) < 1e-12)
    # any five of the lines are independent (rank 5 at a pose: exact)
    assert not any(lines_dependent_everywhere(robot, c) for c in itertools.combinations(range(6), 5))
    sub, sols = solve_taut_set(robot, robot.lengths, range(6))
    assert not sub.complete and sub.paths == 0 and sum(sub.outcomes.values()) == 0 and not sols
    assert "linearly dependent at every pose" in sub.skipped


def test_a_moved_anchor_makes_them_independent():
    robot = _hexagons(shift=1e-3)
    assert not lines_dependent_everywhere(robot, range(6))
    assert np.all(_smallest_singular_values(robot, range(6)) > 1e-8)


@pytest.mark.parametrize("name", ["seed000_test2", "seed002_8cables"])
def test_no_taut_set_of_the_published_robots_is_flagged(name):
    robot = load_robot(ROOT / "examples" / f"{name}.toml")
    assert not any(lines_dependent_everywhere(robot, c) for m in range(2, min(robot.n, 6) + 1)
                   for c in itertools.combinations(range(robot.n), m))
