"""Settling incomplete DGP subproblems by the interval branch and prune (cdpr_algebra.comparison.settle, cdpr dgp
--settle): with every homotopy path of Test 1's m >= 2 subproblems forced to fail, the interval search proves
their admissible sets, returns the six equilibria of Berti et al. 2016 Table 1 (the homotopy's own complete run
finds the same poses), and the CLI exits 0 because every admissible equilibrium is known; a homotopy solution
that the complete interval search does not have is a disagreement, never settled."""

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.dgp import study_retrack

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def test1():
    from cdpr_algebra.model.robot import load_robot

    return load_robot(ROOT / "examples" / "seed000_test1.toml")


@pytest.fixture(scope="module")
def normal(test1):
    """The homotopy's own complete run (before any patch)."""
    from cdpr_algebra.dgp.solve import dgp

    return dgp(test1, jobs=1)


@pytest.fixture()
def failing(monkeypatch):
    """Every path of m >= 2 fails: a budget of 3 steps, no projective retry."""
    import cdpr_algebra.dgp.solve as dgp_mod

    base = dgp_mod.default_options()
    tiny = replace(base, tracker=replace(base.tracker, max_steps=3))
    monkeypatch.setattr(dgp_mod, "default_options", lambda: tiny)
    monkeypatch.setattr(dgp_mod, "PROJECTIVE_RETRIES", 0)
    # and stays failed: Newton from the failed paths' estimates (dgp.unheld_roots) would find the roots
    monkeypatch.setattr(dgp_mod, "UNHELD_ROOTS", False)
    # and the endgame over double-double (its hybrid tracker goes on in double-double where 3 steps fail)
    monkeypatch.setattr(study_retrack, "PRECISE_ENDGAME_PATHS", 0)
    return dgp_mod


def test_settle_recovers_every_admissible_equilibrium(test1, normal, failing):
    from cdpr_algebra.comparison.settle import settle_incomplete

    broken = failing.dgp(test1, jobs=1, exclude=False)  # the sets of no equilibrium tracked (and failed) too
    assert not broken.complete and not broken.admissible_complete and len(broken.solutions) == 0
    settled, records = settle_incomplete(test1, broken)
    assert len(records) == len(broken.incomplete) == 4  # [1, 2], [1, 3], [2, 3], [1, 2, 3]
    assert all(r.outcome == "settled" for r in records)
    assert settled.admissible_complete and not settled.complete
    assert all(s.settled and not s.complete for s in settled.incomplete)
    # Table 1 of Berti et al. 2016: six equilibria, all with three taut cables; found here by the interval search
    assert len(settled.solutions) == 6 and all(s.found_by == "interval" and s.certified for s in settled.solutions)
    assert settled.taut_set((1, 2, 3))[0].admissible == 6
    d = settled.to_dict()
    assert d["admissible_complete"] is True and d["complete"] is False and len(d["settled"]) == 4
    assert {s["found_by"] for s in d["solutions"]} == {"interval"}
    # the same poses as the homotopy's own complete run (another method), to the interval enclosures' widths
    assert normal.complete and len(normal.solutions) == 6
    a = np.array([np.concatenate([s.position, s.rotation.ravel()]) for s in sorted(normal.solutions, key=lambda s: s.position[0])])
    b = np.array([np.concatenate([s.position, s.rotation.ravel()]) for s in sorted(settled.solutions, key=lambda s: s.position[0])])
    assert np.max(np.abs(a - b)) <= 1e-6


def test_settle_never_settles_a_disagreement(test1, failing):
    """A homotopy 'solution' that the complete interval search does not have: disagree, not settled."""
    from cdpr_algebra.comparison.settle import settle_incomplete
    from cdpr_algebra.dgp.solve import DGPSolution

    broken = failing.dgp(test1, jobs=1, max_m=2, exclude=False)
    bogus = DGPSolution((1, 2), np.array([1.0, 1.0, 1.0]), np.eye(3), np.array([0.5, 0.5, 0.0]), ">")
    settled, records = settle_incomplete(test1, replace(broken, solutions=(bogus,)))
    rec = {r.taut: r for r in records}
    assert rec[(1, 2)].outcome == "disagree" and "not among the proven solutions" in rec[(1, 2)].detail
    assert settled.taut_set((1, 2))[0].settled is None and not settled.admissible_complete
    assert rec[(1, 3)].outcome == rec[(2, 3)].outcome == "settled"


def test_cli_settle_exit_status(test1, failing, tmp_path, capsys):
    from cdpr_algebra.cli.main import main

    path = tmp_path / "t1.json"
    path.write_text(json.dumps(test1.to_dict()))
    assert main(["dgp", str(path), "--jobs", "1", "--json"]) == 3
    assert "--settle" in capsys.readouterr().err
    assert main(["dgp", str(path), "--jobs", "1", "--json", "--settle"]) == 0
    cap = capsys.readouterr()
    out = json.loads(cap.out)
    assert out["complete"] is False and out["admissible_complete"] is True and len(out["solutions"]) == 6
    # [1, 2], [1, 3], [2, 3] are excluded by the interval filter before tracking; [1, 2, 3] fails and is settled
    assert [r["outcome"] for r in out["settle"]] == ["settled"] and out["settled"] == [[1, 2, 3]]
    assert [s["taut"] for s in out["subproblems"] if s["excluded"]] == [[1, 2], [1, 3], [2, 3]]
    assert "every admissible equilibrium is known" in cap.err
    assert main(["dgp", str(path), "--jobs", "1", "--json", "--settle", "--track-all"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [r["outcome"] for r in out["settle"]] == ["settled"] * 4 and len(out["solutions"]) == 6


def test_settle_same_whatever_the_number_of_threads(test1, failing):
    from cdpr_algebra.comparison.settle import settle_incomplete

    broken = failing.dgp(test1, jobs=1, max_m=2, exclude=False)
    one, r1 = settle_incomplete(test1, broken, jobs=1)
    two, r2 = settle_incomplete(test1, broken, jobs=2)
    assert [(r.taut, r.outcome, r.detail) for r in r1] == [(r.taut, r.outcome, r.detail) for r in r2]
    assert json.dumps(one.to_dict()["solutions"]) == json.dumps(two.to_dict()["solutions"])


def test_track_start_decided_by_a_settled_dgp(test1, normal, failing):
    """The default start of ``track`` (the stable equilibrium of lowest potential) is undecided when the start DGP
    is incomplete, and decided when that DGP's incomplete subproblems are settled: the same start as the complete
    homotopy run's."""
    from cdpr_algebra.comparison.settle import settle_incomplete
    from cdpr_algebra.track.follow import start_equilibrium

    rho = np.asarray(test1.lengths, dtype=float)
    broken = failing.dgp(test1, jobs=1, certify=False)
    settled, _ = settle_incomplete(test1, broken)
    # the same solutions without the proof: undecided
    _, info_unproven = start_equilibrium(test1, rho, 0.0, replace(broken, solutions=settled.solutions))
    assert info_unproven["dgp_complete"] is False and "may be missing" in info_unproven["note"]
    st, info = start_equilibrium(test1, rho, 0.0, settled)
    ref, info_ref = start_equilibrium(test1, rho, 0.0, normal)
    assert info["dgp_complete"] is True and "interval branch and prune" in info["note"]
    assert info_ref["dgp_complete"] is True
    assert np.max(np.abs(st.position - ref.position)) <= 1e-9 * test1.size


def test_settle_box_budget_leaves_subproblems_undecided(test1, failing, tmp_path, capsys):
    """A budget too small to finish: the subproblem stays undecided (with the reason), nothing is settled, exit 3."""
    from cdpr_algebra.bp.results import BPOptions
    from cdpr_algebra.cli.main import main
    from cdpr_algebra.comparison.settle import settle_incomplete

    broken = failing.dgp(test1, jobs=1)
    settled, records = settle_incomplete(test1, broken, options=BPOptions(max_boxes=1))
    rec = {r.taut: r for r in records}
    assert rec[(1, 2, 3)].outcome == "undecided" and "box budget exhausted" in rec[(1, 2, 3)].detail
    assert settled.taut_set((1, 2, 3))[0].settled is None and not settled.admissible_complete
    path = tmp_path / "t1.json"
    path.write_text(json.dumps(test1.to_dict()))
    assert main(["dgp", str(path), "--jobs", "1", "--settle", "--settle-max-boxes", "1"]) == 3
    assert main(["dgp", str(path), "--settle", "--settle-max-boxes", "0"]) == 2
    assert "--settle-max-boxes" in capsys.readouterr().err
