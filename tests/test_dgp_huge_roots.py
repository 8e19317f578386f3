"""Issue 15: a finite root is never dropped because it is large.  A random 6-cable robot (tests/data/
huge_roots_6cables.toml) whose taut set {1, 2, 5, 6} has a conjugate pair of roots with |x| ~ 2e7 (normalized
unknowns), {2, 3, 5, 6} one with |x| ~ 3.8e9: double precision loses their paths in both coordinate systems; tracked
again in double-double from their start points (dgp.taut_extended) they end there, and the endpoint certificates
prove all 216 roots distinct, so the subproblem is complete (216 = the generic count).  Before: 2 failed paths,
incomplete, 22 s and 32 s."""

from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.dgp.solve import taut_set_roots
from cdpr_algebra.dgp.taut_extended import TAUT_EXTENDED

ROBOT = Path(__file__).resolve().parent / "data" / "huge_roots_6cables.toml"


@pytest.mark.parametrize("cables, size", [((0, 1, 4, 5), 2e7), ((1, 2, 4, 5), 3.8e9)])
def test_huge_conjugate_roots_are_reached_and_proven(cables, size):
    """{1, 2, 5, 6}: the pair |x| ~ 2e7 (double-double, the run's predictor tolerance); {2, 3, 5, 6}: |x| ~ 3.8e9
    (double-double with the predictor tolerance 3e-6 to t ~ 3e-7, then python-flint at 212 bits)."""
    robot = load_robot(ROBOT)
    sub, Z, proven = taut_set_roots(robot, robot.lengths, cables)
    assert sub.complete and sub.failed_paths == 0, sub.to_dict()
    assert sub.outcomes["regular"] == sub.paths == sub.generic_count == 216
    assert len(Z) == 216 and proven.all()
    assert sub.retried.get(TAUT_EXTENDED, 0) >= 1
    # the two largest roots: far beyond the robot's size (~10 m), complex, each the conjugate of the other
    norms = np.max(np.abs(Z), axis=1)
    big = np.argsort(norms)[-2:]
    assert 0.5 * size <= norms[big].min() <= 2 * size
    a, b = Z[big]
    assert np.max(np.abs(a - np.conj(b))) <= 1e-8 * np.max(np.abs(a))
    assert np.max(np.abs(a.imag)) > 1e-3 * np.max(np.abs(a))
    # each solves the robot's equations (world coordinates: p, the columns of R, lam = tau / rho), relative to |x|^2
    A, b_, rho = robot.base[list(cables)], robot.platform[list(cables)], robot.lengths[list(cables)]
    for x in Z[big]:
        p, R = x[:3], x[3:12].reshape(3, 3).T
        s = p + b_ @ R.T - A
        scale = np.max(np.abs(x)) ** 2
        assert np.max(np.abs(np.sum(s * s, axis=1) - rho ** 2)) <= 1e-9 * scale
        assert np.max(np.abs(R.T @ R - np.eye(3))) <= 1e-9 * scale
