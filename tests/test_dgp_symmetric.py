"""Issue 15: a symmetric robot (``examples/symmetric_4cables.toml``: rectangular base and platform with the same two
mirror planes).  Its taut set {1, 2, 3, 4} has paths whose tension multipliers and translation grow together as
t -> 0; they were counted ``endgame_failed`` by the rule meant for tensions growing at a finite pose (a wrench matrix
exactly singular there, which double precision cannot tell from a near-double pair of finite roots with huge
tensions, ``tests/large_forces.py``).  Now a path whose pose block grows too stays at infinity.  Since the
twenty-eighth session the Study run decides them itself: its double-double Cauchy endgame shows the translation and
tensions (g, lam) unbounded at the limit (:func:`cdpr_algebra.homotopy.endgame.block_at_infinity`), and their last
samples, mapped back, are the endpoints tested below.

Independent check of those verdicts: at infinity the taut equations reduce to their leading terms in p = p^ / s,
lam = lam^ / s (s -> 0): the cable lengths |A_i - p - R b_i|^2 = rho_i^2 leave p^ . p^ = 0 (the translation runs off
along an isotropic complex direction) and the force balance sum lam_i (A_i - B_i) = -Q d leaves sum lam^_i = 0.
"""

from pathlib import Path

import numpy as np

import cdpr_algebra.dgp.solve as S
from cdpr_algebra.dgp.normalization import normalized_problem
from cdpr_algebra.dgp.tension_infinity import POSE_DIVERGES, tension_infinity_undecided
from cdpr_algebra.homotopy.results import AT_INFINITY, PathResult, SolveResult, TrackResult
from cdpr_algebra.model.robot import load_robot
from cdpr_algebra.model.taut_sets import lengths_and_taut_sets

ROOT = Path(__file__).resolve().parents[1]


def test_paths_whose_translation_grows_with_the_tensions_stay_at_infinity():
    robot = load_robot(ROOT / "examples" / "symmetric_4cables.toml")
    rho, _ = lengths_and_taut_sets(robot)
    target = normalized_problem(robot, rho, (0, 1, 2, 3))[0]
    res, failed = S._track(4, target, 0, False)
    paths = res.track.paths
    counts = {s: sum(p.status == s for p in paths) for s in {p.status for p in paths}}
    assert len(paths) == 216 and failed <= 2, counts
    assert counts.get("endgame_failed", 0) == 0, counts  # 24 before the pose valuation was read
    grow = [p for p in paths if p.status == AT_INFINITY
            and np.max(np.abs(p.endpoint[16 - 4:])) > np.max(np.abs(p.endpoint[:12]))]
    assert len(grow) >= 20, counts
    for p in grow:
        assert p.retried == "precise_endgame" and p.order * p.winding_number >= 0.5  # h ~ t^v, v c >= 1/2
        x = p.endpoint
        pos, lam = x[:3], x[12:]
        assert p.valuation(slice(0, 12)) * p.winding_number <= -POSE_DIVERGES
        assert abs(pos @ pos) / np.sum(np.abs(pos) ** 2) <= 1e-3  # isotropic translation
        assert abs(lam.sum()) / np.max(np.abs(lam)) <= 1e-3  # balanced tensions


def _at_infinity(pose_scale_before, pose_scale_last, winding=1):
    """A path at infinity with |lam| = 100 at t = 1e-4 (10 at 4e-4) and its pose of the given sizes there."""
    x = np.concatenate([np.full(12, pose_scale_last), np.full(4, 100.0)]).astype(complex)
    prev = np.concatenate([np.full(12, pose_scale_before), np.full(4, 10.0)]).astype(complex)
    return PathResult(0, AT_INFINITY, x, 1e-4 + 0j, 0.0, 1.0, 1e-10, 10, winding_number=winding, previous=prev,
                      previous_t=4e-4 + 0j)


def _outcome(path):
    res = SolveResult(solutions=(), track=TrackResult(paths=(path,), seconds=0.0, seed=0))
    return tension_infinity_undecided(res, 4).track.paths[0].status


def test_tensions_growing_at_a_finite_pose_stay_undecided():
    assert _outcome(_at_infinity(0.9, 0.9)) == "endgame_failed"  # pose valuation 0
    assert _outcome(_at_infinity(0.9, 0.9, winding=2)) == "endgame_failed"
    unknown = _at_infinity(0.9, 0.9)
    assert _outcome(PathResult(0, AT_INFINITY, unknown.endpoint, unknown.t, 0.0, 1.0, 1e-10, 10)) == "endgame_failed"
    assert _outcome(_at_infinity(5.0, 20.0)) == AT_INFINITY  # pose valuation -1
    assert _outcome(_at_infinity(5.0, 20.0, winding=2)) == AT_INFINITY  # -1 = -2 / c
    assert _outcome(_at_infinity(10.0, 14.0)) == "endgame_failed"  # -0.24: not a power k / c, k >= 1


def test_the_symmetric_robot_is_complete_by_both_routes():
    """The same taut set by the DGP: its exit points and platform anchors are two rectangles with G 0.2 below the
    plate's centre, so it is tracked from the off-centre parallelograms' generic set (dgp.parallelogram): 184 paths,
    every one regular and proven in a Krawczyk box.  The generic route (``rods=False``, 216 paths) independently
    finds the same: 184 regular roots, every one proven, the same points, and 32 paths at infinity (decided in Study
    parameters, the (g, lam) block unbounded), which make its generic count 216."""
    from cdpr_algebra.dgp.parallelogram import parallelogram_start

    robot = load_robot(ROOT / "examples" / "symmetric_4cables.toml")
    sub, sols = S.solve_taut_set(robot, robot.lengths, (0, 1, 2, 3))
    assert sub.parallelogram == (1, 2, 3, 4) and sub.parallelogram_kind == "off_centre"
    assert sub.outcomes == {"regular": 184, "singular": 0, "at_infinity": 0, "failed": 0}, sub.outcomes
    assert sub.complete and sub.certified == sub.finite == sub.generic_count == 184
    assert len(sols) == 2 and all(s.certified for s in sols)
    rho = np.asarray(robot.lengths)
    gen, gsols, Zg = S._solve_taut_set(robot, rho, (0, 1, 2, 3), exclude=False, rods=False)
    (gen,) = S._with_endpoint_certificates(robot, rho, [((0, 1, 2, 3), gen, Zg)])
    assert gen.parallelogram is None and gen.generic_count == 216
    assert gen.outcomes == {"regular": 184, "singular": 0, "at_infinity": 32, "failed": 0}, gen.outcomes
    assert gen.complete and gen.certified == gen.finite == len(parallelogram_start("off_centre")[1])
    _, _, Z = S._solve_taut_set(robot, rho, (0, 1, 2, 3), exclude=False)
    d = np.max(np.abs(Zg[:, None, :] - Z[None, :, :]), axis=2)
    assert np.all(np.min(d, axis=1) <= 1e-8 * (1 + np.max(np.abs(Z))))  # the same points
    assert sorted(np.round([s.position[2] for s in gsols], 9)) == sorted(np.round([s.position[2] for s in sols], 9))


def test_a_route_from_another_generic_instance_settles_the_crawling_path():
    """One path of the first route (seed 0, no gamma) crawls at t ~ 0.25 next to Study's exceptional set and fails,
    in Study parameters, in the taut system and in double-double alike; its root (well conditioned, |x| ~ 15;
    PHCpack's blackbox finds it too, measured) is reached by the run from another generic instance
    (dgp.other_start), whose regular roots settle the failed path (the DGP itself now completes the set by the
    gamma route first, twenty-eighth session)."""
    from cdpr_algebra.dgp.other_start import other_generic_instance

    robot = load_robot(ROOT / "examples" / "symmetric_4cables.toml")
    rho, _ = lengths_and_taut_sets(robot)
    target = normalized_problem(robot, rho, (0, 1, 2, 3))[0]
    res, failed = S._track(4, target, 0, False)
    assert failed == 1
    other = other_generic_instance(lambda p, s: S._track(4, p, s, True)[0], *S._generic(4))
    settled, left = S._settle_on_other_runs_roots(4, target, res, S._track(4, target, 0, True, None, other)[0], None)
    assert left == 0 and sum(p.retried == "unheld_root" for p in settled.track.paths) == 1
    assert len(settled.solutions) == len(res.solutions) + 1
