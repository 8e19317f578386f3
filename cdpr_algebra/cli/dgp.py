"""``cdpr dgp``: every equilibrium of the robot at its cable lengths, every set of taut cables (Berti, Merlet and
Carricato 2016), by parameter homotopies; exit status 3 when a subproblem is not proven complete (with ``--settle``:
when an admissible equilibrium may be missing, the interval branch and prune having settled what it could)."""

from __future__ import annotations

import sys

from cdpr_algebra.model.errors import CdprInputError

from .common import INCOMPLETE, dgp_lengths, finite, json_text, print_incomplete


def add_parser(subparsers) -> None:
    dgp = subparsers.add_parser("dgp", help="direct geometrico-static problem: every equilibrium, every set of taut cables")
    dgp.add_argument("robot", help="robot file (.json or .toml)")
    dgp.add_argument("--lengths", nargs="+", type=finite("--lengths"), metavar="L",
                     help="cable lengths rho_1 .. rho_n (default: the robot file's)")
    dgp.add_argument("--jobs", type=int, default=None, help="parallel threads (default: all cores)")
    dgp.add_argument("--extended-precision", action="store_true",
                     help="Newton residuals in double-double wherever double precision stalls, also for the paths "
                          "that the Study run (which has them) leaves to the taut system; slower, and on the shipped "
                          "robots no fewer failed paths since every path is tracked in Study parameters first")
    dgp.add_argument("--mpmath-retry", action="store_true",
                     help="track up to 4 paths per subproblem run that every double-precision retry left failed "
                          "once more, in double-double (compiled, about 30 digits) wherever double precision fails "
                          "(slow: up to ~10 s a path; the name is historical: no mpmath); without the flag this "
                          "runs only for subproblems left with at most 2 failed paths")
    dgp.add_argument("--settle", action="store_true",
                     help="run the interval branch and prune on every incomplete subproblem: where it is complete it "
                          "proves the subproblem's admissible equilibria (and adds any the homotopy missed); the exit "
                          "status is then 0 when every admissible equilibrium is known (seconds to minutes per "
                          "subproblem; up to ~25 min on nearly degenerate taut sets with the default budget)")
    dgp.add_argument("--settle-max-boxes", type=int, default=None, metavar="N",
                     help="with --settle: at most N boxes per subproblem (the rest are undecided; default 20 million: "
                          "near-singular robots can take minutes per subproblem)")
    dgp.add_argument("--track-all", action="store_true",
                     help="track every taut set, also those the interval filter proves to hold no admissible "
                          "equilibrium (by default they are not tracked: their real inadmissible and complex "
                          "solutions are then not counted)")
    dgp.add_argument("--json", action="store_true", help="print JSON instead of a table")


def run(args) -> int:
    from cdpr_algebra.dgp.solve import AUTO_RESCUE_MAX_FAILED, dgp, dgp_table
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(args.robot)
    lengths = dgp_lengths(args, robot)
    if args.jobs is not None and args.jobs < 1:
        raise CdprInputError("--jobs", f"expected a number >= 1, got {args.jobs}")
    if args.settle_max_boxes is not None and args.settle_max_boxes < 1:
        raise CdprInputError("--settle-max-boxes", f"expected a number >= 1, got {args.settle_max_boxes}")

    def progress(sub, done, total):
        o = sub.outcomes
        what = f"skipped ({sub.skipped})" if sub.skipped else \
            (f"{sub.paths} paths ({o['regular']} regular, {o['singular']} singular, {o['at_infinity']} at infinity, "
             f"{o['failed']} failed), {sub.real} real, {sub.admissible} admissible"
             + (f", {len(sub.family.members)} admissible famil{'y' if len(sub.family.members) == 1 else 'ies'} of "
                "equilibria (not isolated)" if sub.family is not None and sub.family.members else ""))
        print(f"[{done}/{total}] taut {list(sub.taut)}: {what}, {sub.seconds:.2f} s", file=sys.stderr, flush=True)

    options = None
    if args.mpmath_retry or args.extended_precision:
        from dataclasses import replace

        from cdpr_algebra.dgp.solve import default_options

        options = replace(default_options(extended=args.extended_precision), retry_mpmath=args.mpmath_retry)
    result = dgp(robot, lengths, jobs=args.jobs, progress=progress, options=options, exclude=not args.track_all)
    records = ()
    if args.settle and not result.complete:
        from cdpr_algebra.bp.results import BPOptions
        from cdpr_algebra.comparison.settle import settle_incomplete

        def settle_progress(rec, done, total):
            print(f"[settle {done}/{total}] taut {list(rec.taut)}: {rec.outcome}: {rec.detail}"
                  + (f", {rec.added} equilibrium(s) the homotopy missed" if rec.added else "")
                  + f", {rec.seconds:.2f} s", file=sys.stderr, flush=True)

        bp_options = None if args.settle_max_boxes is None else BPOptions(max_boxes=args.settle_max_boxes)
        result, records = settle_incomplete(robot, result, lengths, bp_options, progress=settle_progress,
                                            jobs=args.jobs)
    if args.json:
        out = result.to_dict()
        if args.settle:
            out["settle"] = [r.to_dict() for r in records]
        print(json_text(out, indent=2))
    else:
        print(f"{robot.name}: DGP, lengths {', '.join(f'{v:g}' for v in lengths)}")
        print(dgp_table(result, robot.n))
    if args.settle and result.admissible_complete and not result.complete:
        print(f"cdpr: every admissible equilibrium is known: the interval branch and prune proved the admissible sets "
              f"of the {len(result.incomplete)} subproblem(s) whose homotopy account is incomplete (their complex "
              f"solution counts stay unproven)", file=sys.stderr)
        return 0
    if not result.complete:
        print_incomplete(result)
        # subproblems with at most AUTO_RESCUE_MAX_FAILED failed paths had that rescue already
        if any(s.failed_paths > AUTO_RESCUE_MAX_FAILED for s in result.incomplete) and not args.mpmath_retry:
            print("  (--mpmath-retry tracks up to 4 failed paths per subproblem again, in double-double where double "
                  "precision fails: up to ~10 s a path)", file=sys.stderr)
        # a set whose solutions come in families has a continuum of them: no branch and prune ends there
        if not args.settle and any(s.family is None for s in result.incomplete):
            print("  (--settle proves their admissible equilibria by interval branch and prune)", file=sys.stderr)
        return INCOMPLETE
    return 0
