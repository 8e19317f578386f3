"""Wall time of the complete DGP (every set of taut cables) on seed 000 Test 1 (target <= 1 s) and, when the
generic sets for m = 4 .. 6 are stored, Test 3 (63 subproblems, target <= 10 s on 2 cores).

    python -m benchmarks.bench_dgp [--repeat 3] [--jobs N] [--no-test3] [--test2] [--profile] [--phc] [--phc-test3]
                                   [--phc-timeout S] [--track-all] [--extended-precision]

``--extended-precision`` runs the DGP with Newton residuals in double-double where double precision stalls
(``dgp.solve.default_options(extended=True)``, in the profile runs too).

``--track-all`` tracks every taut set (``dgp(exclude=False)``), also those the interval filter proves to hold no
admissible equilibrium (by default they are not tracked; the summary counts them as "excluded").

``--profile`` adds, per test, one serial run under cProfile: its top lines by own time, the slowest subproblems and
the path counters (issue 19: every change shows where the time went).

``--phc`` also solves the homotopy subproblems (m >= 2) of Test 1 with PHCpack's blackbox (``phc -b``, Debian
package ``phcpack``) in the same run, on the same normalized equations (:func:`cdpr_algebra.model.taut_equations.taut_family`
at the robot's parameters), next to our time for that subproblem alone (median of ``--repeat``, one thread);
``--phc-test3`` does the same for the first subproblem of each m = 2..6 of Test 3 (each PHCpack run stopped
after ``--phc-timeout`` seconds, default 1800).

The first run of each robot also builds and compiles the families (reported separately as "first run");
the median is over the following runs, with the CPU time of all threads per wall second over them ("cores busy":
2.00 = both cores computing the whole time; below that, waits: the GIL, or the last subproblem running alone).
Peak memory (ru_maxrss of this process: subproblems run in threads) is printed.  Before/after comparisons with an
earlier revision on the same machine: ``python -m benchmarks.bench_against REV`` (interleaved runs).
"""

from __future__ import annotations

import argparse
import resource
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT)]

from cdpr_algebra.dgp.normalization import normalized_problem  # noqa: E402
from cdpr_algebra.dgp.solve import available_m, dgp  # noqa: E402
from cdpr_algebra.homotopy.endgame import EndgameOptions  # noqa: E402
from cdpr_algebra.model.robot import load_robot  # noqa: E402
from timing import machine  # noqa: E402


def bench(path, repeat, jobs, exclude=True, options=None):
    robot = load_robot(path)
    t0 = time.perf_counter()
    res = dgp(robot, jobs=jobs, exclude=exclude, options=options)
    first = time.perf_counter() - t0
    times = []
    cpu0 = time.process_time()
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = dgp(robot, jobs=jobs, exclude=exclude, options=options)
        times.append(time.perf_counter() - t0)
    busy = (time.process_time() - cpu0) / max(sum(times), 1e-9)  # CPU seconds of all threads per wall second
    counts = {m: len(res.by_m(m)) for m in range(1, 7)}
    skipped = sum(1 for s in res.subproblems if s.skipped and s.excluded is None)
    excluded = sum(1 for s in res.subproblems if s.excluded is not None)
    o = res.outcomes()
    paths = sum(s.paths for s in res.subproblems)
    print(f"{robot.name}: first run {first:.2f} s, median {statistics.median(times):.2f} s "
          f"(min {min(times):.2f}, max {max(times):.2f}, {repeat} runs) "
          f"(jobs={jobs}, {busy:.2f} cores busy on average); {len(res.solutions)} admissible ({', '.join(f'm={m}: {c}' for m, c in counts.items() if c)}), "
          f"{len(res.stable)} stable; {len(res.subproblems)} subproblems ({skipped} skipped, {excluded} excluded "
          f"by the interval filter, "
          f"{len(res.incomplete)} incomplete), {paths} paths: {o['regular']} regular, {o['singular']} singular, "
          f"{o['at_infinity']} at infinity, {o['failed']} failed; "
          f"{sum(s.certified or 0 for s in res.subproblems)} endpoints certified, "
          f"{sum(sum(s.uncertified.values()) for s in res.subproblems)} not", flush=True)


def phc_compare(path, cable_sets, repeat, timeout):
    """Per subproblem: our wall time (solve_taut_set, one thread, median of ``repeat``) and PHCpack's blackbox."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_homotopy import phc_run

    from cdpr_algebra.dgp.solve import solve_taut_set
    from cdpr_algebra.model.taut_sets import lengths_and_taut_sets
    from cdpr_algebra.model.taut_equations import taut_family

    robot = load_robot(path)
    rho, _ = lengths_and_taut_sets(robot)
    for cables in cable_sets:
        solve_taut_set(robot, rho, cables)  # warm-up (loads the generic set)
        ts = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            sub, sols = solve_taut_set(robot, rho, cables)
            ts.append(time.perf_counter() - t0)
        target = normalized_problem(robot, rho, cables)[0]
        res = phc_run(taut_family(len(cables)), target, timeout=timeout)
        taut = [c + 1 for c in cables]
        ours = (f"ours {statistics.median(ts):.3f} s ({sub.paths} paths, {sub.finite} finite, {sub.real} real, "
                f"{sub.admissible} admissible, {sub.outcomes['at_infinity']} at infinity, {sub.failed_paths} failed)")
        if res is None:
            print(f"{robot.name} taut {taut}: {ours}; phc: not installed (apt-get install -y phcpack)", flush=True)
        elif res["timeout"]:
            print(f"{robot.name} taut {taut}: {ours}; phc -b: stopped after {res['wall']:.0f} s", flush=True)
        else:
            # PHCpack solves the whole system: it also finds the solutions with a zero tension (lam_i = 0: an
            # equilibrium of fewer taut cables with cable i exactly at its length, a separate component that our
            # generic sets leave out, as the published generic counts do; the DGP reports them in the smaller set)
            X = res["solutions"]
            zero = int(np.sum(np.min(np.abs(X[:, 12:]), axis=1) <= 1e-8)) if len(X) else 0
            print(f"{robot.name} taut {taut}: {ours}; phc -b {res['wall']:.1f} s (mixed volume {res['paths']}, "
                  f"{res['regular']} regular, {res['real']} real; {zero} of them with a zero tension)", flush=True)


PHASES = (("phase 1, t = 1 -> 0.1", "phase1"), ("re-tracks in the chart, t = 1 -> 0.1", "phase1_chart"),
          ("finish t = 0.1 -> 0", "to0"), ("finish in the chart", "to0_chart"),
          ("endgame samples", "samples"), ("endgame samples in the chart", "samples_chart"),
          ("Cauchy loops", "loops"), ("Cauchy loops in the chart", "loops_chart"),
          ("detours around phase-1 failures", "detour"), ("detours in the chart", "detour_chart"),
          ("Study parameters, t = 1 -> 0.1", "phase1_study"), ("finish in Study parameters", "to0_study"),
          ("endgame samples in Study parameters", "samples_study"), ("Cauchy loops in Study parameters", "loops_study"),
          ("detours in Study parameters", "detour_study"))


TE = EndgameOptions().endgame_start


class _PhaseCounter:
    """Seconds, steps and calls of the compiled tracker per phase of the pipeline, told apart by the segment's ends
    (t_a = 1: phase 1, the first leg of a detour included; t_b = 0: the finish; |t_a| = |t_b|: a Cauchy loop chord;
    other complex ends, or a real segment that ends at the endgame start: a detour of the homotopy's detour retry;
    else an endgame sample) and by whether the homotopy is in a projective chart or in Study parameters: wraps
    ``compiled.track_segment_compiled`` while in use."""

    def __enter__(self):
        import numpy as np

        from cdpr_algebra.dgp.study_retrack import FastStudySystem
        from cdpr_algebra.homotopy import compiled

        self.acc = {}
        self._mod, self._orig = compiled, compiled.track_segment_compiled

        def counted(hom, x0, t_a, t_b, o, h0=None):
            t0 = time.perf_counter()
            r = self._orig(hom, x0, t_a, t_b, o, h0)
            ta, tb = complex(np.atleast_1d(t_a)[0]), complex(np.atleast_1d(t_b)[0])
            kind = ("phase1" if abs(ta - 1) < 1e-12 else "to0" if tb == 0
                    else "loops" if abs(abs(ta) - abs(tb)) < 1e-12
                    else "detour" if ta.imag or tb.imag or (tb == TE and ta.real > TE) else "samples")
            if getattr(hom, "chart", None) is not None:
                kind += "_chart"
            elif isinstance(getattr(hom, "system", None), FastStudySystem):
                kind += "_study"  # dgp.study_retrack: the first run of every path, and re-tracks
            sec, steps, calls = self.acc.get(kind, (0.0, 0, 0))
            self.acc[kind] = (sec + time.perf_counter() - t0, steps + int(r.steps.sum()), calls + 1)
            return r

        compiled.track_segment_compiled = counted
        return self

    def __exit__(self, *exc):
        self._mod.track_segment_compiled = self._orig

    def lines(self, paths: int):
        total = sum(v[1] for v in self.acc.values())
        out = [f"  tracker by phase ({total} steps, {total / max(paths, 1):.0f} per path):"]
        for label, key in PHASES:
            if key in self.acc:
                sec, steps, calls = self.acc[key]
                out.append(f"    {label:38s} {sec:7.2f} s  {steps:9d} steps  {calls:6d} calls")
        return out


def profile_run(path, top: int = 12, exclude: bool = True, options=None):
    """One serial run of every subproblem under cProfile (the threads of ``dgp`` hide from it): the profile's top
    lines by own time, the five slowest subproblems, the path counters and the tracker's seconds and steps per
    phase (:class:`_PhaseCounter`), so a change shows where time went; ``options``: the DGP's (default: its own)."""
    import cProfile
    import io
    import pstats

    from cdpr_algebra.dgp.solve import solve_taut_set
    from cdpr_algebra.model.taut_sets import lengths_and_taut_sets

    robot = load_robot(path)
    rho, sets = lengths_and_taut_sets(robot)
    solve_taut_set(robot, rho, sets[-1], options=options)  # compile / load outside the profile
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    with _PhaseCounter() as phases:
        prof.enable()
        subs = [solve_taut_set(robot, rho, c, options=options, exclude=exclude)[0] for c in sets]
        prof.disable()
    wall = time.perf_counter() - t0
    buf = io.StringIO()
    pstats.Stats(prof, stream=buf).sort_stats("tottime").print_stats(top)
    lines = [ln for ln in buf.getvalue().splitlines() if ln.strip()]
    start = next(i for i, ln in enumerate(lines) if ln.lstrip().startswith("ncalls"))
    print(f"{robot.name}: profile of one serial run ({wall:.2f} s under the profiler), top {top} by own time:")
    for ln in lines[start:start + top + 1]:
        print("   " + ln[:150])
    slow = sorted(subs, key=lambda s: -s.seconds)[:5]
    print("  slowest subproblems: " + "; ".join(f"{list(s.taut)} {s.seconds:.2f} s ({s.paths} paths, "
                                                  f"{s.outcomes.get('failed', 0)} failed)" for s in slow))
    paths = sum(s.paths for s in subs)
    failed = sum(s.outcomes.get("failed", 0) for s in subs)
    print(f"  counters: {len(subs)} subproblems, {paths} paths, {failed} failed, "
          f"{sum(s.outcomes.get('singular', 0) for s in subs)} singular, "
          f"{sum(s.outcomes.get('at_infinity', 0) for s in subs)} at infinity", flush=True)
    for ln in phases.lines(paths):
        print(ln)


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=None)
    ap.add_argument("--no-test3", action="store_true", help="Test 1 only")
    ap.add_argument("--test2", action="store_true", help="also Test 2 (63 subproblems; published 187 s single core)")
    ap.add_argument("--phc", action="store_true", help="also PHCpack's blackbox on Test 1's homotopy subproblems")
    ap.add_argument("--phc-test3", action="store_true", help="also PHCpack on one subproblem per m of Test 3")
    ap.add_argument("--phc-timeout", type=float, default=1800.0)
    ap.add_argument("--profile", action="store_true", help="also one serial run of each test under cProfile: the "
                                                          "top lines, the slowest subproblems, path counters")
    ap.add_argument("--extended-precision", action="store_true", help="Newton residuals in double-double where double "
                    "precision stalls (dgp.solve.default_options(extended=True), cdpr dgp --extended-precision)")
    ap.add_argument("--track-all", action="store_true", help="track every taut set (no exclusion by the interval "
                                                             "filter), as before the sixth session")
    args = ap.parse_args(argv)
    ex = not args.track_all
    opts = None
    if args.extended_precision:
        from cdpr_algebra.dgp.solve import default_options

        opts = default_options(extended=True)
    print(machine())
    print(f"stored generic sets: m = {available_m()}")
    bench(ROOT / "examples" / "seed000_test1.toml", args.repeat, args.jobs, ex, opts)
    if args.profile:
        profile_run(ROOT / "examples" / "seed000_test1.toml", exclude=ex, options=opts)
    if args.test2:
        bench(ROOT / "examples" / "seed000_test2.toml", args.repeat, args.jobs, ex, opts)
        if args.profile:
            profile_run(ROOT / "examples" / "seed000_test2.toml", exclude=ex, options=opts)
    if args.no_test3:
        print("Test 3: not run (--no-test3)")
    elif {4, 5, 6} <= set(available_m()):
        bench(ROOT / "examples" / "seed000_test3.toml", args.repeat, args.jobs, ex, opts)
        if args.profile:
            profile_run(ROOT / "examples" / "seed000_test3.toml", exclude=ex, options=opts)
    else:
        print("Test 3: skipped (generic sets for m = 4, 5, 6 not all stored)")
    if args.phc:
        phc_compare(ROOT / "examples" / "seed000_test1.toml", [(0, 1), (0, 2), (1, 2), (0, 1, 2)], args.repeat,
                    args.phc_timeout)
    if args.phc_test3:
        phc_compare(ROOT / "examples" / "seed000_test3.toml", [tuple(range(m)) for m in range(2, 7)], args.repeat,
                    args.phc_timeout)
    self_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(f"peak memory: {self_kb / 1024:.0f} MiB")


if __name__ == "__main__":
    main()
