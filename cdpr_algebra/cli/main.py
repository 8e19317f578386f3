"""Command line: ``cdpr`` (also ``python -m cdpr_algebra``), a thin layer over the library.

    cdpr igp ROBOT --orientation PHI_X PHI_Y PHI_Z [--degrees] [--exact] [--json]
    cdpr igp ROBOT --position X Y Z [--all] [--json]
    cdpr dgp ROBOT [--lengths L1 .. Ln] [--jobs N] [--mpmath-retry] [--json]
    cdpr plot ROBOT [--lengths L1 .. Ln] [--out FILE.png|.svg] [--jobs N]     (see cli_plot.py)
    cdpr cc ROBOT --position X Y Z [--angles ..] [--configuration ..] [--ball R] [--uncertainty DA DB DRHO] [--json]
                                                                               (see cli_cc.py)
    cdpr crosscheck ROBOT [--lengths L1 .. Ln] [--taut C1 .. Cm] [--json]     (see cli_crosscheck.py)

Exit status: 0 on success, 2 on bad input (one line on stderr naming the field and the problem), 3 when the
result is incomplete (``dgp``: some subproblem has failed paths or regular endpoints without a Krawczyk
certificate, so equilibria may be missing there; the subproblems and why are named on stderr).
"""

from __future__ import annotations

import argparse
import json
import math
import sys

import numpy as np

from cdpr_algebra.model.errors import CdprInputError

INCOMPLETE = 3  # exit status: a result not proven complete (failed paths, uncertified endpoints), said on stderr


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit status 2
        self.exit(2, f"{self.prog}: error: {message}\n")


def _finite(name):
    def conv(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name}: expected a number, got {text!r}") from None
        if not math.isfinite(v):
            raise argparse.ArgumentTypeError(f"{name}: expected a finite number, got {text!r}")
        return v
    return conv


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="cdpr", description="Equilibria of underconstrained cable-driven parallel robots.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    igp = sub.add_parser("igp", help="inverse geometrico-static problem of a 3-cable robot (seed 004)")
    igp.add_argument("robot", help="robot file (.json or .toml)")
    group = igp.add_mutually_exclusive_group(required=True)
    group.add_argument("--orientation", nargs=3, type=_finite("--orientation"), metavar=("PHI_X", "PHI_Y", "PHI_Z"),
                       help="assigned orientation, R = Rz(phi_z) Ry(phi_y) Rx(phi_x) (radians unless --degrees)")
    group.add_argument("--position", nargs=3, type=_finite("--position"), metavar=("X", "Y", "Z"),
                       help="assigned position of the centre of mass G (world frame)")
    igp.add_argument("--degrees", action="store_true", help="orientation angles in degrees")
    igp.add_argument("--exact", action="store_true",
                     help="exact rational arithmetic (assigned orientation; angles must give an exact rotation: "
                          "multiples of 90 degrees)")
    igp.add_argument("--all", action="store_true", help="also list complex solutions (assigned position)")
    igp.add_argument("--json", action="store_true", help="print JSON instead of a table")
    dgp = sub.add_parser("dgp", help="direct geometrico-static problem: every equilibrium, every set of taut cables")
    dgp.add_argument("robot", help="robot file (.json or .toml)")
    dgp.add_argument("--lengths", nargs="+", type=_finite("--lengths"), metavar="L",
                     help="cable lengths rho_1 .. rho_n (default: the robot file's)")
    dgp.add_argument("--jobs", type=int, default=None, help="parallel threads (default: all cores)")
    dgp.add_argument("--mpmath-retry", action="store_true",
                     help="track up to 4 paths per subproblem that fail in double precision again in arbitrary "
                          "precision (slow: seconds to minutes per path)")
    dgp.add_argument("--json", action="store_true", help="print JSON instead of a table")
    from . import plot as cli_plot

    cli_plot.add_parser(sub)
    from . import cc as cli_cc

    cli_cc.add_parser(sub)
    from . import crosscheck as cli_crosscheck

    cli_crosscheck.add_parser(sub)
    return p


def _exact_rotation(angles_deg):
    import sympy as sp

    mats = []
    for axis, a in zip("xyz", angles_deg):
        q, r = divmod(a, 90.0)
        if r != 0:
            raise CdprInputError("--orientation", "--exact needs angles that are multiples of 90 degrees")
        c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][int(q) % 4]
        if axis == "x":
            mats.append(sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]]))
        elif axis == "y":
            mats.append(sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]]))
        else:
            mats.append(sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]]))
    return mats[2] * mats[1] * mats[0]


def _run_igp(args) -> int:
    from cdpr_algebra.model.pose import matrix_from_angles
    from cdpr_algebra.model.robot import load_robot
    from cdpr_algebra.report.tables import igp_table

    robot = load_robot(args.robot)
    if args.orientation is not None:
        from cdpr_algebra.igp.orientation import igp_orientation

        angles = np.array(args.orientation)
        if args.exact:
            deg = angles if args.degrees else np.degrees(angles)
            result = igp_orientation(robot, _exact_rotation(deg), exact=True)
        else:
            rad = np.radians(angles) if args.degrees else angles
            result = igp_orientation(robot, matrix_from_angles(*rad))
    else:
        if args.exact:
            raise CdprInputError("--exact", "exact mode of the CLI is for the IGP with assigned orientation")
        from cdpr_algebra.igp.position import igp_position

        result = igp_position(robot, np.array(args.position))
    if args.json:
        print(json.dumps(result.to_dict(include_complex=args.all), indent=2))
    else:
        print(f"{robot.name}: IGP with assigned {result.problem}")
        print(igp_table(result, include_complex=args.all))
    return 0


def _dgp_lengths(args, robot) -> np.ndarray:
    """The DGP's cable lengths: ``--lengths`` (checked) or the robot file's (used by dgp and plot)."""
    if args.lengths is not None:
        if len(args.lengths) != robot.n:
            raise CdprInputError("--lengths", f"expected {robot.n} cable lengths, got {len(args.lengths)}")
        if any(v <= 0 for v in args.lengths):
            raise CdprInputError("--lengths", "cable lengths must be > 0")
        return np.array(args.lengths)
    if robot.lengths is not None:
        return robot.lengths
    raise CdprInputError("--lengths", "no cable lengths: the robot file has none and --lengths is not given")


def _run_dgp(args) -> int:
    from cdpr_algebra.dgp.solve import dgp, dgp_table, incompleteness
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(args.robot)
    lengths = _dgp_lengths(args, robot)
    if args.jobs is not None and args.jobs < 1:
        raise CdprInputError("--jobs", f"expected a number >= 1, got {args.jobs}")

    def progress(sub, done, total):
        o = sub.outcomes
        what = f"skipped ({sub.skipped})" if sub.skipped else \
            (f"{sub.paths} paths ({o['regular']} regular, {o['singular']} singular, {o['at_infinity']} at infinity, "
             f"{o['failed']} failed), {sub.real} real, {sub.admissible} admissible")
        print(f"[{done}/{total}] taut {list(sub.taut)}: {what}, {sub.seconds:.2f} s", file=sys.stderr, flush=True)

    options = None
    if args.mpmath_retry:
        from dataclasses import replace

        from cdpr_algebra.dgp.solve import default_options

        options = replace(default_options(), retry_mpmath=True)
    result = dgp(robot, lengths, jobs=args.jobs, progress=progress, options=options)
    if args.json:
        print(json.dumps(result.to_dict(), indent=2))
    else:
        print(f"{robot.name}: DGP, lengths {', '.join(f'{v:g}' for v in lengths)}")
        print(dgp_table(result, robot.n))
    if not result.complete:
        print(f"cdpr: incomplete: {len(result.incomplete)} subproblem(s) not proven complete, so equilibria may be "
              f"missing there (exit status 3):", file=sys.stderr)
        for s in result.incomplete:
            print(f"  {list(s.taut)}: {incompleteness(s)}", file=sys.stderr)
        if any(s.failed_paths for s in result.incomplete):
            print("  (--mpmath-retry tracks up to 4 failed paths per subproblem in arbitrary precision)", file=sys.stderr)
        return INCOMPLETE
    return 0


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "igp":
            return _run_igp(args)
        if args.command == "dgp":
            return _run_dgp(args)
        if args.command == "plot":
            from . import plot as cli_plot

            return cli_plot.run(args)
        if args.command == "cc":
            from . import cc as cli_cc

            return cli_cc.run(args)
        if args.command == "crosscheck":
            from . import crosscheck as cli_crosscheck

            return cli_crosscheck.run(args)
    except CdprInputError as err:
        print(f"cdpr: error: {err}", file=sys.stderr)
        return 2
    parser.error(f"unknown command {args.command!r}")
    return 2
