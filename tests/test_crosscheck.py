"""``cdpr crosscheck`` claims agreement only where both solvers stand behind their answer (issue 15 item 5).

Oracles: the triangle inequalities behind the homotopy's pruning, computed here with plain numpy; a robot whose
G lies on the line of two anchors (the equilibria of that 2-cable set are not isolated, the interval solver skips
it); lengths built from a computed 2-cable equilibrium so that a third cable is exactly at its length there (a
zero-tension equilibrium: the interval search leaves it undecided on the domain boundary)."""

import json
from dataclasses import fields, replace
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.comparison import compare as cc_mod
from cdpr_algebra.cli.main import main
from cdpr_algebra.comparison.compare import CrosscheckResult, compare_taut_set, crosscheck_table, exit_status, pruning_proof
from cdpr_algebra.dgp.solve import prune, solve_taut_set
from cdpr_algebra.model.robot import Robot, load_robot

ROBOT = "examples/seed000_test1.toml"


def _with_failed(sub, k):
    """The homotopy subproblem with k failed paths (whichever form its record has: an ``outcomes`` dict with a
    ``complete`` flag, or a ``failed_paths`` field)."""
    if "outcomes" in {f.name for f in fields(sub)}:
        return replace(sub, outcomes={**sub.outcomes, "failed": k}, complete=False)
    return replace(sub, failed_paths=k)


@pytest.fixture(scope="module")
def test1():
    return load_robot(ROBOT)


def test_pruning_counts_as_agreement_only_when_proven(test1):
    """Lengths 1, 10, 25: cables 1 and 3 cannot both be taut (|rho1 - rho3| = 24 > |A1A3| + |b1'b3'|, computed
    here); the homotopy prunes [1, 3] and [1, 2, 3], the proof is confirmed in ball arithmetic and the interval search
    (which still runs) is complete and empty: agreement, with the reason."""
    rho = np.array([1.0, 10.0, 25.0])
    gap = abs(rho[0] - rho[2]) - (np.linalg.norm(test1.base[0] - test1.base[2])
                                  + np.linalg.norm(test1.platform[0] - test1.platform[2]))
    assert gap > 10
    for cables in [(0, 2), (0, 1, 2)]:
        assert prune(test1, rho, cables) is not None
        assert "proven in interval arithmetic" in pruning_proof(test1, rho, cables)
        c = compare_taut_set(test1, rho, cables)
        assert c.homotopy_skipped is not None and c.interval_skipped is None and c.undecided == 0
        assert c.agree is True and c.compared.startswith("homotopy pruned") and c.homotopy == c.interval == 0
    # a set the pruning does not touch is compared by running both solvers
    c = compare_taut_set(test1, rho, (0, 1))
    assert c.homotopy_skipped is None and c.agree is True and c.homotopy == c.interval == 2


def test_pruning_proof_at_the_border(test1):
    """With rho3 = rho1 + |A1A3| + |b1'b3'| (equality, up to rounding) nothing is proven; 1e-9 beyond, it is."""
    D = np.linalg.norm(test1.base[0] - test1.base[2]) + np.linalg.norm(test1.platform[0] - test1.platform[2])
    rho = np.array([1.0, 10.0, 1.0 + D])
    assert pruning_proof(test1, rho, (0, 2)) is None
    assert prune(test1, rho, (0, 2)) is None  # the float test has a margin: it does not prune either
    rho[2] *= 1 + 1e-9
    assert pruning_proof(test1, rho, (0, 2)) is not None and pruning_proof(test1, rho, (0, 1)) is None


def test_interval_skip_is_not_agreement(test1):
    """G on the line b1' b2': the interval solver skips taut set [1, 2]; the homotopy finds 0 there, which used to
    be reported as agreement.  Now: not compared, not counted, exit status 3."""
    com = 0.5 * (test1.platform[0] + test1.platform[1])
    robot = Robot(test1.base, test1.platform, com, test1.load, test1.load_direction, test1.lengths)
    c = compare_taut_set(robot, robot.lengths, (0, 1))
    assert c.interval_skipped is not None and "G lies on the line" in c.interval_skipped
    assert c.homotopy == 0 and c.interval == 0
    assert c.agree is None and c.status == "not compared" and "interval search skipped" in c.compared
    one = compare_taut_set(robot, robot.lengths, (0,))
    res = CrosscheckResult(robot.name, robot.lengths, (c, one), 0.0)
    assert one.agree is True and not res.agree and exit_status(res) == 3
    d = res.to_dict()
    assert d["agree"] is None and d["summary"] == {"subproblems": 2, "agree": 1, "disagree": 0, "not_compared": 1}
    assert [s["agree"] for s in d["subproblems"]] == [None, True]
    table = crosscheck_table(res)
    assert "1 agree, 0 disagree, 1 not compared" in table and "not compared" in table.splitlines()[2]


@pytest.fixture(scope="module")
def boundary_case(test1):
    """Lengths making the 2-cable equilibrium of [1, 3] (lengths 1, 10, 10) a zero-tension 3-cable one: rho2 is the
    distance |A2 B2| at that pose."""
    rho = np.array([1.0, 10.0, 10.0])
    _, sols = solve_taut_set(test1, rho, (0, 2))
    (s,) = sols
    B = s.position + test1.platform @ s.rotation.T
    rho[1] = np.linalg.norm(B[1] - test1.base[1])
    return rho, s


def test_zero_tension_equilibrium_is_not_compared(test1, boundary_case):
    rho, s = boundary_case
    c = compare_taut_set(test1, rho, (0, 2))
    # the homotopy reports the equilibrium (cable 2 at its length passes its slack test); the interval search
    # proves it but cannot decide cable 2's slackness: an undecided box near the same pose
    assert c.homotopy == 1 and c.interval == 0 and c.undecided == 1
    assert np.allclose(c.undecided_boxes[0].position, s.position, atol=1e-6)
    assert c.agree is None and "1 undecided box" in c.compared
    assert not c.homotopy_only or c.agree is None  # a homotopy-only solution is no disagreement: the search is open


def test_failed_paths_are_not_compared_and_definite_differences_disagree(test1, monkeypatch):
    """The homotopy's failed paths make its count incomplete: not compared; a proven interval solution that a
    complete homotopy lacks is a disagreement, and so is a homotopy solution outside a complete interval search."""
    rho = np.array([1.0, 10.0, 10.0])
    real = cc_mod._homotopy

    def failing(robot, rho_, cables, seed, extended=False):
        sub, sols = real(robot, rho_, cables, seed)
        return _with_failed(sub, 3), sols

    monkeypatch.setattr(cc_mod, "_homotopy", failing)
    c = compare_taut_set(test1, rho, (0, 2))
    assert c.homotopy == c.interval == 1 and c.agree is None and c.homotopy_failed_paths == 3
    assert "3 failed path(s)" in c.compared

    def dropping(robot, rho_, cables, seed, extended=False):
        sub, sols = real(robot, rho_, cables, seed)
        return sub, sols[1:]

    monkeypatch.setattr(cc_mod, "_homotopy", dropping)
    c = compare_taut_set(test1, rho, (0, 2))
    assert c.homotopy == 0 and c.interval == 1 and c.agree is False and len(c.interval_only) == 1

    def dropping_and_failing(robot, rho_, cables, seed, extended=False):
        sub, sols = dropping(robot, rho_, cables, seed)
        return _with_failed(sub, 1), sols

    monkeypatch.setattr(cc_mod, "_homotopy", dropping_and_failing)
    c = compare_taut_set(test1, rho, (0, 2))
    assert c.agree is None  # the missing solution may be behind the failed path

    def moving(robot, rho_, cables, seed, extended=False):
        sub, sols = real(robot, rho_, cables, seed)
        return _with_failed(sub, 1), [replace(s, position=s.position + 1e-3) for s in sols]

    monkeypatch.setattr(cc_mod, "_homotopy", moving)
    c = compare_taut_set(test1, rho, (0, 2))
    assert c.agree is False and len(c.homotopy_only) == 1 and len(c.interval_only) == 1


def test_cli_exit_status_and_json(monkeypatch, capsys, boundary_case):
    rho, _ = boundary_case
    lengths = [f"{v:.17g}" for v in rho]
    code = main(["crosscheck", ROBOT, "--lengths", *lengths, "--taut", "1", "3", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 3 and out["exit_status"] == 3 and out["agree"] is None
    (sub,) = out["subproblems"]
    assert sub["agree"] is None and sub["compared"].startswith("not compared")
    assert out["summary"]["not_compared"] == 1 and out["summary"]["agree"] == 0
    code = main(["crosscheck", ROBOT, "--lengths", *lengths, "--taut", "1", "3"])
    captured = capsys.readouterr()
    assert code == 3 and "0 agree, 0 disagree, 1 not compared" in captured.out
    assert "incomplete" in captured.err and "[1, 3]" in captured.err.splitlines()[-1]

    real = cc_mod._homotopy
    monkeypatch.setattr(cc_mod, "_homotopy",
                        lambda robot, rho_, cables, seed, extended=False: (real(robot, rho_, cables, seed)[0], []))
    code = main(["crosscheck", ROBOT, "--lengths", "1", "10", "10", "--taut", "1", "3", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 1 and out["agree"] is False and out["subproblems"][0]["agree"] is False
    monkeypatch.setattr(cc_mod, "_homotopy", real)
    code = main(["crosscheck", ROBOT, "--lengths", "1", "10", "10", "--taut", "1", "3", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["agree"] is True and out["summary"]["agree"] == 1


def test_comparison_reuses_a_dgp_run(test1):
    """A comparison built on the subproblem of an earlier whole-robot DGP (``homotopy_result``, taken with
    ``DGPResult.taut_set``) says what a comparison that runs the homotopy itself says, on every taut set."""
    from cdpr_algebra.dgp.solve import dgp
    from cdpr_algebra.model.taut_sets import lengths_and_taut_sets

    res = dgp(test1, exclude=False)  # every set tracked: the homotopy's own answer on each
    rho, sets = lengths_and_taut_sets(test1, None, 6)
    for c in sets:
        sub, sols = res.taut_set([i + 1 for i in c])
        assert sub.taut == tuple(i + 1 for i in c) and all(s.taut == sub.taut for s in sols)
        a = compare_taut_set(test1, rho, c, homotopy_result=(sub, sols))
        b = compare_taut_set(test1, rho, c)
        assert (a.homotopy, a.interval, a.agree, a.compared) == (b.homotopy, b.interval, b.agree, b.compared)
        if sols:  # the given result is what is compared: without its solutions, the interval ones are unmatched
            d = compare_taut_set(test1, rho, c, homotopy_result=(sub, ()))
            assert d.homotopy == 0 and d.agree is False and len(d.interval_only) == len(sols)
    assert sum(len(res.taut_set([i + 1 for i in c])[1]) for c in sets) == len(res.solutions) > 0
    with pytest.raises(KeyError, match="not solved"):
        res.taut_set([1, 2, 3, 4])
    # a set the DGP did not track because the interval filter excluded it is no homotopy answer: not compared
    sub, sols = dgp(test1).taut_set([1, 2])
    assert sub.excluded is not None and sub.paths == 0
    a = compare_taut_set(test1, rho, (0, 1), homotopy_result=(sub, sols))
    assert a.agree is None and "homotopy did not run" in a.compared


def test_crosscheck_same_whatever_the_number_of_threads():
    """The interval searches run ahead in threads; the comparison does not depend on how many."""
    from cdpr_algebra.comparison.compare import crosscheck
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(Path(__file__).resolve().parents[1] / "examples" / "seed000_test1.toml")

    def key(res):
        return [(c.taut, c.homotopy, c.interval, c.undecided, c.agree, c.compared, c.interval_boxes)
                for c in res.comparisons]

    one, two = crosscheck(robot, jobs=1), crosscheck(robot, jobs=2)
    assert key(one) == key(two) and all(c.agree for c in two.comparisons)
