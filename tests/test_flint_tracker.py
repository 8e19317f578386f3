"""The arbitrary-precision tracker (:mod:`cdpr_algebra.homotopy.flint_tracker`) against paths known in closed form."""

import numpy as np

from cdpr_algebra.homotopy.flint_tracker import FlintParameterHomotopy, flint_track
from cdpr_algebra.homotopy.results import SUCCESS, TOO_MANY_STEPS
from cdpr_algebra.homotopy.tracker import TrackerOptions


def _evaluate(x, p, dp, F, J, Ht, with_ht):
    """F(x; p) = (x0^2 - p0, x1 - p1 x0): the solution x0 = +-sqrt(p0), x1 = p1 x0 (the generated evaluators'
    signature: F, the pattern of J, and Ht = dF/dp . dp)."""
    F[0] = x[0] * x[0] - p[0]
    F[1] = x[1] - p[1] * x[0]
    J[0, 0] = 2 * x[0]
    J[1, 0] = -p[1]
    J[1, 1] = 1 + 0 * x[1]
    if with_ht:
        Ht[0] = -dp[0]
        Ht[1] = -dp[1] * x[0]


def test_flint_track_ends_on_the_closed_form_solution():
    """From p1 = (4, 1) to p0 = (9, 2) along a gamma arc, the root (2, 2) goes to (3, 6) (x0 = sqrt(p0(t)) never
    meets 0 on the arc): the endpoint agrees with it to far below double precision's rounding."""
    h = FlintParameterHomotopy(_evaluate, 2, 2, [4, 1], [9, 2], gamma=np.exp(0.7j))
    seg = flint_track(h, [2, 2], 1.0, 0.0, TrackerOptions(predictor_tol=1e-6), prec=106, max_steps=2000)
    assert seg.status == SUCCESS and seg.t == 0
    assert np.abs(seg.x - np.array([3, 6])).max() <= 1e-14
    # the parameter path is the double tracker's (ParameterHomotopy.parameters_at): halfway on the arc
    half = flint_track(h, [2, 2], 1.0, 0.5, TrackerOptions(predictor_tol=1e-6), prec=106, max_steps=2000)
    g = np.exp(0.7j)
    p = (g * 0.5 * np.array([4, 1]) + 0.5 * np.array([9, 2])) / (g * 0.5 + 0.5)
    root = np.sqrt(p[0]) * np.sign(np.sqrt(p[0]).real)
    assert np.abs(half.x - np.array([root, p[1] * root])).max() <= 1e-12


def test_flint_track_stops_at_its_step_budget():
    """A budget too small for the path: ``too_many_steps`` at the t reached, the point still on the path."""
    h = FlintParameterHomotopy(_evaluate, 2, 2, [4, 1], [9, 2])
    seg = flint_track(h, [2, 2], 1.0, 0.0, TrackerOptions(predictor_tol=1e-8), max_steps=3, initial_step=1e-3)
    assert seg.status == TOO_MANY_STEPS and seg.steps == 3
    t = seg.t.real
    p = t * np.array([4, 1]) + (1 - t) * np.array([9, 2])
    assert 0 < t < 1
    assert np.abs(seg.x - np.array([np.sqrt(p[0]), p[1] * np.sqrt(p[0])])).max() <= 1e-12
