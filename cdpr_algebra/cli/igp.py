"""``cdpr igp``: the inverse geometrico-static problem of a 3-cable robot (Carricato 2013), with assigned
orientation (closed form) or assigned position (dialytic elimination, 24 solutions)."""

from __future__ import annotations

import sys

from cdpr_algebra.model.errors import CdprInputError

from .common import INCOMPLETE, finite, json_text


def add_parser(subparsers) -> None:
    igp = subparsers.add_parser("igp", help="inverse geometrico-static problem of a 3-cable robot (Carricato 2013)")
    igp.add_argument("robot", help="robot file (.json or .toml)")
    group = igp.add_mutually_exclusive_group(required=True)
    group.add_argument("--orientation", nargs=3, type=finite("--orientation"), metavar=("PHI_X", "PHI_Y", "PHI_Z"),
                       help="assigned orientation, R = Rz(phi_z) Ry(phi_y) Rx(phi_x) (radians unless --degrees)")
    group.add_argument("--position", nargs=3, type=finite("--position"), metavar=("X", "Y", "Z"),
                       help="assigned position of the centre of mass G (world frame)")
    igp.add_argument("--degrees", action="store_true", help="orientation angles in degrees")
    igp.add_argument("--exact", action="store_true",
                     help="exact rational arithmetic (assigned orientation; angles must give an exact rotation: "
                          "multiples of 90 degrees)")
    igp.add_argument("--all", action="store_true", help="also list complex solutions (assigned position)")
    igp.add_argument("--json", action="store_true", help="print JSON instead of a table")


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


def run(args) -> int:
    import numpy as np  # here, not with the module: ``cdpr --help`` imports every command's module
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
        if args.degrees:
            raise CdprInputError("--degrees", "--degrees goes with --orientation (a position has no angles)")
        from cdpr_algebra.igp.position import igp_position

        result = igp_position(robot, np.array(args.position))
    if args.json:
        print(json_text(result.to_dict(include_complex=args.all), indent=2))
    else:
        print(f"{robot.name}: IGP with assigned {result.problem}")
        print(igp_table(result, include_complex=args.all))
    if result.status == "undecided":
        why = result.solution_set.description
    elif result.status == "incomplete":
        why = (f"{result.found} of the {result.generic_count} solutions found, the others lost to rounding or at "
               f"infinity here (not decided)")
    elif result.status == "uncertified":
        why = f"{sum(not s.certified for s in result.real_solutions)} real solution(s) without an interval certificate"
    else:
        return 0
    print(f"cdpr igp: {result.status}: {why} (exit status {INCOMPLETE})", file=sys.stderr)
    return INCOMPLETE
