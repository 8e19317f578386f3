"""Issue 4, item 4 and issue 15: with ``retry_mpmath`` in the options (``cdpr dgp --mpmath-retry``), paths that every
double-precision retry left failed are tracked again in arbitrary precision before anything is reported: in Study
parameters, by :func:`cdpr_algebra.homotopy.hybrid_tracker.hybrid_track` (the compiled double-double tracker
:mod:`cdpr_algebra.homotopy.dd_tracker` wherever double precision fails; :mod:`cdpr_algebra.dgp.study_retrack`).

Forced here: every double-precision attempt (affine, projective, Study) of one path of a 2-cable subproblem of seed
000 Test 1 reports a failed step at its first step, and so does the hybrid tracker's first double-precision stretch,
which hands the path to the double-double tracker; the subproblem still reports every solution of an ordinary
run, and no failed path.
"""

import importlib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import cdpr_algebra.homotopy.endgame as eg
import cdpr_algebra.homotopy.dd_tracker as dd
import cdpr_algebra.homotopy.tracker as tk
from cdpr_algebra.dgp import solve as dgp_solve, study_retrack
from cdpr_algebra.dgp.solve import STUDY_FIRST, _generic, default_options, solve_taut_set
from cdpr_algebra.dgp.study_retrack import STUDY_EXTENDED, FastStudySystem
from cdpr_algebra.model.taut_sets import lengths_and_taut_sets
from cdpr_algebra.homotopy.results import STEP_TOO_SMALL
from cdpr_algebra.model.robot import load_robot

ROOT = Path(__file__).resolve().parents[1]


def _failing_at_the_start(real, which):
    """``real`` (a track_segment) with the paths ``which(x0)`` of every call from t = 1 failed at once (their start
    point, t = 1)."""
    def failing(homotopy, x0, t_a, t_b, options=None, h0=None):
        r = real(homotopy, x0, t_a, t_b, options, h0)
        if np.all(np.asarray(t_a) == 1.0):
            bad = which(np.asarray(x0))
            status, x, t = r.status.copy(), r.x.copy(), np.array(r.t, dtype=complex, copy=True)
            status[bad], x[bad], t[bad] = STEP_TOO_SMALL, np.asarray(x0)[bad], 1.0
            r = type(r)(x=x, s=r.s, t=t, status=status, steps=r.steps, h=r.h)
        return r
    return failing


@pytest.mark.slow
def test_failed_path_is_tracked_in_arbitrary_precision(monkeypatch):
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    rho, _ = lengths_and_taut_sets(robot)
    cables = (0, 2)
    sub0, sols0 = solve_taut_set(robot, rho, cables, certify=False, exclude=False)  # tracked, though excluded
    assert sub0.paths == 24
    assert sub0.failed_paths == 0
    _, X = _generic(2)

    def first_or_study(x0):  # the path from the first stored start point; any path in other coordinates
        return np.all(np.isclose(x0, X[0]), axis=1) if x0.shape[1] == X.shape[1] else np.ones(len(x0), bool)

    monkeypatch.setattr(eg, "track_segment", _failing_at_the_start(eg.track_segment, first_or_study))
    # the endgame over double-double (study_retrack._precise_endgames) would settle the Study paths forced to fail:
    # off, this test is about the rescue of --mpmath-retry
    monkeypatch.setattr(study_retrack, "PRECISE_ENDGAME_PATHS", 0)
    monkeypatch.setattr(dgp_solve, "AUTO_RESCUE_MAX_FAILED", 0)  # nor the rescue itself unless asked for
    monkeypatch.setattr(dgp_solve, "OTHER_START", False)  # nor the route from another generic instance
    monkeypatch.setattr(dgp_solve, "RERUN_MAX_FAILED", 0)  # nor the roots of the gamma re-run's route
    monkeypatch.setattr(dgp_solve, "EXTENDED_MAX_FAILED", 0)  # nor the double-double track in (p, u, v, w, lam)
    sub1, _ = solve_taut_set(robot, rho, cables, certify=False, exclude=False)
    assert sub1.failed_paths == 1  # forced: without the retry, the path fails

    calls = {"dd": 0, "dd_steps": 0}
    real_dd = dd.dd_track

    def counting_dd(*a, **k):
        out = real_dd(*a, **k)
        calls["dd"] += 1
        calls["dd_steps"] += out[3]
        return out

    monkeypatch.setattr(dd, "dd_track", counting_dd)
    hs = importlib.import_module("cdpr_algebra.homotopy.solve")
    real_solve = hs.solve_parameter_homotopy

    def counting_solve(system, *a, **k):
        calls["study_runs"] = calls.get("study_runs", 0) + isinstance(system, FastStudySystem)
        return real_solve(system, *a, **k)

    monkeypatch.setattr(hs, "solve_parameter_homotopy", counting_solve)
    monkeypatch.setattr(tk, "track_segment", _failing_at_the_start(tk.track_segment, lambda x0: np.ones(len(x0), bool)))
    sub, sols = solve_taut_set(robot, rho, cables, certify=False, options=replace(default_options(), retry_mpmath=True),
                               exclude=False)
    assert calls["dd"] >= 1 and calls["dd_steps"] > 0  # the path went through double-double
    # one Study run in double precision (every path): the rescue does not run the same homotopy again first
    assert calls["study_runs"] == (1 if STUDY_FIRST else 2)
    assert sub.retried.get(STUDY_EXTENDED) == 1
    assert sub.failed_paths == 0 and sub.finite == sub0.finite and sub.real == sub0.real
    assert len(sols) == len(sols0)
    for a, b in zip(sorted(sols, key=lambda s: tuple(s.position)), sorted(sols0, key=lambda s: tuple(s.position))):
        assert np.abs(a.position - b.position).max() <= 1e-9 * robot.size
