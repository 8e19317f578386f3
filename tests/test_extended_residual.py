"""Newton residuals in double-double (homotopy.double_double, the generated taut_residual_dd, compiled.track_kernel):
the arithmetic against exact rationals, the generated residual and the chart residual against mpmath, the tracker
unchanged on paths that never need it, and paths that double precision cannot follow followed with it (their
endpoints checked by Newton's method in 50 digits)."""

from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest

from cdpr_algebra.dgp.normalization import normalized_problem
from cdpr_algebra.dgp.solve import _generic, default_options, fast_family
from cdpr_algebra.generated.taut_residual_dd import taut_residual
from cdpr_algebra.homotopy import compiled, double_double as dd
from cdpr_algebra.homotopy.endgame import EndgameOptions, _track_to_endgame
from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
from cdpr_algebra.homotopy.tracker import track_segment
from cdpr_algebra.model.robot import load_robot
from cdpr_algebra.model.taut_equations import taut_family
from cdpr_algebra.model.taut_sets import lengths_and_taut_sets

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _value(h, l=0.0):
    return Fraction(h) + Fraction(l)


def test_real_operations_against_exact_rationals():
    rng = np.random.default_rng(3)
    for _ in range(200):
        a = (float(rng.normal()), float(rng.normal()) * 1e-17)
        b = (float(rng.normal()) * 10.0 ** int(rng.integers(-5, 5)), 0.0)
        b = (b[0], b[0] * float(rng.normal()) * 1e-17)
        A, B = _value(*a), _value(*b)
        for op, exact in ((dd.dd_mul, A * B), (dd.dd_div, A / B)):
            h, l = op(a[0], a[1], b[0], b[1])
            assert abs(_value(h, l) - exact) <= Fraction(2) ** -100 * abs(exact)
        h, l = dd.dd_add(a[0], a[1], b[0], b[1])
        assert abs(_value(h, l) - (A + B)) <= Fraction(2) ** -100 * (abs(A) + abs(B))


def test_complex_operations_against_exact_rationals():
    rng = np.random.default_rng(4)
    for _ in range(100):
        a = tuple(float(v) for v in rng.normal(size=4) * np.array([1, 1e-17, 1, 1e-17]))
        b = tuple(float(v) for v in rng.normal(size=4) * np.array([1, 1e-17, 1, 1e-17]))
        ar, ai, br, bi = _value(a[0], a[1]), _value(a[2], a[3]), _value(b[0], b[1]), _value(b[2], b[3])
        size = (abs(ar) + abs(ai)) * (abs(br) + abs(bi))
        p = dd.cc_mul(a, b)
        assert abs(_value(p[0], p[1]) - (ar * br - ai * bi)) <= Fraction(2) ** -100 * size
        assert abs(_value(p[2], p[3]) - (ar * bi + ai * br)) <= Fraction(2) ** -100 * size
        q = dd.cc_div(a, b)
        n = br * br + bi * bi
        qr, qi = (ar * br + ai * bi) / n, (ai * br - ar * bi) / n
        scale = (abs(ar) + abs(ai)) / (abs(br) + abs(bi))
        assert abs(_value(q[0], q[1]) - qr) <= Fraction(2) ** -98 * scale * 4
        assert abs(_value(q[2], q[3]) - qi) <= Fraction(2) ** -98 * scale * 4


@pytest.mark.parametrize("m", [2, 4, 6])
def test_generated_residual_against_mpmath(m):
    """At a point of size 1e4 (terms ~1e8 that cancel) the double-double residual matches 50-digit arithmetic to
    ~1e-30 of the terms, where double precision is off by ~1e-16 of them; the parameter path with a gamma too."""
    rng = np.random.default_rng(m)
    n, npar = 12 + m, 7 * m + 6
    x = (rng.normal(size=n) + 1j * rng.normal(size=n)) * 1e4
    p1 = rng.normal(size=npar) + 1j * rng.normal(size=npar)
    p0 = rng.normal(size=npar)
    t, g = 0.37 + 0.01j, 0.6 + 0.8j
    P = np.zeros((npar, 4))
    dd.dd_parameters(p1, p0, g, t, P)
    X = np.zeros((n, 4))
    dd.to_dd(x, X)
    F = np.zeros((n, 4))
    taut_residual(X, P, F)
    with mpmath.workdps(50):
        T, G = mpmath.mpc(t), mpmath.mpc(g)
        pm = [(G * T * mpmath.mpc(a) + (1 - T) * mpmath.mpc(b)) / (G * T + 1 - T) for a, b in zip(p1, p0)]
        for k in range(npar):
            assert abs(mpmath.mpc(P[k, 0], P[k, 2]) + mpmath.mpc(P[k, 1], P[k, 3]) - pm[k]) <= 1e-30 * (1 + abs(pm[k]))
        Fm = taut_family(m).mp_functions()[0]([mpmath.mpc(v) for v in x], pm)
        err = max(abs(mpmath.mpc(F[k, 0], F[k, 2]) + mpmath.mpc(F[k, 1], F[k, 3]) - Fm[k]) for k in range(n))
    assert err <= 1e-28 * 1e8
    # the same point in double precision is off by many orders of magnitude more
    pd = np.array([complex(v) for v in pm])
    Fd = fast_family(m).evaluate(x[None], pd[None])[0]
    assert max(abs(Fd[k] - complex(Fm[k])) for k in range(n)) > 1e3 * err


def test_residual_dd_is_the_homotopy_affine_and_on_a_chart():
    """:func:`compiled.residual_dd` (the compiled double-double residual: F of the parameter path, and on a chart the
    homogenized system from F at y, -y, 0 and the chart row) equals the double-precision homotopy to its rounding."""
    m = 3
    rng = np.random.default_rng(7)
    npar = 7 * m + 6
    p1 = rng.normal(size=npar) + 1j * rng.normal(size=npar)
    p0 = rng.normal(size=npar) + 0j
    hom = ParameterHomotopy(fast_family(m), p1, p0)
    for h in (hom, hom.projective()):
        Y = rng.normal(size=(5, h.n)) + 1j * rng.normal(size=(5, h.n))
        t = np.array([0.3, 0.7 + 0.2j, 1.0, 0.0, 0.05j])
        F = compiled.residual_dd(h)(Y, t)
        Fh = h.evaluate(Y, t)
        assert np.allclose(F, Fh, rtol=0, atol=1e-12 * (1 + np.abs(Fh).max()))


def _hard_subproblem():
    """Seed 000 Test 3's taut set {2,3,4,5} (0-based (1,2,3,4)): paths through large complex solutions."""
    robot = load_robot(EXAMPLES / "seed000_test3.toml")
    rho, _ = lengths_and_taut_sets(robot)
    cables = (1, 2, 3, 4)
    fam = fast_family(len(cables))
    p0 = normalized_problem(robot, rho, cables)[0]
    p1, X = _generic(len(cables))
    return fam, p1, p0, X


def test_paths_that_never_stall_are_unchanged():
    """Allowing the extended residual changes nothing on the paths that do not use it: same points, steps and
    status, bit for bit."""
    fam, p1, p0, X = _hard_subproblem()
    hom = ParameterHomotopy(fam, p1, p0)
    o = default_options().tracker
    a = track_segment(hom, X, 1.0, 0.1, replace(o, extended_residual=False))
    b = track_segment(hom, X, 1.0, 0.1, replace(o, extended_residual=True))
    assert not a.extended.any() and b.extended.any()
    same = ~b.extended
    assert same.sum() > 0.8 * len(X)
    assert np.array_equal(a.x[same], b.x[same]) and np.array_equal(a.steps[same], b.steps[same])
    assert np.array_equal(a.status[same], b.status[same])


def test_extended_residual_follows_paths_double_precision_cannot():
    """Finish segments t = 0.1 -> 0.025 of the subproblem: some fail in double precision; with the extended
    residual fewer fail, and every path that only it brings through ends on a point where Newton's method in 50
    digits (at that t) moves it by less than the corrector tolerance (relative): a point of the path's system."""
    fam, p1, p0, X = _hard_subproblem()
    hom = ParameterHomotopy(fam, p1, p0)
    opts = replace(default_options(), endgame=EndgameOptions(projective=True))
    o = replace(opts.tracker, extended_residual=False)
    x, st, _, _, _, _ = _track_to_endgame(hom, X, np.arange(len(X)), replace(opts, tracker=o), 0.1, o)
    ok = np.flatnonzero(st == "success")
    a = track_segment(hom, x[ok], 0.1, 0.025, o)
    b = track_segment(hom, x[ok], 0.1, 0.025, replace(o, extended_residual=True))
    fa, fb = a.status != "success", b.status != "success"
    assert fa.sum() >= 2 and fb.sum() < fa.sum()
    rescued = np.flatnonzero(fa & ~fb)
    assert rescued.size
    fF, fJ, _ = fam.mp_functions()
    with mpmath.workdps(50):
        T = mpmath.mpf(0.025)
        pm = [T * mpmath.mpc(u) + (1 - T) * mpmath.mpc(v) for u, v in zip(p1, p0)]
        for i in rescued:
            z = mpmath.matrix([mpmath.mpc(v) for v in b.x[i]])
            for _ in range(4):
                z = z - mpmath.lu_solve(fJ(z, pm), fF(z, pm))
            move = mpmath.norm(z - mpmath.matrix([mpmath.mpc(v) for v in b.x[i]]))
            assert move <= o.corrector_tol * (1 + mpmath.norm(z)), (i, move)


@pytest.mark.parametrize("cables", [(1, 3, 4), (2, 3, 4, 5)])
def test_extended_precision_completes_marionet_subproblems(cables, monkeypatch):
    """Seed 000 Test 3, taut sets {2, 4, 5} and {3, 4, 5, 6}: some paths fail in double precision (without the
    re-tracking in Study parameters); with the extended residual (``default_options(extended=True)``) none does, the
    outcomes account for every path, every regular endpoint is certified, and the regular solutions found without it
    are among those found with it.  Failed paths re-tracked in Study parameters with double-double residuals
    (dgp.study_retrack, the pipeline before Study came first) complete them too, every path regular and certified,
    and so does the default DGP (every path in Study parameters first), with the same outcomes and solutions
    (on {2, 4, 5} the extended run ends 4 paths singular, which the Study run ends on 4 distinct certified roots)."""
    from cdpr_algebra.dgp import solve as D
    from cdpr_algebra.dgp.solve import solve_taut_set

    robot = load_robot(EXAMPLES / "seed000_test3.toml")
    monkeypatch.setattr(D, "STUDY_FIRST", False)  # the taut system first (the pipeline before Study came first)
    monkeypatch.setattr(D, "STUDY_RETRACK", False)
    monkeypatch.setattr(D, "OTHER_START", False)  # a run from another generic instance settles the plain run's failures
    monkeypatch.setattr(D, "EXTENDED_MAX_FAILED", 0)  # so does tracking them again in double-double (dgp.taut_extended)
    rerun = D.RERUN_MAX_FAILED
    monkeypatch.setattr(D, "RERUN_MAX_FAILED", 0)  # nor the gamma re-run, whose roots settle the plain run's too,
    monkeypatch.setattr(D, "CONJUGATE_ROOTS", False)  # nor the conjugates of its roots
    plain, _ = solve_taut_set(robot, robot.lengths, cables, options=default_options())
    monkeypatch.setattr(D, "RERUN_MAX_FAILED", rerun)
    monkeypatch.setattr(D, "CONJUGATE_ROOTS", True)
    ext, _ = solve_taut_set(robot, robot.lengths, cables, options=default_options(extended=True))
    assert not plain.complete and plain.outcomes["failed"] > 0
    assert ext.complete and ext.outcomes["failed"] == 0 and sum(ext.outcomes.values()) == ext.paths
    assert ext.certified == ext.outcomes["regular"] >= plain.certified
    assert ext.real >= plain.real and ext.admissible == plain.admissible
    monkeypatch.setattr(D, "STUDY_RETRACK", True)
    study, _ = solve_taut_set(robot, robot.lengths, cables, options=default_options())
    assert study.complete and study.outcomes["failed"] == 0 and sum(study.outcomes.values()) == study.paths
    assert study.certified == study.outcomes["regular"] >= ext.outcomes["regular"]
    assert study.real >= plain.real and study.admissible == ext.admissible
    assert study.retried.get("study", 0) > 0 and study.to_dict()["retried"] == study.retried
    monkeypatch.setattr(D, "STUDY_FIRST", True)  # the default: every path in Study parameters first
    first, _ = solve_taut_set(robot, robot.lengths, cables, options=default_options())
    assert first.complete and first.outcomes == study.outcomes and first.certified == study.certified
    assert (first.finite, first.real, first.admissible) == (study.finite, study.real, study.admissible)


def test_cli_extended_precision(capsys):
    import json

    from cdpr_algebra.cli.main import main

    assert main(["dgp", str(EXAMPLES / "seed000_test1.toml"), "--extended-precision", "--jobs", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["options"]["tracker"]["extended_residual"] is True and out["complete"] is True
    assert len(out["solutions"]) == 6


def test_crosscheck_compares_what_extended_precision_completes(capsys, monkeypatch):
    """`cdpr crosscheck` on Test 3's taut set {2, 4, 5}: the homotopy's account is incomplete in double precision
    (the taut system alone, without Study parameters), so the subproblem is not compared; with --extended-precision it is
    complete and agrees with the interval solver."""
    import json

    from cdpr_algebra.cli.main import main
    from cdpr_algebra.dgp import solve as D

    path = str(EXAMPLES / "seed000_test3.toml")
    monkeypatch.setattr(D, "STUDY_FIRST", False)
    monkeypatch.setattr(D, "STUDY_RETRACK", False)
    monkeypatch.setattr(D, "EXTENDED_MAX_FAILED", 0)  # failed paths not tracked again in double-double
    main(["crosscheck", path, "--taut", "2", "4", "5", "--jobs", "1", "--json"])
    plain = json.loads(capsys.readouterr().out)
    assert main(["crosscheck", path, "--taut", "2", "4", "5", "--jobs", "1", "--extended-precision", "--json"]) == 0
    ext = json.loads(capsys.readouterr().out)
    (p,), (e,) = plain["subproblems"], ext["subproblems"]
    assert p["agree"] is None and e["agree"] is True
