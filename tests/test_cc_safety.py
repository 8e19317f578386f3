"""Second criterion (seed 002 Sec. II-C, IV-B): no equilibrium of a sub-configuration (fewer than 6 cables of the
CC) within a ball of radius 0.03 around (0, 1, 2) and (1, 0, 2).

Oracle: the paper's statement for both poses (reproduced by the interval exclusion for every valid CC).  Checks
that the exclusion can fail: near the tension-zero surface of a cable, a pose where that tension is <= 0 lies in
the ball (found as a witness, and confirmed with plain numpy statics), so nothing is proven there.
"""

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.cc.radii import cc_radii
from cdpr_algebra.cc.safety import exclusion_proof, pose_distance, safety
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.model.pose import matrix_from_angles, matrix_from_rodrigues

CCS = {
    (0, 1, 2): [[1, 2, 3, 4, 5, 6], [1, 3, 4, 5, 6, 8], [2, 3, 4, 5, 6, 7], [3, 4, 5, 6, 7, 8]],
    (1, 0, 2): [[1, 2, 5, 6, 7, 8], [1, 4, 5, 6, 7, 8], [2, 3, 5, 6, 7, 8], [3, 4, 5, 6, 7, 8]],
}


@pytest.fixture(scope="module")
def robot():
    return load_robot("examples/seed002_8cables.toml")


def test_pose_distance():
    R0 = matrix_from_angles(0.1, 0.2, 0.3)
    R1 = R0 @ matrix_from_angles(0.0, 0.0, 0.02)
    d, dp, th = pose_distance([0, 0, 0], R0, [0.03, 0.04, 0], R1)
    assert dp == pytest.approx(0.05) and th == pytest.approx(0.02) and d == pytest.approx(np.hypot(0.05, 0.02))


@pytest.mark.parametrize("position,cc", [(p, c) for p, ccs in CCS.items() for c in ccs[:2]])
def test_none_within_003(robot, position, cc):
    res = safety(robot, position, [c - 1 for c in cc], radius=0.03)
    assert res.safe is True and res.method == "interval exclusion proof" and res.nearest is None


@pytest.mark.slow
@pytest.mark.parametrize("position,cc", [(p, c) for p, ccs in CCS.items() for c in ccs[2:]])
def test_none_within_003_other_ccs(robot, position, cc):
    proven, boxes, _ = exclusion_proof(robot, position, [c - 1 for c in cc], radius=0.03)
    assert proven is True and boxes > 1


def test_exclusion_fails_next_to_a_tension_zero_surface(robot):
    """1 cm from {tau_5 = 0} of CC [3,...,8] at (1,0,2), a ball of 0.03 contains poses where tau_5 <= 0: the
    exclusion returns a witness, at which plain numpy statics indeed give a tension <= 0."""
    res = cc_radii(robot, (1, 0, 2), [3, 4, 5, 6, 7, 8])
    x0 = np.array([1.0, 0, 2])
    x = x0 + (res.rmin - 0.01) * (res.nearest - x0) / res.rmin
    proven, _, witness = exclusion_proof(robot, x, res.cables, radius=0.03)
    assert proven is False
    G, R = witness[:3], matrix_from_rodrigues(*witness[3:])
    assert np.linalg.norm(G - x) <= 0.03 * np.sqrt(3) and 2 * np.arctan(np.linalg.norm(witness[3:])) <= 0.03 * np.sqrt(3)
    B = G + (robot.platform[list(res.cables)] - robot.com) @ R.T
    s = robot.base[list(res.cables)] - B
    M = np.vstack([s.T, np.cross(B - G, s).T])
    lam = np.linalg.solve(M, [0, 0, 1.0, 0, 0, 0])
    assert lam.min() <= 0


def test_safety_input_errors(robot):
    with pytest.raises(CdprInputError, match="not a valid CC"):
        safety(robot, (0, 1, 2), [0, 1, 2, 3, 4, 6])
    with pytest.raises(CdprInputError, match="radius"):
        safety(robot, (0, 1, 2), [0, 1, 2, 3, 4, 5], radius=-1)
