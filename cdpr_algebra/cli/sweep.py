"""``cdpr sweep``: solve a grid of cable lengths or poses on dask.distributed (:mod:`cdpr_algebra.sweep`).

    cdpr sweep ROBOT --vary NAME=START:STOP:NUM [--vary ...] --out DIR [--kind dgp|igp|cc] [--workers N]
               [--scheduler ADDRESS|FILE.json] [--batch N] [--no-certify] [--json]

NAME: ``rho1`` .. ``rhon`` (the DGP at every point, the other lengths from the robot file), or ``x``, ``y``, ``z``,
``phi_x``, ``phi_y``, ``phi_z`` (the IGP with assigned position for 3-cable robots; the cable configurations and
robustness radii for robots with more than 6 cables).  Default: a local cluster of one worker process per core
(``--workers``); ``--scheduler`` runs on an existing cluster.  Results: Parquet in DIR (``points/``,
``equilibria/``); rerunning the same command resumes.  Exit status: 0 when every point is solved and complete, 3
when some point failed (its error is recorded) or is incomplete (failed homotopy paths), 2 on bad input.
"""

from __future__ import annotations

import sys

from .common import INCOMPLETE, json_text


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("sweep", help="solve a grid of cable lengths or poses on a dask cluster")
    p.add_argument("robot", help="robot file (.json or .toml)")
    p.add_argument("--vary", action="append", required=True, metavar="NAME=START:STOP:NUM",
                   help="a grid axis (repeat for more axes)")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory (Parquet; a rerun resumes)")
    p.add_argument("--kind", choices=("dgp", "igp", "cc"), help="what to solve at each point (default from NAME)")
    p.add_argument("--workers", type=int, metavar="N", help="local worker processes (default: all cores)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="an existing dask scheduler (tcp://HOST:PORT or a "
                                                          "scheduler file .json)")
    p.add_argument("--batch", type=int, metavar="N", help="grid points per task (default 8 DGP, 32 IGP, 4 CC)")
    p.add_argument("--no-certify", action="store_true", help="skip the interval certificates (faster)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")


def run(args) -> int:
    from cdpr_algebra.model.errors import CdprInputError
    from cdpr_algebra.model.robot import load_robot
    from cdpr_algebra.sweep.grid import make_grid
    from cdpr_algebra.sweep.run import run_sweep, summary_counts

    robot = load_robot(args.robot)
    if args.workers is not None and args.workers < 1:
        raise CdprInputError("--workers", f"expected >= 1 workers, got {args.workers}")
    grid = make_grid(robot, args.vary, args.kind)
    res = run_sweep(robot, grid, args.out, scheduler=args.scheduler, workers=args.workers, batch=args.batch,
                    certify=not args.no_certify, progress=not args.json)
    counts = summary_counts(args.out)
    if args.json:
        print(json_text({**res.to_dict(), "written": counts}))
    else:
        print(f"{robot.name}: {grid.kind} sweep over {' x '.join(f'{a.name} ({len(a.values)})' for a in grid.axes)}"
              f" = {grid.size} points; solved now {res.solved}, resumed {res.resumed}; in {args.out}: "
              f"{counts['points']} points, {counts['equilibria']} equilibria, {counts['errors']} errors, "
              f"{counts['incomplete']} incomplete; {res.seconds:.3g} s")
    if counts["errors"] or counts["incomplete"] or counts["points"] < grid.size:
        print(f"cdpr: sweep incomplete (exit status {INCOMPLETE}): {counts['errors']} point(s) with an error, "
              f"{counts['incomplete']} incomplete (see the 'error' and 'complete' columns of points/)", file=sys.stderr)
        return INCOMPLETE
    return 0
