"""Completeness of the stored generic DGP solution sets (issue 15 item 3): the recorded trace-test certificates
(``cdpr_algebra/data/dgp_generic_m{m}_completeness.json``, written by ``derivations/certify_generic_dgp.py``)
match the sets they certify; the trace is recomputed from the recorded witnesses for a small case; negative
controls (a point removed) make the trace clearly nonzero; the trace test on a small family with a known count."""

from __future__ import annotations

import importlib.util
import itertools
import json
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from cdpr_algebra.dgp.solve import available_m, fast_family, generic_path
from cdpr_algebra.homotopy import PolynomialSystem, SolveOptions, TrackerOptions
from cdpr_algebra.homotopy.monodromy import MonodromyOptions, load_instance, monodromy_solve
from cdpr_algebra.homotopy.results import FAILURES
from cdpr_algebra.homotopy.trace_test import (TracePencilSystem, TraceSliceSystem, TraceTestOptions, compute_trace,
                                              coordinate_chart, distinct_points, slice_from_chart, slice_to_chart,
                                              verify_solution_completeness)

ROOT = Path(__file__).resolve().parents[1]


def _certify_module():
    spec = importlib.util.spec_from_file_location("certify_generic_dgp", ROOT / "derivations" / "certify_generic_dgp.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


CERT = _certify_module()


def _uc(d):
    return np.asarray(d["re"], dtype=float) + 1j * np.asarray(d["im"], dtype=float)


def certificate(m):
    path = CERT.certificate_path(m)
    assert path.exists(), f"no completeness certificate for the stored m = {m} set (run {path.name}'s derivation)"
    return json.loads(path.read_text())


def _recorded(m):
    """(system, p0, W01, q0, l, W10, trace record) of the certificate of m."""
    p, X, _ = load_instance(generic_path(m))
    tt = certificate(m)["trace_test"]
    W10 = _uc(tt["W10"]).reshape(tt["W10_count"], X.shape[1] + 1)
    return fast_family(m), p, X, _uc(tt["q0"]), _uc(tt["l"]), W10, tt


@pytest.mark.parametrize("m", [2, 3, 4, 5, 6])
def test_certificate_matches_stored_set_and_passed(m):
    """The certificate is for the stored set (hash of its parameters and solutions), its trace is below the
    tolerance with every pencil path regular and distinct, and the monodromy run from scratch without a target
    count found as many distinct solutions as the stored set, every stored point moved there being one of them."""
    if m not in available_m():
        pytest.skip(f"no stored generic set for m = {m}")
    cert = certificate(m)
    p, X, _ = load_instance(generic_path(m))
    assert cert["stored_set"]["data_sha256"] == CERT.data_hash(p, X)
    if "trace_test" not in cert:  # a recorded test that failed or was undecided fails below; a missing one is reported
        pytest.skip(f"no trace test recorded for m = {m} (derivations/certify_generic_dgp.py --m {m})")
    tt = cert["trace_test"]
    assert tt["status"] == "passed" and tt["count"] == len(X) == cert["count"]
    tr = tt["trace"]
    assert tr["status"] == "passed" and tr["relative"] <= tr["tol"] <= 1e-6
    trace = _uc(tr["trace"])
    assert np.max(np.abs(trace)) / tr["scale"] == pytest.approx(tr["relative"], rel=1e-9, abs=1e-300)
    assert tr["points"] == len(X) + tt["W10_count"]
    last = tr["outcomes"][-1]  # the attempt the trace comes from: every path regular, no duplicate endpoint
    for side in ("plus", "minus"):
        assert last[side]["success"] == tr["points"]
        assert sum(v for k, v in last[side].items() if k != "success") == 0
    # separation: the smallest second difference of a single point (the trace of the set without it) is far above
    # the measured trace and above the tolerance
    assert tr["detection"] > max(100 * tr["relative"], tr["tol"])
    mono = cert["monodromy_from_scratch"]
    assert mono["target_solutions_count"] is None and mono["stopped_by"] == "no_progress"
    assert mono["count"] == len(X) <= mono["count_raw"]
    moved = mono["stored_moved"]  # the stored set moved to the new instance: every arriving point was found there
    arrived = sum(r.get("success", 0) for r in moved["outcomes"])  # over the rounds (failed paths re-routed)
    assert moved["stored_matched"] == arrived
    first = moved["outcomes"][0].get("success", 0)  # endpoints of one homotopy's paths are distinct solutions
    assert moved["found_matched"] >= first >= len(X) - 5


def test_recomputed_trace_m2():
    """The trace of the stored m = 2 set and the recorded W10, recomputed along the recorded pencil, is ~0;
    the recorded W10 lies on the recorded slice."""
    if 2 not in available_m():
        pytest.skip("no stored m = 2 set")
    fam, p, X, q0, l, W10, tt = _recorded(2)
    sl = TraceSliceSystem(fam, p, q0 - p, tt["coordinates"])
    assert np.max(np.abs(sl.evaluate(W10, l))) <= 1e-8 * (1 + np.max(np.abs(W10)))
    o = TraceTestOptions(eps=tt["trace"]["eps"], tol=tt["trace"]["tol"], attempts=1)
    g = tt["trace"]["gamma"]
    tr = compute_trace(fam, p, q0, l, X, W10, o, gamma=complex(g["re"], g["im"]), coordinates=tt["coordinates"])
    assert tr.status == "passed", tr.outcomes
    assert tr.relative <= o.tol


@pytest.mark.parametrize("drop", ["W01", "W10"])
def test_trace_detects_a_missing_point_m2(drop):
    """Negative control: the stored m = 2 set (or W10) with one point removed gives a clearly nonzero trace."""
    if 2 not in available_m():
        pytest.skip("no stored m = 2 set")
    fam, p, X, q0, l, W10, tt = _recorded(2)
    o = TraceTestOptions(eps=tt["trace"]["eps"], tol=tt["trace"]["tol"], attempts=1)
    g = complex(tt["trace"]["gamma"]["re"], tt["trace"]["gamma"]["im"])
    k = 5
    if drop == "W01":
        tr = compute_trace(fam, p, q0, l, np.delete(X, k, axis=0), W10, o, gamma=g, coordinates=tt["coordinates"])
    else:
        tr = compute_trace(fam, p, q0, l, X, np.delete(W10, k, axis=0), o, gamma=g, coordinates=tt["coordinates"])
    assert tr.status == "failed"
    assert tr.relative > 100 * o.tol


# ---------------------------------------------------------------------------------------------
def _dense_quadrics(n):
    """n generic quadrics in n unknowns, every coefficient a parameter: 2^n solutions (Bezout, generic)."""
    xs = sp.symbols(f"x0:{n}")
    mons = [sp.Mul(*[xs[i] ** e[i] for i in range(n)]) for e in itertools.product(range(3), repeat=n) if sum(e) <= 2]
    ps, eqs = [], []
    for i in range(n):
        cs = sp.symbols(f"c{i}_0:{len(mons)}")
        ps += cs
        eqs.append(sum(c * mo for c, mo in zip(cs, mons)))
    return PolynomialSystem(eqs, xs, ps, name=f"dense_quadrics{n}")


@pytest.fixture(scope="module")
def quadrics():
    S = _dense_quadrics(2)
    r = monodromy_solve(S, seed=1)
    return S, r.parameters, r.solutions


def test_trace_test_small_family_passes_with_the_full_set(quadrics):
    S, p, X = quadrics
    assert len(X) == 4  # Bezout number of two generic conics
    res = verify_solution_completeness(S, p, X, seed=3)
    assert res.status == "passed" and res.trace.relative <= res.trace.tol
    # W10 lies on the curve and on the hyperplane
    assert np.max(np.abs(TraceSliceSystem(S, p, res.q0 - p).evaluate(res.W10, res.l))) < 1e-9
    for k in range(len(X)):  # and fails with any point removed
        tr = compute_trace(S, p, res.q0, res.l, np.delete(X, k, axis=0), res.W10, seed=3)
        assert tr.status == "failed" and tr.relative > 100 * tr.tol
    tr = compute_trace(S, p, res.q0, res.l, X, res.W10[1:], seed=3)
    assert tr.status == "failed"


def test_monodromy_and_trace_test_inside_a_linear_subfamily():
    """Two conics in a subfamily given by linear relations (c0_1 + c0_2 = 0 and c1_0 = c1_5): the seed, every loop
    point and the trace test's curve keep the relations exactly, and the trace of the subfamily's own solution set
    passes there."""
    from cdpr_algebra.homotopy.monodromy import in_subfamily, subfamily_directions, with_relations

    S = _dense_quadrics(2)  # 6 coefficients per conic: 1, x1, x1^2, x0, x0 x1, x0^2 (itertools order)
    rel = (((1, 1.0), (2, 1.0)), ((6, 1.0), (11, -1.0)))
    N = subfamily_directions(S.m, (), rel)
    assert N.shape == (S.m, S.m - 2) and np.allclose(N.T @ N, np.eye(S.m - 2))
    z = np.arange(S.m) + 1j
    w = with_relations(z + in_subfamily(z, (), rel), rel)
    assert w[1] + w[2] == 0 and w[6] == w[11]
    r = monodromy_solve(S, seed=4, options=MonodromyOptions(parameter_relations=rel, max_loops_no_progress=4))
    p = r.parameters
    assert p[1] + p[2] == 0 and p[6] == p[11]
    assert len(r.solutions) == 4  # the relations leave the conics generic enough for Bezout's 4
    res = verify_solution_completeness(S, p, r.solutions, seed=3, options=TraceTestOptions(parameter_relations=rel))
    assert res.status == "passed"
    assert res.q0[1] + res.q0[2] == 0 and res.q0[6] == res.q0[11]  # the curve stays in the subfamily


def test_a_trace_that_does_not_separate_is_undecided(quadrics):
    """A trace below the tolerance passes only when a single missing point would show clearly above it
    (``separation``): asked for more separation than the measured trace gives, the same test is undecided, with
    the reason, never passed; polishing every point in arbitrary precision lowers the trace, not the signal."""
    S, p, X = quadrics
    res = verify_solution_completeness(S, p, X, seed=3)
    tr = res.trace
    assert tr.status == "passed" and tr.separation >= tr.required_separation == 100
    assert tr.separation == pytest.approx(tr.detection / tr.relative)
    strict = TraceTestOptions(separation=10 * tr.separation)
    weak = compute_trace(S, p, res.q0, res.l, X, res.W10, strict, seed=3, gamma=tr.gamma)
    assert weak.status == "undecided" and not weak.passed and "does not separate" in weak.reason
    assert weak.relative == pytest.approx(tr.relative, rel=1e-6) and weak.to_dict()["reason"] == weak.reason
    polished = compute_trace(S, p, res.q0, res.l, X, res.W10, TraceTestOptions(polish_condition=0.0), seed=3,
                             gamma=tr.gamma)
    assert polished.outcomes[-1]["polished"]["start"] == len(X) + len(res.W10)  # every point refined
    assert polished.status == "passed" and polished.detection == pytest.approx(tr.detection, rel=1e-3)
    assert polished.relative <= max(tr.relative, 1e-14)


def test_trace_test_lost_paths_are_undecided(quadrics):
    """Pencil paths that cannot be tracked (a step budget of 1) make the test undecided, never passed."""
    S, p, X = quadrics
    rng = np.random.default_rng(0)
    q0 = p + rng.normal(size=p.size) + 1j * rng.normal(size=p.size)
    l = rng.normal(size=3) + 1j * rng.normal(size=3)
    bad = SolveOptions(tracker=TrackerOptions(max_steps=1), retry_tight=False, retry_mpmath=False)
    tr = compute_trace(S, p, q0, l, X, np.zeros((0, 3)), TraceTestOptions(pencil=bad, attempts=2))
    assert tr.status == "undecided" and not tr.passed and len(tr.outcomes) == 2
    assert all(o["plus"]["success"] < len(X) for o in tr.outcomes)


def test_slice_and_pencil_jacobians_by_finite_differences():
    S = _dense_quadrics(2)
    rng = np.random.default_rng(1)
    p0 = rng.normal(size=S.m) + 1j * rng.normal(size=S.m)
    v = rng.normal(size=S.m) + 1j * rng.normal(size=S.m)
    l = rng.normal(size=3) + 1j * rng.normal(size=3)
    y = rng.normal(size=(4, 3)) + 1j * rng.normal(size=(4, 3))
    h = 1e-7
    for sysm, par in ((TraceSliceSystem(S, p0, v), l), (TracePencilSystem(S, p0, v, l), np.array([0.3 - 0.2j]))):
        G, J, JP = sysm.evaluate_all(y, par)
        for j in range(3):
            e = np.zeros(3)
            e[j] = h
            fd = (sysm.evaluate(y + e, par) - sysm.evaluate(y - e, par)) / (2 * h)
            np.testing.assert_allclose(J[:, :, j], fd, atol=1e-6)
        for k in range(len(par)):
            e = np.zeros(len(par), dtype=complex)
            e[k] = h
            fd = (sysm.evaluate(y, par + e) - sysm.evaluate(y, par - e)) / (2 * h)
            np.testing.assert_allclose(JP[:, :, k], fd, atol=1e-6)


def test_trace_test_on_a_projection():
    """The test in a subset of the unknowns (the image of the curve under a projection that separates the
    solutions): passes with the full set, fails with a point removed; a projection that merges solutions is
    refused."""
    S = _dense_quadrics(3)
    r = monodromy_solve(S, seed=1)
    p, X = r.parameters, r.solutions
    assert len(X) == 8
    res = verify_solution_completeness(S, p, X, seed=2, coordinates=[0, 1])
    assert res.status == "passed" and list(res.coordinates) == [0, 1] and len(res.l) == 3
    tr = compute_trace(S, p, res.q0, res.l, X[1:], res.W10, seed=2, coordinates=[0, 1])
    assert tr.status == "failed" and tr.relative > 100 * tr.tol
    with pytest.raises(ValueError, match="separate"):
        compute_trace(S, p, res.q0, res.l, np.concatenate([X, X[:1] + [0, 0, 1]]), res.W10, coordinates=[0, 1])


def test_distinct_points_keeps_close_ill_conditioned_solutions_apart():
    """y = x^2, y = e with e = 5e-15 (a line nearly tangent to a parabola): the roots x = +-7.1e-8 (condition ~1e7)
    lie closer than the conditioning allowance of double precision (100 * 2.2e-16 * cond), so without
    arbitrary-precision refinement they are merged; refined, they are two solutions, while copies of one root are
    still one."""
    import sympy as sp

    from cdpr_algebra.homotopy.systems import PolynomialSystem
    from cdpr_algebra.homotopy.trace_test import distinct_points

    x, y, e = sp.symbols("x y e")
    system = PolynomialSystem([y - x ** 2, y - e], [x, y], [e], name="close_pair")
    r = np.sqrt(5e-15)
    X = np.array([[r, 5e-15], [-r, 5e-15], [r * (1 + 1e-12), 5e-15]], dtype=complex)
    merged, _ = distinct_points(system, [5e-15], X, polish_condition=None)
    assert len(merged) == 1
    kept, rec = distinct_points(system, [5e-15], X)
    assert len(kept) == 2 and rec["polished"] == 3
    assert sorted(kept[:, 0].real) == pytest.approx([-r, r], rel=1e-12)


@pytest.mark.parametrize("m", [4, 5])
def test_phcpack_count_recorded_and_contained_in_the_stored_set(m):
    """PHCpack's blackbox on a random complex instance of the m-cable family (recorded by
    derivations/certify_generic_dgp.py --phc): its solutions solve that instance (residuals recomputed here), they are
    distinct, and every one is among the stored set moved to that instance, which has at most as many points as the
    stored set: PHCpack's independent count confirms all but the stored points it missed, and none beyond."""
    cert = certificate(m)
    if "phc" not in cert or "solutions" not in cert["phc"]:
        pytest.skip(f"no PHCpack run recorded for m = {m}")
    phc = cert["phc"]
    fam = fast_family(m)
    p = _uc(phc["parameters"])
    S = _uc(phc["solutions"]).reshape(-1, fam.n)
    F = fam.evaluate(S, p)
    assert np.max(np.abs(F), axis=1).max() <= 1e-8 * (1 + np.abs(S).max())
    P, _ = distinct_points(fam, p, S)
    assert len(P) == phc["phc_distinct"] == phc["regular_all_lam_nonzero"]
    moved = phc["stored_moved"]
    _, X, _ = load_instance(generic_path(m))
    assert moved["phc_unmatched"] == 0 and moved["phc_matched"] == len(P)
    assert moved["distinct"] <= len(X) and phc["union_distinct"] == moved["distinct"] == len(X)
    # recomputed: the stored set moved to PHCpack's instance by the DGP's parameter homotopy reaches every PHCpack
    # solution (but for as many as its paths failed), and its other endpoints are at most the stored points that
    # PHCpack missed
    from cdpr_algebra.dgp.solve import _generic, default_options
    from cdpr_algebra.homotopy.many_targets import solve_targets

    p_gen, X_gen = _generic(m)
    (res,) = solve_targets(fam, p_gen, X_gen, [p], seed=0, options=default_options(), gamma=True, retries=1)
    Z = np.array([s.x for s in res.solutions]).reshape(-1, fam.n)
    failed = sum(1 for q in res.track.paths if q.status in FAILURES)
    d = np.abs(Z[:, None, :] - P[None, :, :]).max(axis=2) / (1 + np.abs(P).max(axis=1))[None, :]
    assert int(np.sum(d.min(axis=0) <= 1e-6)) >= len(P) - failed
    assert int(np.sum(d.min(axis=1) > 1e-6)) <= len(X) - len(P)


# ---------------------------------------------------------------------------------------------
# the trace test on a chart of projective space (W10 points of very large norm; DGP m = 4)
@pytest.mark.parametrize("m", [2, 3, 4, 5, 6])
def test_recorded_witnesses_lie_on_the_recorded_slice(m):
    """The recorded W10 solve the slice system at the recorded hyperplane (recomputed, cheap), are distinct, and a
    certificate whose W10 was found on a chart records a chart of :func:`coordinate_chart` (zero off y0 and the
    trace coordinates, so that its hyperplanes are affine ones)."""
    if m not in available_m():
        pytest.skip(f"no stored generic set for m = {m}")
    if "trace_test" not in certificate(m):
        pytest.skip(f"no trace test recorded for m = {m}")
    fam, p, X, q0, l, W10, tt = _recorded(m)
    sl = TraceSliceSystem(fam, p, q0 - p, tt["coordinates"])
    res = np.max(np.abs(sl.evaluate(W10, l)), axis=1) / (1 + np.max(np.abs(W10), axis=1)) ** 2
    assert res.max() <= 1e-8
    assert len(distinct_points(sl, l, W10)[0]) == len(W10)
    if "chart" in tt:
        c = _uc(tt["chart"]["c"])
        expect = coordinate_chart(fam.n, tt["coordinates"], tt["chart"]["seed"])
        np.testing.assert_allclose(c, expect, atol=1e-15)
        assert np.all(c[1 + np.arange(len(tt["coordinates"]), fam.n)] == 0)


def test_homogenized_mp_functions_match_the_float_evaluators():
    from cdpr_algebra.homotopy.projective import HomogenizedQuadratic, _chart, to_chart
    import mpmath

    fam = fast_family(3)
    p, X, _ = load_instance(generic_path(3))
    h = HomogenizedQuadratic(fam, _chart(fam.n, 5))
    Y = to_chart(X[:2], h.c)
    assert np.max(np.abs(h.evaluate(Y, p))) < 1e-10
    rng = np.random.default_rng(0)
    Y = Y + 0.1 * (rng.normal(size=Y.shape) + 1j * rng.normal(size=Y.shape))
    F, J, JP = h.evaluate_all(Y, p)
    mF, mJ, mP = h.mp_functions()
    pm = [mpmath.mpc(complex(v)) for v in p]
    for k in range(2):
        Ym = [mpmath.mpc(complex(v)) for v in Y[k]]
        np.testing.assert_allclose(np.array(mF(Ym, pm).tolist(), dtype=complex).ravel(), F[k], atol=1e-12)
        np.testing.assert_allclose(np.array(mJ(Ym, pm).tolist(), dtype=complex), J[k], atol=1e-12)
        np.testing.assert_allclose(np.array(mP(Ym, pm).tolist(), dtype=complex), JP[k], atol=1e-12)


def test_slice_chart_round_trip():
    """Witness points of an affine slice taken to a chart of coordinate_chart and back: the same points, and the
    hyperplane recovered from the chart form with any constant term still contains them (it is affine)."""
    from cdpr_algebra.homotopy.projective import from_chart

    S = _dense_quadrics(3)
    r = monodromy_solve(S, seed=1)
    res = verify_solution_completeness(S, r.parameters, r.solutions, seed=2, coordinates=[0, 1])
    c = coordinate_chart(S.n, [0, 1], 7)
    assert c[3] == 0 and np.all(c[:3] != 0)
    Wc, lc = slice_to_chart(res.W10, res.l, c)
    W, l = slice_from_chart(Wc, lc, c, [0, 1])
    np.testing.assert_allclose(W, res.W10, rtol=1e-12, atol=1e-12)
    lc2 = lc + np.array([0, 0, 0, 0.7 - 0.2j])  # a constant k: k = k c . Y on the chart
    lc2[:3] -= (0.7 - 0.2j) * c[:3]
    W2, l2 = slice_from_chart(Wc, lc2, c, [0, 1])
    np.testing.assert_allclose(l2, l, atol=1e-12)
    with pytest.raises(ValueError, match="zero off"):
        slice_from_chart(Wc, lc, np.ones(S.n + 1), [0, 1])
    x, ratio = from_chart(Wc[:, :-1])
    assert np.all(ratio > 0)


def test_trace_test_with_witnesses_found_on_a_chart():
    """verify_solution_completeness(chart=...) on a small family: W10 found on a chart, mapped back to affine
    coordinates, the trace passes; it fails with a point removed."""
    S = _dense_quadrics(2)
    r = monodromy_solve(S, seed=1)
    p, X = r.parameters, r.solutions
    res = verify_solution_completeness(S, p, X, seed=3, chart=11)
    assert res.status == "passed" and res.chart is not None and len(res.W10) > 0
    assert np.max(np.abs(TraceSliceSystem(S, p, res.q0 - p).evaluate(res.W10, res.l))) < 1e-9
    tr = compute_trace(S, p, res.q0, res.l, X, res.W10[1:], seed=3)
    assert tr.status == "failed"


def test_chart_pencil_is_the_affine_pencil():
    """ChartPencilSystem: Jacobians by finite differences, and its paths end at the affine pencil's endpoints
    (mapped back from the chart)."""
    from cdpr_algebra.homotopy.projective import HomogenizedQuadratic, _chart, from_chart, to_chart
    from cdpr_algebra.homotopy.trace_test import ChartPencilSystem, _track

    S = _dense_quadrics(2)
    r = monodromy_solve(S, seed=1)
    p, X = r.parameters, r.solutions
    res = verify_solution_completeness(S, p, X, seed=3)
    h = HomogenizedQuadratic(S, _chart(S.n, 3))
    cp = ChartPencilSystem(h, p, res.q0 - p, res.l)
    ap = TracePencilSystem(S, p, res.q0 - p, res.l)
    P = np.concatenate([np.concatenate([X, np.zeros((len(X), 1))], axis=1), res.W10])
    Pc = np.concatenate([to_chart(P[:, :-1], h.c), P[:, -1:]], axis=1)
    assert np.max(np.abs(cp.evaluate(Pc, [0.0]))) < 1e-9
    rng = np.random.default_rng(2)
    y = Pc[:3] + 0.05 * (rng.normal(size=Pc[:3].shape) + 1j * rng.normal(size=Pc[:3].shape))
    tau = np.array([0.3 - 0.1j])
    G, J, JP = cp.evaluate_all(y, tau)
    hh = 1e-7
    for j in range(cp.n):
        e = np.zeros(cp.n)
        e[j] = hh
        np.testing.assert_allclose(J[:, :, j], (cp.evaluate(y + e, tau) - cp.evaluate(y - e, tau)) / (2 * hh), atol=1e-6)
    np.testing.assert_allclose(JP[:, :, 0], (cp.evaluate(y, tau + hh) - cp.evaluate(y, tau - hh)) / (2 * hh), atol=1e-6)
    g = 0.6 + 0.8j
    ea = np.array([q.endpoint for q in _track(ap, P, [0.0], [g], SolveOptions(), 0)])
    ec = np.array([q.endpoint for q in _track(cp, Pc, [0.0], [g], SolveOptions(), 0)])
    xc, _ = from_chart(ec[:, :-1])
    np.testing.assert_allclose(np.concatenate([xc, ec[:, -1:]], axis=1), ea, rtol=1e-8, atol=1e-8)


def test_lost_pencil_paths_are_tracked_again_on_a_chart():
    """A pencil path marked lost is tracked again on a chart and replaced by its endpoint there, which is the
    affine path's endpoint (retried = "chart")."""
    from dataclasses import replace as dreplace

    from cdpr_algebra.homotopy.trace_test import _retrack_in_chart, _track

    S = _dense_quadrics(2)
    r = monodromy_solve(S, seed=1)
    p, X = r.parameters, r.solutions
    res = verify_solution_completeness(S, p, X, seed=3)
    P = np.concatenate([np.concatenate([X, np.zeros((len(X), 1))], axis=1), res.W10])
    ap = TracePencilSystem(S, p, res.q0 - p, res.l)
    o = TraceTestOptions()
    paths = _track(ap, P, [0.0], [0.5j], o.pencil, 0)
    spoiled = list(paths)
    spoiled[1] = dreplace(paths[1], status="step_too_small")
    out, lost, rescued = _retrack_in_chart(S, p, res.q0, res.l, np.arange(S.n), P, spoiled, 0.5j, o, 0)
    assert (lost, rescued) == (1, 1) and out[1].retried == "chart" and out[1].status == "success"
    np.testing.assert_allclose(out[1].endpoint, paths[1].endpoint, rtol=1e-8, atol=1e-8)
    none, lost, rescued = _retrack_in_chart(S, p, res.q0, res.l, np.arange(S.n), P, spoiled, 0.5j,
                                            TraceTestOptions(chart_retrack=None), 0)
    assert (lost, rescued) == (1, 0) and none[1].status == "step_too_small"


def test_mp_evaluators_of_the_trace_systems_match_the_float_ones():
    """mp_functions (arbitrary-precision polish) of the slice, the pencil and the chart pencil agree with their
    floating-point evaluators (values, Jacobians, parameter derivatives) at an arbitrary point."""
    import mpmath

    from cdpr_algebra.homotopy.projective import HomogenizedQuadratic, _chart
    from cdpr_algebra.homotopy.trace_test import ChartPencilSystem

    fam = fast_family(3)
    p, X, _ = load_instance(generic_path(3))
    rng = np.random.default_rng(0)
    v = rng.normal(size=p.size) + 0.5j * rng.normal(size=p.size)
    l = rng.normal(size=13) + 1j * rng.normal(size=13)
    y = np.concatenate([X[0], [0.3]])[None, :] + 0.01
    h = HomogenizedQuadratic(fam, _chart(fam.n, 3))
    yc = np.concatenate([[0.9], 0.9 * X[0], [0.3]])[None, :]
    tau = np.array([0.2 + 0.1j])
    for sysm, par, yy in ((TraceSliceSystem(fam, p, v, list(range(12))), l, y),
                          (TracePencilSystem(fam, p, v, l, list(range(12))), tau, y),
                          (ChartPencilSystem(h, p, v, l, list(range(12))), tau, yc)):
        G, J, JP = sysm.evaluate_all(yy, par)
        mF, mJ, mP = sysm.mp_functions()
        ym, pm = [mpmath.mpc(complex(a)) for a in yy[0]], [mpmath.mpc(complex(a)) for a in par]
        np.testing.assert_allclose(np.array(mF(ym, pm).tolist(), dtype=complex).ravel(), G[0], atol=1e-12)
        np.testing.assert_allclose(np.array(mJ(ym, pm).tolist(), dtype=complex), J[0], atol=1e-12)
        np.testing.assert_allclose(np.array(mP(ym, pm).tolist(), dtype=complex), JP[0], atol=1e-12)
