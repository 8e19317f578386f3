"""Issue 15: taut sets whose platform anchors lie on one line while the centre of mass does not are tracked from
the generic solution set of that subfamily (:mod:`cdpr_algebra.dgp.collinear_anchors`), so that the generic
family's solutions that leave to infinity there (complex rotations about the line) are not tracked at all.

Independent checks: the stored subfamily sets solve their equations, stay in the subfamily and carry a trace test
that passed inside it (recorded by derivations/solve_generic_collinear.py); the change of platform frame preserves
the equations' residuals and is undone exactly; where the generic route also completes, both routes end on the same
certified roots; the admissible equilibria agree with the interval branch and prune of the same taut set.
"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.dgp.collinear_anchors import COLLINEAR_M, collinear_path, fixed_parameters, line_frame
from cdpr_algebra.dgp.solve import DGPResult, _solve_taut_set, _with_endpoint_certificates, dgp_table
from cdpr_algebra.model.robot import load_robot
from cdpr_algebra.model.taut_equations import encode

ROOT = Path(__file__).resolve().parents[1]


def _low_beam():
    """The beam of examples/beam_4cables.toml with its load 0.25 below the line of its anchors."""
    return replace(load_robot(ROOT / "examples" / "beam_4cables.toml"), com=np.array([0.0, 0.0, -0.25]))


def _solved(robot, cables, **kw):
    rho = np.asarray(robot.lengths)
    sub, sols, Z = _solve_taut_set(robot, rho, cables, **kw)
    (sub,) = _with_endpoint_certificates(robot, rho, [(cables, sub, Z)])
    return sub, sols, Z


@pytest.mark.parametrize("m", COLLINEAR_M)
def test_stored_subfamily_sets_solve_their_equations_and_passed_the_trace_test(m):
    from cdpr_algebra.dgp.taut_system import fast_family
    from cdpr_algebra.homotopy.monodromy import load_instance
    from cdpr_algebra.model.taut_equations import taut_family

    p, X, data = load_instance(collinear_path(m), taut_family(m))  # hash of the sympy system checked
    assert np.all(p[list(fixed_parameters(m))] == 0)  # in the subfamily: anchors on the x axis
    F, J = fast_family(m).evaluate_and_jacobian(X, p)
    assert np.max(np.abs(F)) <= 1e-8 * (1 + np.max(np.abs(X)))
    assert np.all(np.isfinite(np.linalg.cond(J)))
    d = np.max(np.abs(X[:, None, :] - X[None, :, :]), axis=2) + np.eye(len(X))
    assert np.min(d) > 1e-6  # distinct
    meta = data["meta"]
    assert meta["fixed_parameters"] == list(fixed_parameters(m))
    assert meta["check"]["new_solutions"] == 0 and meta["monodromy"]["stopped_by"] == "no_progress"
    trace = meta["trace_test"]
    assert trace["status"] == "passed" and trace["count"] == len(X)
    assert trace["trace"]["relative"] <= trace["trace"]["tol"]
    # the trace separates: a single missing point would add at least 100 times the measured trace (m = 3 did not,
    # 6.9 times, until every point was refined in arbitrary precision before the sums: 1.9e4)
    assert trace["trace"]["detection"] >= 100 * trace["trace"]["relative"]
    assert trace["trace"]["points"] == len(X) + trace["W10_count"]
    # PHCpack's blackbox on another random member of the subfamily (recorded for m = 3, 4, 5): every regular
    # solution it found, with every lam_i nonzero, is one of the stored set's moved there
    runs = [meta["phc"]] + meta.get("phc_history", [])
    for rec in runs:
        assert rec["status"] == "finished" and rec["stored_moved_distinct"] == len(X)
        assert rec["phc_matched"] == rec["phc_distinct"] <= rec["stored_matched"] <= len(X)
    # fewer than the generic family's (156, 216, 140): the others leave to infinity in the subfamily
    generic = len(load_instance(ROOT / "cdpr_algebra" / "data" / f"dgp_generic_m{m}.json", check_hash=False)[1])
    assert len(X) < generic


def test_the_platform_frame_of_the_line_keeps_the_residuals_and_is_undone():
    """A pose of the beam's taut set {1, 2, 4} (any real rotation, position and multipliers) moved into the line's
    frame: the length, force and moment residuals are the same numbers, and the roots map back exactly."""
    from cdpr_algebra.dgp.normalization import normalized_problem
    from cdpr_algebra.dgp.taut_system import fast_family
    from cdpr_algebra.model.pose import rotation_about

    robot = load_robot(ROOT / "examples" / "beam_4cables.toml")
    s = np.array([-1.0, -0.5, 0.5, 1.0])[:, None]  # the beam turned and moved, exactly collinear in binary
    turned = replace(robot, platform=[0.125, 0.25, 0.0625] + s * [0.375, 0.25, -0.125], com=np.array([0.02, -0.03, -0.2]))
    cables = (0, 1, 3)
    frame = line_frame(turned, cables)
    assert frame is not None and frame.reading == "binary"
    assert np.allclose(frame.direction, np.array([0.375, 0.25, -0.125]) / np.linalg.norm([0.375, 0.25, -0.125]))
    rho = np.asarray(turned.lengths)
    target, c, L, Rw, cb = normalized_problem(turned, rho, cables)
    sub_target = frame.target(target, 3, cb, L)
    assert np.all(sub_target[list(fixed_parameters(3))] == 0)
    rng = np.random.default_rng(5)
    a = rng.normal(size=3)
    R = rotation_about(a / np.linalg.norm(a), 2.1)
    x = encode(rng.normal(size=3), R, rng.normal(size=3))[None].astype(complex)
    o, Rp = (frame.origin - cb) / L, frame.turn
    R2 = R @ Rp
    y = encode(x[0, :3].real + R @ o, R2, x[0, 12:].real)[None].astype(complex)
    fam = fast_family(3)
    F = fam.evaluate(x, target)[0]
    G = fam.evaluate(y, sub_target)[0]
    assert np.max(np.abs(F[6:] - G[6:])) <= 1e-12 * (1 + np.max(np.abs(F)))
    assert np.max(np.abs(frame.roots_back(y, 3, cb, L) - x)) <= 1e-13


def test_the_beam_with_its_load_below_the_line_is_complete():
    """The 6-DOF homotopy from the generic sets leaves {1, 2, 3, 4} of this robot with 7 failed paths (twenty-sixth
    session); from the subfamily's set every path is accounted for and every root certified, and the admissible
    equilibria are those the interval branch and prune proves (tests/test_interval_bp.py: 6)."""
    from cdpr_algebra.bp.search import solve_taut_set_interval

    robot = _low_beam()
    cables = (0, 1, 2, 3)
    sub, sols, _ = _solved(robot, cables)
    assert sub.collinear_anchors == "binary" and sub.generic_count == 56
    assert sub.complete and sub.accounted and sub.certified == sub.outcomes["regular"]
    bp = solve_taut_set_interval(robot, robot.lengths, cables)
    assert bp.complete and bp.admissible == sub.admissible == len(sols) == 6
    for s in bp.solutions:
        assert min(np.max(np.abs(s.position - h.position)) for h in sols) <= 1e-8


def test_both_routes_end_on_the_same_roots_where_both_complete():
    """{1, 2, 4} of the low beam: the generic route also completes (its other 140 paths go to infinity); its
    regular endpoints are the subfamily route's 76, root for root."""
    robot = _low_beam()
    cables = (0, 1, 3)
    sub, sols, Z = _solved(robot, cables)
    six, sols6, Z6 = _solved(robot, cables, rods=False)
    assert sub.complete and six.complete and sub.collinear_anchors == "binary" and six.collinear_anchors is None
    assert sub.certified == six.certified == len(Z) == len(Z6) == 76
    scale = 1 + np.max(np.abs(Z), axis=1)
    d = np.max(np.abs(Z[:, None, :] - Z6[None, :, :]), axis=2) / scale[:, None]
    assert np.all(d.min(axis=1) <= 1e-8) and np.all(d.min(axis=0) <= 1e-8)
    assert sub.admissible == six.admissible
    assert "tracked from that subfamily's generic set (76 paths)" in dgp_table(DGPResult(tuple(sols), (sub,), 0.0),
                                                                              robot.n)
    assert sub.to_dict()["collinear_anchors"] == {"start": "collinear_generic", "reading": "binary"}


def test_anchors_collinear_only_in_decimal_are_the_robot_read_in_decimal():
    """The low beam with its platform frame turned (x along (0.6, 0.8, 0)) and moved by (0.1, 0.7, 0.3): every taut
    set's anchors are collinear in the decimals of the file, in no binary reading.  {2, 3, 4} is tracked from the
    subfamily's set as the robot read in decimal, its endpoints proven in ball arithmetic with those decimals, and
    its admissible equilibrium is the unmoved beam's (the same world anchor positions and tensions)."""
    from cdpr_algebra.certificates.families import collinear_exactly
    from cdpr_algebra.dgp.solve import solve_taut_set

    low = _low_beam()
    x = low.platform[:, 0]
    moved = replace(low, platform=np.array([[round(0.1 + v * 0.6, 10), round(0.7 + v * 0.8, 10), 0.3] for v in x]),
                    com=np.array([0.1, 0.7, 0.05]))
    cables = (1, 2, 3)
    assert not collinear_exactly(moved.platform[list(cables)])
    sub, sols = solve_taut_set(moved, moved.lengths, cables)
    assert sub.collinear_anchors == "decimal" and sub.complete and sub.certified == 76
    ref_sub, ref = solve_taut_set(low, low.lengths, cables)
    assert ref_sub.collinear_anchors == "binary" and len(sols) == len(ref) == 1
    (s,), (r,) = sols, ref
    assert s.certified and s.reading == "decimal" and s.certificate.extra["reading"] == "decimal"
    world = s.position + moved.platform[list(cables)] @ s.rotation.T
    world_ref = r.position + low.platform[list(cables)] @ r.rotation.T
    assert np.max(np.abs(world - world_ref)) <= 1e-8 and np.allclose(s.tensions, r.tensions, atol=1e-8)
