"""Issue 15: taut sets whose equilibria form continuous families are named and their real families listed, not left
as unexplained uncertified endpoints, when the 6-DOF homotopy tracks them (``rods=False`` here: the DGP solves
exactly collinear taut sets of 2-5 cables as a rod, tests/test_dgp_rod.py; this route remains for data collinear
only up to rounding, m = 6, and as that test's cross-check).  Robot: ``examples/symmetric_4cables.toml`` with its
centre of mass moved into the platform's plane, at the platform's centre (a flat plate with its attachment points at
the corners): with the cables on a diagonal taut, B1, B3 and G are collinear and the platform turns freely about
that line.

Independent check of the verdict: the endpoints, turned about the line through B1 and B3 by any (complex) angle,
still solve the taut equations, tensions unchanged (the family the test reports is there), and the same taut set
of the shipped robot (G 0.2 m below the plate) is complete with no family.  Of the listed families: the taut
equations at poses turned across each feasible arc, the slack cables' lengths (a cable exactly at its length at an
end of an arc, shorter inside), and the stability classes against the potential energy (the height of G): of the
two real families of {1, 3} with positive tensions, the lower hangs neutrally stable ('>=', the turn a null
direction of H_r), the higher is a saddle.
"""

import json
from dataclasses import replace
from pathlib import Path

import numpy as np

from cdpr_algebra.dgp.solve import (DGPResult, _solve_taut_set, _with_endpoint_certificates, dgp_table, incompleteness,
                                     summary_line)
from cdpr_algebra.model.robot import Robot, load_robot
from cdpr_algebra.model.taut_equations import decode, encode

ROOT = Path(__file__).resolve().parents[1]


def _turned(p, R, axis_point, axis, theta):
    """The pose turned by the complex angle theta about the world line through axis_point along the unit axis."""
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    Q = np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K  # Rodrigues, valid for complex theta
    return axis_point + Q @ (p - axis_point), Q @ R


def _poses_across_arcs(robot, cables, f, k):
    """(theta, (lo, hi), p, R, x) at k turning angles across each arc (lo, hi) of the listed family f, x the taut
    root (p, u, v, w, lam) there."""
    lam = f.tensions[list(cables)] / np.asarray(robot.lengths)[list(cables)]
    B = f.position + f.rotation @ robot.platform[cables[0]]
    for lo, hi in f.arcs:
        for theta in np.linspace(lo, hi, k):
            p, R = _turned(f.position, f.rotation, B, f.axis, theta)
            yield theta, (lo, hi), p, R, encode(p, R, lam)


def _residual(robot, cables, x):
    """max |equation| of the taut set's statics at x = (p, u, v, w, lam) (complex allowed), in plain numpy: lengths
    |B_i - A_i|^2 = rho_i^2, force sum lam_i (A_i - B_i) + Q d = 0, moment about G sum (B_i - G) x lam_i (A_i - B_i),
    rotation R^T R = I."""
    idx = list(cables)
    p, R, lam = x[:3], np.column_stack([x[3:6], x[6:9], x[9:12]]), x[12:]
    B = p + robot.platform[idx] @ R.T
    G = p + R @ robot.com
    A = robot.base[idx]
    forces = lam[:, None] * (A - B)
    rho = np.asarray(robot.lengths)[idx]
    eqs = [np.sum((B - A) ** 2, axis=1) - rho ** 2, forces.sum(axis=0) + robot.load * robot.load_direction,
           np.cross(B - G, forces).sum(axis=0), (R.T @ R - np.eye(3)).ravel()]
    return max(np.max(np.abs(e)) for e in eqs)


def test_a_taut_set_with_a_family_of_equilibria_is_named():
    shipped = load_robot(ROOT / "examples" / "symmetric_4cables.toml")
    flat = replace(shipped, com=np.zeros(3))
    cables = (0, 2)
    sub, _, Z = _solve_taut_set(flat, flat.lengths, cables, rods=False)
    (sub,) = _with_endpoint_certificates(flat, flat.lengths, [(cables, sub, Z)])
    assert not sub.complete and sub.certified == 0
    fam = sub.family
    assert fam is not None and fam.endpoints == sub.outcomes["regular"] == len(Z) > 0
    assert fam.dimensions == (1,) and fam.undecided == 0
    assert fam.fixed == ("B1", "B3", "G") and fam.turns and not fam.tensions_change
    assert "positive-dimensional" in incompleteness(sub) and "B1, B3, G" in incompleteness(sub)
    assert sub.to_dict()["positive_dimensional"]["fixed_points"] == ["B1", "B3", "G"]
    # the family is there: every endpoint turned about B1 B3 still solves the equations
    for x in Z[:6]:
        p, R, lam = (a[0] for a in decode(x[None], 2))
        B1, B3 = p + R @ flat.platform[0], p + R @ flat.platform[2]
        axis = (B3 - B1) / np.sqrt((B3 - B1) @ (B3 - B1))
        scale = 1 + np.max(np.abs(x))
        assert _residual(flat, cables, x) <= 1e-9 * scale ** 2
        for theta in (0.3, -1.1 + 0.4j):
            p2, R2 = _turned(p, R, B1, axis, theta)
            x2 = encode(p2, R2, lam)
            assert np.max(np.abs(x2 - x)) > 1e-3  # a different point of the set ...
            assert _residual(flat, cables, x2) <= 1e-9 * scale ** 2  # ... on it


def test_the_same_taut_set_of_a_generic_platform_has_no_family():
    shipped = load_robot(ROOT / "examples" / "symmetric_4cables.toml")
    cables = (0, 2)
    sub, _, Z = _solve_taut_set(shipped, shipped.lengths, cables)
    (sub,) = _with_endpoint_certificates(shipped, shipped.lengths, [(cables, sub, Z)])
    assert sub.complete and sub.family is None and sub.to_dict()["positive_dimensional"] is None


def test_the_real_families_are_listed_with_their_feasible_arcs():
    flat = replace(load_robot(ROOT / "examples" / "symmetric_4cables.toml"), com=np.zeros(3))
    rho = np.asarray(flat.lengths)
    for cables, slack in (((0, 2), (1, 3)), ((1, 3), (0, 2))):
        sub, _, Z = _solve_taut_set(flat, rho, cables, rods=False)
        (sub,) = _with_endpoint_certificates(flat, rho, [(cables, sub, Z)])
        fam = sub.family
        # 12 families, each holding two endpoints (module doc of dgp.positive_dimensional)
        assert len(fam.groups) == 12 and set(fam.groups) == {2} and fam.real == 2
        assert 1 <= len(fam.members) <= fam.real
        for f in fam.members:
            assert f.taut == tuple(c + 1 for c in cables) and np.all(f.tensions[list(cables)] > 0)
            assert np.all(f.tensions[list(slack)] == 0)
            for theta, (lo, hi), p, R, x in _poses_across_arcs(flat, cables, f, 5):
                assert _residual(flat, cables, x) <= 1e-10
                d = np.linalg.norm(p + flat.platform[list(slack)] @ R.T - flat.base[list(slack)], axis=1)
                assert np.all(d <= rho[list(slack)] * (1 + 1e-8))
                if lo < theta < hi:
                    continue
                if hi - lo < 2 * np.pi - 1e-9:  # an end of an arc: some slack cable exactly at its length
                    assert np.min(np.abs(d - rho[list(slack)])) <= 1e-8
        assert "family of equilibria" in fam.members[0].describe(fam.fixed)
    # the stable one hangs: of the two real families of {1, 3} with positive tensions, the lower one
    sub, _, Z = _solve_taut_set(flat, rho, (0, 2), rods=False)
    (sub,) = _with_endpoint_certificates(flat, rho, [((0, 2), sub, Z)])
    low, high = sorted(sub.family.members, key=lambda f: f.position[2])
    assert low.hessian == ">=" and high.hessian == "<>"
    # the table lists them under the (empty) table of isolated equilibria, and the summary counts them
    result = DGPResult((), (sub,), 0.0, 0, None)
    text = dgp_table(result, flat.n)
    assert text.count("a family of equilibria turning about the line through B1, B3, G") == 2
    assert "2 admissible families of equilibria (not isolated; 2 of their listed poses certified)" in summary_line(result)
    assert not result.complete
    out = json.loads(json.dumps(result.to_dict()))
    members = out["subproblems"][0]["positive_dimensional"]["members"]
    assert out["families"] == members and result.families == sub.family.members
    assert [m["certified"] for m in members] == [True, True]  # the certificates: the next test


def test_the_pose_of_a_turning_family_is_certified_only_for_exactly_collinear_data():
    from cdpr_algebra.certificates.families import certify_turning_equilibrium, collinear_exactly

    flat = replace(load_robot(ROOT / "examples" / "symmetric_4cables.toml"), com=np.zeros(3))
    rho = np.asarray(flat.lengths)
    sub, _, Z = _solve_taut_set(flat, rho, (0, 2), rods=False)
    (sub,) = _with_endpoint_certificates(flat, rho, [((0, 2), sub, Z)])
    for f in sub.family.members:
        cert = f.certificate
        assert f.certified and cert.exists_unique and cert.hessian == "undecided"
        assert cert.tension_signs == ("positive", "slack", "positive", "slack") and cert.slack_proven
        # the proven root is the listed pose to the rounding of its rebuilding (residual ~1e-13)
        assert np.all(cert.position_lower - 1e-9 <= f.position) and np.all(f.position <= cert.position_upper + 1e-9)
        assert np.all(cert.tension_lower[[0, 2]] - 1e-9 <= f.tensions[[0, 2]])
        assert np.all(f.tensions[[0, 2]] <= cert.tension_upper[[0, 2]] + 1e-9)
        assert "certified" in f.describe(sub.family.fixed) and f.to_dict()["certificate"]["certified"]
        # a pose off the family by 1e-4 m is no root: no certificate
        wrong = certify_turning_equilibrium(flat, rho, (0, 2), f.position + 1e-4, f.rotation, f.tensions[[0, 2]])
        assert not wrong.certified and not wrong.exists_unique
    # a centre of mass at 0.4 of the diagonal is collinear on paper, not once 0.1 and 0.06 are rounded to doubles
    b1, b3 = flat.platform[0], flat.platform[2]
    assert collinear_exactly([b1, b3, np.zeros(3)])
    assert not collinear_exactly([b1, b3, np.array([0.1, 0.06, 0.0])])
    off = replace(flat, com=np.array([0.1, 0.06, 0.0]))
    f = sub.family.members[0]
    cert = certify_turning_equilibrium(off, rho, (0, 2), f.position, f.rotation, f.tensions[[0, 2]])
    assert not cert.certified and "not exactly collinear" in cert.reason


def test_a_beam_hung_from_four_cables_has_turning_families():
    """``examples/beam_4cables.toml``: every anchor on one line with G; the four-cable set's real families."""
    from cdpr_algebra.comparison.settle import FAMILY_NOT_SEARCHED, settle_incomplete

    beam = load_robot(ROOT / "examples" / "beam_4cables.toml")
    cables = (0, 1, 2, 3)
    sub, _, Z = _solve_taut_set(beam, beam.lengths, cables, rods=False)
    (sub,) = _with_endpoint_certificates(beam, beam.lengths, [(cables, sub, Z)])
    fam = sub.family
    assert fam is not None and fam.endpoints == sub.outcomes["regular"] and fam.undecided == 0
    assert fam.fixed == ("B1", "B2", "B3", "B4", "G") and set(fam.groups) == {2}
    assert "not certified (" not in incompleteness(sub)  # the family accounts for every refused endpoint
    assert len(fam.members) == 2 and all(f.certified for f in fam.members)
    for f in fam.members:
        lam = f.tensions / np.asarray(beam.lengths)
        for theta in (0.0, 1.0, 2.5):  # all around the beam (full arcs: four taut cables, none slack)
            B1 = f.position + f.rotation @ beam.platform[0]
            p, R = _turned(f.position, f.rotation, B1, f.axis, theta)
            assert _residual(beam, cables, encode(p, R, lam)) <= 1e-10
    low = min(fam.members, key=lambda f: (f.position + f.rotation @ beam.com)[2])
    assert low.hessian == ">="  # the lower centre of mass hangs (neutral along the turn)
    # --settle does not search it: a continuum of solutions leaves every box around it undecided
    settled, records = settle_incomplete(beam, DGPResult((), (sub,), 0.0, 0, None))
    assert [r.outcome for r in records] == ["undecided"] and records[0].detail == FAMILY_NOT_SEARCHED


def random_rod(seed):
    """A random 3-cable robot whose anchors and centre of mass lie on the platform's x axis (exactly collinear in
    doubles), hung about 4.5 m below its base's centroid."""
    rng = np.random.default_rng(seed)
    base = rng.uniform(-4, 4, (3, 3)) + np.array([0, 0, 6])
    s = np.sort(rng.uniform(-0.6, 0.6, 3))
    platform = np.array([[v, 0.0, 0.0] for v in s])
    com = np.array([rng.uniform(s[0], s[-1]), 0.0, 0.0])
    lengths = np.linalg.norm(base - (base.mean(0) - [0, 0, 4.5]), axis=1) + rng.uniform(-0.3, 0.3, 3)
    return Robot(base=base, platform=platform, com=com, load=1.0, load_direction=[0, 0, -1], lengths=lengths)


def test_random_rods_have_turning_families_of_two_cables():
    """Random 3-cable robots whose anchors and G lie on one line of the platform (the platform's x axis, so exactly
    collinear in doubles): every 2-cable set is a family; each endpoint group holds 2 endpoints, and every listed
    family's pose solves the statics (plain numpy) at turning angles across its arcs and is certified."""
    listed, tracked = 0, 0
    for seed in (11, 12):
        rod = random_rod(seed)
        lengths = np.asarray(rod.lengths)
        for cables in ((0, 1), (0, 2), (1, 2)):
            # tracked even with no admissible equilibrium
            sub, _, Z = _solve_taut_set(rod, lengths, cables, exclude=False, rods=False)
            if sub.skipped:  # pruned: the distance conditions prove the set empty
                assert "cannot" in sub.skipped and sub.complete
                continue
            tracked += 1
            (sub,) = _with_endpoint_certificates(rod, lengths, [(cables, sub, Z)])
            fam = sub.family
            assert fam is not None and fam.endpoints == sub.outcomes["regular"] and set(fam.groups) == {2}
            assert {f"B{c + 1}" for c in cables} | {"G"} <= set(fam.fixed) and not fam.tensions_change
            for f in fam.members:
                listed += 1
                assert f.certified
                for *_, x in _poses_across_arcs(rod, cables, f, 3):
                    assert _residual(rod, cables, x) <= 1e-10
    assert listed >= 2 and tracked >= 4
