"""Issue 15: a robot whose platform triangle is similar to its base triangle (``examples/similar_3cables.toml``, the
base scaled by 1/8, both planes horizontal).  Four paths of its taut set {1, 2, 3} run to infinity with the
translation along an isotropic complex direction and the tensions, the rotation converging; the Cauchy means of
such paths converge too (to the constant term of their Puiseux series), so they were left failed (exit status 3)
until the endgame read the translation and tensions themselves (:func:`cdpr_algebra.homotopy.endgame.block_at_infinity`,
twenty-eighth session).

Independent checks: every equilibrium the interval branch and prune proves is among the admissible ones; the roots
at infinity are the ones a small change of the platform sends away (a robot no longer similar has all 156 roots
finite, 152 near the similar robot's and 4 whose size grows like 1 / the change).
"""

from pathlib import Path

import numpy as np

from cdpr_algebra.dgp.solve import _solve_taut_set, _with_endpoint_certificates
from cdpr_algebra.homotopy.endgame import EndgameOptions, block_at_infinity
from cdpr_algebra.model.robot import load_robot

ROOT = Path(__file__).resolve().parents[1]
CABLES = (0, 1, 2)


def _solved(robot):
    sub, sols, Z = _solve_taut_set(robot, robot.lengths, CABLES)
    (sub,) = _with_endpoint_certificates(robot, robot.lengths, [(CABLES, sub, Z)])
    return sub, sols, Z


def test_the_similar_robot_is_complete_and_has_the_interval_search_s_equilibria():
    from cdpr_algebra.bp.search import solve_taut_set_interval

    robot = load_robot(ROOT / "examples" / "similar_3cables.toml")
    sub, sols, Z = _solved(robot)
    assert sub.outcomes == {"regular": 152, "singular": 0, "at_infinity": 4, "failed": 0}, sub.outcomes
    assert sub.complete and sub.certified == 152 and sub.retried.get("precise_endgame") == 4
    bp = solve_taut_set_interval(robot, robot.lengths, CABLES)  # 2 boxes undecided there (a tension unbounded)
    assert len(bp.solutions) >= 1 and sub.admissible == len(sols) >= len(bp.solutions)
    for s in bp.solutions:  # every equilibrium it proves is one of ours
        assert min(np.max(np.abs(s.position - h.position)) for h in sols) <= 1e-8


def test_its_roots_at_infinity_are_those_a_change_of_the_platform_sends_away():
    robot = load_robot(ROOT / "examples" / "similar_3cables.toml")
    _, _, Z = _solved(robot)
    big = []
    for eps in (1e-4, 1e-6):
        changed = robot.__class__(base=robot.base, platform=robot.platform * [1 + eps, 1, 1], com=robot.com,
                                  load=robot.load, load_direction=robot.load_direction, lengths=robot.lengths,
                                  name="changed")
        sub, _, W = _solved(changed)
        assert sub.complete and sub.outcomes["regular"] == sub.certified == 156
        d = np.max(np.abs(W[:, None, :] - Z[None, :, :]), axis=2) / (1 + np.max(np.abs(Z), axis=1))[None, :]
        near = d.min(axis=1) <= 100 * eps  # each similar root moves by O(eps) (22 eps at most, measured)
        assert near.sum() == 152 and np.all(d.min(axis=0) <= 100 * eps)
        big.append(np.sort(np.max(np.abs(W[~near]), axis=1)))
    assert np.all(big[1] > 30 * big[0])  # the other 4 grow like 1 / eps (635 and 63,473, measured)


def _loops(y, r, c=1, M=8):
    """The samples of y(s), s = t^(1/c), on c loops of |t| = r (M points a loop), as the endgame takes them."""
    s = r ** (1 / c) * np.exp(2j * np.pi * np.arange(c * M) / (c * M))
    return np.array([y(v) for v in s])


def test_block_at_infinity_reads_the_loops():
    o = EndgameOptions()
    u = np.array([1.0, 1j, 0.3, -2.0])  # a block of 4 coordinates
    r0, r1 = 1e-3, 1e-3 * o.sample_ratio

    def pole(s):  # y ~ u / s^2 (winding number 2: y ~ t^(-1)), with lower terms
        return u / s**2 + (0.5 - 1j) * u[::-1] / s + 3.0 + s

    moved, bounded, v = block_at_infinity(_loops(pole, r1, 2), _loops(pole, r0, 2), slice(None), 2, o)
    assert moved and not bounded and abs(v - 1.0) < 0.05

    def finite(s):  # a finite limit of two sheets
        return u * 7.0 + 2.0 + (1 + 1j) * u[::-1] * s

    moved, bounded, v = block_at_infinity(_loops(finite, r1, 2), _loops(finite, r0, 2), slice(None), 2, o)
    assert bounded and not moved

    def near_pole(s, delta=1e-14):  # a huge finite limit, 1 / (s + delta): the loops' means repeat h(0) != 0
        return u / (s + delta) + 1.0

    moved, bounded, _ = block_at_infinity(_loops(near_pole, r1), _loops(near_pole, r0), slice(None), 1, o)
    assert not moved and not bounded  # neither: the endgame samples on, to smaller radii
