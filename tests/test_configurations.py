"""Cable configurations (CC) and the first criterion of seed 002 (Merlet, 8-cable suspended robot).

Oracles: the valid CCs printed in Sec. IV-B.1 for poses (0, 1, 2) and (1, 0, 2); the radii and r_min printed in
the tables of Sec. IV-B.1 (to the printed digits, 1e-9 relative: the paper's last digits differ from a 40-digit
recomputation by up to 3e-9); the errata of the seeds README (CC [2,3,4,5,6,7] at (0,1,2): cable 4 gives
0.81475417241 and r_min = 0.76009994231, not the printed 0.547094056; the per-cable values of CC [1..6]).
Independent checks: statics residuals with plain numpy, the cubics against direct determinants, and the global
minimum against a brute-force ray search with the tensions themselves.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from cdpr_algebra import Robot, load_robot
from cdpr_algebra.cc.cubic_distances import ED_DEGREE, MONOMIALS, _generic, distance_to_cubics, evaluate_cubic
from cdpr_algebra.cc.radii import cc_polynomials, cc_radii, cc_radii_many
from cdpr_algebra.cc.configurations import configuration_tensions, valid_configurations
from cdpr_algebra.model.errors import CdprInputError

ROBOT = "examples/seed002_8cables.toml"

PRINTED_CC = {
    (0, 1, 2): [[1, 2, 3, 4, 5, 6], [1, 3, 4, 5, 6, 8], [2, 3, 4, 5, 6, 7], [3, 4, 5, 6, 7, 8]],
    (1, 0, 2): [[1, 2, 5, 6, 7, 8], [1, 4, 5, 6, 7, 8], [2, 3, 5, 6, 7, 8], [3, 4, 5, 6, 7, 8]],
}

# Sec. IV-B.1 tables, de-interleaved (seeds README): {cable: r, "d": singular}, r_min; erratum applied to
# [2,3,4,5,6,7] at (0,1,2) (printed 0.547094056 for cable 4 and r_min 0.547094056081)
PRINTED_RADII = {
    ((0, 1, 2), (1, 2, 3, 4, 5, 6)): ({1: 4.4946264798, "d": 2.9411453193, 2: 4.050982548, 3: 0.755452449,
                                       4: 0.789817071}, 0.755452449),
    ((0, 1, 2), (1, 3, 4, 5, 6, 8)): ({1: 4.494269494, "d": 2.9452771, 3: 0.759251662181, 6: 0.79751117,
                                       8: 4.0509825480}, 0.75925166218),
    ((0, 1, 2), (2, 3, 4, 5, 6, 7)): ({2: 4.0273984389, "d": 3.005642354, 4: 0.81475417241, 5: 0.7600999421,
                                       7: 4.4946264798}, 0.76009994231),
    ((0, 1, 2), (3, 4, 5, 6, 7, 8)): ({5: 0.759563273849, "d": 3.00951266946, 6: 0.780833856164,
                                       7: 4.4942694944, 8: 4.0273984389697}, 0.759563273849),
    ((1, 0, 2), (1, 2, 5, 6, 7, 8)): ({"d": 2.940956688, 6: 4.977861655, 7: 0.63930665576, 8: 0.607434554380417},
                                      0.60743455438),
    ((1, 0, 2), (1, 4, 5, 6, 7, 8)): ({"d": 2.9452947689, 6: 0.5191414561, 7: 0.6358634180}, 0.5191414561),
    ((1, 0, 2), (2, 3, 5, 6, 7, 8)): ({"d": 3.0087565393, 5: 0.5343214029, 6: 4.686335251, 8: 0.5699690786},
                                      0.53432140),
    ((1, 0, 2), (3, 4, 5, 6, 7, 8)): ({"d": 3.01281464529, 5: 0.5324771755, 6: 0.5606442268}, 0.5324771755),
}
RTOL = 1e-9


def printed_tol(v: float) -> float:
    """Tolerance for a printed number: 1e-9 relative, or half a unit of its last printed digit if coarser."""
    decimals = len(repr(float(v)).split(".")[1])
    return max(RTOL * abs(v), 0.5 * 10.0 ** -decimals)


@pytest.fixture(scope="module")
def robot():
    return load_robot(ROBOT)


@pytest.fixture(scope="module")
def table(robot):
    keys = list(PRINTED_RADII)
    res = cc_radii_many(robot, [(pos, [c - 1 for c in cc]) for pos, cc in keys], certify=True)
    return dict(zip(keys, res))


# ---------------------------------------------------------------------------------------------------- valid CCs


def _statics_residual(robot, position, cables, tensions):
    """Plain numpy: sum tau_i u_i + Q d and sum (B_i - G) x tau_i u_i (identity orientation, G = position)."""
    G = np.asarray(position, float)
    B = G + robot.platform[list(cables)] - robot.com
    s = robot.base[list(cables)] - B
    f = tensions[:, None] * s / np.linalg.norm(s, axis=1)[:, None]
    return np.concatenate([f.sum(0) + robot.load * robot.load_direction, np.cross(B - G, f).sum(0)])


@pytest.mark.parametrize("position", list(PRINTED_CC))
def test_valid_configurations_are_the_printed_ones(robot, position):
    ccs = valid_configurations(robot, position)
    assert sorted(c.numbers for c in ccs) == PRINTED_CC[position]
    for c in ccs:
        assert c.valid and np.all(c.tensions > 0)
        assert np.abs(_statics_residual(robot, position, c.cables, c.tensions)).max() < 1e-12
    # ranked: 6 cables first, then by largest tension
    assert [c.max_tension for c in ccs] == sorted(c.max_tension for c in ccs)


def test_invalid_configuration_has_a_negative_tension(robot):
    cc = configuration_tensions(robot, (0, 1, 2), [0, 1, 2, 3, 4, 6])  # [1,2,3,4,5,7] is not printed
    assert not cc.valid and cc.min_tension < 0
    assert np.abs(_statics_residual(robot, (0, 1, 2), cc.cables, cc.tensions)).max() < 1e-12


def test_fewer_than_six_cables_valid_only_where_consistent():
    """Two symmetric cables hold a platform whose centre of mass lies on their plane of symmetry: {1, 2} is a valid
    CC with equal tensions Q |A_i - B_i| / (2 * 5) (vertical balance), {1} alone is not; a third cable is slack."""
    r = Robot(base=[[-1, 0, 5], [1, 0, 5], [0, 3, 5]], platform=[[-0.1, 0, 0], [0.1, 0, 0], [0, 0.1, 0]],
              com=[0, 0, 0], load=2.0)
    ccs = valid_configurations(r, (0, 0, 0))
    two = [c for c in ccs if c.numbers == [1, 2]]
    assert len(two) == 1
    np.testing.assert_allclose(two[0].tensions, 2.0 * np.sqrt(0.9**2 + 25) / 10, rtol=1e-12)
    assert all(len(c.cables) >= 2 for c in ccs)
    assert not configuration_tensions(r, (0, 0, 0), [0]).valid


def test_valid_configurations_at_a_turned_pose_match_plain_numpy(robot):
    from cdpr_algebra.model.pose import matrix_from_angles

    R = matrix_from_angles(0.05, -0.03, 0.2)
    G = np.array([0.3, 0.4, 2.1])
    ccs = valid_configurations(robot, G, R, sizes=[6])
    B = G + (robot.platform - robot.com) @ R.T
    s = robot.base - B
    u = s / np.linalg.norm(s, axis=1)[:, None]
    J = np.vstack([u.T, np.cross(B - G, u).T])
    F = -robot.load * np.concatenate([robot.load_direction, np.zeros(3)])
    expected = [list(S) for S in itertools.combinations(range(8), 6) if np.all(np.linalg.solve(J[:, S], F) > 0)]
    assert sorted(list(c.cables) for c in ccs) == expected


# ------------------------------------------------------------------------------------------------------ radii


def test_cubics_equal_the_determinants(robot):
    """|M| and |M_i| are cubics in the position: the interpolated coefficients reproduce direct determinants at
    random points far from the interpolation grid; no coefficient of degree > 3."""
    pol = cc_polynomials(robot, (0, 1, 2), [0, 1, 2, 3, 4, 5])
    assert pol.truncation < 1e-10
    rng = np.random.default_rng(1)
    X = np.array([0, 1, 2]) + rng.uniform(-3, 3, size=(20, 3))
    B = X[:, None, :] + robot.platform[:6]
    s = robot.base[:6] - B
    M = np.concatenate([s, np.cross(robot.platform[:6], s)], axis=-1).swapaxes(-1, -2)
    Y = (X - np.array([0, 1, 2])) / pol.scale
    det = np.linalg.det(M)
    np.testing.assert_allclose(evaluate_cubic(pol.coefficients[0], Y), det, rtol=1e-9, atol=1e-9 * np.abs(det).max())
    Mi = M.copy()
    Mi[:, :, 2] = [0, 0, -1, 0, 0, 0]
    det3 = np.linalg.det(Mi)
    np.testing.assert_allclose(evaluate_cubic(pol.coefficients[3], Y), det3, rtol=1e-9,
                               atol=1e-9 * np.abs(det3).max())


def test_generic_cubic_has_21_critical_points():
    """The Euclidean distance degree of a general cubic surface is 3 (1 + 2 + 4) = 21."""
    assert ED_DEGREE == 21 and len(_generic(0).solutions) == 21
    # a random real cubic: every real critical point solves the Lagrange system, all paths finish
    rng = np.random.default_rng(7)
    c = rng.normal(size=len(MONOMIALS))
    (cd,) = distance_to_cubics(c[None])
    assert cd.failed == 0 and cd.finite == 21
    for y in cd.points:
        assert abs(evaluate_cubic(c, y)) < 1e-9 * np.abs(c).max() * (1 + np.abs(y).max()) ** 3


@pytest.mark.parametrize("key", list(PRINTED_RADII), ids=[f"{p}-{list(c)}" for p, c in PRINTED_RADII])
def test_seed002_radii_table(table, key):
    printed, rmin = PRINTED_RADII[key]
    res = table[key]
    got = res.radii_by_number()
    for k, v in printed.items():
        assert got["singular" if k == "d" else str(k)] == pytest.approx(v, abs=printed_tol(v)), k
    assert res.rmin == pytest.approx(rmin, abs=printed_tol(rmin))
    assert res.failed_paths == 0
    assert res.certified
    lo, hi = res.certificate["radius_enclosure"]
    assert lo <= res.rmin <= hi and hi - lo < 1e-9


def test_seed002_erratum_cable4_not_within_0547(robot, table):
    """Seeds README erratum: on the sphere of radius 0.547 around (0,1,2) tau_4 of CC [2,3,4,5,6,7] keeps its sign
    (so the printed 0.547094056 is not a radius); every tension is positive inside the ball of radius r_min."""
    res = table[((0, 1, 2), (2, 3, 4, 5, 6, 7))]
    assert res.radii[3] == pytest.approx(0.81475417241, rel=RTOL)
    rng = np.random.default_rng(3)
    u = rng.normal(size=(4000, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    for radius in (0.547094056, 0.999 * res.rmin):
        for G in np.array([0, 1, 2]) + radius * u[:1000]:
            assert configuration_tensions(robot, G, res.cables).valid


def _ray_radius(robot, x0, cables, u, rmax=8.0, step=0.02):
    """First r along the ray x0 + r u where a tension of the CC stops being > 0 (or |M| changes sign), by a scan
    of the tensions from np.linalg.solve and bisection: an independent upper bound of r_min for each ray."""
    def ok(r):
        return configuration_tensions(robot, x0 + r * u, cables).valid
    r = step
    while r < rmax and ok(r):
        r += step
    if r >= rmax:
        return np.inf
    lo, hi = r - step, r
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return hi


def test_rmin_is_the_global_minimum_by_ray_search(robot, table):
    """Along rays towards (and around) the reported nearest point, no ray leaves the validity region before r_min,
    and the ray through the nearest point leaves it at r_min."""
    res = table[((1, 0, 2), (3, 4, 5, 6, 7, 8))]
    x0 = np.array([1.0, 0, 2])
    u0 = (res.nearest - x0) / res.rmin
    assert _ray_radius(robot, x0, res.cables, u0) == pytest.approx(res.rmin, rel=1e-7)
    rng = np.random.default_rng(5)
    U = rng.normal(size=(150, 3))
    U = np.vstack([U / np.linalg.norm(U, axis=1)[:, None], u0 + 0.05 * rng.normal(size=(50, 3))])
    U /= np.linalg.norm(U, axis=1)[:, None]
    rays = np.array([_ray_radius(robot, x0, res.cables, u, step=0.05) for u in U])
    assert rays.min() >= res.rmin * (1 - 1e-9)
    assert rays.min() <= res.rmin * 1.01  # near-misses around the nearest direction


def test_cc_radii_input_errors(robot):
    with pytest.raises(CdprInputError, match="configuration"):
        cc_radii(robot, (0, 1, 2), [1, 2, 3, 4, 5])
    with pytest.raises(CdprInputError, match="1..8"):
        cc_radii(robot, (0, 1, 2), [1, 2, 3, 4, 5, 9])
    with pytest.raises(CdprInputError, match="distinct"):
        cc_radii(robot, (0, 1, 2), [1, 2, 3, 4, 5, 5])
    with pytest.raises(CdprInputError, match="position"):
        cc_radii(robot, (0, np.nan, 2), [1, 2, 3, 4, 5, 6])


def test_radii_at_a_turned_pose(robot):
    """Constant orientation R != I: the nearest point of the limiting surface is where the CC stops being valid
    along the ray from the pose (tensions from np.linalg.solve at the turned platform)."""
    from cdpr_algebra.model.pose import matrix_from_angles

    R = matrix_from_angles(0.03, -0.02, 0.1)
    G = np.array([0.2, 0.8, 2.0])
    (cc,) = [c for c in valid_configurations(robot, G, R, sizes=[6])][:1]
    (res,) = cc_radii_many(robot, [(G, cc.cables, R)], certify=True)
    assert res.failed_paths == 0 and res.certified
    u = (res.nearest - G) / res.rmin

    def valid(r):
        return configuration_tensions(robot, G + r * u, cc.cables, R).valid

    assert valid(res.rmin * (1 - 1e-6)) and not valid(res.rmin * (1 + 1e-6))
