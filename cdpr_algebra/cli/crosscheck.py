"""``cdpr crosscheck``: homotopy DGP against the interval branch and prune, subproblem by subproblem (issue 8).

    cdpr crosscheck ROBOT [--lengths L1 .. Ln] [--taut C1 .. Cm] [--max-m M] [--json]
    cdpr crosscheck ROBOT [--lengths L1 .. Ln] --against FILE [--json]
    cdpr crosscheck ROBOT [--lengths L1 .. Ln] --taut C1 .. Cm --roots FILE [--json]

With ``--against``: another solver's results (JSON ``{"solver", "subproblems": [{"taut", "count", "boxes"}]}`` or
text lines ``1 2 3 ; [lo, hi] [lo, hi] [lo, hi]``, :mod:`cdpr_algebra.comparison.external`) against our certified
DGP, taut set by taut set; exit status 1 when some subproblem disagrees, 3 when some could not be compared.

With ``--roots``: another solver's complex roots of the taut set's equations (those of ``cdpr export --format phc``:
PHCpack's output file of ``phc -b``, or JSON ``{"solver", "variables", "roots"}``,
:mod:`cdpr_algebra.comparison.roots`) matched one to one with our proven roots; exit status 1 when they differ
definitely (a proven root on one side only), 3 when not compared.

Without ``--taut``: every set of m = 1 .. min(n, 6, M) taut cables; with it, that one set (cable numbers from 1).
Prints a table (one row per subproblem: both admissible counts, the interval solver's undecided boxes, agree /
NO / not compared, times) followed by every disagreement with the solutions involved, every subproblem not
compared with the reason, and a summary line counting agree / disagree / not compared; ``--json`` gives
:meth:`cdpr_algebra.comparison.compare.CrosscheckResult.to_dict` (per subproblem ``"agree": true | false | null`` and ``"compared"``,
the reason).  Progress goes to stderr.

Exit status (:func:`cdpr_algebra.comparison.compare.exit_status`): 0 when every subproblem was compared and agrees; 1 when some
subproblem disagrees; 3 when none disagrees but some subproblem was not compared (a solver skipped it or left it
incomplete: homotopy failed paths, undecided interval boxes); 2 on bad input.
"""

from __future__ import annotations

import sys

from cdpr_algebra.model.errors import CdprInputError

from .common import INCOMPLETE, finite, json_text


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("crosscheck", help="compare the homotopy DGP with the interval branch and prune")
    p.add_argument("robot", help="robot file (.json or .toml)")
    p.add_argument("--lengths", nargs="+", type=finite("--lengths"), metavar="L",
                   help="cable lengths rho_1 .. rho_n (default: the robot file's)")
    p.add_argument("--taut", nargs="+", type=int, metavar="C", help="only this set of taut cables (numbers from 1)")
    p.add_argument("--max-m", type=int, default=None, metavar="M", help="largest number of taut cables (default 6)")
    p.add_argument("--against", metavar="FILE", help="another solver's results (JSON or text boxes, see "
                                                     "cdpr_algebra.comparison.external) instead of our interval solver")
    p.add_argument("--roots", metavar="FILE", help="another solver's complex roots of the --taut set's equations "
                                                   "(PHCpack's output of `cdpr export --format phc`, or JSON; see "
                                                   "cdpr_algebra.comparison.roots)")
    p.add_argument("--jobs", type=int, default=None,
                   help="threads for the interval searches (default: all cores; the result does not depend on it)")
    p.add_argument("--extended-precision", action="store_true",
                   help="the homotopy side with Newton residuals in double-double where double precision stalls (as "
                        "cdpr dgp --extended-precision): fewer subproblems left 'not compared', about twice its time")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")


def run(args) -> int:
    import numpy as np  # here, not with the module: ``cdpr --help`` imports every command's module
    from cdpr_algebra.comparison.compare import crosscheck, crosscheck_table, exit_status
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(args.robot)
    if args.lengths is not None:
        if len(args.lengths) != robot.n:
            raise CdprInputError("--lengths", f"expected {robot.n} cable lengths, got {len(args.lengths)}")
        if any(v <= 0 for v in args.lengths):
            raise CdprInputError("--lengths", "cable lengths must be > 0")
        lengths = np.array(args.lengths)
    elif robot.lengths is not None:
        lengths = robot.lengths
    else:
        raise CdprInputError("--lengths", "no cable lengths: the robot file has none and --lengths is not given")
    sets = None
    if args.taut is not None:
        if len(set(args.taut)) != len(args.taut):
            raise CdprInputError("--taut", f"repeated cable number in {args.taut}")
        bad = [c for c in args.taut if not 1 <= c <= robot.n]
        if bad:
            raise CdprInputError("--taut", f"cable numbers must be in 1 .. {robot.n}, got {bad[0]}")
        if len(args.taut) > 6:
            raise CdprInputError("--taut", f"at most 6 taut cables, got {len(args.taut)}")
        sets = [tuple(sorted(c - 1 for c in args.taut))]
    if args.max_m is not None and (args.taut is not None or args.against is not None or args.roots is not None):
        raise CdprInputError("--max-m", "--max-m limits the taut sets of a whole cross-check: not with --taut, "
                                        "--against or --roots")
    max_m = 6 if args.max_m is None else args.max_m
    if max_m < 1:
        raise CdprInputError("--max-m", f"expected a number >= 1, got {max_m}")

    if args.against is not None:
        if args.roots is not None:
            raise CdprInputError("--roots", "give either --against or --roots, not both")
        return _against(args, robot, lengths)
    if args.roots is not None:
        return _roots(args, robot, lengths, sets)

    def progress(c, done, total):
        h = "-" if c.homotopy is None else c.homotopy
        what = {True: "agree", False: "DISAGREE", None: c.compared}[c.agree]
        print(f"[{done}/{total}] taut {list(c.taut)}: homotopy {h}, interval {c.interval} ({c.undecided} undecided, "
              f"{c.interval_boxes} boxes), {what}, "
              f"{c.homotopy_seconds:.2f} s + {c.interval_seconds:.2f} s", file=sys.stderr, flush=True)

    if args.jobs is not None and args.jobs < 1:
        raise CdprInputError("--jobs", f"expected a number >= 1, got {args.jobs}")
    result = crosscheck(robot, lengths, sets=sets, max_m=max_m, progress=progress, jobs=args.jobs,
                        extended=args.extended_precision)
    if args.json:
        print(json_text(result.to_dict(), indent=2))
    else:
        print(f"{robot.name}: cross-check homotopy / interval, lengths {', '.join(f'{v:g}' for v in lengths)}")
        print(crosscheck_table(result))
    code = exit_status(result)
    if code == 3:
        print(f"cdpr crosscheck: incomplete: {len(result.not_compared)} subproblem(s) not compared: "
              + ", ".join(str(list(c.taut)) for c in result.not_compared), file=sys.stderr)
    return code


def _against(args, robot, lengths) -> int:
    from cdpr_algebra.comparison.compare import exit_status
    from cdpr_algebra.comparison.external import crosscheck_against, external_table

    if args.taut is not None:
        raise CdprInputError("--taut", "with --against, the taut sets are those of the results file")

    def progress(c, done, total):
        what = {True: "agree", False: "DISAGREE", None: "not compared"}[c.agree]
        print(f"[{done}/{total}] taut {list(c.taut)}: theirs {c.theirs}, ours {c.ours}, {what}", file=sys.stderr,
              flush=True)

    result = crosscheck_against(robot, lengths, args.against, progress=progress)
    if args.json:
        print(json_text(result.to_dict(), indent=2))
    else:
        print(f"{robot.name}: {result.solver} against cdpr_algebra, lengths {', '.join(f'{v:g}' for v in lengths)}")
        print(external_table(result))
    code = exit_status(result)  # the same rule: 1 on a disagreement, 3 when something was not compared
    if code:
        print(f"cdpr crosscheck: {len(result.disagreements)} subproblem(s) disagree, {len(result.not_compared)} not "
              "compared: " + ", ".join(str(list(c.taut)) for c in result.disagreements + result.not_compared),
              file=sys.stderr)
    return code


def _roots(args, robot, lengths, sets) -> int:
    from cdpr_algebra.comparison.roots import compare_roots, roots_report

    if sets is None:
        raise CdprInputError("--taut", "--roots compares one taut set: give its cables with --taut")
    c = compare_roots(robot, lengths, sets[0], args.roots)
    if args.json:
        print(json_text(c.to_dict(), indent=2))
    else:
        print(f"{robot.name}: lengths {', '.join(f'{v:g}' for v in lengths)}")
        print(roots_report(c))
    if c.agree is None:
        print(f"cdpr crosscheck: {c.compared}", file=sys.stderr)
    return {True: 0, False: 1, None: INCOMPLETE}[c.agree]
