"""Another solver's complex roots of one subproblem against ours (:mod:`cdpr_algebra.comparison.roots`, ``cdpr
crosscheck --taut .. --roots FILE``): PHCpack's blackbox output on Test 1's {1, 2} (tests/data, cut to its last
list), JSON roots, and every verdict (agree, a definite difference either way, not compared)."""

import gzip
import json
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.comparison.roots import TheirRoots, compare_root_sets, compare_roots, read_roots, roots_report
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.model.robot import load_robot

ROOT = Path(__file__).resolve().parents[1]
ROBOT = ROOT / "examples" / "seed000_test1.toml"
CABLES = (0, 1)
NAMES = ["px", "py", "pz", "ux", "uy", "uz", "vx", "vy", "vz", "wx", "wy", "wz", "lam1", "lam2"]


@pytest.fixture(scope="module")
def phc_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("phc") / "phc_seed000_test1_12.out"
    path.write_text(gzip.open(ROOT / "tests" / "data" / "phc_seed000_test1_12.out.gz", "rt").read())
    return path


@pytest.fixture(scope="module")
def ours():
    from cdpr_algebra.dgp.solve import taut_set_roots

    robot = load_robot(ROBOT)
    return (robot, *taut_set_roots(robot, robot.lengths, CABLES))


def test_phcpack_output_is_read_with_its_classes(phc_file):
    """The counts PHCpack prints under its last list ('A list of 384 solutions has been refined: 32 regular, 28 at
    infinity, 324 failures') are those of the solutions read."""
    t = read_roots(phc_file)
    assert t.solver == "PHCpack" and sorted(t.variables) == sorted(NAMES)  # in PHCpack's order
    assert len(t.roots) == 32 and t.classes.get("at infinity") == 28 and t.classes.get("no solution") == 324
    assert t.classes["real regular"] + t.classes["complex regular"] == 32 and t.failed == 324


def test_phcpack_roots_of_test1_12_are_ours(ours, phc_file):
    """PHCpack's 32 regular roots: 24 with both tensions nonzero, matched one to one with our 24 proven roots (the
    subproblem's generic count), and 8 with a zero tension, which the homotopy does not track."""
    robot, sub, Z, proven = ours
    c = compare_roots(robot, robot.lengths, CABLES, phc_file)
    assert c.agree is True, c.compared
    assert (c.theirs, c.ours, c.ours_proven, len(c.matched)) == (24, 24, 24, 24) and sub.complete
    assert c.theirs_zero_tension == 8 and not c.theirs_only and not c.ours_only
    t = read_roots(phc_file)
    T = t.roots[:, [t.variables.index(v) for v in NAMES]]
    zero = np.min(np.abs(T[:, 12:]), axis=1) <= 1e-9 * (1 + np.max(np.abs(T), axis=1))
    assert zero.sum() == 8
    for i, j in c.matched:  # their values, not ours, within the tolerance
        assert np.max(np.abs(c.their_roots[i] - Z[j])) <= 1e-6 * (1 + np.max(np.abs(Z[j])))
    assert "agree" in roots_report(c)


def test_a_proven_root_missing_on_either_side_is_a_definite_difference(ours, phc_file):
    robot, sub, Z, proven = ours
    t = read_roots(phc_file)
    # one of our roots left out: theirs has a root, proven by our Krawczyk test, that ours lacks
    c = compare_root_sets(robot, robot.lengths, CABLES, t, sub, Z[1:], proven[1:])
    assert c.agree is False and len(c.theirs_only_proven) == 1
    assert np.max(np.abs(c.their_roots[c.theirs_only_proven[0]] - Z[0])) <= 1e-6 * (1 + np.max(np.abs(Z[0])))
    # one of theirs left out: a difference only where their file reports no failed path
    order = [t.variables.index(v) for v in NAMES]
    keep = [k for k in range(len(t.roots)) if np.max(np.abs(t.roots[k][order] - Z[0])) > 1e-6 * (1 + np.abs(Z[0]).max())]
    assert len(keep) == len(t.roots) - 1
    fewer = replace(t, roots=t.roots[keep])
    c = compare_root_sets(robot, robot.lengths, CABLES, fewer, sub, Z, proven)
    assert c.agree is None and len(c.ours_only) == 1 and "324 of their paths failed" in c.compared
    c = compare_root_sets(robot, robot.lengths, CABLES, replace(fewer, failed=0), sub, Z, proven)
    assert c.agree is False and "no failed path" in c.compared


def test_the_same_roots_do_not_agree_while_our_subproblem_is_incomplete(ours, phc_file):
    robot, sub, Z, proven = ours
    c = compare_root_sets(robot, robot.lengths, CABLES, read_roots(phc_file), replace(sub, complete=False), Z, proven)
    assert c.agree is None and len(c.matched) == 24 and "a root both missed is not ruled out" in c.compared


def test_a_moved_root_is_neither_matched_nor_proven(ours, phc_file):
    robot, sub, Z, proven = ours
    t = read_roots(phc_file)
    lam = [t.variables.index(v) for v in ("lam1", "lam2")]
    k = int(np.argmax(np.min(np.abs(t.roots[:, lam]), axis=1)))  # a root with both tensions nonzero
    R = t.roots.copy()
    R[k, t.variables.index("px")] += 1e-3
    c = compare_root_sets(robot, robot.lengths, CABLES, replace(t, roots=R), sub, Z, proven)
    assert c.agree is None and c.theirs_only == (k,) and not c.theirs_only_proven and len(c.ours_only) == 1
    assert "not proven roots" in c.compared


def test_json_roots_in_any_order_of_the_unknowns(ours, tmp_path):
    robot, sub, Z, proven = ours
    perm = np.random.default_rng(3).permutation(len(NAMES))
    data = {"solver": "a homotopy solver", "variables": [NAMES[k] for k in perm], "failed": 0,
            "roots": [[[float(z.real), float(z.imag)] for z in row[perm]] for row in Z[::-1]]}
    path = tmp_path / "roots.json"
    path.write_text(json.dumps(data))
    c = compare_roots(robot, robot.lengths, CABLES, path)
    assert c.agree is True and len(c.matched) == 24 and c.solver == "a homotopy solver"
    assert all(i == len(Z) - 1 - j for i, j in c.matched)


@pytest.mark.parametrize("text, words", [
    ("hello\n", "no 'THE SOLUTIONS'"),
    ('{"variables": ["px"], "roots": [[[1, 0]]]}', "their unknowns must be those of `cdpr export`"),
    ('{"variables": ["px"], "roots": [[[1, 0], [2, 0]]]}', "root 1: expected 1 finite values"),
    ('{"variables": "px", "roots": []}', "variables must be a list"),
    ('{"roots": []', "invalid JSON"),
])
def test_bad_root_files_name_the_option_and_the_problem(tmp_path, text, words):
    robot = load_robot(ROBOT)
    path = tmp_path / "bad.txt"
    path.write_text(text)
    with pytest.raises(CdprInputError) as e:
        compare_roots(robot, robot.lengths, CABLES, path)
    assert e.value.field == "--roots" and words in str(e.value)


def test_cli_exit_status_and_json(phc_file):
    run = [sys.executable, "-m", "cdpr_algebra", "crosscheck", str(ROBOT)]
    r = subprocess.run(run + ["--taut", "1", "2", "--roots", str(phc_file), "--json"], capture_output=True,
                       text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["agree"] is True and d["matched"] == 24 and d["theirs_zero_tension"] == 8
    assert d["our_subproblem"]["complete"] is True
    r = subprocess.run(run + ["--roots", str(phc_file)], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 2 and "--taut" in r.stderr and "Traceback" not in r.stderr
