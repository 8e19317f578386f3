"""``cdpr track``: follow the robot's equilibrium while its cables move (:mod:`cdpr_algebra.track.follow`).

    cdpr track ROBOT [--lengths L1 .. Ln] --to L1 .. Ln [--steps N] [--json] [--plot FILE] [--animate FILE]
    cdpr track ROBOT --trajectory FILE [--steps N] [--json] [--plot FILE]
    cdpr track ROBOT --expressions E1 .. En [--range T0 T1] [--steps N] [--json] [--plot FILE]

From the robot's stable equilibrium of lowest potential at the start lengths (``--lengths``, default the robot
file's), the lengths move straight to ``--to`` (t from 0 to 1), along the table of ``--trajectory`` (CSV rows
``t, rho_1 .. rho_n`` or JSON ``{"t": [..], "lengths": [[..], ..]}``), or as ``--expressions`` of t over ``--range``
(the syntax of ``cdpr cc --path``: sin, cos, pi, ...).  States are reported at ``--steps`` + 1
evenly spaced t (default 10 steps) and at every event (slack, taut, fold, jump, singular) between them.  A table
for people, or ``--json``: ``{"steps": [...], "events": [...], "status", ...}``; ``--plot`` saves tensions and the
lowest reduced-Hessian eigenvalue against t with the events marked; ``--animate`` an animation of the robot (GIF;
MP4 when ffmpeg is installed) with slack cables dashed.

Exit status: 0 when the whole trajectory was followed; 3 when tracking stopped (the reason on stderr: a branch
that ends at a singular wrench matrix, a fold with no landing found, ...) or when the default start is not proven
(the DGP at the start lengths is incomplete, so a stable equilibrium of lower potential may be missing; ``--settle``
proves the admissible equilibria of its incomplete subproblems by interval branch and prune, as ``cdpr dgp
--settle`` does); 2 on bad input.
"""

from __future__ import annotations

import sys

from cdpr_algebra.model.errors import CdprInputError

from .common import FIGURE_SUFFIXES, INCOMPLETE, as_flags, dgp_lengths, finite, json_text, output_file


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("track", help="follow the equilibrium while the cable lengths change")
    p.add_argument("robot", help="robot file (.json or .toml)")
    p.add_argument("--lengths", nargs="+", type=finite("--lengths"), metavar="L",
                   help="start lengths rho_1 .. rho_n (default: the robot file's)")
    p.add_argument("--to", nargs="+", type=finite("--to"), metavar="L", help="end lengths rho_1 .. rho_n")
    p.add_argument("--trajectory", metavar="FILE", help="a table of lengths against t (CSV or JSON)")
    p.add_argument("--expressions", nargs="+", metavar="EXPR",
                   help="the lengths as expressions of t, one per cable (e.g. '7.5 + 2*sin(pi*t)')")
    p.add_argument("--range", nargs=2, default=None, metavar=("T0", "T1"),
                   help="the range of t for --expressions (numbers or constants like pi/2; default 0 1)")
    p.add_argument("--steps", type=int, default=10, metavar="N", help="report states at N + 1 evenly spaced t")
    p.add_argument("--settle", action="store_true",
                   help="prove the admissible equilibria of the start DGP's incomplete subproblems by interval branch "
                        "and prune, so that the default start (stable, lowest potential) is decided")
    p.add_argument("--start-position", nargs=3, type=finite("--start-position"), metavar=("X", "Y", "Z"),
                   help="start from the equilibrium at this pose (the platform frame's origin, as the DGP prints it; "
                        "within 1e-3 of the robot's size: it is polished); default: the DGP's stable equilibrium of "
                        "lowest potential")
    p.add_argument("--start-angles", nargs=3, type=finite("--start-angles"), metavar=("PHI_X", "PHI_Y", "PHI_Z"),
                   help="orientation of the start pose, R = Rz Ry Rx, radians unless --degrees (default 0 0 0)")
    p.add_argument("--degrees", action="store_true", help="--start-angles in degrees")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.add_argument("--plot", metavar="FILE", help="save a picture of tensions and stability against t")
    p.add_argument("--animate", metavar="FILE", help="save an animation of the robot (.gif, or .mp4 with ffmpeg)")


def run(args) -> int:
    import numpy as np  # here, not with the module: ``cdpr --help`` imports every command's module
    from cdpr_algebra.model.robot import load_robot
    from cdpr_algebra.track.follow import track, tracking_table
    from cdpr_algebra.track.trajectory import load_trajectory, straight

    robot = load_robot(args.robot)
    if args.steps < 1:
        raise CdprInputError("--steps", f"expected a positive number of steps, got {args.steps}")
    given = [f for f, v in (("--to", args.to), ("--trajectory", args.trajectory), ("--expressions", args.expressions))
             if v is not None]
    if len(given) != 1:
        raise CdprInputError(given[1] if len(given) > 1 else "--to",
                             "give one of --to L1 .. Ln, --trajectory FILE or --expressions E1 .. En")
    if args.range is not None and args.expressions is None:
        raise CdprInputError("--range", "--range goes with --expressions (t runs from 0 to 1 along --to and as the "
                                        "--trajectory file says)")
    if args.expressions is not None:
        from cdpr_algebra.track.trajectory import from_expressions

        if args.lengths is not None:
            raise CdprInputError("--lengths", "the expressions give the start lengths")
        traj = from_expressions(args.expressions, args.range or ["0", "1"], robot.n)
    elif args.trajectory is not None:
        if args.lengths is not None:
            raise CdprInputError("--lengths", "the trajectory file gives the start lengths")
        traj = load_trajectory(args.trajectory, robot.n)
    else:
        if any(v <= 0 for v in args.to):
            raise CdprInputError("--to", "cable lengths must be > 0")
        traj = straight(dgp_lengths(args, robot), np.array(args.to), robot.n)
    if args.animate:
        output_file(args.animate, "--animate", (".gif", ".mp4"))
    if args.plot:
        output_file(args.plot, "--plot", FIGURE_SUFFIXES)
    samples = np.linspace(traj.start, traj.end, args.steps + 1)
    start = None
    if args.start_angles is not None and args.start_position is None:
        raise CdprInputError("--start-angles", "give --start-position with it")
    if args.start_position is not None:
        from cdpr_algebra.model.pose import matrix_from_angles

        angles = np.zeros(3) if args.start_angles is None else np.array(args.start_angles)
        start = (np.array(args.start_position), matrix_from_angles(*(np.radians(angles) if args.degrees else angles)))
    if args.settle and start is None:
        from cdpr_algebra.comparison.settle import settle_incomplete
        from cdpr_algebra.dgp.solve import dgp

        rho0 = traj(samples[0])
        start = dgp(robot, rho0, certify=False)
        if not start.complete:
            start, _ = settle_incomplete(robot, start, rho0)
    with as_flags({"start": "--start-position"}):
        res = track(robot, traj, samples, start=start)
    if args.json:
        print(json_text(res.to_dict()))
    else:
        print(tracking_table(res, robot))
    if args.plot:
        from cdpr_algebra.track.pictures import save_tracking_figure

        save_tracking_figure(res, robot, args.plot)
    if args.animate:
        from cdpr_algebra.track.pictures import save_tracking_animation

        save_tracking_animation(res, robot, args.animate)
    code = 0
    if res.start.get("dgp_complete") is False:
        print(f"cdpr: undecided start (exit status {INCOMPLETE}): {res.start['note']}; give --start-position to "
              "choose it", file=sys.stderr)
        code = INCOMPLETE
    if not res.complete:
        print(f"cdpr: tracking stopped (exit status {INCOMPLETE}): {res.reason}", file=sys.stderr)
        code = INCOMPLETE
    return code
