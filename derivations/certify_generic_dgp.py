"""Certify the stored generic DGP solution sets (``cdpr_algebra/data/dgp_generic_m{m}.json``) independently of
the literature, and record the certificates next to them (``dgp_generic_m{m}_completeness.json``).

Re-runnable, NOT a ``derive_*.py`` (randomized, minutes per m):

    python derivations/certify_generic_dgp.py --m 2 3 4 5 6          # trace test + monodromy from scratch
    python derivations/certify_generic_dgp.py --m 4 5 --phc --only phc  # PHCpack's blackbox (needs ``phc``)
    python derivations/certify_generic_dgp.py --m 4 --only trace --chart 20131  # W10 on a chart (m = 4 needs it)

Per m, three independent computations (each a section of the certificate; a run updates only the sections
it computes, and drops every old section when the stored set changed):

* ``trace_test`` -- the multiprojective trace test (:mod:`cdpr_algebra.homotopy.trace_test`) of the stored set
  W01 at its parameters p0: the additional witnesses W10 (the curve F(x; p0 + s (q0 - p0)) = 0 cut by a
  random hyperplane l(x) = 0, by monodromy, re-solved at other random l until the count agrees), then the
  trace of W01 x {0} + W10 along the pencil s l(x) = tau.  The test works in the 12 pose unknowns (p, u, v, w;
  ``--coordinates all`` for every unknown): they separate the solutions (checked on W01) and the tensions, which
  follow linearly from the pose, have poles along the curve that multiply the size of W10 (m = 6: 327 points
  in the pose coordinates, more than 1400 and still growing when stopped in all of them).  Recorded: the hashes of the set it certifies,
  q0, l, W10, gamma, eps, the trace and its relative size, the tolerance, every path outcome, the
  monodromy runs, the seed and the seconds.  ``count`` is the size of the certified set.  With ``--chart``, W10
  is found by monodromy on a random chart of projective space (zero off y0 and the pose) and mapped back: m = 4 has
  a witness point of norm 1.7e4 that monodromy in affine coordinates never reached (1887 points, trace 1.4e-3;
  on the chart 1888, trace 3e-12); the chart is recorded (``chart``).
* ``monodromy_from_scratch`` -- monodromy from ONE seed solution of a new random complex instance (the
  construction of ``solve_generic_dgp.py``) with NO target count, until ``--loops-no-progress`` (10)
  consecutive loops add nothing.  ``count_raw`` is the number of points the run returns, ``count`` the number of
  distinct solutions among them by a duplicate test that accounts for conditioning
  (:func:`cdpr_algebra.homotopy.trace_test.distinct_points`; monodromy's own fixed 1e-8 counts an
  ill-conditioned solution once per loop that finds it again: m = 3, seed 1, one solution of condition 6e9 came
  back 31 times).  The stored set is then moved to the new instance by parameter homotopies and matched against
  the set found there (``moved_unmatched`` must be 0: a stored point outside the found set would be a solution
  the run from scratch missed).
* ``phc`` (``--phc``, only where ``phc`` is installed) -- PHCpack's blackbox ``phc -b`` on a random complex
  instance of the m-cable system (the whole system, so also the solutions with some lam_i = 0, another
  component): mixed volume, regular solutions, those with every lam_i nonzero and those with some lam_i = 0,
  wall time, and PHCpack's solutions themselves.  The stored set is moved to the same instance by whole
  parameter homotopies with different gammas, combined as sets (a route's start-to-end correspondence is its own),
  and matched against PHCpack's solutions both ways, after a conditioning-aware de-duplication of each side;
  ``union_distinct`` counts the distinct solutions either side found.  ``--rematch`` redoes the matching from the
  recorded solutions without running ``phc``.  Run it alone and ``nice -n 19``: m = 4, 5 take an hour or more
  (m = 4: 2979 s; PHCpack found 215 regular solutions, all among the 216 moved stored points).

Exit status 0 when every computation that ran gave a definite answer (trace test passed, monodromy count equal
to the stored count), 1 otherwise.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "derivations"))

from cdpr_algebra.dgp.solve import fast_family, generic_path  # noqa: E402
from cdpr_algebra.homotopy.endgame import SolveOptions  # noqa: E402
from cdpr_algebra.homotopy.monodromy import MonodromyOptions, load_instance, monodromy_solve  # noqa: E402
from cdpr_algebra.homotopy.solve import solve_parameter_homotopy  # noqa: E402
from cdpr_algebra.homotopy.tracker import TrackerOptions  # noqa: E402
from cdpr_algebra.homotopy.projective import HomogenizedQuadratic  # noqa: E402
from cdpr_algebra.homotopy.trace_test import (TraceSliceSystem, TraceTestOptions,  # noqa: E402
                                              coinciding, complete_witnesses, compute_trace, distinct_points,
                                              chart_coordinates, slice_from_chart, slice_to_chart,
                                              verify_solution_completeness)

FORMAT = "cdpr_algebra.dgp_generic_completeness"
FORMAT_VERSION = 1


def certificate_path(m: int) -> Path:
    return generic_path(m).with_name(f"dgp_generic_m{m}_completeness.json")


def data_hash(parameters, solutions) -> str:
    """SHA-256 of the stored instance's numbers: parameters then solutions, complex128 little-endian, row-major."""
    h = hashlib.sha256()
    for a in (parameters, solutions):
        h.update(np.ascontiguousarray(np.asarray(a, dtype="<c16")).tobytes())
    return h.hexdigest()


def complex_record(a):
    """A complex array as JSON: {"re": [...], "im": [...]} (nested as the array)."""
    a = np.asarray(a, dtype=complex)
    return {"re": a.real.tolist(), "im": a.imag.tolist()}


def _match(A, B, tol=1e-6):
    """Rows of A with a row of B within tol (1 + |a|) (max-norm), and rows of B with a row of A."""
    if not len(A) or not len(B):
        return 0, 0
    d = np.max(np.abs(A[:, None, :] - B[None, :, :]), axis=2)
    close = d <= tol * (1 + np.max(np.abs(A), axis=1))[:, None]
    return int(close.any(axis=1).sum()), int(close.any(axis=0).sum())


def _move_stored(m, p_from, X, p_to, seed, runs=4):
    """The stored set moved to parameters p_to by up to ``runs`` whole gamma-trick parameter homotopies with
    different gammas (compiled tracker, the engine's projective retries), until the moved points number as many
    as the stored ones.  Each run's successful endpoints that do not coincide with another path's (a path that
    jumped) are solutions at p_to; a route's start-to-end correspondence is its own (another gamma may permute it,
    monodromy), so runs are combined as sets: the union of their endpoints, distinct.  Returns (those points,
    per-run outcome counts)."""
    fam = fast_family(m)
    found = np.zeros((0, fam.n), dtype=complex)
    runs_rec = []
    for r in range(runs):
        if len(found) >= len(X):
            break
        tr = solve_parameter_homotopy(fam, p_from, X, p_to, seed=seed + 7919 * r, gamma=True,
                                      options=SolveOptions(retry_mpmath=False)).track
        counts = {}
        for path in tr.paths:
            counts[path.status] = counts.get(path.status, 0) + 1
        ok = np.flatnonzero([path.status == "success" for path in tr.paths])
        E = np.array([tr.paths[i].endpoint for i in ok]).reshape(-1, fam.n)
        jumped = coinciding(fam, p_to, E, polish_condition=None)  # mask of the points in groups of 2 or more
        counts["coinciding"] = int(jumped.sum())
        found, _ = distinct_points(fam, p_to, np.concatenate([found, E[~jumped]]))
        counts["union"] = int(len(found))
        runs_rec.append(counts)
    return found, runs_rec


POSE = list(range(12))  # p, u, v, w: the tensions lam_i follow linearly from the pose (and have poles on the curve)
COORDINATES = {"pose": POSE, "all": None}


def trace_options():
    """The trace test's settings for the DGP sets: the W10 monodromy tracks with predictor tolerance 1e-4 (every
    point it adds is refined by Newton, so a coarser step only risks missing points, which the trace would show);
    the pencil paths with the engine's defaults, to tau = +-gamma (eps = 1): the trace's rounding noise does not grow
    with eps, while a single point's relative second difference grows like eps (m = 5, the same W10: at eps = 0.1,
    1.07e-11 against a smallest single-point signal of 1.6e-9, below the 1e-8 tolerance; at eps = 1, 1.5e-12
    against 1.6e-8).  The m = 2, 3, 6 certificates were made at eps = 0.1 (recorded in their options)."""
    return TraceTestOptions(solve=SolveOptions(tracker=TrackerOptions(predictor_tol=1e-4), retry_mpmath=False),
                            witness_loops_no_progress=5, confirm_loops_no_progress=3, confirmations=2, eps=1.0)


def run_trace_test(m, p, X, seed, coordinates, verbose=True, start=None, chart=None):
    """The trace test of the stored set; ``start``: None, or a dict {"W10": known points of W10 from an earlier
    run with the same seed (same q0 and l), "note": where they come from} (recorded as ``start_witnesses``);
    ``chart``: None, or the seed of the chart W10 is found on (recorded as ``chart``)."""
    fam = fast_family(m)
    o = trace_options()
    t0 = time.perf_counter()
    res = verify_solution_completeness(fam, p, X, seed=seed, options=o, verbose=verbose, coordinates=coordinates,
                                       start=None if start is None else start["W10"], chart=chart)
    tr = res.trace
    out = {"status": tr.status, "count": int(len(X)), "seed": seed, "q0": complex_record(res.q0),
           "l": complex_record(res.l),
           "coordinates": [int(c) for c in res.coordinates],
           "W10_count": int(len(res.W10)), "W10": complex_record(res.W10), "witnesses": res.witnesses,
           "trace": tr.to_dict(),
           "options": o.to_dict(), "seconds": time.perf_counter() - t0}
    if chart is not None:
        out["chart"] = {"seed": int(chart), "c": complex_record(res.chart),
                        "note": "W10 found by monodromy on this chart of projective space (zero off y0 and the "
                                "trace coordinates), mapped back; W10, l and the trace are in affine coordinates"}
    if start is not None:
        out["start_witnesses"] = {"count": int(len(start["W10"][0] if isinstance(start["W10"], tuple) else start["W10"])),
                                  "note": start["note"],
                                  "earlier_seconds": start.get("seconds")}
    if verbose:
        print(f"m = {m}: trace test {tr.status}: |W01| = {len(X)}, |W10| = {len(res.W10)}, relative trace "
              f"{tr.relative:.2e} (tol {tr.tol:.0e}; one point missing would give >= {tr.detection:.1e}), "
              f"{out['seconds']:.0f} s", flush=True)
    return out


def complex_from_record(d):
    """The complex array of :func:`complex_record`'s record."""
    return np.asarray(d["re"], dtype=float) + 1j * np.asarray(d["im"], dtype=float)


def resume_trace_test(m, p, X, prev, seed, grow=True, verbose=True):
    """Continue a recorded trace test (one that did not pass; with ``grow`` False also one that did): the recorded
    W10 (same seed, q0, l, coordinates) grown by :func:`complete_witnesses` rounds (unless ``grow`` is False), then
    the trace again with the current options.  The earlier runs stay in ``history``."""
    seed = prev.get("seed", seed)
    fam = fast_family(m)
    o = trace_options()
    t0 = time.perf_counter()
    cs = prev["coordinates"]
    q0, l = complex_from_record(prev["q0"]), complex_from_record(prev["l"])
    W10 = complex_from_record(prev["W10"]).reshape(prev["W10_count"], fam.n + 1)
    slice_ = TraceSliceSystem(fam, p, q0 - p, cs)
    gseed = seed + 1000 * (1 + len(prev.get("history", [])))
    if grow and "chart" in prev:  # grow on the recorded chart (see run_trace_test), then map back
        c = complex_from_record(prev["chart"]["c"])
        Wc, lc = slice_to_chart(W10, l, c)
        sc = TraceSliceSystem(HomogenizedQuadratic(fam, c), p, q0 - p, chart_coordinates(cs))
        Wc, lc, rec = complete_witnesses(sc, lc, Wc, o, seed=gseed, verbose=verbose)
        W, l = slice_from_chart(Wc, lc, c, cs)
    elif grow:
        W, l, rec = complete_witnesses(slice_, l, W10, o, seed=gseed, verbose=verbose)
    else:
        W, rec = W10, {"moves": [], "monodromy": [], "count": int(len(W10)), "note": "trace recomputed only"}
    tr = compute_trace(fam, p, q0, l, X, W, o, seed=seed, coordinates=cs)
    hist = prev.get("history", []) + [{"W10_count": prev["W10_count"], "status": prev["status"],
                                       "relative": prev["trace"]["relative"], "eps": prev["trace"].get("eps"),
                                       "detection": prev["trace"].get("detection"), "seconds": prev["seconds"],
                                       "witnesses": prev["witnesses"], "trace_outcomes": prev["trace"]["outcomes"]}]
    out = {**prev, "status": tr.status, "l": complex_record(l), "W10_count": int(len(W)), "W10": complex_record(W),
           "witnesses": rec,
           "trace": tr.to_dict(), "options": o.to_dict(), "seconds": time.perf_counter() - t0, "history": hist}
    if verbose:
        print(f"m = {m}: trace test (resumed from |W10| = {prev['W10_count']}) {tr.status}: |W01| = {len(X)}, "
              f"|W10| = {len(W)}, relative trace {tr.relative:.2e} (tol {tr.tol:.0e}; one point missing would give "
              f">= {tr.detection:.1e}), {out['seconds']:.0f} s", flush=True)
    return out


def run_monodromy(m, seed, loops_no_progress, p_stored, X_stored, verbose=True):
    from solve_generic_dgp import complex_rotation, regular_robot  # noqa: E402
    from cdpr_algebra.model.taut_equations import encode

    fam = fast_family(m)
    rng = np.random.default_rng(seed)
    R = complex_rotation(rng)
    pos = 0.3 * (rng.normal(size=3) + 1j * rng.normal(size=3))
    lam = rng.normal(size=m) + 1j * rng.normal(size=m)
    x0 = encode(pos, R, lam)
    base = regular_robot(m)
    guess = base + 0.3 * (np.abs(base) + 0.1) * (rng.normal(size=base.size) + 1j * rng.normal(size=base.size))
    o = MonodromyOptions(target_solutions_count=None, max_loops_no_progress=loops_no_progress, max_loops=400)
    res = monodromy_solve(fam, seed=seed, x0=x0, p_guess=guess, options=o)
    D, merged = distinct_points(fam, res.parameters, res.solutions)  # monodromy's own test is blind to conditioning
    out = {**res.to_dict(), "count_raw": int(len(res.solutions)), "count": int(len(D)), "merge": merged,
           "max_loops_no_progress": loops_no_progress, "target_solutions_count": None,
           "parameters": complex_record(res.parameters)}
    Y, counts = _move_stored(m, p_stored, X_stored, res.parameters, seed)
    a, b = _match(Y, D)
    # every stored point that arrives must be one of the points found (else the run from scratch missed it);
    # found points not reached are those whose stored path failed (every round), or reached twice by a retry
    out["stored_moved"] = {"paths": int(len(X_stored)), "outcomes": counts, "arrived": int(len(Y)),
                           "stored_matched": a, "moved_unmatched": int(len(Y) - a), "found_matched": b}
    if verbose:
        print(f"m = {m}: {res.summary_line()}; {len(D)} distinct after the conditioning-aware merge "
              f"(max cond {merged['max_condition']:.1e}); stored set moved there: {a} of {len(X_stored)} match, "
              f"{b} of {len(D)} found points matched", flush=True)
    return out


def run_phc(m, seed, timeout, p_stored, X_stored, verbose=True):
    import sympy as sp

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_homotopy import phc_run  # noqa: E402
    from solve_generic_dgp import regular_robot  # noqa: E402
    from cdpr_algebra.model.taut_equations import taut_family
    from cdpr_algebra.homotopy.systems import PolynomialSystem

    fam = taut_family(m)
    rng = np.random.default_rng(seed)
    base = regular_robot(m)
    p = base + 0.3 * (np.abs(base) + 0.1) * (rng.normal(size=base.size) + 1j * rng.normal(size=base.size))
    sub = {s: sp.Float(v.real, 17) + sp.Float(v.imag, 17) * sp.I for s, v in zip(fam.parameters, p)}
    inst = PolynomialSystem([sp.expand(e.xreplace(sub)) for e in fam.equations], fam.variables, (),
                            name=f"{fam.name}_instance")
    res = phc_run(inst, np.zeros(0), timeout=timeout)
    out = {"parameters": complex_record(p), "seed": seed, "timeout_seconds": timeout}
    if res is None:
        out["status"] = "phc not installed"
        return out
    out.update({"wall_seconds": res["wall"], "timeout": bool(res["timeout"]), "mixed_volume": res["paths"]})
    if res["timeout"]:
        out["status"] = "timeout"
        if verbose:
            print(f"m = {m}: phc -b stopped after {res['wall']:.0f} s (timeout)", flush=True)
        return out
    S = res["solutions"]
    out.update({"status": "finished", "regular": int(len(S)), "regular_real": res["real"],
                "solutions": complex_record(S)})
    out.update(phc_match(m, seed, out, p_stored, X_stored, verbose))
    if verbose:
        print(f"m = {m}: phc -b {res['wall']:.0f} s, mixed volume {res['paths']}, {len(S)} regular", flush=True)
    return out


def phc_match(m, seed, phc, p_stored, X_stored, verbose=True):
    """Compare PHCpack's regular solutions (recorded in ``phc``) with the stored set moved to PHCpack's instance:
    both refined by Newton and de-duplicated with the conditioning-aware test of
    :func:`cdpr_algebra.homotopy.trace_test.distinct_points` (so a path of the move that jumped onto another's
    endpoint shows as a missing point, not as a match), then matched both ways."""
    fam = fast_family(m)
    p = complex_from_record(phc["parameters"])
    S = complex_from_record(phc["solutions"]).reshape(-1, fam.n)
    lam = S[:, 12:12 + m]
    zero = np.any(np.abs(lam) <= 1e-8 * (1 + np.max(np.abs(S), axis=1))[:, None], axis=1)
    P, _ = distinct_points(fam, p, S[~zero])
    Y, counts = _move_stored(m, p_stored, X_stored, p, seed)
    D, _ = distinct_points(fam, p, Y)
    a, b = _match(D, P)
    rec = {"regular_all_lam_nonzero": int((~zero).sum()), "regular_some_lam_zero": int(zero.sum()),
           "phc_distinct": int(len(P)),
           "stored_moved": {"paths": int(len(X_stored)), "outcomes": counts, "arrived": int(len(Y)),
                            "distinct": int(len(D)), "stored_matched": a, "moved_unmatched": int(len(D) - a),
                            "phc_matched": b, "phc_unmatched": int(len(P) - b)},
           # distinct solutions of PHCpack's instance found by either side: both sides' points are regular solutions
           "union_distinct": int(len(D) + len(P) - b)}
    if verbose:
        print(f"m = {m}: PHCpack {len(P)} distinct solutions with every lam_i != 0 ({int(zero.sum())} with some "
              f"lam_i = 0); stored set moved there: {len(D)} distinct of {len(X_stored)}, {a} match a PHCpack "
              f"solution, {b} of PHCpack's {len(P)} matched; {len(D) + len(P) - b} distinct in the union", flush=True)
    return rec


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--m", type=int, nargs="+", default=[2, 3, 4, 5, 6], choices=[2, 3, 4, 5, 6])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--only", nargs="+", choices=["trace", "monodromy", "phc"], default=None,
                    help="sections to compute (default: trace and monodromy, plus phc with --phc)")
    ap.add_argument("--phc", action="store_true", help="also PHCpack's blackbox on a random complex instance")
    ap.add_argument("--phc-timeout", type=float, default=3 * 3600.0)
    ap.add_argument("--rematch", action="store_true",
                    help="with --only phc: match the recorded PHCpack solutions again, without running phc")
    ap.add_argument("--loops-no-progress", type=int, default=10)
    ap.add_argument("--resume", action="store_true",
                    help="continue a recorded trace test that failed or was undecided (grow its W10, trace again)")
    ap.add_argument("--retrace", action="store_true",
                    help="with --resume: recompute the trace only (with the current options; also of a test that "
                         "passed), the earlier trace kept in the record's history")
    ap.add_argument("--coordinates", choices=["pose", "all"], default="pose",
                    help="unknowns the trace test works in: the 12 pose unknowns (default; they separate the "
                         "solutions, checked) or all")
    ap.add_argument("--chart", type=int, default=None, metavar="SEED",
                    help="trace test: find W10 by monodromy on a random chart of projective space (this seed), where "
                         "witness points of very large norm are ordinary points (m = 4 needs it); the trace stays "
                         "in affine coordinates")
    ap.add_argument("--start-witnesses", type=Path, default=None,
                    help="trace test: start the W10 monodromy from the points of this .npz (arrays W10, note, "
                         "seconds, and l, the hyperplane they lie on, when it is not the seed's first), saved from "
                         "an earlier run with the same --seed and --coordinates (one --m)")
    args = ap.parse_args(argv)
    start = None
    if args.start_witnesses is not None:
        if len(args.m) != 1:
            ap.error("--start-witnesses needs exactly one --m")
        z = np.load(args.start_witnesses)
        start = {"W10": (z["W10"], z["l"]) if "l" in z else z["W10"], "note": str(z["note"]),
                 "seconds": float(z["seconds"]) if "seconds" in z else None}
    sections = set(args.only or ["trace", "monodromy"] + (["phc"] if args.phc else []))
    status = 0
    for m in args.m:
        path = generic_path(m)
        p, X, _ = load_instance(path)
        h = data_hash(p, X)
        cpath = certificate_path(m)
        cert = json.loads(cpath.read_text()) if cpath.exists() else {}
        if cert.get("stored_set", {}).get("data_sha256") != h:
            cert = {}  # a new stored set: every old section is void
        cert.update({"format": FORMAT, "format_version": FORMAT_VERSION, "m": m,
                     "stored_set": {"path": f"cdpr_algebra/data/{path.name}", "data_sha256": h,
                                    "file_sha256": hashlib.sha256(path.read_bytes()).hexdigest(),
                                    "count": int(len(X)), "unknowns": int(X.shape[1])},
                     "command": f"python derivations/certify_generic_dgp.py --m {m}"
                                + (f" --seed {args.seed}" if args.seed != 1 else "")
                                + (f" --chart {args.chart}" if args.chart is not None else "")})
        if "trace" in sections and args.resume and (args.retrace and "trace_test" in cert
                                                    or cert.get("trace_test", {}).get("status") in ("failed",
                                                                                                   "undecided")):
            cert["trace_test"] = resume_trace_test(m, p, X, cert["trace_test"], args.seed, grow=not args.retrace)
            status |= cert["trace_test"]["status"] != "passed"
        elif "trace" in sections:
            cert["trace_test"] = run_trace_test(m, p, X, args.seed, COORDINATES[args.coordinates],
                                                start=start, chart=args.chart)
            status |= cert["trace_test"]["status"] != "passed"
        if "monodromy" in sections:
            cert["monodromy_from_scratch"] = run_monodromy(m, args.seed, args.loops_no_progress, p, X)
            status |= cert["monodromy_from_scratch"]["count"] != len(X)
        if "phc" in sections and args.rematch:
            if "solutions" not in cert.get("phc", {}):
                print(f"m = {m}: no recorded PHCpack solutions to match (run --only phc first)", flush=True)
                status = 1
            else:
                cert["phc"].update(phc_match(m, args.seed, cert["phc"], p, X))
        elif "phc" in sections:
            cert["phc"] = run_phc(m, args.seed, args.phc_timeout, p, X)
        if "trace_test" in cert and cert["trace_test"]["status"] == "passed":
            cert["count"] = cert["trace_test"]["count"]
        else:
            cert.pop("count", None)
        cpath.write_text(json.dumps(cert, indent=1) + "\n", encoding="utf-8")
        print(f"m = {m}: written {cpath.relative_to(ROOT)}", flush=True)
    return int(status)


if __name__ == "__main__":
    raise SystemExit(main())
