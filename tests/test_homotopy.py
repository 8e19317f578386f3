"""Homotopy continuation engine (issue #3): known root counts, endgame classes, parameter
homotopies, monodromy, stored instances, determinism."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from cdpr_algebra.homotopy import (ParameterHomotopy, PolynomialSystem, SolveOptions, TrackerOptions,
                                   multi_homogeneous, multi_homogeneous_bezout_number, solve,
                                   solve_parameter_homotopy, track_paths, track_segment)
from cdpr_algebra.homotopy.endgame import mp_track
from cdpr_algebra.dgp.anchor_points import dgp3_family, dgp3_parameters, dgp3_poses
from cdpr_algebra.homotopy.families import cyclic, katsura, stewart_gough
from cdpr_algebra.homotopy.monodromy import (MonodromyOptions, load_instance, monodromy_solve, save_instance)
from cdpr_algebra.homotopy.start_systems import random_gamma, total_degree
from cdpr_algebra.model.robot import load_robot

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "cdpr_algebra" / "data" / "dgp3_generic.json"
FAST = SolveOptions(tracker=TrackerOptions(predictor_tol=1e-4))
NO_MP = SolveOptions(tracker=TrackerOptions(predictor_tol=1e-4), retry_mpmath=False)


@pytest.fixture(scope="module")
def dgp():
    S = dgp3_family()
    p1, X1, _ = load_instance(DATA, S)
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    return S, p1, X1, robot


def test_compiled_evaluators_match_sympy():
    x, y = sp.symbols("x y")
    a, b = sp.symbols("a b")
    S = PolynomialSystem([x**3 * y + a * x - 2, b * x * y**2 - sp.Rational(1, 3) + sp.I * a * b], [x, y], [a, b])
    rng = np.random.default_rng(0)
    X = rng.normal(size=(5, 2)) + 1j * rng.normal(size=(5, 2))
    P = rng.normal(size=(5, 2)) + 1j * rng.normal(size=(5, 2))
    F, J, JP = S.evaluate_all(X, P)
    M = sp.Matrix(S.equations)
    for k in range(5):
        sub = {x: X[k, 0], y: X[k, 1], a: P[k, 0], b: P[k, 1]}
        np.testing.assert_allclose(F[k], np.array(M.subs(sub).evalf(), dtype=complex).ravel(), rtol=1e-12)
        np.testing.assert_allclose(J[k], np.array(M.jacobian([x, y]).subs(sub).evalf(), dtype=complex), rtol=1e-12)
        np.testing.assert_allclose(JP[k], np.array(M.jacobian([a, b]).subs(sub).evalf(), dtype=complex), rtol=1e-12)
    # same parameters for all points, and the F-only evaluator
    np.testing.assert_allclose(S.evaluate(X, P[0]), S.evaluate_all(X, np.tile(P[0], (5, 1)))[0])
    with pytest.raises(ValueError):
        PolynomialSystem([x + a], [x])  # a is neither unknown nor parameter


@pytest.mark.parametrize("n", [3, 4, 5])
def test_katsura_root_count(n):
    r = solve(katsura(n), seed=1)
    s = r.summary()
    assert s.paths == 2**n
    assert len(r.nonsingular) == 2**n and s.success == 2**n
    assert s.failed == 0 and s.singular == 0 and s.at_infinity == 0
    assert max(p.residual for p in r.track.paths) < 1e-12


def test_cyclic5_70_roots_50_at_infinity():
    r = solve(cyclic(5), seed=3)
    s = r.summary()
    assert s.paths == 120
    assert len(r.nonsingular) == 70
    assert s.failed == 0
    assert s.at_infinity + s.singular == 50


def test_stewart_gough_40_solutions():
    """General 6-6 platform in Study coordinates: 128 paths, 40 nonsingular (the generic count)."""
    r = solve(stewart_gough(7), seed=3)
    s = r.summary()
    assert s.paths == 128
    assert len(r.nonsingular) == 40
    assert s.failed == 0
    X = r.solution_array()
    assert np.all(np.abs(np.sum(X[:, :4] ** 2, axis=1)) > 1e-8)  # off the exceptional quadric e.e = 0
    # the real pose the leg lengths came from is among them: real up to the complex patch scaling
    Y = X / X[:, :1]
    assert np.any(np.max(np.abs(Y.imag), axis=1) < 1e-6)


def test_solutions_at_infinity():
    x, y = sp.symbols("x y")
    r = solve(PolynomialSystem([x * y - 2, x * y + x + y - 5], [x, y]), seed=0)
    s = r.summary()
    assert (s.paths, s.success, s.at_infinity, s.failed) == (4, 2, 2, 0)
    got = sorted(tuple(np.round(v.x.real, 10)) for v in r.solutions)
    assert got == [(1.0, 2.0), (2.0, 1.0)]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_double_root_is_singular_with_multiplicity_2(seed):
    x, y = sp.symbols("x y")
    # circle and its tangent at (1.3, 0.8): one double root
    S = PolynomialSystem([(x - 0.3) ** 2 + (y + 0.2) ** 2 - 2, (x - 1.3) + (y - 0.8)], [x, y])
    r = solve(S, seed=seed)
    assert r.summary().singular == 2 and r.summary().failed == 0
    assert len(r.solutions) == 1
    sol = r.solutions[0]
    assert sol.singular and sol.multiplicity == 2
    np.testing.assert_allclose(sol.x, [1.3, 0.8], atol=1e-6)


def test_triple_root_winding_number_3():
    x, y = sp.symbols("x y")
    r = solve(PolynomialSystem([y - x**3, y], [x, y]), seed=0)
    assert [p.winding_number for p in r.track.paths] == [3, 3, 3]
    assert len(r.solutions) == 1 and r.solutions[0].multiplicity == 3
    np.testing.assert_allclose(r.solutions[0].x, [0, 0], atol=1e-8)


def test_multi_homogeneous_start_system():
    """Generalized eigenproblem (A - l B) v = 0, c.v = 1: 2-homogeneous Bezout number 2 < total degree 4."""
    l, v1, v2 = sp.symbols("l v1 v2")
    A = sp.Matrix([[2, 1], [1, 3]])
    B = sp.Matrix([[1, 0], [0, 2]])
    eqs = list((A - l * B) * sp.Matrix([v1, v2])) + [v1 + 2 * v2 - 1]
    S = PolynomialSystem(eqs, [l, v1, v2])
    groups = [[l], [v1, v2]]
    assert multi_homogeneous_bezout_number(S, groups) == 2
    st = multi_homogeneous(S, groups, seed=0)
    assert len(st.solutions) == 2
    np.testing.assert_allclose(st.system.evaluate(st.solutions), 0, atol=1e-12)
    r = solve(S, groups=groups, seed=0)
    assert r.summary().paths == 2 and len(r.nonsingular) == 2
    ev = sorted(float(s.x[0].real) for s in r.solutions)
    np.testing.assert_allclose(ev, sorted(np.linalg.eigvals(np.linalg.solve(np.array(B, float), np.array(A, float))).real))


def test_determinism_same_seed_same_result():
    S = katsura(4)
    r1, r2 = solve(S, seed=5), solve(S, seed=5)
    assert r1.track.statuses() == r2.track.statuses()
    assert [p.steps for p in r1.track.paths] == [p.steps for p in r2.track.paths]
    np.testing.assert_array_equal(r1.track.endpoints(None), r2.track.endpoints(None))
    assert r1.summary().seed == 5
    r3 = solve(S, seed=6)
    assert len(r3.nonsingular) == 16


def test_results_records_and_summary_line():
    r = solve(katsura(3), seed=0)
    line = r.summary_line()
    for word in ("solutions", "real", "singular", "at infinity", "failed", "paths tracked", "seed 0"):
        assert word in line
    d = r.to_dict()
    json.dumps(d)
    p = d["track"]["paths"][0]
    for key in ("status", "endpoint", "residual", "condition", "accuracy", "steps"):
        assert key in p
    assert set(d["summary"]) >= {"paths", "success", "real", "singular", "at_infinity", "failed", "seconds", "seed"}
    with pytest.raises(Exception):
        r.track.paths[0].endpoint[0] = 1  # immutable


def test_mpmath_tracker_agrees_with_double_precision():
    S = katsura(2)
    st = total_degree(S)
    H = st.homotopy(S, random_gamma(np.random.default_rng(0)))
    seg = track_segment(H, st.solutions[:1], 1.0, 0.1)
    xm, status, steps = mp_track(H, st.solutions[0], 1.0, 0.1, dps=30)
    assert status == "success" and steps > 0
    np.testing.assert_allclose(xm, seg.x[0], rtol=1e-7)


def test_failed_paths_are_retried():
    """Paths that fail the first attempt (tiny step budget) are retried with tighter settings."""
    from dataclasses import replace as dc_replace
    from cdpr_algebra.homotopy.endgame import _track_to_endgame

    S = katsura(3)
    st = total_degree(S)
    H = st.homotopy(S, random_gamma(np.random.default_rng(0)))
    tr = TrackerOptions(max_steps=6)
    opts = SolveOptions(tracker=tr, retry_mpmath=False)
    idx = np.arange(len(st.solutions))
    x, status, steps, retried, h, _ = _track_to_endgame(H, st.solutions, idx, opts, 0.1, dc_replace(tr, max_steps=6))
    assert (retried == "tight").any()
    # the last step length is handed on to phase 2 only for paths tracked in one go
    assert np.all(np.isnan(h[retried == "tight"])) and np.all(h[retried == ""] > 0)
    # the retry used the tightened options (4x the step budget) and succeeded where it could
    assert all(s == "success" or r == "tight" for s, r in zip(status, retried))
    r = solve(S, seed=0, options=SolveOptions(tracker=TrackerOptions(max_steps=40), retry_mpmath=False))
    assert len(r.nonsingular) == 8 and r.summary().failed == 0


def test_dgp_parameter_homotopy_table1(dgp):
    S, p1, X1, robot = dgp
    assert len(X1) == 156
    r = solve_parameter_homotopy(S, p1, X1, dgp3_parameters(robot), seed=0, options=FAST)
    s = r.summary()
    assert (s.paths, len(r.nonsingular), s.failed) == (156, 156, 0)
    real = np.array([v.x for v in r.solutions if v.is_real(1e-8)]).real
    assert len(real) == 10
    adm = real[np.all(real[:, 9:] >= 0, axis=1)]
    poses = dgp3_poses(robot, adm)
    rows = json.loads((ROOT / "tests/data/seed000_tables.json").read_text())["tables"]["1"]["rows"]
    assert len(poses) == len(rows) == 6
    for row in rows:
        d = min(np.max(np.abs(p["position"] - np.array(row["position"]))) for p in poses)
        assert d <= 5e-3, row  # printed to 3 decimals, platform data rounded
        k = int(np.argmin([np.max(np.abs(p["position"] - np.array(row["position"]))) for p in poses]))
        np.testing.assert_allclose(poses[k]["tensions"], row["tensions"], atol=3e-3)


def test_parameter_homotopy_20_random_points_generic_count(dgp):
    """20 random real robots around seed 000 Test 1 (each parameter moved by 5 % of its scale): always
    156 nonsingular solutions, 0 failed (failed or coinciding paths are re-tracked in projective coordinates
    along the same parameter path; the mpmath retry is off here because it takes minutes per 12-unknown path)."""
    S, p1, X1, robot = dgp
    base = dgp3_parameters(robot)
    rng = np.random.default_rng(12)
    for k in range(20):
        p0 = base + 0.05 * (1 + np.abs(base)) * rng.normal(size=base.size)
        r = solve_parameter_homotopy(S, p1, X1, p0, seed=k, options=NO_MP)
        s = r.summary()
        assert (len(r.nonsingular), s.failed, s.singular) == (156, 0, 0), (k, r.summary_line())


def test_parameter_homotopy_variants_agree():
    """Straight segment, random complex detour and gamma-trick variants give the same solution set."""
    x, y, a, b = sp.symbols("x y a b")
    S = PolynomialSystem([x**2 + a * y - 1, y**2 + b * x * y - 2], [x, y], [a, b])
    p1 = np.array([0.3 + 0.7j, -0.2 + 0.4j])
    r0 = solve(S.substitute_parameters(p1), seed=0)
    X1 = r0.solution_array()
    assert len(X1) == 4
    p0 = np.array([1.5, -0.5])
    sets = []
    for kw in ({}, {"detour": True}, {"gamma": True}):
        r = solve_parameter_homotopy(S, p1, X1, p0, seed=1, **kw)
        assert len(r.nonsingular) == 4 and r.summary().failed == 0
        sets.append(np.array(sorted(r.solution_array().tolist(), key=lambda v: (round(v[0].real, 6), round(v[0].imag, 6)))))
    np.testing.assert_allclose(sets[0], sets[1], atol=1e-10)
    np.testing.assert_allclose(sets[0], sets[2], atol=1e-10)


def test_parameter_homotopy_arbitrary_precision_round(monkeypatch):
    """Paths that every double-precision attempt fails (forced here: every segment from t = 1 reports a failed
    step) are tracked in arbitrary precision last, along the same parameter path: the solutions are the ones
    of an ordinary run; without ``retry_mpmath`` they stay failed, and ``max_mpmath_paths`` bounds the round."""
    import cdpr_algebra.homotopy.endgame as eg
    from cdpr_algebra.homotopy.results import STEP_TOO_SMALL

    x, y, a, b = sp.symbols("x y a b")
    S = PolynomialSystem([x**2 + a * y - 1, y**2 + b * x * y - 2], [x, y], [a, b])
    p1 = np.array([0.3 + 0.7j, -0.2 + 0.4j])
    X1 = solve(S.substitute_parameters(p1), seed=0).solution_array()
    p0 = np.array([1.5, -0.5])
    ref = solve_parameter_homotopy(S, p1, X1, p0, seed=1, options=NO_MP)
    assert len(ref.nonsingular) == 4

    real_segment = eg.track_segment

    def failing(homotopy, x0, t_a, t_b, options=None, h0=None):
        r = real_segment(homotopy, x0, t_a, t_b, options, h0)
        if np.all(np.asarray(t_a) == 1.0):  # phase 1 (and every retry of it) fails
            r = replace(r, status=np.full(len(r.status), STEP_TOO_SMALL, dtype=object))
        return r

    monkeypatch.setattr(eg, "track_segment", failing)
    off = solve_parameter_homotopy(S, p1, X1, p0, seed=1, options=NO_MP)
    assert off.summary().failed == 4 and not off.nonsingular
    some = solve_parameter_homotopy(S, p1, X1, p0, seed=1, options=replace(FAST, max_mpmath_paths=2))
    assert some.summary().failed == 2 and len(some.nonsingular) == 2
    on = solve_parameter_homotopy(S, p1, X1, p0, seed=1, options=FAST)
    assert on.summary().failed == 0 and [p.retried for p in on.track.paths] == ["mpmath"] * 4
    key = lambda v: (round(v[0].real, 6), round(v[0].imag, 6))  # noqa: E731
    np.testing.assert_allclose(sorted(on.solution_array().tolist(), key=key),
                               sorted(ref.solution_array().tolist(), key=key), atol=1e-10)


def _dense_quadric_family(n=3):
    xs = sp.symbols(f"x0:{n}")
    mons = [sp.Integer(1)] + list(xs) + [xs[i] * xs[j] for i in range(n) for j in range(i, n)]
    ps = []
    eqs = []
    for i in range(n):
        cs = sp.symbols(f"c{i}_0:{len(mons)}")
        ps += cs
        eqs.append(sum(c * m for c, m in zip(cs, mons)))
    return PolynomialSystem(eqs, xs, ps, name="dense_quadrics")


def test_monodromy_recovers_generic_count():
    S = _dense_quadric_family(3)  # 3 generic quadrics in 3 unknowns: 8 solutions
    r = monodromy_solve(S, seed=2)
    assert len(r.solutions) == 8 and r.stopped_by == "no_progress"
    np.testing.assert_allclose(S.evaluate(r.solutions, r.parameters), 0, atol=1e-9)
    r2 = monodromy_solve(S, seed=3, options=MonodromyOptions(target_solutions_count=8))
    assert len(r2.solutions) == 8 and r2.stopped_by == "target"


def test_save_and_load_instance(tmp_path):
    S = _dense_quadric_family(2)
    r = monodromy_solve(S, seed=0, options=MonodromyOptions(target_solutions_count=4))
    f = tmp_path / "inst.json"
    save_instance(f, S, r.parameters, r.solutions, note="test")
    p, X, data = load_instance(f, S)
    np.testing.assert_array_equal(p, r.parameters)
    np.testing.assert_array_equal(X, r.solutions)
    assert data["format_version"] == 1 and data["meta"]["note"] == "test"
    with pytest.raises(ValueError, match="another system"):
        load_instance(f, _dense_quadric_family(3))
    data["format_version"] = 99
    f.write_text(json.dumps(data))
    with pytest.raises(ValueError, match="format version"):
        load_instance(f)


def test_stored_dgp_instance_matches_family(dgp):
    S, p1, X1, _ = dgp
    assert np.max(np.abs(S.evaluate(X1, p1))) < 1e-8
    assert np.iscomplexobj(p1) and np.max(np.abs(p1.imag)) > 0.01  # a generic complex instance
    assert len({tuple(np.round(x, 6)) for x in X1}) == 156



def test_numeric_homogenization_of_quadratic_systems_equals_the_symbolic_one():
    """HomogenizedQuadratic (y0^2 F(y/y0) from F at y, -y, 0) against the sympy-built homogenized system, at
    random complex points (y0 = 0 included) and parameters, for the DGP families with 2 and 4 taut cables."""
    from cdpr_algebra.dgp.solve import fast_family
    from cdpr_algebra.homotopy.projective import HomogenizedQuadratic, projectivize

    rng = np.random.default_rng(3)
    for m in (2, 4):
        fast = fast_family(m)
        sym, c = projectivize(fast.family)
        num, c2 = projectivize(fast)
        assert isinstance(num, HomogenizedQuadratic) and np.array_equal(c, c2)
        Y = rng.normal(size=(5, fast.n + 1)) + 1j * rng.normal(size=(5, fast.n + 1))
        Y[0, 0] = 0
        P = rng.normal(size=(5, fast.m)) + 1j * rng.normal(size=(5, fast.m))
        for a, b in zip(sym.evaluate_all(Y, P), num.evaluate_all(Y, P)):
            assert np.max(np.abs(a - b)) <= 1e-12 * (1 + np.max(np.abs(a)))


def test_directional_parameter_derivatives_equal_the_full_parameter_jacobian():
    """evaluate_directional (central differences, exact for equations quadratic in the parameters) equals
    dF/dp . dp from the full parameter Jacobian, for the DGP family and its numeric homogenization."""
    from cdpr_algebra.dgp.solve import fast_family
    from cdpr_algebra.homotopy.projective import projectivize

    rng = np.random.default_rng(5)
    fast = fast_family(3)
    proj, _ = projectivize(fast)
    for system in (fast, proj):
        X = rng.normal(size=(6, system.n)) + 1j * rng.normal(size=(6, system.n))
        P = rng.normal(size=(6, system.m)) + 1j * rng.normal(size=(6, system.m))
        dP = rng.normal(size=(6, system.m)) + 1j * rng.normal(size=(6, system.m))
        F, J, JP = system.evaluate_all(X, P)
        F2, J2, Ht = system.evaluate_directional(X, P, dP)
        assert np.array_equal(F, F2) and np.array_equal(J, J2)
        ref = np.einsum("nik,nk->ni", JP, dP)
        assert np.max(np.abs(Ht - ref)) <= 1e-12 * (1 + np.max(np.abs(ref)))


def test_many_target_solver_against_closed_form_roots():
    """The engine's many-target parameter homotopy (homotopy/many_targets.py) on x^2 + a x + b = 0,
    y - c x - d = 0 for 300 random real (a, b, c, d): the real solutions of every target are exactly the real
    roots of its quadratic (numpy), none lost, none extra, no failed path."""
    import sympy as sp

    from cdpr_algebra.homotopy.many_targets import ManyTargetSolver
    from cdpr_algebra.homotopy.systems import PolynomialSystem

    x, y, a, b, c, d = sp.symbols("x y a b c d")
    system = PolynomialSystem([x ** 2 + a * x + b, y - c * x - d], [x, y], [a, b, c, d], name="quadratic_line")
    rng = np.random.default_rng(5)
    P = rng.normal(size=(300, 4)) * [2.0, 1.0, 1.0, 1.0]
    out = ManyTargetSolver(system, seed=1).solve(P)
    assert len(out) == len(P)
    for (sols, failed), (pa, pb, pc, pd) in zip(out, P):
        assert failed == 0
        disc = pa * pa - 4 * pb
        expect = sorted(np.roots([1, pa, pb]).real) if disc > 1e-9 else []
        got = sorted(sols[:, 0]) if len(sols) else []
        assert len(got) == len(expect), (pa, pb, got, expect)
        assert np.allclose(got, expect, atol=1e-9)
        if len(sols):
            assert np.allclose(sols[:, 1], pc * sols[:, 0] + pd, atol=1e-9)


class _CubeRoot:
    """H(x, t) = x^3 - (0.05 + t): the path x(t) = (0.05 + t)^(1/3) (numpy tracker; no compiled kernels)."""

    n = neq = 1

    def evaluate_all(self, x, t):
        t = np.asarray(t, dtype=complex)
        return x ** 3 - (0.05 + t)[:, None], 3 * x[:, :, None] ** 2, -np.ones_like(x)

    def evaluate_and_jacobian(self, x, t):
        return self.evaluate_all(x, t)[:2]


def test_third_newton_update_accepts_a_step_two_updates_leave_above_the_corrector_tolerance():
    """A predictor error up to predictor_tol (1e-2) is corrected in three Newton updates to corrector_tol (1e-10):
    such steps are accepted, so the path takes few steps (6), against 16 when two updates must reach the
    tolerance (the round-off acceptance is kept out of the way by noise_tol = 1e-12); the endpoint is
    0.05^(1/3) to 1e-12."""
    H = _CubeRoot()
    x0 = np.array([[1.05 ** (1 / 3) + 0j]])
    o = TrackerOptions(predictor_tol=1e-2, corrector_tol=1e-10, noise_tol=1e-12)
    seg = track_segment(H, x0, 1.0, 0.0, o)
    assert seg.status[0] == "success"
    assert abs(seg.x[0, 0] - 0.05 ** (1 / 3)) <= 1e-12
    assert seg.steps[0] <= 8


def test_duplicate_groups_match_the_pairwise_definition():
    """duplicate_groups (sorted windows, vectorized in chunks) gives the groups linked by the pairwise test on every
    pair (each coordinate within tol (1 + the larger modulus)), on clustered random points with huge coordinates,
    non-finite rows and chunks smaller than the candidate count."""
    from cdpr_algebra.homotopy import clusters as EG
    from cdpr_algebra.homotopy.clusters import linked_groups

    rng = np.random.default_rng(11)
    for trial in range(30):
        N, n = int(rng.integers(2, 60)), int(rng.integers(1, 4))
        base = rng.normal(size=(N // 3 + 1, n)) + 1j * rng.normal(size=(N // 3 + 1, n))
        P = base[rng.integers(0, len(base), N)] * 10.0 ** rng.integers(0, 9, (N, 1))
        P = P + 1e-9 * rng.normal(size=P.shape) * (1 + np.abs(P)) * rng.integers(0, 2, (N, 1))
        if trial % 5 == 0:
            P[0, 0] = np.nan
        tol = 1e-7
        scale = 1 + np.maximum(np.abs(P)[:, None], np.abs(P)[None, :])
        with np.errstate(invalid="ignore"):
            close = np.all(np.abs(P[:, None] - P[None, :]) <= tol * scale, axis=2)
        i, j = np.nonzero(np.triu(close, 1))
        want = sorted(sorted(g) for g in linked_groups(N, i, j) if len(g) > 1)
        for chunk in (3, 1 << 16):
            old, EG.DUPLICATE_CHUNK = EG.DUPLICATE_CHUNK, chunk
            try:
                got = sorted(sorted(g) for g in EG.duplicate_groups(P, tol))
            finally:
                EG.DUPLICATE_CHUNK = old
            assert got == want


def test_endgame_without_infinity_verdicts_decides_no_path_at_infinity():
    """``EndgameOptions.infinity_verdicts=False``: the two paths of x y - 2 = x y + x + y - 5 = 0 that go to infinity
    are not decided at infinity (they end failed, undecided); the two finite solutions are found as before."""
    from cdpr_algebra.homotopy.results import FAILURES

    x, y = sp.symbols("x y")
    o = SolveOptions()
    o = replace(o, endgame=replace(o.endgame, infinity_verdicts=False))
    r = solve(PolynomialSystem([x * y - 2, x * y + x + y - 5], [x, y]), seed=0, options=o)
    s = r.summary()
    assert (s.paths, s.success, s.at_infinity) == (4, 2, 0)
    assert sum(p.status in FAILURES for p in r.track.paths) == 2
    got = sorted(tuple(np.round(v.x.real, 10)) for v in r.solutions)
    assert got == [(1.0, 2.0), (2.0, 1.0)]
