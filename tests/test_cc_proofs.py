"""Robustness radii and the second criterion say what is proven (issue 15 item 5).

Radii: the critical point of r_min is certified (Krawczyk) and its nearest-ness is proven by an interval exclusion
(:func:`.cc_radii.prove_nearest`); both parts are reported.  Oracles for the exclusion: surfaces whose distance to
the origin is known in closed form (a sphere, a plane), and the homotopy's own nearest point (a point of the
surface, so no exclusion may succeed beyond it).  Second criterion: 'safe' only from the interval exclusion proof,
'unsafe' only with a certified counterexample whose distance is bounded in ball arithmetic, 'not proven' when only
the homotopy search ran; the counterexample is checked with plain statics here."""

import json

import numpy as np
import pytest

from cdpr_algebra.cc import radii as radii_mod
from cdpr_algebra.cc import safety as safety_mod
from cdpr_algebra import load_robot
from cdpr_algebra.cc.cubic_distances import MONOMIALS
from cdpr_algebra.cc.radii import cc_radii
from cdpr_algebra.cc.radius_proofs import arb_cubic, exclude_critical_points, prove_nearest
from cdpr_algebra.cc.safety import PROOF, SEARCH, distance_upper_bound, pose_distance, safety
from cdpr_algebra.cli.main import main

ROBOT = "examples/seed002_8cables.toml"


@pytest.fixture(scope="module")
def robot():
    return load_robot(ROBOT)


def _coefficients(terms):
    c = np.zeros(len(MONOMIALS))
    for e, v in terms.items():
        c[MONOMIALS.index(e)] = v
    return c


@pytest.mark.parametrize("terms,distance", [
    # sphere of radius 1 centred at (2, 0, 0): (y1 - 2)^2 + y2^2 + y3^2 - 1, nearest point (1, 0, 0)
    ({(2, 0, 0): 1.0, (1, 0, 0): -4.0, (0, 2, 0): 1.0, (0, 0, 2): 1.0, (0, 0, 0): 3.0}, 1.0),
    # plane y1 + y2 + y3 = 1: distance 1 / sqrt(3)
    ({(1, 0, 0): 1.0, (0, 1, 0): 1.0, (0, 0, 1): 1.0, (0, 0, 0): -1.0}, 1 / np.sqrt(3)),
    # a cubic: y1 (1 + y2^2) = 0.5 has its nearest point (0.5, 0, 0) (y1 = 0.5 / (1 + y2^2) <= 0.5 off the axis is
    # no nearer: |y|^2 = 0.25 / (1 + y2^2)^2 + y2^2 + y3^2 >= 0.25 with equality at y2 = y3 = 0)
    ({(1, 0, 0): 1.0, (1, 2, 0): 1.0, (0, 0, 0): -0.5}, 0.5),
])
def test_exclusion_proves_known_distances(terms, distance):
    c = _coefficients(terms)
    ok, boxes = exclude_critical_points(c, c, distance * (1 - 1e-9))
    assert ok and boxes > 1
    ok_beyond, _ = exclude_critical_points(c, c, distance * (1 + 1e-6))
    assert not ok_beyond  # the nearest point lies inside: nothing may be proven


def test_radius_certificate_parts(robot):
    res = cc_radii(robot, (0, 1, 2), [1, 2, 3, 4, 5, 6], certify=True)
    rc = res.radius_certificate
    assert rc["critical_point"] == "certified" and rc["nearest"] == "proven" and res.certified
    lo, hi = rc["proven_interval"]
    assert lo <= res.rmin <= hi and (hi - lo) <= 2e-9 * res.rmin
    assert lo == rc["proven_lower_bound"] and hi == rc["radius_enclosure"][1]
    assert res.rmin == pytest.approx(0.755452449, abs=5e-10)  # seed 002 Sec. IV-B.1, printed
    # the homotopy's nearest point is on the limiting surface: the exclusion must fail just beyond it
    h = radii_mod._default_scale(robot)
    beyond = prove_nearest(robot, res.position, res.rotation, res.cables, h, res.rmin * (1 + 1e-6))
    assert not beyond["proven"] and "tau_3" in beyond["reason"]
    column = res.cables.index(res.limiting)
    cb = arb_cubic(robot, res.position, res.rotation, res.cables, column, h)
    y = (res.nearest - res.position) / h
    value = sum(float(cv) * y[0] ** e[0] * y[1] ** e[1] * y[2] ** e[2] for cv, e in zip(cb, MONOMIALS))
    scale = sum(abs(float(cv)) * abs(y[0]) ** e[0] * abs(y[1]) ** e[1] * abs(y[2]) ** e[2] for cv, e in zip(cb, MONOMIALS))
    assert abs(value) <= 1e-9 * scale


def test_nearest_not_proven_is_reported_as_float_search(robot, capsys):
    res = cc_radii(robot, (1, 0, 2), [3, 4, 5, 6, 7, 8], certify=True, nearest_max_boxes=3)
    rc = res.radius_certificate
    assert rc["critical_point"] == "certified" and rc["nearest"] == "float search"
    assert res.certified is False and rc["proven_interval"] is None and rc["proven_lower_bound"] is None
    assert main(["cc", ROBOT, "--position", "1", "0", "2", "--configuration", "3", "4", "5", "6", "7", "8",
                 "--proof-boxes", "3"]) == 0
    text = capsys.readouterr().out
    row = text.splitlines()[3]
    assert "critical point" in row and "certified robustness radius" not in text
    assert "nearest by a floating-point search (homotopy), not proven" in text


def test_cli_radius_json_and_table(capsys):
    assert main(["cc", ROBOT, "--position", "1", "0", "2", "--json"]) == 0
    confs = json.loads(capsys.readouterr().out)["configurations"]
    assert len(confs) == 4
    for c in confs:
        rc = c["radius_certificate"]
        assert c["certified"] is True and rc["critical_point"] == "certified" and rc["nearest"] == "proven"
        assert rc["proven_interval"][0] <= c["rmin"] <= rc["proven_interval"][1]
    assert main(["cc", ROBOT, "--position", "1", "0", "2"]) == 0
    text = capsys.readouterr().out
    assert text.count("nearest proven (interval exclusion") == 4 and "r_min certified" in text.splitlines()[1]


def test_distance_upper_bound_encloses_the_distance():
    """On the certified equilibria of seed 000 Test 1 (3 taut cables): the ball-arithmetic bound is >= the float
    distance and within 1e-6 of it; no bound without a proven box."""
    from cdpr_algebra.dgp.solve import solve_taut_set

    robot = load_robot("examples/seed000_test1.toml")
    _, sols = solve_taut_set(robot, robot.lengths, (0, 1, 2))
    assert len(sols) == 6
    G0, R0 = np.array([3.0, 4.0, 5.0]), np.eye(3)
    for s in sols:
        d = pose_distance(G0, R0, s.position + s.rotation @ robot.com, s.rotation)[0]
        bound = distance_upper_bound(G0, R0, s.certificate, robot.com)
        assert s.certified and d <= bound <= d + 1e-6
    assert distance_upper_bound(G0, R0, None, robot.com) is None


@pytest.mark.slow
def test_second_criterion_names_its_method(robot, monkeypatch, capsys):
    """CC [3, .., 8] at a pose 1 cm inside its tau_5 = 0 surface (tests/test_cc_safety.py): within 0.03 the
    exclusion fails and the homotopy search finds nothing -- not proven, never plain 'safe'; within 2.5 it finds a
    certified 4-cable equilibrium -- unsafe with a verified counterexample (checked here with plain statics)."""
    res = cc_radii(robot, (1, 0, 2), [3, 4, 5, 6, 7, 8])
    x0 = np.array([1.0, 0, 2])
    x = x0 + (res.rmin - 0.01) * (res.nearest - x0) / res.rmin
    real = safety_mod.sub_configuration_equilibria
    cache = {}

    def once(*args, **kwargs):  # the same DGP search serves every call below
        if "v" not in cache:
            cache["v"] = real(*args, **kwargs)
        return cache["v"]

    monkeypatch.setattr(safety_mod, "sub_configuration_equilibria", once)
    near = safety(robot, x, res.cables, radius=0.03)
    assert near.safe is None and near.method == SEARCH and not near.proven
    assert near.status.startswith("not proven: no sub-configuration equilibrium found within 0.03")
    far = safety(robot, x, res.cables, radius=2.5)
    assert far.safe is False and far.counterexample_verified is True and far.method == SEARCH
    n = far.nearest
    assert n["certified"] and n["distance"] <= n["distance_upper_bound"] <= 2.5
    # plain statics at the counterexample: taut cables at the pose's lengths, forces and moments balanced
    from cdpr_algebra.model.pose import matrix_from_angles

    cables = list(res.cables)
    R = matrix_from_angles(*n["angles"])
    G = np.asarray(n["position"])
    B = G + (robot.platform[cables] - robot.com) @ R.T
    rho_pose = np.linalg.norm(robot.base[cables] - (x + (robot.platform[cables] - robot.com)), axis=1)
    tau = np.asarray(n["tensions"])
    taut = tau > 0
    assert [cables[k] + 1 for k in np.flatnonzero(taut)] == n["cables"]
    dist = np.linalg.norm(robot.base[cables] - B, axis=1)
    assert np.allclose(dist[taut], rho_pose[taut], atol=1e-9) and np.all(dist[~taut] <= rho_pose[~taut] + 1e-9)
    u = (robot.base[cables] - B) / dist[:, None]
    f = robot.load * robot.load_direction
    assert np.allclose((tau[:, None] * u).sum(0) + f, 0, atol=1e-8)
    assert np.allclose(np.cross(B - G, tau[:, None] * u).sum(0), 0, atol=1e-8)
    # the CLI: JSON names the method; the table never prints a plain "safe" / "yes" for an unproven result
    args = ["cc", ROBOT, "--position", *[repr(float(v)) for v in x], "--configuration", "3", "4", "5", "6", "7", "8",
            "--ball", "0.03"]
    assert main(args + ["--json"]) == 0
    (c,) = json.loads(capsys.readouterr().out)["configurations"]
    sc = c["second_criterion"]
    assert c["safe_nearby"] is None and sc["method"] == SEARCH and sc["proven"] is False
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "not proven" in text.splitlines()[3] and "(a floating-point search, not a proof" in text
    assert main(args[:-1] + ["2.5"]) == 0
    assert "no (verified)" in capsys.readouterr().out


def test_proven_safety_names_the_proof(robot, capsys):
    s = safety(robot, (1, 0, 2), [2, 3, 4, 5, 6, 7], radius=0.03)
    assert s.safe is True and s.method == PROOF and s.proven and s.status.startswith("proven safe")
    assert main(["cc", ROBOT, "--position", "1", "0", "2", "--configuration", "3", "4", "5", "6", "7", "8",
                 "--ball", "0.03", "--json"]) == 0
    (c,) = json.loads(capsys.readouterr().out)["configurations"]
    assert c["safe_nearby"] is True and c["second_criterion"]["method"] == PROOF
