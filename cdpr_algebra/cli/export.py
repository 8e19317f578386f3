"""``cdpr export``: one DGP subproblem's equations for another solver (:mod:`cdpr_algebra.dgp.export`).

    cdpr export ROBOT --taut C1 .. Cm [--lengths L1 .. Ln] [--format minibex|phc|json] [--out FILE]

Minibex for IbexSolve, PHCpack's input format (``phc -b FILE out``), or JSON; cables numbered from 1.
"""

from __future__ import annotations

from cdpr_algebra.model.errors import CdprInputError

from .common import dgp_lengths, finite, output_file


def add_parser(subparsers) -> None:
    p = subparsers.add_parser("export", help="a DGP subproblem's equations for IbexSolve, PHCpack or as JSON")
    p.add_argument("robot", help="robot file (.json or .toml)")
    p.add_argument("--taut", nargs="+", type=int, required=True, metavar="C", help="the taut cables (from 1)")
    p.add_argument("--lengths", nargs="+", type=finite("--lengths"), metavar="L",
                   help="cable lengths rho_1 .. rho_n (default: the robot file's)")
    p.add_argument("--format", default="minibex", help="minibex (default), phc or json")
    p.add_argument("--out", metavar="FILE", help="write to FILE instead of standard output")


def run(args) -> int:
    from cdpr_algebra.dgp.export import export_subproblem
    from cdpr_algebra.model.robot import load_robot

    if args.out:
        output_file(args.out, "--out")
    robot = load_robot(args.robot)
    lengths = dgp_lengths(args, robot)
    if len(set(args.taut)) != len(args.taut) or any(not 1 <= c <= robot.n for c in args.taut):
        raise CdprInputError("--taut", f"expected distinct cable numbers in 1 .. {robot.n}, got {args.taut}")
    text = export_subproblem(robot, sorted(c - 1 for c in args.taut), lengths, args.format)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(text)
        print(f"wrote {args.out}")
    else:
        print(text, end="")
    return 0
