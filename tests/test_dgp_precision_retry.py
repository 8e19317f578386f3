"""Issue 4, item 4: with ``retry_mpmath`` in the options (``cdpr dgp --mpmath-retry``), paths that fail in double
precision are tracked in arbitrary precision before anything is reported.

Forced here: every double-precision attempt (affine and projective) of one path of a 2-cable subproblem of seed 000
Test 1 reports a failed step; the subproblem still reports every solution of an ordinary run, and no failed path.
"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import cdpr_algebra.homotopy.endgame as eg
from cdpr_algebra.dgp.solve import _generic, default_options, solve_taut_set
from cdpr_algebra.model.taut_sets import lengths_and_taut_sets
from cdpr_algebra.homotopy.results import STEP_TOO_SMALL
from cdpr_algebra.model.robot import load_robot

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_failed_path_is_tracked_in_arbitrary_precision(monkeypatch):
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    rho, _ = lengths_and_taut_sets(robot)
    cables = (0, 2)
    sub0, sols0 = solve_taut_set(robot, rho, cables, certify=False, exclude=False)  # tracked, though excluded
    assert sub0.paths == 24
    assert sub0.failed_paths == 0
    _, X = _generic(2)
    real_segment = eg.track_segment
    calls = {"mp": 0}
    real_mp = eg.mp_track

    def failing(homotopy, x0, t_a, t_b, options=None, h0=None):
        r = real_segment(homotopy, x0, t_a, t_b, options, h0)
        if np.all(np.asarray(t_a) == 1.0):
            x0 = np.asarray(x0)
            # the path from the first stored start point, in affine coordinates or re-tracked projectively
            bad = np.all(np.isclose(x0, X[0]), axis=1) if x0.shape[1] == X.shape[1] else np.ones(len(x0), bool)
            status = r.status.copy()
            status[bad] = STEP_TOO_SMALL
            r = type(r)(x=r.x, s=r.s, t=r.t, status=status, steps=r.steps, h=r.h)
        return r

    def counting_mp(*a, **k):
        calls["mp"] += 1
        return real_mp(*a, **k)

    monkeypatch.setattr(eg, "track_segment", failing)
    monkeypatch.setattr(eg, "mp_track", counting_mp)  # the arbitrary-precision tracker behind eg.mp_path
    sub, sols = solve_taut_set(robot, rho, cables, certify=False, options=replace(default_options(), retry_mpmath=True),
                               exclude=False)
    assert calls["mp"] == 1  # the one path, once
    assert sub.failed_paths == 0 and sub.finite == sub0.finite and sub.real == sub0.real
    assert len(sols) == len(sols0)
    for a, b in zip(sorted(sols, key=lambda s: tuple(s.position)), sorted(sols0, key=lambda s: tuple(s.position))):
        assert np.abs(a.position - b.position).max() <= 1e-9 * robot.size
