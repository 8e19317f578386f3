"""Issue 15: taut sets whose platform anchors and centre of mass lie exactly on one line are solved as a rod
(:mod:`cdpr_algebra.dgp.rod`): one root of the rod system per family of turning equilibria, every path accounted
for, every root certified, the subproblem complete.

Independent checks: the 6-DOF homotopy of the same taut set (``rods=False``) finds the same families, as groups of
endpoints with the same taut anchors' world positions and tensions (:mod:`cdpr_algebra.dgp.positive_dimensional`):
the same number of families and the same real ones; the listed poses solve the 6-DOF statics (plain numpy) at
turning angles across their arcs; the stored generic sets solve their equations, carry a trace test that passed
and agree with PHCpack's blackbox solver on another random instance (recorded by derivations/solve_generic_rod.py).
"""

import json
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.certificates.families import collinear_exactly
from cdpr_algebra.dgp.rod import rod_generic_path, rod_geometry
from cdpr_algebra.comparison.compare import compare_taut_set
from cdpr_algebra.dgp.solve import (DGPResult, _solve_taut_set, _with_endpoint_certificates, dgp_table,
                                    excluded_subproblem, summary_line)
from cdpr_algebra.model.robot import load_robot
from cdpr_algebra.model.rod_equations import ROD_M, line_coordinates
from test_dgp_families import _poses_across_arcs, _residual, random_rod

ROOT = Path(__file__).resolve().parents[1]


def _flat():
    return replace(load_robot(ROOT / "examples" / "symmetric_4cables.toml"), com=np.zeros(3))


def _solved(robot, cables, **kw):
    rho = np.asarray(robot.lengths)
    sub, _, Z = _solve_taut_set(robot, rho, cables, **kw)
    (sub,) = _with_endpoint_certificates(robot, rho, [(cables, sub, Z)])
    return sub


def _invariants(f, robot, cables):
    """The taut anchors' world positions and the tensions of a listed family (the same for every turning angle)."""
    idx = list(cables)
    return np.concatenate([(f.position + robot.platform[idx] @ f.rotation.T).ravel(), f.tensions[idx]])


@pytest.mark.parametrize("m", ROD_M)
def test_stored_generic_rod_sets_solve_their_equations_and_passed_the_trace_test(m):
    from cdpr_algebra.homotopy.monodromy import load_instance
    from cdpr_algebra.model.rod_equations import rod_family

    fam = rod_family(m)
    p, X, data = load_instance(rod_generic_path(m), fam)  # hash of the sympy system checked
    F, J = fam.evaluate_and_jacobian(X, p)
    assert np.max(np.abs(F)) <= 1e-10 * (1 + np.max(np.abs(X)))
    assert np.max(np.linalg.cond(J)) < 1e10  # nonsingular
    d = np.max(np.abs(X[:, None, :] - X[None, :, :]), axis=2) + np.eye(len(X))
    assert np.min(d) > 1e-6  # distinct
    meta = data["meta"]
    assert meta["trace_test"]["status"] == "passed" and meta["trace_test"]["count"] == len(X)
    assert meta["check"]["new_solutions"] == 0 and meta["monodromy"]["stopped_by"] == "no_progress"
    tr = meta["trace_test"]["trace"]
    assert tr["relative"] <= tr["tol"] and tr["points"] == len(X) + meta["trace_test"]["W10_count"]
    # the trace separates: a single missing point would add at least 100 times the measured trace (m = 2, 3, 4 did
    # not, 7.6 to 47 times, until every point was refined in arbitrary precision before the sums); PHCpack's
    # polyhedral homotopy on another random instance is a second, independent count
    assert tr["detection"] >= 100 * tr["relative"]
    phc = meta["phc"]
    assert phc["status"] == "finished" and phc["regular"] <= phc["mixed_volume"]
    assert phc["phc_distinct"] == phc["stored_moved_distinct"] == phc["stored_matched"] == phc["phc_matched"] == len(X)


def test_rod_trace_recomputed_from_its_record_separates_and_notices_a_missing_point():
    """The m = 2 rod set's trace, recomputed from the recorded W10 along the recorded pencil with every point refined
    in arbitrary precision, passes with a separation of at least 100; with the witness point of the smallest
    second difference left out it does not pass (before the points were refined, such a point's signal, 1.3e-10,
    was below the tolerance and only 7.6 times the trace's rounding noise: that test would have passed)."""
    from cdpr_algebra.homotopy.monodromy import load_instance
    from cdpr_algebra.homotopy.trace_test import TraceTestOptions, compute_trace
    from cdpr_algebra.model.rod_equations import rod_family

    def uc(d):
        return np.asarray(d["re"], dtype=float) + 1j * np.asarray(d["im"], dtype=float)

    fam = rod_family(2)
    p, X, data = load_instance(rod_generic_path(2), fam)
    tt = data["meta"]["trace_test"]
    q0, l, gamma = uc(tt["q0"]), uc(tt["l"]), complex(tt["trace"]["gamma"]["re"], tt["trace"]["gamma"]["im"])
    W10 = uc(tt["W10"]).reshape(tt["W10_count"], fam.n + 1)
    o = TraceTestOptions(eps=tt["trace"]["eps"], polish_condition=0.0, attempts=1)
    tr = compute_trace(fam, p, q0, l, X, W10, o, gamma=gamma, coordinates=tt["coordinates"], keep_endpoints=True)
    assert tr.status == "passed" and tr.separation >= 100 and tr.relative <= 1e-12, tr.reason
    S0 = np.concatenate([np.concatenate([X, np.zeros((len(X), 1))], axis=1), W10])[:, tt["coordinates"] + [fam.n]]
    d2 = np.max(np.abs(tr.endpoints_plus - 2 * S0 + tr.endpoints_minus), axis=1)
    k = int(np.argmin(d2[len(X):]))  # the witness point that moves most nearly linearly
    short = compute_trace(fam, p, q0, l, X, np.delete(W10, k, axis=0), o, gamma=gamma, coordinates=tt["coordinates"])
    assert short.status != "passed" and short.relative >= 0.5 * tr.detection, (short.status, short.relative)


def test_line_coordinates_are_exact():
    D, s, DD = line_coordinates([[-0.5, 0, 0], [0.25, 0, 0], [0.5, 0, 0]], [0.1, 0, 0])
    assert D == (Fraction(-0.5) - Fraction(0.1), 0, 0) and DD == D[0] ** 2  # the farthest point from g
    assert s == [1, (Fraction(0.25) - Fraction(0.1)) / D[0], (Fraction(0.5) - Fraction(0.1)) / D[0]]
    flat = _flat()
    assert rod_geometry(flat, (0, 2)) is not None and rod_geometry(flat, (0, 1)) is None
    assert rod_geometry(flat, (0, 2))[2] == "binary"
    # collinear on paper (G at 0.4 of the diagonal), not in doubles: the rod of the robot read in decimal
    assert not collinear_exactly([flat.platform[0], flat.platform[2], [0.1, 0.06, 0.0]])
    assert rod_geometry(replace(flat, com=np.array([0.1, 0.06, 0.0])), (0, 2))[2] == "decimal"
    assert line_coordinates([[0.25, 0.15, 0]], [0.1, 0.06, 0], "decimal")[1] == [1]  # G + s D is B: s = 1 exactly
    # off the line in every reading: the 6-DOF homotopy
    assert rod_geometry(replace(flat, com=np.array([0.1, 0.0600001, 0.0])), (0, 2)) is None
    assert rod_geometry(load_robot(ROOT / "examples" / "symmetric_4cables.toml"), (0, 2)) is None


def test_a_flat_plates_diagonal_is_solved_as_a_rod_and_complete():
    flat = _flat()
    for cables in ((0, 2), (1, 3)):
        sub = _solved(flat, cables)
        fam = sub.family
        assert sub.complete and sub.accounted and fam.method == "rod system"
        assert sub.certified == sub.outcomes["regular"] == fam.certified and sub.paths == sub.generic_count
        assert "solved as a rod" in fam.describe()
        # the 6-DOF homotopy of the same set: the same families (two endpoints each) and the same real ones
        six = _solved(flat, cables, rods=False).family
        assert len(six.groups) == len(fam.groups) and six.real == fam.real
        assert len(six.members) == len(fam.members) >= 1
        for f in fam.members:
            v = _invariants(f, flat, cables)
            assert min(np.max(np.abs(v - _invariants(g, flat, cables))) for g in six.members) <= 1e-8
            assert f.certified and f.residual <= 1e-12
            for *_, x in _poses_across_arcs(flat, cables, f, 4):
                assert _residual(flat, cables, x) <= 1e-10
    # JSON and text
    sub = _solved(flat, (0, 2))
    result = DGPResult((), (sub,), 0.0, 0, None)
    assert result.complete
    out = json.loads(json.dumps(result.to_dict()))
    pd = out["subproblems"][0]["positive_dimensional"]
    assert pd["test"] == "rod system" and pd["certified"] == sub.certified and out["families"] == pd["members"]
    assert dgp_table(result, flat.n).count("a family of equilibria turning about the line through B1, B3, G") == 2
    assert "2 admissible families of equilibria" in summary_line(result)


def test_a_line_collinear_only_in_decimal_is_the_robot_read_in_decimal():
    """The flat plate with its platform frame moved by (0.1, 0.2, 0.3), written in decimal: B1, B3 and G stay on one
    line on paper, not in doubles (B2, B4 and G likewise).  Solved as the robot read in decimal, each diagonal is
    complete, and its families are those of the plate in its first frame, exactly collinear in doubles: the same
    number, the same real ones, the taut anchors' world positions and the tensions of the listed ones equal to 1e-8,
    every listed pose certified in the decimal reading and solving the doubles' statics."""
    flat = _flat()
    moved = replace(flat, platform=np.array([[-0.15, 0.05, 0.3], [0.35, 0.05, 0.3], [0.35, 0.35, 0.3],
                                             [-0.15, 0.35, 0.3]]), com=np.array([0.1, 0.2, 0.3]))
    for cables in ((0, 2), (1, 3)):
        points = [moved.platform[i] for i in cables] + [moved.com]
        assert not collinear_exactly(points) and collinear_exactly(points, "decimal")
        sub, ref = _solved(moved, cables), _solved(flat, cables)
        assert sub.complete and sub.certified == sub.outcomes["regular"] == sub.generic_count
        fam, want = sub.family, ref.family
        assert fam.reading == "decimal" and want.reading == "binary" and "read in decimal" in fam.describe()
        assert len(fam.groups) == len(want.groups) and fam.real == want.real
        assert len(fam.members) == len(want.members) >= 1
        for f in fam.members:
            v = _invariants(f, moved, cables)
            assert min(np.max(np.abs(v - _invariants(g, flat, cables))) for g in want.members) <= 1e-8
            assert f.certified and f.certificate.extra["reading"] == "decimal" and f.residual <= 1e-12
            for *_, x in _poses_across_arcs(moved, cables, f, 4):
                assert _residual(moved, cables, x) <= 1e-10
    result = DGPResult((), (sub,), 0.0, 0, None)
    pd = result.to_dict()["subproblems"][0]["positive_dimensional"]
    assert pd["test"] == "rod system" and pd["reading"] == "decimal"
    assert dgp_table(result, moved.n).count("(rod system, the robot read in decimal)") == len(fam.members)
    # the interval filter and search read the doubles, a robot off the line: they neither exclude the set (its
    # proof that {2, 4} holds no admissible equilibrium, true of the doubles, hid the decimal robot's family) nor
    # agree with the families (the interval search of {2, 4} is complete with no solution: not an agreement)
    assert excluded_subproblem(moved, moved.lengths, (1, 3)) is not None
    c = compare_taut_set(moved, moved.lengths, (1, 3))
    assert c.agree is None and "as a rod" in c.compared and "decimal" in c.compared
    # four cables on a line: the beam with its frame turned (x along (0.6, 0.8, 0)) and moved by (0.1, 0.7, 0.3)
    beam = load_robot(ROOT / "examples" / "beam_4cables.toml")
    turned = replace(beam, platform=np.array([[-0.2, 0.3, 0.3], [-0.05, 0.5, 0.3], [0.25, 0.9, 0.3], [0.4, 1.1, 0.3]]),
                     com=np.array([0.1, 0.7, 0.3]))
    cables = (0, 1, 2, 3)
    sub, ref = _solved(turned, cables), _solved(beam, cables)
    assert sub.complete and sub.family.reading == "decimal" and len(sub.family.members) == len(ref.family.members) == 2
    for f in sub.family.members:
        v = _invariants(f, turned, cables)
        assert min(np.max(np.abs(v - _invariants(g, beam, cables))) for g in ref.family.members) <= 1e-8
        assert f.certified


def test_the_beam_is_complete():
    """``examples/beam_4cables.toml``: every taut set of 2 to 4 cables is a rod; each is complete and its families
    are those the 6-DOF homotopy groups for the four-cable set."""
    beam = load_robot(ROOT / "examples" / "beam_4cables.toml")
    sub = _solved(beam, (0, 1, 2, 3))
    assert sub.complete and sub.family.method == "rod system" and len(sub.family.members) == 2
    six = _solved(beam, (0, 1, 2, 3), rods=False).family
    assert len(six.groups) == len(sub.family.groups) and six.real == sub.family.real
    for f in sub.family.members:
        v = _invariants(f, beam, (0, 1, 2, 3))
        assert min(np.max(np.abs(v - _invariants(g, beam, (0, 1, 2, 3)))) for g in six.members) <= 1e-8


def test_random_rods_solved_as_rods_match_the_six_dof_homotopy():
    """Random 3-cable robots with anchors and G on the platform's x axis: for each 2- and 3-cable set the rod's
    families are the 6-DOF homotopy's groups (count, real ones, invariants)."""
    compared = 0
    for seed in (11, 12):
        rod = random_rod(seed)
        for cables in ((0, 1), (0, 2), (1, 2), (0, 1, 2)):
            sub = _solved(rod, cables, exclude=False)
            if sub.skipped:
                continue
            assert sub.complete and sub.family.method == "rod system"
            six = _solved(rod, cables, exclude=False, rods=False).family
            assert len(six.groups) == len(sub.family.groups) and six.real == sub.family.real
            for f in sub.family.members:
                v = _invariants(f, rod, cables)
                assert min(np.max(np.abs(v - _invariants(g, rod, cables))) for g in six.members) <= 1e-7
            compared += 1
    assert compared >= 4


def test_a_rod_path_forced_to_fail_leaves_the_subproblem_incomplete():
    """A step budget too small for any path: every outcome failed and counted, the subproblem incomplete and saying
    why, the families not claimed complete."""
    from cdpr_algebra.dgp.solve import incompleteness
    from cdpr_algebra.homotopy.endgame import SolveOptions
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    flat = _flat()
    bad = SolveOptions(tracker=TrackerOptions(max_steps=3), retry_tight=False, retry_mpmath=False)
    sub = _solved(flat, (0, 2), options=bad)
    assert sub.family.method == "rod system" and not sub.complete
    assert sub.failed_paths > 0 and sum(sub.outcomes.values()) == sub.paths == sub.generic_count
    assert "paths failed" in incompleteness(sub)
    out = json.loads(json.dumps(DGPResult((), (sub,), 0.0, 0, None).to_dict()))
    assert out["complete"] is False and out["incomplete"] == [[1, 3]]


@pytest.mark.parametrize("m", ROD_M)
def test_the_generated_rod_evaluator_is_the_sympy_family(m):
    """The tracker's system (the generated evaluator on numpy columns) against the sympy family's own evaluators at
    random complex points and parameters (one row, and one row per point), and its directional parameter derivative
    against dF/dp . dp; the parameters are not modified by the evaluation."""
    from cdpr_algebra.dgp.rod import fast_rod_family
    from cdpr_algebra.model.rod_equations import rod_family

    rng = np.random.default_rng(m)
    fast, fam = fast_rod_family(m), rod_family(m)
    x = rng.normal(size=(4, fam.n)) + 1j * rng.normal(size=(4, fam.n))
    dp = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
    for p in (rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m), rng.normal(size=(4, fam.m)) + 0j):
        kept = p.copy()
        F0, J0, JP0 = fam.evaluate_all(x, p)
        F, J, H = fast.evaluate_directional(x, p, dp)
        assert np.max(np.abs(F - F0)) <= 1e-13 and np.max(np.abs(J - J0)) <= 1e-13
        assert np.max(np.abs(H - np.einsum("nik,k->ni", JP0, dp))) <= 1e-12
        assert np.array_equal(p, kept)


def test_singular_endpoints_on_a_family_leave_the_six_dof_route_incomplete():
    """Seed 002's 8-cable robot: B1, B5 and G are collinear, so {1, 5} is a rod (complete, 12 certified roots).  Its
    6-DOF homotopy ends all 24 paths on the families' circles labelled singular; those endpoints are not isolated
    roots of some multiplicity, so that route is incomplete and names the families -- the same 12, 2 of them real
    with positive tensions, as the rod's."""
    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    rod = _solved(robot, (0, 4))
    assert rod.complete and rod.family.method == "rod system" and rod.certified == rod.paths
    six = _solved(robot, (0, 4), rods=False)
    assert six.outcomes["singular"] > 0 and not six.complete
    assert six.family is not None and six.family.method == "numerical local dimension test"
    assert len(six.family.groups) == len(rod.family.groups) and six.family.real == rod.family.real
