"""Stability labels match the proofs (issue 15 item 5): the IGP's tables and JSON give the class of H_r proven by
the interval certificate, or 'undecided' with the floating-point class labelled as an estimate; the DGP table never
shows an unproven class beside a plain "yes".

Oracles: the eigenvalues of the floating-point reduced Hessian (seed 000 eq. 28) away from a sign change, and,
at the orientation where an eigenvalue crosses zero, their smallness (nothing can prove the class there)."""

import json

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.cli.main import main
from cdpr_algebra.igp.orientation import igp_orientation
from cdpr_algebra.model.pose import matrix_from_angles
from cdpr_algebra.model.stability import reduced_hessian, stability_classes
from cdpr_algebra.report.tables import igp_table

ROBOT = "examples/seed004_table1.toml"


@pytest.fixture(scope="module")
def robot():
    return load_robot(ROBOT)


def _solve(robot, phi_x):
    (s,) = igp_orientation(robot, matrix_from_angles(phi_x, 0.0, 0.0)).real_solutions
    return s


def _eigenvalues(robot, s):
    B = s.com_position + (robot.platform - robot.com) @ s.rotation.T
    Hr = reduced_hessian(robot.base, B, s.com_position, s.tensions, s.lengths, length_scale=robot.size)
    return np.linalg.eigvalsh(0.5 * (Hr + Hr.T))


def _class(lam, rtol=1e-6):
    tol = rtol * np.max(np.abs(lam))
    if np.all(lam > tol):
        return ">"
    if np.all(lam < -tol):
        return "<"
    return "<>" if np.any(lam > tol) and np.any(lam < -tol) else None


@pytest.fixture(scope="module")
def crossing(robot):
    """Scan phi_x (Table 1's robot, rotations about x) for two orientations whose proven classes are '<>' and '>',
    then bisect on the proven class until the certificate cannot decide: an eigenvalue of H_r crosses zero."""
    angles = np.linspace(-0.1, -0.05, 11)
    sols = [_solve(robot, a) for a in angles]
    for a, s in zip(angles, sols):
        assert s.certified
        expected = _class(_eigenvalues(robot, s))
        if expected is not None:  # well separated eigenvalues: the proof and the float estimate agree
            assert s.hessian_proven == expected == s.hessian, a
    k = next(k for k in range(10) if (sols[k].hessian_proven, sols[k + 1].hessian_proven) == ("<>", ">"))
    lo, hi = angles[k], angles[k + 1]
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        s = _solve(robot, mid)
        if s.hessian_proven is None:
            return float(mid), s
        if s.hessian_proven == "<>":
            lo = mid
        else:
            hi = mid
    pytest.fail("no undecided class found between '<>' and '>'")


def test_undecided_class_is_printed_as_undecided(robot, crossing):
    phi, s = crossing
    lam = _eigenvalues(robot, s)
    assert np.min(np.abs(lam)) < 1e-9 * np.max(np.abs(lam))  # why nothing is proven: a (near) zero eigenvalue
    assert s.certified and s.certificate.hessian == "undecided" and s.hessian_label == "undecided"
    assert s.stable_proven is None and s.hessian in (">", ">=", "<>", "<", "<=")
    d = s.to_dict()
    assert d["hessian"] == "undecided" and d["hessian_float"] == s.hessian
    assert d["stable"] is None and d["stable_float"] == (s.hessian == ">")
    result = igp_orientation(robot, matrix_from_angles(phi, 0.0, 0.0))
    text = igp_table(result)
    row = text.splitlines()[2]
    assert f"undecided (float: {s.hessian})" in row and row.rstrip().endswith("yes")
    assert "H_r undecided for 1" in text.splitlines()[-1] and "0 admissible and proven stable" in text


def test_proven_class_is_printed_and_in_the_json(robot, capsys):
    s = _solve(robot, 0.0)
    assert _class(_eigenvalues(robot, s)) == ">"  # Table 1's pose is stable (seed 004)
    assert s.hessian_proven == ">" and s.stable_proven is True
    assert main(["igp", ROBOT, "--orientation", "0", "0", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    (sol,) = out["solutions"]
    assert sol["hessian"] == ">" and sol["hessian_float"] == ">" and sol["stable"] is True
    assert out["count"]["stable"] == out["count"]["stable_float"] == 1
    assert main(["igp", ROBOT, "--orientation", "0", "0", "0"]) == 0
    text = capsys.readouterr().out
    assert "undecided" not in text and "1 admissible and proven stable" in text


def test_cli_table_and_json_at_the_crossing(robot, crossing, capsys):
    phi, s = crossing
    assert main(["igp", ROBOT, "--orientation", repr(phi), "0", "0", "--json"]) == 0
    (sol,) = json.loads(capsys.readouterr().out)["solutions"]
    assert sol["hessian"] == "undecided" and sol["hessian_float"] == s.hessian and sol["certified"] is True
    assert main(["igp", ROBOT, "--orientation", repr(phi), "0", "0"]) == 0
    assert "undecided (float:" in capsys.readouterr().out


def test_dgp_table_never_shows_an_unproven_class_beside_a_plain_yes():
    """Test 1's robot at lengths 1, 10, 25: two 1-cable equilibria (neutral about the cable: H_r singular, its class
    with that zero proven since the thirty-second session) and two 2-cable ones.  A row whose certificate leaves H_r
    undecided says so in the certified column; here every class is proven and equals the floating-point class."""
    from cdpr_algebra.dgp.solve import dgp, dgp_table

    robot = load_robot("examples/seed000_test1.toml")
    res = dgp(robot, [1.0, 10.0, 25.0], jobs=1)
    lines = dgp_table(res, robot.n).splitlines()
    start = lines[0].index("certified")
    undecided = 0
    for s, row in zip(res.solutions, lines[2:2 + len(res.solutions)]):
        label = row[start:].strip()
        if s.certified and s.certificate.hessian != "proven":
            undecided += 1
            assert label == "yes (H_r undecided)", row
        elif s.certified:
            assert s.hessian == s.certificate.hessian_class and label == "yes", row
    assert undecided == 0 and sum(1 for s in res.solutions if len(s.taut) == 1) == 2
    for s in res.solutions:  # the proven class is the one the floating-point eigenvalues give
        taut = list(s.taut)
        A, b = robot.base[[c - 1 for c in taut]], robot.platform[[c - 1 for c in taut]]
        B, G = s.position + b @ s.rotation.T, s.position + s.rotation @ robot.com
        lengths = np.linalg.norm(B - A, axis=1)
        cls = stability_classes(A, B, G, s.tensions[[c - 1 for c in taut]], lengths, robot.load, robot.size)
        assert s.certificate.hessian_class == cls
        assert len(taut) > 1 or cls in (">=", "<=", "<>")
